//! The report's plots as data: each figure holds the very numbers it is drawn from, so the JSON and
//! the drawing cannot disagree. [`super::plot`] draws them.

use serde::Serialize;
use shared::linalg::{self, Mat3, Vec3};

#[cfg(test)]
use super::position::residual_mg;
use super::position::PositionResult;
use crate::fit::Fit;
use crate::session::Verification;

/// Points on each sphere outline.
const OUTLINE_POINTS: usize = 96;
/// Largest radial deviation of a sphere view after exaggeration, as a fraction of the radius.
const SHOWN_DEVIATION: f64 = 0.25;

/// One plot: axes and the series drawn on them.
#[derive(Debug, Clone, Serialize)]
pub struct Figure {
    /// Identifies the plot in the page (`sphere-xy`, ...).
    pub id: &'static str,
    /// Caption.
    pub title: String,
    /// Horizontal axis label, with unit.
    pub x_label: String,
    /// Vertical axis label, with unit.
    pub y_label: String,
    /// Whether both axes share one scale (a sphere stays round).
    pub equal_axes: bool,
    /// Whether both axes are logarithmic (an Allan deviation); the points stay in their units.
    pub log_axes: bool,
    /// Whether the horizontal axis counts things (positions, turns): labelled at whole numbers only.
    #[serde(skip)]
    pub index_x: bool,
    /// The series, drawn in order.
    pub series: Vec<Series>,
}

/// One series of a figure.
#[derive(Debug, Clone, Serialize)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// Markers or a connected line.
    pub style: SeriesStyle,
    /// What the series shows, which sets its colour.
    pub role: Role,
    /// The points, in the axes' units.
    pub points: Vec<[f64; 2]>,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SeriesStyle {
    /// A marker at every point.
    Points,
    /// A line through the points.
    Line,
    /// A filled area (an interval): the points trace its outline, the upper edge forward and the
    /// lower edge back.
    Band,
}

/// What a series shows: every plot draws raw data in one colour, calibrated in another.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Role {
    /// Uncalibrated readings, or what they trace.
    Raw,
    /// Calibrated readings.
    Calibrated,
    /// A reference to read the others against (the 1 g sphere, a noise floor).
    Reference,
    /// The sensor's x axis, where a plot shows the three axes side by side.
    AxisX,
    /// The sensor's y axis.
    AxisY,
    /// The sensor's z axis.
    AxisZ,
}

/// The role of the sensor axis `k` (0, 1, 2).
pub fn axis_role(k: usize) -> Role {
    [Role::AxisX, Role::AxisY, Role::AxisZ][k.min(2)]
}

impl Series {
    /// A series named `name`.
    pub fn new(name: &str, role: Role, style: SeriesStyle, points: Vec<[f64; 2]>) -> Self {
        Series { name: name.to_owned(), style, role, points }
    }
}

/// The positions seen along the axis missing from `axes` (orthographic), raw and calibrated, with
/// the unit sphere and the ellipsoid raw readings trace (its cross-section in the plane of
/// `axes`); radial deviations from 1 g are exaggerated so millig become visible.
pub fn sphere_view(positions: &[PositionResult], fit: &Fit, axes: [usize; 2]) -> Figure {
    let ellipse = ellipsoid_section(&fit.matrix, &fit.offset, axes);
    let largest = positions.iter().map(|p| p.residual_before_mg.abs() / 1000.0);
    let gain = exaggeration(largest.chain(ellipse.iter().map(|r| (linalg::norm(*r) - 1.0).abs())));
    let project = |v: &Vec3<f64>| {
        let v = exaggerate(*v, gain);
        [v[axes[0]], v[axes[1]]]
    };
    let name = |axis: usize| ["x", "y", "z"][axis];
    let seen_along = name(3 - axes[0] - axes[1]);
    Figure {
        id: if axes == [0, 1] { "sphere-xy" } else { "sphere-xz" },
        title: format!("seen along {seen_along}; deviation from 1 g magnified {gain}x"),
        x_label: format!("{} (g)", name(axes[0])),
        y_label: format!("{} (g)", name(axes[1])),
        equal_axes: true,
        log_axes: false,
        index_x: false,
        series: vec![
            Series::new(
                "1 g sphere",
                Role::Reference,
                SeriesStyle::Line,
                in_plane(axes).map(|v| project(&v)).collect(),
            ),
            Series::new("raw ellipsoid", Role::Raw, SeriesStyle::Line, ellipse.iter().map(project).collect()),
            Series::new("raw", Role::Raw, SeriesStyle::Points, positions.iter().map(|p| project(&p.raw_g)).collect()),
            Series::new(
                "calibrated",
                Role::Calibrated,
                SeriesStyle::Points,
                positions.iter().map(|p| project(&p.calibrated_g)).collect(),
            ),
        ],
    }
}

/// Each position's |v| - 1 g, raw and calibrated, each on its own scale (the calibrated ones are
/// hundreds of times smaller).
pub fn residuals(positions: &[PositionResult]) -> [Figure; 2] {
    let before: Vec<f64> = positions.iter().map(|p| p.residual_before_mg).collect();
    let after: Vec<f64> = positions.iter().map(|p| p.residual_after_mg).collect();
    [
        numbered("residuals-raw", "raw: each position's |m| - 1 g", "position", Role::Raw, &before, None),
        numbered(
            "residuals-calibrated",
            "calibrated: each position's |a| - 1 g",
            "position",
            Role::Calibrated,
            &after,
            None,
        ),
    ]
}

/// The verification's orientations, raw and calibrated, the calibrated ones within the band of
/// plus and minus the noise floor.
pub fn verification(v: &Verification) -> Option<[Figure; 2]> {
    if v.after_mg.is_empty() {
        return None;
    }
    let (title_raw, title_calibrated) =
        ("raw: |m| - 1 g at fresh orientations", "calibrated: |a| - 1 g at fresh orientations");
    Some([
        numbered("verification-raw", title_raw, "orientation", Role::Raw, &v.before_mg, None),
        numbered(
            "verification-calibrated",
            title_calibrated,
            "orientation",
            Role::Calibrated,
            &v.after_mg,
            Some(v.noise_floor_mg),
        ),
    ])
}

/// `values` against their number from 1, with a band of plus and minus `floor` when given.
fn numbered(id: &'static str, title: &str, x_label: &str, role: Role, values: &[f64], floor: Option<f64>) -> Figure {
    let points = values.iter().enumerate().map(|(i, v)| [(i + 1) as f64, *v]).collect();
    let mut series = vec![Series::new(title.split(':').next().unwrap_or(title), role, SeriesStyle::Points, points)];
    if let Some(floor) = floor {
        let (left, right) = (0.5, values.len() as f64 + 0.5);
        let band = vec![[left, floor], [right, floor], [right, -floor], [left, -floor], [left, floor]];
        series.push(Series::new("noise floor (+-)", Role::Reference, SeriesStyle::Line, band));
    }
    let (x_label, y_label) = (x_label.to_owned(), "mg".to_owned());
    Figure { id, title: title.to_owned(), x_label, y_label, equal_axes: false, log_axes: false, index_x: true, series }
}

/// The unit circle in the plane of `axes` (a great circle of the 1 g sphere).
fn in_plane(axes: [usize; 2]) -> impl Iterator<Item = Vec3<f64>> {
    (0..=OUTLINE_POINTS).map(move |i| {
        let t = i as f64 / OUTLINE_POINTS as f64 * std::f64::consts::TAU;
        let mut direction = [0.0; 3];
        direction[axes[0]] = t.cos();
        direction[axes[1]] = t.sin();
        direction
    })
}

/// Points of the raw-reading ellipsoid |M (m - o)| = 1 g along directions in the plane of `axes`.
fn ellipsoid_section(matrix: &Mat3<f64>, offset: &Vec3<f64>, axes: [usize; 2]) -> Vec<Vec3<f64>> {
    in_plane(axes).map(|d| linalg::scale(d, ray_to_ellipsoid(matrix, offset, d))).collect()
}

/// The distance r > 0 along unit `d` with |M (r d - o)| = 1: the root of
/// r^2 |Md|^2 - 2 r (Md . Mo) + |Mo|^2 - 1 = 0 on the far side of the offset.
fn ray_to_ellipsoid(matrix: &Mat3<f64>, offset: &Vec3<f64>, d: Vec3<f64>) -> f64 {
    let (md, mo) = (linalg::mul_vec(matrix, d), linalg::mul_vec(matrix, *offset));
    let (a, b, c) = (linalg::dot(md, md), linalg::dot(md, mo), linalg::dot(mo, mo) - 1.0);
    (b + (b * b - a * c).max(0.0).sqrt()) / a
}

/// A round magnification (1, 2 or 5 times a power of ten) that shows the largest radial deviation
/// as about [`SHOWN_DEVIATION`] of the radius.
fn exaggeration(deviations: impl Iterator<Item = f64>) -> f64 {
    let largest = deviations.fold(0.0f64, f64::max);
    if largest <= 0.0 {
        return 1.0;
    }
    let wanted = (SHOWN_DEVIATION / largest).max(1.0);
    let decade = 10f64.powf(wanted.log10().floor());
    [5.0, 2.0, 1.0].into_iter().map(|step| step * decade).find(|g| *g <= wanted).unwrap_or(decade)
}

/// `v` with its deviation from 1 g multiplied by `gain`, direction kept.
fn exaggerate(v: Vec3<f64>, gain: f64) -> Vec3<f64> {
    let norm = linalg::norm(v);
    if norm == 0.0 {
        return v;
    }
    linalg::scale(v, (1.0 + gain * (norm - 1.0)) / norm)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ellipsoid_section_is_where_the_calibration_reads_1_g() {
        let matrix = [[1.02, 0.01, 0.0], [0.0, 0.97, 0.02], [0.0, 0.0, 1.01]];
        let offset = [0.03, -0.02, 0.05];
        for point in ellipsoid_section(&matrix, &offset, [0, 2]) {
            let calibrated = linalg::mul_vec(&matrix, linalg::sub(point, offset));
            assert!(residual_mg(calibrated).abs() < 1e-9, "{point:?} reads {calibrated:?}");
            assert_eq!(point[1], 0.0);
        }
    }

    #[test]
    fn magnification_is_round_and_shows_the_largest_deviation_at_most_a_quarter_radius() {
        assert_eq!(exaggeration([0.001, -0.0002].into_iter()), 200.0);
        assert_eq!(exaggeration([0.004].into_iter()), 50.0);
        assert_eq!(exaggeration([0.5].into_iter()), 1.0);
        let shown = exaggerate([0.0, 0.0, 1.004], 50.0);
        assert!((shown[2] - 1.2).abs() < 1e-12);
    }
}
