//! MATLAB/Octave: A and b in the form the Navigation Toolbox's magcal documents, C = (D - b) * A, with
//! one reading per row of D (https://www.mathworks.com/help/nav/ref/magcal.html); so A = M' and b = o'.
//! Also c0 = -b * A for the form C = D * A + c0. Carries everything.

use shared::linalg::{self, Mat3, Vec3};
use shared::STANDARD_GRAVITY;

use super::loss::loss;
use super::statement::{lines, Said};
use super::{float, text, Comment, Export, Source};

/// `% ...`.
const PERCENT: Comment = Comment { open: "", line: "% ", close: "" };

const CONVENTION: &[&str] = &[
    "C = (D - b) * A: D is N-by-3, one reading per row, in g (raw counts / accel_lsb_per_g); C in g",
    "row vectors: A is accelcal's M transposed (A = M'), b = o' (1-by-3, in g); equally C = D * A + c0",
    "gyro: W = (Wraw - bg) * Ag, Ag = G', bg in deg/s, Wraw = raw counts / gyro_lsb_per_dps",
];

const MATLAB_SAID: Said = Said {
    title: "MATLAB/Octave (magcal's convention)",
    convention: CONVENTION,
    carries: "M, o, G, b in full",
    temperature: "not applied",
    lossy: false,
};

/// The MATLAB/Octave script.
pub fn matlab(source: &Source) -> Export {
    let full = source.full();
    let loss = loss(&full, &full);
    let c0 = linalg::scale(linalg::mul_vec(&full.matrix, full.offset_g), -1.0);
    let body = format!(
        "\naccel_lsb_per_g = {};\ngyro_lsb_per_dps = {};\nstandard_gravity = {STANDARD_GRAVITY};\n\n\
         A = {};\nb = {};\nc0 = {};\n\nAg = {};\nbg = {};\n",
        source.accel_per_g(),
        source.gyro_per_dps(),
        matrix(&linalg::transpose(&full.matrix)),
        row(&full.offset_g),
        row(&c0),
        matrix(&linalg::transpose(&full.gyro_matrix)),
        row(&source.gyro_bias_dps()),
    );
    text(lines(source, &MATLAB_SAID, &loss), &PERCENT, &body, loss)
}

fn row(v: &Vec3<f64>) -> String {
    format!("[{} {} {}]", float(v[0]), float(v[1]), float(v[2]))
}

fn matrix(m: &Mat3<f64>) -> String {
    let inner = |v: &Vec3<f64>| format!("{} {} {}", float(v[0]), float(v[1]), float(v[2]));
    format!("[{}; {}; {}]", inner(&m[0]), inner(&m[1]), inner(&m[2]))
}
