//! The client takes as the answer to a request only a frame carrying that request's id (or id 0, the
//! device's answer to a frame it could not read): a stale answer to an earlier request, or any frame
//! with another id, is ignored. Driven over an in-memory pipe by a scripted device sending frames
//! made with the shared protocol's encoder.

use accelcal::link::{pipe, Client, LinkError};
use accelcal_tests::scripted::{self, frame};
use shared::protocol::{CalibrationSlot, DeviceError, FrameError, Request, Response, Sample, StreamKind};

fn sample(index: u32) -> Response {
    Response::Sample(Sample {
        index,
        time_us: u64::from(index) * 10_000,
        accel_g: [0.0, 0.0, 1.0],
        gyro_dps: [0.0; 3],
        temp_c: 25.0,
    })
}

#[test]
fn a_stale_answer_to_an_earlier_request_is_not_taken_as_the_answer() {
    let (host, device) = pipe();
    let _device = scripted::spawn(device, |id, _| {
        // A late answer to the previous request, another id's error, then this request's answer.
        let stale = frame(id - 1, &Response::Done);
        let foreign = frame(id + 7, &Response::Error(DeviceError::Busy));
        [stale, foreign, frame(id, &Response::Calibration(None))].concat()
    });
    let (mut client, _) = Client::connect(host).expect("the scripted device says hello");
    for _ in 0..3 {
        let answer = client.call(Request::GetCalibration(CalibrationSlot::Active)).expect("an answer");
        assert_eq!(answer, Response::Calibration(None));
    }
}

#[test]
fn samples_of_another_request_are_not_counted_as_this_stream_s() {
    let (host, device) = pipe();
    let _device = scripted::spawn(device, |id, _| {
        let mut frames =
            vec![frame(id - 1, &sample(99)), frame(id - 1, &Response::StreamEnded { samples: 1, dropped: 0 })];
        frames.extend((0..3).map(|i| frame(id, &sample(i))));
        frames.push(frame(id, &Response::StreamEnded { samples: 3, dropped: 0 }));
        frames.concat()
    });
    let (mut client, _) = Client::connect(host).expect("the scripted device says hello");
    let mut indices = Vec::new();
    let last = client
        .run(Request::Stream { kind: StreamKind::Raw, rate_hz: 20, count: 3 }, |update| {
            if let Response::Sample(sample) = update {
                indices.push(sample.index);
            }
        })
        .expect("the stream ends");
    assert_eq!(indices, [0, 1, 2]);
    assert_eq!(last, Response::StreamEnded { samples: 3, dropped: 0 });
}

#[test]
fn an_answer_with_id_0_to_an_unreadable_frame_is_taken_as_the_answer() {
    let (host, device) = pipe();
    let _device = scripted::spawn(device, |_, _| frame(0, &Response::Error(DeviceError::Frame(FrameError::Crc))));
    let (mut client, _) = Client::connect(host).expect("the scripted device says hello");
    let error = client.call(Request::SaveCalibration).expect_err("the device's error");
    assert!(matches!(error, LinkError::Device(DeviceError::Frame(FrameError::Crc))), "{error}");
}
