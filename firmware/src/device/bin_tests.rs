//! The chip's temperature bins as the capture and stream engine fill them and the host takes them.

use shared::protocol::{Request, Response, TempBin};

use super::tests::{ask, boot, capture_at, run, Flash, SimDevice};
use crate::sim::SimMpu6050;

/// Every bin the device holds, as the host takes them (several requests when there are many).
fn take_all(device: &mut SimDevice) -> Vec<TempBin> {
    let mut bins = Vec::new();
    loop {
        let Response::TemperatureBins(taken) = ask(device, 9, Request::TakeTemperatureBins) else { panic!("no bins") };
        let last = taken.len() < shared::protocol::TEMP_BINS_PER_MESSAGE;
        bins.extend(taken);
        if last {
            return bins;
        }
    }
}

#[test]
fn the_bins_of_a_capture_hold_its_every_sample_and_average_to_its_mean() {
    let mut device = boot(SimMpu6050::new(3), Flash::new());
    let Response::Captured { stats, .. } = capture_at(&mut device, [0.0, 0.0, 1.0]) else { panic!("no capture") };
    let bins = take_all(&mut device);
    let samples: u32 = bins.iter().map(|b| b.samples).sum();
    assert_eq!(samples, stats.samples, "{bins:?}");
    // The realistic sensor warms after power-on: the capture's samples span whole degrees.
    let weighted = |f: fn(&TempBin) -> f32| bins.iter().map(|b| f(b) * b.samples as f32).sum::<f32>() / samples as f32;
    assert!((weighted(|b| b.accel_g[2]) - stats.mean_g[2]).abs() < 2e-6, "{bins:?} vs {stats:?}");
    assert!((weighted(|b| b.gyro_dps[0]) - stats.gyro_mean_dps[0]).abs() < 2e-5, "{bins:?} vs {stats:?}");
    assert!((weighted(|b| b.temp_c) - stats.temp_c).abs() < 1e-3, "{bins:?} vs {stats:?}");
    for bin in &bins {
        assert!((f32::from(bin.degree_c)..f32::from(bin.degree_c) + 1.0).contains(&bin.temp_c), "{bin:?}");
    }
    assert!(take_all(&mut device).is_empty(), "taking empties the bins");
}

#[test]
fn a_stream_fills_the_bins_with_every_sample_it_reads() {
    let mut device = boot(SimMpu6050::new(4), Flash::new());
    let (last, _) =
        run(&mut device, 2, Request::Stream { kind: shared::protocol::StreamKind::Raw, rate_hz: 100, count: 300 });
    assert_eq!(last, Response::StreamEnded { samples: 300, dropped: 0 });
    let samples: u32 = take_all(&mut device).iter().map(|b| b.samples).sum();
    // The engine reads the FIFO in batches: the last batch may hold a few samples past the count.
    assert!((300..300 + 16).contains(&samples), "{samples} samples binned");
}
