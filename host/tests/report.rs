//! `accelcal report` on a simulated session: the page holds exactly the numbers `--json` prints,
//! stands alone, says what the session lacks, and loads in a real browser with every plot drawn.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn accelcal(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_accelcal")).args(args).output().expect("accelcal runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A directory of its own for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("accelcal-report-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A whole simulated calibration kept as `DIR/session`; the JSON path of the session.
fn simulated_session(dir: &Path) -> PathBuf {
    let stem = dir.join("session");
    let output = accelcal(&["calibrate", "--sim", "--yes", "--seed", "7", "--session", stem.to_str().unwrap()]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    let page = stem.with_extension("html");
    let said = text(&output.stdout) + &text(&output.stderr);
    assert!(said.contains(&format!("report written to {}", page.display())), "calibrate did not say where: {said}");
    assert!(page.exists(), "calibrate wrote no page at {}", page.display());
    stem.with_extension("json")
}

/// What `report --thermal` and `--noise` take, made in `dir`: the simulated board's `thermal --json`
/// (the session's board: seed 7) and a 60 s recording at 1 kHz of the same board with its `noise --json`.
struct Extras {
    thermal: PathBuf,
    recording: PathBuf,
    noise: PathBuf,
}

fn extras(dir: &Path) -> Extras {
    let (thermal, recording, noise) = (dir.join("thermal.json"), dir.join("rec.npy"), dir.join("noise.json"));
    thermal_json(&thermal, "7");
    let output = accelcal(&["record", "--sim", "--seed", "7", "--seconds", "60", "-o", recording.to_str().unwrap()]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    let output = accelcal(&["noise", recording.to_str().unwrap(), "--json"]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    std::fs::write(&noise, &output.stdout).unwrap();
    Extras { thermal, recording, noise }
}

/// `thermal --sim --json` of the simulated board of `seed`, written to `path`.
fn thermal_json(path: &Path, seed: &str) {
    let output = accelcal(&["thermal", "--sim", "--json", "--seed", seed]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    std::fs::write(path, &output.stdout).unwrap();
}

#[test]
fn a_thermal_json_of_another_board_is_refused_and_one_naming_no_board_is_read_with_a_caveat() {
    let dir = scratch("other-board");
    let session = simulated_session(&dir);
    let other = dir.join("other.json");
    thermal_json(&other, "3");
    let output = accelcal(&["report", session.to_str().unwrap(), "--json", "--thermal", other.to_str().unwrap()]);
    let stderr = text(&output.stderr);
    assert!(!output.status.success(), "another board's thermal model was added: {stderr}");
    assert!(stderr.contains("it was learned on board 53494D000000000000000003"), "{stderr}");
    assert!(stderr.contains("the session was taken on board 53494D000000000000000007"), "{stderr}");
    // A file written before the serial was recorded: read, and said to be unchecked.
    let mut json: Value = serde_json::from_str(&std::fs::read_to_string(&other).unwrap()).unwrap();
    json.as_object_mut().unwrap().remove("serial");
    let older = dir.join("older.json");
    std::fs::write(&older, json.to_string()).unwrap();
    let output = accelcal(&["report", session.to_str().unwrap(), "--json", "--thermal", older.to_str().unwrap()]);
    let stderr = text(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(stderr.contains("names no board") && stderr.contains("is not checked"), "{stderr}");
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert!(report["temperature"].is_object(), "{report}");
}

#[test]
fn a_recording_of_another_board_is_refused_and_a_noise_json_naming_no_board_is_read_with_a_caveat() {
    let dir = scratch("other-recording");
    let session = simulated_session(&dir);
    let recording = dir.join("other.npy");
    let output = accelcal(&["record", "--sim", "--seed", "3", "--seconds", "5", "-o", recording.to_str().unwrap()]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    let output = accelcal(&["report", session.to_str().unwrap(), "--json", "--noise", recording.to_str().unwrap()]);
    let stderr = text(&output.stderr);
    assert!(!output.status.success(), "another board's recording was added: {stderr}");
    assert!(stderr.contains("it was recorded on board 53494D000000000000000003"), "{stderr}");
    assert!(stderr.contains("the session was taken on board 53494D000000000000000007"), "{stderr}");
    // Its noise JSON names the board too; named as the session's board it is taken, naming none it is
    // taken with the caveat.
    let output = accelcal(&["noise", recording.to_str().unwrap(), "--json"]);
    let mut json: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(json["serial"], "53494D000000000000000003");
    let noise_json = dir.join("noise.json");
    let mut with_noise = |serial: Value| {
        json["serial"] = serial;
        std::fs::write(&noise_json, json.to_string()).unwrap();
        accelcal(&["report", session.to_str().unwrap(), "--json", "--noise", noise_json.to_str().unwrap()])
    };
    let output = with_noise(Value::from("53494D000000000000000007"));
    assert!(output.status.success() && !text(&output.stderr).contains("names no board"), "{}", text(&output.stderr));
    let output = with_noise(Value::Null);
    let stderr = text(&output.stderr);
    assert!(output.status.success() && stderr.contains("names no board"), "{stderr}");
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert!(report["allan_deviation"].is_object(), "{report}");
}

fn report_json(session: &Path) -> Value {
    report_json_with(session, &[])
}

fn report_json_with(session: &Path, extra: &[&str]) -> Value {
    let output = accelcal(&[&["report", session.to_str().unwrap(), "--json"], extra].concat());
    assert!(output.status.success(), "{}", text(&output.stderr));
    serde_json::from_slice(&output.stdout).expect("report --json prints one JSON object")
}

/// Every tagged number of the page: (JSON pointer, full value, text shown).
fn tagged(html: &str) -> Vec<(String, Option<String>, String)> {
    let mut found = Vec::new();
    for piece in html.split("data-json=\"").skip(1) {
        let (pointer, rest) = piece.split_once('"').unwrap();
        let value = rest.strip_prefix(" data-value=\"").map(|r| r.split_once('"').unwrap().0.to_owned());
        let shown = rest.split_once('>').unwrap().1.split_once('<').unwrap().0;
        found.push((pointer.to_owned(), value, unescape(shown)));
    }
    found
}

fn unescape(text: &str) -> String {
    text.replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&amp;", "&")
}

/// The pointers the page must show: every parameter, position, verification figure, the verdict,
/// the temperature model's figures and every fitted noise term.
fn required_pointers(json: &Value) -> BTreeSet<String> {
    let mut wanted: BTreeSet<String> = ["/verdict/line", "/fit/cost", "/fit/rms_mg"].map(String::from).into();
    for key in ["ref_temp_c", "learned_c/0", "learned_c/1", "held_out_mg"] {
        wanted.insert(format!("/temperature/{key}"));
    }
    for k in 0..3 {
        wanted.extend(["offset_change_mg", "gyro_bias_change_dps"].map(|key| format!("/temperature/{key}/{k}")));
    }
    wanted.extend(["/allan_deviation/sample_rate_hz", "/allan_deviation/capture_limit_s"].map(String::from));
    for i in 0..6 {
        let terms = ["white_noise_density", "bias_instability", "bias_instability_tau_s", "random_walk"];
        wanted.extend(terms.map(|key| format!("/allan_deviation/axes/{i}/{key}")));
    }
    for key in ["positions", "before_rms_mg", "after_rms_mg", "after_max_mg", "noise_floor_mg", "on_chip_difference_mg"]
    {
        wanted.insert(format!("/verification/{key}"));
    }
    for name in json["fit"]["parameters"].as_object().expect("parameters keyed by name").keys() {
        wanted.extend(["value", "std_error"].map(|key| format!("/fit/parameters/{name}/{key}")));
    }
    // The gyro's turns: a calibration on the simulated board records the 13 between its 14 positions.
    let turns = json["gyro_turns"].as_array().expect("the session records its gyro turns");
    assert_eq!(turns.len(), 13);
    for i in 0..turns.len() {
        wanted.extend(
            ["expected_deg", "raw_deg", "calibrated_deg", "residual_raw_deg", "residual_calibrated_deg"]
                .map(|key| format!("/gyro_turns/{i}/{key}")),
        );
    }
    for i in 0..json["positions"].as_array().unwrap().len() {
        wanted.extend(["residual_before_mg", "residual_after_mg"].map(|key| format!("/positions/{i}/{key}")));
        wanted.extend(
            (0..3).flat_map(|k| [format!("/positions/{i}/raw_g/{k}"), format!("/positions/{i}/calibrated_g/{k}")]),
        );
    }
    wanted
}

/// Checks one tagged number against the JSON: the full value exactly, the text to its last digit.
fn check_number(pointer: &str, value: &str, shown: &str, json: &Value) {
    let printed = json.pointer(pointer).unwrap_or_else(|| panic!("{pointer} is not in report --json"));
    if value == "null" {
        assert!(printed.is_null(), "{pointer}: the page shows nothing, the JSON {printed}");
        return;
    }
    let (full, printed) = (value.parse::<f64>().unwrap(), printed.as_f64().unwrap());
    assert_eq!(full, printed, "{pointer}: page {full}, JSON {printed}");
    let rounded: f64 = shown.parse().unwrap_or_else(|_| panic!("{pointer} shows {shown:?}"));
    let mantissa = shown.split(['e', 'E']).next().unwrap();
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    let exponent: i32 = shown.split_once(['e', 'E']).map_or(0, |(_, e)| e.parse().unwrap());
    let half_unit = 0.5 * 10f64.powi(exponent - decimals) * (1.0 + 1e-9);
    assert!((rounded - printed).abs() <= half_unit, "{pointer}: shows {shown}, JSON {printed}");
}

#[test]
fn every_number_on_the_page_is_the_one_report_json_prints() {
    let dir = scratch("numbers");
    let session = simulated_session(&dir);
    let extras = extras(&dir);
    let given = ["--thermal", extras.thermal.to_str().unwrap(), "--noise", extras.noise.to_str().unwrap()];
    let json = report_json_with(&session, &given);
    let page = dir.join("with-extras.html");
    let output = accelcal(&[&["report", session.to_str().unwrap(), "-o", page.to_str().unwrap()], &given[..]].concat());
    assert!(output.status.success(), "{}", text(&output.stderr));
    let html = std::fs::read_to_string(page).unwrap();
    // The noise terms are the ones `noise --json` printed, the bins the ones `thermal --json` learned.
    let noise: Value = serde_json::from_str(&std::fs::read_to_string(&extras.noise).unwrap()).unwrap();
    assert_eq!(json["allan_deviation"]["axes"][2]["white_noise_density"], noise["accel_z"]["white_noise_density"]);
    let thermal: Value = serde_json::from_str(&std::fs::read_to_string(&extras.thermal).unwrap()).unwrap();
    assert_eq!(json["temperature"]["bins"], thermal["fit"]["points"]);
    let tags = tagged(&html);
    let shown: BTreeSet<String> = tags.iter().map(|(pointer, _, _)| pointer.clone()).collect();
    let missing: Vec<_> = required_pointers(&json).difference(&shown).cloned().collect();
    assert!(missing.is_empty(), "the page does not show {missing:?}");
    for (pointer, value, shown) in &tags {
        match value {
            Some(value) => check_number(pointer, value, shown, &json),
            None => assert_eq!(Some(shown.as_str()), json.pointer(pointer).and_then(Value::as_str), "{pointer}"),
        }
    }
}

#[test]
fn the_page_stands_alone_and_names_what_the_session_does_not_hold() {
    let dir = scratch("alone");
    let session = simulated_session(&dir);
    let mut stored: Value = serde_json::from_str(&std::fs::read_to_string(&session).unwrap()).unwrap();
    let serial =
        stored.pointer("/board/serial").and_then(Value::as_str).expect("calibrate records the board").to_owned();
    let recorded = std::fs::read_to_string(session.with_extension("html")).unwrap();
    assert!(recorded.contains(&serial), "the page of a session that records its board names the serial {serial}");
    // A session of `accelcal capture` records no board, and an unverified one no verification.
    stored.as_object_mut().unwrap().remove("verification");
    stored.as_object_mut().unwrap().remove("board");
    let unverified = dir.join("unverified.json");
    std::fs::write(&unverified, stored.to_string()).unwrap();
    let page = dir.join("unverified-page.html");
    let output = accelcal(&["report", unverified.to_str().unwrap(), "-o", page.to_str().unwrap()]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    assert!(text(&output.stdout).contains("not verified at fresh orientations"), "{}", text(&output.stdout));
    let html = std::fs::read_to_string(&page).unwrap();
    for outside in ["<script", "<link", "src=", "url(", "@import", "https:"] {
        assert!(!html.contains(outside), "the page reaches outside itself: {outside}");
    }
    assert!(html.replace("http://www.w3.org/2000/svg", "").find("http:").is_none(), "the page links out");
    // Verification, temperature, Allan deviation: none is in this session; its gyro turns are.
    assert_eq!(html.matches("not part of this session").count(), 3);
    assert!(html.contains("<figure id=\"gyro-turns\">"), "the page draws the gyro's turns");
    assert_eq!(
        html.matches("not recorded").count(),
        4,
        "serial, firmware, sensor and configuration are not in this session"
    );
    assert!(!html.contains("id=\"verification"));
}

/// Put first in the head: records every resource that fails to load (an image, a stylesheet).
const LISTEN: &str = r#"<meta charset="utf-8"><script>
window.failed = []; addEventListener("error", e => failed.push(String(e.target.src || e.target.href || e.message)), true);
</script>"#;

/// Put last in the body: once the page has loaded, writes into the DOM each plot's drawn size and
/// how many of its markers the browser laid out with a size, and every resource fetched or failed.
const PROBE: &str = r#"<script>addEventListener("load", () => {
document.body.setAttribute("data-plots", JSON.stringify([...document.querySelectorAll("figure")].map(f => {
  const svg = f.querySelector("svg"); const box = svg ? svg.getBBox() : {width: 0, height: 0};
  const markers = svg ? [...svg.querySelectorAll("circle")].filter(c => c.getBBox().width > 0).length : 0;
  return {id: f.id, width: box.width, height: box.height, markers: markers};
})));
document.body.setAttribute("data-fetched", JSON.stringify(failed.concat(
  performance.getEntriesByType("resource").map(e => e.name))));
});</script></body>"#;

/// Headless Chromium; the test that needs it is ignored where the build found none (and CI is not set).
fn chromium() -> &'static str {
    let found = Command::new("chromium").arg("--version").output().is_ok_and(|o| o.status.success());
    assert!(found, "chromium is not installed (apt-get install chromium)");
    "chromium"
}

#[test]
#[cfg_attr(not(has_chromium), ignore = "needs chromium (apt-get install chromium); CI=true runs it")]
fn the_page_loads_in_headless_chromium_without_console_errors_and_draws_every_plot() {
    let browser = chromium();
    let dir = scratch("browser");
    let session = simulated_session(&dir);
    let extras = extras(&dir);
    // The noise straight from the recording this time: `report` analyses it as `noise` would.
    let given = ["--thermal", extras.thermal.to_str().unwrap(), "--noise", extras.recording.to_str().unwrap()];
    let page = dir.join("with-extras.html");
    let output = accelcal(&[&["report", session.to_str().unwrap(), "-o", page.to_str().unwrap()], &given[..]].concat());
    assert!(output.status.success(), "{}", text(&output.stderr));
    let html = std::fs::read_to_string(page).unwrap();
    let probed = dir.join("probed.html");
    std::fs::write(&probed, html.replacen("<meta charset=\"utf-8\">", LISTEN, 1).replace("</body>", PROBE)).unwrap();
    let output = Command::new(browser)
        .args(["--headless", "--disable-gpu", "--no-sandbox", "--enable-logging=stderr", "--v=0", "--dump-dom"])
        .arg(format!("--user-data-dir={}", dir.join("profile").display()))
        .arg(format!("file://{}", probed.display()))
        .output()
        .expect("chromium runs");
    assert!(output.status.success(), "{}", text(&output.stderr));
    let console: Vec<String> =
        text(&output.stderr).lines().filter(|l| l.contains("CONSOLE")).map(String::from).collect();
    assert!(console.is_empty(), "the page logged to the console: {console:?}");
    let dom = text(&output.stdout);
    let fetched: Vec<Value> = probed_attribute(&dom, "data-fetched");
    assert!(fetched.is_empty(), "the page fetched, or failed to fetch, {fetched:?}");
    let plots: Vec<Value> = probed_attribute(&dom, "data-plots");
    let ids: Vec<&str> = plots.iter().map(|p| p["id"].as_str().unwrap()).collect();
    let all = ["sphere-xy", "sphere-xz", "residuals-raw", "residuals-calibrated"];
    let later = ["verification-raw", "verification-calibrated", "temperature", "allan-deviation", "gyro-turns"];
    assert_eq!(ids, [&all[..], &later[..]].concat());
    let figures = figures_by_id(&report_json_with(&session, &given)["figures"]);
    for plot in &plots {
        let (width, height) = (plot["width"].as_f64().unwrap(), plot["height"].as_f64().unwrap());
        assert!(width > 200.0 && height > 200.0, "{plot} is drawn smaller than its axes");
        let figure = figures.iter().find(|f| f["id"] == plot["id"]).expect("every plot is in the JSON");
        assert_eq!(plot["markers"].as_u64(), Some(points_marked(figure)), "{plot}: a marker per point");
    }
}

/// A JSON list the probe wrote into the DOM.
fn probed_attribute(dom: &str, name: &str) -> Vec<Value> {
    let (_, rest) = dom.split_once(&format!("{name}=\"")).unwrap_or_else(|| panic!("the probe wrote no {name}"));
    serde_json::from_str(&unescape(rest.split_once('"').unwrap().0)).unwrap()
}

/// Every figure of report --json, whether alone or in a pair.
fn figures_by_id(figures: &Value) -> Vec<Value> {
    let flat = figures.as_object().unwrap().values().flat_map(|f| f.as_array().cloned().unwrap_or(vec![f.clone()]));
    flat.filter(|f| f.is_object()).collect()
}

/// How many points of a figure are drawn as markers.
fn points_marked(figure: &Value) -> u64 {
    let series = figure["series"].as_array().unwrap_or_else(|| panic!("no figure {figure}"));
    let marked = series.iter().filter(|s| s["style"] == "points");
    marked.map(|s| s["points"].as_array().unwrap().len() as u64).sum()
}

#[test]
fn the_report_of_a_quick_session_shows_the_ortho9_calibration_the_chip_fitted() {
    let dir = scratch("quick");
    let stem = dir.join("quick");
    let output =
        accelcal(&["calibrate", "--sim", "--chip-fit", "--yes", "--seed", "3", "--session", stem.to_str().unwrap()]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    let json = report_json(&stem.with_extension("json"));
    assert_eq!(json.pointer("/fit/model").and_then(Value::as_str), Some("ortho9"), "{json:#}");
}

#[test]
fn the_report_of_a_default_session_fits_as_the_upload_did_with_the_drift_taken_out() {
    let dir = scratch("adaptive");
    let stem = dir.join("adaptive");
    let output =
        accelcal(&["calibrate", "--sim", "--yes", "--json", "--seed", "2", "--session", stem.to_str().unwrap()]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    let uploaded: Value = serde_json::from_slice(&output.stdout).unwrap();
    let json = report_json(&stem.with_extension("json"));
    let parameter =
        |name: &str| json.pointer(&format!("/fit/parameters/{name}/value")).and_then(Value::as_f64).unwrap();
    let calibration = &uploaded["calibration"];
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        // The uploaded record holds f32: its offsets agree with the report's f64 fit to f32 rounding.
        let offset = calibration["offset"][k].as_f64().unwrap();
        assert!((parameter(&format!("o_{axis}")) - offset).abs() < 1e-7, "o_{axis}: {offset} uploaded, {json:#}");
        let scale = calibration["matrix"][k][k].as_f64().unwrap();
        assert!((parameter(&format!("s_{axis}")) - scale).abs() < 1e-6, "s_{axis}: {scale} uploaded");
    }
    // The positions' raw readings are the ones taken (the drift is taken out of the fit's input only).
    let session: Value = serde_json::from_str(&std::fs::read_to_string(stem.with_extension("json")).unwrap()).unwrap();
    let captures = session["captures"].as_array().unwrap();
    let positions = json["positions"].as_array().unwrap();
    assert_eq!(captures.len(), positions.len());
    for (capture, position) in captures.iter().zip(positions) {
        for k in 0..3 {
            let (taken, shown) =
                (capture["stats"]["mean_g"][k].as_f64().unwrap(), position["raw_g"][k].as_f64().unwrap());
            // The session keeps f32 readings as JSON text: equal to its printed digits.
            assert!((taken - shown).abs() < 1e-6, "{}: raw {shown} vs taken {taken}", capture["name"]);
        }
    }
}
