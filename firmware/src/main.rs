//! The board binary for the STM32F411CE "Black Pill": clocks, LED and the USB CDC-ACM serial port.
//!
//! Setup only; everything the board does lives in the `firmware` library, where host tests reach it.
//! On the host this file builds to an empty program so that `cargo test --workspace` stays plain.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {}

#[cfg(target_os = "none")]
mod board {
    use defmt::{info, warn};
    use embassy_embedded_hal::adapter::BlockingAsync;
    use embassy_executor::Spawner;
    use embassy_futures::join::join;
    use embassy_futures::select::{select, Either};
    use embassy_stm32::flash::Flash;
    use embassy_stm32::gpio::{Level, Output, Speed};
    use embassy_stm32::i2c::{self, I2c};
    use embassy_stm32::time::Hertz;
    use embassy_stm32::{bind_interrupts, peripherals, usb, Config};
    use embassy_time::{Duration, Instant, Timer};
    use embassy_usb::class::cdc_acm::{CdcAcmClass, State};
    use embassy_usb::Builder;
    use firmware::board::CALIBRATION_FLASH_RANGE;
    use firmware::device::Device;
    use firmware::server::Server;
    use shared::protocol::{SerialNumber, MAX_FRAME_LEN, USB_MANUFACTURER, USB_PID, USB_PRODUCT, USB_VID};
    use {defmt_rtt as _, panic_probe as _};

    bind_interrupts!(struct Irqs {
        OTG_FS => usb::InterruptHandler<peripherals::USB_OTG_FS>;
    });

    /// USB full-speed bulk packet size in bytes.
    const USB_PACKET_LEN: u16 = 64;
    /// How often the device drains the sensor FIFO (1 kHz sampling fills 14 bytes/ms of 1024).
    const POLL_PERIOD: Duration = Duration::from_millis(10);
    /// How long the LED flashes fast after an error.
    const ERROR_SHOWN_FOR: Duration = Duration::from_secs(3);

    /// 96 MHz system clock and the 48 MHz USB clock from the Black Pill's 25 MHz crystal.
    fn clocks() -> Config {
        use embassy_stm32::rcc::{AHBPrescaler, APBPrescaler, Hse, HseMode, Pll, PllMul, PllPDiv, PllPreDiv};
        use embassy_stm32::rcc::{PllQDiv, PllSource, Sysclk};
        let mut config = Config::default();
        config.rcc.hse = Some(Hse { freq: Hertz(25_000_000), mode: HseMode::Oscillator });
        config.rcc.pll_src = PllSource::HSE;
        // NOTE: 25 MHz / 25 * 192 = 192 MHz VCO; / 2 = 96 MHz system clock (the F411 tops out at
        // 100 MHz); / 4 = 48 MHz, which USB OTG FS requires exactly (RM0383 section 6.2).
        config.rcc.pll = Some(Pll {
            prediv: PllPreDiv::DIV25,
            mul: PllMul::MUL192,
            divp: Some(PllPDiv::DIV2),
            divq: Some(PllQDiv::DIV4),
            divr: None,
        });
        config.rcc.ahb_pre = AHBPrescaler::DIV1;
        config.rcc.apb1_pre = APBPrescaler::DIV2; // APB1 at most 50 MHz
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

    /// The LED on PC13 (lit when low): slow heartbeat idle, steady while capturing or streaming,
    /// fast flashing for a few seconds after an error.
    fn led_level(busy: bool, last_error: Option<Instant>) -> Level {
        let now = Instant::now();
        let millis = now.as_millis();
        let lit = match last_error {
            Some(at) if now - at < ERROR_SHOWN_FOR => millis % 200 < 100,
            _ if busy => true,
            _ => millis % 1000 < 100,
        };
        if lit {
            Level::Low
        } else {
            Level::High
        }
    }

    #[embassy_executor::main]
    async fn main(_spawner: Spawner) {
        let p = embassy_stm32::init(clocks());
        info!("accelcal firmware {}", env!("CARGO_PKG_VERSION"));
        let mut led = Output::new(p.PC13, Level::High, Speed::Low);

        let mut i2c_config = i2c::Config::default();
        i2c_config.frequency = Hertz::khz(400);
        let i2c = I2c::new_blocking(p.I2C1, p.PB6, p.PB7, i2c_config);
        let flash = BlockingAsync::new(Flash::new_blocking(p.FLASH));
        let serial = SerialNumber(unique_id());
        let serial_text = serial.hex();
        // NOTE: the device is moved into the server inside this block, so that the main task's state
        // does not keep room for both across the await below (that doubled the device in static RAM).
        let mut server = {
            let Ok(device) = Device::boot(i2c, flash, CALIBRATION_FLASH_RANGE, serial).await else {
                // NOTE: only a flash range that does not fit the chip fails here: a build error.
                defmt::panic!("calibration flash range does not fit the flash");
            };
            info!("calibration active: {}", device.active_calibration().is_some());
            Server::new(device)
        };

        let mut ep_out_buffer = [0u8; 256];
        let mut usb_config = usb::Config::default();
        // NOTE: the Black Pill does not route VBUS to PA9, so VBUS sensing must stay off.
        usb_config.vbus_detection = false;
        let driver = usb::Driver::new_fs(p.USB_OTG_FS, Irqs, p.PA12, p.PA11, &mut ep_out_buffer, usb_config);
        let config = usb_identity(&serial_text);
        let mut config_descriptor = [0; 256];
        let mut bos_descriptor = [0; 256];
        let mut control_buf = [0; 64];
        let mut state = State::new();
        let mut builder =
            Builder::new(driver, config, &mut config_descriptor, &mut bos_descriptor, &mut [], &mut control_buf);
        let mut class = CdcAcmClass::new(&mut builder, &mut state, USB_PACKET_LEN);
        let mut usb = builder.build();

        join(usb.run(), serve(&mut server, &mut class, &mut led)).await;
    }

    /// The board's USB identity: shared's ids and strings, and its own serial number (24 hex digits).
    fn usb_identity(serial_text: &[u8; 24]) -> embassy_usb::Config<'_> {
        let mut config = embassy_usb::Config::new(USB_VID, USB_PID);
        config.manufacturer = Some(USB_MANUFACTURER);
        config.product = Some(USB_PRODUCT);
        // NOTE: hex digits are ASCII, so the conversion cannot fail.
        config.serial_number = core::str::from_utf8(serial_text).ok();
        config
    }

    /// Serves the USB serial port for ever: the library's serve step, with the LED showing what
    /// the device does.
    async fn serve<'d, I, E, F>(server: &mut Server<I, F>, class: &mut UsbSerial<'d>, led: &mut Output<'_>)
    where
        I: embedded_hal::blocking::i2c::Write<Error = E> + embedded_hal::blocking::i2c::WriteRead<Error = E>,
        F: embedded_storage_async::nor_flash::NorFlash,
    {
        let mut last_error = None;
        loop {
            let mut packet = [0u8; USB_PACKET_LEN as usize];
            let connected = class.dtr();
            match select(class.read_packet(&mut packet), Timer::after(POLL_PERIOD)).await {
                Either::First(Ok(n)) => server.receive(&packet[..n]).await,
                Either::First(Err(_)) => Timer::after(POLL_PERIOD).await, // not connected yet
                Either::Second(()) => server.poll(),
            }
            let mut buffer = [0u8; MAX_FRAME_LEN];
            while let Some((frame, is_error)) = server.next_frame(&mut buffer) {
                if is_error {
                    // NOTE: core::fmt of the error (it holds floats) would cost 15 KiB of flash;
                    // the host names the error, the log only marks that one happened.
                    warn!("a request was answered with an error");
                    last_error = Some(Instant::now());
                }
                if connected {
                    send(class, frame).await;
                }
            }
            led.set_level(led_level(server.device().is_busy(), last_error));
        }
    }

    /// The CDC-ACM serial port on the USB OTG FS peripheral.
    type UsbSerial<'d> = CdcAcmClass<'d, usb::Driver<'d, peripherals::USB_OTG_FS>>;

    /// Writes one frame in USB packets, ending a transfer that fills whole packets with an empty one.
    async fn send(class: &mut UsbSerial<'_>, frame: &[u8]) {
        for chunk in frame.chunks(USB_PACKET_LEN as usize) {
            if class.write_packet(chunk).await.is_err() {
                return; // host gone: the response is dropped, the device carries on
            }
        }
        if frame.len().is_multiple_of(USB_PACKET_LEN as usize) {
            let _ = class.write_packet(&[]).await;
        }
    }
}
