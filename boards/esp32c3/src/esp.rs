//! The ESP32-C3 setup, built for the board only.

use core::ops::Range;

use embassy_embedded_hal::adapter::BlockingAsync;
use embassy_executor::Spawner;
use esp_bootloader_esp_idf::partitions::{read_partition_table, PARTITION_TABLE_MAX_LEN};
use esp_hal::gpio::{Level, Output, OutputConfig};
use esp_hal::i2c::master::{Config as I2cConfig, I2c};
use esp_hal::time::Rate;
use esp_hal::timer::timg::TimerGroup;
use esp_hal::usb::usb_serial_jtag::UsbSerialJtag;
use esp_storage::FlashStorage;
use firmware::board::{serial_number, serve, EmbassyClock, LedPin};
use firmware::device::Device;
use firmware::server::Server;
use panic_halt as _;

// NOTE: the application descriptor the ESP-IDF second-stage bootloader checks before it starts the
// image (and espflash requires in the ELF).
esp_bootloader_esp_idf::esp_app_desc!();

/// The label of the data partition that holds the calibration: the partition table
/// (`boards/esp32c3/partitions.csv`, flashed with the image) gives it its own 64 KiB.
const CALIBRATION_PARTITION: &str = "calibration";
/// The partition table's type of a data partition (ESP-IDF "Partition Tables": app 0, data 1).
const DATA_PARTITION: u8 = 1;

/// Where the calibration partition lies in flash, in bytes from its start; `None` when the flash
/// holds no partition table with one (the image was flashed without ours).
fn calibration_range(flash: &mut FlashStorage<'_>) -> Option<Range<u32>> {
    let mut table = [0u8; PARTITION_TABLE_MAX_LEN];
    let table = read_partition_table(flash, &mut table).ok()?;
    let partition = table
        .iter()
        .find(|entry| entry.raw_type() == DATA_PARTITION && entry.label_as_str() == CALIBRATION_PARTITION)?;
    Some(partition.offset()..partition.offset() + partition.len())
}

#[esp_rtos::main]
async fn main(_spawner: Spawner) {
    let p = esp_hal::init(esp_hal::Config::default());
    let timers = TimerGroup::new(p.TIMG0);
    esp_rtos::start(timers.timer0, p.FROM_CPU_INTR0);
    // NOTE: the ESP32-C3 SuperMini's blue LED is on GPIO8, lit when low (on Espressif's DevKitM-1
    // GPIO8 drives an addressable RGB LED instead, which stays dark).
    let mut led = LedPin::active_low(Output::new(p.GPIO8, Level::High, OutputConfig::default()));
    let i2c_config = I2cConfig::default().with_frequency(Rate::from_khz(400));
    let Ok(i2c) = I2c::new(p.I2C0, i2c_config) else {
        panic!("400 kHz is a valid I2C frequency");
    };
    let i2c = i2c.with_sda(p.GPIO4).with_scl(p.GPIO5).into_async();
    let mut flash = FlashStorage::new(p.FLASH);
    let Some(range) = calibration_range(&mut flash) else {
        // NOTE: flashing dist/accelcal-esp32c3.bin writes the partition table with the image.
        panic!("no calibration partition: flash the merged image");
    };
    let serial = serial_number(esp_hal::efuse::base_mac_address().as_bytes());
    // NOTE: the device is moved into the server inside this block, so that the main task's state does
    // not keep room for both across the await below.
    let mut server = {
        let Ok(device) = Device::boot(i2c, BlockingAsync::new(flash), range, serial).await else {
            panic!("the calibration partition does not fit the flash");
        };
        Server::new(device)
    };
    // NOTE: the chip's own USB-Serial-JTAG is the port: a CDC-ACM serial port in hardware, with
    // Espressif's fixed USB identity (303a:1001), so the host finds this board by its handshake.
    let mut port = UsbSerialJtag::new(p.USB_DEVICE).into_async();
    serve(&mut server, &mut port, &mut led, &mut EmbassyClock).await;
}
