//! The six named positions, detection of the position from an averaged reading, and the tilt angles
//! (toolface, inclination) of `data/README.md`.

use num_traits::Float;
use serde::{Deserialize, Serialize};

use crate::linalg::{self, Vec3};

mod position_map;

pub use position_map::PositionMap;

/// Default largest tilt, in degrees, between a reading and a face for it to count as that face.
///
/// NOTE: the reading's own offset tilts it too: an MPU-6050 may have 150 mg of zero-g offset on z
/// (datasheet section 6.2), 8.5 degrees on its own, and the published phone's -Y reading lies 10.0
/// degrees from its face. 20 degrees accepts that plus a hand's placement, and still refuses a reading
/// halfway between faces (at least 45 degrees from every face).
pub const DEFAULT_FACE_TOLERANCE_DEG: f32 = 20.0;
/// cos([`DEFAULT_FACE_TOLERANCE_DEG`]), for the check without an angle (a test holds the two together).
pub const DEFAULT_FACE_TOLERANCE_COS: f32 = 0.939_692_6;

/// A position, named by the body axis that points up (so that axis reads +1 g).
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
// NOTE: a JSON file spells each variant as a person reads it (issue 40: sessions said "G2", "Hz44",
// "HostFit"); the old spellings are still read. postcard (the wire and the flash) keeps the variant's
// index, so the renames change no byte there.
pub enum Position {
    /// +x up.
    #[serde(rename = "+X", alias = "PosX")]
    PosX,
    /// -x up.
    #[serde(rename = "-X", alias = "NegX")]
    NegX,
    /// +y up.
    #[serde(rename = "+Y", alias = "PosY")]
    PosY,
    /// -y up.
    #[serde(rename = "-Y", alias = "NegY")]
    NegY,
    /// +z up.
    #[serde(rename = "+Z", alias = "PosZ")]
    PosZ,
    /// -z up.
    #[serde(rename = "-Z", alias = "NegZ")]
    NegZ,
}

/// Why a reading could not be assigned to a position.
#[derive(Serialize, Deserialize, Debug, Clone, Copy, PartialEq)]
pub enum PositionError {
    /// The reading is too far from every face: `nearest` is `tilt_deg` away.
    BetweenPositions { nearest: Position, tilt_deg: f32 },
    /// The reading is zero or not finite, so it has no direction.
    NoDirection,
}

impl Position {
    /// All six positions, in the order `+X, -X, +Y, -Y, +Z, -Z`.
    pub const ALL: [Position; 6] =
        [Position::PosX, Position::NegX, Position::PosY, Position::NegY, Position::PosZ, Position::NegZ];

    /// The name printed on the board's axes: `+X` ... `-Z`.
    pub const fn name(self) -> &'static str {
        match self {
            Position::PosX => "+X",
            Position::NegX => "-X",
            Position::PosY => "+Y",
            Position::NegY => "-Y",
            Position::PosZ => "+Z",
            Position::NegZ => "-Z",
        }
    }

    /// Index in [`Position::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The body axis that points up (0 = x, 1 = y, 2 = z).
    pub const fn axis(self) -> usize {
        self.index() / 2
    }

    /// +1 when the positive axis points up, -1 when the negative one does.
    pub const fn sign(self) -> i8 {
        match self {
            Position::PosX | Position::PosY | Position::PosZ => 1,
            Position::NegX | Position::NegY | Position::NegZ => -1,
        }
    }

    /// The position with `axis` up (sign > 0) or down.
    pub const fn from_axis(axis: usize, positive: bool) -> Position {
        Position::ALL[axis * 2 + if positive { 0 } else { 1 }]
    }

    /// The specific force the sensor feels at rest in this position, in g.
    pub fn specific_force_g<T: Float>(self) -> Vec3<T> {
        let mut up = [T::zero(); 3];
        up[self.axis()] = if self.sign() > 0 { T::one() } else { -T::one() };
        up
    }

    /// The face a reading (any unit) lies within [`DEFAULT_FACE_TOLERANCE_DEG`] of: as
    /// [`Position::detect`] without the tilt, so without an arc tangent (the chip's check; its
    /// flash has no room for `atan2`).
    pub fn within_default_tolerance(reading: Vec3<f32>) -> Option<Position> {
        let magnitude = linalg::norm(reading);
        if !magnitude.is_finite() || magnitude == 0.0 {
            return None;
        }
        let axis = dominant_axis(reading);
        // NOTE: the angle to the nearest face is within the tolerance when the reading's component
        // along that face's axis is at least the tolerance's cosine times its length.
        let within = reading[axis].abs() >= DEFAULT_FACE_TOLERANCE_COS * magnitude;
        within.then(|| Position::from_axis(axis, reading[axis] > 0.0))
    }

    /// The position of a reading (any unit) within `tolerance_deg` of a face, with its tilt from it.
    pub fn detect(reading: Vec3<f32>, tolerance_deg: f32) -> Result<(Position, f32), PositionError> {
        let magnitude = linalg::norm(reading);
        if !magnitude.is_finite() || magnitude == 0.0 {
            return Err(PositionError::NoDirection);
        }
        let axis = dominant_axis(reading);
        let nearest = Position::from_axis(axis, reading[axis] > 0.0);
        let tilt_deg = angle_between_deg(reading, nearest.specific_force_g());
        if tilt_deg <= tolerance_deg {
            Ok((nearest, tilt_deg))
        } else {
            Err(PositionError::BetweenPositions { nearest, tilt_deg })
        }
    }
}

/// The axis with the largest magnitude.
fn dominant_axis(v: Vec3<f32>) -> usize {
    let mut best = 0;
    for axis in 1..3 {
        if v[axis].abs() > v[best].abs() {
            best = axis;
        }
    }
    best
}

/// Angle between two vectors in degrees, accurate also for nearly parallel vectors.
///
/// NOTE: `atan2(|a x b|, a . b)` keeps full precision near 0 and 180 degrees, where `acos` loses it.
pub fn angle_between_deg<T: Float>(a: Vec3<T>, b: Vec3<T>) -> T {
    let sine = linalg::norm(linalg::cross(a, b));
    sine.atan2(linalg::dot(a, b)).to_degrees()
}

/// Inclination in degrees: the elevation of the specific force above the x-y plane, asin(a_z / |a|).
pub fn inclination_deg<T: Float>(a: Vec3<T>) -> T {
    // NOTE: atan2 of the z component against the x-y magnitude equals asin(a_z/|a|) and stays exact
    // near +-90 degrees.
    let horizontal = (a[0] * a[0] + a[1] * a[1]).sqrt();
    a[2].atan2(horizontal).to_degrees()
}

/// Toolface in degrees in [0, 360): atan2(a_x, a_y), measured from +y toward +x.
///
/// Undefined (returned as 0) when the x-y projection is zero, at inclination +-90 degrees.
pub fn toolface_deg<T: Float>(a: Vec3<T>) -> T {
    let angle = a[0].atan2(a[1]).to_degrees();
    let full = T::from(360.0).unwrap_or_else(T::zero);
    if angle < T::zero() {
        angle + full
    } else {
        angle
    }
}

/// The unit specific force for an inclination and toolface in degrees: (cos i sin tf, cos i cos tf, sin i).
pub fn from_inclination_toolface<T: Float>(inclination_deg: T, toolface_deg: T) -> Vec3<T> {
    let (incl, tf) = (inclination_deg.to_radians(), toolface_deg.to_radians());
    [incl.cos() * tf.sin(), incl.cos() * tf.cos(), incl.sin()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_check_without_an_angle_agrees_with_detect_on_either_side_of_the_tolerance() {
        assert!((DEFAULT_FACE_TOLERANCE_COS - DEFAULT_FACE_TOLERANCE_DEG.to_radians().cos()).abs() < 1e-7);
        for position in Position::ALL {
            for tilt in [0.0, 10.0, 19.9, 20.1, 30.0, 44.0] {
                let reading = tilted(position, tilt).map(|v| v * 9.8);
                let detected = Position::detect(reading, DEFAULT_FACE_TOLERANCE_DEG).ok().map(|(p, _)| p);
                assert_eq!(Position::within_default_tolerance(reading), detected, "{position:?} {tilt}");
                assert_eq!(detected.is_some(), tilt < 20.0, "{position:?} {tilt}");
            }
        }
        assert_eq!(Position::within_default_tolerance([0.0; 3]), None);
        assert_eq!(Position::within_default_tolerance([f32::NAN, 1.0, 0.0]), None);
    }

    /// A unit vector tilted `tilt_deg` from `position` toward the next axis.
    fn tilted(position: Position, tilt_deg: f32) -> Vec3<f32> {
        let mut v: Vec3<f32> = linalg::scale(position.specific_force_g(), tilt_deg.to_radians().cos());
        v[(position.axis() + 1) % 3] += tilt_deg.to_radians().sin();
        v
    }

    #[test]
    fn every_face_within_tolerance_is_detected_with_its_tilt() {
        for position in Position::ALL {
            for tilt in [0.0, 3.0, 9.9] {
                let (found, tilt_deg) = Position::detect(tilted(position, tilt), 10.0).unwrap();
                assert_eq!(found, position);
                assert!((tilt_deg - tilt).abs() < 1e-3, "{position:?} tilt {tilt} read {tilt_deg}");
            }
        }
    }

    #[test]
    fn readings_between_faces_are_refused_with_the_nearest_face() {
        for position in Position::ALL {
            let err = Position::detect(tilted(position, 30.0), 10.0).unwrap_err();
            match err {
                PositionError::BetweenPositions { nearest, tilt_deg } => {
                    assert_eq!(nearest, position);
                    assert!((tilt_deg - 30.0).abs() < 1e-3);
                }
                other => panic!("expected BetweenPositions, got {other:?}"),
            }
        }
        // Exactly between +X and +Y and +Z: 54.7 degrees from every face.
        assert!(Position::detect([1.0, 1.0, 1.0], 10.0).is_err());
    }

    #[test]
    fn zero_and_nan_readings_have_no_direction() {
        assert_eq!(Position::detect([0.0; 3], 10.0), Err(PositionError::NoDirection));
        assert_eq!(Position::detect([f32::NAN, 1.0, 0.0], 10.0), Err(PositionError::NoDirection));
    }

    #[test]
    fn detection_works_in_any_unit() {
        let m_per_s2 = [0.31, 10.14, -0.91]; // phone row 4 of the published data, +Y up
        assert_eq!(Position::detect(m_per_s2, 10.0).unwrap().0, Position::PosY);
    }

    #[test]
    fn toolface_and_inclination_invert_the_published_definition() {
        for (incl, tf) in [(0.0, 0.0), (50.0, 30.0), (50.0, 330.0), (-20.0, 180.0), (10.0, 270.0)] {
            let a: Vec3<f64> = from_inclination_toolface(incl, tf);
            assert!((inclination_deg(a) - incl).abs() < 1e-12);
            assert!((toolface_deg(a) - tf).abs() < 1e-12, "tf {tf} read {}", toolface_deg(a));
        }
    }

    #[test]
    fn angle_between_is_exact_for_small_and_straight_angles() {
        let a = [1.0f64, 0.0, 0.0];
        let tiny = [1.0, 1e-9, 0.0];
        assert!((angle_between_deg(a, tiny) - 1e-9f64.to_degrees()).abs() < 1e-18);
        assert!((angle_between_deg(a, [-1.0, 0.0, 0.0]) - 180.0).abs() < 1e-12);
        assert!((angle_between_deg(a, [0.0, 2.0, 0.0]) - 90.0).abs() < 1e-12);
    }
}
