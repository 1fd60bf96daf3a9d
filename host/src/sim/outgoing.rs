//! Frames the simulated board has written but the port has not yet taken. A port that would block
//! (the host reads slowly) holds the board up, as USB does the real one: no frame is ever dropped
//! for it. Only a `lose` command drops frames, to inject a flaky link.

use std::io::ErrorKind;
use std::time::Duration;

use shared::protocol::{decode, Response};

use super::Port;

/// Bytes waiting for the port, and the streamed samples the link is told to lose.
#[derive(Default)]
pub(super) struct Outgoing {
    pending: Vec<u8>,
    samples_to_lose: u32,
}

impl Outgoing {
    /// Whether everything written so far has been taken by the port.
    pub(super) fn is_empty(&self) -> bool {
        self.pending.is_empty()
    }

    /// The link will lose the next `count` streamed samples.
    pub(super) fn lose_samples(&mut self, count: u32) {
        self.samples_to_lose = self.samples_to_lose.saturating_add(count);
    }

    /// Queues one encoded frame (delimiter included), unless the link is to lose it.
    pub(super) fn queue(&mut self, frame: &[u8]) {
        if self.samples_to_lose > 0 && is_sample(frame) {
            self.samples_to_lose -= 1;
            return;
        }
        self.pending.extend_from_slice(frame);
    }

    /// Writes what the port takes without waiting; `false` when the host end is gone.
    pub(super) fn write<P: Port>(&mut self, port: &mut P) -> bool {
        let _ = port.set_read_timeout(Duration::ZERO);
        while !self.pending.is_empty() {
            match port.write(&self.pending) {
                Ok(0) => break,
                Ok(n) => drop(self.pending.drain(..n)),
                Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::WouldBlock | ErrorKind::Interrupted) => {
                    break;
                }
                Err(e) if e.kind() == ErrorKind::BrokenPipe => return false,
                // NOTE: a pty with no one on the other side: what was written is gone with the reader.
                Err(_) => self.pending.clear(),
            }
        }
        let _ = port.flush();
        true
    }
}

/// Whether an encoded frame carries a streamed sample.
fn is_sample(frame: &[u8]) -> bool {
    let mut body = frame.strip_suffix(&[0]).unwrap_or(frame).to_vec();
    matches!(decode::<Response>(&mut body), Ok((_, Response::Sample(_))))
}
