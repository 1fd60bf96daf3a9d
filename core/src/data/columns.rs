//! Column names of the data file: the one list the reader and the writer share.

/// Accepted names of the three reading columns, in order of preference.
pub(super) const READING: [[&str; 3]; 3] = [["x", "y", "z"], ["mx", "my", "mz"], ["raw_x", "raw_y", "raw_z"]];
/// Names of the known-specific-force columns.
pub(super) const REFERENCE: [&str; 3] = ["ref_x", "ref_y", "ref_z"];
/// Names of the inclination and toolface columns of the published lab data, in degrees.
pub(super) const ANGLES: [&str; 2] = ["incl_deg", "toolface_deg"];
/// Samples averaged.
pub(super) const COUNT: &str = "count";
/// Standard deviation of the samples per axis.
pub(super) const STD: [&str; 3] = ["std_x", "std_y", "std_z"];
/// Mean die temperature.
pub(super) const TEMP: &str = "temp_c";
/// Mean gyro reading per axis.
pub(super) const GYRO: [&str; 3] = ["gyro_x_dps", "gyro_y_dps", "gyro_z_dps"];
