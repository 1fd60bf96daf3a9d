//! What a guided calibration reports: the calibration chosen, the simulator's truth when there is
//! one, the verification, and the fits it was chosen from.

use serde::Serialize;
use shared::Calibration;

use super::gyro::{GyroJson, GyroOutcome, TruthGyroJson};
use crate::calibration::CalibrationJson;
use crate::certificate::Certificate;
use crate::fit::{parameters_by_name, Fit, Parameter};
use crate::session::{TargetVerdict, TurnCheck, Verification};

/// The object `accelcal calibrate --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrateReport {
    /// The calibration uploaded and saved.
    pub calibration: ChosenJson,
    /// The simulated sensor's truth at the calibration's temperature, and its drift (only with `--sim`).
    pub truth: Option<TruthJson>,
    /// With `--sim`: the calibration's true error, the rms of | |a| - 1 g | in mg over 200
    /// orientations of the simulated sensor at the calibration's temperature (noise-free readings).
    pub true_error_mg: Option<f64>,
    /// The errors at fresh orientations before and after.
    pub verification: Verification,
    /// Positions captured.
    pub captures: usize,
    /// The chip's own `ortho9` fit of the captures it kept (the calibration itself for `--chip-fit`; absent
    /// for a resumed session: the chip holds only the captures of the last run).
    pub chip_fit: Option<CalibrationJson>,
    /// The host's fit, when it made the calibration.
    pub host_fit: Option<HostFitSummary>,
    /// Seconds of the board's time from the first capture's start to the last verification
    /// capture's end (the simulated board's own clock with `--sim`, the wall clock otherwise).
    pub board_seconds: Option<f64>,
    /// The gyro's verification turn, when it was measured.
    pub gyro_check: Option<TurnCheck>,
    /// The verification against `--target-mg` (trusted or not, without a target).
    pub target: Option<TargetVerdict>,
    /// The board's calibration certificate (parameters with u and U at k = 2).
    pub certificate: Option<Certificate>,
}

/// The calibration uploaded, with its gyro part and what its fit gave.
#[derive(Debug, Clone, Serialize)]
pub struct ChosenJson {
    /// The calibration as `download` writes it.
    #[serde(flatten)]
    pub device: CalibrationJson,
    /// G and b, with standard errors.
    pub gyro: GyroJson,
}

/// The simulated sensor's truth (the simulator fills it in: `accelcal::sim::truth`) at the temperature the calibration was made at: a = matrix (m - offset) in
/// g, w = G (w_raw - b), so each compares with `calibration` as it stands.
#[derive(Debug, Clone, Serialize)]
pub struct TruthJson {
    /// The temperature it holds at, as the sensor's TEMP_OUT reads it: the calibration's reference (the
    /// captures' mean temperature), degC.
    pub temp_c: f32,
    /// True M at `temp_c`.
    pub matrix: [[f32; 3]; 3],
    /// True o at `temp_c`, in g.
    pub offset: [f32; 3],
    /// The true gyro correction at `temp_c`: G and the one bias.
    pub gyro: TruthGyroJson,
    /// How the truth moves with the temperature, for the truth at any other (null for the settled
    /// sensor, whose truth is the same at every temperature).
    pub drift: Option<DriftJson>,
}

/// The simulated sensor's drift: at die temperature T (TEMP_OUT minus `reading_offset_c`) and
/// dT = T - `ref_die_c`, o(T) = `ref_offset` + c1 dT + c2 dT^2, M(T) = `ref_matrix` diag(1 + d1 dT + d2 dT^2)^-1,
/// b(T) = `ref_gyro_bias_dps` + e1 dT + e2 dT^2; G does not drift.
#[derive(Debug, Clone, Serialize)]
pub struct DriftJson {
    /// How much TEMP_OUT reads above the die, degC.
    pub reading_offset_c: f32,
    /// The die temperature the polynomials are taken about, degC.
    pub ref_die_c: f32,
    /// True M at `ref_die_c`.
    pub ref_matrix: [[f32; 3]; 3],
    /// True o at `ref_die_c`, in g.
    pub ref_offset: [f32; 3],
    /// True gyro bias at `ref_die_c`, deg/s.
    pub ref_gyro_bias_dps: [f32; 3],
    /// [c1, c2] per axis: g/degC, g/degC^2.
    pub offset_g: [[f32; 3]; 2],
    /// [d1, d2] per axis: 1/degC, 1/degC^2.
    pub scale: [[f32; 3]; 2],
    /// [e1, e2] per axis: deg/s/degC, deg/s/degC^2.
    pub gyro_bias_dps: [[f32; 3]; 2],
}

/// The host fit's statistics.
#[derive(Debug, Clone, Serialize)]
pub struct HostFitSummary {
    /// Model name.
    pub model: &'static str,
    /// Dimensionless cost at the solution.
    pub cost: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Every parameter by name, with its standard errors (as `fit --json` writes them).
    #[serde(serialize_with = "parameters_by_name")]
    pub parameters: Vec<Parameter>,
}

impl CalibrateReport {
    /// The report of a calibration that chose `chosen` (from `host` when the host fitted it).
    pub fn new(
        chosen: &Calibration,
        chip: Option<&Calibration>,
        host: Option<&Fit>,
        truth: Option<TruthJson>,
        verification: Verification,
        captures: usize,
    ) -> Self {
        CalibrateReport {
            calibration: ChosenJson::new(chosen, &GyroOutcome::default()),
            truth,
            true_error_mg: None,
            verification,
            captures,
            chip_fit: chip.map(CalibrationJson::from_device),
            host_fit: host.map(HostFitSummary::new),
            board_seconds: None,
            gyro_check: None,
            target: None,
            certificate: None,
        }
    }

    /// The report with what the gyro fit gave and the verification turn.
    pub fn with_gyro(mut self, outcome: &GyroOutcome, check: Option<TurnCheck>) -> Self {
        self.calibration.gyro = GyroJson::new(&self.calibration.device, outcome);
        self.gyro_check = check;
        self
    }
}

impl ChosenJson {
    fn new(chosen: &Calibration, outcome: &GyroOutcome) -> Self {
        let device = CalibrationJson::from_device(chosen);
        ChosenJson { gyro: GyroJson::new(&device, outcome), device }
    }
}

impl HostFitSummary {
    fn new(fit: &Fit) -> Self {
        HostFitSummary {
            model: fit.model.name(),
            cost: fit.cost,
            iterations: fit.iterations,
            parameters: fit.parameters.clone(),
        }
    }
}
