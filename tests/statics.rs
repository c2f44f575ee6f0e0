//! Static equilibrium: large deflections against the elastica, loss of
//! stability at Euler's load, unsupported loads and mechanisms.

mod common;
use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::error::AnalysisError;
use ancf_modal::System;
use common::*;
use serde_json::json;

/// A slender cantilever of the blade's material along x, clamped at s = 0,
/// with a dead tip load `force` [N] (global frame).
fn loaded_cantilever(elements: usize, h: f64, force: [f64; 2]) -> ancf_modal::Model {
    model(json!({
        "name": "elastica",
        "beams": [{
            "id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": L,
            "elements": elements, "nodes_at_attachments": false,
            "section": {"height": h, "width": W},
            "material": {"young": E, "density": RHO}
        }],
        "joints": [{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}}],
        "loads": [{"at": {"beam": "b", "s": L}, "force": force}]
    }))
}

fn ei(h: f64) -> f64 {
    E * W * h.powi(3) / 12.0
}

#[test]
fn elastica_tip_displacements() {
    // Inextensible elastica, cantilever with a dead tip load normal to the
    // undeformed axis, α = P L² / EI (standard tables, e.g. Mattiasson 1981).
    let table = [
        (1.0, 0.30172, 0.05643),
        (2.0, 0.49346, 0.16064),
        (5.0, 0.71379, 0.38763),
        (10.0, 0.81061, 0.55500),
    ];
    let h = 1e-3 * L;
    for (alpha, v_ref, u_ref) in table {
        let p = alpha * ei(h) / (L * L);
        let m = loaded_cantilever(16, h, [0.0, p]);
        let sys = System::new(&m);
        let eq = solve_equilibrium(&sys, &StaticSettings::default()).expect("equilibrium");
        let tip = 4 * 16;
        let v = eq.q[tip + 1] / L;
        let u = (L - eq.q[tip]) / L;
        eprintln!("alpha {alpha}: v/L {v:.6} (ref {v_ref}) u/L {u:.6} (ref {u_ref}) steps {} iters {} res {:e}", eq.steps, eq.iterations, eq.residual);
        assert!(
            (v - v_ref).abs() <= 1e-3,
            "α = {alpha}: tip deflection v/L = {v:.6}, elastica {v_ref} (limit 1e-3)"
        );
        assert!(
            (u - u_ref).abs() <= 1e-3,
            "α = {alpha}: tip shortening u/L = {u:.6}, elastica {u_ref} (limit 1e-3)"
        );
    }
}

#[test]
fn clamp_reaction_balances_the_tip_load() {
    // The weld's force on the beam is −P: the beam's equilibrium as a whole.
    let h = 1e-3 * L;
    let p = 5.0 * ei(h) / (L * L);
    let sys = System::new(&loaded_cantilever(16, h, [0.0, p]));
    let eq = solve_equilibrium(&sys, &StaticSettings::default()).expect("equilibrium");
    let (fx, fy) = (-eq.lambda[0], -eq.lambda[1]);
    assert!(
        fx.abs() <= 1e-9 * p && (fy + p).abs() <= 1e-9 * p,
        "clamp force ({fx:e}, {fy:e}) vs (0, −{p:e}) N"
    );
    // Moment about the clamp: −λ₂ balances P times the deformed lever arm x_tip.
    let x_tip = eq.q[4 * 16];
    let m = -eq.lambda[2];
    assert!(
        (m + p * x_tip).abs() <= 1e-6 * p * L,
        "clamp moment {m:e} vs −P x_tip = {:e} N m",
        -p * x_tip
    );
}

#[test]
fn load_without_support_is_refused() {
    let m = model(json!({
        "name": "free", "beams": [blade(8)],
        "loads": [{"at": {"beam": "blade", "s": L}, "force": [0.0, 1.0]}]
    }));
    let err = solve_equilibrium(&System::new(&m), &StaticSettings::default()).unwrap_err();
    assert_eq!(
        err,
        AnalysisError::NoSupport,
        "a loaded free beam has no equilibrium"
    );
}

#[test]
fn mechanism_names_the_free_motion() {
    // Pinned at one end only: the tangent at the reference has no stiffness
    // against turning about the pin, the motion the transverse tip load
    // drives; the tip moves most. (A dead load could pull the beam round into
    // line with it, but Newton from a singular tangent has no direction to
    // get there, so the solver refuses rather than guess.)
    let m = model(json!({
        "name": "pinned", "beams": [blade(8)],
        "joints": [{"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}}],
        "loads": [{"at": {"beam": "blade", "s": L}, "force": [0.0, 1.0]}]
    }));
    match solve_equilibrium(&System::new(&m), &StaticSettings::default()) {
        Err(AnalysisError::Mechanism { dof }) => {
            // The kinetic share √M_ii |φ_i| peaks near the tip (the end node
            // has half the consistent mass of an interior one).
            let near_tip = ["node 7", "node 8"].iter().any(|n| dof.contains(n));
            assert!(
                near_tip && dof.ends_with("ry"),
                "free motion moves the outer nodes transversely most: {dof}"
            );
        }
        other => panic!("expected a mechanism error, got {other:?}"),
    }
    // With a torsion spring at the pin the same load is carried.
    let mut v = serde_json::to_value(&m).unwrap();
    v["joints"][0]["torsion_stiffness"] = json!(10.0);
    assert!(solve_equilibrium(&System::new(&model(v)), &StaticSettings::default()).is_ok());
}

#[test]
fn starved_newton_reports_non_convergence() {
    // α = 10 needs ~16 full Newton iterations from the straight state; with
    // 3 per step and no load-step cutting below half the load, it must fail.
    let h = 1e-3 * L;
    let p = 10.0 * ei(h) / (L * L);
    let sys = System::new(&loaded_cantilever(16, h, [0.0, p]));
    let settings = StaticSettings {
        max_iterations: 3,
        min_increment: 0.5,
        ..Default::default()
    };
    match solve_equilibrium(&sys, &settings) {
        Err(AnalysisError::NotConverged {
            iterations,
            residual,
            ..
        }) => {
            assert!(
                iterations <= 3 && residual > 0.0,
                "iterations {iterations}, residual {residual:e}"
            );
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}
