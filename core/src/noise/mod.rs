//! Noise characterisation of a still recording by overlapping Allan deviation: the deviation of each of
//! the six axes at log-spaced averaging times ([`allan`]), the fitted white noise, bias instability and
//! random walk ([`fit`]), what they mean for a calibration, computed once ([`NoiseReport`]) and
//! rendered as text ([`text`]), JSON ([`json`]) or an SVG plot ([`plot`]).

pub mod allan;
pub mod fit;
pub mod json;
pub mod kalibr;
pub mod stream;
pub mod text;

pub use allan::AllanPoint;
pub use fit::NoiseTerms;

/// Averaging times per decade of the Allan deviation curves.
pub const TAUS_PER_DECADE: usize = 10;

/// The six axes of a recording, in file and report order.
pub const AXES: [&str; 6] = ["accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"];

/// Six still-sensor rate series sampled together: accelerometer in g, gyro in deg/s.
#[derive(Debug, Clone, PartialEq)]
pub struct RateSeries {
    /// Samples per second.
    pub rate_hz: f64,
    /// One series per axis of [`AXES`]: three in g, three in deg/s.
    pub axes: [Vec<f64>; 6],
    /// The serial of the board recorded, when the file names it.
    pub board: Option<String>,
}

/// The Allan deviation and the fitted noise terms of one axis, in the axis's unit (g or deg/s).
#[derive(Debug, Clone, PartialEq)]
pub struct AxisNoise {
    /// One of [`AXES`].
    pub name: &'static str,
    /// The deviation at each averaging time.
    pub curve: Vec<AllanPoint>,
    /// The fitted terms (`None` when the series is too short for any averaging time).
    pub terms: Option<NoiseTerms>,
}

impl AxisNoise {
    /// Whether the axis is an accelerometer axis (g) rather than a gyro axis (deg/s).
    pub fn is_accel(&self) -> bool {
        self.name.starts_with("accel")
    }

    /// Whether the curve resolves the fitted random walk (see [`NoiseTerms::random_walk_resolved`]).
    pub fn random_walk_resolved(&self) -> bool {
        match (self.terms, self.curve.last()) {
            (Some(terms), Some(last)) => terms.random_walk_resolved(last.tau_s),
            _ => false,
        }
    }

    /// The largest random walk the curve allows: K^2 tau / 3 cannot exceed the Allan variance, so
    /// K <= sigma(tau) sqrt(3 / tau) at the longest averaging time (its 68 % upper end).
    pub fn random_walk_bound(&self) -> Option<f64> {
        self.curve.last().map(|last| last.adev_high * (3.0 / last.tau_s).sqrt())
    }

    /// The random walk to rely on: the fitted one where the curve resolves it, else the bound.
    pub fn random_walk_or_bound(&self) -> Option<f64> {
        match self.random_walk_resolved() {
            true => self.terms.map(|t| t.random_walk),
            false => self.random_walk_bound(),
        }
    }

    /// Whether the curve resolves the fitted bias instability (see [`NoiseTerms::bias_instability_resolved`]).
    pub fn bias_instability_resolved(&self) -> bool {
        match (self.terms, self.curve.last()) {
            (Some(terms), Some(last)) => terms.bias_instability_resolved(last.tau_s),
            _ => false,
        }
    }
}

/// The noise of a recording: each axis analysed once, for every renderer.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseReport {
    /// Samples per second of the recording.
    pub rate_hz: f64,
    /// Samples per axis.
    pub samples: usize,
    /// The six axes in [`AXES`] order.
    pub axes: Vec<AxisNoise>,
    /// The serial of the board recorded, when the file names it.
    pub board: Option<String>,
}

/// Analyses one rate series at `rate_hz` under the name `name`.
pub fn analyse_axis(name: &'static str, rate: &[f64], rate_hz: f64) -> AxisNoise {
    let factors = allan::averaging_factors(rate.len(), TAUS_PER_DECADE);
    let curve = allan::overlapping_adev(rate, rate_hz, &factors);
    let terms = fit::fit(&curve);
    AxisNoise { name, curve, terms }
}

/// Analyses the six axes one after the other (the host runs them one thread each:
/// `accelcal::noise::analyse`; the results are the same).
pub fn analyse(series: &RateSeries) -> NoiseReport {
    let axes = AXES.iter().zip(&series.axes).map(|(name, rate)| analyse_axis(name, rate, series.rate_hz)).collect();
    NoiseReport::of(series, axes)
}

impl NoiseReport {
    /// The report of `series` from its analysed `axes` (in [`AXES`] order).
    pub fn of(series: &RateSeries, axes: Vec<AxisNoise>) -> Self {
        NoiseReport { rate_hz: series.rate_hz, samples: series.axes[0].len(), axes, board: series.board.clone() }
    }
}

/// Micro-g per g.
pub const UG_PER_G: f64 = 1e6;

/// The factor from the axis's own unit to the usual one: g to ug, deg/s unchanged.
pub fn usual_scale(axis: &AxisNoise) -> f64 {
    if axis.is_accel() {
        UG_PER_G
    } else {
        1.0
    }
}

/// Capture lengths in seconds whose reachable accuracy the report shows.
pub const CAPTURE_SECONDS_SHOWN: [f64; 6] = [1.0, 2.0, 5.0, 10.0, 30.0, 60.0];

/// Averaging time in seconds beyond which no accelerometer axis improves with a longer capture: the
/// largest of their bias-instability averaging times.
pub fn capture_limit_s(report: &NoiseReport) -> Option<f64> {
    accel_axes(report).filter_map(|a| a.terms.map(|t| t.bias_instability_tau_s)).reduce(f64::max)
}

/// Whether an accelerometer axis's deviation was still falling at the longest averaging time analysed,
/// so [`capture_limit_s`] is only a lower bound: longer captures help at least up to there.
pub fn capture_limit_is_lower_bound(report: &NoiseReport) -> bool {
    accel_axes(report).any(|a| match (a.terms, a.curve.last()) {
        (Some(t), Some(last)) => t.bias_instability_tau_s >= last.tau_s,
        _ => false,
    })
}

pub(super) fn accel_axes(report: &NoiseReport) -> impl Iterator<Item = &AxisNoise> {
    report.axes.iter().filter(|a| a.is_accel())
}

/// Reports written before a `..._resolved` flag do not say: taken as resolved.
pub(super) fn resolved_unless_said() -> bool {
    true
}
