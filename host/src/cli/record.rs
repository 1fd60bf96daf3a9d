//! `accelcal record`: raw samples at the sensor's rate into a `.npy` recording, written as they
//! arrive; lost samples are counted and fail the command, Ctrl-C ends it with the file readable.

use indicatif::{ProgressBar, ProgressStyle};
use shared::protocol::{SensorConfig, StreamKind};

use super::args::RecordArgs;
use super::terminal::interrupt_on_ctrl_c;
use crate::error::Error;
use crate::link::{Client, LinkError, Port, StreamRequest, Tally};
use crate::recording::{Recorder, RecordingError};
use crate::session::BoardRecord;

/// `accelcal record (--port P | --sim) -o FILE [--seconds S] [--rate HZ]`.
pub(super) fn record(args: &RecordArgs) -> Result<(), Error> {
    // NOTE: before the board is opened: an earlier recording is kept, not cut to this one's length.
    args.replace.check(&args.output, "give another -o")?;
    let mut opened = args.device.open()?;
    let config = SensorConfig { sample_rate_hz: args.rate, ..opened.connection.info.config };
    let client = &mut opened.connection.client;
    let achieved = client.configure(config)?;
    if achieved.sample_rate_hz != args.rate {
        return Err(Error::RateNotAchieved { wanted_hz: args.rate, achieved_hz: achieved.sample_rate_hz });
    }
    client.interrupt_on(interrupt_on_ctrl_c());
    let request =
        StreamRequest { kind: StreamKind::Raw, rate_hz: args.rate, count: args.seconds * u32::from(args.rate) };
    let serial = BoardRecord::of(&opened.connection.info).serial;
    let mut recorder = Recorder::create(&args.output, args.rate, &serial)?;
    let streamed = stream_into(client, request, &mut recorder);
    let written = recorder.finish()?;
    leave_as_found(client, opened.connection.info.config);
    let shown = args.output.display();
    // NOTE: Ctrl-C ends the recording as a pulled cable does: short of what was asked, so not a
    // success; the message names the cause and how many samples the file keeps.
    match streamed {
        Err(Streamed::Link(error)) => Err(Error::RecordingCut { written, path: args.output.clone(), source: error }),
        Err(Streamed::Write(error)) => Err(error.into()),
        Ok(tally) => {
            eprintln!("{written} samples in {shown}");
            Ok(tally.complete()?)
        }
    }
}

/// Sets the board back to the configuration it had before the recording (a board left at 1000 Hz
/// would make the next calibration run there), and says so; a board that cannot be set back is named.
fn leave_as_found<P: Port>(client: &mut Client<P>, found: SensorConfig) {
    // NOTE: after Ctrl-C every request would end as interrupted: the way back must still be sent.
    client.interrupt_on(std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false)));
    match client.configure(found) {
        Ok(_) => eprintln!("the board is back at its {} Hz", found.sample_rate_hz),
        Err(error) => eprintln!(
            "the board could not be set back to {} Hz ({error}): it stays at the recording's rate",
            found.sample_rate_hz
        ),
    }
}

/// Why a stream into a recording ended early.
enum Streamed {
    Link(LinkError),
    Write(RecordingError),
}

/// Streams `request` into `recorder` with a progress bar; what arrived and what was lost.
fn stream_into<P: Port>(
    client: &mut Client<P>,
    request: StreamRequest,
    recorder: &mut Recorder,
) -> Result<Tally, Streamed> {
    let bar = progress_bar(request.count);
    let mut failed = None;
    let streamed = client.stream_while(request, |sample| {
        bar.inc(1);
        failed = recorder.push(sample).err();
        failed.is_none()
    });
    bar.finish_and_clear();
    match (failed, streamed) {
        (Some(error), _) => Err(Streamed::Write(error)),
        (None, streamed) => streamed.map_err(Streamed::Link),
    }
}

fn progress_bar(samples: u32) -> ProgressBar {
    let bar = ProgressBar::new(u64::from(samples));
    let style = ProgressStyle::with_template("recording [{bar:40}] {pos}/{len} samples, {elapsed} (eta {eta})")
        .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}
