//! `accelcal stream`'s CSV: one row per sample, each written and flushed as it comes, each naming
//! its board.

use std::io::Write;

use shared::protocol::Sample;

pub use super::stream_csv_columns;

/// One row, flushed at once: the stream is live, and a reader that went away shows at the next row.
pub fn write_row<T: AsRef<[u8]>>(
    out: &mut csv::Writer<impl Write>,
    cells: impl IntoIterator<Item = T>,
) -> std::io::Result<()> {
    out.write_record(cells)?;
    out.flush()
}

/// One sample's cells; every row names the board, so that a file cut or joined still says whose it is.
pub fn sample_cells(s: &Sample, serial: &str) -> [String; 10] {
    let [ax, ay, az] = s.accel_g.map(|v| format!("{v:.6}"));
    let [gx, gy, gz] = s.gyro_dps.map(|v| format!("{v:.4}"));
    let time_s = format!("{:.6}", s.time_us as f64 * 1e-6);
    [s.index.to_string(), time_s, ax, ay, az, gx, gy, gz, format!("{:.2}", s.temp_c), serial.to_owned()]
}

/// `accelcal stream`'s own CSV without its last column, the board's serial, which no stream
/// dialect reads as a number: its samples then read as any CSV log's. Any other text as it is.
pub fn without_board_column(text: String) -> String {
    let header = stream_csv_columns().join(",");
    if text.lines().next().map(str::trim_end) != Some(header.as_str()) {
        return text;
    }
    let line = |line: &str| line.rsplit_once(',').map_or(line, |(kept, _board)| kept).to_owned();
    text.lines().map(|l| line(l) + "\n").collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use shared::protocol::Sample;

    /// Records what reached it in each `write` call, as a pipe's reader would see it arrive.
    #[derive(Default)]
    struct Arrivals(Vec<String>);

    impl Write for Arrivals {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0.push(String::from_utf8_lossy(bytes).into_owned());
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn each_sample_reaches_the_reader_as_its_own_line_with_the_stream_s_decimals() {
        let sample = |index: u32| Sample {
            index,
            time_us: 1_250_000 + u64::from(index) * 10_000,
            accel_g: [0.012_345_67, -0.5, 1.000_000_4],
            gyro_dps: [0.123_456, -2.0, 250.0],
            temp_c: 24.126,
        };
        let mut out = csv::Writer::from_writer(Arrivals::default());
        write_row(&mut out, stream_csv_columns()).unwrap();
        write_row(&mut out, sample_cells(&sample(3), "53494D")).unwrap();
        write_row(&mut out, sample_cells(&sample(4), "53494D")).unwrap();
        let arrived = out.into_inner().map_err(|_| "unflushed").unwrap().0;
        // Written literally: the line `accelcal stream` printed before the csv crate wrote it.
        let expected = [
            "index,time_s,ax_g,ay_g,az_g,gx_dps,gy_dps,gz_dps,temp_c,board\n",
            "3,1.280000,0.012346,-0.500000,1.000000,0.1235,-2.0000,250.0000,24.13,53494D\n",
            "4,1.290000,0.012346,-0.500000,1.000000,0.1235,-2.0000,250.0000,24.13,53494D\n",
        ];
        assert_eq!(arrived, expected);
    }
}
