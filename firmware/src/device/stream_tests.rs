//! A stream's sequence numbers and sample times; a host that does not read (samples are dropped
//! and counted, never silently lost, and the FIFO does not overflow); and what hello says of a
//! sensor that came loose.

use embassy_futures::block_on;
use shared::protocol::{Request, Response, Sample, StreamKind};

use super::tests::{boot, drain, run, Flash, SimDevice};
use super::OUTBOX_LEN;
use crate::sim::SimMpu6050;

fn samples_of(responses: &[Response]) -> Vec<Sample> {
    responses.iter().filter_map(|r| if let Response::Sample(s) = r { Some(*s) } else { None }).collect()
}

#[test]
fn sequence_numbers_count_up_and_sample_times_follow_the_sensor_clock() {
    let mut device = boot(SimMpu6050::new(31), Flash::new());
    let (last, streamed) = run(&mut device, 2, Request::Stream { kind: StreamKind::Raw, rate_hz: 25, count: 40 });
    assert_eq!(last, Response::StreamEnded { samples: 40, dropped: 0 });
    let samples = samples_of(&streamed);
    for (k, sample) in samples.iter().enumerate() {
        assert_eq!(sample.index, k as u32);
        // 25 Hz out of the 100 Hz sample rate: every 4th sample, 40 ms apart on the sensor's clock.
        assert_eq!(sample.time_us, 40_000 * k as u64, "sample {k}");
    }
}

/// Polls `device` every 10 ms of simulated time for `seconds`, never draining its responses.
fn poll_without_reading(device: &mut SimDevice, seconds: u32) {
    for _ in 0..seconds * 100 {
        device.bus_mut().advance_us(10_000);
        block_on(device.poll());
    }
}

#[test]
fn a_host_that_does_not_read_gets_counted_drops_and_gaps_not_a_fifo_overflow() {
    let mut device = boot(SimMpu6050::new(32), Flash::new());
    block_on(device.handle(2, Request::Stream { kind: StreamKind::Raw, rate_hz: 100, count: 300 }));
    // 3 s at 100 Hz: the outbox holds 15 samples and the final response; 285 are dropped.
    poll_without_reading(&mut device, 3);
    let responses: Vec<Response> = drain(&mut device).into_iter().map(|(_, r)| r).collect();
    let sent = (OUTBOX_LEN - 1) as u32;
    assert_eq!(responses.last(), Some(&Response::StreamEnded { samples: sent, dropped: 300 - sent }));
    let indices: Vec<u32> = samples_of(&responses).iter().map(|s| s.index).collect();
    assert_eq!(indices, (0..sent).collect::<Vec<_>>());
    assert!(!device.is_busy(), "the stream ended after 300 sequence numbers");
}

#[test]
fn a_sensor_unplugged_while_idle_is_missing_in_the_next_hello_and_found_after_replug() {
    use shared::protocol::{DeviceError, PROTOCOL_VERSION};
    let hello_sensor = |device: &mut SimDevice| match super::tests::ask(
        device,
        1,
        Request::Hello { protocol_version: PROTOCOL_VERSION },
    ) {
        Response::Hello(info) => info.sensor.map(|s| s.address),
        other => panic!("no hello: {other:?}"),
    };
    let mut device = boot(SimMpu6050::new(33), Flash::new());
    assert_eq!(hello_sensor(&mut device), Ok(0x68));
    device.bus_mut().set_connected(false);
    assert_eq!(hello_sensor(&mut device), Err(DeviceError::SensorMissing));
    device.bus_mut().set_connected(true);
    assert_eq!(hello_sensor(&mut device), Ok(0x68));
}
