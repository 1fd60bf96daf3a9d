//! MPU-6050 register addresses and bits used here.
//!
//! NOTE: from the MPU-6000/MPU-6050 Register Map and Descriptions, revision 4.2 (RM-MPU-6000A-00).
//! One home for every address and bit: the driver and the simulated chip both read them from here.

/// The two addresses the chip answers at: AD0 low (0x68) or high (0x69).
pub const ADDRESSES: [u8; 2] = [0x68, 0x69];

/// SMPLRT_DIV (0x19): sample rate = gyro output rate / (1 + divider), section 4.2.
pub const SMPLRT_DIV: u8 = 0x19;
/// CONFIG (0x1A): DLPF_CFG in bits 2:0, section 4.3.
pub const CONFIG: u8 = 0x1A;
/// GYRO_CONFIG (0x1B): FS_SEL in bits 4:3, section 4.4.
pub const GYRO_CONFIG: u8 = 0x1B;
/// ACCEL_CONFIG (0x1C): AFS_SEL in bits 4:3, section 4.5.
pub const ACCEL_CONFIG: u8 = 0x1C;
/// ACCEL_CONFIG2 (0x1D) of the MPU-6500 family: the accelerometer's own low-pass filter
/// (RM-MPU-6500A 4.8); not in the MPU-6050's map.
pub const ACCEL_CONFIG2: u8 = 0x1D;
/// XA_OFFSET_H (0x77) of the MPU-6500 family: the accelerometer's x offset, high byte (the family's
/// offset map is [`shared::part::Family::accel_offset_registers`]).
pub const XA_OFFSET_H_6500: u8 = shared::part::Family::Mpu6500.accel_offset_registers()[0];
/// FIFO_EN (0x23): which measurements go into the FIFO, section 4.6.
pub const FIFO_EN: u8 = 0x23;
/// INT_ENABLE (0x38), section 4.15.
pub const INT_ENABLE: u8 = 0x38;
/// INT_STATUS (0x3A): cleared when read, section 4.16.
pub const INT_STATUS: u8 = 0x3A;
/// ACCEL_XOUT_H (0x3B): start of accel (6), temperature (2) and gyro (6) data, section 4.17-4.19.
pub const ACCEL_XOUT_H: u8 = 0x3B;
/// USER_CTRL (0x6A), section 4.29.
pub const USER_CTRL: u8 = 0x6A;
/// PWR_MGMT_1 (0x6B), section 4.30.
pub const PWR_MGMT_1: u8 = 0x6B;
/// FIFO_COUNT_H (0x72): byte count in the FIFO, high byte first, section 4.31.
pub const FIFO_COUNT_H: u8 = 0x72;
/// FIFO_COUNT_L (0x73): low byte of the FIFO count, section 4.31.
pub const FIFO_COUNT_L: u8 = 0x73;
/// FIFO_R_W (0x74): reading pops bytes from the FIFO, section 4.32.
pub const FIFO_R_W: u8 = 0x74;
/// WHO_AM_I (0x75): 0x68 on a genuine MPU-6050 whatever the AD0 pin, section 4.33.
pub const WHO_AM_I: u8 = 0x75;

/// FIFO_EN: temperature, the three gyro axes and the accelerometer (TEMP, XG, YG, ZG, ACCEL).
pub const FIFO_EN_TEMP_GYRO_ACCEL: u8 = 0b1111_1000;
/// INT_ENABLE / INT_STATUS: FIFO overflow bit.
pub const FIFO_OFLOW: u8 = 1 << 4;
/// USER_CTRL: FIFO enable bit.
pub const USER_CTRL_FIFO_EN: u8 = 1 << 6;
/// USER_CTRL: FIFO reset bit (self-clearing).
pub const USER_CTRL_FIFO_RESET: u8 = 1 << 2;
/// GYRO_CONFIG and ACCEL_CONFIG: the self-test bits of the x, y and z axes, bits 7:5 (sections
/// 4.4, 4.5; the same on the MPU-6500 family).
pub const SELF_TEST_BITS: u8 = 0b1110_0000;
/// Bit position of the full-scale field in GYRO_CONFIG and ACCEL_CONFIG (sections 4.4, 4.5).
pub const FULL_SCALE_SHIFT: u8 = 3;
/// PWR_MGMT_1: SLEEP bit, set at power-up (section 4.30).
pub const PWR_MGMT_1_SLEEP: u8 = 1 << 6;
/// PWR_MGMT_1: DEVICE_RESET bit, self-clearing (section 4.30).
pub const PWR_MGMT_1_DEVICE_RESET: u8 = 1 << 7;
/// PWR_MGMT_1: awake, clock from the x gyro PLL (recommended over the internal oscillator, 4.30).
pub const PWR_MGMT_1_AWAKE_PLL_X: u8 = 0x01;

/// Bytes of one FIFO sample: accel x,y,z, temperature, gyro x,y,z, each big-endian i16, in register
/// order (section 4.6: "data is written in order of register number").
pub const FIFO_SAMPLE_LEN: usize = 14;
/// FIFO size in bytes (Product Specification section 7.17).
pub const FIFO_LEN: usize = 1024;
/// Gyro output rate with the digital low-pass filter on, in Hz (section 4.2).
pub const GYRO_OUTPUT_RATE_HZ: u32 = 1000;
/// Gyro sensitivity of the range the firmware sets ([`shared::protocol::GYRO_RANGE`], which says
/// why), LSB per deg/s, as the f32 every conversion on the chip divides by.
pub const GYRO_LSB_PER_DPS: f32 = shared::protocol::GYRO_RANGE.lsb_per_dps() as f32;
/// Temperature: degC = raw / 340 + 36.53 (section 4.18); the driver hands every part's temperature
/// on in this encoding.
pub const TEMP_LSB_PER_C: f32 = shared::part::TemperatureFormula::MPU6050.lsb_per_c;
/// Temperature offset in degC.
pub const TEMP_OFFSET_C: f32 = shared::part::TemperatureFormula::MPU6050.offset_c;

/// The temperature, in degC, of a reading in the driver's encoding: one raw value, or the mean of
/// several (the one conversion after the driver: samples, captures and temperature bins).
pub fn temp_c(raw: f32) -> f32 {
    raw / TEMP_LSB_PER_C + TEMP_OFFSET_C
}
