//! The USB budget of a 1 kHz stream: the largest frame a streamed sample takes, times 1000 per second,
//! against USB full speed's bulk capacity.

use shared::protocol::{encode, Response, Sample, MAX_FRAME_LEN};

/// USB full speed's bulk payload capacity: at most 19 packets of 64 bytes per 1 ms frame (USB 2.0
/// spec, table 5-9), 1 216 000 bytes per second, before the host controller's own limits.
const FULL_SPEED_BULK_BYTES_PER_S: f64 = 19.0 * 64.0 * 1000.0;

/// The budget share a 1 kHz stream may take, leaving room for host scheduling that delivers fewer
/// packets per frame than the theoretical 19.
const MAX_SHARE: f64 = 0.1;

#[test]
fn a_1_khz_sample_stream_takes_under_a_tenth_of_full_speed_bulk_capacity() {
    // Every byte of the worst case: the largest index and floats whose bytes are all non-zero (COBS
    // adds a byte per zero run, so this is also its worst case for this length).
    // The time is the largest a varint takes for a day of samples (u64 varints grow with the value).
    let time_us = 86_400 * 1_000_000;
    let sample = Sample { index: u32::MAX, time_us, accel_g: [-1.2345e-3; 3], gyro_dps: [-245.67; 3], temp_c: 36.53 };
    let mut frame = [0u8; MAX_FRAME_LEN];
    let length = encode(u16::MAX, &Response::Sample(sample), &mut frame).expect("a sample frame encodes");
    let bytes_per_s = length as f64 * 1000.0;
    let share = bytes_per_s / FULL_SPEED_BULK_BYTES_PER_S;
    println!(
        "sample frame {length} bytes (with delimiter): {bytes_per_s:.0} B/s at 1 kHz, {:.1} % of full-speed bulk",
        share * 100.0
    );
    assert!(share < MAX_SHARE, "a 1 kHz stream takes {:.1} % of the bulk capacity", share * 100.0);
}
