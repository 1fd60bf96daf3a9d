use super::*;
use crate::session::SessionKind;
use crate::sim::sessions::adaptive as session;

#[test]
fn a_changed_copy_of_a_certificate_is_detected() {
    let certificate = Certificate::issue(&session(1, 1.0, 2.8e-3)).unwrap();
    let path = std::path::Path::new("board.certificate.json");
    assert_eq!(check_text::<Certificate>(path, &certificate.to_json()).unwrap(), certificate);
    let value = certificate.parameters["o_x"].value;
    let changed = certificate.to_json().replacen(&format!("{value}"), &format!("{}", value + 1e-6), 1);
    assert_ne!(changed, certificate.to_json());
    assert!(
        matches!(check_text::<Certificate>(path, &changed), Err(SealError::Changed { .. })),
        "{:?}",
        check_text::<Certificate>(path, &changed)
    );
}

#[test]
fn the_noise_s_part_of_the_budget_is_the_fit_s_own_standard_error() {
    // No warming: no drift is fitted, and the noise moved through the fit must give what the fit's
    // covariance gives for the same noise.
    let session = session(2, 0.0, 2.8e-3);
    let fit = session.fit().unwrap().0;
    let certificate = Certificate::issue(&session).unwrap();
    for parameter in &fit.parameters {
        let expected = parameter.noise_std_error.unwrap();
        let noise = certificate.parameters[parameter.name].budget[&Component::Noise];
        assert!((noise / expected - 1.0).abs() < 0.03, "{}: {noise:e} vs the fit's {expected:e}", parameter.name);
    }
    assert!(certificate.parameters.keys().all(|name| !name.starts_with("c_")));
}

#[test]
fn a_drift_the_session_fits_leaves_its_slope_no_temperature_uncertainty_when_the_captures_are_precise() {
    // Captures known to 0.05 ug over 2 degC: the fitted slope follows any true offset slope (the prior
    // weighs nothing), so the temperature's share of a slope's u is what the fit misses (the
    // sensitivity's drift, which aliases into it: measured 0.10 mg/degC), not the spread of offset
    // slopes between parts (1 mg/degC).
    let certificate = Certificate::issue(&session(3, 2.0, 1e-6)).unwrap();
    for name in ["c_x", "c_y", "c_z"] {
        let temperature = certificate.parameters[name].budget[&Component::Temperature];
        assert!(temperature < 3e-4, "{name}: {temperature:e} g/degC");
    }
}

#[test]
fn the_certificate_quotes_the_self_test_the_board_kept_and_has_none_without_one() {
    use crate::selftest::HistoryEntry;
    use crate::session::BoardRecord;
    use shared::protocol::{FirmwareVersion, SensorConfig};
    let mut session = session(3, 0.0, 2.8e-3);
    assert_eq!(Certificate::issue(&session).unwrap().self_test, None, "a session without a board record");
    let result = serde_json::json!({ "part": "MPU-6050", "passed": true, "axes": [{ "deviation_percent": 2.5 }] });
    let entry = HistoryEntry { date_utc: "2026-11-24 18:00".into(), result };
    session.board = Some(BoardRecord {
        serial: "0123456789ABCDEF01234567".into(),
        firmware: FirmwareVersion { major: 0, minor: 1, patch: 0 },
        config: SensorConfig::default(),
        sensor: Some("MPU-6050 at 0x68".into()),
        self_test: Some(entry),
    });
    let certificate = Certificate::issue(&session).unwrap();
    assert_eq!(certificate.board.part.as_deref(), Some("MPU-6050 at 0x68"));
    let page = html::page(&certificate);
    assert!(page.contains(">MPU-6050 at 0x68</td>"), "the page names the part the board reported");
    assert!(
        page.contains(">passed (2026-11-24 18:00 UTC); largest deviation from the factory trim 2.5 %</td>"),
        "{page}"
    );
    let quoted = certificate.self_test.as_ref().expect("quoted");
    assert_eq!(quoted["date_utc"], "2026-11-24 18:00");
    assert_eq!(quoted["result"]["axes"][0]["deviation_percent"], 2.5);
    let path = std::path::Path::new("board.certificate.json");
    assert_eq!(check_text::<Certificate>(path, &certificate.to_json()).unwrap(), certificate, "sealed with it");
}

#[test]
fn a_certificate_states_the_captures_temperatures_and_none_where_a_stream_carried_none() {
    // The session warms 1 degC from 21.5 over its fifteen captures (the last at 22.5 again).
    let mut session = session(4, 1.0, 2.8e-3);
    let conditions = Certificate::issue(&session).unwrap().conditions;
    let mean = 21.5 + 1.0 * (0..15).map(|i| f64::from(i) / 14.0).sum::<f64>() / 15.0;
    assert!((conditions.temp_mean_c.unwrap() - mean).abs() < 1e-9, "{conditions:?}");
    assert_eq!((conditions.temp_low_c, conditions.temp_high_c), (Some(21.5), Some(22.5)));
    session.kind = SessionKind::Stream;
    let certificate = Certificate::issue(&session).unwrap();
    let conditions = &certificate.conditions;
    assert_eq!((conditions.temp_mean_c, conditions.temp_low_c, conditions.temp_high_c), (None, None, None));
    // NOTE: with no temperature there is no spread to move the captures by: the budget has no
    // temperature part (before, a stream's 0 degC against a NaN mean made every moved capture NaN).
    let parameter = &certificate.parameters["o_x"];
    assert!(parameter.value.is_finite() && parameter.u > 0.0, "{parameter:?}");
    assert!(!parameter.budget.contains_key(&Component::Temperature), "{parameter:?}");
    let page = html::page(&certificate);
    assert!(page.contains(">not measured (the captures carry no temperature)</td>"), "{page}");
    assert!(!page.contains("NaN") && !page.contains("inf to -inf"), "{page}");
}

#[test]
fn checking_a_session_file_as_a_certificate_says_it_is_the_session_and_how_to_issue_its_certificate() {
    let path = std::path::Path::new("board-session.json");
    let error = seal::check_text::<Certificate>(path, &session(1, 0.5, 0.004).json_text()).unwrap_err();
    assert!(matches!(error, SealError::ASession { .. }), "{error}");
    assert!(error.to_string().contains("accelcal certificate issue"), "{error}");
}

// NOTE: GUM (JCGM 100:2008) 6.2.1: U = k u; the certificate states k = 2 (about 95 % for a normal
// distribution) for every parameter and every predicted error.
#[test]
fn every_expanded_uncertainty_is_twice_its_standard_uncertainty() {
    let certificate = Certificate::issue(&session(1, 1.0, 2.8e-3)).unwrap();
    assert_eq!(certificate.coverage_factor, 2.0);
    assert_eq!(certificate.parameters.len(), 12);
    for (name, p) in &certificate.parameters {
        assert!(p.u > 0.0 && (p.expanded - 2.0 * p.u).abs() <= 1e-12 * p.u, "{name}: U {} for u {}", p.expanded, p.u);
    }
    for interval in [certificate.predicted.norm_error_mg, certificate.predicted.tilt_error_deg] {
        assert!(interval.u > 0.0 && (interval.expanded - 2.0 * interval.u).abs() <= 1e-12 * interval.u, "{interval:?}");
    }
}
