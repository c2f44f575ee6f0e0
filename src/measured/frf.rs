//! Frequency-response estimation from averaged hits.
//!
//! Each hit i gives the DFTs F_i(f_k) and X_i(f_k) of its windowed force and
//! response (n samples, bins f_k = k·fs/n up to the Nyquist frequency, no
//! zero padding). The auto and cross spectra are summed over the hits,
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
//! hit γ² = 1 identically: the coherence says something only for two or
//! more hits.
//!
//! The window scale factors cancel in the ratios as long as force and
//! response share the window (or, for the force window, as long as the
//! force lies inside its kept fraction). Units: H in response unit per N.

use realfft::num_complex::Complex64;
use realfft::RealFftPlanner;

use super::window::Window;
use super::{MeasuredError, TimeRecord};

/// Bins whose force power is this factor below the strongest force bin
/// carry no excitation: H1, H2 and γ² are NaN there.
pub const FORCE_FLOOR: f64 = 1e-12;

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

/// H1, H2 and γ² from one or more hits (see the module doc).
///
/// # Panics
/// If `records` is empty.
pub fn estimate(records: &[TimeRecord], window: Window) -> Result<FrfEstimate, MeasuredError> {
    assert!(!records.is_empty(), "estimate needs at least one record");
    check_alike(records)?;
    let n = records[0].force.len();
    let fs = records[0].sample_rate_hz;
    if let Window::Exponential { .. } = window {
        if n < 2 {
            return Err(MeasuredError::ShortRecord {
                file: records[0].file.clone(),
                duration: records[0].duration(),
            });
        }
    }
    let wf = window.force_weights(n);
    let wx = window.response_weights(n);
    let fft = RealFftPlanner::<f64>::new().plan_fft_forward(n);
    let bins = n / 2 + 1;
    let mut gff = vec![0.0; bins];
    let mut gxx = vec![0.0; bins];
    let mut gfx = vec![Complex64::new(0.0, 0.0); bins];
    let mut buf = fft.make_input_vec();
    let mut fk = fft.make_output_vec();
    let mut xk = fft.make_output_vec();
    for r in records {
        for ((b, v), w) in buf.iter_mut().zip(&r.force).zip(&wf) {
            *b = v * w;
        }
        fft.process(&mut buf, &mut fk)
            .expect("buffers are sized by the plan");
        for ((b, v), w) in buf.iter_mut().zip(&r.response).zip(&wx) {
            *b = v * w;
        }
        fft.process(&mut buf, &mut xk)
            .expect("buffers are sized by the plan");
        for k in 0..bins {
            gff[k] += fk[k].norm_sqr();
            gxx[k] += xk[k].norm_sqr();
            gfx[k] += fk[k].conj() * xk[k];
        }
    }
    let floor = FORCE_FLOOR * gff.iter().cloned().fold(0.0, f64::max);
    let nan = Complex64::new(f64::NAN, f64::NAN);
    let mut h1 = Vec::with_capacity(bins);
    let mut h2 = Vec::with_capacity(bins);
    let mut coherence = Vec::with_capacity(bins);
    for k in 0..bins {
        if gff[k] <= floor || gxx[k] == 0.0 {
            h1.push(nan);
            h2.push(nan);
            coherence.push(f64::NAN);
            continue;
        }
        h1.push(gfx[k] / gff[k]);
        h2.push(gxx[k] / gfx[k].conj());
        coherence.push((gfx[k].norm_sqr() / (gff[k] * gxx[k])).min(1.0));
    }
    Ok(FrfEstimate {
        frequency_hz: (0..bins).map(|k| k as f64 * fs / n as f64).collect(),
        h1,
        h2,
        coherence,
        averages: records.len(),
        sample_rate_hz: fs,
        samples: n,
        window,
        window_decay_rate: window.decay_rate(n, fs),
        force_power: gff.iter().map(|g| g / records.len() as f64).collect(),
    })
}
