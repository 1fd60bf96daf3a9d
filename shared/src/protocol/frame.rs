//! Framing: `COBS(version | request id | postcard payload | CRC-32) 0x00`.
//!
//! The version byte comes first and outside the payload so that a peer of another protocol version
//! is recognised before anything is decoded. The CRC covers version, id and payload. Request id 0 is
//! reserved for answers to frames that could not be read (their id is unknown).

use crc::{Crc, NoTable, CRC_32_ISO_HDLC};
use serde::{de::DeserializeOwned, Deserialize, Serialize};

use super::{MAX_FRAME_LEN, MAX_PAYLOAD_LEN, PROTOCOL_VERSION};

/// Bytes before the payload: version (1) and request id (2, little-endian).
pub const HEADER_LEN: usize = 3;
/// Bytes of the CRC-32 after the payload.
pub const CRC_LEN: usize = 4;
/// Request id used when the id of the frame being answered is unknown.
pub const UNKNOWN_REQUEST_ID: u16 = 0;

// NOTE: bit by bit, without the 1 KiB lookup table: the board's 64 KiB of flash is full, and a
// frame of at most ~600 bytes takes tens of microseconds this way at the board's clock.
const CRC: Crc<u32, NoTable> = Crc::<u32, NoTable>::new(&CRC_32_ISO_HDLC);
const RAW_LEN: usize = HEADER_LEN + MAX_PAYLOAD_LEN + CRC_LEN;

/// Why a frame could not be built or read.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameError {
    /// The frame is longer than [`MAX_FRAME_LEN`], or the message does not fit the payload limit.
    Oversized,
    /// The bytes are not valid COBS.
    Cobs,
    /// Too short to hold header and CRC.
    Truncated,
    /// The CRC does not match: the frame was corrupted.
    Crc,
    /// The frame carries another protocol version.
    Version { got: u8 },
    /// The payload is not a valid message.
    Payload,
}

/// Encodes one message into `out`, delimiter included; returns the frame length.
pub fn encode<T: Serialize>(request_id: u16, message: &T, out: &mut [u8; MAX_FRAME_LEN]) -> Result<usize, FrameError> {
    let mut raw = [0u8; RAW_LEN];
    raw[0] = PROTOCOL_VERSION;
    raw[1..HEADER_LEN].copy_from_slice(&request_id.to_le_bytes());
    let payload_len = postcard::to_slice(message, &mut raw[HEADER_LEN..HEADER_LEN + MAX_PAYLOAD_LEN])
        .map_err(|_| FrameError::Oversized)?
        .len();
    let crc_at = HEADER_LEN + payload_len;
    let crc = CRC.checksum(&raw[..crc_at]);
    raw[crc_at..crc_at + CRC_LEN].copy_from_slice(&crc.to_le_bytes());
    let encoded =
        cobs::try_encode(&raw[..crc_at + CRC_LEN], &mut out[..MAX_FRAME_LEN - 1]).map_err(|_| FrameError::Oversized)?;
    out[encoded] = 0;
    Ok(encoded + 1)
}

/// Decodes one frame (the bytes before its 0x00 delimiter) in place into its request id and message.
pub fn decode<T: DeserializeOwned>(frame: &mut [u8]) -> Result<(u16, T), FrameError> {
    let raw_len = cobs::decode_in_place(frame).map_err(|_| FrameError::Cobs)?;
    let raw = &frame[..raw_len];
    if raw_len < HEADER_LEN + CRC_LEN {
        return Err(FrameError::Truncated);
    }
    let (body, crc) = raw.split_at(raw_len - CRC_LEN);
    if CRC.checksum(body).to_le_bytes() != crc {
        return Err(FrameError::Crc);
    }
    if body[0] != PROTOCOL_VERSION {
        return Err(FrameError::Version { got: body[0] });
    }
    let request_id = u16::from_le_bytes([body[1], body[2]]);
    let message = postcard::from_bytes(&body[HEADER_LEN..]).map_err(|_| FrameError::Payload)?;
    Ok((request_id, message))
}

/// The result of feeding one byte to a [`FrameAccumulator`].
#[derive(Debug, PartialEq, Eq)]
pub enum Feed<'a> {
    /// The byte was taken; no frame is complete yet.
    Pending,
    /// A delimiter completed a frame: its bytes, ready for [`decode`].
    Frame(&'a mut [u8]),
    /// A delimiter ended a frame that was too long; its bytes were dropped.
    Oversized,
}

/// Collects bytes from a stream into frames, in a fixed buffer; survives garbage and overlong frames.
#[derive(Debug)]
pub struct FrameAccumulator {
    buffer: [u8; MAX_FRAME_LEN],
    len: usize,
    overflowed: bool,
}

impl Default for FrameAccumulator {
    fn default() -> Self {
        FrameAccumulator { buffer: [0; MAX_FRAME_LEN], len: 0, overflowed: false }
    }
}

impl FrameAccumulator {
    /// An empty accumulator.
    pub fn new() -> Self {
        Self::default()
    }

    /// Takes one byte; at a delimiter, returns the frame it ends. Empty frames are skipped.
    pub fn feed(&mut self, byte: u8) -> Feed<'_> {
        if byte != 0 {
            if self.len < self.buffer.len() {
                self.buffer[self.len] = byte;
                self.len += 1;
            } else {
                self.overflowed = true;
            }
            return Feed::Pending;
        }
        let len = core::mem::take(&mut self.len);
        if core::mem::take(&mut self.overflowed) {
            Feed::Oversized
        } else if len == 0 {
            Feed::Pending
        } else {
            Feed::Frame(&mut self.buffer[..len])
        }
    }

    /// Drops any partial frame (after a timeout or a reconnect).
    pub fn reset(&mut self) {
        self.len = 0;
        self.overflowed = false;
    }
}
