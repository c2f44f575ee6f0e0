//! The `frf` pipeline as one call: measurement files → averaged H1, H2 and
//! coherence (or an FRF read as such) → the band the hammer excited → the
//! modal fit ([`crate::signal::fit`]) of the chosen estimator.
//!
//! Default band: [`super::band::automatic_band`] (the force drop, the
//! noise floor of the quiet tail, 0.8 × Nyquist, whichever comes first).
//!
//! No silent loss: the spectrum outside the band (up to the automatic
//! band's end) is fitted too, and the modes found there are listed in [`FrfAnalysis::rejected`] as outside the
//! band, beside the fit's own rejected poles.

use std::path::PathBuf;

use realfft::num_complex::Complex64;

use super::band::automatic_band;
pub use super::band::BandEnd;
use super::frf::{estimate, FrfEstimate};
use super::{record_checks, MeasuredError, Measurement, TimeRecord};
use crate::signal::fit::{
    fit, fit_records, FitSettings, FittedMode, ModalFit, PoleBasis, Records, RejectReason,
    RejectedPole,
};
use crate::signal::Window;

/// Which estimator the fit uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Estimator {
    /// G_fx/G_ff: unbiased by response noise (the usual choice).
    #[default]
    H1,
    /// G_xx/G_xf: unbiased by force noise, better at resonances when
    /// leakage or force noise dominates.
    H2,
}

impl Estimator {
    pub fn name(self) -> &'static str {
        match self {
            Estimator::H1 => "h1",
            Estimator::H2 => "h2",
        }
    }
}

/// Settings of [`analyse`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnalysisSettings {
    pub window: Window,
    pub estimator: Estimator,
    /// Fit band, Hz; `None` picks it (module doc).
    pub band: Option<(f64, f64)>,
    /// Highest LSCF order.
    pub max_order: usize,
}

impl Default for AnalysisSettings {
    fn default() -> Self {
        AnalysisSettings {
            window: Window::Rectangular,
            estimator: Estimator::H1,
            band: None,
            max_order: 40,
        }
    }
}

pub use super::band::FORCE_BAND_DB;

/// The result of [`analyse`].
#[derive(Debug, Clone)]
pub struct FrfAnalysis {
    pub files: Vec<PathBuf>,
    /// The (force, response) channel names of each time record, in file
    /// order (none for an FRF read from a file).
    pub channels: Vec<[String; 2]>,
    pub frequency_hz: Vec<f64>,
    pub h1: Vec<Complex64>,
    /// H2 and the coherence exist for time records (and the coherence for
    /// a UFF FRF that carries one).
    pub h2: Option<Vec<Complex64>>,
    pub coherence: Option<Vec<f64>>,
    /// The spectral estimate (time records only).
    pub estimate: Option<FrfEstimate>,
    pub settings: AnalysisSettings,
    /// What the response measures, as an FRF file says (none for records:
    /// their channels' names say it).
    pub file_quantity: Option<super::ResponseQuantity>,
    pub band: (f64, f64),
    /// What ended the band.
    pub band_end: BandEnd,
    pub fit: ModalFit,
    /// Stable poles that are not modes: the fit's own and the modes found
    /// outside the band, by frequency.
    pub rejected: Vec<RejectedPole>,
    /// What the user must know of the input: a given band cut at the
    /// data's last line, and what the records themselves show
    /// ([`super::record_checks`]): slow sampling, channels that look
    /// swapped, noise on the force, records too short for the fit, modes
    /// whose residue the records do not determine.
    pub notes: Vec<String>,
}

impl FrfAnalysis {
    /// What the user must know beside the table: a taper on impact records
    /// (its damping is the window's, not the structure's), then the
    /// analysis' notes ([`FrfAnalysis::notes`]).
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if is_taper(self.settings.window) && self.estimate.is_some() {
            out.push(format!(
                "the {} window tapers the blow and the start of the decay of impact records: the fitted poles carry the window's broadening, not the structure's damping (rect, force:P or exponential:P suit a hammer test)",
                self.settings.window
            ));
        }
        out.extend(self.notes.iter().cloned());
        out
    }

    /// The estimator the fit used.
    pub fn fitted_frf(&self) -> &[Complex64] {
        match (self.settings.estimator, &self.h2) {
            (Estimator::H2, Some(h2)) => h2,
            _ => &self.h1,
        }
    }
}

/// What the records show beside the fit ([`record_checks`]): sampling too
/// slow for a hammer test, channels that look swapped, and, but under a
/// taper (whose own warning says the blow is cut, so these follow from
/// it), noise on the force, records too short for any mode, and modes
/// whose residue the records do not determine (`untied`). No mode found
/// is put down to the records' length unless `outside_dominates`: a mode
/// outside the band that stands above it is the likelier cause
/// ([`dominant_outside_note`]).
fn record_notes(
    records: &[TimeRecord],
    est: Option<&FrfEstimate>,
    settings: &AnalysisSettings,
    band: (f64, f64),
    (fit, outside_dominates): (&ModalFit, bool),
    untied: &[FittedMode],
) -> Vec<String> {
    let mut notes: Vec<String> = record_checks::slow_sampling(records)
        .into_iter()
        .chain(record_checks::swapped_channels(records))
        .collect();
    if !is_taper(settings.window) {
        notes.extend(est.and_then(|e| record_checks::force_noise_note(records, e, band)));
        if !outside_dominates {
            notes.extend(record_checks::short_records(records, fit.modes.len()));
        }
        notes.extend(est.and_then(|e| record_checks::ringing_at_end(untied, e)));
    }
    notes
}

/// A cosine window, which tapers an impact record's blow away.
fn is_taper(window: Window) -> bool {
    matches!(window, Window::Hann | Window::FlatTop | Window::Blackman)
}

/// Smallest width of a stretch outside the band worth fitting, in bins.
const MIN_OUTSIDE_BINS: usize = 16;

/// The modes of the spectrum outside `band` (below it, and above it up to
/// `top`, the end of the automatic band: beyond it H is noise), as
/// rejected poles; a pole within 0.5 % of one of `modes` (a mode at the
/// band's edge) is left out. With them, the (frequency [Hz], |H| at the
/// peak) of each.
fn outside_band(
    frequency_hz: &[f64],
    h: &[Complex64],
    (band, top): ((f64, f64), f64),
    fit_settings: &FitSettings,
    modes: &[f64],
) -> (Vec<RejectedPole>, Vec<(f64, f64)>) {
    let first = frequency_hz.get(1).copied().unwrap_or(0.0);
    let bins = |lo: f64, hi: f64| {
        frequency_hz
            .iter()
            .filter(|f| **f >= lo && **f <= hi)
            .count()
    };
    let (mut out, mut peaks) = (Vec::new(), Vec::new());
    for (lo, hi) in [(first, band.0), (band.1, top)] {
        if hi <= lo || bins(lo, hi) < MIN_OUTSIDE_BINS {
            continue;
        }
        let outside = fit(
            frequency_hz,
            h,
            &FitSettings {
                f_lo: lo,
                f_hi: hi,
                ..*fit_settings
            },
        );
        for m in &outside.modes {
            let f = m.frequency_hz;
            if modes.iter().any(|g| (f - g).abs() <= 0.005 * g) {
                continue;
            }
            out.push(RejectedPole {
                frequency_hz: f,
                damping_ratio: m.damping_ratio,
                reason: RejectReason::OutsideBand,
            });
            peaks.push((f, m.magnitude));
        }
    }
    (out, peaks)
}

/// A mode outside the band whose peak |H| exceeds everything in it: its
/// tail across the band (and, for records, the leakage of its decay cut
/// off at their end) enters the band's fit through the residual terms
/// alone, which do not follow it. The trial's noise-free records with a
/// 12 Hz or 20 Hz mode 96–1419 × the others: a band of 100–1500 Hz gave
/// ζ −8.6 % and called clean modes not significant; 400–3000 Hz found no
/// mode. Said, not fitted: a band that holds it fits them.
fn dominant_outside_note(
    frequency_hz: &[f64],
    h: &[Complex64],
    band: (f64, f64),
    peaks: &[(f64, f64)],
) -> Option<String> {
    let largest = frequency_hz
        .iter()
        .zip(h)
        .filter(|(f, v)| **f >= band.0 && **f <= band.1 && v.norm().is_finite())
        .fold(0.0_f64, |m, (_, v)| m.max(v.norm()));
    let strong: Vec<String> = peaks
        .iter()
        .filter(|(_, a)| largest > 0.0 && *a > largest)
        .map(|(f, a)| format!("{f:.3} Hz ({:.0} ×)", a / largest))
        .collect();
    (!strong.is_empty()).then(|| {
        format!(
            "the mode{} at {} outside the fit band {:.1}–{:.1} Hz stand{} above the band's largest |H| ({largest:.4e}): {} tail across the band is fitted by the residual terms alone, which do not follow it, and can bias the band's modes or hide them; a fit band that holds {} fits them",
            if strong.len() > 1 { "s" } else { "" },
            strong.join(", "),
            band.0,
            band.1,
            if strong.len() > 1 { "" } else { "s" },
            if strong.len() > 1 { "their" } else { "its" },
            if strong.len() > 1 { "them" } else { "it" },
        )
    })
}

/// Runs the pipeline on the measurements of one test (several hits, or
/// one FRF).
///
/// # Panics
/// If `measurements` is empty.
pub fn analyse(
    measurements: Vec<Measurement>,
    settings: AnalysisSettings,
) -> Result<FrfAnalysis, MeasuredError> {
    assert!(!measurements.is_empty(), "analyse needs a measurement");
    let files: Vec<PathBuf> = measurements
        .iter()
        .map(|m| match m {
            Measurement::Time(r) => r.file.clone(),
            Measurement::Frf(f) => f.file.clone(),
        })
        .collect();
    let mut records = Vec::new();
    let mut file_quantity = None;
    let (frequency_hz, h1, h2, coherence, est) =
        if measurements.len() == 1 && matches!(measurements[0], Measurement::Frf(_)) {
            let Some(Measurement::Frf(f)) = measurements.into_iter().next() else {
                unreachable!("checked above")
            };
            file_quantity = f.quantity;
            (f.frequency_hz, f.h, None, f.coherence, None)
        } else {
            records = Vec::with_capacity(measurements.len());
            for m in measurements {
                match m {
                    Measurement::Time(r) => records.push(r),
                    Measurement::Frf(f) => return Err(MeasuredError::MixedKinds { file: f.file }),
                }
            }
            let e = estimate(&records, settings.window)?;
            (
                e.frequency_hz.clone(),
                e.h1.clone(),
                Some(e.h2.clone()),
                Some(e.coherence.clone()),
                Some(e),
            )
        };
    let (automatic, automatic_end) = automatic_band(
        &frequency_hz,
        est.as_ref().map(|e| e.force_power.as_slice()),
        &records,
    );
    let mut notes = Vec::new();
    let last = frequency_hz.last().copied().unwrap_or(0.0);
    let (band, band_end) = match settings.band {
        Some((lo, _)) if lo >= last => {
            return Err(MeasuredError::BandPastData {
                file: files[0].clone(),
                lo_hz: lo,
                last_hz: last,
            })
        }
        Some((lo, hi)) if hi > last * (1.0 + 1e-9) => {
            notes.push(format!(
                "the fit band {lo:.1}–{hi:.1} Hz reaches past the data's last line: fitted over {lo:.1}–{last:.1} Hz"
            ));
            ((lo, last), BandEnd::Given)
        }
        Some(b) => (b, BandEnd::Given),
        None => (automatic, automatic_end),
    };
    let h = match (settings.estimator, &h2) {
        (Estimator::H2, Some(h2)) => h2,
        _ => &h1,
    };
    let fit_settings = FitSettings {
        f_lo: band.0,
        f_hi: band.1,
        max_order: settings.max_order,
        window_decay_rate: est.as_ref().map_or(0.0, |e| e.window_decay_rate),
        basis: est
            .as_ref()
            .map_or(PoleBasis::Continuous, |e| PoleBasis::Filtered {
                interval_s: 1.0 / e.sample_rate_hz,
            }),
    };
    let fit = match &est {
        Some(e) => fit_records(
            &frequency_hz,
            h,
            Records {
                truncation: &e.truncation_weight,
                force_power: &e.force_power,
                duration_s: e.samples as f64 / e.sample_rate_hz,
            },
            &fit_settings,
        ),
        None => fit(&frequency_hz, h, &fit_settings),
    };
    let mut fit = fit;
    let undetermined = match &est {
        Some(e) => super::cut_off::tie_residues(&mut fit, &records, e, h),
        None => Vec::new(),
    };
    let mut untied: Vec<_> = undetermined.iter().map(|&j| fit.modes[j]).collect();
    // The tied residues tell a nonlinear response's terms from modes.
    if let Some(e) = &est {
        fit.set_apart_harmonics(e.df());
        untied.retain(|u| fit.modes.iter().any(|m| m.pole == u.pole));
    }
    let found: Vec<f64> = fit.modes.iter().map(|m| m.frequency_hz).collect();
    let mut rejected = fit.rejected.clone();
    let (outside, outside_peaks) =
        outside_band(&frequency_hz, h, (band, automatic.1), &fit_settings, &found);
    rejected.extend(outside);
    let dominant = dominant_outside_note(&frequency_hz, h, band, &outside_peaks);
    rejected.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    // Two seeds the refinement took to one pole (to its own tolerance:
    // 1.5e-8 apart in ζ were seen) are one pole.
    rejected.dedup_by(|a, b| {
        a.reason == b.reason
            && (a.frequency_hz - b.frequency_hz).abs() <= 1e-6 * b.frequency_hz
            && (a.damping_ratio - b.damping_ratio).abs() <= 1e-4 * b.damping_ratio
    });
    notes.extend(record_notes(
        &records,
        est.as_ref(),
        &settings,
        band,
        (&fit, dominant.is_some()),
        &untied,
    ));
    notes.extend(dominant);
    Ok(FrfAnalysis {
        files,
        channels: records
            .iter()
            .map(|r| [r.force_label.clone(), r.response_label.clone()])
            .collect(),
        frequency_hz,
        h1,
        h2,
        coherence,
        estimate: est,
        settings,
        file_quantity,
        band,
        band_end,
        notes,
        fit,
        rejected,
    })
}
