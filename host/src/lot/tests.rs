use std::collections::BTreeMap;

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

/// A closed lot of three boards (B1 twice) at `path`, as `lot add` leaves it (WAL checkpointed).
fn closed_lot(name: &str) -> PathBuf {
    let (mut lot, path) = temporary_lot(name);
    for (seed, serial, date) in
        [(1, "B1", "2026-11-24 10:00"), (2, "B2", "2026-11-24 10:05"), (3, "B1", "2026-11-25 09:00")]
    {
        lot.add(&certificate(seed, serial, date)).unwrap();
    }
    drop(lot);
    path
}

/// What `lot show` and `lot board` print for every board of the lot at `path`, or the refusal.
fn printed(path: &Path) -> Result<String, LotError> {
    let lot = Lot::open_existing(path)?;
    let latest = lot.latest()?;
    let mut out = super::text::summary(&LotSummary::of(&latest, &Spec::default()));
    for serial in ["B1", "B2"] {
        out.push_str(&serde_json::to_string_pretty(&lot.board(serial)?).unwrap());
        out.push_str(&super::text::board(&lot.board(serial)?));
    }
    Ok(out)
}

/// The refusal of reading the lot at `path`; empty when it was read.
fn refused(path: &Path) -> String {
    printed(path).err().map(|e| e.to_string()).unwrap_or_default()
}

fn sql(path: &Path, statement: &str) {
    rusqlite::Connection::open(path).unwrap().execute_batch(statement).unwrap();
}

#[test]
fn one_digit_changed_in_a_stored_certificate_is_refused_naming_the_board() {
    let path = closed_lot("digit");
    printed(&path).unwrap();
    let connection = rusqlite::Connection::open(&path).unwrap();
    let json: String =
        connection.query_row("SELECT json FROM certificates WHERE serial = 'B2'", [], |row| row.get(0)).unwrap();
    // NOTE: the last digit of the first parameter's value, as someone editing the file would.
    let value = json.find("\"value\": ").unwrap() + "\"value\": ".len();
    let digit = value + json[value..].find([',', '\n']).unwrap() - 1;
    let changed = (json.as_bytes()[digit] - b'0' + 1) % 10 + b'0';
    let altered = format!("{}{}{}", &json[..digit], changed as char, &json[digit + 1..]);
    connection.execute("UPDATE certificates SET json = ?1 WHERE serial = 'B2'", [&altered]).unwrap();
    drop(connection);
    let refused = printed(&path).err();
    assert!(matches!(&refused, Some(LotError::Altered { serial, .. }) if serial == "B2"), "{refused:?}");
    let said = refused.map(|e| e.to_string()).unwrap_or_default();
    assert!(
        said.contains("board B2's certificate hashes to") && said.contains("from their certificate files"),
        "{said}"
    );
    remove(&path);
}

#[test]
fn a_parameters_row_that_differs_from_its_certificate_is_refused_naming_the_board_and_the_row() {
    let path = closed_lot("parameters");
    let b2 = "(SELECT id FROM certificates WHERE serial = 'B2')";
    sql(&path, &format!("UPDATE parameters SET value = value * (1 + 1e-12) WHERE name = 'o_y' AND certificate = {b2}"));
    let said = refused(&path);
    assert!(said.contains("board B2's `parameters` row o_y differs"), "{said}");
    let path = closed_lot("parameters");
    sql(&path, &format!("DELETE FROM parameters WHERE name = 's_z' AND certificate = {b2}"));
    let said = refused(&path);
    assert!(said.contains("board B2's `parameters` row s_z differs"), "{said}");
    remove(&path);
}

/// What one bit flipped in the lot file did to what is printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Flipped {
    Identical,
    RefusedAltered,
    RefusedDamaged,
    RefusedOther,
    ChangedSilently,
}

#[test]
fn no_bit_flipped_in_the_lot_file_changes_what_is_printed_without_a_refusal() {
    use rand_xoshiro::rand_core::{Rng, SeedableRng};
    let original_path = closed_lot("flips");
    let (original, bytes) = (printed(&original_path).unwrap(), std::fs::read(&original_path).unwrap());
    let trial = original_path.with_extension("flipped.sqlite");
    let mut random = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(40);
    let mut counts: BTreeMap<Flipped, usize> = BTreeMap::new();
    for _ in 0..200 {
        let bit = random.next_u64() % (bytes.len() as u64 * 8);
        let mut flipped = bytes.clone();
        flipped[(bit / 8) as usize] ^= 1 << (bit % 8);
        remove(&trial);
        std::fs::write(&trial, &flipped).unwrap();
        let outcome = match printed(&trial) {
            Ok(text) if text == original => Flipped::Identical,
            Ok(_) => Flipped::ChangedSilently,
            Err(LotError::Altered { .. }) => Flipped::RefusedAltered,
            Err(refused) => match refused.to_string() {
                said if said.contains(&*trial.to_string_lossy()) && said.contains("from their certificate files") => {
                    Flipped::RefusedDamaged
                }
                _ => Flipped::RefusedOther,
            },
        };
        *counts.entry(outcome).or_default() += 1;
    }
    eprintln!("200 bit flips of a {}-byte lot: {counts:?}", bytes.len());
    let wrong = [Flipped::ChangedSilently, Flipped::RefusedOther].map(|k| counts.get(&k).copied().unwrap_or(0));
    assert_eq!(wrong, [0, 0], "{counts:?}");
    remove(&trial);
    remove(&original_path);
}

#[test]
fn three_writers_on_a_new_lot_each_wait_for_the_others_and_every_board_goes_in() {
    let certificates: Vec<Certificate> =
        (1..=3).map(|s| certificate(s, &format!("B{s}"), "2026-11-24 10:00")).collect();
    let path = std::env::temp_dir().join(format!("accelcal-lot-writers-{}.sqlite", std::process::id()));
    let mut failures = Vec::new();
    for _ in 0..60 {
        remove(&path);
        let start = std::sync::Barrier::new(3);
        let written: Vec<Result<Added, LotError>> = std::thread::scope(|scope| {
            let writers: Vec<_> = certificates
                .iter()
                .map(|certificate| {
                    let (start, path) = (&start, &path);
                    scope.spawn(move || {
                        start.wait();
                        Lot::create_or_open(path)?.add(certificate)
                    })
                })
                .collect();
            writers.into_iter().map(|writer| writer.join().unwrap()).collect()
        });
        failures.extend(written.into_iter().filter_map(Result::err).map(|e| e.to_string()));
    }
    assert_eq!(failures, Vec::<String>::new());
    let consistency = Lot::open_existing(&path).unwrap().consistency().unwrap();
    assert_eq!((consistency.certificates, consistency.parameters, consistency.complete), (3, 36, true));
    remove(&path);
}

#[test]
fn a_writer_waits_for_another_connection_holding_a_new_lot_as_its_busy_wait_says() {
    let path = std::env::temp_dir().join(format!("accelcal-lot-held-{}.sqlite", std::process::id()));
    remove(&path);
    // NOTE: another writer half way through creating the lot: it holds the new file (still in
    // rollback mode) for writing, and SQLite refuses the switch to WAL at once, without waiting.
    let holder = rusqlite::Connection::open(&path).unwrap();
    holder.execute_batch("BEGIN IMMEDIATE; CREATE TABLE held (x);").unwrap();
    let started = std::time::Instant::now();
    let writer = std::thread::spawn({
        let path = path.clone();
        move || Lot::create_or_open(&path).map(|_| started.elapsed())
    });
    std::thread::sleep(Duration::from_millis(500));
    holder.execute_batch("COMMIT").unwrap();
    let waited = writer.join().unwrap().map_err(|e| e.to_string());
    assert!(matches!(waited, Ok(waited) if waited >= Duration::from_millis(500)), "{waited:?}");
    remove(&path);
}

#[test]
fn a_lot_is_read_without_writing_even_where_its_shared_memory_file_cannot_be_made() {
    let path = closed_lot("read-only");
    let before = std::fs::read(&path).unwrap();
    // NOTE: a dangling link where SQLite makes the WAL's `-shm` (it opens it without following
    // links): the reader cannot make it, as in a folder it cannot write.
    let shm = format!("{}-shm", path.display());
    std::os::unix::fs::symlink("/nonexistent/accelcal-lot-shm", &shm).unwrap();
    let lot = Lot::open_existing(&path).unwrap();
    assert_eq!(lot.latest().unwrap().len(), 2);
    let write = lot.file_connection().execute("DELETE FROM parameters", []).map_err(|e| e.sqlite_error_code());
    assert_eq!(write, Err(Some(rusqlite::ErrorCode::ReadOnly)));
    drop(lot);
    assert!(std::fs::read(&path).unwrap() == before, "a read changed the lot file");
    remove(&path);
}

#[test]
fn a_version_1_lot_file_reads_as_it_was_and_is_migrated_to_version_2_when_written() {
    let path = closed_lot("migrated");
    // NOTE: a version 1 file as issue 28's accelcal left it: no station column.
    sql(&path, "ALTER TABLE certificates DROP COLUMN station; PRAGMA user_version = 1;");
    let read = Lot::open_existing(&path).unwrap();
    assert_eq!((read.version, read.latest().unwrap().len()), (1, 2));
    drop(read);
    let mut lot = Lot::create_or_open(&path).unwrap();
    lot.station = "st-2".into();
    lot.add(&certificate(4, "B3", "2026-11-26 08:00")).unwrap();
    let stations: Vec<String> = lot.all().unwrap().into_iter().map(|(_, station)| station).collect();
    assert_eq!(stations, ["", "", "", "st-2"]);
    let version: i64 = lot.file_connection().pragma_query_value(None, "user_version", |r| r.get(0)).unwrap();
    assert_eq!(version, schema::LATEST);
    remove(&path);
}

#[test]
fn the_station_whose_boards_lie_away_from_the_others_is_named_and_each_group_has_its_own_cpk() {
    let made: Vec<Certificate> = (1..=6).map(|s| certificate(s, "B", "2026-11-24 10:00")).collect();
    let mut all = Vec::new();
    for (k, station) in ["st-a", "st-b", "st-c", "st-d"].into_iter().enumerate() {
        for (n, base) in made.iter().enumerate() {
            let mut c = base.clone();
            c.board.serial = Some(format!("{station}-{n}"));
            c.date_utc = Some(format!("2026-11-2{} 10:00", 4 + k % 2));
            // NOTE: st-c's fixture sits 0.2 g off in x: every board's o_x moves with it.
            if station == "st-c" {
                c.parameters.get_mut("o_x").unwrap().value += 0.2;
            }
            all.push((c.resealed(), station.to_owned()));
        }
    }
    let spec = Spec { limits: [("o_x".to_owned(), Limits { low: Some(-0.5), high: Some(0.5) })].into() };
    let by_station = stations::grouped(&all, stations::Grouping::Station, &spec);
    let named: Vec<(&str, &str)> =
        by_station.drifting.iter().map(|d| (d.station.as_str(), d.parameter.as_str())).collect();
    assert_eq!(named, [("st-c", "o_x")], "{:?}", by_station.drifting);
    assert!((by_station.drifting[0].mean - by_station.drifting[0].others_mean - 0.2).abs() < 1e-12);
    let st_a: Vec<Certificate> = all.iter().filter(|(_, s)| s == "st-a").map(|(c, _)| c.clone()).collect();
    assert_eq!(by_station.groups[0].summary, LotSummary::of(&st_a, &spec));
    let by_day = stations::grouped(&all, stations::Grouping::Day, &spec);
    let days: Vec<(&str, usize)> = by_day.groups.iter().map(|g| (g.name.as_str(), g.summary.boards)).collect();
    assert_eq!(days, [("2026-11-24", 12), ("2026-11-25", 12)]);
    assert!(by_day.drifting.is_empty());
    let said = text::grouped(&by_station, "station");
    assert!(said.contains("station st-c drifts from the others: o_x"), "{said}");
}

#[test]
fn a_difference_of_means_is_in_welch_s_standard_errors_and_needs_five_boards_a_side() {
    let (a, b) = ([1.0, 2.0, 3.0, 4.0, 5.0], [0.0, 0.0, 1.0, 1.0, 3.0]);
    // mean 3 vs 1; var/n 2.5/5 and 1.5/5: (3 - 1) / sqrt(0.8).
    let z = stations::difference_in_standard_errors(&a, &b).unwrap();
    assert!((z - 2.0 / 0.8f64.sqrt()).abs() < 1e-12, "{z}");
    assert_eq!(stations::difference_in_standard_errors(&a[..4], &b), None);
}
