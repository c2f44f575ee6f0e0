//! The residues of modes still ringing at the records' end.
//!
//! **Physics.** A record of N samples ends while a mode's decay goes on.
//! Its transform misses the tail Σ_(j≥N) x_j z^(−j). After the whole
//! record the response of hit h is, per pole s (λ = e^(sΔt)),
//! x_j = R Δt λ^j F̃_h(s) with F̃_h(s) = Σ_i F_h,i λ^(−i) (the force's
//! transform at the pole), so at the DFT lines (z^N = 1) the tail is
//! R λ^N F̃_h(s) g(ω, s) and H1 = Σ X F̄/Σ|F|² holds, per pole,
//!
//! ```text
//! R g(ω, s) (1 − Φ_k),   Φ_k = Σ_h F̄_h,k λ^N F̃_h(s) / Σ_h |F_h,k|²
//! ```
//!
//! The poles are found ([`crate::signal::lsfd`]) with the tail as a free
//! term W_k D g(ω, s) beside R g(ω, s), W_k = conj(Σ_h F_h,k)/Σ_h|F_h,k|².
//! For a short blow W is nearly flat across a mode's lines, so the two
//! terms are nearly one: that fit determines R + W D, not R and D apart.
//! Tying D to R after the fit, at one line, was not enough: on a 10 s
//! record of a lightly damped cantilever the two free coefficients came
//! out large and opposite, and the residue tied at one line left |H| at
//! the first mode's peak 50 % high (the third outside-eyes trial of issue
//! 33; 16 % on a tuning fork's 0.5 s record).
//!
//! So the residues are fitted again, the poles kept, with each pole's tail
//! tied to its residue in the model itself: one column per pole,
//!
//! ```text
//! R [g(ω_k, s) − Φ_k(s) g_c(ω_k, s)] + R̄ [g(ω_k, s̄) − Φ_k(s̄) g_c(ω_k, s̄)]
//! ```
//!
//! (g_c the cut-off's basis: the filtered basis has a continuous mode term
//! and a sampled tail, [`crate::signal::pole_basis::PoleBasis::cutoff`]),
//! with Φ_k(s) per line from the records' own forces, so several hits of
//! different shapes are tied exactly. Windows act on force and response
//! alike: the window's decay is on the pole and the weights on the force.
//! Where |1 − Φρ| at the mode's line is under [`MIN_DENOMINATOR`]
//! (ρ = g_c/g there; a decay that hardly falls over the record) the data
//! hardly tell R from the tail and the residue is reported as not
//! determined: the warning of [`super::record_checks::ringing_at_end`]
//! names those modes.
//!
//! Measured on `impulse`'s 4 s record of a clamped blade (the trial's):
//! modes 1 and 2 (0.43 and 0.12 left at the end) 131 % and 127 % off with
//! the free term, within 1.2 % tied (tests/measured_cut_off.rs).

use std::f64::consts::PI;

use realfft::num_complex::Complex64;
use realfft::RealFftPlanner;

use super::frf::FrfEstimate;
use super::TimeRecord;
use crate::signal::fit::{BandData, ModalFit, Records};
use crate::signal::projection::{design, solve};

/// Smallest |1 − Φρ| for which the residue is solved for.
pub const MIN_DENOMINATOR: f64 = 0.1;

/// Fits the residues of the fit's modes again with their cut-off decays
/// tied to them (module doc), the poles kept; updates the residual terms
/// and `magnitude`. `h` is the FRF the fit was made of. Returns the
/// indices of the modes whose residue the records hardly determine
/// (|1 − Φρ| under [`MIN_DENOMINATOR`] at their line).
pub fn tie_residues(
    fit: &mut ModalFit,
    records: &[TimeRecord],
    estimate: &FrfEstimate,
    h: &[Complex64],
) -> Vec<usize> {
    let n = estimate.samples;
    let dt = 1.0 / estimate.sample_rate_hz;
    let data = BandData::new(
        &estimate.frequency_hz,
        h,
        Some(Records {
            truncation: &estimate.truncation_weight,
            force_power: &estimate.force_power,
            duration_s: n as f64 * dt,
        }),
        &fit.settings,
    );
    if fit.modes.is_empty() || data.bins.is_empty() || records.is_empty() {
        return Vec::new();
    }
    let basis = fit.settings.basis;
    // The residual terms the fit ended with.
    let powers: Vec<i32> = fit.residual_powers.iter().map(|(n, _)| *n).collect();
    let band = data.band(basis, false, &powers);
    let poles: Vec<Complex64> = fit
        .modes
        .iter()
        .map(|m| m.pole - estimate.window_decay_rate)
        .collect();
    // The windowed forces v_i = F_i w_i of the records, once.
    let weights = estimate.window.force_weights(n);
    let windowed: Vec<Vec<f64>> = records
        .iter()
        .map(|r| r.force.iter().zip(&weights).map(|(x, w)| x * w).collect())
        .collect();
    let forces = force_spectra(&windowed, n, &data.in_band);
    let power: Vec<f64> = (0..data.in_band.len())
        .map(|k| forces.iter().map(|f| f[k].norm_sqr()).sum())
        .collect();
    let mut a = design(band, &poles);
    let mut undetermined = Vec::new();
    let mut tails_mean = Vec::with_capacity(poles.len());
    let i = Complex64::new(0.0, 1.0);
    for (r, s) in poles.iter().enumerate() {
        let tails = tails(&windowed, (*s * dt).exp());
        tails_mean.push(tails.iter().sum::<Complex64>() / tails.len() as f64);
        let phi = |k: usize, conj: bool| -> Complex64 {
            if power[k] <= 0.0 {
                return Complex64::new(0.0, 0.0);
            }
            let sum: Complex64 = forces
                .iter()
                .zip(&tails)
                .map(|(f, t)| f[k].conj() * if conj { t.conj() } else { *t })
                .sum();
            sum / power[k]
        };
        let fd = s.im / (2.0 * PI);
        let k0 = data
            .bins
            .iter()
            .enumerate()
            .min_by(|x, y| (x.1 .0 - fd).abs().total_cmp(&(y.1 .0 - fd).abs()))
            .map(|(k, _)| k);
        let pole = basis.factor(*s);
        for (k, (f, _)) in data.bins.iter().enumerate() {
            let at_cut = basis.cutoff().at(*f);
            let e1 = phi(k, false) * at_cut.term(pole);
            let e2 = phi(k, true) * at_cut.term(pole.conj());
            // As the design's columns: R = x + iy enters as x·(e1 + e2) + y·i(e1 − e2).
            let (cx, cy) = (band.row(k) * (e1 + e2), band.row(k) * i * (e1 - e2));
            a[(2 * k, 2 * r)] -= cx.re;
            a[(2 * k + 1, 2 * r)] -= cx.im;
            a[(2 * k, 2 * r + 1)] -= cy.re;
            a[(2 * k + 1, 2 * r + 1)] -= cy.im;
            if Some(k) == k0 {
                let rho = at_cut.term(pole) / basis.at(*f).term(pole);
                if (Complex64::new(1.0, 0.0) - phi(k, false) * rho).norm() < MIN_DENOMINATOR {
                    undetermined.push(r);
                }
            }
        }
    }
    let tied = solve(band, poles.len(), a).fitted;
    for ((m, residue), tail) in fit.modes.iter_mut().zip(tied.residues).zip(tails_mean) {
        m.residue = residue;
        m.cut_off = -residue * tail;
    }
    fit.upper_residual = tied.upper;
    fit.lower_residual = tied.lower;
    fit.residual_powers = tied.powers;
    fit.update_magnitudes();
    undetermined
}

/// Per windowed force record v (n samples), its DFT at the bins
/// `in_band`: F_k = Σ v_i e^(−2πi k i/n) (unscaled, as H1's).
fn force_spectra(windowed: &[Vec<f64>], n: usize, in_band: &[usize]) -> Vec<Vec<Complex64>> {
    let mut planner = RealFftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(n);
    windowed
        .iter()
        .map(|v| {
            let mut input = v.clone();
            let mut out = fft.make_output_vec();
            // Lengths are the plan's own: the transform cannot fail.
            fft.process(&mut input, &mut out)
                .expect("buffers made by the plan");
            in_band
                .iter()
                .map(|&k| out.get(k).copied().unwrap_or_default())
                .collect()
        })
        .collect()
}

/// Per windowed force record v, λ^N F̃(s) = Σ_i v_i λ^(N−i) (module doc),
/// by running powers from the record's end (n multiplications, no exp per
/// sample; their round-off is n ε relative).
fn tails(windowed: &[Vec<f64>], lambda: Complex64) -> Vec<Complex64> {
    windowed
        .iter()
        .map(|v| {
            let (mut tail, mut decay) = (Complex64::new(0.0, 0.0), Complex64::new(1.0, 0.0));
            for x in v.iter().rev() {
                decay *= lambda;
                tail += x * decay;
            }
            tail
        })
        .collect()
}
