//! The one frequency-response estimator: averaged auto and cross spectra of
//! force–response pairs, and from them H1, H2 and the coherence.
//!
//! Each pair i (force f, response x, n samples at f_s, windowed by
//! [`Window::force_weights`] and [`Window::response_weights`], zero-padded
//! to the FFT length L) gives the DFTs F_i(f_k) and X_i(f_k) at the bins
//! f_k = k·f_s/L up to the Nyquist frequency. The spectra are summed over
//! the pairs,
//!
//!   G_ff = Σ|F_i|²,  G_xx = Σ|X_i|²,  G_fx = Σ F̄_i X_i,
//!
//! and give the two classic estimators and the coherence
//!
//!   H1 = G_fx / G_ff,   H2 = G_xx / Ḡ_fx,   γ² = |G_fx|² / (G_ff G_xx).
//!
//! Uncorrelated noise on the response inflates G_xx only, so H1 stays
//! unbiased and H2 reads high; noise on the force inflates G_ff only, so H1
//! reads low and H2 stays unbiased. Always |H1| = γ²|H2| ≤ |H2|. With one
//! pair γ² = 1 identically: the coherence says something only for two or
//! more pairs. For one impact whose response decays inside the record, with
//! the rectangular window and no mean removed, F and X are samples of the
//! continuous Fourier transforms and H1 is free of leakage.
//!
//! The window scale factors cancel in the ratios as long as force and
//! response share the window (or, for the force window, as long as the
//! force lies inside its kept fraction). Units: H in response unit per
//! force unit.

use realfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

use super::spectrum::{
    bin_frequencies, check_rate, check_samples, padded_length, SpectrumError, SpectrumSettings,
    WindowedFft,
};
use super::window::Window;

/// Bins whose force power is this factor (−120 dB) below the strongest
/// force bin carry no excitation: H1, H2 and γ² are NaN there.
pub const FORCE_FLOOR: f64 = 1e-12;

/// How pairs are transformed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrossSpectraSettings {
    pub window: Window,
    /// FFT length, at least the record length (zero padding above it).
    pub fft_len: usize,
    /// Subtract each record's mean before windowing.
    pub remove_mean: bool,
}

/// Summed auto and cross spectra of one or more force–response pairs.
#[derive(Debug, Clone, PartialEq)]
pub struct CrossSpectra {
    /// Bin frequencies k·f_s/L, Hz.
    pub frequency_hz: Vec<f64>,
    /// Σ|F_i|² per bin (unscaled DFT), force unit².
    pub gff: Vec<f64>,
    /// Σ|X_i|² per bin, response unit².
    pub gxx: Vec<f64>,
    /// Σ F̄_i X_i per bin.
    pub gfx: Vec<Complex64>,
    /// Σ F_i per bin, force unit (for [`CrossSpectra::truncation_weight`]).
    pub sum_f: Vec<Complex64>,
    /// Pairs summed.
    pub averages: usize,
    /// Samples per record.
    pub samples: usize,
    pub sample_rate_hz: f64,
    pub settings: CrossSpectraSettings,
}

impl CrossSpectra {
    /// Sums the spectra of `pairs` (force, response), all of one length n
    /// at `sample_rate_hz`, with 4 ≤ n ≤ `settings.fft_len`.
    pub fn estimate<'a>(
        pairs: impl IntoIterator<Item = (&'a [f64], &'a [f64])>,
        sample_rate_hz: f64,
        settings: CrossSpectraSettings,
    ) -> Result<CrossSpectra, SpectrumError> {
        check_rate(sample_rate_hz)?;
        let mut fft = WindowedFft::new(settings.fft_len);
        let bins = settings.fft_len / 2 + 1;
        let mut out = CrossSpectra {
            frequency_hz: (0..bins)
                .map(|k| k as f64 * sample_rate_hz / settings.fft_len as f64)
                .collect(),
            gff: vec![0.0; bins],
            gxx: vec![0.0; bins],
            gfx: vec![Complex64::new(0.0, 0.0); bins],
            sum_f: vec![Complex64::new(0.0, 0.0); bins],
            averages: 0,
            samples: 0,
            sample_rate_hz,
            settings,
        };
        let (mut wf, mut wx) = (Vec::new(), Vec::new());
        let (mut fk, mut xk) = (Vec::new(), Vec::new());
        for (force, response) in pairs {
            out.check_pair(force, response)?;
            if out.averages == 0 {
                out.samples = force.len();
                wf = settings.window.force_weights(force.len());
                wx = settings.window.response_weights(force.len());
            }
            fft.transform(force, &wf, settings.remove_mean, &mut fk);
            fft.transform(response, &wx, settings.remove_mean, &mut xk);
            for k in 0..bins {
                out.gff[k] += fk[k].norm_sqr();
                out.gxx[k] += xk[k].norm_sqr();
                out.gfx[k] += fk[k].conj() * xk[k];
                out.sum_f[k] += fk[k];
            }
            out.averages += 1;
        }
        if out.averages == 0 {
            return Err(SpectrumError::NoRecords);
        }
        Ok(out)
    }

    /// The weight W_k = e^(−2πi k n/L) conj(Σ F_i)/Σ|F_i|² with which a
    /// response decay cut off by the end of the n-sample records enters H1
    /// (L the DFT length): a record ends while the decay D λ^j of a mode
    /// goes on, and the part it misses, Σ_(j≥n) D λ^j z^(−j), is
    /// D λ^n z^(−n)/(1 − λ z^(−1)): the mode's own pole term, weighted by
    /// z^(−n) and divided by the force (for hits of one shape). Zero where
    /// the force has no power.
    pub fn truncation_weight(&self) -> Vec<Complex64> {
        let l = self.settings.fft_len as f64;
        self.gff
            .iter()
            .zip(&self.sum_f)
            .enumerate()
            .map(|(k, (g, f))| {
                if *g > 0.0 {
                    let z = Complex64::from_polar(
                        1.0,
                        -2.0 * std::f64::consts::PI * k as f64 * self.samples as f64 / l,
                    );
                    z * f.conj() / *g
                } else {
                    Complex64::new(0.0, 0.0)
                }
            })
            .collect()
    }

    /// The share ε of G_ff per bin that white noise of variance
    /// `noise_variance` (N², per sample) on every force record makes:
    /// E|N|² = σ² Σw² per record (w the force weights), so
    /// ε = hits σ² Σw²/Σ|F_i|², capped at 1. To first order in ε,
    /// E[H1]/H = 1 − ε(1 − 1/hits) (one hit's H1 = X/F is not lowered on
    /// average: exactly, E[S/(S + N)] = 1 − e^(−|S|²/E|N|²)), and H1
    /// scatters by √(ε/(hits (1 − ε))) of H (δH1 = −H Σ F̄_i N_i/Σ|F_i|²). Zero where the force has no power;
    /// with the bins over which that error is correlated, n/Σw² (1
    /// without a window, 1/P under `force:P`).
    pub fn force_noise_share(&self, noise_variance: f64) -> (Vec<f64>, f64) {
        let w = self.settings.window.force_weights(self.samples);
        let energy: f64 = w.iter().map(|v| v * v).sum();
        let noise = self.averages as f64 * noise_variance * energy;
        let share = self
            .gff
            .iter()
            .map(|g| if *g > 0.0 { (noise / g).min(1.0) } else { 0.0 })
            .collect();
        let bins = self.settings.fft_len as f64 / energy.max(f64::MIN_POSITIVE);
        (share, bins.max(1.0))
    }

    fn check_pair(&self, force: &[f64], response: &[f64]) -> Result<(), SpectrumError> {
        check_samples(force, "force")?;
        check_samples(response, "response")?;
        let expected = if self.averages == 0 {
            force.len()
        } else {
            self.samples
        };
        for (name, len) in [("force", force.len()), ("response", response.len())] {
            if len != expected {
                return Err(SpectrumError::LengthMismatch {
                    first: "the first force",
                    first_len: expected,
                    second: name,
                    second_len: len,
                });
            }
        }
        if expected > self.settings.fft_len {
            return Err(SpectrumError::LongerThanFft {
                n: expected,
                fft_len: self.settings.fft_len,
            });
        }
        Ok(())
    }

    /// Bin spacing f_s/L, Hz.
    pub fn df(&self) -> f64 {
        self.sample_rate_hz / self.settings.fft_len as f64
    }

    /// Whether bin k's force power is above [`FORCE_FLOOR`] times the
    /// strongest bin's.
    fn excited(&self) -> impl Fn(usize) -> bool + '_ {
        let floor = FORCE_FLOOR * self.gff.iter().cloned().fold(0.0, f64::max);
        move |k| self.gff[k] > floor
    }

    /// H1 = G_fx/G_ff; NaN where the force carries no excitation.
    pub fn h1(&self) -> Vec<Complex64> {
        let excited = self.excited();
        (0..self.gff.len())
            .map(|k| {
                if excited(k) {
                    self.gfx[k] / self.gff[k]
                } else {
                    Complex64::new(f64::NAN, f64::NAN)
                }
            })
            .collect()
    }

    /// H2 = G_xx/Ḡ_fx; NaN where the force carries no excitation or the
    /// response is exactly zero.
    pub fn h2(&self) -> Vec<Complex64> {
        let excited = self.excited();
        (0..self.gff.len())
            .map(|k| {
                if excited(k) && self.gxx[k] != 0.0 {
                    self.gxx[k] / self.gfx[k].conj()
                } else {
                    Complex64::new(f64::NAN, f64::NAN)
                }
            })
            .collect()
    }

    /// γ² = |G_fx|²/(G_ff G_xx) in [0, 1]; NaN where H2 is.
    pub fn coherence(&self) -> Vec<f64> {
        let excited = self.excited();
        (0..self.gff.len())
            .map(|k| {
                if excited(k) && self.gxx[k] != 0.0 {
                    (self.gfx[k].norm_sqr() / (self.gff[k] * self.gxx[k])).min(1.0)
                } else {
                    f64::NAN
                }
            })
            .collect()
    }

    /// Decay rate the window added to every mode, 1/s (exponential window;
    /// 0 otherwise).
    pub fn window_decay_rate(&self) -> f64 {
        self.settings
            .window
            .decay_rate(self.samples, self.sample_rate_hz)
    }
}

/// Frequency-response function estimate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Frf {
    /// Bin frequencies, Hz.
    pub frequency_hz: Vec<f64>,
    /// Real part of H (response unit per force unit); NaN where the force
    /// carries no excitation (see [`FORCE_FLOOR`]).
    pub re: Vec<f64>,
    /// Imaginary part of H; NaN where `re` is.
    pub im: Vec<f64>,
    /// Bin spacing, Hz.
    pub df: f64,
}

impl Frf {
    /// `|H|` per bin.
    pub fn magnitude(&self) -> Vec<f64> {
        self.re
            .iter()
            .zip(&self.im)
            .map(|(r, i)| r.hypot(*i))
            .collect()
    }

    /// Phase of H in radians, in (−π, π].
    pub fn phase_rad(&self) -> Vec<f64> {
        self.re
            .iter()
            .zip(&self.im)
            .map(|(r, i)| i.atan2(*r))
            .collect()
    }
}

/// H1 of one force–response pair sampled at `sample_rate_hz`, windowed and
/// padded by `settings` like [`super::spectrum::amplitude_spectrum`]:
/// [`CrossSpectra`] of the one pair, as real and imaginary parts.
pub fn frf_h1(
    force: &[f64],
    response: &[f64],
    sample_rate_hz: f64,
    settings: &SpectrumSettings,
) -> Result<Frf, SpectrumError> {
    check_rate(sample_rate_hz)?;
    if force.len() != response.len() {
        return Err(SpectrumError::LengthMismatch {
            first: "force",
            first_len: force.len(),
            second: "response",
            second_len: response.len(),
        });
    }
    check_samples(force, "force")?;
    let fft_len = padded_length(force.len(), settings.zero_pad_factor)?;
    let cross = CrossSpectra::estimate(
        [(force, response)],
        sample_rate_hz,
        CrossSpectraSettings {
            window: settings.window,
            fft_len,
            remove_mean: settings.remove_mean,
        },
    )?;
    let (re, im) = cross.h1().iter().map(|h| (h.re, h.im)).unzip();
    let df = sample_rate_hz / fft_len as f64;
    Ok(Frf {
        frequency_hz: bin_frequencies(cross.gff.len(), df),
        re,
        im,
        df,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A decaying two-tone response to a short pulse, n samples at 1 kHz.
    fn pair(n: usize) -> (Vec<f64>, Vec<f64>) {
        let force = (0..n).map(|i| if i < 3 { 1.0 } else { 0.0 }).collect();
        let response = (0..n)
            .map(|i| {
                let t = i as f64 * 1e-3;
                (-20.0 * t).exp() * (2.0 * std::f64::consts::PI * 60.0 * t).sin()
                    + 0.3 * (-35.0 * t).exp() * (2.0 * std::f64::consts::PI * 170.0 * t).cos()
            })
            .collect();
        (force, response)
    }

    fn settings(fft_len: usize) -> CrossSpectraSettings {
        CrossSpectraSettings {
            window: Window::Rectangular,
            fft_len,
            remove_mean: false,
        }
    }

    /// Zero padding samples the same transform more densely: bin p·k of
    /// the padded estimate is bin k of the unpadded one.
    #[test]
    fn padding_interpolates_between_the_bins() {
        let (f, x) = pair(1024);
        let plain = CrossSpectra::estimate([(&f[..], &x[..])], 1e3, settings(1024)).unwrap();
        let padded = CrossSpectra::estimate([(&f[..], &x[..])], 1e3, settings(4096)).unwrap();
        let (h, hp) = (plain.h1(), padded.h1());
        let scale = h.iter().map(|v| v.norm()).fold(0.0, f64::max);
        for (k, v) in h.iter().enumerate() {
            assert!((hp[4 * k] - v).norm() < 1e-12 * scale, "bin {k}");
            assert_eq!(padded.frequency_hz[4 * k], plain.frequency_hz[k]);
        }
        // One pair: γ² = 1 and H1 = H2 wherever the force is excited.
        for ((c, a), b) in plain.coherence().iter().zip(&h).zip(plain.h2()) {
            assert!((c - 1.0).abs() < 1e-12 && (a - b).norm() < 1e-12 * scale);
        }
    }

    #[test]
    fn mismatched_records_are_refused() {
        let (f, x) = pair(64);
        let e = |pairs: Vec<(&[f64], &[f64])>, fft_len| {
            CrossSpectra::estimate(pairs, 1e3, settings(fft_len)).unwrap_err()
        };
        assert!(matches!(
            e(vec![(&f[..], &x[..63])], 64),
            SpectrumError::LengthMismatch { second_len: 63, .. }
        ));
        assert!(matches!(
            e(vec![(&f[..], &x[..]), (&f[..32], &x[..32])], 64),
            SpectrumError::LengthMismatch {
                first_len: 64,
                second_len: 32,
                ..
            }
        ));
        assert_eq!(
            e(vec![(&f[..], &x[..])], 32),
            SpectrumError::LongerThanFft { n: 64, fft_len: 32 }
        );
        assert_eq!(e(Vec::new(), 64), SpectrumError::NoRecords);
    }
}
