//! `--sim-part` and `--sim-faulty-axis`: which simulated part a simulated board carries.

use firmware::sim::part::SimPart;

/// The simulated part (register map, temperature formula, factory trim, self-test response).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum SimPartChoice {
    /// A genuine MPU-6050 (WHO_AM_I 0x68).
    #[default]
    Mpu6050,
    /// An MPU-6500 (0x70).
    Mpu6500,
    /// An MPU-9250 without its magnetometer (0x71).
    Mpu9250,
    /// An ICM-20689 (0x98).
    Icm20689,
    /// A part answering 0x72, no InvenSense part, that behaves as the MPU-6500 family.
    Unknown72,
}

/// The axis whose self-test response is made 20 % off its factory trim (accelerometer and gyro).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FaultyAxis {
    X,
    Y,
    Z,
}

impl SimPartChoice {
    /// The simulated part, with its faulty axis if one is given.
    pub fn part(self, faulty: Option<FaultyAxis>) -> SimPart {
        let part = match self {
            SimPartChoice::Mpu6050 => SimPart::mpu6050(),
            SimPartChoice::Mpu6500 => SimPart::mpu6500(),
            SimPartChoice::Mpu9250 => SimPart::mpu9250(),
            SimPartChoice::Icm20689 => SimPart::icm20689(),
            SimPartChoice::Unknown72 => SimPart::unknown72(),
        };
        match faulty {
            Some(axis) => part.with_faulty_axis(axis as usize),
            None => part,
        }
    }
}
