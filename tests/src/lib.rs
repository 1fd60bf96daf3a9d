//! Helpers shared by the workspace integration tests: where the published data lives, the
//! published phone data set with the orientations its paper gives, synthetic data files with a known
//! truth, and a scripted device for the link.

pub mod problem;
pub mod scripted;

use std::path::PathBuf;

use accelcal::data::Dataset;

/// Local gravity used by Georgieva and Hofreither for the phone data, in m/s^2.
pub const PHONE_G: f64 = 9.81;

/// The known orientation of the first six phone rows, in the publication's order:
/// (-g,0,0), (+g,0,0), (0,-g,0), (0,+g,0), (0,0,-g), (0,0,+g).
pub const PHONE_REFERENCE_DIRECTIONS: [[f64; 3]; 6] =
    [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [0.0, 0.0, 1.0]];

/// Path of a data file copied into `tests/data`.
pub fn data_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data").join(name)
}

/// The 13 published phone rows, the first six with their known orientation (m/s^2).
pub fn phone_dataset() -> Dataset {
    let mut dataset = accelcal::data::read_file(&data_path("huawei-phone-13.csv"), PHONE_G).expect("phone data reads");
    for (row, direction) in dataset.rows.iter_mut().zip(PHONE_REFERENCE_DIRECTIONS) {
        row.reference = Some(direction.map(|v| v * PHONE_G));
    }
    dataset
}
