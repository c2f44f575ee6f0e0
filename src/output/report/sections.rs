//! Report sections built from analysis results, with the figures of
//! `--plot` ([`crate::output::figures`]).

use super::{Section, Table};
use crate::analysis::impulse::{Excitation, ImpulseResult};
use crate::analysis::switch_off::SwitchOffResult;
use crate::analysis::switch_off_study::SwitchOffStudy;
use crate::measured::analysis::FrfAnalysis;
use crate::model::{Model, TimeFunction};
use crate::output::calibrate_report::calibrate_table;
use crate::output::figures::switch_off::{time_figure, trajectory_figure};
use crate::output::figures::{response_figure, spectrum_figure};
use crate::output::frf_report::{frf_figure, frf_table, ResponseQuantity};
use crate::output::plot::{Figure, PlotSize};
use crate::output::switch_off_report::study_label;
use crate::results::{CalibrationOutput, IdentifyOutput};
use realfft::num_complex::Complex64;

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
        preformatted: Vec::new(),
        figures: vec![
            (response_figure(&model.name, r), FIGURE_SIZE),
            (Figure::Line(spectrum_figure(model, r)), FIGURE_SIZE),
        ],
    }
}

/// Whether `model` lets go of something in time (a load that ends or
/// ramps down, a released support): then the report has a switch-off.
pub fn has_release(model: &Model) -> bool {
    let ends =
        |t: &TimeFunction| matches!(t, TimeFunction::Until(_) | TimeFunction::RampDown { .. });
    model.loads.iter().any(|l| ends(&l.time)) || model.joints.iter().any(|j| j.release.is_some())
}

/// The switch-off: time to the distance, flexible against rigid, what was
/// calibrated (nothing for the built-in model), and the figures of
/// `switch-off --plot` (the tracked point against time with the contact
/// forces and released loads, and the trajectory).
pub fn switch_off_section(r: &SwitchOffResult, study: Option<&SwitchOffStudy>) -> Section {
    let ms = |t: Option<f64>| t.map_or("not reached".to_string(), |t| format!("{:.4} ms", t * 1e3));
    let fitted = r
        .calibrated
        .iter()
        .any(|c| c.target.starts_with("time_to_distance_s"));
    let mut rows = vec![vec![
        if fitted {
            "this model, flexible (calibrated)"
        } else {
            "this model, flexible"
        }
        .to_string(),
        ms(r.flexible.time_to_distance_s),
    ]];
    if let Some(u) = &r.uncalibrated {
        rows.push(vec![
            format!(
                "uncalibrated ({}, F_x² at the blade tip; a prediction)",
                u.model
            ),
            ms(u.time_to_distance_s),
        ]);
    }
    if let Some(rigid) = &r.rigid {
        rows.push(vec![
            "this model, rigid beams".into(),
            ms(rigid.time_to_distance_s),
        ]);
    }
    if r.builtin {
        rows.push(vec!["paper (Fig. 7, measured)".into(), "1.7500 ms".into()]);
    }
    let mut notes = vec![if r.calibrated.is_empty() {
        "Calibrated: nothing; every time is a prediction of the model.".to_string()
    } else {
        let list: Vec<String> = r
            .calibrated
            .iter()
            .map(|c| format!("{} = {} (to match {})", c.name, c.value, c.target))
            .collect();
        format!("Calibrated: {}.", list.join("; "))
    }];
    if let Some(d) = r.departure_s {
        let y = r.departure_y_s.map_or_else(
            || String::from("not within the run"),
            |t| format!("{:.4} ms", t * 1e3),
        );
        notes.push(format!(
            "The rigid run departs from the flexible one (paths more than 5 % of the distance apart) at {:.4} ms; in y alone at {y}.",
            d * 1e3
        ));
    }
    notes.extend(r.warnings.iter().cloned());
    let mut tables = vec![Table {
        caption: format!(
            "Time for {} to travel {} mm",
            r.point_label,
            r.settings.distance * 1e3
        ),
        header: vec!["run".into(), "time".into()],
        rows,
    }];
    if let Some(study) = study {
        tables.push(study_report_table(study, r));
        if let Some(q) = study.combined_ratio {
            notes.push(format!(
                "Fig. 10: all three together / reference = {q:.3}, a prediction, beside the paper's ≈ 1/3 (2 mm in ≈ {:.1} ms).",
                study.paper_combined_time_s * 1e3
            ));
        }
    }
    Section {
        id: "switch-off".into(),
        title: "Switch-off".into(),
        notes,
        tables,
        preformatted: Vec::new(),
        figures: vec![
            (Figure::Line(time_figure(r)), FIGURE_SIZE),
            (Figure::Line(trajectory_figure(r)), FIGURE_SIZE),
        ],
    }
}

/// The paper's Fig. 10 study as a table (`switch-off --fig10`'s).
fn study_report_table(study: &SwitchOffStudy, r: &SwitchOffResult) -> Table {
    let rows = study
        .rows
        .iter()
        .map(|row| {
            vec![
                row.change.clone(),
                row.time_to_distance_s.map_or_else(
                    || row.error.clone().unwrap_or_else(|| "not reached".into()),
                    |t| format!("{:.4} ms", t * 1e3),
                ),
                row.ratio_to_reference
                    .map_or_else(|| "–".into(), |q| format!("{q:.3}")),
                row.paper.clone(),
            ]
        })
        .collect();
    Table {
        caption: format!(
            "The paper's Fig. 10: time for {} to travel {} mm ({})",
            r.point_label,
            r.settings.distance * 1e3,
            study_label(study)
        ),
        header: vec![
            "change".into(),
            "time".into(),
            "ratio to the reference".into(),
            "the paper's text".into(),
        ],
        rows,
    }
}

/// The first bending frequency against the experiment (the paper's Table 3
/// for the paper's assembly, else the model's reference or the measured
/// records), as `identify` prints it; `None` without an experiment (the
/// impulse section holds the frequencies then).
pub fn comparison_section(output: &IdentifyOutput, paper: bool) -> Option<Section> {
    output.experiment_hz?;
    let pct = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:+.2} %"));
    let rows = output
        .table
        .iter()
        .map(|r| {
            let mut row = vec![
                r.source.clone(),
                r.first_bending_hz
                    .map_or("–".into(), |f| crate::model::number::significant(f, 7)),
                pct(r.error_percent),
            ];
            // The paper's own error convention, for the paper's assembly.
            if paper {
                row.push(pct(r.paper_error_percent));
            }
            row
        })
        .collect();
    let mut header = vec!["source".into(), "f [Hz]".into(), "(f − exp)/exp".into()];
    if paper {
        header.push("paper: (exp − f)/f".into());
    }
    let mut notes = vec![format!("Supports: {}.", output.supports)];
    if let Some(source) = &output.reference_source {
        notes.push(format!("Experiment: {}.", source.trim_end_matches('.')));
    }
    Some(Section {
        id: "comparison".into(),
        title: if paper {
            "First bending frequency (the paper's Table 3)".into()
        } else {
            "First bending frequency against the experiment".into()
        },
        notes,
        tables: vec![Table {
            caption: String::new(),
            header,
            rows,
        }],
        preformatted: Vec::new(),
        figures: Vec::new(),
    })
}

/// The equivalent-geometry fit: what was calibrated, to what, and the
/// fitted model's frequencies (the `calibrate` table).
pub fn calibration_section(c: &CalibrationOutput) -> Section {
    Section {
        id: "calibration".into(),
        title: "Calibration".into(),
        notes: vec![format!(
            "Calibrated to the experiment (a fit, not a prediction): the fitted model {} is the model with these values.",
            c.fitted_model
        )],
        tables: Vec::new(),
        preformatted: vec![calibrate_table(&c.model, &c.result)],
        figures: Vec::new(),
    }
}

/// The measured records: FRF magnitude and phase with the fitted modes,
/// the coherence and the stabilization diagram, with the model's FRF at
/// the sensor when `overlay` is given (label, frequencies [Hz], values).
pub fn measured_section(
    a: &FrfAnalysis,
    q: ResponseQuantity,
    overlay: Option<(&str, &[f64], &[Complex64])>,
) -> Section {
    Section {
        id: "measured".into(),
        title: "Measured FRF".into(),
        notes: vec![format!(
            "{} record file(s); band {:.0}–{:.0} Hz.",
            a.files.len(),
            a.band.0,
            a.band.1
        )],
        tables: Vec::new(),
        preformatted: vec![frf_table(a, q)],
        figures: vec![(Figure::Line(frf_figure(a, q, overlay)), FIGURE_SIZE)],
    }
}
