//! accelcal in the browser (issue 37): the entry points of the web page (web/page) in [`browser`]
//! (the board run over Web Serial, the simulated board a Web Worker serves), and
//! [`simulated_session_json`] with its plain WebAssembly exports ([`exports`]), which the tests run
//! under node to check that the core computes there, bit for bit, what it computes natively.

pub mod browser;
pub mod exports;

use accelcal_core::calibration::CalibrationJson;
use accelcal_core::limits::DEFAULT_TARGET_MG;
use accelcal_core::sim::SimulatedSession;
use serde::Serialize;

/// The hand's placement error, in degrees: `calibrate --sim`'s default (`--sim-placement-deg`).
pub(crate) const PLACEMENT_DEG: f64 = 3.0;

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

/// The JSON text of the calibration of a whole default simulated session: the realistic simulated
/// MPU-6050 of `seed` behind the firmware's own serve step, in this process, turned by the simulated
/// hand of `seed` through the core's adaptive run, fitted as `calibrate --sim --seed SEED` fits it.
/// Every number is printed in its shortest form that reads back to the same bits, so two texts are
/// equal exactly when the numbers are.
pub fn simulated_session_json(seed: u64) -> String {
    let how = SimulatedSession { placement_deg: PLACEMENT_DEG, hand_seed: seed, target_mg: DEFAULT_TARGET_MG };
    let outcome = how.in_process(seed).map_err(|e| e.to_string()).and_then(|session| {
        let config = session.board.as_ref().map(|board| board.config).unwrap_or_default();
        session.outcome(config).map_err(|e| e.to_string())
    });
    let yielded = match outcome {
        Ok(outcome) => Yielded::Calibration(Box::new(Calibrations {
            device: CalibrationJson::from_device(&outcome.calibration),
            fit: CalibrationJson::from_fit(&outcome.fit, 1.0),
        })),
        Err(why) => Yielded::Error(why),
    };
    // NOTE: cannot fail: these types have no maps, so no key that JSON could not take.
    serde_json::to_string(&yielded).expect("a calibration's JSON form has only string keys")
}
