//! Report sections built from analysis results, with the figures of
//! `--plot` ([`crate::output::figures`]).

use super::{Section, Table};
use crate::analysis::impulse::{Excitation, ImpulseResult};
use crate::model::Model;
use crate::output::figures::{response_figure, spectrum_figure};
use crate::output::plot::{Figure, PlotSize};

/// Size of the report's line figures [px].
pub const FIGURE_SIZE: PlotSize = PlotSize {
    width: 900,
    height: 560,
};

/// The impulse experiment: force and response with the first periods
/// zoomed, the spectrum with the eigenfrequencies marked, and the first
/// bending frequency from the spectrum against the eigenvalue.
pub fn impulse_section(model: &Model, r: &ImpulseResult) -> Section {
    let excitation = match r.excitation {
        Excitation::HalfSine => "half-sine pulse",
        Excitation::Step => "step",
    };
    let mut notes = vec![format!(
        "Excitation: {excitation} on {}; sensor {} ({}) sampled at {:.0} Hz; {} steps of the transient.",
        r.excitation_loads.join(", "),
        r.sensor,
        format!("{:?}", r.quantity).to_lowercase(),
        r.sample_rate_hz,
        r.stats.steps
    )];
    let mut tables = Vec::new();
    if let Some(fb) = &r.first_bending {
        tables.push(Table {
            caption: "First bending frequency".into(),
            header: vec![
                "source".into(),
                "f [Hz]".into(),
                "against the eigenvalue".into(),
            ],
            rows: vec![
                vec![
                    "eigenvalue".into(),
                    format!("{:.2}", fb.eigen_hz),
                    String::new(),
                ],
                vec![
                    "impulse + FFT (raw)".into(),
                    format!("{:.2}", fb.raw_hz),
                    format!("{:+.2e}", fb.raw_error()),
                ],
                vec![
                    "impulse + FFT (integrator's period error removed)".into(),
                    format!("{:.2}", fb.corrected_hz),
                    format!("{:+.2e}", fb.corrected_error()),
                ],
            ],
        });
    } else {
        notes.push("No bending peak was identified in the spectrum.".into());
    }
    Section {
        id: "impulse".into(),
        title: "Impulse test".into(),
        notes,
        tables,
        figures: vec![
            (response_figure(&model.name, r), FIGURE_SIZE),
            (Figure::Line(spectrum_figure(model, r)), FIGURE_SIZE),
        ],
    }
}
