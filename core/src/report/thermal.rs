//! The report of a thermal calibration: the calibration with its temperature model and, on the
//! simulated board, its verification at several temperatures against the simulator's truth.

use serde::{Deserialize, Serialize};

use crate::calibration::CalibrationJson;
use crate::fit::hysteresis::Hysteresis;
use crate::fit::thermal::{ThermalFit, ThermalPoint};

/// One verification temperature (the `accelcal thermal --sim --json` interface, DESIGN.md).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ThermalRow {
    /// The die temperature the sensor reported, in degC (mean over the row's captures).
    pub temp_c: f64,
    /// The simulated sensor's true correction at that temperature: a = matrix (m - offset), in g.
    pub matrix: [[f64; 3]; 3],
    /// Its true offset, in g.
    pub offset: [f64; 3],
    /// The correction matrix the chip applies at that temperature.
    pub applied_matrix: [[f64; 3]; 3],
    /// The offset the chip applies at that temperature, in g.
    pub applied_offset: [f64; 3],
    /// The correction matrix without the temperature model.
    pub static_matrix: [[f64; 3]; 3],
    /// The offset without the temperature model, in g.
    pub static_offset: [f64; 3],
    /// RMS of | |a| - 1 g | at the row's orientations with the static calibration only, in mg.
    pub uncompensated_rms_mg: f64,
    /// The same with the temperature model, in mg.
    pub compensated_rms_mg: f64,
    /// Largest error of the gyro bias the chip subtracts at that temperature, per axis, in deg/s.
    pub gyro_bias_error_dps: f64,
    /// Fresh orientations captured.
    pub positions: usize,
}

/// One learning bin: the resting board's averages at one temperature and orientation.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq)]
pub struct ThermalBinJson {
    /// Die temperature the sensor reported, in degC.
    pub temp_c: f64,
    /// The specific force of the face the board rested on, in g.
    pub force_g: [f64; 3],
    /// Mean accelerometer reading, raw, in g.
    pub accel_g: [f64; 3],
    /// Mean gyro reading, raw, in deg/s.
    pub gyro_dps: [f64; 3],
}

impl From<&ThermalPoint> for ThermalBinJson {
    fn from(p: &ThermalPoint) -> Self {
        ThermalBinJson { temp_c: p.temp_c, force_g: p.force_g, accel_g: p.accel_g, gyro_dps: p.gyro_dps }
    }
}

/// The fit's choices, for the report.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ThermalFitJson {
    /// Polynomial order per accelerometer axis.
    pub accel_order: [usize; 3],
    /// Polynomial order per gyro axis.
    pub gyro_order: [usize; 3],
    /// Held-out RMS error of the accelerometer at those orders, in mg.
    pub held_out_mg: f64,
    /// Whether the sensitivity's drift was fitted (several orientations) or only the offset's.
    pub scale_fitted: bool,
    /// Temperature bins learned.
    pub bins: usize,
    /// Lowest and highest temperature learned, in degC.
    pub learned_c: [f64; 2],
    /// Why learning stopped.
    pub stopped: String,
    /// The bins the model was fitted to (`accelcal report --thermal` plots them).
    #[serde(default)]
    pub points: Vec<ThermalBinJson>,
    /// Heating against cooling, when the run learned both ways.
    #[serde(default)]
    pub hysteresis: Option<Hysteresis>,
}

impl ThermalFitJson {
    /// The report's view of a fit to `points`, binned into `bins` bins spanning `learned_c`.
    pub fn new(fit: &ThermalFit, points: &[ThermalPoint], bins: usize, learned_c: [f64; 2], stopped: String) -> Self {
        ThermalFitJson {
            accel_order: fit.accel_order,
            gyro_order: fit.gyro_order,
            held_out_mg: fit.held_out_mg,
            scale_fitted: fit.scale_fitted,
            bins,
            learned_c,
            stopped,
            points: points.iter().map(ThermalBinJson::from).collect(),
            hysteresis: None,
        }
    }
}

/// The whole report.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ThermalReport {
    /// The serial number of the board it was learned on (24 hexadecimal digits, as sessions record
    /// it); `None` in files written before accelcal recorded it.
    #[serde(default)]
    pub serial: Option<String>,
    /// The calibration with its temperature model.
    pub calibration: CalibrationJson,
    /// How the temperature model was fitted.
    pub fit: ThermalFitJson,
    /// Verification rows (simulated board only).
    #[serde(default)]
    pub verification: Vec<ThermalRow>,
}

impl ThermalReport {
    /// The JSON object `accelcal thermal --json` prints.
    pub fn json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// The text form: the fit, then a table of temperature, error before and after.
    pub fn text(&self) -> String {
        let f = &self.fit;
        let mut text = format!(
            "learned {} bins over {:.1}-{:.1} degC ({}); orders accel {:?} gyro {:?}; held-out {:.3} mg; sensitivity {}\n",
            f.bins,
            f.learned_c[0],
            f.learned_c[1],
            f.stopped,
            f.accel_order,
            f.gyro_order,
            f.held_out_mg,
            if f.scale_fitted { "fitted" } else { "not observable (one orientation)" }
        );
        if let Some(h) = &f.hysteresis {
            text.push_str(&hysteresis_line(h));
        }
        if !self.verification.is_empty() {
            text.push_str("temp_c  static_rms_mg  compensated_rms_mg  gyro_bias_error_dps\n");
        }
        for row in &self.verification {
            text.push_str(&format!(
                "{:6.1}  {:13.3}  {:18.3}  {:19.4}\n",
                row.temp_c, row.uncompensated_rms_mg, row.compensated_rms_mg, row.gyro_bias_error_dps
            ));
        }
        text
    }
}

/// Heating against cooling in one line.
fn hysteresis_line(h: &Hysteresis) -> String {
    let axes: Vec<String> =
        (0..3).map(|k| format!("{:+.3} +- {:.3}", h.heating_minus_cooling_mg[k], h.std_error_mg[k])).collect();
    format!(
        "heating minus cooling offset at {:.1} degC (overlap {:.1}-{:.1} degC, {} and {} bins): {} mg (x, y, z)\n",
        h.temp_c,
        h.overlap_c[0],
        h.overlap_c[1],
        h.bins[0],
        h.bins[1],
        axes.join(", ")
    )
}
