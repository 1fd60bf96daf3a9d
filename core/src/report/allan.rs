//! The report's Allan deviation section, from the JSON `accelcal noise --json` prints (given to
//! `accelcal report --noise`, or computed there from a recording): the fitted noise terms of each
//! axis and a log-log plot of the accelerometer's deviation with the fitted curve.

use std::fmt::Write;

use serde::Serialize;

use super::figure::{axis_role, Figure, Series, SeriesStyle};
use super::plot::{colour, svg, PlotError, SIZE};
use crate::noise::json::{AxisJson, NoiseJson};
use crate::noise::{NoiseTerms, AXES};
use crate::shown::escape;

/// The noise of the board, as the report shows it.
#[derive(Debug, Clone, Serialize)]
pub struct AllanSection {
    /// Samples per second of the recording analysed.
    pub sample_rate_hz: f64,
    /// Samples per axis.
    pub samples: u64,
    /// Averaging time beyond which no accelerometer axis improves with a longer capture, in s.
    pub capture_limit_s: Option<f64>,
    /// Whether that limit is only a lower bound (the deviation still fell at the longest averaging time).
    pub capture_limit_is_lower_bound: bool,
    /// The six axes in `accel_x` ... `gyro_z` order.
    pub axes: Vec<AllanAxis>,
}

/// One axis's fitted terms, in the units `accelcal noise --json` names.
#[derive(Debug, Clone, Serialize)]
pub struct AllanAxis {
    /// `accel_x` ... `gyro_z`.
    pub name: &'static str,
    /// White noise density, one-sided as datasheets give it (ug/sqrt(Hz), deg/s/sqrt(Hz)).
    pub white_noise_density: Option<f64>,
    /// Bias instability (ug, deg/s).
    pub bias_instability: Option<f64>,
    /// Where the fitted deviation is smallest, in s.
    pub bias_instability_tau_s: Option<f64>,
    /// Whether the curve resolves the bias instability (older noise reports do not say: taken as so).
    pub bias_instability_resolved: bool,
    /// Random walk (ug/s/sqrt(Hz), deg/s/s/sqrt(Hz)).
    pub random_walk: Option<f64>,
    /// Whether the curve resolves the random walk (older noise reports do not say: taken as so).
    pub random_walk_resolved: bool,
}

impl AllanSection {
    /// The section and its plot from a noise report's JSON; `Err` says what it lacks.
    pub fn new(noise: &NoiseJson) -> Result<(Self, Figure), String> {
        let axes =
            AXES.iter().map(|&name| Ok(AllanAxis::new(name, noise.axis(name)?))).collect::<Result<_, String>>()?;
        let section = AllanSection {
            sample_rate_hz: noise.sample_rate_hz.ok_or("it has no sample_rate_hz")?,
            samples: noise.samples.ok_or("it has no samples")? as u64,
            capture_limit_s: noise.calibration.capture_limit_s,
            capture_limit_is_lower_bound: noise.calibration.capture_limit_is_lower_bound,
            axes,
        };
        let figure = figure(noise, AllanPlot::Accel)?;
        Ok((section, figure))
    }
}

impl AllanAxis {
    fn new(name: &'static str, axis: &AxisJson) -> Self {
        AllanAxis {
            name,
            white_noise_density: axis.white_noise_density,
            bias_instability: axis.bias_instability,
            bias_instability_tau_s: axis.bias_instability_tau_s,
            bias_instability_resolved: axis.bias_instability_resolved,
            random_walk: axis.random_walk,
            random_walk_resolved: axis.random_walk_resolved,
        }
    }
}

/// One sensor's deviation plot: the accelerometer's (in ug) or the gyro's (in deg/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AllanPlot {
    /// The accelerometer's three axes, in ug.
    Accel,
    /// The gyro's three axes, in deg/s.
    Gyro,
}

impl AllanPlot {
    /// The section's axes this plot shows, and its id, caption and unit.
    fn of(self) -> (std::ops::Range<usize>, &'static str, &'static str, &'static str) {
        match self {
            AllanPlot::Accel => (0..3, "allan-deviation", "accelerometer", "ug"),
            AllanPlot::Gyro => (3..6, "allan-deviation-gyro", "gyro", "deg/s"),
        }
    }
}

/// The one Allan deviation plot (the report's, and `accelcal noise --plot`'s): per axis the deviation
/// (markers), its 68 % interval (a band, when the report gives it) and the fitted curve (a line), log-log.
pub fn figure(noise: &NoiseJson, plot: AllanPlot) -> Result<Figure, String> {
    let (axes, id, sensor, unit) = plot.of();
    let mut series = Vec::new();
    for (k, name) in AXES[axes].iter().enumerate() {
        let curve = noise.axis(name)?;
        let (taus, adev) = (&curve.tau_s, &curve.adev);
        if taus.is_empty() || taus.len() != adev.len() {
            return Err(format!("{name} has no deviation curve (tau_s and adev of one length)"));
        }
        let (short, role) = (["x", "y", "z"][k], axis_role(k));
        if curve.adev_low.len() == taus.len() && curve.adev_high.len() == taus.len() {
            let upper = taus.iter().zip(&curve.adev_high).map(|(t, a)| [*t, *a]);
            let band = upper.chain(taus.iter().zip(&curve.adev_low).rev().map(|(t, a)| [*t, *a])).collect();
            series.push(Series::new(&format!("{short} 68 % interval"), role, SeriesStyle::Band, band));
        }
        let measured = taus.iter().zip(adev).map(|(t, a)| [*t, *a]).collect();
        series.push(Series::new(&format!("{short} deviation"), role, SeriesStyle::Points, measured));
        if let Some(terms) = fitted(&AllanAxis::new(name, curve)) {
            let line = taus.iter().map(|&t| [t, terms.adev(t)]).collect();
            series.push(Series::new(&format!("{short} fitted"), role, SeriesStyle::Line, line));
        }
    }
    Ok(Figure {
        id,
        title: format!("{sensor} Allan deviation and the fitted noise terms"),
        x_label: "averaging time (s)".into(),
        y_label: format!("Allan deviation ({unit})"),
        equal_axes: false,
        log_axes: true,
        index_x: false,
        series,
    })
}

/// Height of the two caption lines above each plot of [`svg_document`], in SVG user units.
const CAPTION_HEIGHT: u32 = 48;

/// `accelcal noise --plot`'s file: the accelerometer's and the gyro's plot side by side in one SVG
/// document on white, each under its caption and key (the plots' text is black until a page sets it).
pub fn svg_document(noise: &NoiseJson) -> Result<String, PlotError> {
    let (width, height) = SIZE;
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
        2 * width,
        height + CAPTION_HEIGHT
    );
    for (k, plot) in [AllanPlot::Accel, AllanPlot::Gyro].into_iter().enumerate() {
        let figure = figure(noise, plot).map_err(|reason| PlotError::new(plot.of().1, reason))?;
        let left = k as u32 * width;
        let _ = writeln!(out, "<text x=\"{}\" y=\"18\" font-size=\"15\">{}</text>", left + 8, escape(&figure.title));
        let _ = writeln!(out, "<text x=\"{}\" y=\"40\" font-size=\"13\">{}</text>", left + 8, key(plot));
        let _ = writeln!(out, "<g transform=\"translate({left},{CAPTION_HEIGHT})\">{}</g>", svg(&figure)?);
    }
    out.push_str("</svg>\n");
    Ok(out)
}

/// The key of a plot in the document: each axis's name in its colour, then what each mark means.
fn key(plot: AllanPlot) -> String {
    let names = AXES[plot.of().0].iter().enumerate();
    let coloured = names.map(|(k, name)| format!("<tspan fill=\"{}\">{name}</tspan>", colour(axis_role(k))));
    format!("{} (dots: deviation; band: 68 % interval; line: fitted terms)", coloured.collect::<Vec<_>>().join(" "))
}

/// The fitted terms of an axis as the noise analysis models them (its N is the one-sided density
/// over sqrt(2), see `noise::fit`).
fn fitted(axis: &AllanAxis) -> Option<NoiseTerms> {
    Some(NoiseTerms {
        white_noise_n: axis.white_noise_density? / std::f64::consts::SQRT_2,
        bias_instability: axis.bias_instability?,
        bias_instability_tau_s: axis.bias_instability_tau_s?,
        random_walk: axis.random_walk?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A noise report of two averaging times per axis: the accelerometer's in ug, the gyro's in deg/s.
    fn noise() -> NoiseJson {
        let axis = |scale: f64| {
            format!(
                r#"{{"tau_s": [0.01, 0.1], "adev": [{}, {}], "adev_low": [{}, {}], "adev_high": [{}, {}],
                "white_noise_density": {}, "bias_instability": {}, "bias_instability_tau_s": 10.0,
                "random_walk": {}}}"#,
                300.0 * scale,
                95.0 * scale,
                290.0 * scale,
                90.0 * scale,
                310.0 * scale,
                100.0 * scale,
                42.0 * scale,
                5.0 * scale,
                0.1 * scale
            )
        };
        let axes: Vec<String> = AXES
            .iter()
            .map(|name| format!("\"{name}\": {}", axis(if name.starts_with("accel") { 1.0 } else { 1e-3 })))
            .collect();
        crate::noise::json::read(&format!("{{\"sample_rate_hz\": 100.0, \"samples\": 6000, {}}}", axes.join(", ")))
            .unwrap()
    }

    #[test]
    fn the_allan_plot_shows_each_axis_with_its_interval_as_a_band_and_its_fitted_curve() {
        let noise = noise();
        let accel = figure(&noise, AllanPlot::Accel).unwrap();
        assert_eq!((accel.id, accel.y_label.as_str()), ("allan-deviation", "Allan deviation (ug)"));
        let styles: Vec<SeriesStyle> = accel.series.iter().map(|s| s.style).collect();
        assert_eq!(styles, [SeriesStyle::Band, SeriesStyle::Points, SeriesStyle::Line].repeat(3));
        // The band's outline: the upper ends forward, then the lower ends back.
        assert_eq!(accel.series[0].points, [[0.01, 310.0], [0.1, 100.0], [0.1, 90.0], [0.01, 290.0]]);
        assert_eq!(accel.series[1].points, [[0.01, 300.0], [0.1, 95.0]]);
        let gyro = figure(&noise, AllanPlot::Gyro).unwrap();
        assert_eq!((gyro.id, gyro.y_label.as_str()), ("allan-deviation-gyro", "Allan deviation (deg/s)"));
        assert!((gyro.series[1].points[0][1] - 0.3).abs() < 1e-12, "{:?}", gyro.series[1].points);
        // `noise --plot`'s document draws both, each with its key.
        let document = svg_document(&noise).unwrap();
        assert_eq!(document.matches("<g transform=").count(), 2);
        assert!(document.contains("accel_x") && document.contains("gyro_z"));
    }
}
