//! One typed method per request: what the device answers, or why not.

use shared::protocol::{
    CalibrationSlot, CaptureGoal, CaptureProgress, CaptureStats, DeviceInfo, Request, Response, Sample, SensorConfig,
    StreamKind, TempBin, PROTOCOL_VERSION, TEMP_BINS_PER_MESSAGE,
};
use shared::selftest::StoredSelfTest;
use shared::{Calibration, Position};

use super::{request_name, Link, LinkError, Tally, Transport};

/// What a stream asks for: raw or corrected samples, how many per second, how many.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamRequest {
    /// Raw or corrected on the chip.
    pub kind: StreamKind,
    /// Samples per second (must divide the sample rate).
    pub rate_hz: u16,
    /// Samples to send.
    pub count: u32,
}

/// The chip's own 9-parameter fit of the captures it kept, as [`Link::fit_ortho9`] returns it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChipOrtho9 {
    /// The fit (not active); `residual_mg` is the RMS of |a| - 1 g over the captures, in mg.
    pub calibration: Calibration,
    /// Captures it used.
    pub captures: u8,
    /// Solver iterations.
    pub iterations: u8,
}

impl<T: Transport> Link<T> {
    /// Says hello (again: the device's state now); refuses a device of another protocol version.
    pub async fn hello(&mut self) -> Result<DeviceInfo, LinkError> {
        let request = Request::Hello { protocol_version: PROTOCOL_VERSION };
        match self.call(request.clone()).await? {
            Response::Hello(info) if info.protocol_version == PROTOCOL_VERSION => Ok(info),
            Response::Hello(info) => Err(LinkError::version(info.protocol_version)),
            other => Err(unexpected(&request, &other)),
        }
    }

    /// Averages the still sensor for `seconds`, reporting progress; the statistics and the face the
    /// device detected.
    pub async fn capture(
        &mut self,
        seconds: u8,
        mut on_progress: impl FnMut(&CaptureProgress),
    ) -> Result<(CaptureStats, Option<Position>), LinkError> {
        self.captured_by(Request::Capture { seconds }, &mut on_progress).await
    }

    /// Averages the still sensor until `goal` stops it, reporting progress; the statistics and the
    /// face the device detected.
    pub async fn capture_until(
        &mut self,
        goal: CaptureGoal,
        mut on_progress: impl FnMut(&CaptureProgress),
    ) -> Result<(CaptureStats, Option<Position>), LinkError> {
        self.captured_by(Request::CaptureUntil(goal), &mut on_progress).await
    }

    /// Runs a capture request, reporting its progress; the statistics and the face detected.
    async fn captured_by(
        &mut self,
        request: Request,
        on_progress: &mut dyn FnMut(&CaptureProgress),
    ) -> Result<(CaptureStats, Option<Position>), LinkError> {
        let response = self
            .run(request.clone(), |update| {
                if let Response::Progress(progress) = update {
                    on_progress(progress)
                }
            })
            .await?;
        match response {
            Response::Captured { stats, position } => Ok((stats, position)),
            other => Err(unexpected(&request, &other)),
        }
    }

    /// Sets range, sample rate and filter; the configuration the device achieved.
    pub async fn configure(&mut self, config: SensorConfig) -> Result<SensorConfig, LinkError> {
        let request = Request::Configure(config);
        match self.call(request.clone()).await? {
            Response::Configured(achieved) => Ok(achieved),
            other => Err(unexpected(&request, &other)),
        }
    }

    /// Streams samples, each to `on_sample`; what arrived and what was lost.
    pub async fn stream(
        &mut self,
        wanted: StreamRequest,
        mut on_sample: impl FnMut(&Sample),
    ) -> Result<Tally, LinkError> {
        self.stream_while(wanted, |sample| {
            on_sample(sample);
            true
        })
        .await
    }

    /// As [`Link::stream`]; once `on_sample` returns `false` the stream is cancelled on the board.
    pub async fn stream_while(
        &mut self,
        wanted: StreamRequest,
        mut on_sample: impl FnMut(&Sample) -> bool,
    ) -> Result<Tally, LinkError> {
        let request = Request::Stream { kind: wanted.kind, rate_hz: wanted.rate_hz, count: wanted.count };
        let mut tally = Tally::default();
        let response = self
            .run_while(request.clone(), |update| match update {
                Response::Sample(sample) => {
                    tally.arrived(sample.index);
                    on_sample(sample)
                }
                _ => true,
            })
            .await?;
        match response {
            Response::StreamEnded { samples, dropped } => Ok(tally.ended(samples, dropped)),
            other => Err(unexpected(&request, &other)),
        }
    }

    /// The active or the stored calibration; `None` when the slot is empty.
    pub async fn calibration(&mut self, slot: CalibrationSlot) -> Result<Option<Calibration>, LinkError> {
        let request = Request::GetCalibration(slot);
        match self.call(request.clone()).await? {
            Response::Calibration(calibration) => Ok(calibration),
            other => Err(unexpected(&request, &other)),
        }
    }

    /// Makes a calibration active (until reset, or until saved).
    pub async fn set_calibration(&mut self, calibration: Calibration) -> Result<(), LinkError> {
        self.expect_done(Request::SetCalibration(calibration)).await
    }

    /// Stores the active calibration in flash.
    pub async fn save_calibration(&mut self) -> Result<(), LinkError> {
        self.expect_done(Request::SaveCalibration).await
    }

    /// Erases the stored calibration.
    pub async fn erase_calibration(&mut self) -> Result<(), LinkError> {
        self.expect_done(Request::EraseCalibration).await
    }

    /// Forgets the captures kept for the chip's fits.
    pub async fn clear_positions(&mut self) -> Result<(), LinkError> {
        self.expect_done(Request::ClearPositions).await
    }

    /// Every temperature bin the chip holds, coolest first; the chip's bins are then empty.
    pub async fn take_temperature_bins(&mut self) -> Result<Vec<TempBin>, LinkError> {
        let mut bins = Vec::new();
        loop {
            let request = Request::TakeTemperatureBins;
            match self.call(request.clone()).await? {
                Response::TemperatureBins(taken) => {
                    let last = taken.len() < TEMP_BINS_PER_MESSAGE;
                    bins.extend(taken);
                    if last {
                        return Ok(bins);
                    }
                }
                other => return Err(unexpected(&request, &other)),
            }
        }
    }

    /// The on-chip six-position fit of the captures the device kept.
    pub async fn fit_six_position(&mut self) -> Result<Calibration, LinkError> {
        let request = Request::FitSixPosition;
        match self.call(request.clone()).await? {
            Response::Fitted(calibration) => Ok(calibration),
            other => Err(unexpected(&request, &other)),
        }
    }

    /// The chip's 9-parameter (`ortho9`) fit of the captures it kept since they were last cleared.
    pub async fn fit_ortho9(&mut self) -> Result<ChipOrtho9, LinkError> {
        let request = Request::FitOrtho9;
        match self.call(request.clone()).await? {
            Response::Ortho9Fitted { calibration, captures, iterations } => {
                Ok(ChipOrtho9 { calibration, captures, iterations })
            }
            other => Err(unexpected(&request, &other)),
        }
    }

    /// Writes `write` to a sensor register when given, then reads it: the value it holds.
    pub async fn register(&mut self, register: u8, write: Option<u8>) -> Result<u8, LinkError> {
        let request = Request::Register { register, write };
        match self.call(request.clone()).await? {
            Response::Register(value) => Ok(value),
            other => Err(unexpected(&request, &other)),
        }
    }

    /// `count` consecutive sensor registers from `first`, one request each.
    pub async fn read_registers(&mut self, first: u8, count: u8) -> Result<Vec<u8>, LinkError> {
        let mut values = Vec::with_capacity(usize::from(count));
        for register in first..first.saturating_add(count) {
            values.push(self.register(register, None).await?);
        }
        Ok(values)
    }

    /// Writes one sensor register; the value it holds afterwards.
    pub async fn write_register(&mut self, register: u8, value: u8) -> Result<u8, LinkError> {
        self.register(register, Some(value)).await
    }

    /// Keeps a self-test in the board's flash in place of the one before (every hello carries it).
    pub async fn store_self_test(&mut self, self_test: &StoredSelfTest) -> Result<(), LinkError> {
        self.expect_done(Request::StoreSelfTest(self_test.record())).await
    }

    async fn expect_done(&mut self, request: Request) -> Result<(), LinkError> {
        match self.call(request.clone()).await? {
            Response::Done => Ok(()),
            other => Err(unexpected(&request, &other)),
        }
    }
}

fn unexpected(request: &Request, answer: &Response) -> LinkError {
    LinkError::UnexpectedAnswer { request: request_name(request), answer: format!("{answer:?}") }
}
