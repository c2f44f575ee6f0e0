//! The load path does not decide whether an equilibrium exists.
//!
//! - A steel strip pinned at one end and on a slider at the other, pulled
//!   taut by a load at the slider end, under gravity: without its tension
//!   the strip hangs ~0.1 m (it is a slack string under gravity alone), yet
//!   at every load factor the taut equilibrium must be found, and its
//!   midspan sag must equal the closed form of a pinned beam under tension T
//!   and uniform load q (independent source): w = qL²/(8T) −
//!   (q/(Tλ²))(1 − 1/cosh(λL/2)), λ² = T/EI, L the stretched span, q the
//!   weight per current length.
//! - For generated pre-stressed assemblies whose reduced tangent stays
//!   positive definite on the way, the equilibrium does not depend on the
//!   order in which gravity and the loads are applied (invariance).

use ancf_modal::analysis::statics::{
    solve_equilibrium, solve_equilibrium_along, LoadPath, StaticSettings,
};
use ancf_modal::error::Source;
use ancf_modal::model::Model;
use ancf_modal::model::ValidModel;
use ancf_modal::system::System;
use proptest::prelude::*;
use serde_json::json;

const E: f64 = 210e9;
const RHO: f64 = 7850.0;
const H: f64 = 0.3e-3;
const W: f64 = 1e-3;
const L: f64 = 0.65;
const G: f64 = 9.81;
const T0: f64 = 80.0;

fn string(elements: usize) -> ValidModel {
    let v = json!({
        "name": "taut_string", "gravity": [0.0, -G],
        "beams": [{"id": "strip", "start": [0.0, 0.0], "angle_deg": 0.0, "length": L,
                   "elements": elements, "section": {"height": H, "width": W},
                   "material": {"young": E, "density": RHO}}],
        "joints": [
            {"id": "left", "type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "strip", "s": 0.0}},
            {"id": "right", "type": "slider", "a": {"ground": [L, 0.0]}, "b": {"beam": "strip", "s": L},
             "axis": [1.0, 0.0]}
        ],
        "loads": [{"id": "tension", "at": {"beam": "strip", "s": L}, "force": [T0, 0.0], "time": "constant"}]
    });
    Model::from_json(&v.to_string(), Source::BuiltIn).expect("valid model")
}

/// Midspan sag of a pinned beam under tension `t` and uniform load `q`
/// over span `l` [SI: m].
fn tensioned_beam_sag(q: f64, t: f64, l: f64) -> f64 {
    let ei = E * W * H.powi(3) / 12.0;
    let lam2 = t / ei;
    let lam = lam2.sqrt();
    q * l * l / (8.0 * t) - (q / (t * lam2)) * (1.0 - 1.0 / (lam * l / 2.0).cosh())
}

#[test]
fn tensioned_string_under_gravity_is_found_at_every_load_factor() {
    let factors = [0.05, 0.2, 0.45, 0.5, 0.65, 0.95, 1.0, 1.2, 1.5, 3.0];
    for elements in [8usize, 16, 32] {
        let m = string(elements);
        let sys = System::new(&m);
        let beam = &sys.beams[0];
        let mid = beam.node_count() / 2;
        assert!(
            (beam.node_s[mid] - L / 2.0).abs() < 1e-12,
            "a node at midspan"
        );
        for &f in &factors {
            let eq = solve_equilibrium(
                &sys,
                &StaticSettings {
                    load_scale: f,
                    ..Default::default()
                },
            )
            .unwrap_or_else(|e| panic!("{elements} elements, load factor {f}: {e}"));
            let t = T0 * f;
            let strain = t / (E * H * W);
            let last = beam.dof0 + 4 * (beam.node_count() - 1);
            let first = beam.dof0;
            let span = eq.q[last] - eq.q[first];
            let q = RHO * H * W * G / (1.0 + strain);
            let expected = tensioned_beam_sag(q, t, span);
            let sag = eq.q[first + 1] - eq.q[beam.dof0 + 4 * mid + 1];
            let rel = (sag - expected) / expected;
            assert!(
                rel.abs() <= 1e-4,
                "{elements} elements, load factor {f}: sag {sag:.9e} m, closed form {expected:.9e} m ({rel:.2e}), found {}",
                eq.branch
            );
        }
    }
}

#[test]
fn a_model_with_one_of_gravity_and_loads_names_that_one_path() {
    // Without gravity only the loads are ramped, and gravity alone at load
    // factor 0 (outside-eyes trial of issue 33: a gravity-free column was
    // said to be on the path "gravity first, then the loads").
    let mut v = serde_json::to_value(string(8)).unwrap();
    v["gravity"] = json!([0.0, 0.0]);
    let no_gravity = Model::from_json(&v.to_string(), Source::BuiltIn).unwrap();
    let path = |m: &ValidModel, load_scale: f64| {
        let sys = System::new(m);
        let settings = StaticSettings {
            load_scale,
            ..Default::default()
        };
        solve_equilibrium(&sys, &settings).unwrap().branch.path
    };
    assert_eq!(path(&no_gravity, 1.0), Some(LoadPath::LoadsOnly));
    assert_eq!(path(&string(8), 0.0), Some(LoadPath::GravityOnly));
    assert!(matches!(
        path(&string(8), 1.0),
        Some(LoadPath::GravityFirst | LoadPath::Together | LoadPath::LoadsFirst)
    ));
}

/// A clamped beam with a tip mass and a preloaded spring from its tip to
/// the ground, under gravity and a dead tip load, all moderate (below a
/// quarter of the cantilever's buckling load in compression).
fn prestressed_cantilever(
    length: f64,
    height: f64,
    angle_deg: f64,
    tip_force: [f64; 2],
    preload: f64,
    gravity_angle_deg: f64,
) -> ValidModel {
    let width = 2.0 * height;
    let ei = E * width * height.powi(3) / 12.0;
    // Forces in units of the cantilever's buckling load π²EI/(4L²).
    let p_cr = std::f64::consts::PI.powi(2) * ei / (4.0 * length * length);
    let (s, c) = angle_deg.to_radians().sin_cos();
    let tip = [length * c, length * s];
    let (gs, gc) = gravity_angle_deg.to_radians().sin_cos();
    let v = json!({
        "name": "prestressed_cantilever", "gravity": [G * gc, G * gs],
        "beams": [{"id": "b", "start": [0.0, 0.0], "angle_deg": angle_deg, "length": length,
                   "elements": 6, "section": {"height": height, "width": width},
                   "material": {"young": E, "density": RHO}}],
        "point_masses": [{"id": "tip", "mass": RHO * length * height * width, "position": tip}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}},
            {"id": "tip_pin", "type": "pin", "a": {"body": "tip"}, "b": {"beam": "b", "s": length}}
        ],
        "springs": [{"id": "s", "a": {"ground": [tip[0] - length * s, tip[1] + length * c]},
                     "b": {"beam": "b", "s": length}, "stiffness": p_cr / length,
                     "preload": preload * p_cr}],
        "loads": [{"id": "f", "at": {"beam": "b", "s": length},
                   "force": [tip_force[0] * p_cr, tip_force[1] * p_cr], "time": "constant"}]
    });
    Model::from_json(&v.to_string(), Source::BuiltIn).expect("valid model")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn equilibrium_does_not_depend_on_the_load_order(
        length in 0.01f64..2.0,
        slender in 30.0f64..300.0,
        angle in -180.0f64..180.0,
        fx in -0.25f64..0.25,
        fy in -0.25f64..0.25,
        preload in 0.0f64..0.2,
        gravity_angle in -180.0f64..180.0,
    ) {
        let m = prestressed_cantilever(length, length / slender, angle, [fx, fy], preload, gravity_angle);
        let sys = System::new(&m);
        let settings = StaticSettings::default();
        let solved: Vec<_> = [LoadPath::GravityFirst, LoadPath::Together, LoadPath::LoadsFirst]
            .into_iter()
            .map(|p| solve_equilibrium_along(&sys, &settings, p))
            .collect();
        // Only paths that stay definite count (a path that loses stability is
        // not the premise); at least one must succeed.
        let found: Vec<_> = solved.iter().filter_map(|r| r.as_ref().ok()).collect();
        prop_assert!(!found.is_empty(), "no path converged: {:?}", solved);
        let scale = sys.length_scale();
        for eq in &found[1..] {
            let d = eq.q.iter().zip(&found[0].q).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            prop_assert!(d <= 1e-8 * scale, "{} vs {}: states differ by {d:.3e} m", eq.branch, found[0].branch);
        }
    }
}
