//! The hello the host writes to a port it does not know yet: a frame with no byte that a REPL or a
//! bootloader on the other end acts on (issue 40: the old hello held 0x03 and 0x01, which stop a
//! silent MicroPython program and put its REPL into raw mode).
//!
//! The frame is the ordinary hello (the board reads it as any other) with text after the message:
//! postcard reads the message and leaves what follows, and the CRC covers it all. The text makes the
//! frame long enough that COBS's one code byte is printable, and its last letter is chosen so that
//! the CRC's four bytes are safe too.

use super::{encode, FrameError, Request, MAX_FRAME_LEN, PROTOCOL_VERSION};

/// Bytes something on a serial port may act on, which the probe's hello never holds:
/// - 0x01-0x05: MicroPython's and CircuitPython's REPL control characters (raw REPL, normal REPL,
///   interrupt the running program, soft reset, paste mode; MicroPython's REPL documentation);
/// - 0x0A, 0x0D: the end of a line, which runs what a REPL was given;
/// - 0x20: STK500's end of command (Atmel AVR061): an Arduino bootloader answers a command only
///   when this follows it, and otherwise starts the sketch;
/// - 0xC0: SLIP's frame end (RFC 1055), which frames the ESP ROM loader's commands;
/// - 0x00 inside the frame (only its delimiter is 0x00; a zero inside would split COBS's code byte
///   into small ones).
pub const ACTED_ON: [u8; 9] = [0x01, 0x02, 0x03, 0x04, 0x05, 0x0A, 0x0D, 0x20, 0xC0];

/// Text after the hello's message: what a person watching the port sees, and the length that makes
/// COBS's code byte printable (a frame with no zero has one code byte, its length plus one).
const TEXT: &[u8; 28] = b"accelcal.hello.from.the.host";

/// Letters tried last in the text until the CRC holds no byte that is acted on.
const LAST_LETTERS: core::ops::RangeInclusive<u8> = b'A'..=b'Z';

/// Whether a byte of the frame (before its delimiter) is one nothing on the port acts on.
pub fn is_inert(byte: u8) -> bool {
    byte != 0 && !ACTED_ON.contains(&byte)
}

/// The probe's hello: its request id (the first at or after `first_id` whose two bytes are inert,
/// wrapping round past the last id to 1; id 0 is reserved)
/// and the frame's length in `out`, every byte before the delimiter inert.
pub fn inert_hello(first_id: u16, out: &mut [u8; MAX_FRAME_LEN]) -> Result<(u16, usize), FrameError> {
    let hello = Request::Hello { protocol_version: PROTOCOL_VERSION };
    let ids = (first_id.max(1)..=u16::MAX).chain(1..first_id).filter(|id| id.to_le_bytes().into_iter().all(is_inert));
    for id in ids {
        for last in LAST_LETTERS {
            // NOTE: postcard writes a tuple's fields, and an array's bytes, one after another with no
            // length: the hello's message, then the text and the letter as they are.
            let len = encode(id, &(&hello, TEXT, last), out)?;
            if out[..len - 1].iter().all(|&b| is_inert(b)) {
                return Ok((id, len));
            }
        }
    }
    // NOTE: unreachable in practice (a test finds one within the first ids); an error, not a panic.
    Err(FrameError::Oversized)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::decode;

    #[test]
    fn the_probe_s_hello_holds_no_byte_a_repl_or_bootloader_acts_on_and_the_board_reads_it() {
        let mut frame = [0u8; MAX_FRAME_LEN];
        for first in [1u16, 2, 300, 0x0606, 40_000, 65_000] {
            let (id, len) = inert_hello(first, &mut frame).expect("an inert hello");
            assert!(id >= first && id - first < 1600, "id {id} from {first}");
            let bytes = &frame[..len - 1];
            for byte in ACTED_ON.into_iter().chain([0]) {
                assert!(!bytes.contains(&byte), "0x{byte:02x} in {bytes:02x?}");
            }
            assert_eq!(frame[len - 1], 0, "the delimiter");
            let (read_id, request) = decode::<Request>(&mut frame[..len - 1]).expect("the board reads it");
            assert_eq!((read_id, request), (id, Request::Hello { protocol_version: PROTOCOL_VERSION }));
        }
    }

    #[test]
    fn an_ordinary_hello_would_hold_bytes_a_repl_acts_on() {
        // NOTE: why the probe needs its own frame: the first request's id is 1, which is 0x01 0x00.
        let mut frame = [0u8; MAX_FRAME_LEN];
        let len = super::super::encode(1, &Request::Hello { protocol_version: PROTOCOL_VERSION }, &mut frame).unwrap();
        assert!(frame[..len - 1].iter().any(|&b| !is_inert(b)), "{:02x?}", &frame[..len]);
    }
}
