use shared::protocol::{self, CaptureProgress, DeviceError, Request, Response, MAX_FRAME_LEN};

use super::*;

const MS: Duration = Duration::from_millis(1);

fn frame(id: u16, response: &Response) -> Vec<u8> {
    let mut bytes = [0u8; MAX_FRAME_LEN];
    let len = protocol::encode(id, response, &mut bytes).unwrap();
    bytes[..len].to_vec()
}

fn progress() -> Response {
    Response::Progress(CaptureProgress { samples: 10, total_samples: 100, mean_g: [0.0, 0.0, 1.0] })
}

#[test]
fn only_the_request_s_own_id_or_the_unreadable_frame_id_answers_it() {
    let mut call = Call::new(7);
    assert!(matches!(call.answered(6, Response::Done), Step::Ignore));
    assert!(matches!(call.answered(8, Response::Done), Step::Ignore));
    assert!(matches!(call.answered(protocol::frame::UNKNOWN_REQUEST_ID, progress()), Step::Update(_)));
    assert!(matches!(call.answered(7, Response::Done), Step::Done(Ok(Response::Done))));
}

#[test]
fn an_interrupted_call_cancels_the_board_s_work_once_and_ends_interrupted_whatever_it_answers() {
    let mut call = Call::new(3);
    assert!(call.interrupt(), "the first Ctrl-C sends a Cancel");
    assert!(!call.interrupt(), "and only the first");
    assert!(!call.decline(), "a call already cancelled asks for no second Cancel");
    assert!(matches!(call.answered(3, progress()), Step::Update(_)), "updates still come in");
    assert!(matches!(call.answered(3, Response::Done), Step::Done(Err(LinkError::Interrupted))));
    // A call the caller declined first is still cancelled by the board when the person interrupts.
    let mut declined = Call::new(4);
    assert!(declined.decline() && !declined.decline());
    assert!(declined.interrupt());
}

#[test]
fn a_board_that_falls_silent_after_updates_stopped_answering_and_before_them_was_silent() {
    let silent = || LinkError::Silent { seconds: 2.0, at_open: false };
    let mut call = Call::new(1);
    assert!(matches!(call.failed(silent()), LinkError::Silent { .. }));
    let _ = call.answered(1, progress());
    assert!(matches!(call.failed(silent()), LinkError::StoppedAnswering));
    assert!(matches!(call.failed(LinkError::Interrupted), LinkError::Interrupted), "other errors pass as they are");
}

#[test]
fn a_device_error_ends_the_call_as_that_error() {
    let mut call = Call::new(2);
    let step = call.answered(2, Response::Error(DeviceError::SensorMissing));
    assert!(matches!(step, Step::Done(Err(LinkError::Device(DeviceError::SensorMissing)))), "{step:?}");
}

#[test]
fn requests_get_ids_from_1_and_the_answer_split_over_reads_is_heard_whole() {
    let mut exchange = Exchange::new(Duration::ZERO);
    let (first, bytes) = exchange.send(&Request::SaveCalibration).unwrap();
    let (second, _) = exchange.send(&Request::Cancel).unwrap();
    assert_eq!((first, second), (1, 2));
    assert_eq!(bytes.last(), Some(&0), "a frame ends with its delimiter");
    exchange.listen(Duration::ZERO);
    let answer = frame(1, &Response::Done);
    let (head, tail) = answer.split_at(answer.len() / 2);
    exchange.received(head);
    assert!(exchange.answer(10 * MS).unwrap().is_none(), "half a frame is no answer yet");
    exchange.received(tail);
    assert_eq!(exchange.answer(20 * MS).unwrap(), Some((1, Response::Done)));
}

#[test]
fn an_answer_heard_after_the_silence_limit_is_taken_before_the_silence_is_judged() {
    let mut exchange = Exchange::new(Duration::ZERO);
    exchange.listen(Duration::ZERO);
    exchange.received(&frame(1, &Response::Done));
    let late = SILENCE_LIMIT + 100 * MS;
    assert_eq!(exchange.answer(late).unwrap(), Some((1, Response::Done)));
    assert!(exchange.answer(late).unwrap().is_none(), "the frame restarted the wait");
    assert!(matches!(exchange.answer(late + SILENCE_LIMIT + MS), Err(LinkError::Silent { .. })));
}

#[test]
fn a_port_that_chatters_without_frames_is_named_not_accelcal_at_the_silence_limit() {
    let mut exchange = Exchange::new(Duration::ZERO);
    exchange.listen(Duration::from_secs(5));
    exchange.received(b"$GPGGA,123519,4807.038,N\r\n");
    assert!(exchange.answer(Duration::from_secs(5) + SILENCE_LIMIT).unwrap().is_none(), "not yet past it");
    let error = exchange.answer(Duration::from_secs(5) + SILENCE_LIMIT + MS).unwrap_err();
    assert!(matches!(&error, LinkError::NotAccelcal { seen, .. } if seen.contains("$GPGGA")), "{error}");
}

#[test]
fn a_frame_of_another_protocol_version_is_heard_as_the_version_mismatch() {
    // NOTE: a frame is COBS(version | request id | message | CRC-32) 0x00 (DESIGN.md, the wire
    // protocol): the version changed and the CRC made again, a frame of another protocol.
    let answer = frame(1, &Response::Done);
    let mut raw = cobs::decode_vec(&answer[..answer.len() - 1]).unwrap();
    let body_len = raw.len() - 4;
    raw[0] = raw[0].wrapping_add(1);
    let crc = crc::Crc::<u32, crc::NoTable>::new(&crc::CRC_32_ISO_HDLC).checksum(&raw[..body_len]);
    raw[body_len..].copy_from_slice(&crc.to_le_bytes());
    let mut answer = cobs::encode_vec(&raw);
    answer.push(0);
    let mut exchange = Exchange::new(Duration::ZERO);
    exchange.received(&answer);
    assert!(matches!(exchange.answer(MS), Err(LinkError::Version { .. })));
}

#[test]
fn leftover_frames_of_our_protocol_are_told_from_a_sketch_s_text_and_from_noise() {
    let mut frames = Vec::new();
    for (id, response) in [(7, Response::Error(shared::protocol::DeviceError::Cancelled)), (8, Response::Done)] {
        let mut frame = [0u8; shared::protocol::MAX_FRAME_LEN];
        let len = protocol::encode(id, &response, &mut frame).unwrap();
        frames.extend_from_slice(&frame[..len]);
    }
    // NOTE: the port opened in the middle of the first frame: its first 3 bytes were read before.
    assert!(holds_accelcal_frame(&frames[3..]), "{:02x?}", &frames[3..]);
    assert!(!holds_accelcal_frame(b"ax,ay,az\r\n0.01,0.02,1.00\r\n"));
    // Zero bytes in line noise delimit chunks that are no valid frame (their CRC-32 fails).
    assert!(!holds_accelcal_frame(&[0x81, 0x00, 0x02, 0x10, 0x7f, 0x03, 0x00, 0x05, 0x11, 0x22, 0x33, 0x00]));
}
