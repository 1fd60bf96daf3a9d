//! What a request has heard so far: silence and progress are judged by accelcal frames, never by
//! bytes, so a port that chatters (a GPS printing NMEA, another board, noise) cannot hold a request
//! open for ever. The host says when each thing arrived (time since an origin of its choosing).

use std::time::Duration;

use super::error::LinkError;

/// Bytes of foreign traffic kept to show the user what the port sent.
const EVIDENCE_LEN: usize = 48;

/// The state of one request's wait for frames.
pub struct Listening {
    last_frame: Duration,
    foreign: Vec<u8>,
    foreign_bytes: usize,
}

impl Listening {
    /// Starts listening at `now` (the request was just sent).
    pub fn new(now: Duration) -> Self {
        Listening { last_frame: now, foreign: Vec::new(), foreign_bytes: 0 }
    }

    /// Bytes read from the port, frames or not: kept until a frame shows they belonged to one.
    pub fn bytes(&mut self, bytes: &[u8]) {
        self.foreign_bytes += bytes.len();
        let room = EVIDENCE_LEN.saturating_sub(self.foreign.len());
        self.foreign.extend_from_slice(&bytes[..bytes.len().min(room)]);
    }

    /// A valid accelcal frame arrived at `now`: the device is there, and what came before was its own.
    pub fn frame(&mut self, now: Duration) {
        self.last_frame = now;
        self.foreign.clear();
        self.foreign_bytes = 0;
    }

    /// `Err` once `limit` has passed at `now` without a frame: silent, or talking but not an accelcal
    /// board.
    pub fn check(&self, limit: Duration, now: Duration) -> Result<(), LinkError> {
        if now.saturating_sub(self.last_frame) <= limit {
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
pub fn describe(evidence: &[u8], total: usize) -> String {
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
        let (start, limit) = (Duration::from_secs(100), Duration::from_secs(2));
        let mut listening = Listening::new(start);
        listening.bytes(b"$GPGGA,1\r\n");
        assert!(listening.check(limit, start + limit).is_ok(), "not yet past the limit");
        let error = listening.check(limit, start + limit + Duration::from_millis(1)).unwrap_err();
        assert!(matches!(&error, LinkError::NotAccelcal { seen, .. } if seen == "text such as \"$GPGGA,1\""));
        listening.frame(start + Duration::from_secs(3));
        let later = start + Duration::from_secs(5) + Duration::from_millis(1);
        assert!(matches!(listening.check(limit, later), Err(LinkError::Silent { .. })));
        assert!(listening.check(limit, start + Duration::from_secs(5)).is_ok());
    }
}
