//! The sensor a board found, named for a person: the part its WHO_AM_I names, the family it
//! behaves as, and a contradiction between the two when there is one; the family confirmed by what
//! its offset registers do ([`check`]); a board described as `accelcal info` shows it ([`info`]).

pub mod check;
mod check_text;
pub mod info;
pub mod offsets;

use firmware::sensor::registers::FIFO_R_W;

use crate::link::{Client, LinkError, Port};

pub use accelcal_core::part::{describe, family_name, part_name};

/// Registers in the map of every family: 0x00-0x7F.
const REGISTER_COUNT: u8 = 0x80;

/// Every register of the sensor, 0x00-0x7F; `None` for FIFO_R_W (0x74), which is not read: reading
/// it takes a byte out of the FIFO.
pub fn register_dump<P: Port>(client: &mut Client<P>) -> Result<Vec<Option<u8>>, LinkError> {
    let read = |client: &mut Client<P>, register| client.register(register, None).map(Some);
    (0..REGISTER_COUNT).map(|r| if r == FIFO_R_W { Ok(None) } else { read(client, r) }).collect()
}

/// A register dump as a person pastes it into a report: a heading, then 16 registers a line in
/// hexadecimal, `--` where a register was not read.
pub fn format_dump(heading: &str, registers: &[Option<u8>]) -> String {
    let mut out = format!("{heading}\n   ");
    out += &(0..16).map(|column| format!(" {column:>2x}")).collect::<String>();
    for (row, values) in registers.chunks(16).enumerate() {
        let cells: String = values.iter().map(|v| v.map_or(" --".to_owned(), |v| format!(" {v:02x}"))).collect();
        out += &format!("\n{:02x}:{cells}", row * 16);
    }
    out + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;
    use shared::part::Family;
    use shared::protocol::SensorIdentity;

    fn identity(who_am_i: u8, family: Family) -> SensorIdentity {
        SensorIdentity { address: 0x68, who_am_i, family }
    }

    #[test]
    fn parts_are_named_and_a_contradiction_is_said() {
        assert_eq!(describe(&identity(0x98, Family::Mpu6500)), "ICM-20689 at 0x68 (MPU-6500 family)");
        assert_eq!(
            describe(&identity(0x72, Family::Mpu6500)),
            "unknown 0x72, not an InvenSense part, at 0x68 (behaves as the MPU-6500 family)"
        );
        let contradiction = describe(&identity(0x68, Family::Mpu6500));
        assert!(contradiction.contains("WHO_AM_I 0x68 (MPU-6050)") && contradiction.contains("not the part it claims"));
        assert_eq!(part_name(&identity(0x74, Family::Mpu6050)), "unknown");
    }

    #[test]
    fn the_dump_of_the_unknown_0x72_part_holds_its_who_am_i_and_trim_codes_and_skips_the_fifo() {
        let part = firmware::sim::part::SimPart::unknown72();
        let (mut connection, _board) =
            crate::sim::SimBoard::in_process_part((1, crate::sim::SimSensor::Settled, part)).unwrap();
        let dump = register_dump(&mut connection.client).unwrap();
        assert_eq!(dump.len(), 128);
        // WHO_AM_I (0x75), FIFO_R_W (0x74) not read, SELF_TEST_X/Y/Z_ACCEL (0x0D-0x0F) and _GYRO (0x00-0x02).
        assert_eq!((dump[0x75], dump[0x74]), (Some(0x72), None));
        assert_eq!(dump[0x0D..=0x0F], part.codes[..3].iter().map(|&c| Some(c)).collect::<Vec<_>>()[..]);
        assert_eq!(dump[0x00..=0x02], part.codes[3..].iter().map(|&c| Some(c)).collect::<Vec<_>>()[..]);
        // The board's configuration: +-1000 deg/s (GYRO_CONFIG 0x1B), +-2 g (ACCEL_CONFIG 0x1C).
        assert_eq!(dump[0x1B..=0x1C], [Some(0x10), Some(0x00)]);
        let text = format_dump("unknown 0x72", &dump);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2 + 8, "{text}");
        assert_eq!(lines[1], "     0  1  2  3  4  5  6  7  8  9  a  b  c  d  e  f");
        assert!(lines[9].starts_with("70:") && lines[9][3..].split_whitespace().nth(4) == Some("--"), "{text}");
        assert_eq!(lines[9][3..].split_whitespace().nth(5), Some("72"), "{text}");
    }
}
