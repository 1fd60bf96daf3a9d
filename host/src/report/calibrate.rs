//! What a guided calibration reports: the calibration chosen, the simulator's truth when there is
//! one, the verification, and the fits it was chosen from.

use std::collections::BTreeMap;

use firmware::sim::physics::TrueErrors;
use serde::Serialize;
use shared::Calibration;

use super::gyro::{GyroJson, GyroOutcome, TruthGyroJson};
use crate::calibration::CalibrationJson;
use crate::certificate::Certificate;
use crate::fit::Fit;
use crate::procedure::{TargetVerdict, TurnCheck};
use crate::session::Verification;

/// The object `accelcal calibrate --json` prints.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrateReport {
    /// The calibration uploaded and saved.
    pub calibration: ChosenJson,
    /// The simulated sensor's true errors, under the same convention (only with `--sim`).
    pub truth: Option<TruthJson>,
    /// The errors at fresh orientations before and after.
    pub verification: Verification,
    /// Positions captured.
    pub captures: usize,
    /// The chip's own `ortho9` fit of the captures it kept (the calibration itself for `--quick`; absent
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

/// The simulated sensor's true calibration: a = matrix (m - offset), in g.
#[derive(Debug, Clone, Serialize)]
pub struct TruthJson {
    /// True M.
    pub matrix: [[f32; 3]; 3],
    /// True o, in g.
    pub offset: [f32; 3],
    /// True gyro bias, in deg/s.
    pub gyro_bias_dps: [f32; 3],
    /// The true gyro correction at the session's temperature.
    pub gyro: Option<TruthGyroJson>,
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
    /// Standard error of every parameter.
    pub std_errors: BTreeMap<String, Option<f64>>,
}

impl CalibrateReport {
    /// The report of a calibration that chose `chosen` (from `host` when the host fitted it).
    pub fn new(
        chosen: &Calibration,
        chip: Option<&Calibration>,
        host: Option<&Fit>,
        truth: Option<TrueErrors>,
        verification: Verification,
        captures: usize,
    ) -> Self {
        CalibrateReport {
            calibration: ChosenJson::new(chosen, &GyroOutcome::default()),
            truth: truth.map(|t| TruthJson {
                matrix: t.matrix,
                offset: t.offset_g,
                gyro_bias_dps: t.gyro_bias_dps,
                gyro: None,
            }),
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

    /// The report with what the gyro fit gave, the true gyro correction at the session's
    /// temperature (with `--sim`) and the verification turn.
    pub fn with_gyro(mut self, outcome: &GyroOutcome, truth: Option<&TrueErrors>, check: Option<TurnCheck>) -> Self {
        self.calibration.gyro = GyroJson::new(&self.calibration.device, outcome);
        if let (Some(json), Some(truth)) = (self.truth.as_mut(), truth) {
            json.gyro = Some(TruthGyroJson::new(truth));
        }
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
            std_errors: fit.parameters.iter().map(|p| (p.name.clone(), p.std_error)).collect(),
        }
    }
}
