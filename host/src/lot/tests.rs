use super::*;
use crate::sim::sessions::adaptive as session;

/// A sealed certificate of a made-up adaptive session (`seed`), as board `serial` calibrated on `date`.
fn certificate(seed: u64, serial: &str, date: &str) -> Certificate {
    let mut certificate = Certificate::issue(&session(seed, 1.0, 2.8e-3)).unwrap();
    certificate.board.serial = Some(serial.to_owned());
    certificate.date_utc = Some(date.to_owned());
    certificate.resealed()
}

fn temporary_lot(name: &str) -> (Lot, PathBuf) {
    let path = std::env::temp_dir().join(format!("accelcal-lot-{name}-{}.sqlite", std::process::id()));
    let _ = std::fs::remove_file(&path);
    (Lot::create_or_open(&path).unwrap(), path)
}

fn remove(path: &Path) {
    for suffix in ["", "-wal", "-shm"] {
        let _ = std::fs::remove_file(format!("{}{suffix}", path.display()));
    }
}

#[test]
fn each_board_counts_by_its_latest_certificate_and_keeps_its_history() {
    let (mut lot, path) = temporary_lot("latest");
    let (first, second, again) = (
        certificate(1, "B1", "2026-11-24 10:00"),
        certificate(2, "B2", "2026-11-24 10:05"),
        certificate(3, "B1", "2026-11-25 09:00"),
    );
    for c in [&again, &first, &second] {
        assert_eq!(lot.add(c).unwrap(), Added::New);
    }
    assert_eq!(lot.add(&first).unwrap(), Added::AlreadyThere);
    let latest = lot.latest().unwrap();
    assert_eq!(latest, vec![again.clone(), second.clone()]);
    assert_eq!(lot.board("B1").unwrap(), vec![first, again]);
    assert!(matches!(lot.board("B9"), Err(LotError::UnknownBoard { .. })));
    let consistency = lot.consistency().unwrap();
    assert_eq!((consistency.certificates, consistency.parameters, consistency.complete), (3, 36, true));
    remove(&path);
}

#[test]
fn a_board_whose_write_fails_part_way_leaves_the_lot_as_it_was() {
    let (mut lot, path) = temporary_lot("rollback");
    lot.add(&certificate(1, "B1", "2026-11-24 10:00")).unwrap();
    // NOTE: SQLite stores a NaN as NULL, which the parameters' NOT NULL refuses: the last
    // parameter's row fails after the certificate's row and the others went in.
    let mut broken = certificate(2, "B2", "2026-11-24 10:05");
    broken.parameters.last_entry().unwrap().get_mut().value = f64::NAN;
    assert!(matches!(lot.add(&broken), Err(LotError::Sql { .. })));
    let consistency = lot.consistency().unwrap();
    assert_eq!((consistency.certificates, consistency.parameters, consistency.complete), (1, 12, true));
    assert_eq!(lot.latest().unwrap().len(), 1);
    remove(&path);
}

#[test]
fn cpk_is_the_distance_to_the_nearer_limit_in_three_standard_deviations() {
    let both = Limits { low: Some(-3.0), high: Some(6.0) };
    assert!((summary::cpk(0.0, 1.0, &both).unwrap() - 1.0).abs() < 1e-12);
    let upper = Limits { low: None, high: Some(1.5) };
    assert!((summary::cpk(0.0, 1.0, &upper).unwrap() - 0.5).abs() < 1e-12);
    assert!((summary::cpk(2.0, 0.5, &upper).unwrap() + 1.0 / 3.0).abs() < 1e-12, "a mean beyond the limit: negative");
    assert_eq!(summary::cpk(0.0, 0.0, &both), None);
}

#[test]
fn the_summary_states_each_parameter_s_spread_and_the_boards_outside_the_limits() {
    let lot: Vec<Certificate> = (1..=3).map(|s| certificate(s, &format!("B{s}"), "2026-11-24 10:00")).collect();
    let values: Vec<f64> = lot.iter().map(|c| c.parameters["o_x"].value).collect();
    let mean = values.iter().sum::<f64>() / 3.0;
    let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 2.0).sqrt();
    let highest = (0..3).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap();
    let between = values.iter().copied().filter(|v| *v < values[highest]).fold(f64::MIN, f64::max);
    let high = (between + values[highest]) / 2.0;
    let spec = Spec { limits: [("o_x".to_owned(), Limits { low: None, high: Some(high) })].into() };
    let summary = LotSummary::of(&lot, &spec);
    let o_x = summary.parameters.iter().find(|d| d.name == "o_x").unwrap();
    assert!((o_x.mean - mean).abs() < 1e-15 && (o_x.std.unwrap() - std).abs() < 1e-15, "{o_x:?}");
    assert!((o_x.cpk.unwrap() - (high - mean) / (3.0 * std)).abs() < 1e-12);
    let outside = format!("B{}", highest + 1);
    assert_eq!(o_x.outside, vec![outside.clone()]);
    assert_eq!(summary.outside, [(outside, vec!["o_x".to_owned()])].into());
}

#[test]
fn a_spec_file_is_read_and_a_wrong_one_refused_with_its_reason() {
    let path = std::env::temp_dir().join(format!("accelcal-spec-{}.toml", std::process::id()));
    std::fs::write(&path, "[limits.o_x]\nlow = -0.05\nhigh = 0.05\n[limits.s_y]\nhigh = 1.02\n").unwrap();
    let spec = Spec::load(&path).unwrap();
    assert_eq!(spec.limits["o_x"], Limits { low: Some(-0.05), high: Some(0.05) });
    assert_eq!(spec.limits["s_y"], Limits { low: None, high: Some(1.02) });
    std::fs::write(&path, "[limits.o_x]\nlow = 0.05\nhigh = -0.05\n").unwrap();
    let refused = Spec::load(&path).unwrap_err().to_string();
    assert!(refused.contains("low 0.05 is not below high -0.05"), "{refused}");
    std::fs::write(&path, "[limits.o_x]\nlo = 0.05\n").unwrap();
    assert!(Spec::load(&path).unwrap_err().to_string().contains("unknown field"));
    let names = ["o_y".to_owned()];
    let misspelt = spec.check_names(&path, names.iter()).unwrap_err().to_string();
    assert!(misspelt.contains("no certificate in the lot states `o_x`"), "{misspelt}");
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn the_summary_says_no_spec_was_given_rather_than_that_no_board_is_outside_it() {
    let one = vec![certificate(1, "B1", "2026-11-24 10:00")];
    let without = super::text::summary(&LotSummary::of(&one, &Spec { limits: Default::default() }));
    assert!(without.starts_with("1 board (each"), "{without}");
    assert!(without.contains("no spec given: --spec SPEC.toml") && !without.contains("no board outside"), "{without}");
    let wide = Spec { limits: [("o_x".to_owned(), Limits { low: Some(-1.0), high: Some(1.0) })].into() };
    let within = super::text::summary(&LotSummary::of(&one, &wide));
    assert!(within.contains("no board outside the spec's limits"), "{within}");
}
