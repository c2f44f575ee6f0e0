//! Rayleigh damping C = αM + βK in the time integration: the first bending
//! mode of a pulsed cantilever decays at ζω with ζ = α/(2ω) + βω/2 (the
//! proportional-damping formula, ω from the eigenvalue problem), for α
//! only, β only and both; a free beam's rigid spin is not damped by β and
//! is damped by α at exactly the rate α (the α force is the drag αρAṙ, so
//! dL/dt = −αL); the energy balance closes with the damping's dissipation.

mod common;
use ancf_modal::analysis::simulate::{simulate, SimulationSettings};
use ancf_modal::analysis::transient::{Integrator, TransientSettings};
use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::model::RayleighDamping;
use ancf_modal::model::ValidModel;
use ancf_modal::System;
use common::*;
use serde_json::json;
use std::f64::consts::PI;

/// Time step [s]: (ωh)² = 4.5e-5 for the first cantilever mode (1071 Hz),
/// so the trapezoidal rule's error in the decay rate is ~1e-5 relative.
const STEP: f64 = 1e-6;

/// The paper's blade clamped at s = 0, with a 20 µs half-sine pulse of
/// 0.1 N at the tip (tip deflection ~1e-7 m: linear).
fn pulsed_cantilever(damping: RayleighDamping) -> ValidModel {
    model(json!({
        "name": "pulsed cantilever", "beams": [blade(8)],
        "joints": [{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}}],
        "loads": [{"at": {"beam": "blade", "s": L}, "force": [0.0, 0.1],
                   "time": {"half_sine": {"duration": 2e-5}}}],
        "damping": {"alpha": damping.alpha, "beta": damping.beta}
    }))
}

/// Decay rate [1/s] of the first mode's coordinate η = φ₁ᵀM(q − q₀) after
/// the pulse: the slope of ln(peak) against the peak times (successive
/// maxima of a damped sinusoid A e^{−σt} sin(ω_d t + ψ) fall exactly by
/// e^{−σT_d}), peaks located by a parabola through three samples.
fn first_mode_decay(model: &ValidModel, periods: f64) -> (f64, f64) {
    let sys = System::new(model);
    let modal = modal_at_reference(&sys, &ModalSettings::default()).unwrap();
    let mode = modal.first_bending().unwrap();
    let omega = 2.0 * PI * mode.frequency_hz;
    let mut m_phi = vec![0.0; sys.ndof()];
    sys.mass().mul_vec(&mode.shape, &mut m_phi);
    let settings = TransientSettings {
        step: STEP,
        end_time: periods * 2.0 * PI / omega,
        spectral_radius: 1.0,
        tolerance: 1e-12,
        damping: model.damping,
        ..TransientSettings::default()
    };
    let mut integ = Integrator::new(&sys, settings).unwrap();
    let mut st = integ.initial_state().unwrap();
    let (mut t, mut eta) = (Vec::new(), Vec::new());
    integ
        .run(&mut st, |s| {
            t.push(s.t);
            let d: f64 = (0..sys.ndof())
                .map(|i| m_phi[i] * (s.q[i] - sys.q0[i]))
                .sum();
            eta.push(d);
        })
        .unwrap();
    let (mut pt, mut pa) = (Vec::new(), Vec::new());
    for k in 1..eta.len() - 1 {
        if t[k] > 1e-4 && eta[k] > eta[k - 1] && eta[k] >= eta[k + 1] {
            let (a, b, c) = (eta[k - 1], eta[k], eta[k + 1]);
            let denom = a - 2.0 * b + c;
            let x = 0.5 * (a - c) / denom;
            pt.push(t[k] + x * STEP);
            pa.push((b - 0.25 * (a - c) * x).ln());
        }
    }
    assert!(pt.len() >= 10, "{} peaks", pt.len());
    let n = pt.len() as f64;
    let (mt, ma) = (pt.iter().sum::<f64>() / n, pa.iter().sum::<f64>() / n);
    let sxy: f64 = pt.iter().zip(&pa).map(|(x, y)| (x - mt) * (y - ma)).sum();
    let sxx: f64 = pt.iter().map(|x| (x - mt).powi(2)).sum();
    (-sxy / sxx, omega)
}

#[test]
fn first_mode_decays_at_zeta_omega() {
    // ζ₁ = 2 % from α alone, from β alone, and 1 % + 1 % (ω₁ = 2π·1071 Hz).
    let omega = 2.0 * PI * euler_bernoulli_hz(CANTILEVER_BL[0], L, H);
    let zeta = 0.02;
    for (name, damping) in [
        (
            "alpha only",
            RayleighDamping {
                alpha: 2.0 * zeta * omega,
                beta: 0.0,
            },
        ),
        (
            "beta only",
            RayleighDamping {
                alpha: 0.0,
                beta: 2.0 * zeta / omega,
            },
        ),
        (
            "alpha and beta",
            RayleighDamping {
                alpha: zeta * omega,
                beta: zeta / omega,
            },
        ),
    ] {
        let (sigma, omega_modal) = first_mode_decay(&pulsed_cantilever(damping), 20.0);
        let expected = damping.ratio(omega_modal) * omega_modal;
        let err = (sigma - expected) / expected;
        println!("{name}: decay {sigma:.4} 1/s, ζω {expected:.4} 1/s, error {err:.2e}");
        assert!(
            err.abs() < 5e-3,
            "{name}: decay rate {sigma} 1/s vs ζω = {expected} 1/s ({err:e})"
        );
    }
}

/// A free beam spinning rigidly at Ω about its centre: v = Ω ẑ × (r − c)
/// at the nodes and Ω ẑ × r′ for the slopes.
fn spinning_beam(damping: RayleighDamping, turns: f64) -> (f64, f64, f64, f64) {
    let mut m = free_beam(8).into_model();
    m.damping = Some(damping);
    let m = m.validated().expect("a valid model");
    let sys = System::new(&m);
    let omega = 200.0;
    let mut v = vec![0.0; sys.ndof()];
    let b = &sys.beams[0];
    for node in 0..b.node_count() {
        let d = b.dof0 + 4 * node;
        let (x, y) = (sys.q0[d] - 0.5 * L, sys.q0[d + 1]);
        v[d] = -omega * y;
        v[d + 1] = omega * x;
        v[d + 2] = -omega * sys.q0[d + 3];
        v[d + 3] = omega * sys.q0[d + 2];
    }
    let settings = TransientSettings {
        step: 1e-5,
        end_time: turns * 2.0 * PI / omega,
        spectral_radius: 1.0,
        damping: Some(damping),
        ..TransientSettings::default()
    };
    let mut integ = Integrator::new(&sys, settings).unwrap();
    let mut st = integ.state_at(sys.q0.clone(), v).unwrap();
    let (_, l0) = sys.momentum(&st.q, &st.v);
    let stats = integ.run(&mut st, |_| {}).unwrap();
    let (_, l1) = sys.momentum(&st.q, &st.v);
    let e0 = 0.5 * (sys.total_mass() * L * L / 12.0) * omega * omega;
    (l0, l1, stats.damping_dissipation / e0, st.t)
}

#[test]
fn rigid_spin_is_not_damped_by_beta_and_decays_at_alpha() {
    // β = 1e-5 s gives the first free-free mode ζ = 0.21: strong damping.
    // The spin stretches the beam (centrifugal strain ρΩ²L²/(8E) ≈ 2e-7,
    // strain energy ~1e-5 of the spin's), and β may absorb the vibration of
    // that stretch once, but not the spin: the loss must not grow with the
    // angle turned, and the angular momentum must stay (the damping forces
    // are internal).
    let beta_only = RayleighDamping {
        alpha: 0.0,
        beta: 1e-5,
    };
    let (l0, l1, lost_one, _) = spinning_beam(beta_only, 1.0);
    let (_, l3, lost_three, _) = spinning_beam(beta_only, 3.0);
    println!("β: lost {lost_one:e} after one turn, {lost_three:e} after three");
    for l in [l1, l3] {
        assert!(
            ((l - l0) / l0).abs() < 1e-6,
            "β damping changed the angular momentum by {:e}",
            (l - l0) / l0
        );
    }
    assert!(
        lost_one < 1e-4 && lost_three < 1.01 * lost_one + 1e-9,
        "β damping dissipated {lost_one:e} of the spin energy in one turn, {lost_three:e} in three"
    );
    // α damps absolute velocities: L(t) = L₀ e^{−αt}.
    let alpha = 30.0;
    let (l0, l1, _, t) = spinning_beam(RayleighDamping { alpha, beta: 0.0 }, 1.0);
    let expected = (-alpha * t).exp();
    println!("α: L/L₀ = {} vs e^(−αt) = {expected}", l1 / l0);
    assert!(
        (l1 / l0 - expected).abs() < 1e-4 * expected,
        "α: L/L₀ = {} vs e^(−αt) = {expected}",
        l1 / l0
    );
}

#[test]
fn energy_balance_closes_with_the_damping_dissipation() {
    let model = pulsed_cantilever(RayleighDamping {
        alpha: 100.0,
        beta: 2e-6,
    });
    let sim = simulate(
        System::new(&model),
        &[],
        &SimulationSettings {
            transient: TransientSettings {
                step: STEP,
                end_time: 0.01,
                spectral_radius: 1.0,
                tolerance: 1e-12,
                damping: model.damping,
                ..TransientSettings::default()
            },
            start: ancf_modal::analysis::statics::start::Start::Reference,
            sample_rate: 0.0,
            keep_partial: false,
        },
    )
    .unwrap();
    let e = &sim.energy;
    assert!(
        e.damping_dissipation_j > 0.5 * e.load_work_j,
        "damping dissipated {} J of {} J put in",
        e.damping_dissipation_j,
        e.load_work_j
    );
    assert!(
        e.error_j.abs() < 1e-3 * e.load_work_j,
        "energy balance error {} J against load work {} J",
        e.error_j,
        e.load_work_j
    );
}

#[test]
fn no_damping_entry_runs_exactly_as_before() {
    // `damping` α = β = 0 and no `damping` give bitwise the same run.
    let mut a = pulsed_cantilever(RayleighDamping {
        alpha: 0.0,
        beta: 0.0,
    })
    .into_model();
    let plain = {
        let mut m = a.clone();
        m.damping = None;
        m.validated().expect("a valid model")
    };
    a.damping = Some(RayleighDamping {
        alpha: 0.0,
        beta: 0.0,
    });
    let a = a.validated().expect("a valid model");
    let run = |m: &ValidModel| {
        let sys = System::new(m);
        let settings = TransientSettings {
            end_time: 2e-4,
            damping: m.damping,
            ..TransientSettings::default()
        };
        let mut integ = Integrator::new(&sys, settings).unwrap();
        let mut st = integ.initial_state().unwrap();
        integ.run(&mut st, |_| {}).unwrap();
        st
    };
    assert_eq!(run(&a), run(&plain));
}
