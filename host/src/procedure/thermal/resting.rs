//! `accelcal thermal --port`: a person's board rests in one orientation while its temperature
//! changes, around the calibration active on it. The learned bins are kept on disk after every
//! capture and a later run goes on from them; Ctrl-C ends the learning and fits what it learned.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use shared::linalg::Vec3;
use shared::protocol::CalibrationSlot;

use super::error::ThermalError;
use super::learned::{fit_and_activate, learn_bins, learn_options};
use super::{ThermalBins, ThermalBoard};
use crate::calibration::CalibrationJson;
use crate::files::unix_time_s;
use crate::link::{Connection, LinkError};
use crate::procedure::ProcedureError;
use crate::report::thermal::ThermalReport;
use crate::session::BoardRecord;

/// Rest between rounds of captures on a person's board, in seconds.
const REST_S: f64 = 30.0;
/// How often a resting board looks for Ctrl-C, so that it ends at once.
const INTERRUPT_POLL: Duration = Duration::from_millis(100);

/// How a person's thermal run goes.
#[derive(Debug, Clone)]
pub struct RestingOptions {
    /// Stop learning once the temperature has spanned this much, in degC.
    pub target_span_c: f64,
    /// Where the learned bins are kept (and gone on from); by default a file named by the time.
    pub bins: Option<PathBuf>,
    /// The port the board is on, for the command that goes on from the kept bins.
    pub port: String,
    /// No live line (the report is printed as JSON).
    pub quiet: bool,
}

/// A person's board: it rests where it is while real time passes, until Ctrl-C.
struct RestingBoard {
    interrupt: Arc<AtomicBool>,
}

impl ThermalBoard for RestingBoard {
    fn place(&mut self, _force_g: Vec3<f64>) -> Result<(), ProcedureError> {
        Ok(())
    }

    fn rest(&mut self, seconds: f64) -> Result<(), ProcedureError> {
        let until = Instant::now() + Duration::from_secs_f64(seconds);
        while Instant::now() < until {
            if self.interrupt.load(Ordering::SeqCst) {
                return Err(LinkError::Interrupted.into());
            }
            std::thread::sleep(INTERRUPT_POLL);
        }
        Ok(())
    }
}

/// Learns around the calibration active on the board, keeping the bins in `options.bins` (or a
/// file named by the time), and makes the fitted temperature model active; the flag that
/// `on_ctrl_c` gives once the learning begins (set by Ctrl-C) ends the learning.
pub fn learn_at_rest(
    connection: &mut Connection,
    options: &RestingOptions,
    on_ctrl_c: impl FnOnce() -> Arc<AtomicBool>,
) -> Result<ThermalReport, ThermalError> {
    let active = connection.client.calibration(CalibrationSlot::Active)?.ok_or(ProcedureError::NoActiveCalibration)?;
    let serial = BoardRecord::of(&connection.info).serial;
    let path = options
        .bins
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("accelcal-thermal-{}.json", unix_time_s() as u64)));
    let bins = kept_or_new(&path, &serial)?;
    let interrupt = on_ctrl_c();
    connection.client.interrupt_on(interrupt.clone());
    let learn = learn_options(vec![[0.0, 0.0, 1.0]], options.target_span_c, REST_S);
    let mut keep = |bins: &ThermalBins| bins.save(&path, &serial).map_err(ProcedureError::from);
    let mut board = RestingBoard { interrupt: interrupt.clone() };
    let learned = learn_bins(connection, &mut board, &learn, options.quiet, bins, &mut keep);
    // NOTE: Ctrl-C ended the learning; the fit is still made active on the board.
    interrupt.store(false, Ordering::SeqCst);
    let fitted = learned.and_then(|learned| fit_and_activate(connection, &active, &learned, None));
    let (calibration, fit) = fitted.map_err(|source| ThermalError::Stopped {
        source: Box::new(source),
        span_c: ThermalBins::load(&path, &serial).map_or(0.0, |bins| bins.span_c()),
        path: path.clone(),
        device: options.port.clone(),
    })?;
    eprintln!("the learned bins are kept in {}", path.display());
    let (serial, calibration) = (Some(serial), CalibrationJson::from_device(&calibration));
    Ok(ThermalReport { serial, calibration, fit, verification: Vec::new() })
}

/// The bins an earlier run kept at `path` on this board, or none when there is no such file.
fn kept_or_new(path: &Path, serial: &str) -> Result<ThermalBins, ThermalError> {
    if !path.exists() {
        eprintln!("the learned bins are kept in {} as they are learned", path.display());
        return Ok(ThermalBins::default());
    }
    let bins = ThermalBins::load(path, serial)?;
    let (low, high) = bins.range_c().unwrap_or_default();
    eprintln!("going on from the {} bins ({low:.1} to {high:.1} degC) kept in {}", bins.len(), path.display());
    Ok(bins)
}
