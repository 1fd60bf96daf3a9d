//! `accelcal record`: raw samples at the sensor's rate into a `.npy` recording, written as they
//! arrive; lost samples are counted and fail the command, Ctrl-C ends it with the file readable.

use shared::protocol::{SensorConfig, StreamKind};

use super::args::RecordArgs;
use crate::error::Error;
use crate::link::StreamRequest;
use crate::recording::record::{leave_as_found, stream_into, Streamed};
use crate::recording::Recorder;
use crate::session::BoardRecord;
use crate::terminal::interrupt_on_ctrl_c;

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
    let bar = crate::terminal::counting(
        "recording [{bar:40}] {pos}/{len} samples, {elapsed} (eta {eta})",
        u64::from(request.count),
    );
    let streamed = stream_into(client, request, &mut recorder, &mut || bar.inc(1));
    bar.finish_and_clear();
    let written = recorder.finish()?;
    eprintln!("{}", leave_as_found(client, opened.connection.info.config));
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
