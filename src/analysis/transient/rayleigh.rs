//! Rayleigh (proportional) damping in the time integration.
//!
//! The model's `damping {alpha, beta}` gives the viscous force
//! f_d = C q̇ [SI: N, N m] with C = αM + βK (α [1/s], β [s]), so that a mode
//! of angular frequency ω decays at the rate ζω with ζ = α/(2ω) + βω/2, as
//! `modal` reports.
//!
//! **Which K.** K is the stiffness of the linearization `modal` uses
//! without pre-stress: the tangent of the beams, springs and torsion
//! springs at the reference configuration q₀ (no load stiffness, no
//! multipliers), assembled once. A free assembly turns through several
//! radians under the paper's pulse, and K₀q̇ of a rigid rotation that far
//! from q₀ is not zero; so K acts in the assembly's co-rotated frame:
//! f_β = β 𝐑 K₀ 𝐑ᵀ q̇, with 𝐑 the best-fit (Procrustes) rigid rotation from
//! q₀ to the current configuration ([`super::frame::RotatingFrame`]), applied
//! to every (x, y) pair of coordinates. For a rigid motion 𝐑ᵀq̇ is a
//! translation plus an infinitesimal rotation about q₀, both in the null
//! space of K₀ (the reference is stress free): the β part vanishes for any
//! rigid motion at any angle. The α part damps absolute velocities by
//! design (DESIGN section 9): it also slows a free assembly's drift and
//! spin.
//!
//! **Iteration matrix.** The velocity of the new state depends on its
//! coordinates through q̇₁ = … + γ′Δq, γ′ = γ/(βₙh) (βₙ, γ the Newmark
//! parameters of generalized-α), so the Newton matrix gains γ′C, in the
//! integrator's scaling γ′/β′·(αM + βK). There K is the elastic tangent at
//! the configuration being factored: 𝐑K₀𝐑ᵀ up to the geometric stiffness
//! of the current stresses, which only changes the Newton convergence rate,
//! not the converged step.

use super::frame::RotatingFrame;
use super::solver::Placed;
use crate::linalg::sparse::{mul_vec, Triplets};
use crate::linalg::Scatter;
use crate::model::RayleighDamping;
use crate::system::{Linearization, System};
use faer::sparse::SparseColMat;

/// K₀, the stiffness Rayleigh damping uses: the tangent of the beams,
/// springs and torsion springs at the reference (module doc).
pub fn reference_stiffness(sys: &System) -> Triplets {
    let n = sys.ndof();
    let mut k0 = Triplets::new(n, n);
    sys.add_tangent_stiffness(&sys.reference(), &mut k0);
    k0
}

/// The damping ratio C = αM + βK₀ gives a mode of angular frequency ω
/// [rad/s] and mass-normalized shape φ: φᵀCφ/(2ω) = (α + β φᵀK₀φ)/(2ω)
/// [–]. For a mode of the unloaded reference φᵀK₀φ = ω² and this is
/// α/(2ω) + βω/2; a mode of a pre-stressed equilibrium is damped by the
/// reference's K₀ all the same (a guyed mast: 0.76173 %, where
/// α/(2ω) + βω/2 at its pre-stressed ω reads 0.74247 %).
pub fn mode_ratio(damping: RayleighDamping, k0: &Triplets, shape: &[f64], omega: f64) -> f64 {
    let stiffness: f64 = k0.entries().map(|(i, j, v)| shape[i] * v * shape[j]).sum();
    (damping.alpha + damping.beta * stiffness) / (2.0 * omega)
}

/// The Rayleigh damping force of one system.
pub struct RayleighForce {
    alpha: f64,
    beta: f64,
    /// K₀, the elastic stiffness at the reference [SI: N/m, N, N m].
    stiffness: SparseColMat<usize, f64>,
    /// Rotation from q₀ to the current configuration.
    frame: RotatingFrame,
    /// Scratch of length n + m (the frame also turns multiplier pairs).
    turned: Vec<f64>,
    product: Vec<f64>,
}

impl RayleighForce {
    /// The damping of `sys`; `None` without damping or with α = β = 0 (the
    /// integrator then runs exactly as without a `damping` entry).
    pub fn new(sys: &System, damping: Option<RayleighDamping>) -> Option<Self> {
        let d = damping?;
        if d.alpha == 0.0 && d.beta == 0.0 {
            return None;
        }
        let n = sys.ndof();
        let k0 = reference_stiffness(sys);
        let mut frame = RotatingFrame::new(sys);
        frame.anchor(&sys.q0);
        let len = n + sys.constraint_count();
        Some(RayleighForce {
            alpha: d.alpha,
            beta: d.beta,
            stiffness: k0.to_sparse(),
            frame,
            turned: vec![0.0; len],
            product: vec![0.0; len],
        })
    }

    /// out += αM q̇ + β𝐑K₀𝐑ᵀq̇ at coordinates q, velocities v.
    pub fn add_force(&mut self, sys: &System, q: &[f64], v: &[f64], out: &mut [f64]) {
        let n = sys.ndof();
        if self.alpha != 0.0 {
            let mv = &mut self.product[..n];
            sys.mass().mul_vec(v, mv);
            for (o, f) in out.iter_mut().zip(mv.iter()) {
                *o += self.alpha * f;
            }
        }
        if self.beta != 0.0 {
            self.frame.update(q);
            self.turned[..n].copy_from_slice(v);
            self.turned[n..].fill(0.0);
            self.frame.to_reference(&mut self.turned);
            mul_vec(&self.stiffness, &self.turned[..n], &mut self.product[..n]);
            self.product[n..].fill(0.0);
            self.frame.from_reference(&mut self.product);
            for (o, f) in out.iter_mut().zip(&self.product[..n]) {
                *o += self.beta * f;
            }
        }
    }

    /// out += scale·(αM + βK_t(at.q)), K_t the elastic tangent (no load
    /// stiffness, no multipliers): the velocity Jacobian of the force
    /// times scale.
    pub fn add_matrix(&self, sys: &System, at: &Linearization, scale: f64, out: &mut impl Scatter) {
        if self.alpha != 0.0 {
            sys.mass()
                .add_into(&mut Placed::scaled(out, scale * self.alpha));
        }
        if self.beta != 0.0 {
            let elastic = Linearization {
                q: at.q,
                lambda: None,
                time: at.time,
                load_scale: 0.0,
            };
            sys.add_tangent_stiffness(&elastic, &mut Placed::scaled(out, scale * self.beta));
        }
    }
}
