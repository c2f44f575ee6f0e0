//! Analytic eigenvalue sensitivities at the unstressed reference.
//!
//! For K φ = λ M φ with a mass-normalized φ (φᵀMφ = 1) and a simple
//! eigenvalue, dλ/dp = φᵀ(∂K/∂p − λ ∂M/∂p)φ. The constraints do not depend
//! on the parameters fitted here (they change no geometry), so φ — which
//! satisfies C_q φ = 0 — can be used in full coordinates. λ = ω² [SI:
//! rad²/s²]; f = ω/2π gives df/dp = (dλ/dp) / (8π² f).
//!
//! The parameter derivatives of K and M, without assembling them:
//! - Beam section: at the straight stress-free reference the element
//!   stiffness is EA·K_a + EI·K_b and the mass ρA·M₁, so φᵀ∂K/∂pφ =
//!   (∂EA/∂p / EA)·φᵀK_aφ·EA + (∂EI/∂p / EI)·φᵀK_bφ·EI, with
//!   ∂ln EA/∂h = 1/h, ∂ln EI/∂h = 3/h, ∂ln ρA/∂h = 1/h; for the width
//!   1/w, 1/w, 1/w; for E 1/E, 1/E, 0; for ρ 0, 0, 1/ρ. With `keep_mass` the
//!   density follows the section and ∂ρA/∂h = ∂ρA/∂w = 0. The beam parts of
//!   φᵀKφ come from the strain-variation form (no cancellation).
//! - Rigid-body mass and inertia, point mass: ∂M/∂p is a unit entry on the
//!   body's coordinates: φᵀ∂M/∂mφ = φx² + φy², φᵀ∂M/∂Jφ = φθ².
//! - Torsion spring: at the reference the relative angle is zero, so its
//!   Hessian is k g gᵀ and ∂K/∂k = H/k. Spring with a free length: every term
//!   of its Hessian is proportional to k (tension k(l − l₀)), so ∂K/∂k = H/k;
//!   with a preload the tension stays fixed and ∂K/∂k = ∇l ∇lᵀ.

use super::params::{ParamTarget, ParameterSet};
use crate::mechanics::pair::{PairGrad, PairHess};
use crate::mechanics::spring::{ForceElement, LinearSpring};
use crate::model::Model;
use crate::system::System;
use faer::Mat;

/// Quadratic forms of one mode shape, per beam.
struct BeamForms {
    /// φᵀ K_axial φ [SI: N/m · m² …] (2 × axial strain energy).
    axial: f64,
    /// φᵀ K_bending φ.
    bending: f64,
    /// φᵀ M_beam φ.
    mass: f64,
}

fn beam_forms(system: &System, beam: usize, phi: &[f64]) -> BeamForms {
    let b = &system.beams[beam];
    let q = &system.q0;
    let mut out = BeamForms {
        axial: 0.0,
        bending: 0.0,
        mass: 0.0,
    };
    for (k, el) in b.elements.iter().enumerate() {
        let dofs = b.element_dofs(k);
        let v = crate::mechanics::element::Vec8::from_fn(|i, _| phi[dofs[i]]);
        let s = el.quadratic_form(&system.element_state(q, &dofs), &v);
        out.axial += 2.0 * s.axial;
        out.bending += 2.0 * s.bending;
        out.mass += v.dot(&(el.mass() * v));
    }
    out
}

/// Index in `system.force_elements` of joint `j`'s torsion spring, and of
/// spring `s` (the order in which the system is assembled: torsion springs
/// of joints in joint order, then springs).
fn force_element_of(model: &Model, target: ParamTarget) -> Option<usize> {
    let has_torsion =
        |j: &crate::model::Joint| j.torsion_stiffness.is_some() || j.torsion_damping.is_some();
    match target {
        ParamTarget::TorsionStiffness(j) => {
            if !has_torsion(&model.joints[j]) {
                return None;
            }
            Some(model.joints[..j].iter().filter(|x| has_torsion(x)).count())
        }
        ParamTarget::SpringStiffness(s) => {
            Some(model.joints.iter().filter(|x| has_torsion(x)).count() + s)
        }
        _ => None,
    }
}

/// φᵀ H φ on a force element's local coordinates.
fn local_form(fe: &dyn ForceElement, h: &PairHess, phi: &[f64]) -> f64 {
    let mut v = PairGrad::zeros();
    for (i, d) in fe.pair().dofs().enumerate() {
        v[i] = phi[d];
    }
    v.dot(&(h * v))
}

/// dλ/dp for each parameter of `set`, for one mode (λ = ω², φ its shape in
/// full coordinates), of the system built from `model` (the model at the
/// current parameter values). `mass` is the system's mass matrix, used to
/// normalize φ.
pub fn eigenvalue_sensitivities(
    model: &Model,
    system: &System,
    mass: &Mat<f64>,
    set: &ParameterSet,
    lambda: f64,
    phi: &[f64],
    out: &mut [f64],
) {
    let norm = system.mass_quadratic_form(mass, phi);
    let q = &system.q0;
    for (p, slot) in set.params.iter().zip(out.iter_mut()) {
        let t = p.target;
        let value = t.get(model);
        let (dk, dm) = match t {
            ParamTarget::BeamHeight(i)
            | ParamTarget::BeamWidth(i)
            | ParamTarget::BeamYoung(i)
            | ParamTarget::BeamDensity(i) => {
                let f = beam_forms(system, i, phi);
                // Logarithmic derivatives of EA, EI, ρA times the value.
                let keep = set.keep_mass;
                let (la, lb, lm) = match t {
                    ParamTarget::BeamHeight(_) => (1.0, 3.0, if keep { 0.0 } else { 1.0 }),
                    ParamTarget::BeamWidth(_) => (1.0, 1.0, if keep { 0.0 } else { 1.0 }),
                    ParamTarget::BeamYoung(_) => (1.0, 1.0, 0.0),
                    _ => (0.0, 0.0, 1.0),
                };
                ((la * f.axial + lb * f.bending) / value, lm * f.mass / value)
            }
            ParamTarget::RigidMass(i) => {
                let d = system.rigid_bodies[i].dof0;
                (0.0, phi[d] * phi[d] + phi[d + 1] * phi[d + 1])
            }
            ParamTarget::RigidInertia(i) => {
                let d = system.rigid_bodies[i].dof0 + 2;
                (0.0, phi[d] * phi[d])
            }
            ParamTarget::PointMass(i) => {
                let d = system.point_masses[i].dof0;
                (0.0, phi[d] * phi[d] + phi[d + 1] * phi[d + 1])
            }
            ParamTarget::TorsionStiffness(_) | ParamTarget::SpringStiffness(_) => {
                let idx = force_element_of(model, t).expect("a fitted spring exists");
                let fe = system.force_elements[idx].as_ref();
                let mut h = PairHess::zeros();
                let preloaded = matches!(t, ParamTarget::SpringStiffness(s)
                    if model.springs[s].free_length.is_none());
                if preloaded {
                    // Tension fixed by the preload: only k ∇l ∇lᵀ scales with k.
                    let unit = LinearSpring {
                        label: String::new(),
                        pair: fe.pair().clone(),
                        stiffness: 1.0,
                        damping: 0.0,
                        free_length: fe.pair().separation(q).norm(),
                    };
                    unit.hessian(q, &mut h);
                    (local_form(&unit, &h, phi), 0.0)
                } else {
                    fe.hessian(q, &mut h);
                    (local_form(fe, &h, phi) / value, 0.0)
                }
            }
            // A load's force acts through the static equilibrium: its fit
            // is pre-stressed and takes finite differences there
            // ([`super::evaluate::EigenFrequencies`]); a dead load changes
            // no stiffness of the unstressed reference.
            ParamTarget::LoadForce(..) => (0.0, 0.0),
        };
        *slot = (dk - lambda * dm) / norm;
    }
}
