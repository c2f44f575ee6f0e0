//! Ready-made line figures: a calibration curve and a convergence study.

use super::line::{LineFigure, Panel};
use super::series::{Guide, MarkerShape, PointMarker, Series, SeriesStyle};
use super::style::{format_sig, Scale};
use super::ticks::superscript;

/// Calibration of one model parameter so that a frequency meets a target.
#[derive(Debug, Clone, Default)]
pub struct Calibration {
    pub title: String,
    /// The parameter, without unit (e.g. "Joint stiffness").
    pub parameter_label: String,
    pub parameter_scale: Scale,
    /// Show the parameter on a log axis (for parameters spanning decades).
    pub parameter_log: bool,
    /// How frequencies are shown (e.g. `Scale::hz()`).
    pub frequency_scale: Scale,
    /// A sweep of the model: parameter values and their frequencies (Hz);
    /// may be empty.
    pub sweep_parameter: Vec<f64>,
    pub sweep_frequency: Vec<f64>,
    /// The frequency to meet (Hz) and its label (e.g. "experiment 4600 Hz").
    pub target_hz: f64,
    pub target_label: String,
    /// The iterates (parameter, frequency), in order; they are numbered 1, 2, ….
    pub iterations: Vec<(f64, f64)>,
    /// The accepted (parameter, frequency), if any.
    pub fitted: Option<(f64, f64)>,
}

/// Frequency against the parameter: the sweep as a line, the target as a
/// reference line, the iteration path with numbered points, and the fit.
pub fn calibration_figure(c: &Calibration) -> LineFigure {
    let mut panel = Panel::new("Frequency", c.frequency_scale.clone());
    if !c.sweep_parameter.is_empty() {
        panel.series.push(Series::line(
            "model",
            c.sweep_parameter.clone(),
            c.sweep_frequency.clone(),
        ));
    }
    if !c.iterations.is_empty() {
        let (p, f): (Vec<f64>, Vec<f64>) = c.iterations.iter().copied().unzip();
        panel
            .series
            .push(Series::new("iterations", p, f, SeriesStyle::LinePoints));
        // Numbers; repeated iterates share one label ("4, 5").
        let mut k = 0;
        while k < c.iterations.len() {
            let (p, f) = c.iterations[k];
            let same = c.iterations[k..]
                .iter()
                .take_while(|&&q| q == (p, f))
                .count();
            let label = (k + 1..=k + same)
                .map(|i| i.to_string())
                .collect::<Vec<_>>()
                .join(", ");
            panel.points.push(PointMarker {
                shape: MarkerShape::None,
                ..PointMarker::new(p, f, label)
            });
            k += same;
        }
    }
    panel
        .hlines
        .push(Guide::reference(c.target_hz, c.target_label.clone()));
    if let Some((p, f)) = c.fitted {
        let s = &c.parameter_scale;
        let mut label = format!("fit: {}", format_sig(s.apply(p), 4));
        if !s.unit.is_empty() {
            label.push(' ');
            label.push_str(&s.unit);
        }
        panel.points.push(PointMarker {
            shape: MarkerShape::Square,
            colour: Some(2),
            ..PointMarker::new(p, f, label)
        });
    }
    LineFigure {
        x_log: c.parameter_log,
        panels: vec![panel],
        ..LineFigure::new(
            c.title.clone(),
            c.parameter_label.clone(),
            c.parameter_scale.clone(),
        )
    }
}

/// A mesh-convergence study.
#[derive(Debug, Clone, Default)]
pub struct Convergence {
    pub title: String,
    /// Numbers of elements, shared by all error series.
    pub elements: Vec<f64>,
    /// Named relative errors (e.g. per mode), one value per element count.
    pub errors: Vec<(String, Vec<f64>)>,
    /// Expected order p: a reference line ∝ n⁻ᵖ labelled "O(hᵖ)" is drawn.
    pub order: i32,
}

/// Relative error against the number of elements, log-log, with a reference
/// slope through half the first error of the first series.
pub fn convergence_figure(c: &Convergence) -> LineFigure {
    let mut panel = Panel::new("Relative error", Scale::none());
    panel.y_log = true;
    for (name, err) in &c.errors {
        panel.series.push(Series::new(
            name.clone(),
            c.elements.clone(),
            err.clone(),
            SeriesStyle::LinePoints,
        ));
    }
    let anchor = c.errors.first().and_then(|(_, e)| {
        c.elements
            .iter()
            .zip(e)
            .find(|(n, e)| **n > 0.0 && **e > 0.0 && e.is_finite())
    });
    if let (Some((&n0, &e0)), true) = (anchor, c.order > 0) {
        let p = c.order as f64;
        let y = c
            .elements
            .iter()
            .map(|n| 0.5 * e0 * (n0 / n).powf(p))
            .collect();
        panel.series.push(Series::new(
            format!("O(h{})", superscript(c.order)),
            c.elements.clone(),
            y,
            SeriesStyle::Reference,
        ));
    }
    LineFigure {
        x_log: true,
        panels: vec![panel],
        ..LineFigure::new(c.title.clone(), "Number of elements", Scale::none())
    }
}
