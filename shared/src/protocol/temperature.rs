//! The chip's temperature bins on the wire: the averages of the samples the capture and stream
//! engine took, one bin per whole degC of die temperature.

use serde::{Deserialize, Serialize};

/// Bins one [`super::Response::TemperatureBins`] carries at most; the host asks again until fewer come.
///
/// NOTE: a bin takes at most 34 postcard bytes (i8, u32 varint, seven f32); six keep the message
/// within half the frame, as every message is (shared's size tests). A capture spans a degree or two.
pub const TEMP_BINS_PER_MESSAGE: usize = 6;

/// The averages of the samples whose die temperature fell in one whole degree.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub struct TempBin {
    /// The bin: die temperatures from `degree_c` to `degree_c + 1`, in degC.
    pub degree_c: i8,
    /// Samples averaged.
    pub samples: u32,
    /// Mean die temperature of those samples, in degC.
    pub temp_c: f32,
    /// Mean accelerometer reading, raw, in g.
    pub accel_g: [f32; 3],
    /// Mean gyro reading, raw, in deg/s.
    pub gyro_dps: [f32; 3],
}
