//! Twenty sketches people run on an MPU-6050, each printing a [`PersonSession`] as it would: the
//! lines it prints before its data, each sample's line (and the records it prints between), its
//! pace, and its line ending. What `sim --sketch` replays on a pseudo-terminal and the stream tests
//! read.

use std::f64::consts::PI;

use super::person::{ChipSample, PersonSession, Reading};

mod more;

/// A sketch as people run it.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr, strum::EnumIter, strum::EnumMessage,
)]
#[strum(serialize_all = "kebab-case")]
pub enum Sketch {
    /// i2cdevlib's MPU6050_raw: `a/g:` and six counts, tab-separated, about 9 Hz, CRLF.
    I2cdevlib,
    /// Adafruit's calibration sketch for MotionCal: `Raw:` counts at about 51 Hz, `Uni:`/`Cal1:`/`Cal2:` between.
    Motioncal,
    /// Adafruit_MPU6050's plotter example: m/s^2 and rad/s with two decimals, about 57 Hz, low-pass 21 Hz.
    Plotter,
    /// An ESP32 logger: boot lines, a header, `millis,ax,ay,az,gx,gy,gz` in counts at 100 Hz, low-pass 44 Hz.
    Csv,
    /// MicroPython on a Pico: the REPL banner, then `(ax, ay, az)` in g with four decimals, about 19 Hz, LF.
    Micropython,
    /// A sketch for the Arduino Serial Plotter: `ax:..,ay:..,...,gz:..` counts, about 50 Hz, low-pass 44 Hz.
    SerialPlotter,
    /// A C program on a single-board computer: six counts separated by spaces, 100 Hz, low-pass 44 Hz, LF.
    Whitespace,
    /// A logger writing Kalibr's IMU CSV: a header, then ns, rad/s and m/s^2, 200 Hz, low-pass 94 Hz, LF.
    Kalibr,
    /// The Arduino Playground's MPU-6050 example: `AcX = 1234 | AcY = ... | GyZ = ...` counts, about 3 Hz.
    Playground,
    /// Adafruit_MPU6050's `basic_readings`: a sample over three lines and an empty one, m/s^2 and rad/s, 2 Hz.
    BasicReadings,
    /// An ESP32 logger printing a JSON object a sample (ArduinoJson): millis, m/s^2, rad/s, 50 Hz.
    Esp32Json,
    /// MicroPython printing a dictionary of counts (`{'GyZ': -46, ..., 'AcX': 516}`), about 20 Hz.
    MicropythonDict,
    /// ESPHome's mpu6050 sensor logged at DEBUG: ANSI colours, `[D][sensor:093]:`, eight lines a sample, 10 Hz.
    Esphome,
    /// Six counts comma-separated, each line ended by a carriage return alone, 50 Hz.
    CrOnly,
    /// A European-locale CSV: seconds, g and deg/s with decimal commas, separated by semicolons, 50 Hz.
    SemicolonCsv,
    /// Espressif's mpu6050 component test: ESP-IDF log lines `I (ms) tag: acce_x:0.01, ...`, coloured, 10 Hz.
    EspIdf,
    /// kriswiner's MPU6050IMU: `X-acceleration: 12.30 mg ...`, gyro in degrees/s, over three lines, 2 Hz.
    Kriswiner,
    /// CircuitPython printing a list of m/s^2 and rad/s: `[0.119713, ...]`, 20 Hz.
    Array,
    /// MicroPython printing several arguments: `Accel: 0.01 -0.02 0.99 Gyro: 0.1 0.2 0.3`, 20 Hz.
    Grouped,
    /// The registers in their order with no label: accelerometer, temperature and gyro counts, tab-separated, 20 Hz.
    Registers,
}

/// What the ESP32's ROM prints at power-on (the logger's lines come after it).
const ESP32_BOOT: &str = "ets Jun  8 2016 00:22:57\r\n\r\nrst:0x1 (POWERON_RESET),boot:0x13 (SPI_FAST_FLASH_BOOT)\r\n\
configsip: 0, SPIWP:0xee\r\nclk_drv:0x00,q_drv:0x00,d_drv:0x00,cs0_drv:0x00,hd_drv:0x00,wp_drv:0x00\r\n\
mode:DIO, clock div:1\r\nload:0x3fff0030,len:1184\r\nentry 0x400805e4\r\nmillis,ax,ay,az,gx,gy,gz\r\n";

/// A line of the stream and when the sketch prints it.
#[derive(Debug, Clone, PartialEq)]
pub struct TimedLine {
    /// Seconds since the sketch started.
    pub at_s: f64,
    /// The line with its ending.
    pub text: String,
}

impl Sketch {
    /// Every sketch.
    pub const ALL: [Sketch; 20] = [
        Sketch::I2cdevlib,
        Sketch::Motioncal,
        Sketch::Plotter,
        Sketch::Csv,
        Sketch::Micropython,
        Sketch::SerialPlotter,
        Sketch::Whitespace,
        Sketch::Kalibr,
        Sketch::Playground,
        Sketch::BasicReadings,
        Sketch::Esp32Json,
        Sketch::MicropythonDict,
        Sketch::Esphome,
        Sketch::CrOnly,
        Sketch::SemicolonCsv,
        Sketch::EspIdf,
        Sketch::Kriswiner,
        Sketch::Array,
        Sketch::Grouped,
        Sketch::Registers,
    ];

    /// How it reads the chip.
    pub fn reading(self) -> Reading {
        let (rate_hz, filtered) = match self {
            Sketch::I2cdevlib => (9.0, false),
            Sketch::Motioncal => (51.0, false),
            Sketch::Plotter => (57.0, true),
            Sketch::Csv => (100.0, true),
            Sketch::Micropython => (19.0, false),
            Sketch::SerialPlotter => (50.0, true),
            Sketch::Whitespace => (100.0, true),
            Sketch::Kalibr => (200.0, true),
            Sketch::Playground => (3.0, false),
            Sketch::BasicReadings | Sketch::Kriswiner => (2.0, true),
            Sketch::Esp32Json | Sketch::CrOnly | Sketch::SemicolonCsv => (50.0, true),
            Sketch::MicropythonDict | Sketch::Array | Sketch::Grouped | Sketch::Registers => (20.0, false),
            Sketch::Esphome | Sketch::EspIdf => (10.0, true),
        };
        Reading { rate_hz, filtered }
    }

    /// The units of its accelerometer's values in a g, as it prints them.
    pub fn accel_per_g(self) -> f64 {
        match self {
            Sketch::I2cdevlib | Sketch::Csv | Sketch::SerialPlotter | Sketch::Whitespace => 16384.0,
            Sketch::Playground | Sketch::MicropythonDict | Sketch::CrOnly | Sketch::Registers => 16384.0,
            Sketch::Motioncal => 9.80665 * 8192.0 / 9.8,
            Sketch::Plotter | Sketch::Kalibr | Sketch::BasicReadings | Sketch::Esp32Json => 9.80665,
            Sketch::Esphome | Sketch::Array => 9.80665,
            Sketch::Micropython | Sketch::SemicolonCsv | Sketch::EspIdf | Sketch::Grouped => 1.0,
            Sketch::Kriswiner => 1000.0,
        }
    }

    /// Everything it prints for a session.
    pub fn lines(self, session: &PersonSession) -> Vec<TimedLine> {
        let mut lines = vec![TimedLine { at_s: 0.0, text: self.start().to_owned() }];
        for (k, sample) in session.samples.iter().enumerate() {
            lines.push(TimedLine { at_s: sample.at_s, text: self.line(sample, k) });
        }
        lines
    }

    /// What it prints before its first sample.
    fn start(self) -> &'static str {
        match self {
            Sketch::I2cdevlib => "Initializing I2C devices...\r\nTesting device connections...\r\nMPU6050 connection successful\r\n",
            Sketch::Motioncal => "Adafruit SensorLab - Calibration\r\nFound MPU6050\r\n",
            Sketch::Plotter => "Adafruit MPU6050 test!\r\nMPU6050 Found!\r\n",
            Sketch::Csv => ESP32_BOOT,
            Sketch::Micropython => {
                "MicroPython v1.22.2 on 2024-02-22; Raspberry Pi Pico with RP2040\nType \"help()\" for more information.\n>>> import logger\n"
            }
            Sketch::SerialPlotter => "MPU6050 ready\r\n",
            Sketch::Whitespace => "",
            Sketch::Kalibr => "timestamp,omega_x,omega_y,omega_z,alpha_x,alpha_y,alpha_z\n",
            Sketch::BasicReadings => "Adafruit MPU6050 test!\r\nMPU6050 Found!\r\nAccelerometer range set to: +-8G\r\n\
                Gyro range set to: +- 500 deg/s\r\nFilter bandwidth set to: 21 Hz\r\n\r\n",
            Sketch::Esphome => "\u{1b}[0;32m[I][app:029]: Running through setup()...\u{1b}[0m\r\n",
            Sketch::SemicolonCsv => "Zeit;ax;ay;az;gx;gy;gz\r\n",
            Sketch::EspIdf => "\u{1b}[0;32mI (312) mpu6050 test: mpu6050 device ID is: 0x68\n\u{1b}[0m\n",
            Sketch::MicropythonDict | Sketch::Array | Sketch::Grouped => {
                "MicroPython v1.22.2 on 2024-02-22; ESP32 module with ESP32\r\nType \"help()\" for more information.\r\n"
            }
            Sketch::Playground | Sketch::Esp32Json | Sketch::CrOnly | Sketch::Kriswiner | Sketch::Registers => "",
        }
    }

    fn line(self, s: &ChipSample, k: usize) -> String {
        let [ax, ay, az] = s.accel.map(f64::from);
        let [gx, gy, gz] = s.gyro.map(f64::from);
        match self {
            Sketch::I2cdevlib => format!("a/g:\t{ax}\t{ay}\t{az}\t{gx}\t{gy}\t{gz}\r\n"),
            Sketch::Motioncal => motioncal(s, k),
            Sketch::Plotter => plotter(s),
            Sketch::Csv => format!("{},{ax},{ay},{az},{gx},{gy},{gz}\r\n", (s.at_s * 1000.0).round() as i64 + 312),
            Sketch::Micropython => format!("({:.4}, {:.4}, {:.4})\n", ax / 16384.0, ay / 16384.0, az / 16384.0),
            Sketch::SerialPlotter => format!("ax:{ax},ay:{ay},az:{az},gx:{gx},gy:{gy},gz:{gz}\r\n"),
            Sketch::Whitespace => format!("{ax} {ay} {az} {gx} {gy} {gz}\n"),
            Sketch::Kalibr => kalibr(s),
            Sketch::Playground => more::playground(s),
            Sketch::BasicReadings => more::basic_readings(s),
            Sketch::Esp32Json => more::esp32_json(s),
            Sketch::MicropythonDict => more::micropython_dict(s),
            Sketch::Esphome => more::esphome(s),
            Sketch::CrOnly => more::cr_only(s),
            Sketch::SemicolonCsv => more::semicolon_csv(s),
            Sketch::EspIdf => more::esp_idf(s),
            Sketch::Kriswiner => more::kriswiner(s),
            Sketch::Array => more::array(s),
            Sketch::Grouped => more::grouped(s),
            Sketch::Registers => more::registers(s),
        }
    }
}

/// Adafruit's sketch: `int(m/s^2 * 8192 / 9.8)` and `int(deg/s * 16)` (truncated, as C's cast does),
/// the magnetometer absent (zeros), then the same in SI units; the calibration it was sent every 50 lines.
fn motioncal(s: &ChipSample, k: usize) -> String {
    let ms2 = s.accel.map(|c| f64::from(c) / 16384.0 * 9.80665);
    let rads = s.gyro.map(|c| f64::from(c) / 131.0 * PI / 180.0);
    let a = ms2.map(|v| (v * 8192.0 / 9.8) as i64);
    let g = rads.map(|v| (v.to_degrees() * 16.0) as i64);
    let mut text = format!("Raw:{},{},{},{},{},{},0,0,0\r\n", a[0], a[1], a[2], g[0], g[1], g[2]);
    text += &format!(
        "Uni:{:.2},{:.2},{:.2},{:.4},{:.4},{:.4},0.0,0.0,0.0\r\n",
        ms2[0], ms2[1], ms2[2], rads[0], rads[1], rads[2]
    );
    if k % 50 == 49 {
        text += "Cal1:0.000,0.000,0.000,0.000,0.000,0.000,0.000,0.000,0.000,50.000\r\nCal2:1.000,0.000,0.000,0.000,1.000,0.000,0.000,0.000,1.000\r\n";
    }
    text
}

/// Adafruit_MPU6050 at +-8 g and +-500 deg/s, printed with Serial.print's two decimals.
fn plotter(s: &ChipSample) -> String {
    let (ms2, rads) = more::adafruit_si(s);
    format!(
        "AccelX:{:.2},AccelY:{:.2},AccelZ:{:.2}, GyroX:{:.2},GyroY:{:.2},GyroZ:{:.2}\r\n",
        ms2[0], ms2[1], ms2[2], rads[0], rads[1], rads[2]
    )
}

/// Kalibr's IMU CSV: nanoseconds (from an epoch of November 2026), rad/s and m/s^2, as such loggers
/// write them (full precision; six decimals here).
fn kalibr(s: &ChipSample) -> String {
    let ns = 1_795_000_000_000_000_000u64 + (s.at_s * 1e9).round() as u64;
    let ms2 = s.accel.map(|c| f64::from(c) / 16384.0 * 9.80665);
    let rads = s.gyro.map(|c| (f64::from(c) / 131.0).to_radians());
    format!("{ns},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}\n", rads[0], rads[1], rads[2], ms2[0], ms2[1], ms2[2])
}
