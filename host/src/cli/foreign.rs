//! `accelcal calibrate --port P` on a board that prints its own stream: the arguments turned into
//! the session it keeps and the options of [`crate::stream::calibrate`], which runs it.

use super::args::CalibrateArgs;
use super::length::ADAPTIVE_VERIFY_POSITIONS;
use crate::error::Error;
use crate::link::TalkingPort;
use crate::procedure::Feedback;
use crate::session::{default_name, first_free, hold, holder, new_session_path, stem_file, stem_of, Session};
use crate::stream::calibrate::{self, CalibrateOptions};
use crate::stream::session::Kept;
use crate::terminal::{interrupt_on_ctrl_c, Terminal};

/// Calibrates from the stream of `talking`.
pub(super) fn calibrate_from_stream(args: &CalibrateArgs, talking: TalkingPort) -> Result<(), Error> {
    let kept = kept(args, &talking.path)?;
    let options = CalibrateOptions {
        stream: args.stream.options(None),
        baud: args.device.baud,
        target_mg: args.length.target_mg(),
        verify: usize::from(args.verify.unwrap_or(ADAPTIVE_VERIFY_POSITIONS)),
        lot: args.lot.clone(),
        json: args.json,
    };
    // NOTE: unlike a board's session, a stream's does not fail on a missed --target-mg (the sketch's
    // rate and digits bound what it reaches), so only a contradiction withholds the certificate.
    let mut certify = |session: &Session, feedback: &mut dyn Feedback| {
        crate::ended::issue_beside(session, &kept.json(), args.lot.as_deref(), feedback)
    };
    let interrupt = interrupt_on_ctrl_c();
    print!("{}", calibrate::calibrate(talking, &kept, &options, &interrupt, &mut Terminal::new(true), &mut certify)?);
    Ok(())
}

/// The session the arguments name, held by this run: the one `--resume` names, or a new one
/// (`--session`, or a default name), its log `--stream-log` or beside it.
fn kept(args: &CalibrateArgs, port: &str) -> Result<Kept, Error> {
    let serial = args.serial.as_deref();
    let holder = holder(&serial.map_or_else(|| format!("port {port}"), |serial| format!("board {serial}")));
    if let Some(path) = &args.resume {
        return Kept::resume(path, hold(&stem_of(path), &holder)?, port, serial);
    }
    let (stem, held) = match new_session_path(args.session.as_deref(), args.device.port.is_some(), serial, &holder)? {
        Some(new) => new,
        None => first_free(&default_name(serial), &holder)?,
    };
    let log = args.stream_log.clone().unwrap_or_else(|| stem_file(&stem, "log"));
    // NOTE: a new session's log holds its lines alone: appended to another's, it would be fitted
    // with that session's lines too.
    args.replace.check(&log, "give another --stream-log, or go on with the session it keeps with --resume")?;
    Ok(Kept::new(stem, held, port, log, args.serial.clone()))
}
