//! What a request has heard so far: silence and progress are judged by accelcal frames, never by
//! bytes, so a port that chatters (a GPS printing NMEA, another board, noise) cannot hold a request
//! open for ever.

use std::time::{Duration, Instant};

use super::error::LinkError;

/// Bytes of foreign traffic kept to show the user what the port sent.
const EVIDENCE_LEN: usize = 48;

/// The state of one request's wait for frames.
pub(super) struct Listening {
    last_frame: Instant,
    foreign: Vec<u8>,
    foreign_bytes: usize,
}

impl Listening {
    /// Starts listening now (the request was just sent).
    pub(super) fn new() -> Self {
        Listening { last_frame: Instant::now(), foreign: Vec::new(), foreign_bytes: 0 }
    }

    /// Bytes read from the port, frames or not: kept until a frame shows they belonged to one.
    pub(super) fn bytes(&mut self, bytes: &[u8]) {
        self.foreign_bytes += bytes.len();
        let room = EVIDENCE_LEN.saturating_sub(self.foreign.len());
        self.foreign.extend_from_slice(&bytes[..bytes.len().min(room)]);
    }

    /// A valid accelcal frame arrived: the device is there, and what came before was its own.
    pub(super) fn frame(&mut self) {
        self.last_frame = Instant::now();
        self.foreign.clear();
        self.foreign_bytes = 0;
    }

    /// `Err` once `limit` has passed without a frame: silent, or talking but not an accelcal board.
    pub(super) fn check(&self, limit: Duration) -> Result<(), LinkError> {
        if self.last_frame.elapsed() <= limit {
            return Ok(());
        }
        let seconds = limit.as_secs_f64();
        if self.foreign_bytes == 0 {
            return Err(LinkError::Silent { seconds, at_open: false });
        }
        Err(LinkError::NotAccelcal { seconds, seen: describe(&self.foreign, self.foreign_bytes) })
    }
}

/// What the port sent, in words: a quote of its text, or a count of its bytes.
pub(super) fn describe(evidence: &[u8], total: usize) -> String {
    let printable = evidence.iter().filter(|b| b.is_ascii_graphic() || b.is_ascii_whitespace()).count();
    // NOTE: a few stray bytes do not make text binary; line noise is mostly unprintable.
    if printable * 10 >= evidence.len() * 9 {
        let text = String::from_utf8_lossy(evidence);
        let first_line = text.split(['\r', '\n']).find(|l| !l.trim().is_empty()).unwrap_or("");
        format!("text such as {first_line:?}")
    } else {
        format!("{total} bytes that are not accelcal frames")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_quoted_and_binary_is_counted() {
        assert_eq!(describe(b"\r\n$GPGGA,1235\r\n$GPRMC", 99), "text such as \"$GPGGA,1235\"");
        assert_eq!(describe(&[0x81, 0xff, 0x02, 0x10, 0x7f], 700), "700 bytes that are not accelcal frames");
    }

    #[test]
    fn bytes_without_a_frame_are_not_accelcal_and_a_frame_clears_them() {
        let mut listening = Listening::new();
        listening.bytes(b"$GPGGA,1\r\n");
        let error = listening.check(Duration::ZERO).unwrap_err();
        assert!(matches!(&error, LinkError::NotAccelcal { seen, .. } if seen == "text such as \"$GPGGA,1\""));
        listening.frame();
        std::thread::sleep(Duration::from_millis(2));
        assert!(matches!(listening.check(Duration::ZERO), Err(LinkError::Silent { .. })));
        assert!(listening.check(Duration::from_secs(60)).is_ok());
    }
}
