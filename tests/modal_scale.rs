//! The modal core at scale: exact zero-mode counts and Euler–Bernoulli
//! frequencies on 2,000-element beams (sparse path), slender, MEMS-sized
//! and 25 m beams, a free ladder frame of welded beams (dense and sparse
//! paths agree), and the accuracy estimate against the other path.

mod common;

use ancf_modal::analysis::{modal_at_reference, EigenMethod, ModalResult, ModalSettings, ModeKind};
use ancf_modal::model::ValidModel;
use ancf_modal::System;
use common::*;
use serde_json::{json, Value};

fn run(model: &ValidModel, modes: usize, method: EigenMethod) -> ModalResult {
    let settings = ModalSettings {
        modes: Some(modes),
        method,
    };
    modal_at_reference(&System::new(model), &settings).expect("modal analysis succeeds")
}

/// A beam of length l and height h along x, scaled section width w = h·W/H.
fn beam(elements: usize, l: f64, h: f64) -> Value {
    json!({
        "id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": l,
        "elements": elements, "nodes_at_attachments": false,
        "section": {"height": h, "width": W},
        "material": {"young": E, "density": RHO}
    })
}

fn supported(elements: usize, l: f64, h: f64, joints: Value) -> ValidModel {
    model(json!({"name": "beam", "beams": [beam(elements, l, h)], "joints": joints}))
}

fn check_bending(r: &ModalResult, bl: &[f64], l: f64, h: f64, tol: f64, what: &str) {
    let f = freqs(r, ModeKind::Bending);
    assert!(
        f.len() >= bl.len(),
        "{what}: {} bending modes computed",
        f.len()
    );
    for (k, (&fk, &b)) in f.iter().zip(bl).enumerate() {
        let exact = euler_bernoulli_hz(b, l, h);
        let e = rel(fk, exact);
        assert!(
            e.abs() <= tol,
            "{what}: bending mode {} at {fk:.9} Hz, Euler–Bernoulli {exact:.9} Hz, relative error {e:.2e} > {tol:e}",
            k + 1
        );
    }
}

const PINNED_FREE_BL: [f64; 4] = [3.926602312, 7.068582745, 10.21017612, 13.35176878];
const PINNED_PINNED_BL: [f64; 4] = [
    std::f64::consts::PI,
    2.0 * std::f64::consts::PI,
    3.0 * std::f64::consts::PI,
    4.0 * std::f64::consts::PI,
];

#[test]
fn two_thousand_element_beams_count_zero_modes_exactly_and_match_euler_bernoulli() {
    let n = 2000;
    let clamp =
        json!([{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}}]);
    let pin = json!([{"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}}]);
    let pin_roller = json!([
        {"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}},
        {"type": "slider", "a": {"ground": [L, 0.0]}, "b": {"beam": "b", "s": L}, "axis": [1.0, 0.0]}
    ]);
    let cases: [(&str, Value, usize, &[f64]); 4] = [
        ("cantilever", clamp, 0, &CANTILEVER_BL),
        ("pinned-free", pin, 1, &PINNED_FREE_BL),
        ("pinned-pinned", pin_roller, 0, &PINNED_PINNED_BL),
        ("free-free", json!([]), 3, &FREE_FREE_BL),
    ];
    for (what, joints, zeros, bl) in cases {
        let r = run(&supported(n, L, H, joints), 10, EigenMethod::Auto);
        assert_eq!(
            r.solver, "sparse shift-invert Lanczos",
            "{what}: large model, sparse path"
        );
        assert_eq!(r.rigid_modes, zeros, "{what}: zero-frequency modes");
        check_bending(&r, bl, L, H, 1e-6, what);
    }
}

#[test]
fn slender_mems_and_large_beams_keep_exact_zero_counts_and_their_frequencies() {
    // (length, height, elements); 64 Hermite elements leave a
    // discretization error of ~2e-8 on f₁ (O(h⁴)).
    let cases = [
        ("cable h/L = 1e-5", 1.0, 1e-5, 64),
        ("MEMS blade", 25e-6, 1.1e-6, 64),
        ("25 m blade", 25.0, 1.1, 64),
    ];
    for (what, l, h, n) in cases {
        let clamp =
            json!([{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}}]);
        let r = run(&supported(n, l, h, clamp), 8, EigenMethod::Auto);
        assert_eq!(r.rigid_modes, 0, "{what}, clamped: zero-frequency modes");
        check_bending(
            &r,
            &CANTILEVER_BL[..2],
            l,
            h,
            1e-6,
            &format!("{what}, clamped"),
        );
        let r = run(&supported(n, l, h, json!([])), 8, EigenMethod::Auto);
        assert_eq!(r.rigid_modes, 3, "{what}, free: zero-frequency modes");
        check_bending(&r, &FREE_FREE_BL[..2], l, h, 1e-6, &format!("{what}, free"));
    }
}

/// Two rails along x, `rungs` rungs across, welded at the rail nodes.
fn ladder(rungs: usize) -> ValidModel {
    let (span, gap) = (0.02, 0.01);
    let len = span * rungs as f64;
    let section = json!({"height": 1e-3, "width": 5e-3});
    let material = json!({"young": E, "density": RHO});
    let mut beams = vec![
        json!({"id": "rail0", "start": [0.0, 0.0], "angle_deg": 0.0, "length": len,
               "elements": 2 * rungs, "section": section, "material": material}),
        json!({"id": "rail1", "start": [0.0, gap], "angle_deg": 0.0, "length": len,
               "elements": 2 * rungs, "section": section, "material": material}),
    ];
    let mut joints = Vec::new();
    for k in 0..rungs {
        let s = span * (k as f64 + 0.5);
        let id = format!("rung{k}");
        beams.push(
            json!({"id": id, "start": [s, 0.0], "angle_deg": 90.0, "length": gap,
                          "elements": 2, "section": section, "material": material}),
        );
        joints.push(
            json!({"type": "weld", "a": {"beam": "rail0", "s": s}, "b": {"beam": id, "s": 0.0}}),
        );
        joints.push(
            json!({"type": "weld", "a": {"beam": "rail1", "s": s}, "b": {"beam": id, "s": gap}}),
        );
    }
    model(json!({"name": "ladder", "beams": beams, "joints": joints}))
}

#[test]
fn free_ladder_frame_dense_and_sparse_paths_agree_within_their_bounds() {
    let m = ladder(40);
    let dense = run(&m, 12, EigenMethod::Dense);
    let sparse = run(&m, 12, EigenMethod::Sparse);
    assert_eq!(dense.rigid_modes, 3, "free frame, dense: 3 zero modes");
    assert_eq!(sparse.rigid_modes, 3, "free frame, sparse: 3 zero modes");
    assert!(
        dense.reduced_dofs > 800,
        "a frame of {} free coordinates",
        dense.reduced_dofs
    );
    for (a, b) in dense.modes.iter().zip(&sparse.modes) {
        assert_eq!(a.kind, b.kind, "mode {}: kind", a.index);
        if a.kind == ModeKind::Rigid {
            continue;
        }
        let diff = rel(b.frequency_hz, a.frequency_hz).abs();
        assert!(
            diff <= 1e-9,
            "mode {}: dense {} Hz, sparse {} Hz, relative difference {diff:.2e} > 1e-9",
            a.index,
            a.frequency_hz,
            b.frequency_hz
        );
        // The accuracy estimates bound the difference of the two solves.
        let (ea, eb) = (a.error_bound.unwrap(), b.error_bound.unwrap());
        assert!(
            diff <= ea + eb,
            "mode {}: difference {diff:.2e} exceeds the error bounds {ea:.1e} + {eb:.1e}",
            a.index
        );
    }
}

#[test]
fn a_large_free_frame_counts_three_zero_modes_on_the_sparse_path() {
    let r = run(&ladder(300), 10, EigenMethod::Auto);
    assert_eq!(
        r.solver, "sparse shift-invert Lanczos",
        "large frame: sparse path"
    );
    assert_eq!(
        r.rigid_modes, 3,
        "free frame of 302 welded beams: 3 zero modes"
    );
    let first = &r.modes[3];
    assert!(
        first.frequency_hz > 0.0 && !first.kind.is_zero(),
        "the first elastic mode is elastic: {first:?}"
    );
}

#[test]
fn the_error_bound_bounds_the_difference_to_the_other_path() {
    // A cantilever both paths can do: dense (all coordinates) against sparse.
    let m = supported(
        200,
        L,
        H,
        json!([{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}}]),
    );
    let dense = run(&m, 6, EigenMethod::Dense);
    let sparse = run(&m, 6, EigenMethod::Sparse);
    for (a, b) in dense.modes.iter().zip(&sparse.modes) {
        let diff = rel(b.frequency_hz, a.frequency_hz).abs();
        let bound = a.error_bound.unwrap() + b.error_bound.unwrap();
        assert!(
            diff <= bound,
            "mode {}: |Δf|/f = {diff:.2e} between the paths, bounds sum to {bound:.2e}",
            a.index
        );
        assert!(
            bound < 1e-3,
            "mode {}: a bound of {bound:.1e} says nothing",
            a.index
        );
    }
}

#[test]
fn a_mass_between_preloaded_springs_keeps_its_transverse_frequency() {
    // Point mass m between two springs of stiffness k and tension T along
    // x, each of length l: axial ω² = 2k/m, transverse ω² = 2T/(l m) (a
    // string); without the preload the transverse motion is a mechanism.
    let (m, k, l) = (2e-3, 500.0, 0.01);
    for (tension, zeros) in [(3.0, 0), (0.0, 1)] {
        let model = model(json!({
            "name": "preloaded",
            "point_masses": [{"id": "p", "mass": m, "position": [0.0, 0.0]}],
            "springs": [
                {"a": {"ground": [-l, 0.0]}, "b": {"body": "p"}, "stiffness": k, "preload": tension},
                {"a": {"body": "p"}, "b": {"ground": [l, 0.0]}, "stiffness": k, "preload": tension}
            ]
        }));
        let r = run(&model, 2, EigenMethod::Auto);
        assert_eq!(
            r.rigid_modes, zeros,
            "preload {tension} N: zero-frequency modes"
        );
        let omega2: Vec<f64> = r.modes.iter().map(|md| md.eigenvalue).collect();
        let mut expected = vec![2.0 * k / m];
        if tension > 0.0 {
            expected.insert(0, 2.0 * tension / (l * m));
        } else {
            expected.insert(0, 0.0);
        }
        for (got, want) in omega2.iter().zip(&expected) {
            assert!(
                (got - want).abs() <= 1e-10 * (2.0 * k / m),
                "preload {tension} N: ω² = {got:e}, expected {want:e}"
            );
        }
    }
}

/// A square grid of `k` horizontal and `k` vertical beams of 1 m, welded
/// at all k² crossings.
fn grid(k: usize, elements: usize) -> ValidModel {
    let step = 1.0 / (k - 1) as f64;
    let section = json!({"height": 5e-3, "width": 5e-3});
    let material = json!({"young": 210e9, "density": 7850.0});
    let mut beams = Vec::new();
    let mut joints = Vec::new();
    for i in 0..k {
        let y = i as f64 * step;
        beams.push(
            json!({"id": format!("h{i}"), "start": [0.0, y], "angle_deg": 0.0, "length": 1.0,
                          "elements": elements, "section": section, "material": material}),
        );
        beams.push(
            json!({"id": format!("v{i}"), "start": [y, 0.0], "angle_deg": 90.0, "length": 1.0,
                          "elements": elements, "section": section, "material": material}),
        );
    }
    for i in 0..k {
        for j in 0..k {
            joints.push(json!({"type": "weld",
                "a": {"beam": format!("h{i}"), "s": j as f64 * step},
                "b": {"beam": format!("v{j}"), "s": i as f64 * step}}));
        }
    }
    model(json!({"name": "grid", "beams": beams, "joints": joints}))
}

#[test]
fn a_welded_grid_frame_has_three_zero_modes_on_both_paths() {
    let m = grid(6, 15);
    let dense = run(&m, 10, EigenMethod::Dense);
    let sparse = run(&m, 10, EigenMethod::Sparse);
    assert_eq!(dense.rigid_modes, 3, "free grid, dense: 3 zero modes");
    assert_eq!(sparse.rigid_modes, 3, "free grid, sparse: 3 zero modes");
    for (a, b) in dense.modes.iter().zip(&sparse.modes).skip(3) {
        let diff = rel(b.frequency_hz, a.frequency_hz).abs();
        assert!(
            diff <= 1e-9,
            "mode {}: dense {} Hz, sparse {} Hz, relative difference {diff:.2e} > 1e-9",
            a.index,
            a.frequency_hz,
            b.frequency_hz
        );
    }
}

#[test]
fn a_hanging_grid_under_gravity_gives_the_same_prestressed_modes_on_both_paths() {
    // A welded grid clamped at one corner and hanging under gravity: its
    // pre-stressed frequencies from the sparse statics and shift-invert
    // agree with the dense statics and eigen-solve.
    use ancf_modal::analysis::prestress::prestressed_modal;
    use ancf_modal::analysis::statics::StaticSettings;
    let mut v = serde_json::to_value(grid(6, 15)).expect("model serializes");
    v["gravity"] = json!([0.0, -9.81]);
    v["joints"]
        .as_array_mut()
        .expect("joints")
        .push(json!({"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "h0", "s": 0.0}}));
    let m = model(v);
    let sys = System::new(&m);
    let result = |method| {
        let settings = ModalSettings {
            modes: Some(6),
            method,
        };
        prestressed_modal(&sys, &StaticSettings::default(), &settings)
            .expect("pre-stressed modal analysis succeeds")
    };
    let (dense, sparse) = (result(EigenMethod::Dense), result(EigenMethod::Sparse));
    assert_eq!(
        sparse.prestressed.rigid_modes, 0,
        "clamped grid: no zero modes"
    );
    assert!(
        sparse.prestressed.reduced_dofs > 300,
        "the statics run on the sparse tangent ({} free coordinates)",
        sparse.prestressed.reduced_dofs
    );
    for (a, b) in dense
        .prestressed
        .modes
        .iter()
        .zip(&sparse.prestressed.modes)
    {
        let diff = rel(b.frequency_hz, a.frequency_hz).abs();
        assert!(
            diff <= 1e-9,
            "pre-stressed mode {}: dense {} Hz, sparse {} Hz, relative difference {diff:.2e} > 1e-9",
            a.index,
            a.frequency_hz,
            b.frequency_hz
        );
    }
}
