//! The thresholds of the fits and of the data they read: when a drift, a gyro fit, a temperature
//! order or a hysteresis is fitted at all, and when a file is single samples.

/// Smallest temperature span of the captures, in degC, that a drift per degree is fitted over;
/// below it the sensor did not warm and no correction is made.
///
/// NOTE: the reading's resolution is 1/340 degC (register map 4.18); over a tenth of a degree a
/// drift of 1 mg/degC moves the offset by 0.1 mg, half the default target.
pub const DRIFT_MIN_CHANGE_C: f64 = 0.1;

/// Fewest captures a drift is fitted from: twelve parameters and one more.
pub const DRIFT_MIN_CAPTURES: usize = 13;

/// Turns needed at least: nine parameters, two constraints per turn, with room to judge the residuals.
pub const MIN_GYRO_TURNS: usize = 6;

/// Turning, in degrees, each gyro axis needs about a horizontal line for its column of G.
///
/// NOTE: a single quarter turn about an axis already fixes its scale to about the noise of the
/// gravity directions; half a turn (two quarter turns) leaves margin for a hand's wobble.
pub const MIN_INFORMATIVE_TURN_DEG: f64 = 150.0;

/// Narrowest overlap of the heating and cooling segments worth comparing, in degC.
///
/// NOTE: each segment's 1 degC bins inside the overlap get a quadratic; five bins are two more than
/// its three coefficients, so its scatter can be judged.
pub const MIN_HYSTERESIS_OVERLAP_C: f64 = 5.0;

/// The learned span each polynomial order needs, in degC: order k is tried from k times this.
///
/// NOTE: the chip applies the model over the whole operating range (-40..85 degC), mostly outside
/// the span learned, where a polynomial's error grows as (distance / span)^order: a cubic fitted to
/// a quick 16 degC warming once drifted past the 0.5 g plausibility limit at -40 degC and the fit was
/// refused. It is the smallest span `thermal` accepts, so a first order is always allowed.
pub const THERMAL_SPAN_PER_ORDER_C: f64 = super::MIN_THERMAL_SPAN_C;

/// Force along an axis, in g, that the learning run must have seen both up and down for a
/// temperature drift of that axis's scale to be fitted.
///
/// NOTE: a scale drift changes sign with the force, an offset drift does not; readings at +-0.5 g
/// (within 60 degrees of up and of down) tell the two apart, while an axis that stayed near 0 g
/// shows no scale drift at all.
pub const SCALE_DRIFT_FORCE_G: f64 = 0.5;

/// Fewest samples for an Allan deviation curve worth fitting (ten averaging times from 1 to N / 10).
pub const NOISE_MIN_SAMPLES: usize = 100;

/// Rows from which a file of single samples is told from a file of averaged positions.
///
/// NOTE: a calibration by positions has a few dozen rows at most (the guided procedure's 14); a
/// logged resting board prints hundreds.
pub const SAMPLE_FILE_ROWS: usize = 30;

/// Successive rows this close (relative to the reading's size) repeat one position.
///
/// NOTE: 5 % of |a| is about 3 degrees of tilt: two positions lie further apart, two samples of a
/// resting board far closer.
pub const REPEAT_FRACTION: f64 = 0.05;

/// Slowest sample rate, in Hz, a session is fitted with its motion (issue 38); below it the still
/// periods alone are fitted.
///
/// NOTE: a hand's turn peaks at 150-200 deg/s (`sim::turn`); at 50 Hz a sample's rotation is up to
/// 4 degrees, and the turn's integral, exact to the noise at 1 kHz, rests on the quadrature of a
/// motion the samples barely resolve (a hand's motion reaches 10-20 Hz).
pub const MOTION_MIN_RATE_HZ: f64 = 50.0;

/// Fewest rests a session is fitted with its motion from: the rests' gyro means fix the gyro's bias
/// and g-sensitivity (twelve numbers, three a rest) and the turns between them its matrix, which
/// needs as many turns as the turn fit ([`MIN_GYRO_TURNS`]).
pub const MOTION_MIN_RESTS: usize = MIN_GYRO_TURNS + 1;
