//! Layer 1b: joints, springs and rigid bodies against closed-form frequencies.

mod common;
use common::*;
use serde_json::json;
use std::f64::consts::PI;

fn hz(omega2: f64) -> f64 {
    omega2.sqrt() / (2.0 * PI)
}

#[test]
fn rigid_body_on_a_pin_with_torsion_spring() {
    // ω² = k_t / (J + m d²), d = distance from the pin to the centre of mass.
    let (m, j, d, kt) = (2e-3, 5e-9, 7e-3, 0.02);
    let r = modal_all(&model(json!({
        "name": "torsion pendulum",
        "rigid_bodies": [{"id": "r", "mass": m, "inertia": j, "position": [d * 0.6, d * 0.8], "angle_deg": 20.0}],
        "joints": [{"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"body": "r"}, "torsion_stiffness": kt}]
    })));
    assert_eq!(r.modes.len(), 1, "3 coordinates − 2 pin equations");
    let expect = hz(kt / (j + m * d * d));
    assert!(
        rel(r.modes[0].frequency_hz, expect).abs() <= 1e-12,
        "f = {} vs {expect}",
        r.modes[0].frequency_hz
    );
    assert_eq!(r.modes[0].kind.to_string(), "spring");
}

#[test]
fn point_mass_between_two_preloaded_springs() {
    // Two springs of stiffness k along x with tension T hold a mass m:
    // axial ω² = 2k/m, transverse ω² = 2T/(m l) (geometric stiffness).
    let (m, k, t, l) = (1e-3, 400.0, 3.0, 0.01);
    let r = modal_all(&model(json!({
        "name": "string",
        "point_masses": [{"id": "p", "mass": m, "position": [0.0, 0.0]}],
        "springs": [
            {"a": {"ground": [-l, 0.0]}, "b": {"body": "p"}, "stiffness": k, "preload": t},
            {"a": {"body": "p"}, "b": {"ground": [l, 0.0]}, "stiffness": k, "preload": t}
        ]
    })));
    let f: Vec<f64> = r.modes.iter().map(|x| x.frequency_hz).collect();
    assert!(
        rel(f[0], hz(2.0 * t / (m * l))).abs() <= 1e-12,
        "transverse {} vs {}",
        f[0],
        hz(2.0 * t / (m * l))
    );
    assert!(
        rel(f[1], hz(2.0 * k / m)).abs() <= 1e-12,
        "axial {} vs {}",
        f[1],
        hz(2.0 * k / m)
    );
}

#[test]
fn point_mass_on_a_slider_with_an_inclined_spring() {
    // Slider along the axis u at 30°, spring along v at 75° (stress-free):
    // ω² = k (u·v)² / m.
    let (m, k) = (2e-3, 900.0);
    let (ua, va) = (30f64.to_radians(), 75f64.to_radians());
    let r = modal_all(&model(json!({
        "name": "slider",
        "point_masses": [{"id": "p", "mass": m, "position": [0.0, 0.0]}],
        "joints": [{"type": "slider", "a": {"ground": [0.0, 0.0]}, "b": {"body": "p"}, "axis": [ua.cos(), ua.sin()]}],
        "springs": [{"a": {"body": "p"}, "b": {"ground": [0.02 * va.cos(), 0.02 * va.sin()]}, "stiffness": k, "free_length": 0.02}]
    })));
    assert_eq!(r.modes.len(), 1);
    let expect = hz(k * (ua - va).cos().powi(2) / m);
    assert!(
        rel(r.modes[0].frequency_hz, expect).abs() <= 1e-12,
        "{} vs {expect}",
        r.modes[0].frequency_hz
    );
}

#[test]
fn cantilever_with_tip_mass_matches_rayleigh_bound_and_converges() {
    // A tip mass much heavier than the beam: ω² → 3EI/(L³(M + 0.2357 m_beam))
    // (Rayleigh with the static deflection shape); exact answer slightly below.
    let tip = 20.0 * RHO * H * W * L;
    let m = model(json!({
        "name": "tip mass", "beams": [blade(16)],
        "point_masses": [{"id": "tip", "mass": tip, "position": [L, 0.0]}],
        "joints": [
            {"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}},
            {"type": "pin", "a": {"body": "tip"}, "b": {"beam": "blade", "s": L}}
        ]
    }));
    let f = modal_all(&m).modes[0].frequency_hz;
    let ei = E * W * H.powi(3) / 12.0;
    let rayleigh = hz(3.0 * ei / (L.powi(3) * (tip + 0.2357 * RHO * H * W * L)));
    let e = rel(f, rayleigh);
    assert!(
        e <= 0.0 && e > -2e-3,
        "tip-mass cantilever {f} Hz vs Rayleigh {rayleigh} Hz: {e:e}"
    );
}
