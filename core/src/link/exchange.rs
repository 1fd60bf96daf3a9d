//! The wire, free of I/O: a request becomes a frame to write under its own id, bytes read become the
//! answers they hold, and a wait for an answer is judged by frames at the times the host gives. One
//! request's call ([`Call`]) says what each answer means: an update, the end, or another request's.

use std::collections::VecDeque;
use std::time::Duration;

use shared::protocol::{self, Feed, FrameAccumulator, Request, Response, MAX_FRAME_LEN};

use super::{request_name, LinkError, Listening};
use crate::limits::SILENCE_LIMIT;

/// A connection's frames: the ids given out, the bytes of a frame not yet ended, the answers heard and
/// not yet taken, and the wait for the next one.
pub struct Exchange {
    accumulator: FrameAccumulator,
    heard: VecDeque<Result<(u16, Response), LinkError>>,
    next_id: u16,
    listening: Listening,
}

impl Exchange {
    /// A connection opened at `now` (the host's time since an origin of its own).
    pub fn new(now: Duration) -> Self {
        Exchange {
            accumulator: FrameAccumulator::new(),
            heard: VecDeque::new(),
            next_id: 1,
            listening: Listening::new(now),
        }
    }

    /// The bytes to write for `request`, under the next id, with that id.
    pub fn send(&mut self, request: &Request) -> Result<(u16, Vec<u8>), LinkError> {
        let mut frame = [0u8; MAX_FRAME_LEN];
        // NOTE: every hello is the probe's, whose bytes nothing on a port acts on: it is what accelcal
        // writes to a port it does not know yet (issue 40), and its id may skip ahead for that.
        let encoded = match request {
            Request::Hello { .. } => protocol::probe::inert_hello(self.next_id, &mut frame),
            _ => protocol::encode(self.next_id, request, &mut frame).map(|len| (self.next_id, len)),
        };
        let (id, len) =
            encoded.map_err(|e| LinkError::Encode { request: request_name(request), reason: format!("{e:?}") })?;
        // NOTE: id 0 is reserved for answers to unreadable frames (DESIGN.md, the wire protocol).
        self.next_id = id.checked_add(1).unwrap_or(1);
        Ok((id, frame[..len].to_vec()))
    }

    /// Starts the wait for a request's answers at `now` (it was just sent; a Cancel sent during the
    /// wait does not start it again).
    pub fn listen(&mut self, now: Duration) {
        self.listening = Listening::new(now);
    }

    /// Bytes the port gave, frames or not.
    pub fn received(&mut self, bytes: &[u8]) {
        self.listening.bytes(bytes);
        for &byte in bytes {
            if let Feed::Frame(frame) = self.accumulator.feed(byte) {
                self.heard.extend(heard(frame));
            }
        }
    }

    /// The next answer heard (with the id it answers), taken at `now`; `Ok(None)` while none has come
    /// and the silence limit has not passed; an error once it has (silent, or not an accelcal board).
    pub fn answer(&mut self, now: Duration) -> Result<Option<(u16, Response)>, LinkError> {
        if let Some(answer) = self.heard.pop_front() {
            self.listening.frame(now);
            return answer.map(Some);
        }
        self.listening.check(SILENCE_LIMIT, now).map(|()| None)
    }
}

/// What a whole frame says: an answer, a frame of another protocol version (named as such, never
/// misread), or `None` for a broken frame, which is line noise (the silence limit judges a port that
/// sends only those).
fn heard(frame: &mut [u8]) -> Option<Result<(u16, Response), LinkError>> {
    match protocol::decode::<Response>(frame) {
        Ok(answer) => Some(Ok(answer)),
        Err(protocol::FrameError::Version { got }) => Some(Err(LinkError::version(got))),
        Err(_) => None,
    }
}

/// Whether `bytes` hold a whole frame of accelcal's protocol (of any version): what a board of ours
/// still sends for an earlier run's request (Ctrl-C or a kill ended that run before its last
/// frames were read). A sketch's text holds no 0x00, so never a frame; the first bytes may be the
/// end of a frame begun before the port was opened, which decodes to nothing.
pub fn holds_accelcal_frame(bytes: &[u8]) -> bool {
    let mut accumulator = FrameAccumulator::new();
    bytes.iter().any(|&byte| match accumulator.feed(byte) {
        Feed::Frame(frame) => heard(frame).is_some(),
        _ => false,
    })
}

/// What an answer means to the call waiting for it.
#[derive(Debug)]
pub enum Step {
    /// Another request's answer: wait on.
    Ignore,
    /// Progress or a sample of the work asked for.
    Update(Response),
    /// The call's end: its last answer, or why it failed.
    Done(Result<Response, LinkError>),
}

/// One request's call: how many updates came, whether its work was cancelled and why.
#[derive(Debug, Clone, Copy)]
pub struct Call {
    id: u16,
    updates: usize,
    cancelled: bool,
    interrupted: bool,
}

impl Call {
    /// The call of the request sent under `id`.
    pub fn new(id: u16) -> Self {
        Call { id, updates: 0, cancelled: false, interrupted: false }
    }

    /// The person interrupted (Ctrl-C): whether to send the board a Cancel now (once). The call then
    /// ends as interrupted, whatever the board answers.
    pub fn interrupt(&mut self) -> bool {
        self.cancelled = true;
        !std::mem::replace(&mut self.interrupted, true)
    }

    /// The caller wants no more updates: whether to send the board a Cancel now (once).
    pub fn decline(&mut self) -> bool {
        !std::mem::replace(&mut self.cancelled, true)
    }

    /// What `response`, answering `answer_id`, means to this call.
    pub fn answered(&mut self, answer_id: u16, response: Response) -> Step {
        if answer_id != self.id && answer_id != protocol::frame::UNKNOWN_REQUEST_ID {
            return Step::Ignore;
        }
        match response {
            Response::Progress(_) | Response::Sample(_) => {
                self.updates += 1;
                Step::Update(response)
            }
            _ if self.interrupted => Step::Done(Err(LinkError::Interrupted)),
            Response::Error(error) => Step::Done(Err(error.into())),
            last => Step::Done(Ok(last)),
        }
    }

    /// Why the call failed when the wait for an answer did with `error`: a board that was sending
    /// updates and fell silent stopped answering (it restarted or lost power).
    pub fn failed(&self, error: LinkError) -> LinkError {
        match error {
            LinkError::Silent { .. } if self.updates > 0 => LinkError::StoppedAnswering,
            other => other,
        }
    }
}

#[cfg(test)]
mod tests;
