//! A wanted orientation: a name for the user, the body-frame direction that should point up, and
//! how far from it the board may rest. The one type for it on the host: the procedure's targets, the
//! simulated hand and the session records all use it.

use serde::{Deserialize, Serialize};
use shared::linalg;
use shared::Position;

use crate::limits::{CORNER_TOLERANCE_DEG, FACE_TOLERANCE_DEG};

/// An orientation the board should rest in.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Orientation {
    /// "+X" ... "-Z" for the faces, "+X+Y+Z" ... for the corners.
    pub name: String,
    /// Unit vector of the body frame that should point up.
    pub up: [f64; 3],
    /// Largest tilt from `up`, in degrees, still accepted as this orientation.
    pub tolerance_deg: f64,
}

impl Orientation {
    /// One of the six faces.
    pub fn face(face: Position) -> Self {
        Orientation { name: face.name().to_owned(), up: face.specific_force_g(), tolerance_deg: FACE_TOLERANCE_DEG }
    }

    /// The corner whose x, y and z point up (`true`) or down, each 54.7 degrees from its three faces.
    pub fn corner(signs: [bool; 3]) -> Self {
        let sign = |up: bool| if up { 1.0 } else { -1.0 };
        let letters = ["X", "Y", "Z"];
        let name = (0..3).map(|k| format!("{}{}", if signs[k] { '+' } else { '-' }, letters[k])).collect();
        let up = linalg::scale(signs.map(sign), 1.0 / 3f64.sqrt());
        Orientation { name, up, tolerance_deg: CORNER_TOLERANCE_DEG }
    }

    /// A face or a corner by its name (`+X`, `-x`, `+X+Y-Z`, ...), if it is one.
    pub fn named(name: &str) -> Option<Self> {
        faces().into_iter().chain(corners()).find(|o| o.name.eq_ignore_ascii_case(name.trim()))
    }

    /// The face this orientation rests on, by its direction (so the closing capture "+Z again" is
    /// the face +Z), or `None` for a corner or any other direction.
    pub fn face_up(&self) -> Option<Position> {
        Position::ALL.into_iter().find(|p| p.specific_force_g::<f64>() == self.up)
    }

    /// Whether this is one of the six faces.
    pub fn is_face(&self) -> bool {
        self.face_up().is_some()
    }

    /// The tilt, in degrees, of a direction from this orientation's up.
    pub fn tilt_deg(&self, up: [f64; 3]) -> f64 {
        shared::orientation::angle_between_deg(up, self.up)
    }
}

/// The six faces.
pub fn faces() -> Vec<Orientation> {
    Position::ALL.into_iter().map(Orientation::face).collect()
}

/// The eight corners of the cube: together with the faces they spread 14 positions over the
/// sphere, which the orientation-free fit needs.
pub fn corners() -> Vec<Orientation> {
    let mut corners = Vec::with_capacity(8);
    for x in [true, false] {
        for y in [true, false] {
            for z in [true, false] {
                corners.push(Orientation::corner([x, y, z]));
            }
        }
    }
    corners
}

/// The quick calibration's ten orientations, in the order they are asked for: the six faces and
/// the four corners of a tetrahedron (+X+Y+Z, -X-Y+Z, -X+Y-Z, +X-Y-Z).
///
/// NOTE: why these. The orientation-free 9-parameter fit needs at least nine readings; on the six
/// faces alone its cross-axis terms enter |a| only to second order and are not determined, so some
/// readings must have two axes loaded at once. The tetrahedron's corners load every pair of axes
/// with each sign pattern of the three products x y, x z, y z, which separates the three cross-axis
/// terms; the tenth reading leaves one degree of freedom for the fit's residual.
/// NOTE: why this order. A warming sensor's offsets drift during the session (about 0.03 mg/s just
/// after power-on, simulated sensor); opposite faces back to back keep that drift out of the scales,
/// and the faces in the middle with two corners either side centre each axis's information on the
/// session's middle. Measured (tests/quick_mode.rs, realistic simulated sensor just powered on,
/// 20 seeds, 5 s captures): 0.320 mg rms true error, worst seed 0.421 mg; asked faces first and
/// corners last, the same captures left 0.507 mg, worst 0.654 mg.
pub fn quick_set() -> Vec<Orientation> {
    let face = |p: Position| Orientation::face(p);
    vec![
        Orientation::corner([true, true, true]),
        Orientation::corner([false, false, true]),
        face(Position::NegX),
        face(Position::PosX),
        face(Position::NegZ),
        face(Position::PosZ),
        face(Position::PosY),
        face(Position::NegY),
        Orientation::corner([false, true, false]),
        Orientation::corner([true, false, false]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_are_named_by_their_signs_and_lie_54_7_degrees_from_their_faces() {
        let corner = Orientation::named("+x-y+z").unwrap();
        assert_eq!(corner.name, "+X-Y+Z");
        assert!((Orientation::face(Position::NegY).tilt_deg(corner.up) - 54.7356).abs() < 1e-3);
        assert_eq!(corners().len(), 8);
        assert!(corners().iter().all(|c| !c.is_face()) && faces().iter().all(Orientation::is_face));
        assert_eq!(Orientation::named("sideways"), None);
    }
}
