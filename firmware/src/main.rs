//! The board binary for the STM32F411CE "Black Pill": clocks, LED and the USB CDC-ACM serial port.
//!
//! Setup only; everything the board does lives in the `firmware` library, where host tests reach it.
//! On the host this file builds to an empty program so that `cargo test --workspace` stays plain.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {}

#[cfg(target_os = "none")]
mod board {
    use defmt::info;
    use embassy_executor::Spawner;
    use embassy_futures::join::join;
    use embassy_stm32::gpio::{Level, Output, Speed};
    use embassy_stm32::time::Hertz;
    use embassy_stm32::{bind_interrupts, peripherals, usb, Config};
    use embassy_time::Timer;
    use embassy_usb::class::cdc_acm::{CdcAcmClass, State};
    use embassy_usb::Builder;
    use shared::protocol::{USB_MANUFACTURER, USB_PID, USB_PRODUCT, USB_VID};
    use {defmt_rtt as _, panic_probe as _};

    bind_interrupts!(struct Irqs {
        OTG_FS => usb::InterruptHandler<peripherals::USB_OTG_FS>;
    });

    /// USB full-speed bulk packet size in bytes.
    const USB_PACKET_LEN: u16 = 64;

    /// 96 MHz system clock and the 48 MHz USB clock from the Black Pill's 25 MHz crystal.
    fn clocks() -> Config {
        use embassy_stm32::rcc::{
            AHBPrescaler, APBPrescaler, Hse, HseMode, Pll, PllMul, PllPDiv, PllPreDiv,
        };
        use embassy_stm32::rcc::{PllQDiv, PllSource, Sysclk};
        let mut config = Config::default();
        config.rcc.hse = Some(Hse {
            freq: Hertz(25_000_000),
            mode: HseMode::Oscillator,
        });
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

    #[embassy_executor::main]
    async fn main(_spawner: Spawner) {
        let p = embassy_stm32::init(clocks());
        info!("accelcal firmware {}", env!("CARGO_PKG_VERSION"));
        // The Black Pill's blue LED on PC13 lights when the pin is low.
        let mut led = Output::new(p.PC13, Level::High, Speed::Low);

        let mut ep_out_buffer = [0u8; 256];
        let mut usb_config = usb::Config::default();
        // NOTE: the Black Pill does not route VBUS to PA9, so VBUS sensing must stay off.
        usb_config.vbus_detection = false;
        let driver = usb::Driver::new_fs(
            p.USB_OTG_FS,
            Irqs,
            p.PA12,
            p.PA11,
            &mut ep_out_buffer,
            usb_config,
        );

        let mut config = embassy_usb::Config::new(USB_VID, USB_PID);
        config.manufacturer = Some(USB_MANUFACTURER);
        config.product = Some(USB_PRODUCT);
        config.serial_number = Some("accelcal");
        let mut config_descriptor = [0; 256];
        let mut bos_descriptor = [0; 256];
        let mut control_buf = [0; 64];
        let mut state = State::new();
        let mut builder = Builder::new(
            driver,
            config,
            &mut config_descriptor,
            &mut bos_descriptor,
            &mut [],
            &mut control_buf,
        );
        let mut class = CdcAcmClass::new(&mut builder, &mut state, USB_PACKET_LEN);
        let mut usb = builder.build();

        let serial = async {
            loop {
                class.wait_connection().await;
                info!("host connected");
                let mut packet = [0u8; USB_PACKET_LEN as usize];
                while let Ok(n) = class.read_packet(&mut packet).await {
                    // NOTE: requests are answered once the firmware library's request handler lands
                    // (firmware issue); until then the port enumerates and drains what it receives.
                    info!("received {} bytes", n);
                }
                info!("host disconnected");
            }
        };
        let heartbeat = async {
            loop {
                led.toggle();
                Timer::after_millis(500).await;
            }
        };
        join(usb.run(), join(serial, heartbeat)).await;
    }
}
