//! Every message round-trips and fits a frame; arbitrary bytes never panic the decoder; corruption is
//! detected.

use proptest::prelude::*;

use super::*;
use crate::calibration::{
    AccelRange, Calibration, CalibrationError, GyroCalibration, ModelTag, Origin, Procedure, TemperatureModel,
};
use crate::orientation::{Position, PositionMap};
use crate::ortho9::Ortho9Error;
use crate::part::Family;
use crate::selftest::{SelfTestRaw, StoredSelfTest};
use crate::six_position::SixPositionError;

/// Large values take the most postcard bytes (varints), so sizes here are the worst case: every
/// optional part present, the longest model tag.
fn calibration() -> Calibration {
    Calibration {
        origin: Origin { procedure: Procedure::Uploaded, model: ModelTag::new("reference-norm12").unwrap() },
        range: AccelRange::G16,
        filter: LowPassFilter::Hz5,
        matrix: [[1.0006, 3.58e-4, -7.29e-3], [0.0, 1.003, 4.62e-4], [0.0, 0.0, 0.9834]],
        offset_g: [0.0276, -0.0057, -0.0783],
        gyro: GyroCalibration {
            matrix: [[1.01, 0.002, 0.0], [0.0, 0.99, 0.0], [0.0, 0.0, 1.0]],
            bias_dps: [-1.25, 0.5, 3.0],
        },
        mean_temp_c: 31.5,
        temperature: Some(TemperatureModel {
            offset_g: [[1e-3; 3], [-2e-5; 3], [3e-7; 3]],
            scale: [[2e-4; 3], [1e-6; 3], [1e-8; 3]],
            gyro_bias_dps: [[0.05; 3], [1e-4; 3], [1e-6; 3]],
            ..TemperatureModel::flat(25.0)
        }),
        residual_mg: 0.42,
    }
}

fn stats() -> CaptureStats {
    CaptureStats {
        samples: u32::MAX,
        seconds: 20.0,
        mean_g: [0.01, -0.02, 1.01],
        std_g: [0.002; 3],
        gyro_mean_dps: [-1.0, 0.3, 0.1],
        gyro_std_dps: [0.05; 3],
        temp_c: 29.9,
        clipped: u32::MAX,
        range: AccelRange::G2,
    }
}

fn every_request() -> Vec<Request> {
    let all = vec![
        Request::Hello { protocol_version: PROTOCOL_VERSION },
        Request::Configure(SensorConfig {
            range: AccelRange::G8,
            sample_rate_hz: u16::MAX,
            filter: LowPassFilter::Hz5,
        }),
        Request::Capture { seconds: 20 },
        Request::Cancel,
        Request::ClearPositions,
        Request::FitSixPosition,
        Request::GetCalibration(CalibrationSlot::Stored),
        Request::SetCalibration(calibration()),
        Request::SaveCalibration,
        Request::EraseCalibration,
        Request::Stream { kind: StreamKind::Calibrated, rate_hz: u16::MAX, count: u32::MAX },
        Request::TakeTemperatureBins,
        Request::FitOrtho9,
        Request::CaptureUntil(CaptureGoal { mean_std_g: f32::MAX, min_samples: u32::MAX, max_samples: u32::MAX }),
        Request::Register { register: u8::MAX, write: Some(u8::MAX) },
        Request::Register { register: 0, write: None },
        Request::StoreSelfTest(stored_self_test().record()),
    ];
    // NOTE: the match fails to compile when a variant is added without being listed above.
    for request in &all {
        match request {
            Request::Hello { .. }
            | Request::Configure(_)
            | Request::Capture { .. }
            | Request::Cancel
            | Request::ClearPositions
            | Request::FitSixPosition
            | Request::GetCalibration(_)
            | Request::SetCalibration(_)
            | Request::SaveCalibration
            | Request::EraseCalibration
            | Request::Stream { .. }
            | Request::TakeTemperatureBins
            | Request::FitOrtho9
            | Request::CaptureUntil(_)
            | Request::Register { .. }
            | Request::StoreSelfTest(_) => {}
        }
    }
    all
}

fn every_error() -> Vec<DeviceError> {
    vec![
        DeviceError::SensorMissing,
        DeviceError::UnknownSensor { address: 0x69, who_am_i: 0xff },
        DeviceError::Bus,
        DeviceError::FifoOverflow,
        DeviceError::Moved { accel_std_mg: 12.5, gyro_std_dps: 3.0 },
        DeviceError::Clipped { samples: u32::MAX },
        DeviceError::Cancelled,
        DeviceError::InvalidDuration { seconds: 255 },
        DeviceError::InvalidRate { rate_hz: u16::MAX },
        DeviceError::SixPosition(SixPositionError::Missing(Position::NegZ)),
        DeviceError::InvalidCalibration(CalibrationError::CrossAxisOutOfRange { row: 2, col: 1, value: 0.5 }),
        DeviceError::RangeMismatch { calibration: AccelRange::G2, configured: AccelRange::G16 },
        DeviceError::NoCalibration,
        DeviceError::Storage,
        DeviceError::Busy,
        DeviceError::Frame(FrameError::Version { got: 200 }),
        DeviceError::UnsupportedVersion { device: PROTOCOL_VERSION, host: 255 },
        DeviceError::Ortho9(Ortho9Error::TooFewReadings(255)),
        DeviceError::Ortho9(Ortho9Error::IllConditioned(8)),
        DeviceError::Ortho9(Ortho9Error::NotConverged),
        DeviceError::InvalidGoal,
    ]
}

/// A self-test record at its largest.
fn stored_self_test() -> StoredSelfTest {
    let raw = SelfTestRaw {
        family: Family::Mpu6500,
        codes: [u8::MAX; 6],
        off_lsb: [f32::MAX; 6],
        on_lsb: [f32::MIN; 6],
        attempts: u8::MAX,
    };
    StoredSelfTest { unix_time_s: u32::MAX, raw }
}

fn every_position() -> PositionMap<()> {
    let mut all = PositionMap::new();
    Position::ALL.into_iter().for_each(|p| all.replace(p, ()));
    all
}

fn every_response() -> Vec<Response> {
    let info = DeviceInfo {
        protocol_version: PROTOCOL_VERSION,
        firmware: FirmwareVersion { major: 255, minor: 255, patch: 255 },
        sensor: Ok(SensorIdentity { address: 0x69, who_am_i: 0x72, family: Family::Mpu6500 }),
        config: SensorConfig::default(),
        active: ActiveCalibration::Unsaved,
        stored: true,
        serial: SerialNumber([0xFF; SERIAL_NUMBER_LEN]),
        positions: every_position(),
        self_test: Some(stored_self_test().record()),
    };
    let mut all = vec![
        Response::Hello(info.clone()),
        Response::Hello(DeviceInfo { sensor: Err(DeviceError::UnknownSensor { address: 0x68, who_am_i: 0 }), ..info }),
        Response::Configured(SensorConfig::default()),
        Response::Progress(CaptureProgress { samples: u32::MAX, total_samples: u32::MAX, mean_g: [1.0; 3] }),
        Response::Captured { stats: stats(), position: Some(Position::NegY) },
        Response::Fitted(calibration()),
        Response::Calibration(Some(calibration())),
        Response::Calibration(None),
        Response::Sample(Sample {
            index: u32::MAX,
            time_us: u64::MAX,
            accel_g: [1.0; 3],
            gyro_dps: [250.0; 3],
            temp_c: 85.0,
        }),
        Response::StreamEnded { samples: u32::MAX, dropped: u32::MAX },
        Response::Done,
        Response::TemperatureBins(full_temperature_bins()),
        Response::Ortho9Fitted { calibration: calibration(), captures: u8::MAX, iterations: u8::MAX },
        Response::Register(u8::MAX),
    ];
    all.extend(every_error().into_iter().map(Response::Error));
    for response in &all {
        match response {
            Response::Hello(_)
            | Response::Configured(_)
            | Response::Progress(_)
            | Response::Captured { .. }
            | Response::Fitted(_)
            | Response::Calibration(_)
            | Response::Sample(_)
            | Response::StreamEnded { .. }
            | Response::Done
            | Response::Error(_)
            | Response::TemperatureBins(_)
            | Response::Ortho9Fitted { .. }
            | Response::Register(_) => {}
        }
    }
    all
}

/// As many temperature bins as one message carries, each at its largest.
fn full_temperature_bins() -> heapless::Vec<TempBin, TEMP_BINS_PER_MESSAGE> {
    let bin = TempBin { degree_c: i8::MIN, samples: u32::MAX, temp_c: -40.0, accel_g: [2.0; 3], gyro_dps: [250.0; 3] };
    (0..TEMP_BINS_PER_MESSAGE).map(|_| bin).collect()
}

fn round_trip<T>(message: &T, request_id: u16) -> (u16, T, usize)
where
    T: serde::Serialize + serde::de::DeserializeOwned,
{
    let mut frame = [0u8; MAX_FRAME_LEN];
    let len = encode(request_id, message, &mut frame).expect("message fits a frame");
    assert_eq!(frame[len - 1], 0, "frame ends with its delimiter");
    assert!(!frame[..len - 1].contains(&0), "no delimiter inside a frame");
    let (id, decoded) = decode(&mut frame[..len - 1]).expect("own frame decodes");
    (id, decoded, len)
}

#[test]
fn every_request_round_trips_and_fits_the_frame_buffer() {
    let mut largest = 0;
    for request in every_request() {
        let (id, decoded, len) = round_trip(&request, 0xBEEF);
        assert_eq!((id, &decoded), (0xBEEF, &request));
        largest = largest.max(len);
    }
    // As for responses: the largest request (an upload) stays well inside the frame buffer.
    assert!(largest < MAX_FRAME_LEN / 2, "largest request frame is {largest} bytes");
}

#[test]
fn every_response_round_trips_and_fits_the_frame_buffer() {
    let mut largest = 0;
    for response in every_response() {
        let (id, decoded, len) = round_trip(&response, u16::MAX);
        assert_eq!((id, &decoded), (u16::MAX, &response));
        largest = largest.max(len);
    }
    // The payload limit leaves room to grow; the largest message is well inside it.
    assert!(largest < MAX_FRAME_LEN / 2, "largest response frame is {largest} bytes");
}

#[test]
fn a_message_larger_than_the_payload_limit_is_refused_not_truncated() {
    let big = [7u32; MAX_PAYLOAD_LEN];
    let mut frame = [0u8; MAX_FRAME_LEN];
    assert_eq!(encode(1, &big.as_slice(), &mut frame), Err(FrameError::Oversized));
}

#[test]
fn every_single_bit_flip_in_a_frame_is_detected() {
    let mut clean = [0u8; MAX_FRAME_LEN];
    let len = encode(42, &Request::SetCalibration(calibration()), &mut clean).unwrap() - 1;
    for bit in 0..len * 8 {
        let mut frame = clean;
        frame[bit / 8] ^= 1 << (bit % 8);
        let result = decode::<Request>(&mut frame[..len]);
        assert!(result.is_err(), "flip of bit {bit} went undetected: {result:?}");
    }
}

#[test]
fn another_protocol_version_is_named() {
    let mut frame = [0u8; MAX_FRAME_LEN];
    let len = encode(1, &Request::Cancel, &mut frame).unwrap() - 1;
    let mut raw = [0u8; MAX_FRAME_LEN];
    let raw_len = cobs::decode(&frame[..len], &mut raw).unwrap();
    raw[0] = PROTOCOL_VERSION + 1;
    let crc = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC).checksum(&raw[..raw_len - 4]);
    raw[raw_len - 4..raw_len].copy_from_slice(&crc.to_le_bytes());
    let len = cobs::encode(&raw[..raw_len], &mut frame);
    assert_eq!(decode::<Request>(&mut frame[..len]), Err(FrameError::Version { got: PROTOCOL_VERSION + 1 }));
}

#[test]
fn truncated_frames_are_refused() {
    let mut frame = [0u8; MAX_FRAME_LEN];
    let len = encode(7, &Request::Capture { seconds: 10 }, &mut frame).unwrap() - 1;
    for cut in 0..len {
        let mut copy = frame;
        assert!(decode::<Request>(&mut copy[..cut]).is_err(), "frame cut to {cut} bytes decoded");
    }
}

#[test]
fn accumulator_splits_a_stream_into_frames_and_skips_garbage_and_overlong_ones() {
    let mut stream = Vec::new();
    let mut frame = [0u8; MAX_FRAME_LEN];
    stream.extend_from_slice(&[0x55; MAX_FRAME_LEN + 10]); // line noise, longer than any frame
    stream.push(0);
    for (id, request) in every_request().iter().enumerate() {
        let len = encode(id as u16, request, &mut frame).unwrap();
        stream.extend_from_slice(&frame[..len]);
        stream.push(0); // empty frames are skipped
    }
    let mut accumulator = FrameAccumulator::new();
    let (mut decoded, mut oversized) = (Vec::new(), 0);
    for byte in stream {
        match accumulator.feed(byte) {
            Feed::Pending => {}
            Feed::Oversized => oversized += 1,
            Feed::Frame(bytes) => decoded.push(decode::<Request>(bytes).unwrap()),
        }
    }
    assert_eq!(oversized, 1);
    let expected: Vec<_> = every_request().into_iter().enumerate().map(|(i, r)| (i as u16, r)).collect();
    assert_eq!(decoded, expected);
}

proptest! {
    #[test]
    fn decoding_arbitrary_bytes_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..2 * MAX_FRAME_LEN)) {
        let mut accumulator = FrameAccumulator::new();
        for byte in bytes.iter().copied().chain([0]) {
            if let Feed::Frame(frame) = accumulator.feed(byte) {
                let _ = decode::<Request>(frame);
            }
        }
        let mut copy = bytes.clone();
        let _ = decode::<Response>(&mut copy);
    }

    #[test]
    fn random_corruption_of_a_frame_is_never_accepted_as_a_different_message(
        position in 0usize..64, value in any::<u8>(), which in 0usize..11,
    ) {
        let request = every_request()[which].clone();
        let mut frame = [0u8; MAX_FRAME_LEN];
        let len = encode(9, &request, &mut frame).unwrap() - 1;
        let at = position % len;
        prop_assume!(frame[at] != value);
        frame[at] = value;
        let result = decode::<Request>(&mut frame[..len]);
        prop_assert!(result.is_err(), "corrupted frame decoded as {:?}", result);
    }
}

#[test]
fn a_serial_number_reads_as_24_hex_digits_most_significant_byte_first() {
    let serial = SerialNumber([0x00, 0x1F, 0xA0, 0x5B, 0x12, 0x34, 0x56, 0x78, 0x9A, 0xBC, 0xDE, 0xF0]);
    assert_eq!(&serial.hex(), b"001FA05B123456789ABCDEF0");
}
