//! What the end of a stream run decides: the kept log fitted and verified with the very code of
//! `accelcal fit LOG` (the still periods at faces and corners fitted, those at fresh orientations its
//! verification), the session kept before the fit (so that a log too short to fit still leaves its
//! session to resume) and after it with the verification, whether it certifies (only a complete
//! run), and what to print.

use super::{CalibrateOptions, Keep, Keeping};
use crate::fit::FitOptions;
use crate::report::stream::{self, StreamFitError, StreamReport};
use crate::run::ending::Ended;
use crate::run::Feedback;
use crate::session::{Session, SessionError};
use crate::stream::{StreamError, StreamLog};

/// A stream run's end: the session as kept, whether it certifies, and what to print.
#[derive(Debug, Clone)]
pub struct Finished {
    /// The session as kept last, with its verification.
    pub session: Session,
    /// Whether its certificate may be issued: the run was complete.
    pub certifies: bool,
    /// The report as printed: JSON, or the text with where the session and the log are kept.
    pub printed: String,
}

/// Why a stream run's log was not fitted, or its session not kept.
#[derive(Debug, thiserror::Error)]
pub enum StreamRunError {
    /// The session could not be kept.
    #[error(transparent)]
    Kept(#[from] SessionError),
    /// The kept log does not read as a stream.
    #[error(transparent)]
    Log(StreamError),
    /// Its still periods do not fit.
    #[error(transparent)]
    Fit(StreamFitError),
}

/// Fits the kept log `text` of a run that `ended` so, keeping its session through `keep` before
/// and after; says why no certificate when it was cut short.
pub fn finish(
    text: &str,
    ended: &Ended,
    options: &CalibrateOptions,
    keeping: &Keeping,
    feedback: &mut dyn Feedback,
    keep: Keep<'_>,
) -> Result<Finished, StreamRunError> {
    feedback.say(&format!("{}: fitting the still periods of {}", ended.why, keeping.source.log.display()));
    let log = StreamLog::parse(text, &options.stream).map_err(StreamRunError::Log)?;
    // NOTE: fitted as the session kept fits (`Session::model`), to the rows it keeps: its outcome,
    // which its certificate, export and report take, is the calibration printed here.
    let kept_so_far = keeping.session(&log, None);
    // NOTE: kept before the fit, so that a log too short to fit still leaves its session to resume.
    keep(&kept_so_far)?;
    let report = StreamReport::new(&log, kept_so_far.model(), &FitOptions::default()).map_err(|source| {
        let resume = keeping.resume_command(options);
        feedback.say(&format!("the session is kept in {}: `{resume}` goes on with it", keeping.json.display()));
        StreamRunError::Fit(source)
    })?;
    let session = keeping.session(&log, report.verification.clone());
    keep(&session)?;
    if !ended.certifies() {
        feedback.say(&uncertified(keeping, options));
    }
    let printed = printed(&report, keeping, options);
    Ok(Finished { session, certifies: ended.certifies(), printed })
}

/// Why a run cut short gets no certificate, and the command that goes on with it.
fn uncertified(keeping: &Keeping, options: &CalibrateOptions) -> String {
    format!(
        "no certificate: the session ended before every face and corner was rested and the fresh orientations \
         held; `{}` goes on with it",
        keeping.resume_command(options)
    )
}

/// The report as printed: JSON, or the text with the verification against the target and where the
/// session and the log are kept.
fn printed(report: &StreamReport, keeping: &Keeping, options: &CalibrateOptions) -> String {
    if options.json {
        return format!("{}\n", stream::json(report));
    }
    let mut out = stream::text(report);
    if let Some(verification) = &report.verification {
        out += &format!("{}\n", verification.against(Some(options.target_mg)).line);
    }
    let (session, log) = (keeping.json.display(), keeping.source.log.display());
    out + &format!(
        "kept: the session in {session} (`accelcal report {session}`), every line in {log} (`accelcal fit {log} --model ortho9` gives this calibration again)\n"
    )
}
