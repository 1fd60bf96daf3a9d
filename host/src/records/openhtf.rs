//! A board's run as OpenHTF's JSON output writes a `TestRecord` (`openhtf.output.callbacks.json_factory`,
//! which serialises the record with `openhtf.util.data.convert_to_base_types`): every field that
//! serialisation holds, phases with their measurements keyed by name, each with its `units`
//! (name, code, suffix), its validators as OpenHTF prints an `in_range` one, and its outcome.
//! host/tests/records.rs rebuilds each record with openhtf's own classes and compares.

use serde_json::{json, Map, Value as Json};

use super::{units, Measured, Outcome, Phase, RunRecord, Value};

/// The record as OpenHTF's JSON output holds it.
pub fn record(run: &RunRecord) -> Json {
    let phases: Vec<Json> = run.phases.iter().enumerate().map(|(k, p)| phase(p, k, run.end_unix_ms)).collect();
    json!({
        "branches": [],
        "code_info": code_info(),
        "diagnosers": [],
        "diagnoses": [],
        "dut_id": run.dut_id,
        "end_time_millis": run.end_unix_ms,
        "log_records": [],
        "marginal": null,
        "metadata": {
            "config": null,
            "test_name": "accelcal calibration",
            "certificate_sha256": run.sha256,
            "model": run.model,
        },
        "outcome": outcome(run.outcome()),
        "outcome_details": [],
        "phases": phases,
        "start_time_millis": run.end_unix_ms,
        "station_id": run.station_id,
        "subtests": [],
    })
}

/// OpenHTF's name of an outcome (`Outcome` and `PhaseOutcome`; a measurement never skips).
fn outcome(outcome: Outcome) -> &'static str {
    match outcome {
        Outcome::Pass => "PASS",
        Outcome::Fail => "FAIL",
        Outcome::Skip => "SKIP",
    }
}

/// The code a record was written by: none captured (OpenHTF's `CodeInfo.uncaptured()`).
fn code_info() -> Json {
    json!({ "docstring": null, "name": "", "sourcecode": "" })
}

fn phase(phase: &Phase, index: usize, at_ms: i64) -> Json {
    let measurements: Map<String, Json> = phase.measurements.iter().map(|m| (m.name.clone(), measurement(m))).collect();
    json!({
        "attachments": {},
        "codeinfo": code_info(),
        "descriptor_id": index + 1,
        "diagnosers": [],
        "diagnosis_results": [],
        "end_time_millis": at_ms,
        "failure_diagnosis_results": [],
        "marginal": null,
        "measurements": measurements,
        "name": phase.name,
        "options": null,
        "outcome": outcome(phase.outcome()),
        "result": null,
        "start_time_millis": at_ms,
        "subtest_name": null,
    })
}

fn measurement(m: &Measured) -> Json {
    let mut out = Map::new();
    out.insert("name".into(), m.name.clone().into());
    out.insert("outcome".into(), outcome(m.outcome()).into());
    if let Some(limits) = &m.limits {
        out.insert("validators".into(), json!([in_range(limits.low, limits.high)]));
    }
    if let Some(unit) = &m.unit {
        let (name, code, suffix) = units::of(unit);
        out.insert("units".into(), json!({ "name": name, "code": code, "suffix": suffix }));
    }
    let value = match &m.value {
        Value::Number(v) => json!(v),
        Value::Text(t) => json!(t),
    };
    out.insert("measured_value".into(), value);
    Json::Object(out)
}

/// An `in_range` validator as OpenHTF prints it (`validators.InRange.__str__`).
fn in_range(low: Option<f64>, high: Option<f64>) -> String {
    match (low, high) {
        (Some(low), Some(high)) if low == high => format!("x == {}", python_float(low)),
        (low, high) => {
            let low = low.map_or(String::new(), |l| format!("{} <= ", python_float(l)));
            let high = high.map_or(String::new(), |h| format!(" <= {}", python_float(h)));
            format!("{low}x{high}")
        }
    }
}

/// A float as Python's `str` prints it: the shortest digits that read back, a `.0` on a whole
/// number, an exponent (two digits at least, signed) below 1e-4 and from 1e16.
pub fn python_float(x: f64) -> String {
    let magnitude = x.abs();
    if x != 0.0 && x.is_finite() && !(1e-4..1e16).contains(&magnitude) {
        let shown = format!("{x:e}");
        let (mantissa, exponent) = shown.split_once('e').unwrap_or((&shown, "0"));
        let exponent: i32 = exponent.parse().unwrap_or(0);
        let sign = if exponent < 0 { '-' } else { '+' };
        return format!("{mantissa}e{sign}{:02}", exponent.abs());
    }
    match format!("{x}") {
        shown if shown.contains(['.', 'N', 'i']) => shown,
        whole => format!("{whole}.0"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_limit_is_printed_as_python_prints_a_float() {
        let printed = [1.0, 0.05, -0.05, 1e-5, -2.5e-7, 1e16, 123.25, 0.0001].map(python_float);
        assert_eq!(printed, ["1.0", "0.05", "-0.05", "1e-05", "-2.5e-07", "1e+16", "123.25", "0.0001"]);
        assert_eq!(in_range(Some(0.98), None), "0.98 <= x");
        assert_eq!(in_range(None, Some(1.0)), "x <= 1.0");
    }
}
