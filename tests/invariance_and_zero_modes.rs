//! Layer 3: invariances and zero-frequency mode counts.
//! - Frequencies do not change when the whole model is rotated and translated.
//! - A free planar assembly has 3 rigid modes, plus one per free mechanism
//!   freedom (a pin without torsion spring); a clamped beam has none.

mod common;
use ancf_modal::analysis::{modal_at_reference, ModalSettings, ModeKind};
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};
use common::*;
use serde_json::{json, Value};

/// Rotate a model file by `angle_deg` about the origin, then translate by `shift`.
fn transform(base: &ValidModel, angle_deg: f64, shift: [f64; 2]) -> ValidModel {
    let mut v: Value = serde_json::from_str(&base.to_json()).unwrap();
    let (s, c) = angle_deg.to_radians().sin_cos();
    let map = |p: &Value| -> Value {
        let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        json!([c * x - s * y + shift[0], s * x + c * y + shift[1]])
    };
    let turn = |p: &Value| -> Value {
        let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        json!([c * x - s * y, s * x + c * y])
    };
    for b in v["beams"].as_array_mut().unwrap() {
        b["start"] = map(&b["start"]);
        b["angle_deg"] = json!(b["angle_deg"].as_f64().unwrap() + angle_deg);
    }
    for b in v["rigid_bodies"].as_array_mut().unwrap() {
        b["position"] = map(&b["position"]);
        b["angle_deg"] = json!(b["angle_deg"].as_f64().unwrap() + angle_deg);
    }
    for b in v["point_masses"].as_array_mut().unwrap() {
        b["position"] = map(&b["position"]);
    }
    let fix_point = |p: &mut Value| {
        if let Some(g) = p.get("ground").cloned() {
            p["ground"] = map(&g);
        }
    };
    for j in v["joints"].as_array_mut().unwrap() {
        fix_point(&mut j["a"]);
        fix_point(&mut j["b"]);
        if let Some(a) = j.get("axis").cloned() {
            j["axis"] = turn(&a);
        }
    }
    for l in v["loads"].as_array_mut().unwrap() {
        if l["frame"] == "global" {
            l["force"] = turn(&l["force"]);
        }
    }
    model(v)
}

fn elastic_frequencies(m: &ValidModel) -> Vec<f64> {
    modal_all(m)
        .modes
        .iter()
        .filter(|x| !x.kind.is_zero())
        .map(|x| x.frequency_hz)
        .take(12)
        .collect()
}

#[test]
fn frequencies_invariant_under_rigid_transformation_of_the_model() {
    let base = Model::builtin();
    let reference = elastic_frequencies(&base);
    for (angle, shift) in [
        (37.0, [0.1, -0.2]),
        (-123.4, [5.0, 3.0]),
        (180.0, [0.0, 0.0]),
        (271.0, [-1e-3, 2e-3]),
    ] {
        let f = elastic_frequencies(&transform(&base, angle, shift));
        assert_eq!(
            f.len(),
            reference.len(),
            "same number of elastic modes after rotating by {angle}°"
        );
        for (a, b) in f.iter().zip(&reference) {
            let e = rel(*a, *b);
            assert!(e.abs() <= 1e-9, "rotation {angle}°, shift {shift:?}: frequency {a} vs {b}, relative change {e:e} (limit 1e-9)");
        }
    }
    // A clamped model too: constraints to the ground rotate with it.
    let cl = cantilever(8);
    let reference = elastic_frequencies(&cl);
    let f = elastic_frequencies(&transform(&cl, 63.0, [0.3, 0.4]));
    for (a, b) in f.iter().zip(&reference) {
        assert!(
            rel(*a, *b).abs() <= 1e-9,
            "clamped beam rotated 63°: {a} vs {b}"
        );
    }
}

fn two_beams(joint: Value) -> ValidModel {
    let mut b2 = blade(4);
    b2["id"] = json!("b2");
    b2["start"] = json!([L, 0.0]);
    model(json!({
        "name": "two beams", "beams": [blade(4), b2],
        "joints": [joint]
    }))
}

#[test]
fn zero_frequency_modes_are_counted_and_reported_as_rigid() {
    // (zero modes, of which mechanisms): a zero mode in the span of the
    // whole assembly's rigid motions is `rigid`, any other a `mechanism`.
    let split = |m: &ValidModel| {
        let r = modal_all(m);
        let reported = r.modes.iter().filter(|x| x.kind.is_zero()).count();
        assert_eq!(
            reported, r.rigid_modes,
            "every zero mode is reported with kind rigid or mechanism"
        );
        assert!(
            r.modes
                .iter()
                .filter(|x| x.kind.is_zero())
                .all(|x| x.frequency_hz == 0.0),
            "zero modes have f = 0"
        );
        let mechanisms = r
            .modes
            .iter()
            .filter(|x| x.kind == ModeKind::Mechanism)
            .count();
        assert_eq!(mechanisms, r.mechanism_modes, "mechanisms counted");
        (r.rigid_modes, mechanisms)
    };
    let count = |m: &ValidModel| split(m).0;
    assert_eq!(count(&free_beam(8)), 3, "free beam: 3 rigid-body modes");
    assert_eq!(
        count(&Model::builtin()),
        3,
        "paper's free-free assembly: 3 rigid-body modes"
    );
    assert_eq!(count(&cantilever(8)), 0, "clamped beam: none");
    let pin = json!({"type": "pin", "a": {"beam": "blade", "s": L}, "b": {"beam": "b2", "s": 0.0}});
    assert_eq!(
        split(&two_beams(pin.clone())),
        (4, 1),
        "two beams pinned: 3 rigid + 1 mechanism"
    );
    let mut sprung = pin.clone();
    sprung["torsion_stiffness"] = json!(0.5);
    assert_eq!(
        count(&two_beams(sprung)),
        3,
        "torsion spring removes the mechanism"
    );
    let weld =
        json!({"type": "weld", "a": {"beam": "blade", "s": L}, "b": {"beam": "b2", "s": 0.0}});
    assert_eq!(count(&two_beams(weld)), 3, "two beams welded: 3");
    let pinned = model(json!({
        "name": "pinned", "beams": [blade(6)],
        "joints": [{"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}}]
    }));
    assert_eq!(
        split(&pinned),
        (1, 0),
        "beam pinned to the ground: the swing, a rigid motion of the whole assembly"
    );
    let rigid_chain = model(json!({
        "name": "rigid chain",
        "rigid_bodies": [
            {"id": "r1", "mass": 1e-3, "inertia": 1e-9, "position": [0.0, 0.0]},
            {"id": "r2", "mass": 2e-3, "inertia": 3e-9, "position": [0.02, 0.0]}
        ],
        "joints": [{"type": "pin", "a": {"body": "r1", "local": [0.01, 0.0]}, "b": {"body": "r2", "local": [-0.01, 0.0]}}]
    }));
    assert_eq!(
        split(&rigid_chain),
        (4, 1),
        "two rigid bodies pinned, free: 3 rigid + 1 mechanism, nothing else"
    );
    assert_eq!(
        modal_all(&rigid_chain).modes.len(),
        4,
        "6 coordinates − 2 constraint equations = 4 modes"
    );
}

#[test]
fn zero_modes_beyond_the_requested_ones_are_still_counted() {
    // The zero count is a property of the whole spectrum: asking for fewer
    // modes than there are zero ones must not change it.
    let pin = json!({"type": "pin", "a": {"beam": "blade", "s": L}, "b": {"beam": "b2", "s": 0.0}});
    for (m, zeros, what) in [
        (free_beam(8), 3, "free beam"),
        (two_beams(pin), 4, "two beams pinned"),
    ] {
        let system = System::new(&m);
        for asked in [1, 2, zeros] {
            let settings = ModalSettings {
                modes: Some(asked),
                ..ModalSettings::default()
            };
            let r = modal_at_reference(&system, &settings).unwrap();
            assert_eq!(r.modes.len(), asked, "{what}: {asked} modes reported");
            assert!(
                r.modes.iter().all(|x| x.kind.is_zero()),
                "{what}: the lowest {asked} modes are zero modes"
            );
            assert_eq!(
                r.rigid_modes, zeros,
                "{what}, {asked} modes asked for: zero modes of the whole spectrum"
            );
        }
    }
}

#[test]
fn redundant_constraints_are_named_and_do_not_change_the_result() {
    let twice = model(json!({
        "name": "double clamp", "beams": [blade(8)],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}},
            {"id": "extra_pin", "type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}}
        ]
    }));
    let r = modal_all(&twice);
    assert_eq!(
        r.redundant_constraints,
        vec![String::from("extra_pin")],
        "the repeated pin is reported as redundant"
    );
    let once = modal_all(&cantilever(8));
    assert_eq!(
        r.reduced_dofs, once.reduced_dofs,
        "redundant equations remove no freedom"
    );
    for (a, b) in r.modes.iter().zip(&once.modes).take(6) {
        assert!(
            rel(a.frequency_hz, b.frequency_hz).abs() <= 1e-10,
            "{} vs {}",
            a.frequency_hz,
            b.frequency_hz
        );
    }
}
