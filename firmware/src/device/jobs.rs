//! The long operations: a capture (progress, then its statistics) and a stream (samples, then its
//! end), moved on by [`Device::poll`] with whatever the sensor FIFO holds.

use embedded_hal_async::i2c::I2c;
use embedded_storage_async::nor_flash::NorFlash;
use shared::protocol::{ActiveCalibration, CaptureGoal, CaptureStats, DeviceError, Response, StreamKind};
use shared::Position;

use super::{sample_message, Device, SensorOp, OUTBOX_LEN};
use crate::capture::Capture;
use crate::sensor::RawSample;

/// Samples read from the FIFO per read in a poll.
const READ_BATCH: usize = 16;

/// A long operation in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Job {
    Idle,
    Capturing { request_id: u16, capture: Capture, next_progress: u32 },
    Streaming(Stream),
}

/// A stream in progress: every `decimation`-th FIFO sample is taken, `skip` more are passed over
/// first. A taken sample gets the next sequence number and is sent, or dropped and counted when the
/// outbox is full.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Stream {
    request_id: u16,
    kind: StreamKind,
    decimation: u32,
    remaining: Option<u32>,
    taken: u32,
    sent: u32,
    dropped: u32,
    /// FIFO samples read since the start: the sensor's clock.
    fifo_samples: u64,
    sample_period_us: u32,
    skip: u32,
}

impl Stream {
    /// The final response: what was sent and what was dropped.
    fn ended(&self) -> Response {
        Response::StreamEnded { samples: self.sent, dropped: self.dropped }
    }
}

impl<I, F> Device<I, F>
where
    I: I2c,
    F: NorFlash,
{
    /// Moves the running capture or stream on with whatever the FIFO holds. Call every few ms.
    pub async fn poll(&mut self) {
        match self.job {
            Job::Idle => {}
            Job::Capturing { .. } => self.poll_capture().await,
            Job::Streaming(stream) => self.poll_stream(stream).await,
        }
    }

    pub(super) async fn start_capture(&mut self, request_id: u16, seconds: u8) -> Result<(), DeviceError> {
        let capture = Capture::new(seconds, self.config)?;
        self.run_capture(request_id, capture).await
    }

    /// Starts a capture that stops at `goal`.
    pub(super) async fn start_capture_until(&mut self, request_id: u16, goal: CaptureGoal) -> Result<(), DeviceError> {
        let capture = Capture::until(goal, self.config)?;
        self.run_capture(request_id, capture).await
    }

    async fn run_capture(&mut self, request_id: u16, capture: Capture) -> Result<(), DeviceError> {
        self.start_fifo().await?;
        let next_progress = u32::from(self.config.sample_rate_hz);
        self.job = Job::Capturing { request_id, capture, next_progress };
        Ok(())
    }

    async fn poll_capture(&mut self) {
        let Job::Capturing { request_id, mut capture, mut next_progress } = self.job else {
            return;
        };
        let mut batch = [RawSample::default(); READ_BATCH];
        loop {
            match self.read_fifo(&mut batch).await {
                Ok(0) => break,
                Ok(n) => {
                    let taken = capture.take(&batch[..n]);
                    self.temperature_bins.add(&batch[..taken]);
                    taken
                }
                Err(error) => return self.end_job(request_id, Response::Error(error)).await,
            };
            if capture.is_complete() {
                let response = capture.finish().map_or_else(Response::Error, |stats| self.keep(stats));
                return self.end_job(request_id, response).await;
            }
            if capture.samples() >= next_progress {
                self.send(request_id, Response::Progress(capture.progress()));
                next_progress += u32::from(self.config.sample_rate_hz);
            }
        }
        self.job = Job::Capturing { request_id, capture, next_progress };
    }

    /// Keeps a finished capture for the 9-parameter fit, and for the six-position fit when it was
    /// taken at a face.
    fn keep(&mut self, stats: CaptureStats) -> Response {
        self.kept.keep(&stats);
        let position = face_of(stats.mean_g);
        if let Some(p) = position {
            self.positions.replace(p, stats);
        }
        Response::Captured { stats, position }
    }

    /// Starts the FIFO afresh (one instance of the driver call for captures and streams alike).
    async fn start_fifo(&mut self) -> Result<(), DeviceError> {
        self.with_sensor(SensorOp::StartFifo).await.map(|_| ())
    }

    async fn read_fifo(&mut self, batch: &mut [RawSample]) -> Result<usize, DeviceError> {
        self.with_sensor(SensorOp::ReadFifo(batch)).await
    }

    async fn end_job(&mut self, request_id: u16, response: Response) {
        self.job = Job::Idle;
        let bus = &mut self.bus;
        if let Ok(sensor) = self.sensor.as_mut() {
            let _ = sensor.stop_fifo(bus).await;
        }
        self.send(request_id, response);
    }

    pub(super) async fn cancel(&mut self) -> Response {
        match self.job {
            Job::Idle => {}
            Job::Capturing { request_id, .. } => {
                self.end_job(request_id, Response::Error(DeviceError::Cancelled)).await
            }
            Job::Streaming(s) => self.end_job(s.request_id, s.ended()).await,
        }
        Response::Done
    }

    pub(super) async fn start_stream(
        &mut self,
        request_id: u16,
        kind: StreamKind,
        rate_hz: u16,
        count: u32,
    ) -> Result<(), DeviceError> {
        let sample_rate = self.config.sample_rate_hz;
        if rate_hz == 0 || rate_hz > sample_rate || !sample_rate.is_multiple_of(rate_hz) {
            return Err(DeviceError::InvalidRate { rate_hz });
        }
        let calibrated = kind == StreamKind::Calibrated && self.source != ActiveCalibration::None;
        if calibrated && self.active.range != self.config.range {
            return Err(DeviceError::RangeMismatch { calibration: self.active.range, configured: self.config.range });
        }
        self.start_fifo().await?;
        let decimation = u32::from(sample_rate / rate_hz);
        let remaining = (count > 0).then_some(count);
        let sample_period_us = 1_000_000 / u32::from(sample_rate);
        let (taken, sent, dropped, fifo_samples, skip) = (0, 0, 0, 0, 0);
        let stream = Stream {
            request_id,
            kind,
            decimation,
            remaining,
            taken,
            sent,
            dropped,
            fifo_samples,
            sample_period_us,
            skip,
        };
        self.job = Job::Streaming(stream);
        Ok(())
    }

    async fn poll_stream(&mut self, mut stream: Stream) {
        let room = OUTBOX_LEN - self.outbox.len();
        let mut batch = [RawSample::default(); READ_BATCH];
        // NOTE: read no more samples than the outbox can send, the rest waits in the FIFO; but with
        // the outbox full (a host that does not read) read on and drop, so the FIFO never overflows.
        let readable = match room.saturating_sub(1) {
            0 => READ_BATCH,
            free => (free * stream.decimation as usize).min(READ_BATCH),
        };
        let n = match self.read_fifo(&mut batch[..readable]).await {
            Ok(n) => n,
            Err(error) => return self.end_job(stream.request_id, Response::Error(error)).await,
        };
        self.temperature_bins.add(&batch[..n]);
        for raw in &batch[..n] {
            let time_us = stream.fifo_samples * u64::from(stream.sample_period_us);
            stream.fifo_samples += 1;
            if stream.skip > 0 {
                stream.skip -= 1;
                continue;
            }
            stream.skip = stream.decimation - 1;
            if self.take_sample(&mut stream, raw, time_us) {
                return self.end_job(stream.request_id, stream.ended()).await;
            }
        }
        self.job = Job::Streaming(stream);
    }

    /// Takes one sample of the stream: sent, or dropped when the outbox has no room for it beside
    /// the stream's final response. Whether that was its last.
    fn take_sample(&mut self, stream: &mut Stream, raw: &RawSample, time_us: u64) -> bool {
        if self.outbox.len() + 1 < OUTBOX_LEN {
            let calibrated = stream.kind == StreamKind::Calibrated;
            let calibration = calibrated.then(|| self.active_calibration()).flatten();
            let sample = sample_message(raw, stream.taken, time_us, self.config, calibration.as_ref());
            self.send(stream.request_id, Response::Sample(sample));
            stream.sent += 1;
        } else {
            stream.dropped += 1;
        }
        stream.taken += 1;
        match stream.remaining.as_mut() {
            Some(left) => {
                *left -= 1;
                *left == 0
            }
            None => false,
        }
    }
}

/// The face of an averaged reading in g: within the face tolerance, and of a magnitude that can be
/// gravity (a sensor returning zeros, or nearly, points nowhere).
pub(super) fn face_of(mean_g: shared::linalg::Vec3<f32>) -> Option<Position> {
    if !shared::protocol::reads_gravity(shared::linalg::norm(mean_g)) {
        return None;
    }
    Position::within_default_tolerance(mean_g)
}
