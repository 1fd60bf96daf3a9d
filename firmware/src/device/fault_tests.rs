//! Faults and bad input on the simulated device: each is named, nothing is acted on that should not
//! be, and the device answers the next request.

use embassy_futures::block_on;
use proptest::prelude::{any, prop_assert, prop_assert_eq, proptest, ProptestConfig};
use rand_xoshiro::rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use shared::protocol::{
    self, DeviceError, FrameError, Request, Response, SensorConfig, StreamKind, MAX_FRAME_LEN, PROTOCOL_VERSION,
};
use shared::{AccelRange, Calibration};

use super::Device;
use crate::link::Link;
use crate::sim::flash::RamFlash;
use crate::sim::{sim_serial_number, SimMpu6050};

type Flash = RamFlash<2048, 4>;
type SimDevice = Device<SimMpu6050, Flash>;
const TICK_US: u64 = 20_000;

fn boot(seed: u64) -> SimDevice {
    block_on(Device::boot(SimMpu6050::new(seed), Flash::new(), 0..4 * 2048, sim_serial_number(seed))).unwrap()
}

fn drain(device: &mut SimDevice) -> Vec<(u16, Response)> {
    std::iter::from_fn(|| device.next_response()).collect()
}

/// Polls a started long operation to its final response.
fn finish(device: &mut SimDevice) -> Response {
    for _ in 0..10_000 {
        device.bus_mut().advance_us(TICK_US);
        block_on(device.poll());
        if let Some((_, last)) = drain(device).into_iter().find(|(_, r)| !matches!(r, Response::Progress(_))) {
            return last;
        }
    }
    panic!("no final response");
}

fn capture(device: &mut SimDevice) -> Response {
    block_on(device.handle(1, Request::Capture { seconds: 5 }));
    finish(device)
}

#[test]
fn i2c_errors_at_random_transactions_of_a_capture_are_named_and_the_next_capture_works() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(6);
    let mut device = boot(61);
    for _ in 0..30 {
        // A 5 s capture reads the FIFO in about 250 polls of three or more transactions each.
        let skip = rng.next_u32() % 700;
        block_on(device.handle(1, Request::Capture { seconds: 5 }));
        device.bus_mut().fail_transactions_after(skip, 1 + rng.next_u32() % 3);
        let result = finish(&mut device);
        // NOTE: a burst of faults also fails the re-probe that follows a bus error, and then reads
        // as a missing sensor: either name is right, and the next capture must work.
        assert!(
            matches!(
                result,
                Response::Error(DeviceError::Bus | DeviceError::SensorMissing) | Response::Captured { .. }
            ),
            "fault after {skip} transactions: {result:?}"
        );
        device.bus_mut().fail_next_transactions(0);
        assert!(matches!(capture(&mut device), Response::Captured { .. }), "no recovery after {skip}");
    }
}

#[test]
fn a_sensor_that_vanishes_mid_capture_is_named_missing_and_found_again() {
    let mut device = boot(62);
    block_on(device.handle(1, Request::Capture { seconds: 5 }));
    for _ in 0..50 {
        device.bus_mut().advance_us(TICK_US);
        block_on(device.poll());
    }
    device.bus_mut().set_connected(false);
    assert_eq!(finish(&mut device), Response::Error(DeviceError::SensorMissing));
    device.bus_mut().set_connected(true);
    assert!(matches!(capture(&mut device), Response::Captured { .. }));
}

#[test]
fn a_stalled_reader_gets_a_fifo_overflow_and_the_next_capture_works() {
    let mut device = boot(63);
    block_on(device.handle(1, Request::Capture { seconds: 5 }));
    device.bus_mut().advance_us(2_000_000); // 200 samples of 14 bytes: far beyond the 1024-byte FIFO
    block_on(device.poll());
    assert_eq!(drain(&mut device), [(1, Response::Error(DeviceError::FifoOverflow))]);
    assert!(matches!(capture(&mut device), Response::Captured { .. }));
}

#[test]
fn power_cuts_at_random_points_across_1000_save_cycles_boot_to_the_old_or_new_calibration() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
    let calibration = |n: u32| Calibration {
        offset_g: [n as f32 * 1e-5, 0.01, -0.02],
        mean_temp_c: n as f32,
        ..Calibration::identity(AccelRange::G2)
    };
    let mut flash = Flash::new();
    let mut saved: Option<Calibration> = None;
    let mut cuts = 0;
    for n in 1..=1000u32 {
        let mut storage = crate::storage::Storage::new(flash.clone(), 0..4 * 2048).unwrap();
        let cut = rng.next_u32() % 4 == 0;
        if cut {
            // Somewhere within the save's first few operations (a save takes 1-4 when no page is erased).
            let mut cut_flash = flash.clone();
            cut_flash.cut_power_at(rng.next_u32() % 4);
            storage = crate::storage::Storage::new(cut_flash, 0..4 * 2048).unwrap();
        }
        let result = block_on(storage.save(&calibration(n)));
        let mut after = storage.into_flash();
        if after.was_cut() {
            cuts += 1;
            after.restore_power();
        }
        let loaded = block_on(crate::storage::Storage::new(after.clone(), 0..4 * 2048).unwrap().load()).unwrap();
        assert!(loaded == saved || loaded == Some(calibration(n)), "cycle {n}: {loaded:?}");
        if result.is_ok() {
            assert_eq!(loaded, Some(calibration(n)), "cycle {n}: a completed save was lost");
        }
        saved = loaded;
        flash = after;
    }
    assert!(cuts > 150, "only {cuts} cuts landed");
}

/// Feeds bytes through the link and returns the answers.
fn feed(device: &mut SimDevice, bytes: &[u8]) -> Vec<(u16, Response)> {
    let mut link = Link::new();
    block_on(link.receive(bytes, device));
    drain(device)
}

fn frame(request: &Request) -> Vec<u8> {
    let mut buffer = [0u8; MAX_FRAME_LEN];
    let len = protocol::encode(5, request, &mut buffer).unwrap();
    buffer[..len].to_vec()
}

fn still_responsive(device: &mut SimDevice) {
    let answers = feed(device, &frame(&Request::Hello { protocol_version: PROTOCOL_VERSION }));
    assert!(matches!(answers.as_slice(), [(5, Response::Hello(_))]), "{answers:?}");
}

#[test]
fn truncated_oversized_corrupted_and_foreign_frames_are_answered_with_errors_and_not_acted_on() {
    let mut device = boot(64);
    let upload = frame(&Request::SetCalibration(Calibration::identity(AccelRange::G2)));
    let body = &upload[..upload.len() - 1];
    // NOTE: a frame cut in half is caught by whichever layer sees it first (its COBS code bytes, its
    // length, or its CRC, depending on where the cut falls); every other case has exactly one answer.
    let cut = &[FrameError::Cobs, FrameError::Truncated, FrameError::Crc][..];
    let cases: Vec<(Vec<u8>, &[FrameError])> = vec![
        ([&body[..body.len() / 2], &[0]].concat(), cut),
        (vec![0x55; MAX_FRAME_LEN + 5].into_iter().chain([0]).collect(), &[FrameError::Oversized]),
        (
            {
                let mut corrupted = upload.clone();
                corrupted[10] ^= 0x04;
                corrupted
            },
            &[FrameError::Crc],
        ),
    ];
    for (bytes, expected) in cases {
        let answers = feed(&mut device, &bytes);
        assert!(
            matches!(answers.as_slice(), [(0, Response::Error(DeviceError::Frame(e)))] if expected.contains(e)),
            "{expected:?}: {answers:?}"
        );
        assert_eq!(device.active_calibration(), None, "a bad frame was acted on");
        still_responsive(&mut device);
    }
}

#[test]
fn valid_requests_in_the_wrong_state_are_refused_by_name_and_change_nothing() {
    let mut device = boot(65);
    let refusals = [
        (Request::FitSixPosition, DeviceError::SixPosition(shared::SixPositionError::Missing(shared::Position::PosX))),
        (Request::SaveCalibration, DeviceError::NoCalibration),
        (Request::Capture { seconds: 30 }, DeviceError::InvalidDuration { seconds: 30 }),
        (Request::Stream { kind: StreamKind::Raw, rate_hz: 30, count: 5 }, DeviceError::InvalidRate { rate_hz: 30 }),
        (
            Request::Configure(SensorConfig { sample_rate_hz: 300, ..SensorConfig::default() }),
            DeviceError::InvalidRate { rate_hz: 300 },
        ),
    ];
    for (request, error) in refusals {
        assert_eq!(feed(&mut device, &frame(&request)), [(5, Response::Error(error))]);
        assert!(!device.is_busy());
        assert_eq!(device.active_calibration(), None);
    }
    // While a stream runs, another long operation and the flash are refused; the stream goes on.
    feed(&mut device, &frame(&Request::Stream { kind: StreamKind::Raw, rate_hz: 10, count: 0 }));
    assert_eq!(feed(&mut device, &frame(&Request::Capture { seconds: 5 })), [(5, Response::Error(DeviceError::Busy))]);
    assert_eq!(feed(&mut device, &frame(&Request::EraseCalibration)), [(5, Response::Error(DeviceError::Busy))]);
    assert!(device.is_busy());
    still_responsive(&mut device);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn arbitrary_bytes_never_act_and_never_silence_the_device(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        let mut device = boot(66);
        let answers = feed(&mut device, &bytes);
        for (_, answer) in &answers {
            // Random bytes pass a CRC-32 with odds of 2^-32 per frame: anything else is an error.
            prop_assert!(matches!(answer, Response::Error(DeviceError::Frame(_))), "{answer:?}");
        }
        prop_assert_eq!(device.active_calibration(), None);
        prop_assert!(!device.is_busy());
        still_responsive(&mut device);
    }
}

#[test]
fn non_finite_singular_and_absurd_uploads_are_refused_with_the_reason_and_the_stored_one_is_untouched() {
    use shared::CalibrationError;
    let mut device = boot(67);
    let good = Calibration { offset_g: [0.02, -0.01, 0.07], ..Calibration::identity(AccelRange::G2) };
    assert_eq!(feed(&mut device, &frame(&Request::SetCalibration(good))), [(5, Response::Done)]);
    assert_eq!(feed(&mut device, &frame(&Request::SaveCalibration)), [(5, Response::Done)]);
    let mut non_finite = good;
    non_finite.gyro.bias_dps[2] = f32::INFINITY;
    let mut singular = good;
    singular.matrix = [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    let mut absurd = good;
    absurd.offset_g[1] = 0.9;
    let cases = [
        (non_finite, CalibrationError::NonFinite),
        (singular, CalibrationError::Singular { determinant: 0.0 }),
        (absurd, CalibrationError::OffsetOutOfRange { axis: 1, value_g: 0.9 }),
    ];
    for (upload, reason) in cases {
        let answers = feed(&mut device, &frame(&Request::SetCalibration(upload)));
        assert_eq!(answers, [(5, Response::Error(DeviceError::InvalidCalibration(reason)))]);
        assert_eq!(device.active_calibration(), Some(good));
        let stored = feed(&mut device, &frame(&Request::GetCalibration(shared::protocol::CalibrationSlot::Stored)));
        assert_eq!(stored, [(5, Response::Calibration(Some(good)))]);
    }
}
