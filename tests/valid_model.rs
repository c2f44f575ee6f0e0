//! A validated model is a type: a `System` is built from a `ValidModel`
//! only, so a model edited after validation (a joint on a missing body, a
//! slider without its axis, a spring with neither free length nor preload,
//! a contact on a missing body) is the validation error naming the JSON
//! path, never a panic in the assembly; a model taken out and validated
//! again assembles to the same system to the bit; the assembly of a model
//! with rigid beams (resolved once, on the model as written, and carried
//! to the rigid bodies) is that of the model with the rigid bodies written
//! out; and no edit of a model file's JSON makes the assembly panic.

use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::error::{InvalidModel, ModelError, Problem, Source};
use ancf_modal::model::{Contact, TimeFunction, ValidModel};
use ancf_modal::{Model, System};
use faer::Mat;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use serde_json::{json, Value};

/// Every kind of reference a model has, away from the origin (so the
/// assembly moves it to its centre of mass), with a rigid beam: a clamped
/// blade, a rigid arm joined to it by a pin with a torsion spring, a lever
/// on the arm's end by a pin without `local` (the partner's point), a mass
/// on a released slider pulled by a preloaded spring, a spring with a free
/// length, loads in the beam and global frames, co-rotated and global
/// sensors, the arm's end in a slot of the lever (a stop) and the blade's
/// tip against a ground line without a side.
fn rich_json() -> Value {
    let section = json!({"height": 1.1e-3, "width": 5.2e-3});
    let material = json!({"young": 127e9, "density": 8940.0});
    json!({
        "name": "rich",
        "gravity": [0.0, -9.81],
        "beams": [
            {"id": "blade", "start": [10.0, 5.0], "angle_deg": 90.0, "length": 0.05,
             "elements": 6, "section": section, "material": material},
            {"id": "arm", "start": [10.0, 5.05], "angle_deg": 0.0, "length": 0.03,
             "elements": 4, "section": section, "material": material, "rigid": true}
        ],
        "rigid_bodies": [
            {"id": "lever", "mass": 1e-3, "inertia": 1e-8, "position": [10.03, 5.05],
             "angle_deg": 30.0}
        ],
        "point_masses": [{"id": "bob", "mass": 2e-3, "position": [9.98, 5.0]}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [10.0, 5.0]},
             "b": {"beam": "blade", "s": 0.0}},
            {"id": "elbow", "type": "pin", "a": {"beam": "blade", "s": 0.05},
             "b": {"beam": "arm", "s": 0.0}, "torsion_stiffness": 0.5},
            {"id": "hinge", "type": "pin", "a": {"body": "lever"},
             "b": {"beam": "arm", "s": 0.03}, "torsion_stiffness": 0.1,
             "torsion_damping": 1e-4},
            {"id": "rail", "type": "slider", "a": {"ground": [9.98, 5.0]},
             "b": {"body": "bob"}, "axis": [1.0, 0.0], "release": {"until": 0.0}}
        ],
        "springs": [
            {"id": "pull", "a": {"ground": [9.95, 5.0]}, "b": {"body": "bob"},
             "stiffness": 100.0, "preload": 2.0},
            {"id": "tie", "a": {"beam": "blade", "s": 0.025},
             "b": {"body": "lever", "local": [0.01, 0.0]}, "stiffness": 50.0,
             "free_length": 0.03}
        ],
        "loads": [
            {"id": "push", "at": {"beam": "arm", "s": 0.015}, "frame": "beam",
             "force": [0.0, 1.0]},
            {"id": "side", "at": {"beam": "blade", "s": 0.04}, "force": [0.5, 0.0]}
        ],
        "sensors": [
            {"id": "tip", "at": {"beam": "blade", "s": 0.05}, "quantity": "displacement",
             "direction": [0.0, 1.0]},
            {"id": "arm_end", "at": {"beam": "arm", "s": 0.03}, "quantity": "velocity",
             "direction": [1.0, 0.0]},
            {"id": "bob", "at": {"body": "bob"}, "quantity": "acceleration",
             "frame": "global", "direction": [1.0, 0.0]}
        ],
        "contacts": [
            {"id": "stop", "type": "pin_slot",
             "slot": {"body": "lever", "from": [-0.005, 0.0], "to": [0.005, 0.0], "width": 0.004},
             "pin": {"beam": "arm", "s": 0.03}, "pin_radius": 0.001,
             "law": {"model": "linear", "stiffness": 1e5}},
            {"id": "wall", "type": "point_line", "point": {"beam": "blade", "s": 0.05},
             "radius": 0.001, "line": {"ground": true, "from": [10.01, 4.9], "to": [10.01, 5.2]},
             "law": {"model": "hertz", "stiffness": 1e9}}
        ]
    })
}

fn rich() -> ValidModel {
    Model::from_json(&rich_json().to_string(), Source::BuiltIn).expect("the rich model is valid")
}

/// Everything of a system, every number to the bit (`{:?}` of an f64 is
/// its shortest round-trip form, so equal text is equal bits).
fn fingerprint(sys: &System) -> String {
    format!("{sys:?}")
}

/// M and K (at the reference) of a system, as bits.
fn matrices(sys: &System) -> (Vec<u64>, Vec<u64>) {
    let n = sys.ndof();
    let m = sys.mass_matrix();
    let mut k = Mat::<f64>::zeros(n, n);
    sys.tangent_stiffness(&sys.reference(), &mut k);
    let bits = |a: &Mat<f64>| {
        (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| a[(i, j)].to_bits())
            .collect()
    };
    (bits(&m), bits(&k))
}

/// An edit of an owned model.
type Edit = Box<dyn FnOnce(&mut Model)>;

#[test]
fn edits_after_validation_are_validation_errors_naming_their_paths() {
    let cases: Vec<(&str, Edit, &str, Problem)> = vec![
        (
            "a joint on a missing body",
            Box::new(|m| m.joints[2].a.body = Some(String::from("gone"))),
            "joints[2].a.body",
            Problem::UnknownId {
                kind: "rigid body or point mass",
                id: String::from("gone"),
                available: ancf_modal::error::Ids(vec!["lever".into(), "bob".into()]),
            },
        ),
        (
            "a joint on a missing beam",
            Box::new(|m| m.joints[1].b.beam = Some(String::from("gone"))),
            "joints[1].b.beam",
            Problem::UnknownId {
                kind: "beam",
                id: String::from("gone"),
                available: ancf_modal::error::Ids(vec!["blade".into(), "arm".into()]),
            },
        ),
        (
            "a slider without its axis",
            Box::new(|m| m.joints[3].axis = None),
            "joints[3]",
            Problem::MissingKey { key: "axis" },
        ),
        (
            "a spring with neither free length nor preload",
            Box::new(|m| m.springs[0].preload = None),
            "springs[0]",
            Problem::MissingKey {
                key: "free_length` or `preload",
            },
        ),
        (
            "a contact on a missing body",
            Box::new(|m| {
                if let Contact::PinSlot { slot, .. } = &mut m.contacts[0] {
                    slot.body = Some(String::from("gone"));
                }
            }),
            "contacts[0].slot.body",
            Problem::UnknownId {
                kind: "rigid body",
                id: String::from("gone"),
                available: ancf_modal::error::Ids(vec!["lever".into()]),
            },
        ),
        (
            "a slot without its width",
            Box::new(|m| {
                if let Contact::PinSlot { slot, .. } = &mut m.contacts[0] {
                    slot.width = None;
                }
            }),
            "contacts[0].slot",
            Problem::MissingKey { key: "width" },
        ),
        (
            "a released weld",
            Box::new(|m| m.joints[0].release = Some(TimeFunction::Until(0.0))),
            "joints[0].release",
            Problem::KeyNotAllowed {
                key: "release",
                why: "a weld's reaction includes a moment; only pins and sliders can be released",
            },
        ),
        (
            "a point off its beam",
            Box::new(|m| m.loads[1].at.s = Some(0.06)),
            "loads[1].at.s",
            Problem::OutOfRange {
                value: 0.06,
                min: 0.0,
                max: 0.05,
            },
        ),
    ];
    for (what, edit, path, problem) in cases {
        let mut m = rich().into_model();
        edit(&mut m);
        let text = m.to_json();
        let expected = InvalidModel {
            path: path.to_string(),
            problem,
        };
        // The edited model, and the same model read as a file, give the
        // validation error; no System is made.
        let got = std::panic::catch_unwind(|| m.validated().map(|v| System::new(&v).ndof()));
        match got {
            Ok(Err(e)) => assert_eq!(e, expected, "{what}"),
            Ok(Ok(n)) => panic!("{what}: assembled ({n} coordinates) instead of refused"),
            Err(_) => panic!("{what}: panicked"),
        }
        match Model::from_json(&text, Source::BuiltIn) {
            Err(ModelError::Invalid { path, problem, .. }) => {
                assert_eq!((path, problem), (expected.path, expected.problem), "{what}")
            }
            other => panic!("{what}: {other:?}"),
        }
    }
}

#[test]
fn a_model_taken_out_and_validated_again_assembles_to_the_same_system_to_the_bit() {
    for (name, model) in [
        ("rich", rich()),
        ("switch-off", Model::switch_off_builtin()),
        ("free-free", Model::builtin()),
    ] {
        let a = System::new(&model);
        let again = model.clone().into_model().validated().expect("still valid");
        let b = System::new(&again);
        assert_eq!(fingerprint(&a), fingerprint(&b), "{name}");
        assert_eq!(matrices(&a), matrices(&b), "{name}: M and K");
        assert_eq!(a.origin, b.origin, "{name}");
        // A clone of the valid model, and its owned copy edited back to
        // where it was, too.
        let mut edited = model.to_model();
        let g = edited.gravity;
        edited.gravity = [1.0, 2.0];
        edited.gravity = g;
        let c = System::new(&edited.validated().expect("still valid"));
        assert_eq!(matrices(&a), matrices(&c), "{name}: after an edit undone");
    }
}

#[test]
fn rigid_beams_assemble_as_the_rigid_bodies_written_out() {
    // The assembly resolves the points of the model as written and carries
    // them to the rigid bodies; validating the model with the rigid bodies
    // written out resolves them there directly. Same system, to the bit.
    let m = rich();
    assert!(
        m.beams.iter().any(|b| b.rigid),
        "the test needs a rigid beam"
    );
    let written_out = m.with_rigid_beams().validated().expect("still valid");
    assert!(written_out.beams.iter().all(|b| !b.rigid));
    let (a, b) = (System::new(&m), System::new(&written_out));
    assert_eq!(fingerprint(&a), fingerprint(&b));
    assert_eq!(a.rigid_bodies.len(), 2, "the lever and the arm");
    assert_eq!(a.beams.len(), 1, "the blade");
    // The centre of mass is far from the origin; inside, positions are
    // O(the assembly's size) and the ground points moved along.
    assert!(a.origin.x > 9.0 && a.origin.y > 4.0);
    assert!(a.q0.iter().all(|x| x.abs() <= 1.0));
    // A tracked point resolves in the assembled model, the ground too.
    let tip = m
        .resolve_point(
            &ancf_modal::model::PointSpec {
                beam: Some("arm".into()),
                s: Some(0.03),
                ..Default::default()
            },
            "point",
        )
        .expect("on the arm");
    assert_eq!(
        tip,
        ancf_modal::model::ResolvedPoint::Rigid {
            index: 1,
            local: Some([0.015, 0.0])
        }
    );
    let fixed = m
        .resolve_point(
            &ancf_modal::model::PointSpec {
                ground: Some([10.0, 5.0]),
                ..Default::default()
            },
            "point",
        )
        .expect("on the ground");
    let ancf_modal::model::ResolvedPoint::Ground { position } = fixed else {
        panic!("{fixed:?}")
    };
    let back = a.user_point(nalgebra::Vector2::new(position[0], position[1]));
    assert!((back.x - 10.0).abs() < 1e-14 && (back.y - 5.0).abs() < 1e-14);
    assert_eq!(
        m.resolve_point(
            &ancf_modal::model::PointSpec {
                body: Some("ghost".into()),
                ..Default::default()
            },
            "point"
        )
        .unwrap_err()
        .path,
        "point.body"
    );
}

#[test]
fn a_released_slider_lets_go_with_its_reaction_from_the_resolved_joint() {
    // A 10 g mass on a horizontal ground rail under gravity: the rail, a
    // released slider, holds the weight; released, it becomes the load
    // (0, m g) on the mass — the joint kind validation resolved, no check
    // left for the release.
    let (mass, g) = (0.01, 9.81);
    let m = Model::from_json(
        &json!({
            "name": "rail",
            "gravity": [0.0, -g],
            "point_masses": [{"id": "m", "mass": mass, "position": [0.3, -0.2]}],
            "joints": [{"id": "rail", "type": "slider", "a": {"ground": [0.3, -0.2]},
                        "b": {"body": "m"}, "axis": [1.0, 0.0], "release": {"until": 0.0}}],
            "springs": [{"a": {"ground": [0.2, -0.2]}, "b": {"body": "m"},
                         "stiffness": 1e3, "free_length": 0.1}]
        })
        .to_string(),
        Source::BuiltIn,
    )
    .expect("valid");
    let sys = System::new(&m);
    assert_eq!(sys.released.len(), 1);
    let eq = solve_equilibrium(&sys, &StaticSettings::default()).expect("equilibrium");
    let released = sys.release_supports(&eq.q, &eq.lambda);
    assert_eq!(released.constraint_count(), 0);
    assert_eq!(released.loads.len(), 1, "the ground side carries nothing");
    let f = released.loads[0].force;
    assert!(
        f.x.abs() <= 1e-12 * mass * g && ((f.y - mass * g) / (mass * g)).abs() <= 1e-9,
        "the rail's reaction {f:?} N vs (0, m g = {})",
        mass * g
    );
}

/// Every place in `v` (JSON pointers), the root left out.
fn places(v: &Value, at: String, out: &mut Vec<String>) {
    match v {
        Value::Object(map) => {
            for (k, x) in map {
                let p = format!("{at}/{k}");
                out.push(p.clone());
                places(x, p, out);
            }
        }
        Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                let p = format!("{at}/{i}");
                out.push(p.clone());
                places(x, p, out);
            }
        }
        _ => {}
    }
}

/// Every string value of `v` (ids among them).
fn strings(v: &Value, out: &mut Vec<String>) {
    match v {
        Value::String(s) => out.push(s.clone()),
        Value::Object(map) => map.values().for_each(|x| strings(x, out)),
        Value::Array(items) => items.iter().for_each(|x| strings(x, out)),
        _ => {}
    }
}

/// One edit of a model's JSON.
#[derive(Debug, Clone)]
enum JsonEdit {
    /// Delete the value at the place (a key of an object, an item of a list).
    Delete(usize),
    /// Put another of the model's strings (or an unknown one) at the place.
    Rename(usize, usize),
    /// Put a number at the place.
    Number(usize, f64),
    /// Copy the value at one place over that at another.
    Copy(usize, usize),
}

fn edit_strategy() -> impl Strategy<Value = JsonEdit> {
    let number = prop::sample::select(vec![
        0.0, -1.0, 1e-12, 0.5, 1.0, 2.0, 1e3, -1e-3, 0.025, 1e300,
    ]);
    prop_oneof![
        any::<usize>().prop_map(JsonEdit::Delete),
        (any::<usize>(), any::<usize>()).prop_map(|(p, s)| JsonEdit::Rename(p, s)),
        (any::<usize>(), number).prop_map(|(p, x)| JsonEdit::Number(p, x)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| JsonEdit::Copy(a, b)),
    ]
}

/// `v` with `edit` applied (indices taken modulo what there is).
fn apply(v: &mut Value, edit: &JsonEdit) {
    let mut at = Vec::new();
    places(v, String::new(), &mut at);
    if at.is_empty() {
        return;
    }
    let pick = |i: usize| at[i % at.len()].clone();
    match *edit {
        JsonEdit::Delete(i) => {
            let p = pick(i);
            let (parent, key) = p.rsplit_once('/').expect("a pointer below the root");
            match v.pointer_mut(parent) {
                Some(Value::Object(map)) => {
                    map.remove(key);
                }
                Some(Value::Array(items)) => {
                    if let Ok(k) = key.parse::<usize>() {
                        if k < items.len() {
                            items.remove(k);
                        }
                    }
                }
                _ => {}
            }
        }
        JsonEdit::Rename(i, s) => {
            let mut names = vec![String::from("ghost")];
            strings(v, &mut names);
            let name = names[s % names.len()].clone();
            if let Some(x) = v.pointer_mut(&pick(i)) {
                *x = Value::String(name);
            }
        }
        JsonEdit::Number(i, x) => {
            if let Some(slot) = v.pointer_mut(&pick(i)) {
                *slot = json!(x);
            }
        }
        JsonEdit::Copy(a, b) => {
            let value = v.pointer(&pick(a)).cloned();
            if let (Some(value), Some(slot)) = (value, v.pointer_mut(&pick(b))) {
                *slot = value;
            }
        }
    }
}

#[test]
fn no_edit_of_a_model_file_makes_the_assembly_panic() {
    let bases = [
        rich_json(),
        serde_json::from_str::<Value>(ancf_modal::model::SWITCH_OFF_MODEL_JSON).unwrap(),
    ];
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 512,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &[34; 32]),
    );
    let strategy = (0..bases.len(), prop::collection::vec(edit_strategy(), 1..4));
    // (refused, built)
    let counts = std::sync::Mutex::new((0usize, 0usize));
    runner
        .run(&strategy, |(base, edits)| {
            let mut v = bases[base].clone();
            for e in &edits {
                apply(&mut v, e);
            }
            let text = v.to_string();
            let outcome = std::panic::catch_unwind(|| {
                Model::from_json(&text, Source::BuiltIn).map(|m| {
                    let sys = System::new(&m);
                    sys.mass();
                    sys.ndof()
                })
            });
            let outcome = outcome
                .map_err(|_| TestCaseError::fail(format!("panicked after {edits:?}: {text}")))?;
            let mut c = counts.lock().unwrap();
            match outcome {
                Ok(_) => c.1 += 1,
                Err(_) => c.0 += 1,
            }
            Ok(())
        })
        .unwrap();
    let (refused, built) = *counts.lock().unwrap();
    eprintln!("{refused} edited models refused, {built} assembled");
    // Both outcomes occur: the edits reach the validation's checks and
    // leave valid models too.
    assert!(refused > 0 && built > 0, "{refused} refused, {built} built");
}
