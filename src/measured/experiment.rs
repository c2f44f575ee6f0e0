//! The measured mode `identify` takes as the experiment, and the checks of
//! that mode against the records it was fitted to.
//!
//! **Which mode.** A hammer test's first bending mode is a peak of the
//! records' spectrum. The modal fit ([`crate::signal::fit`]) reports every
//! pole its own tests keep, and a pole can pass them while it makes no
//! peak at all: it stands for a structure of the misfit the other terms
//! leave. The built-in assembly's `impulse --end-time 0.05` records
//! (exponential:0.01 window, 3000–6000 Hz): one build's records gave one
//! mode, 4568.611 Hz; another build's, which differ from them by 5.3e-6 of
//! their largest value (the transient's Newton tolerance), gave a second
//! pole at 4401.364 Hz (LSCF seed 4354 Hz, refined to 4361 Hz, polished to
//! 4401 Hz), |R| 4.3e-6 of the first mode's. Taken as the mode nearest the
//! cantilever's first bending frequency (1071.6 Hz), it became
//! `experiment_hz`, 167 Hz off, with no warning; the spectrum has no peak
//! there (its only one in the band is at 4568.5 Hz).
//!
//! So a mode is a candidate only when it *is* the peak the fitted model
//! shows at its frequency: its own term R g(ω, s) + R̄ g(ω, s̄) makes at
//! least [`PEAK_SHARE`] of |Ĥ| at its damped frequency ([`peak_share`]).
//! The pole above makes 1.7e-5 of it, the 4568.6 Hz mode 1.0. A weak mode
//! on a strong one's skirt can make less than that and still its own peak
//! (a local maximum of |Ĥ| within its half-width: [`makes_fitted_peak`]);
//! it is a candidate too (a new user's weak 5.8 Hz mode beside a strong
//! 15 Hz one was passed over for the 15 Hz one without a word). The
//! experiment is the candidate nearest the model's first bending frequency
//! ([`choose`]); with no candidate, the nearest mode (and the checks below
//! say what is wrong with it). Modes passed over stay in the fit's list.
//! A chosen mode nearer another of the model's modes than its first
//! bending measures that mode, and is no experiment
//! ([`crate::results::identify::measured_mode`]).
//!
//! **Checks** ([`check`]): the records themselves, beside the fit.
//! - The records' |H| must peak at the mode: the local maximum reached
//!   from the mode's line by climbing |H|, placed between lines by a
//!   parabola through ln|H| at three lines, must lie within one line
//!   spacing Δf plus the windowed mode's half-power half-width σ/2π [Hz]
//!   of the mode's damped frequency (a peak's own noise, leakage and a
//!   neighbour's slope move it less).
//! - The fit must follow the records around the mode: the RMS of the
//!   fit's own misfit (the fitted poles, their residues, cut-off decays and
//!   residual terms solved again by least squares, each line weighted as
//!   the fit weights it) over the mode's half-power band and
//!   [`CHECK_LINES`] lines beside it, relative to the RMS of the weighted
//!   |H| there, must stay under [`MAX_MISFIT`].
//!
//! Either failing is a warning: the printed frequency is then not what the
//! records show to its printed digits.
//!
//! Units: frequencies in Hz, decay rates in 1/s, |H| in the FRF's unit.

use std::f64::consts::PI;

use realfft::num_complex::Complex64;

use super::analysis::FrfAnalysis;
use crate::signal::fit::{BandData, FittedMode, ModalFit, Records};
use crate::signal::lsfd;

/// Smallest share of |Ĥ| at a mode's damped frequency that its own term
/// must make for the mode to be the experiment [–]: the mode is then what
/// the fitted spectrum is at that frequency, not a term beside another
/// mode's peak or the residual terms.
pub const PEAK_SHARE: f64 = 0.5;

/// Largest RMS misfit of the fit around the experiment's mode, relative to
/// the RMS |H| there [–], before a warning.
pub const MAX_MISFIT: f64 = 0.1;

/// Lines beside the mode's half-power band over which its misfit is
/// measured [–].
pub const CHECK_LINES: f64 = 2.0;

/// The mode's damped frequency ω_d/2π [Hz].
fn damped_hz(mode: &FittedMode) -> f64 {
    mode.pole.im / (2.0 * PI)
}

/// The mode's half-power half-width in the windowed FRF, σ/2π [Hz] (the
/// window's decay rate `window_decay_rate` [1/s] added to the structure's).
fn half_width_hz(mode: &FittedMode, window_decay_rate: f64) -> f64 {
    (window_decay_rate - mode.pole.re).max(0.0) / (2.0 * PI)
}

/// The share of |Ĥ| (all of the fit's terms, [`ModalFit::evaluate`]) that
/// `mode`'s own term makes at its damped frequency [–] (0 where |Ĥ| is not
/// a positive number).
pub fn peak_share(fit: &ModalFit, mode: &FittedMode) -> f64 {
    let f = damped_hz(mode);
    let windowed = mode.pole - fit.settings.window_decay_rate;
    let own = fit.settings.basis.pair(f, windowed, mode.residue).norm();
    let total = fit.evaluate(f).norm();
    if total > 0.0 && total.is_finite() && own.is_finite() {
        own / total
    } else {
        0.0
    }
}

/// Samples of |Ĥ| per half-width across the window [`makes_fitted_peak`]
/// searches [–].
const PEAK_SAMPLES: usize = 16;

/// Whether the fitted |Ĥ| ([`ModalFit::evaluate`]) has a local maximum
/// within the mode's windowed half-power half-width of its damped
/// frequency: a weak mode beside a strong one can make its own peak on the
/// strong mode's skirt while its own term is less than half of |Ĥ| there
/// (a 5.8 Hz mode of 0.005 the amplitude of a 15 Hz one). A pole that only
/// bends the skirt (the 4401 Hz pole of the module doc) makes none.
pub fn makes_fitted_peak(fit: &ModalFit, mode: &FittedMode) -> bool {
    let f = damped_hz(mode);
    let reach = half_width_hz(mode, fit.settings.window_decay_rate);
    if !(reach > 0.0 && f.is_finite()) {
        return false;
    }
    let step = reach / PEAK_SAMPLES as f64;
    let count = 2 * PEAK_SAMPLES + 2;
    let at = |k: usize| f - reach - step + k as f64 * step;
    let mag: Vec<f64> = (0..=count).map(|k| fit.evaluate(at(k)).norm()).collect();
    (1..count).any(|k| {
        (at(k) - f).abs() <= reach
            && mag[k] > mag[k - 1]
            && mag[k] >= mag[k + 1]
            && mag[k].is_finite()
    })
}

/// Whether the mode is a peak of the fitted spectrum: its own term makes
/// at least [`PEAK_SHARE`] of |Ĥ| at its frequency, or |Ĥ| has its own
/// local maximum there ([`makes_fitted_peak`]).
pub fn is_fitted_peak(fit: &ModalFit, mode: &FittedMode) -> bool {
    peak_share(fit, mode) >= PEAK_SHARE || makes_fitted_peak(fit, mode)
}

/// The index in `fit.modes` of the experiment's mode: the mode nearest
/// `near_hz` among those that are a peak of the fitted spectrum
/// ([`is_fitted_peak`]), or among all when none is (module doc); `None`
/// without modes.
pub fn choose(fit: &ModalFit, near_hz: f64) -> Option<usize> {
    let distance = |j: usize| (fit.modes[j].frequency_hz - near_hz).abs();
    let nearest = |modes: Vec<usize>| {
        modes
            .into_iter()
            .min_by(|&a, &b| distance(a).total_cmp(&distance(b)))
    };
    let all: Vec<usize> = (0..fit.modes.len()).collect();
    let peaks = (all.iter().copied())
        .filter(|&j| is_fitted_peak(fit, &fit.modes[j]))
        .collect();
    nearest(peaks).or_else(|| nearest(all))
}

/// What the records say of one fitted mode ([`check`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ModeCheck {
    /// The mode's undamped frequency, as reported [Hz].
    pub frequency_hz: f64,
    /// Its damped frequency [Hz].
    pub damped_hz: f64,
    /// [`peak_share`] [–].
    pub share: f64,
    /// [`makes_fitted_peak`].
    pub fitted_peak: bool,
    /// The records' own peak of |H| nearest the mode [Hz]; `None` when
    /// |H| climbs to the end of the spectrum from there.
    pub spectrum_peak_hz: Option<f64>,
    /// How far that peak may lie from `damped_hz`: one line spacing and
    /// the windowed half-power half-width [Hz].
    pub peak_tolerance_hz: f64,
    /// RMS misfit of the fit around the mode over the RMS |H| there [–].
    pub misfit: f64,
}

impl ModeCheck {
    /// Whether the records' |H| peaks at the mode.
    pub fn at_spectrum_peak(&self) -> bool {
        self.spectrum_peak_hz
            .is_some_and(|p| (p - self.damped_hz).abs() <= self.peak_tolerance_hz)
    }

    /// The warnings of the mode taken as the experiment (module doc):
    /// none when it is a peak of the fit and of the records and the fit
    /// follows them.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        let f = self.frequency_hz;
        if self.share < PEAK_SHARE && !self.fitted_peak {
            out.push(format!(
                "no measured mode makes its own peak of the fitted |H| (its own term at least {PEAK_SHARE} of |H| at its frequency): the experiment is the fitted mode nearest the model's first bending frequency, {f:.3} Hz, whose own term makes {:.2e} of |H| there; a fit band (--measured-band) around the first bending peak fits it",
                self.share
            ));
        }
        if !self.at_spectrum_peak() {
            let seen = match self.spectrum_peak_hz {
                Some(p) => format!("its nearest peak is at {p:.3} Hz"),
                None => String::from("|H| has no peak near it"),
            };
            out.push(format!(
                "the measured mode taken as the experiment, {f:.3} Hz, is not a peak of the records' |H|: {seen}, more than {:.3} Hz (a line and the peak's half-power half-width) away; the fitted frequency is not what the spectrum shows: check the fit band (--measured-band) and the window (--measured-window)",
                self.peak_tolerance_hz
            ));
        }
        if self.misfit.is_nan() || self.misfit > MAX_MISFIT {
            out.push(format!(
                "the modal fit misses the records' |H| by {:.1} % (RMS) around the measured mode taken as the experiment, {f:.3} Hz, more than {:.0} %: its frequency is not what the records show to the digits printed; check the fit band (--measured-band) and the window (--measured-window)",
                100.0 * self.misfit,
                100.0 * MAX_MISFIT
            ));
        }
        out
    }
}

/// The records' checks of `analysis`'s fitted mode `index` (module doc).
///
/// # Panics
/// If `index` is not a mode of the fit.
pub fn check(analysis: &FrfAnalysis, index: usize) -> ModeCheck {
    let fit = &analysis.fit;
    let mode = &fit.modes[index];
    let h = analysis.fitted_frf();
    let f = &analysis.frequency_hz;
    let line = match f.as_slice() {
        [a, b, ..] => b - a,
        _ => 0.0,
    };
    let half = half_width_hz(mode, fit.settings.window_decay_rate);
    ModeCheck {
        frequency_hz: mode.frequency_hz,
        damped_hz: damped_hz(mode),
        share: peak_share(fit, mode),
        fitted_peak: makes_fitted_peak(fit, mode),
        spectrum_peak_hz: spectrum_peak(f, h, damped_hz(mode)),
        peak_tolerance_hz: line + half,
        misfit: misfit(analysis, damped_hz(mode), half + CHECK_LINES * line),
    }
}

/// The local maximum of |h| reached from the line nearest `f_hz` by
/// climbing to the larger neighbour, placed between lines by a parabola
/// through ln|h| at it and its neighbours [Hz]; `None` when the climb ends
/// at the first or last line (or without three usable lines).
pub fn spectrum_peak(frequency_hz: &[f64], h: &[Complex64], f_hz: f64) -> Option<f64> {
    let n = frequency_hz.len().min(h.len());
    let mag = |k: usize| {
        let m = h[k].norm();
        if m.is_finite() {
            m
        } else {
            0.0
        }
    };
    let mut k = (0..n).min_by(|&a, &b| {
        (frequency_hz[a] - f_hz)
            .abs()
            .total_cmp(&(frequency_hz[b] - f_hz).abs())
    })?;
    loop {
        let left = if k > 0 { mag(k - 1) } else { 0.0 };
        let right = if k + 1 < n { mag(k + 1) } else { 0.0 };
        let here = mag(k);
        if right > here && right >= left {
            k += 1;
        } else if left > here {
            k -= 1;
        } else {
            break;
        }
    }
    if k == 0 || k + 1 >= n || mag(k) <= 0.0 {
        return None;
    }
    let (a, b, c) = (mag(k - 1).ln(), mag(k).ln(), mag(k + 1).ln());
    let curvature = a - 2.0 * b + c;
    let offset = if curvature < 0.0 && a.is_finite() && c.is_finite() {
        (0.5 * (a - c) / curvature).clamp(-0.5, 0.5)
    } else {
        0.0
    };
    let spacing = 0.5 * (frequency_hz[k + 1] - frequency_hz[k - 1]);
    Some(frequency_hz[k] + offset * spacing)
}

/// The RMS of the fit's weighted misfit over the lines within `reach_hz`
/// of `f_hz`, over the RMS of the weighted FRF there (module doc); NaN
/// without such lines.
fn misfit(analysis: &FrfAnalysis, f_hz: f64, reach_hz: f64) -> f64 {
    let fit = &analysis.fit;
    let h = analysis.fitted_frf();
    let records = analysis.estimate.as_ref().map(|e| Records {
        truncation: &e.truncation_weight,
        force_power: &e.force_power,
        duration_s: e.samples as f64 / e.sample_rate_hz,
    });
    let data = BandData::new(&analysis.frequency_hz, h, records, &fit.settings);
    let powers: Vec<i32> = fit.residual_powers.iter().map(|(p, _)| *p).collect();
    let band = data.band(fit.settings.basis, records.is_some(), &powers);
    let poles: Vec<Complex64> = (fit.modes.iter().chain(&fit.harmonics))
        .map(|m| m.pole - fit.settings.window_decay_rate)
        .collect();
    let residual = lsfd::project(band, &poles).residual;
    let (mut e2, mut d2) = (0.0, 0.0);
    for (k, ((f, hk), r)) in data.bins.iter().zip(&residual).enumerate() {
        if (f - f_hz).abs() <= reach_hz {
            e2 += r.norm_sqr();
            d2 += (band.row(k) * hk).norm_sqr();
        }
    }
    if d2 > 0.0 {
        (e2 / d2).sqrt()
    } else {
        f64::NAN
    }
}
