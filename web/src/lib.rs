//! accelcal in the browser. This crate will become the web page (issue 37); today it holds only the
//! browser's entry points: [`simulated_session_json`] and its WebAssembly exports ([`exports`]), which
//! the tests run under node to check that the core computes there, bit for bit, what it computes natively.

pub mod exports;

use accelcal_core::calibration::CalibrationJson;
use accelcal_core::sim::sessions;
use serde::Serialize;
use shared::protocol::SensorConfig;

/// How much the simulated board warms over its session, in degC: enough for the drift to be fitted.
const WARMING_C: f64 = 2.0;

/// The simulated sensor's noise per raw sample, in g (2.8 mg, the one `limits` takes at 100 Hz).
const NOISE_STD_G: f32 = 0.0028;

/// What a simulated session yields, as JSON: its calibration, or why there is none.
#[derive(Serialize)]
#[serde(rename_all = "snake_case")]
enum Yielded {
    // NOTE: boxed: the two records are large beside the error's text.
    Calibration(Box<Calibrations>),
    /// Why the core made no calibration, in words.
    Error(String),
}

/// The device calibration (f32, in g) and the host's fit it was made from (f64, in g).
// NOTE: the fit is kept too because rounding to f32 would hide a difference in the low bits of the f64s.
#[derive(Serialize)]
struct Calibrations {
    /// The calibration record a board would store.
    device: CalibrationJson,
    /// The host's fit, before its numbers are rounded to the record's f32.
    fit: CalibrationJson,
}

/// The JSON text of the calibration the core computes from a made-up adaptive session drawn from
/// `seed`. Every number is printed in its shortest form that reads back to the same bits, so two
/// texts are equal exactly when the numbers are.
///
/// NOTE: a stand-in. The real run replaces this body: a whole simulated adaptive session through the
/// core's run and the firmware's simulated board.
pub fn simulated_session_json(seed: u64) -> String {
    let session = sessions::adaptive(seed, WARMING_C, NOISE_STD_G);
    // NOTE: the made-up session has no board record, so the board's default settings stand in.
    let yielded = match session.outcome(SensorConfig::default()) {
        Ok(outcome) => Yielded::Calibration(Box::new(Calibrations {
            device: CalibrationJson::from_device(&outcome.calibration),
            fit: CalibrationJson::from_fit(&outcome.fit, 1.0),
        })),
        Err(e) => Yielded::Error(e.to_string()),
    };
    // NOTE: cannot fail: these types have no maps, so no key that JSON could not take.
    serde_json::to_string(&yielded).expect("a calibration's JSON form has only string keys")
}
