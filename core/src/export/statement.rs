//! What every export states about itself, in plain lines its target puts in its own comment syntax:
//! the board and sensor setting it belongs to, the temperature it was made at and the temperature
//! model, the convention the target applies, what it carries, and what it loses on this unit.

use shared::calibration::{TempCoefficients, TemperatureModel};
use shared::STANDARD_GRAVITY;

use super::loss::{Loss, SPHERE_POINTS};
use super::Source;

/// What one target says of itself.
pub struct Said<'a> {
    /// The target, as a person knows it ("ArduPilot parameter file").
    pub title: &'a str,
    /// The formula the target applies, vectors, units and the g used, one line each.
    pub convention: &'a [&'a str],
    /// What of the calibration the file carries.
    pub carries: &'a str,
    /// What the target does with the temperature model.
    pub temperature: &'a str,
    /// Whether it leaves part of the calibration behind (then it names the targets that carry all of it).
    pub lossy: bool,
}

/// What a lossy target says of the targets that lose nothing, so that a person who needs all of it
/// knows where to go.
pub const WHOLE: &str = "all of it: --to c carries M, o, G, b in full (float; --to c-fixed on a part with no \
                         floating-point unit, such as an 8-bit AVR; --to rust, --to fusion and --to matlab too)";

/// The lines every export states, with `said` for its target and `loss` on this unit.
pub fn lines(source: &Source, said: &Said, loss: &Loss) -> Vec<String> {
    let mut lines = vec![
        format!("accelcal calibration for {}, written by accelcal {}", said.title, env!("CARGO_PKG_VERSION")),
        format!("from: {}", source.from),
        format!("board serial: {}", serial(source)),
        sensor(source),
        made_at(source),
        format!("temperature model: {}", temperature_model(source.calibration.temperature.as_ref())),
        format!("temperature model in this file: {}", said.temperature),
    ];
    if source.calibration.temperature.is_some() {
        lines.insert(lines.len() - 1, learned_over(source));
    }
    lines.extend(said.convention.iter().map(|line| format!("convention: {line}")));
    lines.push(format!("g: {STANDARD_GRAVITY} m/s^2 per g (standard gravity) wherever a value is in m/s^2"));
    lines.push(format!("carries: {}", said.carries));
    lines.extend(lost(loss, source.has_gyro_matrix()));
    if said.lossy {
        lines.push(WHOLE.to_owned());
    }
    lines
}

/// The serial number, or why there is none.
fn serial(source: &Source) -> String {
    source.serial.clone().unwrap_or_else(|| {
        "not recorded in what this was exported from (export a session file or --port for it)".to_owned()
    })
}

/// Sensor, range and filter: our firmware's setting, or a stream's units.
fn sensor(source: &Source) -> String {
    let (calibration, readings) = (&source.calibration, &source.readings);
    if let Some(printed) = &readings.printed {
        return format!(
            "sensor: as the board's own code set it up (a stream records no part, range or filter); its stream \
             printed {}; {}; the calibration holds at that setting only",
            printed.units(),
            takes(source)
        );
    }
    let part = readings
        .sensor
        .as_deref()
        .unwrap_or("MPU-6050 family (the part is not recorded in what this was exported from)");
    format!(
        "sensor: {part}, accelerometer +-{} g, low-pass filter {} Hz, gyro +-1000 deg/s; {}; the calibration \
         holds at this range and filter only",
        calibration.range.full_scale_g(),
        calibration.filter.bandwidth_hz(),
        takes(source)
    )
}

/// What the exported code takes: raw counts, or the values a stream printed, in its units.
pub fn takes(source: &Source) -> String {
    let (per_g, per_dps) = (source.accel_per_g(), source.gyro_per_dps());
    match &source.readings.printed {
        Some(printed) if !source.takes_counts() => format!(
            "what follows takes the values as the sketch printed them: accelerometer in {} ({per_g} per g), gyro in \
             {} ({per_dps} per deg/s)",
            printed.accel.name(),
            printed.gyro.map_or("counts at +-1000 deg/s (the stream's gyro unit is not recorded)", |g| g.name())
        ),
        _ => format!("what follows takes raw counts at {per_g} LSB per g and {per_dps} LSB per deg/s"),
    }
}

/// The die temperature it was made at, or that none was measured.
fn made_at(source: &Source) -> String {
    match source.readings.made_at_c {
        Some(c) => format!("made at: {c:.1} degC die temperature (the mean of the captures it was fitted to)"),
        None => "made at: die temperature not measured (a board's own stream carries none)".to_owned(),
    }
}

/// The die temperatures the temperature model was learned over, or that they are not recorded.
fn learned_over(source: &Source) -> String {
    match source.readings.drift_span_c {
        Some((low, high)) => {
            format!("temperature model learned over: {low:.1} to {high:.1} degC die temperature (the captures' span)")
        }
        None => "temperature model learned over: not recorded in what this was exported from (a model `accelcal \
                 thermal` learned, or one read from the board): a file that bounds the model takes the operating \
                 range; export the session file instead, which records the span its own drift was learned over"
            .to_owned(),
    }
}

/// The loss lines, in a fixed form (tests read them back).
fn lost(loss: &Loss, has_gyro_matrix: bool) -> Vec<String> {
    let gyro_note = if has_gyro_matrix { "" } else { " (no gyro matrix was fitted in what this was exported from)" };
    vec![
        format!(
            "lost, accelerometer, against accelcal's full calibration over {SPHERE_POINTS} orientations at 1 g: \
             {:.4} mg rms, {:.4} mg worst",
            loss.rms_mg, loss.worst_mg
        ),
        format!(
            "lost, gyro scale and misalignment, of the rate: {:.3} % rms, {:.3} % worst{gyro_note}",
            loss.gyro_rms_pct, loss.gyro_worst_pct
        ),
    ]
}

/// The temperature model in words, or that there is none.
pub fn temperature_model(model: Option<&TemperatureModel>) -> String {
    let Some(model) = model else {
        return "none (offsets and scales hold near the temperature above)".to_owned();
    };
    let parts: Vec<String> = [
        terms("offset", "mg", 1e3, &model.offset_g),
        terms("sensitivity", "ppm", 1e6, &model.scale),
        terms("gyro bias", "deg/s", 1.0, &model.gyro_bias_dps),
    ]
    .into_iter()
    .flatten()
    .collect();
    format!(
        "around T_ref {:.2} degC: {} (o(T) = o + sum c_k (T - T_ref)^k; M(T) = M diag(1 + d(T))^-1; b(T) = b + sum e_k (T - T_ref)^k)",
        model.ref_temp_c,
        if parts.is_empty() { "flat".to_owned() } else { parts.join("; ") }
    )
}

/// The nonzero orders of one part of the temperature model.
fn terms(name: &str, unit: &str, factor: f64, coefficients: &TempCoefficients) -> Option<String> {
    let orders: Vec<String> = coefficients
        .iter()
        .enumerate()
        .filter(|(_, c)| c.iter().any(|v| *v != 0.0))
        .map(|(k, c)| {
            let [x, y, z] = c.map(|v| f64::from(v) * factor);
            format!("order {}: {x:+.5} {y:+.5} {z:+.5} {unit}/degC^{}", k + 1, k + 1)
        })
        .collect();
    (!orders.is_empty()).then(|| format!("{name} {}", orders.join(", ")))
}
