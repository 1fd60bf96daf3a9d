//! A scripted device on the far end of an in-memory pipe: it decodes each request frame with the
//! shared protocol and answers with whatever frames the test script hands back, so a test can send
//! what no real board would (a stale answer, a window of its choosing).

use std::io::{ErrorKind, Read, Write};
use std::thread::JoinHandle;

use accelcal::link::PipeEnd;
use shared::part::Family;
use shared::protocol::{
    self, ActiveCalibration, DeviceInfo, Feed, FirmwareVersion, FrameAccumulator, Request, Response, SensorConfig,
    SensorIdentity, SerialNumber, MAX_FRAME_LEN, PROTOCOL_VERSION,
};

/// The answer to `Hello` of a healthy board with a genuine MPU-6050 and no calibration.
pub fn device_info() -> DeviceInfo {
    DeviceInfo {
        protocol_version: PROTOCOL_VERSION,
        serial: SerialNumber([0x5c; 12]),
        firmware: FirmwareVersion { major: 0, minor: 1, patch: 0 },
        sensor: Ok(SensorIdentity { address: 0x68, who_am_i: 0x68, family: Family::Mpu6050 }),
        config: SensorConfig::default(),
        active: ActiveCalibration::None,
        stored: false,
        positions: shared::PositionMap::new(),
        self_test: None,
    }
}

/// One frame as the device would send it.
pub fn frame(request_id: u16, response: &Response) -> Vec<u8> {
    let mut buffer = [0u8; MAX_FRAME_LEN];
    let len = protocol::encode(request_id, response, &mut buffer).expect("the response fits a frame");
    buffer[..len].to_vec()
}

/// Serves `port` from a thread until the other end goes away: `Hello` is answered with
/// [`device_info`], every other request with the bytes `script(id, request)` returns.
pub fn spawn(mut port: PipeEnd, mut script: impl FnMut(u16, Request) -> Vec<u8> + Send + 'static) -> JoinHandle<()> {
    std::thread::spawn(move || {
        let mut accumulator = FrameAccumulator::new();
        let mut buffer = [0u8; 256];
        loop {
            let n = match port.read(&mut buffer) {
                Ok(n) => n,
                Err(e) if e.kind() == ErrorKind::TimedOut => continue,
                Err(_) => return,
            };
            for &byte in &buffer[..n] {
                let Feed::Frame(bytes) = accumulator.feed(byte) else { continue };
                let Ok((id, request)) = protocol::decode::<Request>(bytes) else { continue };
                let answer = match request {
                    Request::Hello { .. } => frame(id, &Response::Hello(device_info())),
                    request => script(id, request),
                };
                if port.write_all(&answer).is_err() {
                    return;
                }
            }
        }
    })
}
