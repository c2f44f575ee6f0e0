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
