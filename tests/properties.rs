//! Metamorphic properties over generated assemblies (DESIGN §10): the
//! physics does not depend on placement, units (similarity), the order of
//! the file, or how a beam is cut into welded pieces, and the sparse path
//! finds the dense path's modes. Each property runs a fixed number of cases
//! from a fixed seed (deterministic), small assemblies, within seconds.
//!
//! Generated: 1–4 beams in a chain (welds, pins, pins with torsion springs
//! between them), free, pinned, clamped or on a slider; a rigid body welded
//! or pinned at a node or inside an element; a point mass pinned to a beam;
//! a spring to the ground; gravity.

mod common;
use ancf_modal::analysis::{modal_at_reference, EigenMethod, ModalResult, ModalSettings, ModeKind};
use ancf_modal::model::Placement;
use ancf_modal::model::ValidModel;
use ancf_modal::System;
use common::{model, rel};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use serde_json::{json, Value};

/// One beam of the chain: elements, length [mm], height [mm], turn from
/// the previous beam [deg], joint to the previous beam (0 weld, 1 pin,
/// 2 pin with torsion spring).
type BeamSpec = (usize, f64, f64, f64, u8);

#[derive(Debug, Clone)]
struct Spec {
    beams: Vec<BeamSpec>,
    /// 0 free, 1 pinned, 2 clamped, 3 slider at beam 0, s = 0.
    support: u8,
    /// (beam fraction along the chain, snap to a node, welded?, torsion?).
    body: Option<(f64, bool, bool, bool)>,
    /// Beam fraction of a pinned point mass.
    mass: Option<f64>,
    /// Spring from the body (or the last beam's end) to the ground.
    spring: bool,
    gravity: [f64; 2],
    nodes_at_attachments: bool,
}

fn spec() -> impl Strategy<Value = Spec> {
    let beam = (
        2usize..=5,
        10.0..40.0f64,
        0.6..1.4f64,
        -60.0..60.0f64,
        0u8..3,
    );
    (
        prop::collection::vec(beam, 1..=4),
        0u8..4,
        prop::option::of((0.05..0.95f64, any::<bool>(), any::<bool>(), any::<bool>())),
        prop::option::of(0.0..1.0f64),
        any::<bool>(),
        (-9.81..9.81f64, -9.81..9.81f64),
        any::<bool>(),
    )
        .prop_map(|(beams, support, body, mass, spring, g, nodes)| Spec {
            beams,
            support,
            body,
            mass,
            spring,
            gravity: [g.0, g.1],
            nodes_at_attachments: nodes,
        })
}

/// Where arc fraction `f` of the chain falls: (beam index, s [m]).
fn on_chain(beams: &[(f64, f64)], elements: &[usize], f: f64, snap: Option<usize>) -> (usize, f64) {
    let total: f64 = beams.iter().map(|b| b.0).sum();
    let mut left = f * total;
    for (i, &(l, _)) in beams.iter().enumerate() {
        if left <= l || i + 1 == beams.len() {
            let s = left.min(l);
            // On a node when asked, or when within 2 % of an element of
            // one: an attachment a few nm from a node makes an element a
            // millionth of its neighbours (not a property of the physics).
            let n = snap.unwrap_or(elements[i]) as f64;
            let grid = s / l * n;
            let near = (grid - grid.round()).abs() < 0.02;
            return if snap.is_some() || near {
                (i, grid.round() / n * l)
            } else {
                (i, s)
            };
        }
        left -= l;
    }
    unreachable!("at least one beam")
}

fn build(spec: &Spec) -> ValidModel {
    let mut beams = Vec::new();
    let mut joints = Vec::new();
    let (mut start, mut angle) = ([0.0f64, 0.0], 0.0f64);
    let mut placed = Vec::new();
    for (i, &(elements, len_mm, h_mm, turn, joint)) in spec.beams.iter().enumerate() {
        let l = len_mm * 1e-3;
        if i > 0 {
            angle += turn;
        }
        let id = format!("b{i}");
        beams.push(json!({
            "id": id, "start": start, "angle_deg": angle, "length": l, "elements": elements,
            "nodes_at_attachments": spec.nodes_at_attachments,
            "section": {"height": h_mm * 1e-3, "width": 5e-3},
            "material": {"young": 127e9, "density": 8940.0}
        }));
        if i > 0 {
            let prev = format!("b{}", i - 1);
            let kind = if joint == 0 { "weld" } else { "pin" };
            let mut j = json!({"id": format!("j{i}"), "type": kind,
                "a": {"beam": prev, "s": placed.last().map_or(0.0, |b: &(f64, f64)| b.0)},
                "b": {"beam": id, "s": 0.0}});
            if joint == 2 {
                j["torsion_stiffness"] = json!(0.3);
            }
            joints.push(j);
        }
        placed.push((l, angle));
        let t = angle.to_radians();
        start = [start[0] + l * t.cos(), start[1] + l * t.sin()];
    }
    let elements: Vec<usize> = spec.beams.iter().map(|b| b.0).collect();
    let point_on = |i: usize, s: f64| -> [f64; 2] {
        // Reference position of arc length s on beam i.
        let mut p = [0.0f64, 0.0];
        for (l, a) in placed.iter().take(i) {
            let t = a.to_radians();
            p = [p[0] + l * t.cos(), p[1] + l * t.sin()];
        }
        let t = placed[i].1.to_radians();
        [p[0] + s * t.cos(), p[1] + s * t.sin()]
    };
    match spec.support {
        1 => joints.push(json!({"id": "support", "type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b0", "s": 0.0}})),
        2 => joints.push(json!({"id": "support", "type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b0", "s": 0.0}})),
        3 => joints.push(json!({"id": "support", "type": "slider", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b0", "s": 0.0}, "axis": [0.6, 0.8]})),
        _ => {}
    }
    let mut rigid_bodies = Vec::new();
    let mut spring_end =
        json!({"beam": format!("b{}", placed.len() - 1), "s": placed.last().unwrap().0});
    if let Some((f, snap, weld, torsion)) = spec.body {
        let snap = snap.then_some(spec.beams[0].0);
        let (i, s) = on_chain(&placed, &elements, f, snap);
        let p = point_on(i, s);
        rigid_bodies.push(json!({"id": "body", "mass": 4e-4, "inertia": 2e-9,
            "position": [p[0] + 1e-3, p[1] - 2e-3], "angle_deg": 20.0}));
        let mut j = json!({"id": "body_joint", "type": if weld {"weld"} else {"pin"},
            "a": {"body": "body", "local": rotate_back([-1e-3, 2e-3], 20.0)},
            "b": {"beam": format!("b{i}"), "s": s}});
        if !weld && torsion {
            j["torsion_stiffness"] = json!(0.2);
        }
        joints.push(j);
        spring_end = json!({"body": "body"});
    }
    let mut point_masses = Vec::new();
    if let Some(f) = spec.mass {
        let (i, s) = on_chain(&placed, &elements, f, None);
        let p = point_on(i, s);
        point_masses.push(json!({"id": "mass", "mass": 2e-4, "position": p}));
        joints.push(json!({"id": "mass_pin", "type": "pin", "a": {"body": "mass"}, "b": {"beam": format!("b{i}"), "s": s}}));
    }
    let mut springs = Vec::new();
    if spec.spring {
        springs.push(json!({"id": "spring", "a": {"ground": [-0.01, 0.02]}, "b": spring_end, "stiffness": 2000.0, "preload": 0.0}));
    }
    model(json!({
        "name": "generated", "gravity": spec.gravity, "beams": beams,
        "rigid_bodies": rigid_bodies, "point_masses": point_masses,
        "joints": joints, "springs": springs
    }))
}

/// The body-frame vector whose global image (body turned by `deg`) is `v`.
fn rotate_back(v: [f64; 2], deg: f64) -> [f64; 2] {
    let (s, c) = (-deg).to_radians().sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

fn modal(
    m: &ValidModel,
    method: EigenMethod,
    modes: Option<usize>,
) -> Result<ModalResult, TestCaseError> {
    modal_at_reference(&System::new(m), &ModalSettings { modes, method })
        .map_err(|e| TestCaseError::fail(format!("modal failed: {e}")))
}

/// Same counts and kinds; frequencies within max(tol, the two bounds),
/// `scale` applied to the second.
fn same_modes(
    a: &ModalResult,
    b: &ModalResult,
    scale: f64,
    tol: f64,
    what: &str,
) -> Result<(), TestCaseError> {
    // A mode one solve refuses (its bound above 1e-5: no frequency) keeps
    // its number; the two are compared on the modes both report.
    prop_assert_eq!(
        (
            a.rigid_modes,
            a.mechanism_modes,
            a.modes.len() + a.refused_modes.len()
        ),
        (
            b.rigid_modes,
            b.mechanism_modes,
            b.modes.len() + b.refused_modes.len()
        ),
        "{}: zero, mechanism and mode counts",
        what
    );
    let pairs = a
        .modes
        .iter()
        .filter_map(|x| b.modes.iter().find(|y| y.index == x.index).map(|y| (x, y)));
    for (x, y) in pairs {
        prop_assert_eq!(
            x.kind.is_zero(),
            y.kind.is_zero(),
            "{}: mode {}",
            what,
            x.index
        );
        if y.kind.is_zero() {
            continue;
        }
        let bound = x.error_bound.unwrap_or(0.0) + y.error_bound.unwrap_or(0.0);
        let d = rel(x.frequency_hz, y.frequency_hz * scale).abs();
        prop_assert!(
            d <= tol.max(bound),
            "{}: mode {} {} Hz vs {} Hz, relative {:e} (bounds {:e})",
            what,
            x.index,
            x.frequency_hz,
            y.frequency_hz * scale,
            d,
            bound
        );
    }
    Ok(())
}

fn runner(cases: u32, seed: u8) -> TestRunner {
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(
        config,
        TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]),
    )
}

#[test]
fn placement_changes_no_count_kind_or_frequency() {
    let strategy = (spec(), 0.0..360.0f64, -2.0..3.0f64, 0.0..360.0f64);
    runner(1024, 1)
        .run(&strategy, |(spec, angle_deg, log_offset, direction)| {
            let m = build(&spec);
            let r = 10f64.powf(log_offset);
            let d = direction.to_radians();
            let placement = Placement {
                angle_deg,
                offset: [r * d.cos(), r * d.sin()],
            };
            let a = modal(&m, EigenMethod::Dense, None)?;
            let placed = m.placed(&placement).validated();
            let placed = placed.map_err(|e| TestCaseError::fail(format!("placed: {e}")))?;
            let b = modal(&placed, EigenMethod::Dense, None)?;
            same_modes(&b, &a, 1.0, 1e-9, &format!("{placement:?}"))?;
            // Kinds of clear modes (one kind holds 60 % of the energy) away
            // from any neighbour (a close pair may swap).
            let f: Vec<f64> = a.modes.iter().map(|m| m.frequency_hz).collect();
            for (k, (x, y)) in a.modes.iter().zip(&b.modes).enumerate() {
                let e = x.energy;
                let clear = e.axial.max(e.bending).max(e.springs) > 0.6;
                let apart = f
                    .iter()
                    .enumerate()
                    .all(|(j, g)| j == k || (g - f[k]).abs() > 1e-6 * f[k]);
                if !x.kind.is_zero() && clear && apart {
                    prop_assert_eq!(x.kind, y.kind, "mode {} kind", x.index);
                }
            }
            Ok(())
        })
        .unwrap();
}

/// All lengths × λ, same E and ρ: masses × λ³, inertias × λ⁵, spring
/// stiffness × λ, torsion stiffness × λ³, gravity × 1/λ, forces × λ².
fn scaled(m: &ValidModel, lambda: f64) -> ValidModel {
    let mut v: Value = serde_json::from_str(&m.to_json()).unwrap();
    let l = |x: &Value| json!(x.as_f64().unwrap() * lambda);
    let l2 = |p: &Value| {
        json!([
            p[0].as_f64().unwrap() * lambda,
            p[1].as_f64().unwrap() * lambda
        ])
    };
    for b in v["beams"].as_array_mut().unwrap() {
        b["start"] = l2(&b["start"]);
        b["length"] = l(&b["length"]);
        b["section"]["height"] = l(&b["section"]["height"]);
        b["section"]["width"] = l(&b["section"]["width"]);
    }
    for r in v["rigid_bodies"].as_array_mut().unwrap() {
        r["position"] = l2(&r["position"]);
        r["mass"] = json!(r["mass"].as_f64().unwrap() * lambda.powi(3));
        r["inertia"] = json!(r["inertia"].as_f64().unwrap() * lambda.powi(5));
    }
    for p in v["point_masses"].as_array_mut().unwrap() {
        p["position"] = l2(&p["position"]);
        p["mass"] = json!(p["mass"].as_f64().unwrap() * lambda.powi(3));
    }
    let point = |p: &mut Value| {
        for key in ["s"] {
            if let Some(x) = p.get(key).cloned() {
                p[key] = l(&x);
            }
        }
        for key in ["local", "ground"] {
            if let Some(x) = p.get(key).cloned() {
                p[key] = l2(&x);
            }
        }
    };
    for j in v["joints"].as_array_mut().unwrap() {
        point(&mut j["a"]);
        point(&mut j["b"]);
        if let Some(k) = j.get("torsion_stiffness").cloned() {
            j["torsion_stiffness"] = json!(k.as_f64().unwrap() * lambda.powi(3));
        }
    }
    for s in v["springs"].as_array_mut().unwrap() {
        point(&mut s["a"]);
        point(&mut s["b"]);
        s["stiffness"] = l(&s["stiffness"]);
        if let Some(p) = s.get("preload").cloned() {
            s["preload"] = json!(p.as_f64().unwrap() * lambda * lambda);
        }
    }
    let g = &v["gravity"];
    v["gravity"] = json!([
        g[0].as_f64().unwrap() / lambda,
        g[1].as_f64().unwrap() / lambda
    ]);
    model(v)
}

#[test]
fn similarity_scales_every_frequency_by_one_over_lambda() {
    let strategy = (spec(), -3.0..3.0f64);
    runner(1024, 2)
        .run(&strategy, |(spec, log_lambda)| {
            let m = build(&spec);
            let lambda = 10f64.powf(log_lambda);
            let a = modal(&m, EigenMethod::Dense, None)?;
            let b = modal(&scaled(&m, lambda), EigenMethod::Dense, None)?;
            same_modes(&b, &a, 1.0 / lambda, 1e-9, &format!("λ = {lambda:e}"))
        })
        .unwrap();
}

#[test]
fn the_order_of_the_file_changes_nothing() {
    runner(1024, 3)
        .run(&spec(), |spec| {
            let m = build(&spec);
            let mut p = m.to_model();
            p.beams.reverse();
            p.rigid_bodies.reverse();
            p.point_masses.reverse();
            p.joints.reverse();
            p.springs.reverse();
            let p = p.validated();
            let p = p.map_err(|e| TestCaseError::fail(format!("reversed: {e}")))?;
            let a = modal(&m, EigenMethod::Dense, None)?;
            let b = modal(&p, EigenMethod::Dense, None)?;
            same_modes(&b, &a, 1.0, 1e-12, "reversed file")
        })
        .unwrap();
}

#[test]
fn a_beam_cut_at_a_node_into_two_welded_beams_keeps_its_bending_modes() {
    // Uniform mesh of n elements cut at node k: the two pieces have the
    // same element lengths. The weld ties positions and the slope's
    // direction, not |r'|, so only the bending modes must agree.
    let strategy = (2usize..=8, 0.0..1.0f64, 0u8..3, any::<bool>(), 0.0..90.0f64);
    runner(1024, 4)
        .run(&strategy, |(n, cut, support, tip_mass, angle)| {
            let k = 1 + ((n - 1) as f64 * cut) as usize;
            let len = 20e-3;
            let lk = len * k as f64 / n as f64;
            let t = angle.to_radians();
            let beam = |id: &str, start: [f64; 2], l: f64, e: usize| {
                json!({"id": id, "start": start, "angle_deg": angle, "length": l, "elements": e,
                       "nodes_at_attachments": false,
                       "section": {"height": 1e-3, "width": 5e-3},
                       "material": {"young": 127e9, "density": 8940.0}})
            };
            let support_joint = |id: &str| match support {
                1 => Some(json!({"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": id, "s": 0.0}})),
                2 => Some(json!({"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": id, "s": 0.0}})),
                _ => None,
            };
            let tip = [len * t.cos(), len * t.sin()];
            let masses = if tip_mass {
                json!([{"id": "m", "mass": 3e-4, "position": tip}])
            } else {
                json!([])
            };
            let mut whole_joints: Vec<Value> = support_joint("a").into_iter().collect();
            let mut cut_joints: Vec<Value> = support_joint("a").into_iter().collect();
            cut_joints.push(json!({"type": "weld", "a": {"beam": "a", "s": lk}, "b": {"beam": "b", "s": 0.0}}));
            if tip_mass {
                whole_joints.push(json!({"type": "pin", "a": {"body": "m"}, "b": {"beam": "a", "s": len}}));
                cut_joints.push(json!({"type": "pin", "a": {"body": "m"}, "b": {"beam": "b", "s": len - lk}}));
            }
            let whole = model(json!({"name": "whole", "beams": [beam("a", [0.0, 0.0], len, n)],
                "point_masses": masses, "joints": whole_joints}));
            let pieces = model(json!({"name": "cut", "beams": [
                    beam("a", [0.0, 0.0], lk, k),
                    beam("b", [lk * t.cos(), lk * t.sin()], len - lk, n - k)],
                "point_masses": masses, "joints": cut_joints}));
            let a = modal(&whole, EigenMethod::Dense, None)?;
            let b = modal(&pieces, EigenMethod::Dense, None)?;
            prop_assert_eq!(a.rigid_modes, b.rigid_modes);
            let bending = |r: &ModalResult| -> Vec<(f64, f64)> {
                r.modes
                    .iter()
                    .filter(|m| m.kind == ModeKind::Bending && m.energy.bending > 0.999)
                    .map(|m| (m.frequency_hz, m.error_bound.unwrap()))
                    .collect()
            };
            let (ba, bb) = (bending(&a), bending(&b));
            for (x, y) in ba.iter().zip(&bb).take(4) {
                let d = rel(x.0, y.0).abs();
                prop_assert!(d <= 1e-12f64.max(x.1 + y.1), "{} vs {} Hz ({:e})", x.0, y.0, d);
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn the_sparse_path_finds_the_dense_mode_set() {
    runner(1024, 5)
        .run(&spec(), |spec| {
            let m = build(&spec);
            let dense = modal(&m, EigenMethod::Dense, None)?;
            let wanted = dense.modes.len().min(dense.rigid_modes + 8);
            let dense = modal(&m, EigenMethod::Dense, Some(wanted))?;
            let sparse = modal(&m, EigenMethod::Sparse, Some(wanted))?;
            same_modes(&sparse, &dense, 1.0, 1e-9, "sparse vs dense")
        })
        .unwrap();
}
