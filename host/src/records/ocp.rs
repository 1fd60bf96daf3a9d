//! A board's run as OCP Test & Validation artifacts (output spec 2.0): one JSON object a line, each
//! with its `sequenceNumber` and `timestamp`: the schema's version, `testRunStart` (the board as
//! `dutInfo`), per phase a test step (`testStepStart`, a `measurement` each with its unit and
//! validators, `testStepEnd` COMPLETE or SKIP), `testRunEnd` with the result. The fields as the
//! `ocptv` package's own writer emits them (each object's keys in sorted order); host/tests/records.rs
//! writes each run again with it and compares.

use serde_json::{json, Value as Json};

use super::{Measured, Outcome, RunRecord, Value};

/// The artifacts of a run, one JSON text a line.
pub fn artifacts(run: &RunRecord) -> String {
    let mut bodies = vec![("schemaVersion", json!({ "major": 2, "minor": 0 }))];
    bodies.push(("testRunArtifact", json!({ "testRunStart": run_start(run) })));
    for (k, phase) in run.phases.iter().enumerate() {
        let step = |body: Json| ("testStepArtifact", step_artifact(k, body));
        bodies.push(step(json!({ "testStepStart": { "name": phase.name } })));
        bodies.extend(phase.measurements.iter().map(|m| step(json!({ "measurement": measurement(m) }))));
        let status = if phase.outcome() == Outcome::Skip { "SKIP" } else { "COMPLETE" };
        bodies.push(step(json!({ "testStepEnd": { "status": status } })));
    }
    let result = if run.outcome() == Outcome::Fail { "FAIL" } else { "PASS" };
    bodies.push(("testRunArtifact", json!({ "testRunEnd": { "status": "COMPLETE", "result": result } })));
    let timestamp = timestamp(run.end_unix_ms);
    let line = |(n, (kind, body)): (usize, (&str, Json))| {
        let mut artifact = serde_json::Map::new();
        artifact.insert(kind.into(), body);
        artifact.insert("sequenceNumber".into(), n.into());
        artifact.insert("timestamp".into(), timestamp.clone().into());
        Json::Object(artifact).to_string() + "\n"
    };
    bodies.into_iter().enumerate().map(line).collect()
}

fn run_start(run: &RunRecord) -> Json {
    json!({
        "name": "accelcal calibration",
        "version": env!("CARGO_PKG_VERSION"),
        "commandLine": "",
        "parameters": { "station": run.station_id, "certificate_sha256": run.sha256, "model": run.model },
        "dutInfo": {
            "dutInfoId": run.dut_id,
            "name": run.dut_id,
            "platformInfos": [],
            "softwareInfos": [],
            "hardwareInfos": [],
        },
    })
}

/// A test step's artifact: its id (the phase's index, as text) first, then the body's one field.
fn step_artifact(index: usize, body: Json) -> Json {
    let mut artifact = serde_json::Map::new();
    artifact.insert("testStepId".into(), index.to_string().into());
    if let Json::Object(fields) = body {
        artifact.extend(fields);
    }
    Json::Object(artifact)
}

fn measurement(m: &Measured) -> Json {
    let mut out = serde_json::Map::new();
    out.insert("name".into(), m.name.clone().into());
    out.insert(
        "value".into(),
        match &m.value {
            Value::Number(v) => json!(v),
            Value::Text(t) => json!(t),
        },
    );
    if let Some(unit) = &m.unit {
        out.insert("unit".into(), unit.clone().into());
    }
    let limits = m.limits.iter();
    let low = limits.clone().filter_map(|l| l.low).map(|v| json!({ "type": "GREATER_THAN_OR_EQUAL", "value": v }));
    let high = limits.filter_map(|l| l.high).map(|v| json!({ "type": "LESS_THAN_OR_EQUAL", "value": v }));
    out.insert("validators".into(), Json::Array(low.chain(high).collect()));
    Json::Object(out)
}

/// RFC 3339 in UTC with microseconds, as ocptv writes its timestamps.
fn timestamp(unix_ms: i64) -> String {
    let at = time::OffsetDateTime::from_unix_timestamp(unix_ms / 1000).unwrap_or(time::OffsetDateTime::UNIX_EPOCH);
    let (year, month, day) = (at.year(), u8::from(at.month()), at.day());
    let micros = (unix_ms % 1000) * 1000;
    format!("{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}.{micros:06}Z", at.hour(), at.minute(), at.second())
}
