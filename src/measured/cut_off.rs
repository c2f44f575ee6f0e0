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
//! The fit ([`crate::signal::lsfd`]) has the tail as a free term
//! W_k D g(ω, s) beside R g(ω, s), W_k = conj(Σ_h F_h,k)/Σ_h|F_h,k|². For a
//! short blow W is nearly flat across a mode's lines, so the two terms are
//! nearly one: the fit determines R + W D, not R and D apart (the second
//! outside-eyes trial of issue 33 found residues 17–131 % off at
//! e^(Re(s)T) = 0.12–0.45, with f and ζ right). The physical R is then
//!
//! ```text
//! R = (R_fit + W_k0 D_fit ρ) / (1 − Φ_k0 ρ)
//! ```
//!
//! at the line k0 nearest the mode's damped frequency, ρ = g_tail/g_mode
//! there (1 in the sampled basis; the filtered basis has a continuous
//! mode term and a sampled tail, [`crate::signal::pole_basis::PoleBasis::cutoff`]).
//! Windows act on force and response alike: the window's decay is on the
//! pole and the weights on the force. Where 1 − Φρ is under
//! [`MIN_DENOMINATOR`] (a decay that hardly falls over the record), R is
//! not determined and is left as fitted; the warning of
//! [`super::record_checks::ringing_at_end`] names those modes.
//!
//! Measured on `impulse`'s 4 s record of a clamped blade (the trial's):
//! modes 1 and 2 (0.43 and 0.12 left at the end) 131 % and 127 % off with
//! the free term, 0.9 % and 1.2 % tied (tests/measured_cut_off.rs).

use std::f64::consts::PI;

use realfft::num_complex::Complex64;

use super::frf::FrfEstimate;
use super::TimeRecord;
use crate::signal::fit::ModalFit;

/// Smallest |1 − Φρ| for which the residue is solved for.
pub const MIN_DENOMINATOR: f64 = 0.1;

/// Replaces each mode's residue by the one its cut-off decay implies
/// (module doc), for modes with a cut-off term; updates `magnitude`.
/// Returns the indices of the modes with a cut-off term whose residue is
/// not determined (|1 − Φρ| under [`MIN_DENOMINATOR`]), left as fitted.
pub fn tie_residues(
    fit: &mut ModalFit,
    records: &[TimeRecord],
    estimate: &FrfEstimate,
) -> Vec<usize> {
    let n = estimate.samples;
    let dt = 1.0 / estimate.sample_rate_hz;
    let weights = estimate.window.force_weights(n);
    let basis = fit.settings.basis;
    let mut changed = false;
    let mut undetermined = Vec::new();
    for (j, m) in fit.modes.iter_mut().enumerate() {
        if m.cut_off == Complex64::new(0.0, 0.0) {
            continue;
        }
        let s = m.pole - estimate.window_decay_rate;
        let fd = s.im / (2.0 * PI);
        let k0 = (fd / estimate.df()).round() as usize;
        let (Some(&w), Some(&f0)) = (
            estimate.truncation_weight.get(k0),
            estimate.frequency_hz.get(k0),
        ) else {
            continue;
        };
        // F_k0 = Σ v_i z^(−i) and λ^N F̃ = Σ v_i λ^(N−i), both by running
        // powers from the record's end (n multiplications, no exp per
        // sample; their round-off is n ε relative).
        let (lambda, z) = (
            (s * dt).exp(),
            Complex64::from_polar(1.0, 2.0 * PI * k0 as f64 / n as f64),
        );
        let (mut num, mut power) = (Complex64::new(0.0, 0.0), 0.0);
        for r in records {
            let (mut fk, mut tail) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
            let (mut rotation, mut decay) = (Complex64::new(1.0, 0.0), Complex64::new(1.0, 0.0));
            for (x, wi) in r.force.iter().zip(&weights).rev() {
                // Sample i = n − 1 − (steps so far): z^(−i) = z^(n−i) = z·z^(n−1−i),
                // λ^(N−i) = λ·λ^(n−1−i).
                rotation *= z;
                decay *= lambda;
                let v = x * wi;
                fk += v * rotation;
                tail += v * decay;
            }
            num += fk.conj() * tail;
            power += fk.norm_sqr();
        }
        if power <= 0.0 {
            undetermined.push(j);
            continue;
        }
        let phi = num / power;
        let rho = basis.cutoff().term(f0, s) / basis.term(f0, s);
        let denominator = Complex64::new(1.0, 0.0) - phi * rho;
        if denominator.norm() < MIN_DENOMINATOR {
            undetermined.push(j);
            continue;
        }
        m.residue = (m.residue + w * m.cut_off * rho) / denominator;
        changed = true;
    }
    if changed {
        fit.update_magnitudes();
    }
    undetermined
}
