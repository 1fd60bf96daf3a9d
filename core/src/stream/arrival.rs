//! A live stream's lines as they arrive: bytes fed with the time they came become lines, each with its
//! arrival; the silence of the stream judged from those times; the rate of lines by their arrival.
//! The host reads the port and the clock (`accelcal::stream::live`); this decides.

use crate::limits::{STREAM_QUIET_S, STREAM_UNREADABLE_S};

/// Lines assembled from the bytes a stream sent, each with its arrival.
#[derive(Debug, Clone, Default)]
pub struct Arrivals {
    /// The bytes of a line not yet ended.
    pending: Vec<u8>,
    /// Every complete line so far, with its arrival in seconds since listening began.
    pub lines: Vec<(String, f64)>,
    /// When the last bytes came, in seconds since listening began.
    last_bytes_s: f64,
    /// When the last line holding numbers came, in seconds since listening began.
    last_readable_s: f64,
    /// The last byte ended a line with a carriage return: a newline after it ends no other line.
    after_cr: bool,
}

impl Arrivals {
    /// Starts from the lines `before` (a resumed session's log) and the bytes `heard` while the port
    /// was listened to, all at arrival 0 (unknown: kept out of the rate).
    pub fn begun(before: &str, heard: &[u8]) -> Self {
        let lines = super::split_lines(before).map(|line| (line.to_owned(), 0.0)).collect();
        let mut arrivals = Arrivals { lines, ..Default::default() };
        arrivals.take(heard, 0.0);
        arrivals
    }

    /// Takes `bytes` that came at `now_s` (seconds since listening began); the number of new lines.
    pub fn take(&mut self, bytes: &[u8], now_s: f64) -> usize {
        let before = self.lines.len();
        if !bytes.is_empty() {
            self.last_bytes_s = now_s;
        }
        for &byte in bytes {
            // NOTE: a line ends at CR, LF or CR LF, as `split_lines` splits a saved log.
            let (ends, after_cr) = match byte {
                b'\r' => (true, true),
                b'\n' => (!self.after_cr, false),
                _ => (false, false),
            };
            if ends {
                self.end_line(now_s);
            } else if !matches!(byte, b'\r' | b'\n') {
                self.pending.push(byte);
            }
            self.after_cr = after_cr;
        }
        self.lines.len() - before
    }

    fn end_line(&mut self, now_s: f64) {
        let text = super::text_of(&self.pending);
        if holds_numbers(&text) {
            self.last_readable_s = now_s;
        }
        self.lines.push((text, now_s));
        self.pending.clear();
    }

    /// What the stream's silence says at `now_s`.
    pub fn silence(&self, now_s: f64) -> Silence {
        Silence::judge(now_s - self.last_bytes_s, now_s - self.last_readable_s)
    }

    /// Whether bytes of a line not yet ended are waiting.
    pub fn has_pending(&self) -> bool {
        !self.pending.is_empty()
    }

    /// The rate of the lines `data` (indices) by their arrival, when known.
    pub fn rate_hz(&self, data: &[usize]) -> Option<f64> {
        let times: Vec<f64> = data.iter().map(|&i| self.lines[i].1).collect();
        arrival_hz(&times)
    }
}

/// What a live stream's silence says.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Silence {
    /// Lines of numbers keep coming (or not yet long without).
    Talking,
    /// Bytes still come but no line of numbers, for this many seconds: the wrong baud rate, most likely.
    Unreadable { seconds: f64, ended: bool },
    /// Nothing at all has come for [`STREAM_QUIET_S`]: the stream stopped.
    Stopped,
}

impl Silence {
    /// The silence of a stream whose last bytes came `quiet_s` ago and last line of numbers
    /// `unreadable_s` ago.
    pub fn judge(quiet_s: f64, unreadable_s: f64) -> Silence {
        match () {
            _ if quiet_s > STREAM_QUIET_S => Silence::Stopped,
            // NOTE: bytes in the later half of the stretch: a stream that stopped mid-line is not garbled.
            _ if unreadable_s > STREAM_UNREADABLE_S && quiet_s < unreadable_s / 2.0 => {
                Silence::Unreadable { seconds: unreadable_s, ended: unreadable_s > STREAM_QUIET_S }
            }
            _ => Silence::Talking,
        }
    }
}

/// Whether a line holds numbers as some dialect's samples do (its dialect aside): readable.
pub fn holds_numbers(text: &str) -> bool {
    !text.contains(char::REPLACEMENT_CHARACTER) && super::line::fields(text).is_ok()
}

/// The rate of lines that arrived at `times` (seconds; 0 for those heard while listening): their
/// count over their span, since a port hands over lines in bursts.
pub fn arrival_hz(times: &[f64]) -> Option<f64> {
    let timed: Vec<f64> = times.iter().copied().filter(|&t| t > 0.0).collect();
    match (timed.first(), timed.last()) {
        (Some(first), Some(last)) if last > first => Some((timed.len() - 1) as f64 / (last - first)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::text_of;

    #[test]
    fn wrong_baud_bytes_are_unreadable_and_named_before_the_stream_counts_as_stopped() {
        // NOTE: 115200 Bd read at 38400: mostly high bytes, a few newlines (usertrial's junkfeed).
        let garbled = text_of(&[0xf8, 0x80, 0x66, 0xfe, 0x00, 0x1c, 0x78, 0x98, 0x9e, 0x06, 0xe0]);
        assert!(!holds_numbers(&garbled), "{garbled:?}");
        assert!(!holds_numbers("ets Jun  8 2016 00:22:57"));
        assert!(holds_numbers("90112,12449,-11115,-895,-152,96,53"));
        assert_eq!(Silence::judge(0.1, 2.0), Silence::Talking);
        assert_eq!(Silence::judge(0.1, 6.0), Silence::Unreadable { seconds: 6.0, ended: false });
        assert_eq!(Silence::judge(0.1, 10.5), Silence::Unreadable { seconds: 10.5, ended: true });
        assert_eq!(Silence::judge(6.0, 6.0), Silence::Talking, "a stream that stopped is not garbled");
        assert_eq!(Silence::judge(10.5, 10.5), Silence::Stopped);
    }
}
