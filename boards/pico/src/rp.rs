//! The RP2040 and RP2350 setup, built for the board only.

use embassy_embedded_hal::adapter::BlockingAsync;
use embassy_executor::Spawner;
use embassy_rp::flash::{Blocking, Flash};
use embassy_rp::gpio::{Level, Output};
use embassy_rp::i2c::{self, I2c};
use embassy_rp::peripherals::USB;
use embassy_rp::{bind_interrupts, usb};
use firmware::board::{serial_number, EmbassyClock, LedPin};
use firmware::device::Device;
use firmware::server::Server;
use firmware::usb::{serve_usb, UsbBuffers};
use panic_halt as _;

bind_interrupts!(struct Irqs {
    USBCTRL_IRQ => usb::InterruptHandler<USB>;
});

/// Flash size and the calibration's range in it: the last 64 KiB, which the memory map keeps out
/// of FLASH (sixteen 4 KiB sectors; sequential-storage needs at least two).
#[cfg(feature = "pico")]
const FLASH_SIZE: usize = 2 * 1024 * 1024;
#[cfg(feature = "pico2")]
const FLASH_SIZE: usize = 4 * 1024 * 1024;
const CALIBRATION_FLASH_RANGE: core::ops::Range<u32> = (FLASH_SIZE as u32 - 0x1_0000)..FLASH_SIZE as u32;

/// The block the RP2350's boot ROM needs to start the image (RP2350 datasheet 5.9.5).
#[cfg(feature = "pico2")]
#[unsafe(link_section = ".start_block")]
#[used]
static IMAGE_DEF: embassy_rp::block::ImageDef = embassy_rp::block::ImageDef::secure_exe();

/// The chip's unique id: the RP2040's flash chip's 64-bit unique id, or the RP2350's OTP chip id.
fn unique_id(flash: &mut Flash<'_, embassy_rp::peripherals::FLASH, Blocking, FLASH_SIZE>) -> [u8; 8] {
    #[cfg(feature = "pico")]
    {
        let mut id = [0u8; 8];
        let _ = flash.blocking_unique_id(&mut id);
        id
    }
    #[cfg(feature = "pico2")]
    {
        let _ = flash;
        embassy_rp::otp::get_chipid().unwrap_or(0).to_be_bytes()
    }
}

#[embassy_executor::main]
async fn main(_spawner: Spawner) {
    let p = embassy_rp::init(Default::default());
    // NOTE: the Pico's LED is on GP25, lit when high (the Pico W's is on its radio chip instead).
    let mut led = LedPin::active_high(Output::new(p.PIN_25, Level::Low));
    let mut i2c_config = i2c::Config::default();
    i2c_config.frequency = 400_000;
    // NOTE: blocking I2C behind the async trait, as on the Black Pill: a FIFO read takes well under
    // the 10 ms poll period, and the interrupt-driven driver does not fit the 64 KiB budget.
    let i2c = BlockingAsync::new(I2c::new_blocking(p.I2C0, p.PIN_5, p.PIN_4, i2c_config));
    let mut flash = Flash::<_, Blocking, FLASH_SIZE>::new_blocking(p.FLASH);
    let serial = serial_number(&unique_id(&mut flash));
    // NOTE: the device is moved into the server inside this block, so that the main task's state does
    // not keep room for both across the await below (that doubled the device in static RAM).
    let mut server = {
        let Ok(device) = Device::boot(i2c, BlockingAsync::new(flash), CALIBRATION_FLASH_RANGE, serial).await else {
            // NOTE: only a flash range that does not fit the chip fails here: a build error.
            panic!("calibration flash range does not fit the flash");
        };
        Server::new(device)
    };
    let driver = usb::Driver::new(p.USB, Irqs);
    let mut buffers = UsbBuffers::default();
    serve_usb(driver, &mut buffers, &mut server, &mut led, &mut EmbassyClock).await;
}
