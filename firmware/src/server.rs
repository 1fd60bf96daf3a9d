//! The board's serve step, written once: bytes read from the port go to the link, the device is
//! polled, and its responses are encoded and written back. The board's USB loop and the host's
//! simulated board both serve through it, so both speak exactly the same protocol.

use embedded_hal_async::i2c::I2c;
use embedded_storage_async::nor_flash::NorFlash;
use shared::protocol::{Response, MAX_FRAME_LEN};

use crate::device::Device;
use crate::link::Link;

/// What one drain of the device's responses wrote.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Drained {
    /// Frames written.
    pub frames: u32,
    /// Of those, frames that carried an error (the board shows them on its LED).
    pub errors: u32,
}

/// A device and the link that frames its traffic.
pub struct Server<I, F: NorFlash> {
    device: Device<I, F>,
    link: Link,
}

impl<I, F> Server<I, F>
where
    I: I2c,
    F: NorFlash,
{
    /// Serves `device`, with nothing received yet.
    pub fn new(device: Device<I, F>) -> Self {
        Server { device, link: Link::new() }
    }

    /// The device served.
    pub fn device(&self) -> &Device<I, F> {
        &self.device
    }

    /// The device served, to act on its simulated sensor.
    pub fn device_mut(&mut self) -> &mut Device<I, F> {
        &mut self.device
    }

    /// Stops serving; the device (to reboot it on the same bus and flash).
    pub fn into_device(self) -> Device<I, F> {
        self.device
    }

    /// Hands bytes read from the port to the link: every complete request is carried out.
    pub async fn receive(&mut self, bytes: &[u8]) {
        self.link.receive(bytes, &mut self.device).await;
    }

    /// Moves a running capture or stream on.
    pub async fn poll(&mut self) {
        self.device.poll().await;
    }

    /// Encodes the next waiting response into `buffer`: the frame to write, and whether it carries
    /// an error (the board shows those on its LED). For writers that wait, such as USB.
    pub fn next_frame<'b>(&mut self, buffer: &'b mut [u8; MAX_FRAME_LEN]) -> Option<(&'b [u8], bool)> {
        let (request_id, response) = self.device.next_response()?;
        let is_error = matches!(response, Response::Error(_));
        Some((Link::encode(request_id, &response, buffer), is_error))
    }

    /// Encodes every waiting response and hands each frame to `write`, in order.
    pub fn drain(&mut self, mut write: impl FnMut(&[u8])) -> Drained {
        let mut drained = Drained::default();
        let mut buffer = [0u8; MAX_FRAME_LEN];
        while let Some((frame, is_error)) = self.next_frame(&mut buffer) {
            write(frame);
            drained.frames += 1;
            drained.errors += u32::from(is_error);
        }
        drained
    }
}

#[cfg(test)]
mod tests {
    use embassy_futures::block_on;
    use shared::protocol::{decode, encode, Request, PROTOCOL_VERSION};

    use super::*;
    use crate::sim::{sim_serial_number, SimFlash, SimMpu6050, SIM_FLASH_RANGE};

    #[test]
    fn a_request_in_two_reads_is_answered_with_one_frame_after_the_drain() {
        let serial = sim_serial_number(3);
        let device = block_on(Device::boot(SimMpu6050::new(3), SimFlash::new(), SIM_FLASH_RANGE, serial)).unwrap();
        let mut server = Server::new(device);
        let mut frame = [0u8; MAX_FRAME_LEN];
        let len = encode(5, &Request::Hello { protocol_version: PROTOCOL_VERSION }, &mut frame).unwrap();
        block_on(server.receive(&frame[..3]));
        block_on(server.receive(&frame[3..len]));
        block_on(server.poll());
        let mut written = Vec::new();
        let drained = server.drain(|frame| written.push(frame.to_vec()));
        assert_eq!(drained, Drained { frames: 1, errors: 0 });
        let mut body = written[0][..written[0].len() - 1].to_vec();
        let (id, response) = decode::<Response>(&mut body).unwrap();
        assert_eq!(id, 5);
        assert!(matches!(&response, Response::Hello(info) if info.serial == serial), "{response:?}");
    }
}
