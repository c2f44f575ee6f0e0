//! Complex modes of a damped assembly: the damping ratio and damped
//! frequency of each elastic mode when the damping is not proportional
//! (spring dampers, torsion dampers, beside Rayleigh damping).
//!
//! The linearized equations M q̈ + C q̇ + K q = 0 (constrained) are written
//! in the basis of the computed undamped elastic modes Φ (mass-normalized,
//! satisfying the linearized constraints): η̈ + C_m η̇ + Ω² η = 0 with
//! C_m = Φᵀ C_d Φ + α I + β Ω² [SI: 1/s], C_d the dampers' velocity Jacobian
//! at the linearization point and Ω = diag(ω). In the state (Ωη, η̇),
//! balanced so that every entry is of the order of the frequencies (the
//! form with I and Ω² loses digits of the low modes' eigenvalues to the
//! high modes' ω²), its state matrix
//!
//! ```text
//! A = [  0    Ω  ]
//!     [ −Ω  −C_m ]
//! ```
//!
//! has the eigenvalues λ = −ζωₙ ± iωₙ√(1 − ζ²) [SI: rad/s]: natural
//! frequency ωₙ = |λ|, damping ratio ζ = −Re λ / |λ|, damped frequency
//! ω_d = Im λ. Each eigenvalue with Im λ > 0 belongs to the undamped mode
//! that dominates its eigenvector's displacement part; an overdamped pair
//! (two real λ) gives ζ = (|λ₁| + |λ₂|)/(2√(λ₁λ₂)) ≥ 1 and no damped
//! frequency.
//!
//! The basis is the computed modes (a modal truncation): the coupling that
//! dampers create among the computed modes is kept, that with modes above
//! them is not — exact when every mode of the reduced problem is computed,
//! and exact to first order in C (ζⱼ ≈ (C_m)ⱼⱼ/(2ωⱼ)) for light damping in
//! any case. Rigid modes are left out (they have no damping ratio).

use super::modal::ModalResult;
use crate::error::AnalysisError;
use crate::linalg::Triplets;
use crate::model::RayleighDamping;
use crate::system::{Linearization, System};
use faer::Mat;

/// A complex mode, labelled by the undamped mode it grows from.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct DampedMode {
    /// 1-based index of the undamped mode in the modal result.
    pub index: usize,
    /// Undamped natural frequency ωₙ/2π = |λ|/2π [SI: Hz].
    pub natural_hz: f64,
    /// Damped frequency Im λ/2π [SI: Hz]; `None` when overdamped.
    pub damped_hz: Option<f64>,
    /// ζ [–].
    pub damping_ratio: f64,
}

/// Whether the system has any viscous damper (springs' `damping`, pins'
/// `torsion_damping`).
pub fn has_dampers(system: &System, q: &[f64]) -> bool {
    let n = system.ndof();
    let mut f = vec![0.0; n];
    system.add_damping(q, &vec![0.0; n], &mut f, None::<&mut Triplets>)
}

/// The complex modes of the elastic modes of `modal` (linearized at `at`),
/// with the dampers of `system` and the Rayleigh damping `rayleigh`.
pub fn damped_modes(
    system: &System,
    at: &Linearization,
    modal: &ModalResult,
    rayleigh: Option<RayleighDamping>,
) -> Result<Vec<DampedMode>, AnalysisError> {
    let n = system.ndof();
    let elastic: Vec<_> = modal.modes.iter().filter(|m| !m.kind.is_zero()).collect();
    let m = elastic.len();
    if m == 0 {
        return Ok(Vec::new());
    }
    // Dampers' matrix at rest (q̇ = 0: linear in q̇ about it).
    let mut cd = Triplets::new(n, n);
    let mut f = vec![0.0; n];
    system.add_damping(at.q, &vec![0.0; n], &mut f, Some(&mut cd));
    let r = rayleigh.unwrap_or(RayleighDamping {
        alpha: 0.0,
        beta: 0.0,
    });
    let omega: Vec<f64> = elastic
        .iter()
        .map(|e| 2.0 * std::f64::consts::PI * e.frequency_hz)
        .collect();
    // C_d Φ column by column, then Φᵀ (C_d Φ).
    let mut cphi = vec![vec![0.0; n]; m];
    for (i, j, v) in cd.entries() {
        for (col, e) in cphi.iter_mut().zip(&elastic) {
            col[i] += v * e.shape[j];
        }
    }
    let mut a = Mat::<f64>::zeros(2 * m, 2 * m);
    for j in 0..m {
        a[(j, m + j)] = omega[j];
        a[(m + j, j)] = -omega[j];
        for i in 0..m {
            let projected: f64 = elastic[i]
                .shape
                .iter()
                .zip(&cphi[j])
                .map(|(p, c)| p * c)
                .sum();
            let rayleigh = if i == j {
                r.alpha + r.beta * omega[j] * omega[j]
            } else {
                0.0
            };
            a[(m + i, m + j)] = -(projected + rayleigh);
        }
    }
    let evd = a
        .eigen()
        .map_err(|_| AnalysisError::EigenSolver { size: 2 * m })?;
    let (u, s) = (evd.U(), evd.S());
    let lambdas: Vec<(f64, f64)> = (0..2 * m)
        .map(|k| {
            let l = s.column_vector()[k];
            (l.re, l.im)
        })
        .collect();
    // The undamped mode that dominates eigenvector k's displacements
    // (weighted by ω: the strain-energy share).
    let owner = |k: usize| -> usize {
        (0..m)
            .max_by(|&a, &b| u[(a, k)].norm().total_cmp(&u[(b, k)].norm()))
            .expect("m > 0")
    };
    let tiny = 1e-12 * omega.iter().fold(0.0f64, |x, &w| x.max(w));
    let mut out: Vec<Option<DampedMode>> = vec![None; m];
    let mut real_roots: Vec<Vec<f64>> = vec![Vec::new(); m];
    for (k, &(re, im)) in lambdas.iter().enumerate() {
        let j = owner(k);
        if im > tiny {
            let wn = re.hypot(im);
            out[j] = Some(DampedMode {
                index: elastic[j].index,
                natural_hz: wn / (2.0 * std::f64::consts::PI),
                damped_hz: Some(im / (2.0 * std::f64::consts::PI)),
                damping_ratio: -re / wn,
            });
        } else if im.abs() <= tiny {
            real_roots[j].push(re);
        }
    }
    for (j, roots) in real_roots.iter().enumerate() {
        if out[j].is_none() && roots.len() == 2 {
            let wn = (roots[0] * roots[1]).abs().sqrt();
            out[j] = Some(DampedMode {
                index: elastic[j].index,
                natural_hz: wn / (2.0 * std::f64::consts::PI),
                damped_hz: None,
                damping_ratio: -(roots[0] + roots[1]) / (2.0 * wn),
            });
        }
    }
    Ok(out.into_iter().flatten().collect())
}

/// One mode's damping as the commands report it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ModeDamping {
    /// ζ; `None` for rigid modes.
    pub damping_ratio: Option<f64>,
    /// Im λ/2π of a complex mode [SI: Hz]; `None` without dampers (the
    /// Rayleigh formula) or when overdamped.
    pub damped_frequency_hz: Option<f64>,
    /// Whether the ratio comes from complex modes (dampers present).
    pub complex: bool,
}

/// The damping of every mode of `modal`, in its order: complex modes when
/// the system has dampers, else ζ = φᵀ(αM + βK₀)φ/(2ω) (α/(2ω) + βω/2 for
/// a mode of the unloaded reference; 0 without damping).
pub fn mode_damping(
    system: &System,
    at: &Linearization,
    modal: &ModalResult,
    rayleigh: Option<RayleighDamping>,
) -> Result<Vec<ModeDamping>, AnalysisError> {
    let complex = if has_dampers(system, at.q) {
        Some(damped_modes(system, at, modal, rayleigh)?)
    } else {
        None
    };
    let k0 = rayleigh
        .filter(|_| complex.is_none())
        .map(|_| crate::analysis::transient::rayleigh::reference_stiffness(system));
    Ok(modal
        .modes
        .iter()
        .map(|m| {
            if m.kind.is_zero() {
                return ModeDamping::default();
            }
            match &complex {
                Some(c) => {
                    let d = c.iter().find(|d| d.index == m.index);
                    ModeDamping {
                        damping_ratio: d.map(|d| d.damping_ratio),
                        damped_frequency_hz: d.and_then(|d| d.damped_hz),
                        complex: true,
                    }
                }
                None => ModeDamping {
                    damping_ratio: Some(match (rayleigh, &k0) {
                        (Some(r), Some(k0)) => crate::analysis::transient::rayleigh::mode_ratio(
                            r,
                            k0,
                            &m.shape,
                            2.0 * std::f64::consts::PI * m.frequency_hz,
                        ),
                        _ => 0.0,
                    }),
                    ..ModeDamping::default()
                },
            }
        })
        .collect())
}
