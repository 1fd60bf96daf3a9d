//! Another of accelcal's JSON files given where a session is asked for: named, with the command
//! that takes it, rather than answered with the JSON parser's words.

use std::path::Path;

use serde_json::Value;

use super::SessionError;

/// What another accelcal JSON file is and which command takes it, when `value` is one.
pub fn other_file(value: &Value) -> Option<&'static str> {
    let has = |keys: &[&str]| keys.iter().all(|key| value.get(key).is_some());
    if has(&["serial", "calibration", "fit", "verification"]) && value["fit"].get("bins").is_some() {
        Some("the temperature model `accelcal thermal --json` printed; it goes into a session's report as `accelcal report SESSION.json --thermal FILE`")
    } else if has(&["serial", "range_c", "bins"]) {
        Some("the temperature bins `accelcal thermal --bins` keeps; `accelcal thermal --port PORT --bins FILE` goes on learning from them")
    } else if has(&["sample_rate_hz", "white_noise_convention"]) {
        Some("a noise report (`accelcal noise --json`); it goes into a session's report as `accelcal report SESSION.json --noise FILE`")
    } else if has(&["sha256", "parameters", "predicted"]) {
        Some("a calibration certificate; `accelcal certificate verify FILE` checks it, `accelcal lot add LOT FILE` keeps it")
    } else {
        None
    }
}

/// Why the text of the file at `path` is not a session: what it is instead when it is another of
/// accelcal's files, else the parser's `reason`.
pub fn not_a_session(path: &Path, text: &str, reason: String) -> SessionError {
    let value = serde_json::from_str::<Value>(text).unwrap_or_default();
    match other_file(&value) {
        Some(what) => SessionError::OtherFile { path: path.into(), what },
        None => SessionError::NotASession { path: path.into(), reason },
    }
}
