//! Sizes that disagree by orders of magnitude are said (DESIGN §10, unit
//! sanity): generated assemblies whose parts are of one size (beam lengths
//! and rigid-body radii of gyration √(I/m) within 5× of each other, lever
//! arms within 5× of the sizes) give no warning at all; one part made 500×
//! to 100,000× the largest size, or one joint point put that far from a
//! rigid body's centre, gives exactly one warning, naming that part, its
//! JSON path and the ratio, computed here from the generated sizes.
//!
//! The assemblies are trees: a beam welded to the ground, each further
//! part joined to an earlier beam or rigid body (a weld; a pin for a point
//! mass) at an arc length of the beam or a body point, a rigid body's own
//! point given by `local` or, in half the cases, left to the partner's
//! point (the weld of the issue). The common scale runs from 1 µm to 1 m,
//! so a micrometre assembly is as consistent as a metre one.

use ancf_modal::error::Source;
use ancf_modal::model::number::significant;
use ancf_modal::model::Model;
use ancf_modal::model::ValidModel;
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, RngSeed};
use serde_json::{json, Value};

/// What a generated part is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Beam,
    /// A rigid body; `local`: its joint point given by `local` (else
    /// left to the partner's point).
    Rigid {
        local: bool,
    },
    Mass,
}

/// One part: its kind, its size in units of the scale (1–5), its parent
/// (an index among the earlier parts that can carry children), where on the
/// parent it sits (a fraction of its length or size) and the direction
/// of a beam or of a body's centre from its joint [deg].
#[derive(Debug, Clone)]
struct PartSpec {
    kind: Kind,
    size: f64,
    parent: usize,
    at: f64,
    angle_deg: f64,
}

fn part() -> impl Strategy<Value = PartSpec> {
    (
        prop_oneof![
            Just(Kind::Beam),
            any::<bool>().prop_map(|local| Kind::Rigid { local }),
            Just(Kind::Mass)
        ],
        1.0f64..5.0,
        any::<usize>(),
        0.0f64..1.0,
        -180.0f64..180.0,
    )
        .prop_map(|(kind, size, parent, at, angle_deg)| PartSpec {
            kind,
            size,
            parent,
            at,
            angle_deg,
        })
}

/// A generated assembly: its scale [m] (10^-6 … 1) and parts (the first a
/// beam welded to the ground, the second a beam or a rigid body, so that
/// it has a sized neighbour).
fn assembly() -> impl Strategy<Value = (f64, Vec<PartSpec>)> {
    (-6.0f64..0.0, prop::collection::vec(part(), 2..8)).prop_map(|(e, mut parts)| {
        parts[0].kind = Kind::Beam;
        if parts[1].kind == Kind::Mass {
            parts[1].kind = Kind::Beam;
        }
        (10f64.powf(e), parts)
    })
}

/// The built model and, for each part, its id, its JSON path of size, its
/// size [m] (None for a point mass) and the indices of its neighbours.
struct Built {
    model: Value,
    ids: Vec<String>,
    paths: Vec<String>,
    sizes: Vec<Option<f64>>,
    neighbours: Vec<Vec<usize>>,
    /// Global position of each rigid body's centre, and its index among
    /// the rigid bodies.
    centres: Vec<Option<([f64; 2], usize)>>,
}

/// For a part: the point spec of a child joined at fraction `at` of it,
/// and the global position of that point.
type Anchor = Box<dyn Fn(f64) -> (Value, [f64; 2])>;

fn dir(deg: f64) -> [f64; 2] {
    let (s, c) = deg.to_radians().sin_cos();
    [c, s]
}

fn add(p: [f64; 2], d: [f64; 2], k: f64) -> [f64; 2] {
    [p[0] + k * d[0], p[1] + k * d[1]]
}

/// Builds the assembly; `scaled`: part index and factor by which its size
/// grows (a beam's length, a body's √(I/m); its joint points stay put).
fn build(scale: f64, parts: &[PartSpec], scaled: Option<(usize, f64)>) -> Built {
    let factor = |i: usize| match scaled {
        Some((k, f)) if k == i => f,
        _ => 1.0,
    };
    let mut beams = Vec::new();
    let mut bodies = Vec::new();
    let mut masses = Vec::new();
    let mut joints = Vec::new();
    let mut b = Built {
        model: Value::Null,
        ids: Vec::new(),
        paths: Vec::new(),
        sizes: Vec::new(),
        neighbours: vec![Vec::new(); parts.len()],
        centres: Vec::new(),
    };
    let mut anchors: Vec<Anchor> = Vec::new();
    let mut carriers: Vec<usize> = Vec::new();
    for (i, p) in parts.iter().enumerate() {
        let size = p.size * scale;
        let id = format!("p{i}");
        // The anchor where this part is joined to its parent (the root: the
        // ground at the origin), and the parent's point spec.
        let (parent, parent_spec, anchor) = if i == 0 {
            (None, json!({"ground": [0.0, 0.0]}), [0.0, 0.0])
        } else {
            let k = carriers[p.parent % carriers.len()];
            let (spec, at) = anchors[k](p.at);
            (Some(k), spec, at)
        };
        if let Some(k) = parent {
            b.neighbours[i].push(k);
            b.neighbours[k].push(i);
        }
        let u = dir(p.angle_deg);
        match p.kind {
            Kind::Beam => {
                let length = size * factor(i);
                b.paths.push(format!("beams[{}].length", beams.len()));
                b.sizes.push(Some(length));
                b.centres.push(None);
                beams.push(json!({
                    "id": id, "start": anchor, "angle_deg": p.angle_deg, "length": length,
                    "elements": 2,
                    "section": {"height": 0.01 * size, "width": 0.02 * size},
                    "material": {"young": 70e9, "density": 2700.0}
                }));
                joints.push(json!({"type": "weld", "a": parent_spec, "b": {"beam": id, "s": 0.0}}));
                // Children sit at a fraction of the unscaled length.
                let (id2, a) = (id.clone(), anchor);
                anchors.push(Box::new(move |at| {
                    (json!({"beam": id2, "s": at * size}), add(a, u, at * size))
                }));
                carriers.push(i);
            }
            Kind::Rigid { local } => {
                // The centre at 0.5–1 sizes from the joint point.
                let arm = (0.5 + 0.5 * p.at) * size;
                let centre = add(anchor, u, arm);
                let rg = size * factor(i);
                let mass = 2700.0 * size.powi(3);
                b.paths
                    .push(format!("rigid_bodies[{}].inertia", bodies.len()));
                b.sizes.push(Some(rg));
                b.centres.push(Some((centre, bodies.len())));
                bodies.push(json!({
                    "id": id, "mass": mass, "inertia": mass * rg * rg, "position": centre
                }));
                let own = if local {
                    json!({"body": id, "local": [-arm * u[0], -arm * u[1]]})
                } else {
                    json!({"body": id})
                };
                joints.push(json!({"type": "weld", "a": parent_spec, "b": own}));
                // Children at up to 2 sizes from the centre, given by `local`.
                let id2 = id.clone();
                anchors.push(Box::new(move |at| {
                    let d = dir(360.0 * at);
                    let local = [2.0 * at * size * d[0], 2.0 * at * size * d[1]];
                    (
                        json!({"body": id2, "local": local}),
                        add(centre, local, 1.0),
                    )
                }));
                carriers.push(i);
            }
            Kind::Mass => {
                b.paths.push(format!("point_masses[{}]", masses.len()));
                b.sizes.push(None);
                b.centres.push(None);
                masses.push(json!({"id": id, "mass": 2700.0 * size.powi(3), "position": anchor}));
                joints.push(json!({"type": "pin", "a": parent_spec, "b": {"body": id}}));
                anchors.push(Box::new(|_| (Value::Null, [0.0; 2])));
            }
        }
        b.ids.push(id);
    }
    b.model = json!({
        "name": "generated", "beams": beams, "rigid_bodies": bodies,
        "point_masses": masses, "joints": joints
    });
    b
}

fn model(v: &Value) -> ValidModel {
    Model::from_json(&v.to_string(), Source::BuiltIn).expect("a valid generated model")
}

fn config(seed: u64) -> Config {
    Config {
        cases: 256,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::Off)),
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(41))]

    #[test]
    fn parts_of_one_size_give_no_warning((scale, parts) in assembly()) {
        let b = build(scale, &parts, None);
        let w = model(&b.model).unit_warnings();
        prop_assert!(w.is_empty(), "{:?}", w.iter().map(|w| w.to_string()).collect::<Vec<_>>());
    }

    #[test]
    fn one_part_made_large_is_named(
        (scale, parts) in assembly(),
        which in any::<usize>(),
        e in 2.7f64..5.0,
    ) {
        // The parts with a size; the one scaled grows to f times the
        // largest size (f ≥ 500, so over 100× each neighbour's).
        let sized: Vec<usize> = (1..parts.len()).filter(|&i| parts[i].kind != Kind::Mass).collect();
        let i = sized[which % sized.len()];
        let largest = parts.iter().map(|p| p.size).fold(0.0, f64::max);
        let f = 10f64.powf(e) * largest / parts[i].size;
        let b = build(scale, &parts, Some((i, f)));
        let w: Vec<String> = model(&b.model).unit_warnings().iter().map(|w| w.to_string()).collect();
        prop_assert_eq!(w.len(), 1, "{:?}", w);
        let size = b.sizes[i].unwrap();
        let smallest = b.neighbours[i].iter().filter_map(|&k| b.sizes[k]).fold(f64::INFINITY, f64::min);
        let ratio = significant(size / smallest, 3);
        prop_assert!(
            w[0].starts_with(&format!("{}: ", b.paths[i]))
                && w[0].contains(&format!("`{}`", b.ids[i]))
                && w[0].contains(&format!(" is {ratio} times the size of ")),
            "names {} ({}), ratio {}: {}", b.ids[i], b.paths[i], ratio, w[0]
        );
    }

    #[test]
    fn a_joint_point_far_from_a_body_is_named(
        (scale, parts) in assembly(),
        which in any::<usize>(),
        e in 2.7f64..5.0,
        angle in -180.0f64..180.0,
    ) {
        // A point mass pinned to a rigid body at f × the largest size from
        // its centre (a point mass has no size: only the arm counts).
        let mut b = build(scale, &parts, None);
        let bodies: Vec<usize> = (0..parts.len()).filter(|&i| b.centres[i].is_some()).collect();
        prop_assume!(!bodies.is_empty());
        let i = bodies[which % bodies.len()];
        let (centre, _) = b.centres[i].unwrap();
        let largest = parts.iter().map(|p| p.size).fold(0.0, f64::max) * scale;
        let arm = 10f64.powf(e) * largest;
        let d = dir(angle);
        let local = [arm * d[0], arm * d[1]];
        let joint = b.model["joints"].as_array().unwrap().len();
        b.model["point_masses"].as_array_mut().unwrap().push(
            json!({"id": "far", "mass": 1e-3, "position": add(centre, local, 1.0)}),
        );
        b.model["joints"].as_array_mut().unwrap().push(
            json!({"type": "pin", "a": {"body": b.ids[i], "local": local}, "b": {"body": "far"}}),
        );
        let w: Vec<String> = model(&b.model).unit_warnings().iter().map(|w| w.to_string()).collect();
        prop_assert_eq!(w.len(), 1, "{:?}", w);
        let ratio = significant(arm / b.sizes[i].unwrap(), 3);
        prop_assert!(
            w[0].starts_with(&format!("joints[{joint}].a: "))
                && w[0].contains(&format!("rigid body `{}`", b.ids[i]))
                && w[0].contains(&format!(", {ratio} times its radius of gyration")),
            "names {} at joints[{}].a, ratio {}: {}", b.ids[i], joint, ratio, w[0]
        );
    }
}
