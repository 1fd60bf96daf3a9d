//! `accelcal calibrate --port P` on a board that prints its own stream: nothing is written to it;
//! its lines are read and kept in a log, the person told which way to turn, how long to hold and
//! how the board rests, and the session kept after every still period (`accelcal report` takes it;
//! `--resume` goes on with it). Once every face and corner is rested and enough fresh orientations
//! are held, or the stream stops, or Ctrl-C, the kept log is fitted and verified with the very code
//! of `accelcal fit LOG`: the still periods at faces and corners fitted, those at fresh
//! orientations its verification.

use accelcal_core::run::ending::Ended;
use std::path::Path;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use super::args::CalibrateArgs;
use super::foreign_session::Kept;
use super::foreign_status::{status, Progress};
use super::terminal::interrupt_on_ctrl_c;
use super::terminal::Terminal;
use crate::error::Error;
use crate::fit::FitOptions;
use crate::limits::LIVE_DETECTION_LINES;
use crate::link::TalkingPort;
use crate::procedure::Feedback;
use crate::report::stream::{self, StreamReport};
use crate::session::Session;
use crate::stream::live::{LiveStream, Silence};
use crate::stream::{read_heard, StreamLog, StreamOptions};

/// How often the person is told where things stand, in seconds.
const STATUS_EVERY: Duration = Duration::from_secs(1);

/// Calibrates from the stream of `talking`.
pub(super) fn calibrate_from_stream(args: &CalibrateArgs, talking: TalkingPort) -> Result<(), Error> {
    let (kept, before) = Kept::begin(args, &talking.path)?;
    if args.lot.is_some() && kept.source.serial.is_none() {
        return Err(Error::StreamLotNeedsSerial { port: talking.path });
    }
    let log = kept.source.log.clone();
    let unwritable = |source| Error::WriteFile { path: log.clone(), source };
    let file = open_log(&log, args.resume.is_some()).map_err(unwritable)?;
    let late = match talking.greeted {
        true => ", begun only after accelcal's hello (a board the port's opening reset, or a slow sketch); accelcal writes nothing more to it",
        false => ": accelcal writes nothing to it",
    };
    eprintln!(
        "{} prints its own stream{late} and keeps what it prints in {} (the session in {})",
        talking.path,
        log.display(),
        kept.json().display()
    );
    let mut live = LiveStream::new(talking, file, &before).map_err(unwritable)?;
    let options = args.stream.options(None);
    let ended = listen_until_done(&mut live, &options, args, &kept)?;
    let data = data_lines(&live, &options);
    live.finish(&data).map_err(unwritable)?;
    eprintln!("{}: fitting the still periods of {}", ended.why, log.display());
    report(args, &kept, &options, ended.complete)
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
fn resume_command(args: &CalibrateArgs, kept: &Kept) -> String {
    let lot = args.lot.as_ref().map(|lot| format!(" --lot {}", lot.display())).unwrap_or_default();
    format!("accelcal calibrate --port {} --resume {}{lot}", kept.source.port, kept.json().display())
}

/// Reads the stream, telling the person where things stand and keeping the session, until every
/// face and corner is rested and enough fresh orientations are held, the stream stops or goes
/// away, or Ctrl-C; why it ended. What was read is kept in any case.
fn listen_until_done(
    live: &mut LiveStream,
    options: &StreamOptions,
    args: &CalibrateArgs,
    kept: &Kept,
) -> Result<Ended, Error> {
    let interrupt = interrupt_on_ctrl_c();
    let mut last_status = Instant::now();
    let mut progress = Progress::new(args);
    let mut warned = false;
    loop {
        if let Err(e) = live.poll(Duration::from_millis(200)) {
            return Ok(Ended::short(format!("the port went away ({e})")));
        }
        if interrupt.load(Ordering::SeqCst) {
            return Ok(Ended::interrupted());
        }
        match live.silence() {
            Silence::Stopped => return Ok(Ended::short("the stream stopped")),
            Silence::Unreadable { seconds, ended } if ended || !warned => {
                warned = true;
                let words = unreadable(seconds, args.device.baud);
                match ended {
                    true => return Ok(Ended::short(words)),
                    false => eprintln!("{words}"),
                }
            }
            Silence::Unreadable { .. } => {}
            Silence::Talking => warned = false,
        }
        if live.lines().len() < LIVE_DETECTION_LINES || last_status.elapsed() < STATUS_EVERY {
            continue;
        }
        last_status = Instant::now();
        if let Some(done) = status(live, options, kept, &mut progress)? {
            return Ok(Ended::complete(done));
        }
    }
}

/// A stream whose bytes hold no line of numbers, in words, with the likely cause and the way out.
fn unreadable(seconds: f64, baud: u32) -> String {
    format!(
        "nothing readable for {seconds:.0} s: bytes come but no line of numbers, most likely the wrong baud rate \
         (read at {baud} Bd): give the sketch's Serial.begin rate as --baud (9600, 38400, 57600, 115200 ...)"
    )
}

/// The indices of the lines that carry accepted samples.
fn data_lines(live: &LiveStream, options: &StreamOptions) -> Vec<usize> {
    let log = read_heard(live.lines(), options);
    log.map(|log| log.samples.iter().map(|s| s.line - 1).collect()).unwrap_or_default()
}

/// The calibration and verification of the kept log, as `fit LOG` gives them; the session saved
/// with them (and before, so that a log too short to fit still leaves its session to resume).
fn report(args: &CalibrateArgs, kept: &Kept, options: &StreamOptions, complete: bool) -> Result<(), Error> {
    let path = &kept.source.log;
    let log = read_log(path, options)?;
    // NOTE: fitted as the session kept fits (`Session::model`), to the rows it keeps: its outcome,
    // which its certificate, export and report take, is the calibration printed here.
    let kept_so_far = kept.save(&log, None)?;
    let report = StreamReport::new(&log, kept_so_far.model(), &FitOptions::default()).map_err(|source| {
        eprintln!("the session is kept in {}: `{}` goes on with it", kept.json().display(), resume_command(args, kept));
        Error::StreamFit { path: path.clone(), source }
    })?;
    let session = kept.save(&log, report.verification.clone())?;
    match complete {
        true => certify(args, kept, &session)?,
        false => eprintln!(
            "no certificate: the session ended before every face and corner was rested and the fresh orientations \
             held; `{}` goes on with it",
            resume_command(args, kept)
        ),
    }
    if args.json {
        println!("{}", stream::json(&report));
        return Ok(());
    }
    print!("{}", stream::text(&report));
    if let Some(verification) = &report.verification {
        println!("{}", verification.against(Some(args.length.target_mg)).line);
    }
    let (session, log) = (kept.json(), path.display());
    println!(
        "kept: the session in {} (`accelcal report {}`), every line in {log} (`accelcal fit {log} --model ortho9` gives this calibration again)",
        session.display(),
        session.display()
    );
    Ok(())
}

/// Issues the stream session's certificate beside it, and adds it to the lot when one was given,
/// unless its verification contradicts the certificate's prediction (said why).
// NOTE: unlike a board's session, a stream's does not fail on a missed --target-mg (the sketch's
// rate and digits bound what it reaches), so only that contradiction withholds the certificate.
fn certify(args: &CalibrateArgs, kept: &Kept, session: &Session) -> Result<(), Error> {
    let mut feedback = Terminal::new(true);
    let Some(certificate) = super::certificate::unless_contradicted(session, &kept.json(), &mut feedback)? else {
        return Ok(());
    };
    let (json, _) = super::certificate::written(&certificate, &kept.json())?;
    feedback.say(&format!("certificate: {}", json.display()));
    if let Some(lot) = &args.lot {
        feedback.say(&super::lot::add_issued(lot, &certificate)?);
    }
    Ok(())
}

fn read_log(path: &Path, options: &StreamOptions) -> Result<StreamLog, Error> {
    let text = crate::stream::read_text(path).map_err(|source| Error::ReadFile { path: path.to_owned(), source })?;
    StreamLog::parse(&text, options).map_err(|source| Error::Stream { path: path.to_owned(), source })
}
