//! Figures of the impulse experiment ([`crate::analysis::impulse`]).
//!
//! * [`response_figure`] — the sensor signal against time [SI: s, shown in
//!   ms] with its quantity and unit (displacement [m], velocity [m/s] or
//!   acceleration [m/s²], shown with the SI prefix that makes the largest
//!   value a number in 1…1000, e.g. mm/s or µm), over the applied half-sine
//!   force pulse F(t) [N] in a second panel on the same time axis; below
//!   them the same two panels zoomed on up to [`ZOOM_PERIODS`] periods of
//!   the first bending mode from the blow (2.2 ms for the paper's assembly:
//!   the pulse and the first oscillations, which a 100 ms record shows only
//!   as a solid band), within a quarter of the record ([`zoom_window`]; its
//!   title says what it covers).
//! * [`spectrum_figure`] — the amplitude spectrum 20·log₁₀|X(f)| [dB re 1
//!   signal unit] from 0 to the Nyquist frequency f_s/2 [SI: Hz, shown in
//!   kHz]: the identified peaks marked and labelled with their frequency,
//!   the computed eigenfrequencies of the elastic modes as grey guide lines
//!   ("f4 = 4568.9 Hz"; rigid modes have f = 0 and are left out), the
//!   measured first bending frequency of the model's reference (4600 Hz for
//!   the paper's assembly) as the dashed reference line, and the identified
//!   first bending peak labelled with its raw FFT value and the value
//!   corrected for the integrator's period error.
//!
//! [`write_impulse_figures`] writes both, the spectrum to the given path
//! and the response beside it ([`response_path`]).

use super::write::write_figure;
use crate::analysis::impulse::ImpulseResult;
use crate::model::{Model, SensorQuantity};
use crate::output::plot::{
    Figure, Guide, Legend, LineFigure, MarkerShape, Panel, PlotError, PlotSize, PointMarker, Scale,
    Series, StackedFigure,
};
use std::path::{Path, PathBuf};

/// Decibels shown below the highest spectral level (the window's side
/// lobes and round-off lie far below; 100 dB keeps every resonance).
const DB_SHOWN: f64 = 100.0;

/// Name and SI unit of a sensor quantity.
fn quantity_name(q: SensorQuantity) -> (&'static str, &'static str) {
    match q {
        SensorQuantity::Displacement => ("Displacement", "m"),
        SensorQuantity::Velocity => ("Velocity", "m/s"),
        SensorQuantity::Acceleration => ("Acceleration", "m/s²"),
    }
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter()
        .filter(|x| x.is_finite())
        .fold(0.0, |m, x| m.max(x.abs()))
}

/// Most periods of the first bending mode the zoomed panels show.
pub const ZOOM_PERIODS: f64 = 10.0;
/// Longest zoom as a fraction of the record: a longer one shows nothing
/// the whole record does not.
const ZOOM_MOST: f64 = 0.25;
/// Fewest whole periods worth a zoom.
const ZOOM_FEWEST: f64 = 2.0;

/// The zoomed window: its start and end [SI: s] and what it covers, as
/// its title says it. Up to [`ZOOM_PERIODS`] whole periods of the first
/// bending eigenfrequency, counted from the blow at t = 0 (or the record's
/// start after it), within a quarter of the record; without a bending
/// mode, 2 % of the record. `None` when fewer than two periods fit.
pub fn zoom_window(result: &ImpulseResult) -> Option<(f64, f64, String)> {
    let t0 = result.time.first().copied()?;
    let t1 = result.time.last().copied()?;
    let start = t0.max(0.0);
    let record = t1 - t0;
    let (span, what) = match result.modal.first_bending() {
        Some(m) if m.frequency_hz > 0.0 => {
            let fit = (ZOOM_MOST * record * m.frequency_hz).floor();
            let periods = ZOOM_PERIODS.min(fit);
            if periods < ZOOM_FEWEST {
                return None;
            }
            (
                periods / m.frequency_hz,
                format!(
                    "{periods:.0} periods of the first bending mode ({:.1} Hz)",
                    m.frequency_hz
                ),
            )
        }
        _ => (0.02 * record, "2 % of the record".to_string()),
    };
    let end = start + span;
    (end < t1 && end > t0).then(|| {
        let title = format!(
            "{:.3} to {:.3} ms: {what}, from the blow",
            1e3 * t0,
            1e3 * end
        );
        (t0, end, title)
    })
}

/// The signal and force panels over the samples up to `end` (and one
/// beyond, so the curves reach the edge).
fn response_panels(result: &ImpulseResult, end: f64) -> Vec<Panel> {
    let n = result.time.partition_point(|&t| t <= end);
    let n = (n + 1).min(result.time.len());
    let time = &result.time[..n];
    let (name, unit) = quantity_name(result.quantity);
    let mut signal = Panel::new(name, Scale::si(unit, max_abs(&result.signal[..n])));
    signal.series.push(Series::line(
        format!("sensor {}", result.sensor),
        time.to_vec(),
        result.signal[..n].to_vec(),
    ));
    // A long record fills the panel; the title names the sensor.
    signal.legend = Legend::None;
    let mut force = Panel::new("Force", Scale::unit("N"));
    force.series.push(Series::line(
        "force pulse",
        time.to_vec(),
        result.force[..n].to_vec(),
    ));
    force.legend = Legend::UpperRight;
    vec![signal, force]
}

/// Sensor signal over the force pulse, against time in ms: the whole
/// record, and below it the window of [`zoom_window`].
pub fn response_figure(model_name: &str, result: &ImpulseResult) -> Figure {
    let t1 = result.time.last().copied().unwrap_or(0.0);
    let mut whole = LineFigure::new(
        format!("Impulse response: {model_name}, sensor {}", result.sensor),
        "Time",
        Scale::ms(),
    );
    whole.panels = response_panels(result, t1);
    let Some((t0, end, title)) = zoom_window(result) else {
        return whole.into();
    };
    let mut zoom = LineFigure::new(title, "Time", Scale::ms());
    zoom.x_range = Some((t0, end));
    zoom.panels = response_panels(result, end);
    // The whole record's force panel above names the curve.
    zoom.panels[1].legend = Legend::None;
    StackedFigure {
        parts: vec![whole, zoom],
    }
    .into()
}

/// Amplitude of a peak in dB re 1 signal unit.
fn db(magnitude: f64) -> f64 {
    20.0 * magnitude.log10()
}

/// Amplitude spectrum with peaks, eigenfrequencies and the reference.
pub fn spectrum_figure(model: &Model, result: &ImpulseResult) -> LineFigure {
    let (_, unit) = quantity_name(result.quantity);
    let spec = &result.spectrum;
    let level = spec.magnitude_db();
    let nyquist = 0.5 * result.sample_rate_hz;
    let mut panel = Panel::new("Amplitude", Scale::unit(format!("dB re 1 {unit}")));
    let top = level.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let bottom = level.iter().copied().fold(f64::INFINITY, f64::min);
    if top.is_finite() && bottom.is_finite() {
        // Room above the highest peak for the stacked labels.
        let hi = (top / 10.0).ceil() * 10.0 + 30.0;
        let lo = ((top - DB_SHOWN) / 10.0).floor() * 10.0;
        panel.y_range = Some((lo.max((bottom / 10.0).floor() * 10.0), hi));
    }
    panel.series.push(Series::line(
        format!("spectrum ({} window)", spec.window),
        spec.frequency_hz.clone(),
        level,
    ));
    // Upper right: above the aliased high modes, clear of the peaks' feet.
    panel.legend = Legend::UpperRight;
    panel.vlines = result
        .modal
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero() && m.frequency_hz <= nyquist)
        .map(|m| {
            Guide::new(
                m.frequency_hz,
                format!("f{} = {:.1} Hz", m.index, m.frequency_hz),
            )
        })
        .collect();
    if let Some(r) = &model.reference {
        panel.vlines.push(Guide::reference(
            r.first_bending_hz,
            format!("experiment {:.0} Hz", r.first_bending_hz),
        ));
    }
    let first = result.first_bending;
    // The listed peak that is the identified first bending one (same
    // interpolated frequency), if any.
    let first_peak = first.and_then(|fb| {
        result
            .peaks
            .iter()
            .position(|p| (p.frequency_hz - fb.raw_hz).abs() <= 1e-9 * fb.raw_hz)
    });
    for (i, p) in result.peaks.iter().enumerate() {
        if Some(i) == first_peak {
            continue;
        }
        let mut m = PointMarker::new(
            p.frequency_hz,
            db(p.magnitude),
            format!("{:.0} Hz", p.frequency_hz),
        );
        m.colour = Some(0);
        panel.points.push(m);
    }
    if let Some(fb) = first {
        let level = match first_peak {
            Some(i) => db(result.peaks[i].magnitude),
            None => peak_level(result, fb.raw_hz),
        };
        let mut m = PointMarker::new(
            fb.raw_hz,
            level,
            format!(
                "1st bending: {:.1} Hz (corrected {:.1} Hz)",
                fb.raw_hz, fb.corrected_hz
            ),
        );
        m.shape = MarkerShape::Square;
        m.colour = Some(5);
        panel.points.push(m);
    }
    let mut fig = LineFigure::new(
        format!(
            "Spectrum: {}, sensor {} ({})",
            model.name,
            result.sensor,
            quantity_name(result.quantity).0.to_lowercase()
        ),
        "Frequency",
        Scale::khz(),
    );
    fig.x_range = Some((0.0, nyquist));
    fig.panels = vec![panel];
    fig
}

/// Spectral level [dB] at the bin nearest to `f_hz`.
fn peak_level(result: &ImpulseResult, f_hz: f64) -> f64 {
    let s = &result.spectrum;
    let k = ((f_hz / s.df).round() as usize).min(s.magnitude.len().saturating_sub(1));
    s.magnitude.get(k).map_or(f64::NAN, |&m| db(m))
}

/// `spectrum.svg` → `spectrum.response.svg`: where `--plot` puts the
/// response figure beside the spectrum.
pub fn response_path(plot: &Path) -> PathBuf {
    let stem = plot
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = plot
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    plot.with_file_name(format!("{stem}.response{ext}"))
}

/// Writes the spectrum figure to `spectrum` and the response figure to
/// `response` (format from each extension, `.svg` or `.png`).
pub fn write_impulse_figures(
    model: &Model,
    result: &ImpulseResult,
    spectrum: &Path,
    response: &Path,
    size: PlotSize,
) -> Result<(), PlotError> {
    write_figure(&spectrum_figure(model, result).into(), spectrum, size)?;
    write_figure(&response_figure(&model.name, result), response, size)
}
