//! A board running accelcal's firmware, calibrated from the page: the same run as `accelcal
//! calibrate` (the core's `run::board::calibrate`, adaptive, verified at fresh orientations), its
//! session kept by the page after every capture, and at the end what the command line writes: the
//! report (its JSON as `calibrate --json` prints it), the report page, the certificate.

use accelcal_core::certificate::{self, Certificate};
use accelcal_core::fit::drift;
use accelcal_core::limits::DEFAULT_TARGET_MG;
use accelcal_core::link::{Link, LinkError};
use accelcal_core::report::{self, CalibrateReport, SessionReport};
use accelcal_core::run::board::{self, Around, BoardPlan, Calibrated, RunError};
use accelcal_core::run::stop_rule::{Noise, StopRule};
use accelcal_core::run::Hand;
use accelcal_core::session::{BoardRecord, Session, SessionKind};
use shared::protocol::{CalibrationSlot, DeviceInfo};
use wasm_bindgen::prelude::*;

use super::hand::PromptHand;
use super::page::{PageFeedback, PageUi};
use super::transport::{PagePort, PageTransport};

/// What a finished run gives the page: each a text the page offers as a download.
#[wasm_bindgen(getter_with_clone)]
pub struct BoardResult {
    /// The report as `accelcal calibrate --json` prints it (without the simulated truth).
    pub report_json: String,
    /// The session's report page, as `calibrate --session NAME` writes `NAME.html`.
    pub report_html: String,
    /// The certificate's JSON and page; empty when none was issued (`certificate_withheld` says why).
    pub certificate_json: String,
    pub certificate_html: String,
    pub certificate_withheld: String,
    /// The verified session, as `NAME.json` and `NAME.csv`.
    pub session_json: String,
    pub session_csv: String,
}

/// Calibrates the board behind `port`, telling `ui`; `kept` is a session to resume (its JSON), else
/// a new one begins. Rejects with the cause and the way on.
#[wasm_bindgen]
pub async fn calibrate_board(port: PagePort, ui: PageUi, kept: Option<String>) -> Result<BoardResult, JsError> {
    let transport = PageTransport::new(port);
    let clock = transport.clock();
    let mut link = Link::new(transport);
    link.delimit().await.map_err(to_js)?;
    let info = link.hello().await.map_err(to_js)?;
    info.sensor.map_err(LinkError::from).map_err(to_js)?;
    let session = session_to_run(&mut link, &info, kept, &ui).await?;
    ui.keep(&session.json_text());
    let rule = StopRule { target_mg: DEFAULT_TARGET_MG, noise: Noise::Measured, rate_hz: info.config.sample_rate_hz };
    let resumed = !session.captures.is_empty();
    let plan = BoardPlan { seconds: None, rule: Some(rule), verify_positions: None, wait_limit: None, clock, resumed };
    let hand_ui = ui.clone();
    let mut hands = move || {
        hand_ui.new_hand();
        Box::new(PromptHand { ui: hand_ui.clone() }) as Box<dyn Hand>
    };
    let keep_ui = ui.clone();
    let mut keep = move |session: &Session| {
        keep_ui.keep(&session.json_text());
        Ok(())
    };
    let mut feedback = PageFeedback(&ui);
    let around = Around { feedback: &mut feedback, hands: &mut hands, keep: &mut keep };
    match board::calibrate(&mut link, &info, &plan, around, session).await {
        Ok(Some(calibrated)) => finish(calibrated),
        Ok(None) => Err(JsError::new("not uploaded: the board keeps its previous calibration")),
        Err(error) => Err(JsError::new(&stopped(error))),
    }
}

/// The session kept by the page (`kept`, checked to be this board's), or a new adaptive one with the
/// temperature model the board learned, as `calibrate` begins it.
async fn session_to_run(
    link: &mut Link<PageTransport>,
    info: &DeviceInfo,
    kept: Option<String>,
    ui: &PageUi,
) -> Result<Session, JsError> {
    let board = BoardRecord::of(info);
    if let Some(text) = kept {
        let session = Session::from_json_text(&text)
            .map_err(|e| JsError::new(&format!("the session kept in this browser cannot be read ({e}): start anew")))?;
        return match session.board.as_ref().map(|b| &b.serial) {
            Some(serial) if *serial == board.serial => Ok(session),
            _ => Err(JsError::new(&format!(
                "the session kept in this browser is another board's, not {}'s: connect that board, or start anew",
                board.serial
            ))),
        };
    }
    let learned = drift::learned::kept(link.calibration(CalibrationSlot::Active).await.map_err(to_js)?);
    if let Some(model) = learned.and_then(|c| c.temperature) {
        ui.say(&format!(
            "the board has a learned temperature model (around {:.1} degC): the captures are corrected by it and it \
             stays with the new calibration",
            model.ref_temp_c
        ));
    }
    Ok(Session { board: Some(board), kind: SessionKind::Adaptive, learned, ..Session::default() })
}

/// The verified run's report, report page and certificate, as `calibrate` ends a run.
fn finish(calibrated: Calibrated) -> Result<BoardResult, JsError> {
    let verified = &calibrated.verified;
    let (certificate, withheld) = certify(verified, calibrated.target.missed);
    let fitted = &calibrated.fitted;
    let chip = fitted.chip.as_ref().map(|c| &c.calibration);
    let captures = fitted.session.captures.len();
    let mut report =
        CalibrateReport::new(&fitted.chosen, chip, fitted.host.as_ref(), None, calibrated.verification, captures)
            .with_gyro(&fitted.gyro, calibrated.check);
    report.board_seconds = calibrated.board_seconds;
    report.certificate = certificate.clone();
    report.target = Some(calibrated.target);
    let page = SessionReport::new(verified).map_err(|e| JsError::new(&format!("no report page: {e}")))?;
    Ok(BoardResult {
        report_json: report::json::calibrate_report(&report),
        report_html: report::html::page(&page).map_err(|e| JsError::new(&format!("no report page: {e}")))?,
        certificate_json: certificate.as_ref().map(Certificate::to_json).unwrap_or_default(),
        certificate_html: certificate.as_ref().map(certificate::html::page).unwrap_or_default(),
        certificate_withheld: withheld,
        session_json: verified.json_text(),
        session_csv: verified.csv(),
    })
}

/// The certificate, or why none: the calibration missed its target by more than its noise, its
/// captures cannot be certified, or its verification contradicts the prediction.
fn certify(verified: &Session, missed: bool) -> (Option<Certificate>, String) {
    if missed {
        return (None, "the calibration missed its target by more than its noise (see the verdict)".to_owned());
    }
    match Certificate::issue(verified) {
        Ok(certificate) => match certificate.contradicting_verification() {
            Some(v) => (None, format!(
                "the verification found {:.3} mg (noise floor {:.3} mg), more than the {:.3} mg the certificate predicts",
                v.after_rms_without_noise_mg, v.noise_floor_mg, certificate.predicted.norm_error_mg.expanded
            )),
            None => (Some(certificate), String::new()),
        },
        Err(e) => (None, format!("the captures cannot be certified: {e}")),
    }
}

/// Why the run stopped, and the way on (the session is kept in the browser: Resume goes on).
fn stopped(error: RunError) -> String {
    match error {
        RunError::Stopped(e) => format!("{e}; the captures so far are kept in this browser: press Resume to go on"),
        RunError::NotKept(e) => format!("the session could not be kept: {e}"),
        RunError::AfterUpload(e) => {
            format!("{e}; the calibration was uploaded and saved before the verification stopped: press Resume to verify it")
        }
    }
}

/// A link error as the page shows it.
fn to_js(error: LinkError) -> JsError {
    JsError::new(&error.to_string())
}
