//! Results that do not depend on where the model sits, pins at any node,
//! complete mode sets (the cases of the placement issue, each against an
//! independent truth: an invariance, a closed form, Euler–Bernoulli).

mod common;
use ancf_modal::analysis::prestress::prestressed_modal;
use ancf_modal::analysis::statics::StaticSettings;
use ancf_modal::analysis::{modal_at_reference, EigenMethod, ModalResult, ModalSettings, ModeKind};
use ancf_modal::model::Placement;
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};
use common::*;
use serde_json::json;

fn modal_with(m: &ValidModel, modes: Option<usize>, method: EigenMethod) -> ModalResult {
    let settings = ModalSettings { modes, method };
    modal_at_reference(&System::new(m), &settings).expect("modal analysis succeeds")
}

/// The same zero and mechanism counts, the same kinds, and frequencies
/// within max(1e-9, the two error bounds).
fn same_modes(a: &ModalResult, b: &ModalResult, what: &str) {
    assert_eq!(
        (a.rigid_modes, a.mechanism_modes),
        (b.rigid_modes, b.mechanism_modes),
        "{what}: zero modes"
    );
    for (x, y) in a.modes.iter().zip(&b.modes) {
        assert_eq!(x.kind, y.kind, "{what}: mode {} kind", x.index);
        if y.frequency_hz > 0.0 {
            let bound = x.error_bound.unwrap_or(0.0) + y.error_bound.unwrap_or(0.0);
            let d = rel(x.frequency_hz, y.frequency_hz).abs();
            assert!(
                d <= 1e-9_f64.max(bound),
                "{what}: mode {} {} vs {} Hz ({d:e}, bounds {bound:e})",
                x.index,
                x.frequency_hz,
                y.frequency_hz
            );
        }
    }
}

/// A free blade (8 elements, no extra nodes) with a rigid body welded
/// between two nodes (s = 11 mm, inside element 3).
fn welded_blade() -> ValidModel {
    model(json!({
        "name": "welded blade", "beams": [blade(8)],
        "rigid_bodies": [{"id": "lever", "mass": 0.5e-3, "inertia": 3e-9,
                          "position": [11e-3, 2e-3]}],
        "joints": [{"type": "weld", "a": {"body": "lever"}, "b": {"beam": "blade", "s": 11e-3}}]
    }))
}

#[test]
fn a_body_welded_between_nodes_keeps_three_zero_modes_wherever_it_sits() {
    let base = welded_blade();
    let reference = modal_with(&base, None, EigenMethod::Dense);
    assert_eq!(reference.rigid_modes, 3, "free assembly at the origin");
    assert_eq!(reference.mechanism_modes, 0);
    for (angle_deg, offset) in [
        (0.0, [100.0, 0.0]),
        (30.0, [0.7, -1.3]),
        (217.0, [1e3, -1e3]),
    ] {
        let placed = base.placed(&Placement { angle_deg, offset });
        let placed = placed.validated().expect("placed, still valid");
        let r = modal_with(&placed, None, EigenMethod::Dense);
        assert_eq!(
            r.rigid_modes, 3,
            "turned {angle_deg}°, moved to {offset:?}: zero modes"
        );
        same_modes(
            &r,
            &reference,
            &format!("turned {angle_deg}°, moved to {offset:?}"),
        );
    }
}

/// The free blade (8 elements) with a lever pinned at arc length `s`;
/// the lever's centre of mass on the pin.
fn lever_on_blade(s: f64, young: f64, torsion: Option<f64>) -> ValidModel {
    let mut b = blade(8);
    b["material"]["young"] = json!(young);
    let mut pin = json!({"type": "pin", "a": {"body": "lever"}, "b": {"beam": "blade", "s": s}});
    if let Some(k) = torsion {
        pin["torsion_stiffness"] = json!(k);
    }
    model(json!({
        "name": "lever", "beams": [b],
        "rigid_bodies": [{"id": "lever", "mass": 0.5e-3, "inertia": 3e-9, "position": [s, 0.0]}],
        "joints": [pin]
    }))
}

#[test]
fn a_lever_pinned_at_the_middle_node_is_three_rigid_modes_and_one_mechanism() {
    for s in [L / 2.0, L / 4.0] {
        let r = modal_with(&lever_on_blade(s, E, None), None, EigenMethod::Dense);
        assert_eq!(
            (r.rigid_modes, r.mechanism_modes),
            (4, 1),
            "lever pinned at s = {s}: 3 rigid + 1 mechanism"
        );
        let kinds: Vec<ModeKind> = r.modes.iter().take(4).map(|m| m.kind).collect();
        assert_eq!(
            kinds,
            [
                ModeKind::Rigid,
                ModeKind::Rigid,
                ModeKind::Rigid,
                ModeKind::Mechanism
            ]
        );
    }
}

#[test]
fn a_lever_on_a_torsion_spring_rocks_at_the_two_inertia_frequency() {
    // Blade made stiff (E × 1e4): the lever and the blade turn as two rigid
    // bodies about the pin joined by k_t. Free-free, the pin may translate:
    // the blade's inertia about the common centre of mass is
    // J_b,eff = J_b + m_b d² − (m_b d)²/(m_b + m_l), d the pin-to-blade-centre
    // distance, J_b = m_b L²/12; ω² = k_t (1/J_l + 1/J_b,eff).
    let (k_t, j_l, m_l) = (0.5, 3e-9, 0.5e-3);
    let m_b = RHO * H * W * L;
    // The blade's remaining flexibility shifts the frequency by ~1/E:
    // -5e-8 at the middle node with E × 1e4, more off the middle.
    for (s, stiffening) in [(L / 2.0, 1e4), (L / 4.0, 1e5)] {
        let d = L / 2.0 - s;
        let j_b = m_b * L * L / 12.0;
        let j_eff = j_b + m_b * d * d - (m_b * d).powi(2) / (m_b + m_l);
        let omega2 = k_t * (1.0 / j_l + 1.0 / j_eff);
        let exact = omega2.sqrt() / (2.0 * std::f64::consts::PI);
        let r = modal_with(
            &lever_on_blade(s, stiffening * E, Some(k_t)),
            Some(4),
            EigenMethod::Dense,
        );
        assert_eq!((r.rigid_modes, r.mechanism_modes), (3, 0), "s = {s}");
        let f = r.modes[3].frequency_hz;
        assert!(
            rel(f, exact).abs() <= 1e-6,
            "s = {s}: lever mode {f} Hz, two-inertia formula {exact} Hz ({:e})",
            rel(f, exact)
        );
    }
}

#[test]
fn the_sparse_path_lists_every_mode_below_its_highest() {
    // The 400-element cantilever: the second axial mode (113 kHz) lies
    // among the first eight; clamped–free axial f_k = (2k − 1)/(4L) √(E/ρ).
    let m = cantilever(400);
    let sparse = modal_with(&m, Some(8), EigenMethod::Sparse);
    let dense = modal_with(&m, Some(8), EigenMethod::Dense);
    let axial = freqs(&sparse, ModeKind::Axial);
    assert_eq!(axial.len(), 2, "two axial modes among the first eight");
    for (k, f) in axial.iter().enumerate() {
        let exact = (2 * k + 1) as f64 / (4.0 * L) * (E / RHO).sqrt();
        assert!(
            rel(*f, exact).abs() < 1e-6,
            "axial mode {}: {f} Hz vs {exact} Hz",
            k + 1
        );
    }
    for (a, b) in sparse.modes.iter().zip(&dense.modes) {
        assert_eq!(a.kind, b.kind, "same mode set, same order");
        let bound = a.error_bound.unwrap() + b.error_bound.unwrap();
        let d = rel(a.frequency_hz, b.frequency_hz).abs();
        assert!(
            d <= 1e-9_f64.max(bound),
            "mode {}: {d:e} > {bound:e}",
            a.index
        );
    }
}

#[test]
fn every_shipped_model_gives_the_same_modes_turned_and_moved_a_kilometre_away() {
    for name in [
        "beam_free_free",
        "cantilever",
        "rcbo_free_free",
        "rcbo_prestressed",
        "rcbo_switch_off",
    ] {
        let path = format!("{}/models/{name}.json", env!("CARGO_MANIFEST_DIR"));
        let base = Model::from_file(std::path::Path::new(&path)).expect("shipped model");
        let reference = modal_with(&base, Some(12), EigenMethod::Auto);
        for (angle_deg, offset) in [(30.0, [1e3, -1e3]), (-117.0, [0.01, 300.0])] {
            let placed = base.placed(&Placement { angle_deg, offset });
            let placed = placed.validated().expect("placed, still valid");
            let r = modal_with(&placed, Some(12), EigenMethod::Auto);
            same_modes(
                &r,
                &reference,
                &format!("{name} turned {angle_deg}°, moved {offset:?}"),
            );
        }
    }
}

#[test]
fn the_prestressed_assembly_finds_its_equilibrium_and_modes_wherever_it_sits() {
    // Gravity, loads, the spring's ground point and the fixed pin all turn
    // with the model; statics must converge and the pre-stressed modes agree.
    let path = format!(
        "{}/models/rcbo_prestressed.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let base = Model::from_file(std::path::Path::new(&path)).expect("shipped model");
    let settings = ModalSettings {
        modes: Some(10),
        method: EigenMethod::Auto,
    };
    let run = |m: &ValidModel| {
        prestressed_modal(&System::new(m), &StaticSettings::default(), &settings)
            .expect("equilibrium and modes")
    };
    let reference = run(&base);
    for (angle_deg, offset) in [(30.0, [1e3, -1e3]), (200.0, [-250.0, 0.05])] {
        let placed = base.placed(&Placement { angle_deg, offset });
        let placed = run(&placed.validated().expect("placed, still valid"));
        same_modes(
            &placed.prestressed,
            &reference.prestressed,
            &format!("pre-stressed, turned {angle_deg}°, moved {offset:?}"),
        );
    }
}
