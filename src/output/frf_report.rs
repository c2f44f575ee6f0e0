//! `frf` results: the table of identified modes, the JSON document (keys of
//! DESIGN §9), CSV of the spectra, the UFF 58 export (H1 and coherence),
//! and the figure (FRF magnitude and phase with the fitted model, the
//! coherence, and the stabilization diagram).

use std::fmt::Write;

use realfft::num_complex::Complex64;

use crate::measured::analysis::FrfAnalysis;
use crate::measured::uff::{d58, Function, FunctionType, Ordinate, SpecDataType};
use crate::output::plot::{
    Guide, Legend, LineFigure, MarkerShape, Panel, PointMarker, Scale, Series, SeriesStyle,
};
use crate::signal::fit::{RejectedPole, Stability};

pub use crate::measured::ResponseQuantity;

/// Identified modes as a readable table.
pub fn frf_table(a: &FrfAnalysis, q: ResponseQuantity) -> String {
    let mut s = String::new();
    let files: Vec<String> = a.files.iter().map(|f| f.display().to_string()).collect();
    let _ = writeln!(s, "measurement: {}", files.join(", "));
    let mut kinds = a.channels.clone();
    kinds.dedup();
    for [force, response] in &kinds {
        let _ = writeln!(s, "channels: force `{force}`, response `{response}`");
    }
    if let Some(e) = &a.estimate {
        let _ = writeln!(
            s,
            "{} hit(s) of {} samples at {} Hz ({:.4} s, Δf = {:.4} Hz), {} window",
            e.averages,
            e.samples,
            crate::model::number::significant(e.sample_rate_hz, 7),
            e.samples as f64 / e.sample_rate_hz,
            e.df(),
            e.window
        );
    }
    let _ = writeln!(
        s,
        "modal fit of {} ({}) over {:.1}–{:.1} Hz: LSCF up to order {}, poles refined by nonlinear least squares",
        a.settings.estimator.name().to_uppercase(),
        q.frf_unit(),
        a.band.0,
        a.band.1,
        a.fit.settings.max_order
    );
    let _ = writeln!(s, "the band ends {}", a.band_end.describe());
    let _ = writeln!(s, "data taken as {}", a.fit.settings.basis.describe());
    if a.fit.modes.is_empty() {
        let _ = writeln!(s, "no stable mode found in the band");
    } else {
        mode_rows(&mut s, a);
    }
    for run in combs(&a.rejected) {
        let (first, last) = (&run[0], &run[run.len() - 1]);
        if run.len() < COMB {
            for r in run {
                let _ = writeln!(
                    s,
                    "not reported: a stable pole at {:.3} Hz, ζ {:.4} %: {}",
                    r.frequency_hz,
                    100.0 * r.damping_ratio,
                    r.reason.describe()
                );
            }
            continue;
        }
        let zeta = |f: fn(f64, f64) -> f64| {
            100.0
                * run
                    .iter()
                    .map(|r| r.damping_ratio)
                    .fold(first.damping_ratio, f)
        };
        let gaps: Vec<f64> = run
            .windows(2)
            .map(|w| w[1].frequency_hz - w[0].frequency_hz)
            .collect();
        let gap = |f: fn(f64, f64) -> f64| gaps.iter().copied().fold(gaps[0], f);
        let apart = if gap(f64::max) - gap(f64::min) <= 1e-3 * gap(f64::max) {
            format!("{:.3} Hz", gap(f64::max))
        } else {
            format!("{:.3} to {:.3} Hz", gap(f64::min), gap(f64::max))
        };
        let _ = writeln!(
            s,
            "not reported: {} stable poles from {:.3} to {:.3} Hz, {apart} apart (ζ {:.4} to {:.4} %), each: {}",
            run.len(),
            first.frequency_hz,
            last.frequency_hz,
            zeta(f64::min),
            zeta(f64::max),
            first.reason.describe()
        );
    }
    s
}

/// Fewest rejected poles of one reason, evenly spaced, listed on one line.
const COMB: usize = 3;

/// The rejected poles (by frequency) in runs: a comb of poles of one
/// reason whose spacings lie within a factor 2 of its first is one run (a
/// fit's artefact spread over a band: the paper's undamped record shows
/// five 30 Hz apart), every other pole a run of its own.
fn combs(rejected: &[RejectedPole]) -> Vec<&[RejectedPole]> {
    let mut runs = Vec::new();
    let mut start = 0;
    while start < rejected.len() {
        let mut end = start + 1;
        while end < rejected.len() && rejected[end].reason == rejected[start].reason {
            let gap = rejected[end].frequency_hz - rejected[end - 1].frequency_hz;
            let first = rejected[start + 1].frequency_hz - rejected[start].frequency_hz;
            if !(0.5 * first..=2.0 * first).contains(&gap) {
                break;
            }
            end += 1;
        }
        if end - start < COMB {
            end = start + 1;
        }
        runs.push(&rejected[start..end]);
        start = end;
    }
    runs
}

/// The table rows of the identified modes.
fn mode_rows(s: &mut String, a: &FrfAnalysis) {
    let _ = writeln!(
        s,
        "{:>4}  {:>14}  {:>15}  {:>12}",
        "mode", "frequency [Hz]", "damping ratio %", "|H| at peak"
    );
    for (i, m) in a.fit.modes.iter().enumerate() {
        let (zeta, magnitude) = match (m.damping_bound, m.magnitude_lower_bound()) {
            (Some(bound), Some(h)) => (format!("< {:.4}", 100.0 * bound), format!("> {h:.4e}")),
            _ => (
                format!("{:.4}", 100.0 * m.damping_ratio),
                format!("{:.4e}", m.magnitude),
            ),
        };
        let _ = writeln!(
            s,
            "{:>4}  {:>14.3}  {:>15}  {:>12}",
            i + 1,
            m.frequency_hz,
            zeta,
            magnitude
        );
    }
    let no_peak: Vec<String> = (a.fit.modes.iter().enumerate())
        .filter(|(_, m)| !crate::measured::experiment::is_fitted_peak(&a.fit, m))
        .map(|(i, _)| (i + 1).to_string())
        .collect();
    if !no_peak.is_empty() {
        let _ = writeln!(
            s,
            "mode {} makes no peak of its own in the fitted |H| (its own term under half of |H| at its frequency, and no local maximum within its half-width): a term the fit needs beside another mode's peak, not a resonance the records show",
            no_peak.join(", ")
        );
    }
    let ringing: Vec<String> = (a.fit.modes.iter().enumerate())
        .filter(|(_, m)| m.damping_bound.is_some())
        .map(|(i, _)| (i + 1).to_string())
        .collect();
    if !ringing.is_empty() {
        let _ = writeln!(
            s,
            "damping not resolved for mode {}: it rings past the records' end with no decay they can measure, so only a bound is given (ζ + 3 standard errors, at least a 5 % decay over the record), and |H| at its peak, which goes as 1/ζ, only a lower bound; longer records, or an exponential window, measure them",
            ringing.join(", ")
        );
    }
    if let Some(e) = &a.estimate {
        if e.window_decay_rate > 0.0 {
            let _ = writeln!(
                s,
                "the exponential window's decay ({:.3} 1/s) is removed from the damping ratios",
                e.window_decay_rate
            );
        }
    }
}

/// CSV: frequency, |H1|, phase H1, |H2|, phase H2, coherence, |fit|.
pub fn frf_csv(a: &FrfAnalysis) -> String {
    let mut s = String::from("frequency_hz,h1_re,h1_im,h2_re,h2_im,coherence,fit_re,fit_im\n");
    for (k, f) in a.frequency_hz.iter().enumerate() {
        let h2 =
            a.h2.as_ref()
                .map_or(Complex64::new(f64::NAN, f64::NAN), |h| h[k]);
        let c = a.coherence.as_ref().map_or(f64::NAN, |c| c[k]);
        let fit = if *f >= a.band.0 && *f <= a.band.1 && !a.fit.modes.is_empty() {
            a.fit.evaluate(*f)
        } else {
            Complex64::new(f64::NAN, f64::NAN)
        };
        let _ = writeln!(
            s,
            "{f},{},{},{},{},{c},{},{}",
            a.h1[k].re, a.h1[k].im, h2.re, h2.im, fit.re, fit.im
        );
    }
    s.replace("NaN", "")
}

/// UFF 58: H1 (complex double) and, when there is one, the coherence (real
/// double), both on the even frequency abscissa.
pub fn frf_uff(a: &FrfAnalysis, q: ResponseQuantity, model_sha256: Option<&str>) -> String {
    let n = a.frequency_hz.len();
    let df = if n > 1 {
        a.frequency_hz[1] - a.frequency_hz[0]
    } else {
        0.0
    };
    let [tool, model] = crate::results::provenance::header_lines(model_sha256.unwrap_or("none"));
    let base = Function {
        id: [
            "H1".into(),
            tool,
            model,
            a.files
                .iter()
                .map(|f| f.display().to_string())
                .collect::<Vec<_>>()
                .join(" "),
            String::new(),
        ],
        function_type: FunctionType::Frf,
        response_entity: "response".into(),
        response_node: 1,
        response_direction: 2,
        reference_entity: "force".into(),
        reference_node: 1,
        reference_direction: 2,
        even: true,
        x_min: a.frequency_hz.first().copied().unwrap_or(0.0),
        dx: df,
        x: Vec::new(),
        abscissa_type: SpecDataType::FREQUENCY,
        abscissa_label: "Frequency".into(),
        abscissa_units: "Hz".into(),
        ordinate_type: q.uff_type(),
        ordinate_label: q.name().into(),
        ordinate_units: q.unit().into(),
        denominator_type: SpecDataType::FORCE,
        denominator_label: "force".into(),
        denominator_units: "N".into(),
        ordinate: Ordinate::Complex(
            a.h1.iter()
                .map(|c| {
                    if c.re.is_finite() {
                        *c
                    } else {
                        Complex64::new(0.0, 0.0)
                    }
                })
                .collect(),
        ),
        data_line: 0,
        lines: Vec::new(),
    };
    let mut s = String::new();
    d58::write(&mut s, &base);
    if let Some(c) = &a.coherence {
        let mut coh = base.clone();
        coh.id[0] = "coherence".into();
        coh.function_type = FunctionType::Coherence;
        coh.ordinate_type = SpecDataType::UNKNOWN;
        coh.ordinate_label = "coherence".into();
        coh.ordinate_units = "NONE".into();
        coh.denominator_type = SpecDataType::UNKNOWN;
        coh.denominator_label = "NONE".into();
        coh.denominator_units = "NONE".into();
        coh.ordinate = Ordinate::Real(
            c.iter()
                .map(|v| if v.is_finite() { *v } else { 0.0 })
                .collect(),
        );
        d58::write(&mut s, &coh);
    }
    s
}

/// FRF magnitude (dB re 1 FRF unit) and phase with the fitted model and the
/// identified modes, the coherence, and the stabilization diagram.
pub fn frf_figure(
    a: &FrfAnalysis,
    q: ResponseQuantity,
    overlay: Option<(&str, &[f64], &[Complex64])>,
) -> LineFigure {
    let h = a.fitted_frf();
    let shown = |f: &f64| *f > 0.0 && *f <= a.band.1 * 1.25;
    let idx: Vec<usize> = (0..a.frequency_hz.len())
        .filter(|&k| shown(&a.frequency_hz[k]))
        .collect();
    let fx: Vec<f64> = idx.iter().map(|&k| a.frequency_hz[k]).collect();
    let db = |c: Complex64| 20.0 * c.norm().log10();
    let mut mag = Panel::new("|H|", Scale::unit(format!("dB re 1 {}", q.frf_unit())));
    mag.series.push(Series::line(
        format!("measured {}", a.settings.estimator.name().to_uppercase()),
        fx.clone(),
        idx.iter().map(|&k| db(h[k])).collect(),
    ));
    let band: Vec<f64> = fx
        .iter()
        .copied()
        .filter(|f| *f >= a.band.0 && *f <= a.band.1)
        .collect();
    if !a.fit.modes.is_empty() {
        mag.series.push(Series::new(
            "fitted modal model",
            band.clone(),
            band.iter().map(|f| db(a.fit.evaluate(*f))).collect(),
            SeriesStyle::Reference,
        ));
    }
    if let Some((label, f, hm)) = overlay {
        mag.series.push(Series::line(
            label,
            f.to_vec(),
            hm.iter().map(|c| db(*c)).collect(),
        ));
    }
    for m in &a.fit.modes {
        let mut p = PointMarker::new(
            m.frequency_hz,
            20.0 * m.magnitude.log10(),
            format!(
                "{:.1} Hz, ζ {:.2} %",
                m.frequency_hz,
                100.0 * m.damping_ratio
            ),
        );
        p.shape = MarkerShape::Ring;
        p.colour = Some(1);
        mag.points.push(p);
    }
    mag.legend = Legend::Auto;
    let mut phase = Panel::new("Phase", Scale::unit("deg"));
    phase.series.push(Series::line(
        "",
        fx.clone(),
        idx.iter().map(|&k| h[k].arg().to_degrees()).collect(),
    ));
    phase.legend = Legend::None;
    phase.y_range = Some((-180.0, 180.0));
    let mut panels = vec![mag, phase];
    if let Some(c) = &a.coherence {
        let mut coh = Panel::new("Coherence", Scale::none());
        coh.series.push(Series::line(
            "γ²",
            fx.clone(),
            idx.iter().map(|&k| c[k]).collect(),
        ));
        coh.y_range = Some((0.0, 1.05));
        coh.legend = Legend::None;
        panels.push(coh);
    }
    let mut stab = Panel::new("Model order", Scale::none());
    for (name, kind, colour) in [
        ("stable pole", Stability::Stable, 2),
        ("stable frequency", Stability::Frequency, 4),
        ("new pole", Stability::New, 7),
    ] {
        let pts: Vec<_> = a
            .fit
            .diagram
            .iter()
            .filter(|p| p.stability == kind)
            .collect();
        if pts.is_empty() {
            continue;
        }
        let mut s = Series::new(
            name,
            pts.iter().map(|p| p.frequency_hz).collect(),
            pts.iter().map(|p| p.order as f64).collect(),
            SeriesStyle::Points,
        );
        s.colour = Some(colour);
        stab.series.push(s);
    }
    stab.vlines = a
        .fit
        .modes
        .iter()
        .map(|m| Guide::new(m.frequency_hz, ""))
        .collect();
    stab.legend = Legend::UpperLeft;
    if !stab.series.is_empty() {
        panels.push(stab);
    }
    let mut fig = LineFigure::new(
        format!(
            "FRF {} ({} hit(s)) and modal fit",
            a.settings.estimator.name().to_uppercase(),
            a.estimate.as_ref().map_or(1, |e| e.averages)
        ),
        "Frequency",
        Scale::hz(),
    );
    fig.x_range = fx.first().zip(fx.last()).map(|(a, b)| (*a, *b));
    fig.panels = panels;
    fig
}
