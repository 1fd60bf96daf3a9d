//! The STM32 setup, built for the board only.

use embassy_embedded_hal::adapter::BlockingAsync;
use embassy_executor::Spawner;
use embassy_stm32::flash::Flash;
use embassy_stm32::gpio::{Level, Output, Speed};
use embassy_stm32::i2c::{self, I2c};
use embassy_stm32::time::Hertz;
use embassy_stm32::{bind_interrupts, peripherals, usb, Config};
use firmware::board::{serial_number, EmbassyClock, LedPin};
use firmware::device::Device;
use firmware::server::Server;
use firmware::usb::{serve_usb, UsbBuffers};
use panic_halt as _;

bind_interrupts!(struct Irqs {
    OTG_FS => usb::InterruptHandler<peripherals::USB_OTG_FS>;
});

/// Byte offsets, from the start of flash, of the sectors holding the calibration: sectors 6 and 7
/// (0x08040000-0x0807FFFF, 128 KiB each, RM0383 table 5 and RM0368 table 5, the same on both
/// chips). `memory.x` keeps them out of FLASH as its CALIBRATION region; the two must agree.
const CALIBRATION_FLASH_RANGE: core::ops::Range<u32> = 0x0004_0000..0x0008_0000;

/// The PLL from the 25 MHz crystal: VCO = 25 MHz / 25 * MUL; the system clock VCO / 2 or / 4,
/// and the 48 MHz USB OTG FS needs exactly, VCO / Q (RM0383 and RM0368 section 6.2).
#[cfg(feature = "f411")]
mod pll {
    use embassy_stm32::rcc::{PllMul, PllPDiv, PllQDiv};
    /// 192 MHz VCO: 96 MHz system clock (the F411 tops out at 100 MHz), 48 MHz USB.
    pub const MUL: PllMul = PllMul::MUL192;
    pub const P: PllPDiv = PllPDiv::DIV2;
    pub const Q: PllQDiv = PllQDiv::DIV4;
}
#[cfg(feature = "f401")]
mod pll {
    use embassy_stm32::rcc::{PllMul, PllPDiv, PllQDiv};
    /// 336 MHz VCO: 84 MHz system clock (the F401's maximum), 48 MHz USB.
    pub const MUL: PllMul = PllMul::MUL336;
    pub const P: PllPDiv = PllPDiv::DIV4;
    pub const Q: PllQDiv = PllQDiv::DIV7;
}

fn clocks() -> Config {
    use embassy_stm32::rcc::{AHBPrescaler, APBPrescaler, Hse, HseMode, Pll, PllPreDiv, PllSource, Sysclk};
    let mut config = Config::default();
    config.rcc.hse = Some(Hse { freq: Hertz(25_000_000), mode: HseMode::Oscillator });
    config.rcc.pll_src = PllSource::HSE;
    config.rcc.pll =
        Some(Pll { prediv: PllPreDiv::DIV25, mul: pll::MUL, divp: Some(pll::P), divq: Some(pll::Q), divr: None });
    config.rcc.ahb_pre = AHBPrescaler::DIV1;
    config.rcc.apb1_pre = APBPrescaler::DIV2; // APB1 at most 50 MHz (F411) or 42 MHz (F401)
    config.rcc.apb2_pre = APBPrescaler::DIV1;
    config.rcc.sys = Sysclk::PLL1_P;
    config
}

/// The STM32's 96-bit unique device ID (RM0383 section 24.2), in memory order.
///
/// NOTE: read a word at a time: `embassy_stm32::uid::uid()` copies the 12 bytes with a memmove
/// that links 1.5 KiB of flash.
fn unique_id() -> [u8; 12] {
    let mut id = [0u8; 12];
    for (i, word) in id.chunks_exact_mut(4).enumerate() {
        word.copy_from_slice(&embassy_stm32::pac::UID.uid(i).read().to_le_bytes());
    }
    id
}

#[embassy_executor::main]
async fn main(_spawner: Spawner) {
    let p = embassy_stm32::init(clocks());
    let mut led = LedPin::active_low(Output::new(p.PC13, Level::High, Speed::Low));
    let mut i2c_config = i2c::Config::default();
    i2c_config.frequency = Hertz::khz(400);
    // NOTE: blocking I2C behind the async trait: a 14-byte-per-sample FIFO read at 400 kHz takes
    // well under the 10 ms poll period, and the DMA driver does not fit the 64 KiB budget.
    let i2c = BlockingAsync::new(I2c::new_blocking(p.I2C1, p.PB6, p.PB7, i2c_config));
    let flash = BlockingAsync::new(Flash::new_blocking(p.FLASH));
    let serial = serial_number(&unique_id());
    // NOTE: the device is moved into the server inside this block, so that the main task's state does
    // not keep room for both across the await below (that doubled the device in static RAM).
    let mut server = {
        let Ok(device) = Device::boot(i2c, flash, CALIBRATION_FLASH_RANGE, serial).await else {
            // NOTE: only a flash range that does not fit the chip fails here: a build error.
            panic!("calibration flash range does not fit the flash");
        };
        Server::new(device)
    };
    let mut ep_out_buffer = [0u8; 256];
    let mut usb_config = usb::Config::default();
    // NOTE: the Black Pill does not route VBUS to PA9, so VBUS sensing must stay off.
    usb_config.vbus_detection = false;
    let driver = usb::Driver::new_fs(p.USB_OTG_FS, Irqs, p.PA12, p.PA11, &mut ep_out_buffer, usb_config);
    let mut buffers = UsbBuffers::default();
    serve_usb(driver, &mut buffers, &mut server, &mut led, &mut EmbassyClock).await;
}
