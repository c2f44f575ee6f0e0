//! The frequency-response estimate of one hammer test: its hits checked to
//! agree (rate, length), then averaged by the one estimator,
//! [`crate::signal::frf::CrossSpectra`] (its module doc gives H1, H2 and
//! the coherence γ² and what noise does to each), without zero padding or
//! mean removal, so that a rectangular-windowed impact response that dies
//! out inside the record is free of leakage. Units: H in response unit per
//! N.

use realfft::num_complex::Complex64;

use super::record_checks::force_noise_variance;
use super::{MeasuredError, TimeRecord};
use crate::signal::frf::{CrossSpectra, CrossSpectraSettings};
use crate::signal::Window;

/// Averaged spectra and the estimators of one set of hits.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfEstimate {
    /// Bin frequencies k·fs/n, Hz.
    pub frequency_hz: Vec<f64>,
    pub h1: Vec<Complex64>,
    pub h2: Vec<Complex64>,
    /// γ² in [0, 1].
    pub coherence: Vec<f64>,
    /// Number of hits averaged.
    pub averages: usize,
    pub sample_rate_hz: f64,
    /// Samples per hit.
    pub samples: usize,
    pub window: Window,
    /// Decay rate the window added to every mode, 1/s (exponential window).
    pub window_decay_rate: f64,
    /// Mean force auto spectrum G_ff/hits, N² (unscaled DFT), to judge
    /// which band the hammer excited.
    pub force_power: Vec<f64>,
    /// Weight of the decays cut off by the records' end in H1, 1/N
    /// ([`crate::signal::frf::CrossSpectra::truncation_weight`]).
    pub truncation_weight: Vec<Complex64>,
    /// The noise the force records show outside their blows
    /// ([`super::record_checks::force_noise_variance`], the mean over the
    /// hits that have one; zero for none).
    pub force_noise: ForceNoise,
}

/// What noise on the force does to H1, per bin.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ForceNoise {
    /// Variance of the force's noise per sample, N².
    pub variance: f64,
    /// The share ε of G_ff per bin that the noise makes
    /// ([`crate::signal::frf::CrossSpectra::force_noise_share`]: what it
    /// does to H1).
    pub share: Vec<f64>,
    /// Bins over which that error is correlated.
    pub correlation_bins: f64,
}

impl FrfEstimate {
    /// Bin spacing fs/n, Hz.
    pub fn df(&self) -> f64 {
        self.sample_rate_hz / self.samples as f64
    }
}

/// Checks that every hit has the first one's rate and length.
fn check_alike(records: &[TimeRecord]) -> Result<(), MeasuredError> {
    let first = &records[0];
    for r in &records[1..] {
        let rel = (r.sample_rate_hz - first.sample_rate_hz).abs() / first.sample_rate_hz;
        if rel > 1e-6 {
            return Err(MeasuredError::Mismatch {
                file: r.file.clone(),
                first: first.file.clone(),
                what: "the sample rate [Hz]",
                value: r.sample_rate_hz,
                expected: first.sample_rate_hz,
            });
        }
        if r.force.len() != first.force.len() {
            return Err(MeasuredError::Mismatch {
                file: r.file.clone(),
                first: first.file.clone(),
                what: "the number of samples",
                value: r.force.len() as f64,
                expected: first.force.len() as f64,
            });
        }
    }
    Ok(())
}

/// H1, H2 and γ² from one or more hits (the estimator's module doc).
///
/// # Panics
/// If `records` is empty.
pub fn estimate(records: &[TimeRecord], window: Window) -> Result<FrfEstimate, MeasuredError> {
    assert!(!records.is_empty(), "estimate needs at least one record");
    check_alike(records)?;
    let first = &records[0];
    let n = first.force.len();
    let settings = CrossSpectraSettings {
        window,
        fft_len: n,
        remove_mean: false,
    };
    let pairs = records
        .iter()
        .map(|r| (r.force.as_slice(), r.response.as_slice()));
    let cross =
        CrossSpectra::estimate(pairs, first.sample_rate_hz, settings).map_err(|source| {
            MeasuredError::Spectrum {
                file: first.file.clone(),
                source,
            }
        })?;
    let variances: Vec<f64> = records
        .iter()
        .filter_map(|r| force_noise_variance(&r.force))
        .collect();
    let variance = variances.iter().sum::<f64>() / variances.len().max(1) as f64;
    let (share, correlation_bins) = cross.force_noise_share(variance);
    Ok(FrfEstimate {
        force_noise: ForceNoise {
            variance,
            share,
            correlation_bins,
        },
        h1: cross.h1(),
        h2: cross.h2(),
        coherence: cross.coherence(),
        averages: cross.averages,
        sample_rate_hz: cross.sample_rate_hz,
        samples: n,
        window,
        window_decay_rate: cross.window_decay_rate(),
        force_power: cross.gff.iter().map(|g| g / records.len() as f64).collect(),
        truncation_weight: cross.truncation_weight(),
        frequency_hz: cross.frequency_hz,
    })
}
