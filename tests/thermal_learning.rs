//! The learning run on the simulated board: interrupted, it keeps the bins it had; where the
//! temperature does not move, it stops at a stall and the span is refused with the reason.

use std::sync::mpsc::Sender;

use accelcal::fit::thermal::{fit_temperature, ThermalReference};
use accelcal::procedure::thermal::{learn, LearnEnd, LearnOptions, ThermalBins, ThermalBoard};
use accelcal::procedure::ProcedureError;
use accelcal::sim::{SimBoard, SimCommand, SimSensor};

/// The simulated board, with the sensor's wire pulled after `captures_left` captures.
struct Board {
    controls: Sender<SimCommand>,
    captures_left: usize,
}

impl ThermalBoard for Board {
    fn place(&mut self, force_g: [f64; 3]) -> Result<(), ProcedureError> {
        if self.captures_left == 0 {
            let _ = self.controls.send(SimCommand::Connect(false));
        }
        self.captures_left = self.captures_left.saturating_sub(1);
        let _ = self.controls.send(SimCommand::Place(force_g.map(|v| v as f32)));
        Ok(())
    }

    fn rest(&mut self, seconds: f64) -> Result<(), ProcedureError> {
        let _ = self.controls.send(SimCommand::Elapse(seconds as f32));
        Ok(())
    }
}

fn options(target_span_c: f64) -> LearnOptions {
    let faces = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]];
    LearnOptions { faces, capture_seconds: 5, rest_seconds: 60.0, target_span_c, max_rounds: 500 }
}

#[test]
fn an_interrupted_learning_run_keeps_its_bins_and_they_still_fit() {
    let (mut connection, board) = SimBoard::in_process(61, SimSensor::Realistic).unwrap();
    let controls = board.controls();
    // Powered on in a 20 degC room, the die warms by 5 degC; the surroundings warm to 35 degC as well.
    controls.send(SimCommand::Ambient { target_c: 35.0, c_per_s: 1.0 / 60.0 }).unwrap();
    let mut sim = Board { controls, captures_left: 60 };
    let mut bins = ThermalBins::default();
    let result = learn(&mut connection, &mut sim, &options(30.0), &mut bins, &mut |_, _| Ok(()));
    assert!(result.is_err(), "the sensor was disconnected mid-run: {result:?}");
    assert!(bins.len() >= 20, "the 60 captures before the interruption are kept: {} bins", bins.len());
    assert!(bins.span_c() >= 10.0, "span {}", bins.span_c());
    let reference = ThermalReference { ref_temp_c: 25.0, matrix: board.truth().matrix };
    let fit = fit_temperature(&reference, &bins.check_span().unwrap().points()).unwrap();
    // The true z offset drift is 1.4 mg/degC at 25 degC: recovered from the kept bins.
    let slope = fit.model.offset_g[0][2];
    assert!((slope - 1.4e-3).abs() < 0.1e-3, "z offset drift {slope} g/degC from the kept bins");
}

#[test]
fn a_board_whose_temperature_stalls_is_refused_with_the_span_it_reached() {
    let (mut connection, board) = SimBoard::in_process(62, SimSensor::Realistic).unwrap();
    let controls = board.controls();
    controls.send(SimCommand::Elapse(3000.0)).unwrap(); // warmed up and settled: nothing moves
    let mut sim = Board { controls, captures_left: usize::MAX };
    let mut bins = ThermalBins::default();
    let end = learn(&mut connection, &mut sim, &options(30.0), &mut bins, &mut |_, _| Ok(())).unwrap();
    assert_eq!(end, LearnEnd::Stalled);
    let error = bins.check_span().unwrap_err().to_string();
    assert!(error.contains("at least 10 degC"), "{error}");
    assert!(error.contains("spanned only 0."), "a settled board moves by a fraction of a degree: {error}");
}
