//! `accelcal fit LOG` in the page: a log a board's own sketch printed (any of the dialects the core
//! reads), its still periods found, averaged and fitted as the command line fits it by default.

use accelcal_core::fit::{FitOptions, ModelChoice};
use accelcal_core::report::stream::{self, StreamReport};
use accelcal_core::stream::{checked_text, StreamLog, StreamOptions};
use wasm_bindgen::prelude::*;

/// A fitted log: its report as `accelcal fit LOG` prints it, as text and as JSON (`--json`).
#[wasm_bindgen(getter_with_clone)]
pub struct FittedLog {
    pub text: String,
    pub json: String,
}

/// Fits the log's bytes as `accelcal fit LOG` does (the unit and rate found from the log itself, the
/// model chosen by the data); rejects with why it cannot, and what to do.
#[wasm_bindgen]
pub fn fit_log(bytes: &[u8]) -> Result<FittedLog, JsError> {
    let text = checked_text(bytes).map_err(|e| JsError::new(&format!("this file cannot be read as a log: {e}")))?;
    let log = StreamLog::parse(&text, &StreamOptions::default())
        .map_err(|e| JsError::new(&format!("this file is not a sensor's stream accelcal reads: {e}")))?;
    let report = StreamReport::new(&log, ModelChoice::Auto, &FitOptions::default())
        .map_err(|e| JsError::new(&format!("the log cannot be fitted: {e}")))?;
    Ok(FittedLog { text: stream::text(&report), json: stream::json(&report) })
}
