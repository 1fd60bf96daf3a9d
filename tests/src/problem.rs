//! Synthetic calibration data files with a known truth: readings in raw counts of a sensor with
//! per-axis scale, cross-axis terms and offsets, averaged with stated per-axis noise, written as the
//! CSV text a user would feed `accelcal fit`.

use accelcal::data::Dataset;
use nalgebra::{Matrix3, Vector3};
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// |gravity| in the output unit of the synthetic files (m/s^2): not 1, so that a lost factor of g shows.
pub const SYNTHETIC_G: f64 = 9.80665;
/// Samples averaged per row.
pub const SAMPLES_PER_ROW: f64 = 400.0;
/// Standard deviation of the single samples per axis, in counts: a different value on each axis, so
/// that an axis index swapped in the statistics shows.
pub const SAMPLE_STD_COUNTS: [f64; 3] = [40.0, 60.0, 90.0];

/// One averaged reading with what is known about it.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticRow {
    /// Direction of the body frame that points up (unit vector).
    pub up: Vector3<f64>,
    /// The averaged reading, in counts.
    pub reading: Vector3<f64>,
    /// The known specific force, in m/s^2, when the row carries its orientation.
    pub reference: Option<Vector3<f64>>,
    /// Standard deviation of the samples that the row states, per axis, in counts.
    pub stated_std: Vector3<f64>,
}

/// The sensor: m = X a + y with a in m/s^2 and m in counts; the calibration is M = X^-1, o = y.
pub fn sensor_matrix() -> Matrix3<f64> {
    // About 16384 counts per g on each axis, with percent-level scale errors and 1e-3-level
    // cross-axis coupling, none of them symmetric.
    let per_ms2 = 16384.0 / SYNTHETIC_G;
    Matrix3::new(1.021, 0.013, -0.004, -0.007, 0.985, 0.009, 0.002, -0.011, 1.034) * per_ms2
}

/// The sensor's offset y, in counts.
pub fn sensor_offset() -> Vector3<f64> {
    Vector3::new(452.0, -93.0, -1283.0)
}

/// The six faces and eight corners, then `random` directions uniform over the sphere.
pub fn spread_directions(random: usize, seed: u64) -> Vec<Vector3<f64>> {
    let mut directions = Vec::with_capacity(14 + random);
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            let mut up = Vector3::zeros();
            up[axis] = sign;
            directions.push(up);
        }
    }
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                directions.push(Vector3::new(sx, sy, sz) / 3f64.sqrt());
            }
        }
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    for _ in 0..random {
        let v = Vector3::from_fn(|_, _| gaussian(&mut rng));
        directions.push(v.normalize());
    }
    directions
}

/// Rows at `directions`, each averaged from `SAMPLES_PER_ROW` samples of `SAMPLE_STD_COUNTS` noise and
/// stating `std_factor` times that noise; `with_reference(i)` says which rows carry their orientation.
pub fn rows(
    directions: &[Vector3<f64>],
    seed: u64,
    std_factor: f64,
    with_reference: impl Fn(usize) -> bool,
) -> Vec<SyntheticRow> {
    rows_with_noise(directions, seed, SAMPLE_STD_COUNTS, std_factor, with_reference)
}

/// As [`rows`], with `sample_std_counts` of noise per axis instead of [`SAMPLE_STD_COUNTS`].
pub fn rows_with_noise(
    directions: &[Vector3<f64>],
    seed: u64,
    sample_std_counts: [f64; 3],
    std_factor: f64,
    with_reference: impl Fn(usize) -> bool,
) -> Vec<SyntheticRow> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let (x, y) = (sensor_matrix(), sensor_offset());
    let sigma_mean = Vector3::from(sample_std_counts) / SAMPLES_PER_ROW.sqrt();
    directions
        .iter()
        .enumerate()
        .map(|(i, up)| {
            let force = up * SYNTHETIC_G;
            let noise = Vector3::from_fn(|k, _| sigma_mean[k] * gaussian(&mut rng));
            SyntheticRow {
                up: *up,
                reading: x * force + y + noise,
                reference: with_reference(i).then_some(force),
                stated_std: Vector3::from(sample_std_counts) * std_factor,
            }
        })
        .collect()
}

/// The rows as a data file: `x,y,z,ref_x,ref_y,ref_z,count,std_x,std_y,std_z`.
pub fn csv(rows: &[SyntheticRow]) -> String {
    let mut text = String::from("x,y,z,ref_x,ref_y,ref_z,count,std_x,std_y,std_z\n");
    for row in rows {
        let m = row.reading;
        let reference = row.reference.map_or(",,".to_owned(), |r| format!("{:e},{:e},{:e}", r[0], r[1], r[2]));
        let s = row.stated_std;
        text.push_str(&format!(
            "{:e},{:e},{:e},{reference},{SAMPLES_PER_ROW},{:e},{:e},{:e}\n",
            m[0], m[1], m[2], s[0], s[1], s[2]
        ));
    }
    text
}

/// The rows read back as the data file they make.
pub fn dataset(rows: &[SyntheticRow]) -> Dataset {
    Dataset::from_reader(csv(rows).as_bytes(), SYNTHETIC_G).expect("a synthetic data file reads")
}

/// A standard normal draw.
pub fn gaussian(rng: &mut Xoshiro256PlusPlus) -> f64 {
    <StandardNormal as Distribution<f64>>::sample(&StandardNormal, rng)
}
