//! Layer 1: single beams against analytic Euler–Bernoulli frequencies, and
//! the O(h⁴) convergence rate of Hermite cubic elements (DESIGN §3).

mod common;
use ancf_modal::analysis::ModeKind;
use common::*;
use serde_json::json;

#[test]
fn free_free_first_bending_8_and_32_elements() {
    let exact = euler_bernoulli_hz(FREE_FREE_BL[0], L, H);
    let e8 = rel(
        freqs(&modal_all(&free_beam(8)), ModeKind::Bending)[0],
        exact,
    );
    let e32 = rel(
        freqs(&modal_all(&free_beam(32)), ModeKind::Bending)[0],
        exact,
    );
    assert!(
        e8 > 0.0 && e8 <= 1e-4,
        "8 elements: first bending relative error {e8:e} (limit 1e-4, from above)"
    );
    assert!(
        e32 > 0.0 && e32 <= 1e-6,
        "32 elements: first bending relative error {e32:e} (limit 1e-6)"
    );
}

#[test]
fn free_free_first_three_bending_16_elements() {
    let f = freqs(&modal_all(&free_beam(16)), ModeKind::Bending);
    for k in 0..3 {
        let e = rel(f[k], euler_bernoulli_hz(FREE_FREE_BL[k], L, H));
        assert!(
            e.abs() <= 2e-4,
            "16 elements: bending mode {} relative error {e:e} (limit 2e-4)",
            k + 1
        );
    }
}

#[test]
fn free_free_first_axial_8_elements() {
    let f = freqs(&modal_all(&free_beam(8)), ModeKind::Axial);
    let e = rel(f[0], axial_hz(1, L));
    assert!(
        e.abs() <= 1e-6,
        "8 elements: first axial relative error {e:e} (limit 1e-6)"
    );
}

/// Error ratio per halving of h: 2⁴ = 16 for O(h⁴).
fn assert_fourth_order(errors: &[f64], what: &str) {
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!(
            (13.0..=19.0).contains(&ratio),
            "{what}: error ratio {ratio:.2} per halving (expected ≈16), errors {errors:?}"
        );
    }
}

#[test]
fn free_free_converges_at_fourth_order() {
    let exact = euler_bernoulli_hz(FREE_FREE_BL[0], L, H);
    let errors: Vec<f64> = [8, 16, 32]
        .iter()
        .map(|&n| {
            rel(
                freqs(&modal_all(&free_beam(n)), ModeKind::Bending)[0],
                exact,
            )
        })
        .collect();
    assert_fourth_order(&errors, "free-free first bending");
}

#[test]
fn cantilever_matches_euler_bernoulli_and_converges_at_fourth_order() {
    let errs: Vec<Vec<f64>> = [8, 16, 32]
        .iter()
        .map(|&n| {
            let f = freqs(&modal_all(&cantilever(n)), ModeKind::Bending);
            (0..3)
                .map(|k| rel(f[k], euler_bernoulli_hz(CANTILEVER_BL[k], L, H)))
                .collect()
        })
        .collect();
    assert!(
        errs[0][0].abs() <= 1e-4,
        "cantilever 8 el: first bending error {:e}",
        errs[0][0]
    );
    assert!(
        errs[2][0].abs() <= 1e-6,
        "cantilever 32 el: first bending error {:e}",
        errs[2][0]
    );
    for (k, e) in errs[1].iter().enumerate() {
        assert!(
            e.abs() <= 2e-4,
            "cantilever 16 el: bending mode {} error {e:e}",
            k + 1
        );
    }
    let first: Vec<f64> = errs.iter().map(|e| e[0]).collect();
    assert_fourth_order(&first, "cantilever first bending");
}

#[test]
fn clamp_fixes_slope_direction_not_axial_strain() {
    // Clamped-free axial modes: f_k = (2k−1)/(4L) √(E/ρ). A clamp that also
    // fixed r'x would stiffen them (DESIGN §3).
    let f = freqs(&modal_all(&cantilever(16)), ModeKind::Axial);
    let exact = 1.0 / (4.0 * L) * (E / RHO).sqrt();
    let e = rel(f[0], exact);
    assert!(
        e.abs() <= 1e-6,
        "cantilever first axial relative error {e:e}"
    );
}

#[test]
fn pinned_roller_beam_matches_k_pi() {
    // Pin at s = 0, roller (slider along the beam axis) at s = L: simply supported, βL = kπ.
    let m = model(json!({
        "name": "simply supported", "beams": [blade(16)],
        "joints": [
            {"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}},
            {"type": "slider", "a": {"ground": [L, 0.0]}, "b": {"beam": "blade", "s": L}, "axis": [1.0, 0.0]}
        ]
    }));
    let r = modal_all(&m);
    assert_eq!(
        r.rigid_modes, 0,
        "a pinned-roller beam has no zero-frequency mode"
    );
    let f = freqs(&r, ModeKind::Bending);
    for k in 1..=3 {
        let e = rel(
            f[k - 1],
            euler_bernoulli_hz(k as f64 * std::f64::consts::PI, L, H),
        );
        assert!(
            e.abs() <= 2e-4,
            "simply supported mode {k}: relative error {e:e}"
        );
    }
}

#[test]
fn mode_shapes_are_mass_normalized_and_satisfy_constraints() {
    use ancf_modal::analysis::{modal_at_reference, ModalSettings};
    use ancf_modal::System;
    let sys = System::new(&ancf_modal::Model::builtin());
    let r = modal_at_reference(&sys, &ModalSettings::default()).unwrap();
    let m = sys.mass_matrix();
    let mut cq = faer::Mat::zeros(sys.constraint_count(), sys.ndof());
    sys.constraint_jacobian(&sys.q0, &mut cq);
    let n = sys.ndof();
    for a in r.modes.iter().take(10) {
        for b in r.modes.iter().take(10) {
            let mut dot = 0.0;
            for i in 0..n {
                for j in 0..n {
                    dot += a.shape[i] * m[(i, j)] * b.shape[j];
                }
            }
            let expect = if a.index == b.index { 1.0 } else { 0.0 };
            assert!(
                (dot - expect).abs() <= 1e-9,
                "φ{}ᵀMφ{} = {dot:e}, expected {expect}",
                a.index,
                b.index
            );
        }
        for row in 0..cq.nrows() {
            let c: f64 = (0..n).map(|j| cq[(row, j)] * a.shape[j]).sum();
            let scale: f64 = a.shape.iter().map(|x| x.abs()).fold(0.0, f64::max);
            assert!(
                c.abs() <= 1e-10 * scale,
                "mode {} violates constraint row {row}: C_q φ = {c:e}",
                a.index
            );
        }
    }
}
