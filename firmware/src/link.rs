//! The serial link: bytes from the host become requests for the [`Device`], its responses become
//! frames. Shared by the board's USB loop, the host's in-process simulated device and its
//! pseudo-terminal device, so every one of them speaks exactly the board's protocol.

use embedded_hal_async::i2c::I2c;
use embedded_storage_async::nor_flash::NorFlash;
use shared::protocol::{self, Feed, FrameAccumulator, Request, Response, MAX_FRAME_LEN};

use crate::device::Device;

/// Frames in, frames out.
#[derive(Debug, Default)]
pub struct Link {
    accumulator: FrameAccumulator,
}

impl Link {
    /// A link with nothing received yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Feeds received bytes; every complete frame is decoded and handed to the device, and every
    /// unreadable frame answered with an error. Responses wait in the device's outbox.
    pub async fn receive<I, F>(&mut self, bytes: &[u8], device: &mut Device<I, F>)
    where
        I: I2c,
        F: NorFlash,
    {
        for &byte in bytes {
            let decoded = match self.accumulator.feed(byte) {
                Feed::Pending => continue,
                Feed::Oversized => Err(protocol::FrameError::Oversized),
                Feed::Frame(frame) => protocol::decode::<Request>(frame),
            };
            match decoded {
                Ok((request_id, request)) => device.handle(request_id, request).await,
                Err(error) => device.reject_frame(error),
            }
        }
    }

    /// Encodes a response into `buffer`; the frame, delimiter included.
    pub fn encode<'b>(request_id: u16, response: &Response, buffer: &'b mut [u8; MAX_FRAME_LEN]) -> &'b [u8] {
        match protocol::encode(request_id, response, buffer) {
            Ok(len) => &buffer[..len],
            // NOTE: every response fits a frame (shared's size tests); should one ever not, the
            // host still gets an answer rather than silence.
            Err(error) => {
                let fallback = Response::Error(protocol::DeviceError::Frame(error));
                let len = protocol::encode(request_id, &fallback, buffer).unwrap_or(0);
                &buffer[..len]
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use embassy_futures::block_on;
    use shared::protocol::{decode, encode, DeviceError, FrameError, PROTOCOL_VERSION};

    use super::*;
    use crate::sim::flash::RamFlash;
    use crate::sim::{sim_serial_number, SimMpu6050};

    fn responses(device: &mut Device<SimMpu6050, RamFlash<2048, 4>>) -> Vec<(u16, Response)> {
        let mut out = Vec::new();
        while let Some((id, response)) = device.next_response() {
            let mut buffer = [0u8; MAX_FRAME_LEN];
            let frame = Link::encode(id, &response, &mut buffer).to_vec();
            let mut body = frame[..frame.len() - 1].to_vec();
            out.push(decode::<Response>(&mut body).expect("device frames decode"));
        }
        out
    }

    #[test]
    fn requests_split_across_reads_are_answered_and_garbage_is_answered_with_an_error() {
        let mut device =
            block_on(Device::boot(SimMpu6050::new(1), RamFlash::<2048, 4>::new(), 0..8192, sim_serial_number(1)))
                .unwrap();
        let mut link = Link::new();
        let mut frame = [0u8; MAX_FRAME_LEN];
        let len = encode(42, &Request::Hello { protocol_version: PROTOCOL_VERSION }, &mut frame).unwrap();
        let mut stream = vec![0x13, 0x37, 0x00]; // line noise, then a delimiter
        stream.extend_from_slice(&frame[..len]);
        for chunk in stream.chunks(5) {
            block_on(link.receive(chunk, &mut device));
        }
        let answers = responses(&mut device);
        assert_eq!(answers.len(), 2, "{answers:?}");
        assert_eq!(answers[0], (0, Response::Error(DeviceError::Frame(FrameError::Cobs))));
        assert!(matches!(answers[1], (42, Response::Hello(_))));
    }
}
