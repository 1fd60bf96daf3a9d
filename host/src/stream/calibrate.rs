//! Calibrating from a board that prints its own stream: nothing is written to it; its lines are
//! read and kept in a log, the person told which way to turn, how long to hold and how the board
//! rests, and the session kept after every still period (`accelcal report` takes it; `--resume`
//! goes on with it). Once every face and corner is rested and enough fresh orientations are held,
//! or the stream stops, or Ctrl-C, the kept log is fitted and verified with the very code of
//! `accelcal fit LOG`: the still periods at faces and corners fitted, those at fresh orientations
//! its verification.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use super::listen::Watch;
use super::live::LiveStream;
use super::session::Kept;
use super::status::Progress;
use super::{read_heard, StreamLog, StreamOptions};
use crate::error::Error;
use crate::fit::FitOptions;
use crate::link::TalkingPort;
use crate::procedure::stop_rule::{Noise, StopRule};
use crate::procedure::Feedback;
use crate::report::stream::{self, StreamReport};
use crate::session::Session;

/// What a calibration from a board's own stream is asked.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrateOptions {
    /// How the stream's lines are read (units, rate).
    pub stream: StreamOptions,
    /// The port's baud rate, named when nothing readable comes.
    pub baud: u32,
    /// The | |a| - g | wanted, in mg: each position is held until its mean is known to what it needs.
    pub target_mg: f64,
    /// Fresh orientations to hold to verify the fit.
    pub verify: usize,
    /// The lot the certificate goes into, when one is given.
    pub lot: Option<PathBuf>,
    /// The report as JSON rather than text.
    pub json: bool,
}

/// What is done with a complete session's certificate: issued beside the session and added to the
/// lot, or withheld, said why.
pub type Certify<'a> = &'a mut dyn FnMut(&Session, &mut dyn Feedback) -> Result<(), Error>;

/// Calibrates from the stream of `talking`, keeping the session in `kept`, until done or Ctrl-C
/// (`interrupt`); what to print: the report and where the session and the log are kept.
pub fn calibrate(
    talking: TalkingPort,
    kept: &Kept,
    options: &CalibrateOptions,
    interrupt: &AtomicBool,
    feedback: &mut dyn Feedback,
    certify: Certify,
) -> Result<String, Error> {
    if options.lot.is_some() && kept.source.serial.is_none() {
        return Err(Error::StreamLotNeedsSerial { port: talking.path });
    }
    let log = kept.source.log.clone();
    let unwritable = |source| Error::WriteFile { path: log.clone(), source };
    let file = open_log(&log, kept.resumed).map_err(unwritable)?;
    let late = match talking.greeted {
        true => ", begun only after accelcal's hello (a board the port's opening reset, or a slow sketch); accelcal writes nothing more to it",
        false => ": accelcal writes nothing to it",
    };
    feedback.say(&format!(
        "{} prints its own stream{late} and keeps what it prints in {} (the session in {})",
        talking.path,
        log.display(),
        kept.json().display()
    ));
    let mut live = LiveStream::new(talking, file, &kept.logged).map_err(unwritable)?;
    let watch = Watch { stream: &options.stream, baud: options.baud, progress: progress(options) };
    let ended = super::listen::until_done(&mut live, watch, kept, interrupt, feedback)?;
    let data = data_lines(&live, &options.stream);
    live.finish(&data).map_err(unwritable)?;
    feedback.say(&format!("{}: fitting the still periods of {}", ended.why, log.display()));
    report(kept, options, ended.complete, feedback, certify)
}

/// Nothing kept yet; each position held until its mean is known to what the target needs.
fn progress(options: &CalibrateOptions) -> Progress {
    let rule = StopRule { target_mg: options.target_mg, noise: Noise::Measured, rate_hz: 0 };
    Progress::new(rule.mean_std_g(), options.verify)
}

/// The session's log: a resumed session's goes on, a new one's starts empty (one already there was
/// refused unless --overwrite).
fn open_log(log: &Path, resumed: bool) -> std::io::Result<std::fs::File> {
    let mut options = std::fs::OpenOptions::new();
    match resumed {
        true => options.create(true).append(true),
        false => options.create(true).write(true).truncate(true),
    };
    options.open(log)
}

/// The command that goes on with the session, with the lot it was to go into.
fn resume_command(kept: &Kept, options: &CalibrateOptions) -> String {
    let lot = options.lot.as_ref().map(|lot| format!(" --lot {}", lot.display())).unwrap_or_default();
    format!("accelcal calibrate --port {} --resume {}{lot}", kept.source.port, kept.json().display())
}

/// The indices of the lines that carry accepted samples.
fn data_lines(live: &LiveStream, options: &StreamOptions) -> Vec<usize> {
    let log = read_heard(live.lines(), options);
    log.map(|log| log.samples.iter().map(|s| s.line - 1).collect()).unwrap_or_default()
}

/// The calibration and verification of the kept log, as `fit LOG` gives them, to print; the
/// session saved with them (and before, so that a log too short to fit still leaves its session to
/// resume), and certified when `complete`.
fn report(
    kept: &Kept,
    options: &CalibrateOptions,
    complete: bool,
    feedback: &mut dyn Feedback,
    certify: Certify,
) -> Result<String, Error> {
    let path = &kept.source.log;
    let log = read_log(path, &options.stream)?;
    // NOTE: fitted as the session kept fits (`Session::model`), to the rows it keeps: its outcome,
    // which its certificate, export and report take, is the calibration printed here.
    let kept_so_far = kept.save(&log, None)?;
    let report = StreamReport::new(&log, kept_so_far.model(), &FitOptions::default()).map_err(|source| {
        let resume = resume_command(kept, options);
        feedback.say(&format!("the session is kept in {}: `{resume}` goes on with it", kept.json().display()));
        Error::StreamFit { path: path.clone(), source }
    })?;
    let session = kept.save(&log, report.verification.clone())?;
    match complete {
        true => certify(&session, feedback)?,
        false => feedback.say(&format!(
            "no certificate: the session ended before every face and corner was rested and the fresh orientations \
             held; `{}` goes on with it",
            resume_command(kept, options)
        )),
    }
    Ok(printed(&report, kept, options))
}

/// The report as printed: JSON, or the text with the verification against the target and where the
/// session and the log are kept.
fn printed(report: &StreamReport, kept: &Kept, options: &CalibrateOptions) -> String {
    if options.json {
        return format!("{}\n", stream::json(report));
    }
    let mut out = stream::text(report);
    if let Some(verification) = &report.verification {
        out += &format!("{}\n", verification.against(Some(options.target_mg)).line);
    }
    let (session, log) = (kept.json(), kept.source.log.display());
    out + &format!(
        "kept: the session in {} (`accelcal report {}`), every line in {log} (`accelcal fit {log} --model ortho9` gives this calibration again)\n",
        session.display(),
        session.display()
    )
}

fn read_log(path: &Path, options: &StreamOptions) -> Result<StreamLog, Error> {
    let text = super::read_text(path).map_err(|source| Error::ReadFile { path: path.to_owned(), source })?;
    StreamLog::parse(&text, options).map_err(|source| Error::Stream { path: path.to_owned(), source })
}
