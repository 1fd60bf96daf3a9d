//! The emulated chip's time for its own fits: the bridge reads the frames passing through it, and
//! when the host asks for a fit (`FitOrtho9`, `FitSixPosition`) it says on stderr how long the
//! Cortex-M0+ took, in emulated time and in the cycles it executed (asleep excluded).

use shared::protocol::{decode, Feed, FrameAccumulator, Request, Response};

/// A fit the host asked for, and where the chip was when the request reached it.
struct Asked {
    request_id: u16,
    name: &'static str,
    at_ns: u64,
    cycles: u64,
}

/// Watches both directions for the chip's fits.
#[derive(Default)]
pub(super) struct FitTimer {
    from_host: FrameAccumulator,
    from_device: FrameAccumulator,
    asked: Option<Asked>,
    answered: Option<String>,
}

impl FitTimer {
    /// Bytes the host wrote, delivered to the chip at the poll at `at_ns` after `cycles`.
    pub(super) fn host_wrote(&mut self, bytes: &[u8], at_ns: u64, cycles: u64) {
        for &byte in bytes {
            if let Feed::Frame(frame) = self.from_host.feed(byte) {
                let name = match decode::<Request>(frame) {
                    Ok((id, Request::FitOrtho9)) => Some((id, "FitOrtho9")),
                    Ok((id, Request::FitSixPosition)) => Some((id, "FitSixPosition")),
                    _ => None,
                };
                self.asked = name.map(|(request_id, name)| Asked { request_id, name, at_ns, cycles });
            }
        }
    }

    /// Bytes the device sent (between two polls).
    pub(super) fn device_sent(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            if let Feed::Frame(frame) = self.from_device.feed(byte) {
                if let (Ok((id, response)), Some(asked)) = (decode::<Response>(frame), &self.asked) {
                    if id == asked.request_id {
                        self.answered = Some(outcome(&response));
                    }
                }
            }
        }
    }

    /// At a poll: what to say of how long an answered fit took (to the nearest poll, 1 ms).
    pub(super) fn poll(&mut self, at_ns: u64, cycles: u64) -> Option<String> {
        let (outcome, asked) = (self.answered.take()?, self.asked.take()?);
        let executed = cycles - asked.cycles;
        Some(format!(
            "emulated Pico: {} ({outcome}) answered within {:.0} ms of the chip's time; the Cortex-M0+ executed {executed} cycles ({:.0} ms at 125 MHz)",
            asked.name,
            (at_ns - asked.at_ns) as f64 * 1e-6,
            executed as f64 / 125e3,
        ))
    }
}

fn outcome(response: &Response) -> String {
    match response {
        Response::Ortho9Fitted { captures, iterations, .. } => format!("{captures} captures, {iterations} iterations"),
        Response::Error(error) => format!("refused: {error:?}"),
        _ => "fitted".into(),
    }
}

#[cfg(test)]
mod tests {
    use shared::calibration::{AccelRange, Calibration};
    use shared::protocol::{encode, MAX_FRAME_LEN};

    use super::*;

    fn frame<T: serde::Serialize>(id: u16, message: &T) -> Vec<u8> {
        let mut out = [0u8; MAX_FRAME_LEN];
        let len = encode(id, message, &mut out).unwrap();
        out[..len].to_vec()
    }

    #[test]
    fn a_fit_the_host_asked_for_is_timed_from_its_request_to_its_answer() {
        let mut timer = FitTimer::default();
        timer.host_wrote(&frame(7, &Request::FitOrtho9), 1_000_000, 100);
        assert_eq!(timer.poll(2_000_000, 125_100), None, "not answered yet");
        let answer =
            Response::Ortho9Fitted { calibration: Calibration::identity(AccelRange::G2), captures: 10, iterations: 4 };
        timer.device_sent(&frame(6, &Response::Done));
        timer.device_sent(&frame(7, &answer));
        let said = timer.poll(3_000_000, 250_100).unwrap();
        assert!(said.contains("FitOrtho9 (10 captures, 4 iterations) answered within 2 ms"), "{said}");
        assert!(said.contains("executed 250000 cycles (2 ms at 125 MHz)"), "{said}");
        assert_eq!(timer.poll(4_000_000, 250_200), None, "said once");
    }
}
