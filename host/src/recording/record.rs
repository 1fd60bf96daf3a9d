//! A board's raw stream recorded: the samples pushed into the recording as they arrive (a failed
//! write ends the stream on the board), and the board set back to the configuration it had.

use shared::protocol::SensorConfig;

use super::{Recorder, RecordingError};
use crate::link::{Client, LinkError, Port, StreamRequest, Tally};

/// Sets the board back to the configuration it had before the recording (a board left at 1000 Hz
/// would make the next calibration run there); what to tell the person, naming a board that
/// cannot be set back.
pub fn leave_as_found<P: Port>(client: &mut Client<P>, found: SensorConfig) -> String {
    // NOTE: after Ctrl-C every request would end as interrupted: the way back must still be sent.
    client.interrupt_on(std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false)));
    match client.configure(found) {
        Ok(_) => format!("the board is back at its {} Hz", found.sample_rate_hz),
        Err(error) => format!(
            "the board could not be set back to {} Hz ({error}): it stays at the recording's rate",
            found.sample_rate_hz
        ),
    }
}

/// Why a stream into a recording ended early.
pub enum Streamed {
    Link(LinkError),
    Write(RecordingError),
}

/// Streams `request` into `recorder`, calling `arrived` after each sample; what arrived and what
/// was lost.
pub fn stream_into<P: Port>(
    client: &mut Client<P>,
    request: StreamRequest,
    recorder: &mut Recorder,
    arrived: &mut dyn FnMut(),
) -> Result<Tally, Streamed> {
    let mut failed = None;
    let streamed = client.stream_while(request, |sample| {
        arrived();
        failed = recorder.push(sample).err();
        failed.is_none()
    });
    match (failed, streamed) {
        (Some(error), _) => Err(Streamed::Write(error)),
        (None, streamed) => streamed.map_err(Streamed::Link),
    }
}
