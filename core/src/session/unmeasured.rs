//! A stream session's captures carry no die temperature (a sketch's stream has none), and its file
//! says so: `"temp_c": null`. In memory the capture statistics (the wire protocol's, an f32) hold 0
//! and the session's kind says the temperature is not measured (`Session::dataset` leaves it out);
//! files written before, with 0.0 in a stream session, read the same.

use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::Value;

/// Whether a session's JSON is a stream session's.
fn is_stream(json: &Value) -> bool {
    json.get("kind").and_then(Value::as_str) == Some("stream")
}

/// Applies `change` to every capture's `stats.temp_c` of a stream session's JSON.
fn each_temperature(json: &mut Value, change: impl Fn(&mut Value)) {
    if !is_stream(json) {
        return;
    }
    let captures = json.get_mut("captures").and_then(Value::as_array_mut).into_iter().flatten();
    captures.filter_map(|capture| capture.pointer_mut("/stats/temp_c")).for_each(change);
}

/// A stream session's JSON as written, its temperatures null (not measured).
///
/// NOTE: through a JSON value, whose keys come out in alphabetical order; a reader finds them by name.
pub(super) fn stream_json(session: &impl Serialize) -> String {
    let mut json = serde_json::to_value(session).unwrap_or_default();
    each_temperature(&mut json, |temp_c| *temp_c = Value::Null);
    serde_json::to_string_pretty(&json).unwrap_or_default()
}

/// A session file's text read as a session, as [`from_value`] (other sessions' errors with line
/// and column).
pub(super) fn parse<S: DeserializeOwned>(text: &str) -> Result<S, serde_json::Error> {
    let json: Value = serde_json::from_str(text)?;
    match is_stream(&json) {
        true => from_value(json),
        false => serde_json::from_str(text),
    }
}

/// A session file's JSON read as a session: a stream session's null temperatures as the 0 its
/// statistics hold.
pub(super) fn from_value<S: DeserializeOwned>(mut json: Value) -> Result<S, serde_json::Error> {
    each_temperature(&mut json, |temp_c| {
        if temp_c.is_null() {
            *temp_c = Value::from(0.0);
        }
    });
    serde_json::from_value(json)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::session::{CaptureRecord, Session, SessionKind, StreamSource};
    use shared::protocol::CaptureStats;
    use shared::AccelRange;

    fn capture(z: f32, temp_c: f32) -> CaptureRecord {
        let stats = CaptureStats {
            samples: 150,
            seconds: 1.5,
            mean_g: [0.01, 0.0, z],
            std_g: [0.003; 3],
            gyro_mean_dps: [0.5; 3],
            gyro_std_dps: [0.0; 3],
            temp_c,
            clipped: 0,
            range: AccelRange::G2,
        };
        CaptureRecord {
            name: "+Z from line 9".into(),
            target: None,
            face: None,
            unix_time_s: 1.0,
            stats,
            closing: false,
        }
    }

    #[test]
    fn a_stream_sessions_file_says_its_temperatures_are_not_measured_and_old_files_read_the_same() {
        let captures = vec![capture(1.0, 0.0), capture(-1.0, 0.0)];
        let source = Some(StreamSource::for_tests(None, None));
        let stream = Session { kind: SessionKind::Stream, captures, stream: source, ..Session::default() };
        let text = stream.json_text();
        let json: Value = serde_json::from_str(&text).unwrap();
        let temps: Vec<&Value> = json["captures"].as_array().unwrap().iter().map(|c| &c["stats"]["temp_c"]).collect();
        assert_eq!(temps, [&Value::Null, &Value::Null], "{text}");
        assert_eq!(Session::from_json_text(&text).unwrap(), stream);
        assert_eq!(Session::from_json(json).unwrap(), stream, "as the exports read it");
        // Written before: 0.0 in a stream session, which meant the same.
        assert_eq!(Session::from_json_text(&text.replace("\"temp_c\": null", "\"temp_c\": 0.0")).unwrap(), stream);
        // A board's session keeps its temperatures, and a null in one is no session of ours.
        let board = Session { kind: SessionKind::Adaptive, captures: vec![capture(1.0, 25.5)], ..Session::default() };
        let text = board.json_text();
        assert!(text.contains("\"temp_c\": 25.5"), "{text}");
        assert!(Session::from_json_text(&text.replace("25.5", "null")).is_err());
    }
}
