//! Complex modes of damped assemblies (`analysis::damped_modes`) against
//! closed forms: one damped oscillator (ζ = c/(2√(km)), ω_d = ωₙ√(1 − ζ²),
//! also overdamped), a two-mass chain with one damper (the roots of
//! det(λ²M + λC + K), found here from the quartic's companion matrix), and
//! Rayleigh damping alone (ζ = α/(2ω) + βω/2).

mod common;
use ancf_modal::analysis::damped_modes::{damped_modes, has_dampers};
use ancf_modal::analysis::modal::{modal_at_reference, ModalSettings};
use ancf_modal::model::RayleighDamping;
use ancf_modal::System;
use common::model;
use nalgebra::{DMatrix, Schur};
use serde_json::{json, Value};
use std::f64::consts::PI;

/// Masses on x rails, springs (with dampers) along x: ground – k₁ – m₁ –
/// k₂, c₂ – m₂ (m₂ and its spring left out when `m2` is `None`).
fn chain(m1: f64, k1: f64, c1: f64, second: Option<(f64, f64, f64)>) -> Value {
    let mut v = json!({
        "name": "chain",
        "point_masses": [{"id": "m1", "mass": m1, "position": [0.1, 0.0]}],
        "joints": [{"type": "slider", "a": {"ground": [0.0, 0.0]}, "b": {"body": "m1"},
                    "axis": [1.0, 0.0]}],
        "springs": [{"a": {"ground": [0.0, 0.0]}, "b": {"body": "m1"}, "stiffness": k1,
                     "damping": c1, "free_length": 0.1}]
    });
    if let Some((m2, k2, c2)) = second {
        v["point_masses"]
            .as_array_mut()
            .unwrap()
            .push(json!({"id": "m2", "mass": m2, "position": [0.2, 0.0]}));
        v["joints"].as_array_mut().unwrap().push(
            json!({"type": "slider", "a": {"ground": [0.0, 0.0]}, "b": {"body": "m2"},
                   "axis": [1.0, 0.0]}),
        );
        v["springs"].as_array_mut().unwrap().push(
            json!({"a": {"body": "m1"}, "b": {"body": "m2"}, "stiffness": k2, "damping": c2,
                   "free_length": 0.1}),
        );
    }
    v
}

fn complex_modes(v: Value) -> Vec<ancf_modal::analysis::damped_modes::DampedMode> {
    let m = model(v);
    let sys = System::new(&m);
    let at = sys.reference();
    let r = modal_at_reference(&sys, &ModalSettings::default()).unwrap();
    assert!(has_dampers(&sys, at.q));
    damped_modes(&sys, &at, &r, m.damping).unwrap()
}

#[test]
fn one_damped_oscillator_has_the_closed_form_ratio_and_damped_frequency() {
    let (m, k): (f64, f64) = (0.02, 5.0e4);
    let wn = (k / m).sqrt();
    for c in [0.2f64, 10.0, 80.0] {
        let zeta = c / (2.0 * (k * m).sqrt());
        let d = complex_modes(chain(m, k, c, None));
        assert_eq!(d.len(), 1, "one elastic mode");
        let d = d[0];
        assert!(
            (d.damping_ratio - zeta).abs() < 1e-9 * zeta.max(1.0),
            "c = {c}: ζ {} vs c/(2√(km)) = {zeta}",
            d.damping_ratio
        );
        assert!(
            (d.natural_hz - wn / (2.0 * PI)).abs() < 1e-9 * wn,
            "c = {c}: natural {} Hz vs {} Hz",
            d.natural_hz,
            wn / (2.0 * PI)
        );
        match d.damped_hz {
            Some(fd) => {
                let exact = wn * (1.0 - zeta * zeta).sqrt() / (2.0 * PI);
                assert!(
                    zeta < 1.0 && (fd - exact).abs() < 1e-9 * wn,
                    "f_d {fd} vs {exact}"
                );
            }
            None => assert!(zeta > 1.0, "no damped frequency only when overdamped"),
        }
    }
}

/// Roots of a₄λ⁴ + a₃λ³ + a₂λ² + a₁λ + a₀ from the companion matrix.
fn quartic_roots(a: [f64; 5]) -> Vec<(f64, f64)> {
    let [a0, a1, a2, a3, a4] = a;
    let mut c = DMatrix::<f64>::zeros(4, 4);
    for i in 1..4 {
        c[(i, i - 1)] = 1.0;
    }
    for (i, ai) in [a0, a1, a2, a3].into_iter().enumerate() {
        c[(i, 3)] = -ai / a4;
    }
    Schur::new(c)
        .complex_eigenvalues()
        .iter()
        .map(|z| (z.re, z.im))
        .collect()
}

#[test]
fn a_two_mass_chain_with_one_damper_has_the_characteristic_roots() {
    let (m1, k1) = (0.01, 4.0e4);
    let (m2, k2, c2) = (0.03, 2.5e4, 6.0);
    // det(λ²M + λC + K) with M = diag(m₁, m₂), K = [[k₁+k₂, −k₂], [−k₂, k₂]],
    // C = c₂[[1, −1], [−1, 1]]: (m₁λ² + c₂λ + k₁ + k₂)(m₂λ² + c₂λ + k₂) − (c₂λ + k₂)².
    let a = [
        (k1 + k2) * k2 - k2 * k2,
        c2 * k2 + (k1 + k2) * c2 - 2.0 * c2 * k2,
        m1 * k2 + c2 * c2 + m2 * (k1 + k2) - c2 * c2,
        m1 * c2 + m2 * c2,
        m1 * m2,
    ];
    let mut exact: Vec<(f64, f64)> = quartic_roots(a)
        .into_iter()
        .filter(|&(_, im)| im > 0.0)
        .map(|(re, im)| {
            let wn = re.hypot(im);
            (wn / (2.0 * PI), -re / wn)
        })
        .collect();
    exact.sort_by(|x, y| x.0.total_cmp(&y.0));
    let d = complex_modes(chain(m1, k1, 0.0, Some((m2, k2, c2))));
    assert_eq!(d.len(), 2);
    for (mode, (fn_exact, zeta_exact)) in d.iter().zip(&exact) {
        assert!(
            (mode.natural_hz - fn_exact).abs() < 1e-9 * fn_exact,
            "mode {}: natural {} Hz vs the root's {fn_exact} Hz",
            mode.index,
            mode.natural_hz
        );
        assert!(
            (mode.damping_ratio - zeta_exact).abs() < 1e-9,
            "mode {}: ζ {} vs the root's {zeta_exact}",
            mode.index,
            mode.damping_ratio
        );
    }
    // The damper couples the modes: the ratios differ from first-order
    // (diagonal) estimates, which would not see the coupling.
    assert!(exact[0].1 > 0.0 && exact[1].1 > 0.0);
}

#[test]
fn rayleigh_damping_alone_gives_alpha_over_2_omega_plus_beta_omega_over_2() {
    let m = common::cantilever(8);
    let sys = System::new(&m);
    let at = sys.reference();
    let r = modal_at_reference(&sys, &ModalSettings::default()).unwrap();
    assert!(!has_dampers(&sys, at.q));
    let rayleigh = RayleighDamping {
        alpha: 30.0,
        beta: 2.0e-7,
    };
    let d = damped_modes(&sys, &at, &r, Some(rayleigh)).unwrap();
    assert!(!d.is_empty());
    for mode in &d {
        let undamped = &r.modes[mode.index - 1];
        let w = 2.0 * PI * undamped.frequency_hz;
        let zeta = rayleigh.ratio(w);
        assert!(
            (mode.damping_ratio - zeta).abs() < 1e-9 * zeta.max(1e-3),
            "mode {}: ζ {} vs α/(2ω) + βω/2 = {zeta}",
            mode.index,
            mode.damping_ratio
        );
        assert!(
            (mode.natural_hz - undamped.frequency_hz).abs() < 1e-9 * undamped.frequency_hz,
            "mode {}: natural frequency unchanged by damping",
            mode.index
        );
    }
}

#[test]
fn modal_json_reports_the_complex_ratio_of_a_damped_oscillator() {
    let (m, k, c): (f64, f64, f64) = (0.02, 5.0e4, 10.0);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("osc.json");
    std::fs::write(&path, chain(m, k, c, None).to_string()).unwrap();
    let zeta = c / (2.0 * (k * m).sqrt());
    let wn = (k / m).sqrt();
    // At the reference and at the (here unloaded) static equilibrium.
    for prestress in [false, true] {
        let mut cmd = assert_cmd::Command::cargo_bin("ancf-modal").unwrap();
        cmd.args(["modal", "--json"]).arg(&path);
        if prestress {
            cmd.arg("--prestress");
        }
        let out = cmd.assert().success();
        let doc: Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
        let mode = doc["modes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["kind"] != "rigid")
            .expect("one elastic mode")
            .clone();
        let z = mode["damping_ratio"].as_f64().unwrap();
        let fd = mode["damped_frequency_hz"].as_f64().unwrap();
        assert!(
            (z - zeta).abs() < 1e-9,
            "prestress {prestress}: ζ {z} vs c/(2√(km)) = {zeta}"
        );
        let exact = wn * (1.0 - zeta * zeta).sqrt() / (2.0 * PI);
        assert!(
            (fd - exact).abs() < 1e-9 * exact,
            "prestress {prestress}: f_d {fd} vs {exact}"
        );
    }
}
