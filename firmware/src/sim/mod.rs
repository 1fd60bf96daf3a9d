//! The simulated MPU-6050: a register-level model behind the same I2C traits as the real bus, and a
//! RAM flash with power-cut injection. `no_std`, so it runs in tests, in `accelcal --sim` and under
//! QEMU alike.
//!
//! Modelled: WHO_AM_I, power (sleep), range, filter and sample-rate registers, data registers, the
//! 1024-byte FIFO with overflow (oldest bytes lost, INT_STATUS flag), 16-bit quantisation and clipping,
//! temperature; the physics are in [`physics`]. Time only passes when the owner calls
//! [`SimMpu6050::advance_us`], so runs are exactly repeatable.

mod board;
pub mod flash;
mod i2c;
pub mod part;
pub mod physics;
pub mod thermal;

use heapless::Deque;
use shared::linalg::{self, Vec3};
use shared::GyroRange;

use crate::sensor::registers as reg;
pub use board::{sim_serial_number, SimFlash, SIM_FLASH_RANGE};
pub use i2c::{BusFault, BytewiseTarget};
use part::SimPart;
use physics::{Motion, Physics};

/// Register file size: every register address is below 0x80.
const REGISTER_COUNT: usize = 0x80;
/// PWR_MGMT_1 at power-up: asleep (register map section 4.30).
const PWR_MGMT_1_RESET: u8 = 0x40;

/// A simulated MPU-6050 on an I2C bus.
#[derive(Debug, Clone)]
pub struct SimMpu6050 {
    address: u8,
    part: SimPart,
    connected: bool,
    registers: [u8; REGISTER_COUNT],
    fifo: Deque<u8, { reg::FIFO_LEN }>,
    latest: [u8; reg::FIFO_SAMPLE_LEN],
    /// The board's motion and the sensor's imperfections.
    pub physics: Physics,
    now_us: u64,
    next_sample_us: u64,
    pose_since_us: u64,
    failures_left: u32,
    failures_after: u32,
}

impl SimMpu6050 {
    /// A genuine MPU-6050 at 0x68 with the published error model, still with +Z up.
    pub fn new(seed: u64) -> Self {
        let part = SimPart::mpu6050();
        SimMpu6050 {
            address: reg::ADDRESSES[0],
            part,
            connected: true,
            registers: power_up_registers(&part),
            fifo: Deque::new(),
            latest: [0; reg::FIFO_SAMPLE_LEN],
            physics: Physics::new(seed),
            now_us: 0,
            next_sample_us: 0,
            pose_since_us: 0,
            failures_left: 0,
            failures_after: 0,
        }
    }

    /// The published static model held at 25 degC with white noise only (see [`Physics::settled`]):
    /// for tests that need one known temperature.
    pub fn settled(seed: u64) -> Self {
        SimMpu6050 { physics: Physics::settled(seed), ..SimMpu6050::new(seed) }
    }

    /// Lets `seconds` pass in one step with the FIFO not running: for long waits (a thermal soak),
    /// far cheaper than producing every sample. The data registers hold one fresh sample after it.
    pub fn elapse_seconds(&mut self, seconds: f32) {
        self.physics.elapse(seconds);
        self.now_us += (seconds * 1e6) as u64;
        self.next_sample_us = self.now_us + 1;
        self.advance_us(1);
    }

    /// Lets `seconds` pass while the board waits, idle, for the other boards on its fixture: the
    /// surroundings and the die's temperature move on, but no sample is made and the noise stream is
    /// not drawn from (the bias wander stands still), so that what the board reads after the wait is
    /// what the same board alone would have read, at the temperature the wait brought.
    pub fn wait_seconds(&mut self, seconds: f32) {
        self.physics.environment.advance(seconds);
        self.now_us += (seconds * 1e6) as u64;
    }

    /// Answers at another address (AD0 high: 0x69).
    pub fn with_address(mut self, address: u8) -> Self {
        self.address = address;
        self
    }

    /// Reports another WHO_AM_I (a clone, or an unknown chip).
    pub fn with_who_am_i(mut self, who_am_i: u8) -> Self {
        self.part.who_am_i = who_am_i;
        self
    }

    /// Becomes another simulated part (register map, temperature formula, self-test).
    pub fn with_part(mut self, part: SimPart) -> Self {
        self.part = part;
        self.registers = power_up_registers(&part);
        self
    }

    /// The simulated part.
    pub fn part(&self) -> &SimPart {
        &self.part
    }

    /// Rests the board with the body-frame direction `up` (any length) pointing up.
    pub fn place(&mut self, up: Vec3<f32>) {
        let length = linalg::norm(up);
        self.physics.up = if length > 0.0 { linalg::scale(up, 1.0 / length) } else { [0.0, 0.0, 1.0] };
        self.physics.motion = Motion::Still;
        self.pose_since_us = self.now_us;
    }

    /// Starts a motion from the current orientation (where any motion before it brought the board).
    pub fn set_motion(&mut self, motion: Motion) {
        self.stop_motion();
        self.physics.motion = motion;
        self.pose_since_us = self.now_us;
    }

    /// Stops moving, resting where the motion brought the board (a turn ends at its new orientation).
    pub fn stop_motion(&mut self) {
        let seconds = (self.now_us - self.pose_since_us) as f32 * 1e-6;
        let up = self.physics.up_at(seconds);
        self.place(up);
    }

    /// Connects or disconnects the sensor from the bus (a loose wire).
    pub fn set_connected(&mut self, connected: bool) {
        self.connected = connected;
    }

    /// Makes the next `count` transactions fail.
    pub fn fail_next_transactions(&mut self, count: u32) {
        self.fail_transactions_after(0, count);
    }

    /// Lets `skip` transactions pass, then makes `count` fail.
    pub fn fail_transactions_after(&mut self, skip: u32, count: u32) {
        self.failures_after = skip;
        self.failures_left = count;
    }

    /// Simulated time since power-up, in microseconds.
    pub fn now_us(&self) -> u64 {
        self.now_us
    }

    /// Bytes waiting in the FIFO.
    pub fn fifo_len(&self) -> usize {
        self.fifo.len()
    }

    /// Lets time pass: produces every sample due after now and up to the new time, into the data
    /// registers and the FIFO.
    pub fn advance_us(&mut self, microseconds: u64) {
        let until = self.now_us + microseconds;
        while self.next_sample_us <= self.now_us {
            self.next_sample_us += self.sample_period_us();
        }
        while self.next_sample_us <= until {
            self.now_us = self.next_sample_us;
            if self.register(reg::PWR_MGMT_1) & reg::PWR_MGMT_1_SLEEP == 0 {
                self.produce_sample();
            }
            self.next_sample_us += self.sample_period_us();
        }
        self.now_us = until;
    }

    /// Sample period from the filter and SMPLRT_DIV (register map 4.2): 1 kHz with the DLPF on,
    /// 8 kHz with it off, divided by 1 + SMPLRT_DIV.
    fn sample_period_us(&self) -> u64 {
        let dlpf = self.register(reg::CONFIG) & 0x07;
        let base_us = if dlpf == 0 || dlpf == 7 { 125 } else { 1000 };
        base_us * (1 + u64::from(self.register(reg::SMPLRT_DIV)))
    }

    fn sample_rate_hz(&self) -> f32 {
        1e6 / self.sample_period_us() as f32
    }

    fn produce_sample(&mut self) {
        let seconds = (self.now_us - self.pose_since_us) as f32 * 1e-6;
        let rate = self.sample_rate_hz();
        self.physics.accel_bandwidth_hz = self.part.accel_noise_bandwidth_hz(self.register(part::ACCEL_CONFIG2));
        let mut sample = self.physics.sample(seconds, rate);
        self.part.apply_self_test(self.register(reg::ACCEL_CONFIG), self.register(reg::GYRO_CONFIG), &mut sample);
        self.part.apply_offsets(&self.registers, &mut sample);
        let accel_lsb = f32::from(16384u16 >> ((self.register(reg::ACCEL_CONFIG) >> reg::FULL_SCALE_SHIFT) & 0x03));
        let gyro_range = GyroRange::from_fs_sel(self.register(reg::GYRO_CONFIG) >> reg::FULL_SCALE_SHIFT);
        let gyro_lsb = gyro_range.lsb_per_dps() as f32;
        let words = [
            quantise(sample.accel_g[0] * accel_lsb),
            quantise(sample.accel_g[1] * accel_lsb),
            quantise(sample.accel_g[2] * accel_lsb),
            self.part.temperature.raw(sample.temp_c),
            quantise(sample.gyro_dps[0] * gyro_lsb),
            quantise(sample.gyro_dps[1] * gyro_lsb),
            quantise(sample.gyro_dps[2] * gyro_lsb),
        ];
        for (i, word) in words.iter().enumerate() {
            self.latest[2 * i..2 * i + 2].copy_from_slice(&word.to_be_bytes());
        }
        if self.register(reg::USER_CTRL) & reg::USER_CTRL_FIFO_EN != 0 {
            self.push_fifo();
        }
    }

    /// Appends the measurements enabled in FIFO_EN, in register order; drops the oldest on overflow.
    fn push_fifo(&mut self) {
        let enabled = self.register(reg::FIFO_EN);
        // (FIFO_EN bit, byte range in the sample): ACCEL, TEMP, XG, YG, ZG.
        let parts = [(3, 0..6), (7, 6..8), (6, 8..10), (5, 10..12), (4, 12..14)];
        for (bit, range) in parts {
            if enabled & (1 << bit) == 0 {
                continue;
            }
            for &byte in &self.latest[range] {
                if self.fifo.is_full() {
                    self.fifo.pop_front();
                    self.registers[usize::from(reg::INT_STATUS)] |= reg::FIFO_OFLOW;
                }
                let _ = self.fifo.push_back(byte);
            }
        }
    }

    fn register(&self, address: u8) -> u8 {
        self.registers[usize::from(address) % REGISTER_COUNT]
    }

    fn write_register(&mut self, address: u8, value: u8) {
        if !self.part.has_register(address) {
            return;
        }
        match address {
            reg::PWR_MGMT_1 if value & reg::PWR_MGMT_1_DEVICE_RESET != 0 => {
                self.registers = power_up_registers(&self.part);
                self.fifo.clear();
            }
            reg::USER_CTRL => {
                if value & reg::USER_CTRL_FIFO_RESET != 0 {
                    self.fifo.clear();
                }
                // FIFO_RESET clears itself.
                self.registers[usize::from(address)] = value & !reg::USER_CTRL_FIFO_RESET;
            }
            reg::WHO_AM_I | reg::INT_STATUS | reg::FIFO_COUNT_H => {} // read-only
            _ => self.registers[usize::from(address) % REGISTER_COUNT] = value,
        }
    }

    fn read_register(&mut self, address: u8) -> u8 {
        match address {
            reg::INT_STATUS => core::mem::take(&mut self.registers[usize::from(reg::INT_STATUS)]),
            reg::FIFO_COUNT_H => (self.fifo.len() >> 8) as u8,
            reg::FIFO_COUNT_L => self.fifo.len() as u8,
            reg::FIFO_R_W => self.fifo.pop_front().unwrap_or(0),
            a if (reg::ACCEL_XOUT_H..reg::ACCEL_XOUT_H + reg::FIFO_SAMPLE_LEN as u8).contains(&a) => {
                self.latest[usize::from(a - reg::ACCEL_XOUT_H)]
            }
            a => self.part.read(a, self.register(a)),
        }
    }

    /// Whether a transaction to `address` is acknowledged; consumes an injected failure.
    fn acknowledge(&mut self, address: u8) -> Result<(), BusFault> {
        if !self.connected || address != self.address {
            return Err(BusFault::NoAcknowledge);
        }
        if self.failures_after > 0 {
            self.failures_after -= 1;
        } else if self.failures_left > 0 {
            self.failures_left -= 1;
            return Err(BusFault::Injected);
        }
        Ok(())
    }
}

/// The register file at power-up: asleep, the factory's accelerometer offsets loaded, the rest 0.
fn power_up_registers(part: &SimPart) -> [u8; REGISTER_COUNT] {
    let mut registers = [0; REGISTER_COUNT];
    registers[usize::from(reg::PWR_MGMT_1)] = PWR_MGMT_1_RESET;
    part.load_factory_offsets(&mut registers);
    registers
}

fn quantise(lsb: f32) -> i16 {
    libm::roundf(lsb).clamp(f32::from(i16::MIN), f32::from(i16::MAX)) as i16
}

#[cfg(test)]
mod tests;
