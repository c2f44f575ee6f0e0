//! Issue 37, "Right at any mesh": a 1 m steel cantilever (10 × 20 mm
//! section, bending in the 10 mm plane) meshed finely enough that a factor
//! of K − σM carries more round-off than its lowest eigenvalue (stiffness
//! entries EI/Le³ = 3.5e17 at 100,000 elements). Its lowest bending
//! frequencies against Euler–Bernoulli's roots (independent of the code;
//! the Hermite discretization error is below 1e-12 at these meshes), and
//! the printed error bound against the true error.
//!
//! Release test: `cargo test --release --test fine_mesh_cantilever`.

mod common;

use ancf_modal::analysis::{modal_at_reference, EigenMethod, ModalSettings, ModeKind};
use ancf_modal::System;
use common::model;
use serde_json::json;
use std::f64::consts::PI;

/// βL of the clamped–free beam.
const ROOTS: [f64; 4] = [
    1.875104068711961,
    4.694091132974175,
    7.854757438237613,
    10.99554073487547,
];

fn steel_cantilever(elements: usize) -> ancf_modal::model::ValidModel {
    model(json!({
        "name": "c", "beams": [{"id": "b", "start": [0, 0], "angle_deg": 0, "length": 1.0,
            "elements": elements, "section": {"height": 0.01, "width": 0.02},
            "material": {"young": 210e9, "density": 7850.0}}],
        "joints": [{"id": "clamp", "type": "weld", "a": {"ground": [0, 0]}, "b": {"beam": "b", "s": 0}}]
    }))
}

fn euler_bernoulli_hz(bl: f64) -> f64 {
    let (e, rho, h, w, l): (f64, f64, f64, f64, f64) = (210e9, 7850.0, 0.01, 0.02, 1.0);
    let (ei, rho_a) = (e * w * h * h * h / 12.0, rho * w * h);
    bl * bl / (2.0 * PI * l * l) * (ei / rho_a).sqrt()
}

/// The first four bending frequencies within `tolerance` of
/// Euler–Bernoulli, and each printed bound covering its true error (up to
/// the 1e-12 the discretization and the roots' digits leave) and within
/// 10 × max(error, 1e-9) of it.
fn check(elements: usize, tolerance: f64) {
    let m = steel_cantilever(elements);
    let settings = ModalSettings {
        modes: Some(6),
        method: EigenMethod::Auto,
    };
    let r = modal_at_reference(&System::new(&m), &settings).expect("modal analysis succeeds");
    assert!(
        r.refused_modes.is_empty(),
        "{elements}: {:?}",
        r.refused_modes
    );
    let bending: Vec<_> = r.of_kind(ModeKind::Bending).take(4).collect();
    assert_eq!(bending.len(), 4, "{elements} elements: four bending modes");
    for (k, (mode, bl)) in bending.iter().zip(ROOTS).enumerate() {
        let exact = euler_bernoulli_hz(bl);
        let error = (mode.frequency_hz - exact).abs() / exact;
        let bound = mode.error_bound.expect("elastic modes carry a bound");
        assert!(
            error <= tolerance,
            "{elements} elements, f{}: {} Hz against {exact} Hz (error {error:.2e})",
            k + 1,
            mode.frequency_hz
        );
        assert!(
            error <= bound + 1e-12,
            "{elements} elements, f{}: bound {bound:.2e} below the error {error:.2e}",
            k + 1
        );
        assert!(
            bound <= 10.0 * error.max(1e-9),
            "{elements} elements, f{}: bound {bound:.2e} not within 10× of the error {error:.2e}",
            k + 1
        );
    }
}

#[test]
fn twenty_thousand_elements_match_euler_bernoulli_with_tight_bounds() {
    check(2_000, 1e-10);
    check(20_000, 1e-10);
}

#[test]
fn a_hundred_thousand_elements_match_euler_bernoulli_with_tight_bounds() {
    // Before issue 37: f₁ printed as 52.786 Hz (6.3 × 8.355), bound 2.5e4.
    check(100_000, 1e-10);
}

/// A micro-cantilever carrying a 150 m arm (a length typed in metres
/// instead of micrometres): the dense solve cannot resolve its modes
/// (bounds of order 1e6), and refuses them instead of printing them as
/// frequencies; the default solver refines them.
#[test]
fn modes_the_arithmetic_cannot_resolve_are_refused_not_printed() {
    let beam = |id: &str, start: f64, length: f64| {
        json!({
            "id": id, "start": [start, 0.0], "angle_deg": 0.0, "length": length, "elements": 4,
            "section": {"height": 5e-6, "width": 10e-6},
            "material": {"young": 160e9, "density": 2330.0}
        })
    };
    let m = model(json!({
        "name": "micro",
        "beams": [beam("base", 0.0, 200e-6), beam("arm", 200e-6, 150.0)],
        "rigid_bodies": [{"id": "mass", "mass": 1e-9, "inertia": 4e-17, "position": [350e-6, 0.0]}],
        "joints": [
            {"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "base", "s": 0.0}},
            {"type": "weld", "a": {"beam": "base", "s": 200e-6}, "b": {"beam": "arm", "s": 0.0}},
            {"type": "weld", "a": {"beam": "arm", "s": 150.0}, "b": {"body": "mass"}}
        ]
    }));
    let system = System::new(&m);
    let run = |method| {
        modal_at_reference(
            &system,
            &ModalSettings {
                modes: Some(3),
                method,
            },
        )
        .expect("modal analysis succeeds")
    };
    let dense = run(EigenMethod::Dense);
    assert!(!dense.refused_modes.is_empty(), "{:?}", dense.modes);
    for m in &dense.modes {
        assert!(
            m.error_bound.is_none_or(|b| b <= 1e-5),
            "mode {} printed with bound {:?}",
            m.index,
            m.error_bound
        );
    }
    for r in &dense.refused_modes {
        assert!(r.error_bound > 1e-5, "{r:?}");
    }
    assert!(
        dense
            .warnings("the reference")
            .iter()
            .any(|w| w.contains("is not reported as a frequency")),
        "{:?}",
        dense.warnings("the reference")
    );
    let auto = run(EigenMethod::Auto);
    assert!(auto.refused_modes.is_empty(), "{:?}", auto.refused_modes);
    assert_eq!(auto.modes.len(), 3);
    assert!(auto.modes.iter().all(|m| m.error_bound.unwrap() <= 1e-9));
}

/// βL of the clamped–pinned beam (tan βL = tanh βL).
const CLAMPED_PINNED: [f64; 4] = [
    3.926602312047919,
    7.068582745628731,
    10.210176122813031,
    13.351768777754092,
];

/// An aluminium ruler, 1.5 m × 30 mm × 1.5 mm, clamped at `start`, pinned
/// at its other end, along `angle_deg`.
fn turned_ruler(elements: usize, angle_deg: f64, start: [f64; 2]) -> ancf_modal::model::ValidModel {
    let (s, c) = angle_deg.to_radians().sin_cos();
    let end = [start[0] + 1.5 * c, start[1] + 1.5 * s];
    model(json!({
        "name": "ruler", "beams": [{"id": "r", "start": start, "angle_deg": angle_deg,
            "length": 1.5, "elements": elements, "section": {"height": 0.0015, "width": 0.03},
            "material": {"young": 70e9, "density": 2700.0}}],
        "joints": [
            {"type": "weld", "a": {"ground": start}, "b": {"beam": "r", "s": 0.0}},
            {"type": "pin", "a": {"ground": end}, "b": {"beam": "r", "s": 1.5}}
        ]
    }))
}

proptest::proptest! {
    #![proptest_config(proptest::test_runner::Config {
        cases: 4,
        rng_seed: proptest::test_runner::RngSeed::Fixed(37),
        failure_persistence: None,
        ..proptest::test_runner::Config::default()
    })]

    /// Turned and moved anywhere, a fine-meshed straight beam is the same
    /// beam: its lowest bending frequencies stay within their printed
    /// bounds of Euler–Bernoulli (a 30° ruler of 50,000 elements printed
    /// errors of 2.4e-9 under bounds of 1.5e-9: its stored nodes zigzag by
    /// ε|r|, and r'' formed from them bent it), and its unloaded reference
    /// is an equilibrium (at 20,000 elements it was "not an equilibrium:
    /// 7.07 N").
    #[test]
    fn a_turned_fine_beam_keeps_its_frequencies_within_their_bounds(
        elements in 20_000usize..40_000,
        angle_deg in 0.0f64..360.0,
        x in -2.0f64..2.0,
        y in -2.0f64..2.0,
    ) {
        let m = turned_ruler(elements, angle_deg, [x, y]);
        let settings = ModalSettings { modes: Some(4), method: EigenMethod::Auto };
        let r = modal_at_reference(&System::new(&m), &settings).expect("modal analysis succeeds");
        proptest::prop_assert!(r.equilibrium.balanced, "{:?}", r.equilibrium);
        // √(EI/ρA) of the rectangle: √(E h²/12ρ).
        let (e, rho, h, l): (f64, f64, f64, f64) = (70e9, 2700.0, 0.0015, 1.5);
        let c = (e * h * h / (12.0 * rho)).sqrt();
        for (mode, bl) in r.of_kind(ModeKind::Bending).zip(CLAMPED_PINNED) {
            let exact = bl * bl / (2.0 * PI * l * l) * c;
            let error = (mode.frequency_hz - exact).abs() / exact;
            let bound = mode.error_bound.expect("elastic modes carry a bound");
            proptest::prop_assert!(
                error <= bound + 1e-12,
                "{elements} elements at {angle_deg}°: {} Hz against {exact} Hz, error {error:.2e}, bound {bound:.2e}",
                mode.frequency_hz
            );
        }
    }
}
