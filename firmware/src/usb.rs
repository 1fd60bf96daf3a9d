//! The USB serial port of the boards with a USB device peripheral (Black Pill, Pico, Pico 2):
//! embassy-usb's CDC-ACM class with accelcal's USB identity, as an embedded-io-async byte stream
//! for [`crate::board::serve`]. Generic over the USB driver, so each board passes only its own.

use embassy_futures::join::join;
use embassy_usb::class::cdc_acm::{CdcAcmClass, State};
use embassy_usb::driver::{Driver, EndpointError};
use embassy_usb::Builder;
use embedded_hal_async::i2c::I2c;
use embedded_io_async::{ErrorKind, ErrorType, Read, Write};
use embedded_storage_async::nor_flash::NorFlash;
use shared::protocol::{USB_MANUFACTURER, USB_PID, USB_PRODUCT, USB_VID};

use crate::board::{serve, Clock, Led, READ_CHUNK_LEN};
use crate::server::Server;

/// USB full-speed bulk packet size in bytes.
const PACKET_LEN: usize = READ_CHUNK_LEN;

/// The CDC-ACM port as a byte stream. Frames written while no host holds the port open (DTR low)
/// are dropped, so a device whose host went away never blocks.
pub struct UsbSerial<'d, D: Driver<'d>> {
    class: CdcAcmClass<'d, D>,
    /// The last packet written was full: the transfer still needs its closing empty packet.
    open_transfer: bool,
}

impl<'d, D: Driver<'d>> ErrorType for UsbSerial<'d, D> {
    type Error = ErrorKind;
}

impl<'d, D: Driver<'d>> Read for UsbSerial<'d, D> {
    /// One USB packet; `buf` must hold a whole one (64 bytes).
    async fn read(&mut self, buf: &mut [u8]) -> Result<usize, ErrorKind> {
        self.class.read_packet(buf).await.map_err(endpoint_error)
    }
}

impl<'d, D: Driver<'d>> Write for UsbSerial<'d, D> {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, ErrorKind> {
        if !self.class.dtr() {
            return Ok(buf.len()); // nobody listening: dropped
        }
        let len = buf.len().min(PACKET_LEN);
        self.class.write_packet(&buf[..len]).await.map_err(endpoint_error)?;
        self.open_transfer = len == PACKET_LEN;
        Ok(len)
    }

    /// Ends a transfer that filled whole packets with an empty one, so the host's read returns.
    async fn flush(&mut self) -> Result<(), ErrorKind> {
        if core::mem::take(&mut self.open_transfer) && self.class.dtr() {
            self.class.write_packet(&[]).await.map_err(endpoint_error)?;
        }
        Ok(())
    }
}

fn endpoint_error(error: EndpointError) -> ErrorKind {
    match error {
        EndpointError::Disabled => ErrorKind::NotConnected,
        EndpointError::BufferOverflow => ErrorKind::OutOfMemory,
    }
}

/// What the USB stack keeps for as long as it runs: descriptors, control buffer, the class's
/// state and the serial number's text. A board makes one in its main task and lends it to
/// [`serve_usb`] with the driver.
pub struct UsbBuffers<'d> {
    serial_text: [u8; 24],
    config_descriptor: [u8; 256],
    bos_descriptor: [u8; 256],
    control: [u8; 64],
    state: State<'d>,
}

impl Default for UsbBuffers<'_> {
    fn default() -> Self {
        UsbBuffers {
            serial_text: [0; 24],
            config_descriptor: [0; 256],
            bos_descriptor: [0; 256],
            control: [0; 64],
            state: State::new(),
        }
    }
}

/// Runs the USB device with accelcal's identity and serves the host on it, for ever.
pub async fn serve_usb<'d, D, I, F, L, C>(
    driver: D,
    buffers: &'d mut UsbBuffers<'d>,
    server: &mut Server<I, F>,
    led: &mut L,
    clock: &mut C,
) where
    D: Driver<'d>,
    I: I2c,
    F: NorFlash,
    L: Led,
    C: Clock,
{
    buffers.serial_text = server.device().serial().hex();
    let mut builder = Builder::new(
        driver,
        identity(&buffers.serial_text),
        &mut buffers.config_descriptor,
        &mut buffers.bos_descriptor,
        &mut [],
        &mut buffers.control,
    );
    let class = CdcAcmClass::new(&mut builder, &mut buffers.state, PACKET_LEN as u16);
    let mut usb = builder.build();
    let mut port = UsbSerial { class, open_transfer: false };
    join(usb.run(), serve(server, &mut port, led, clock)).await;
}

/// The board's USB identity: shared's ids and strings, and its own serial number (24 hex digits).
fn identity(serial_text: &[u8; 24]) -> embassy_usb::Config<'_> {
    let mut config = embassy_usb::Config::new(USB_VID, USB_PID);
    config.manufacturer = Some(USB_MANUFACTURER);
    config.product = Some(USB_PRODUCT);
    // NOTE: hex digits are ASCII, so the conversion cannot fail.
    config.serial_number = core::str::from_utf8(serial_text).ok();
    config
}
