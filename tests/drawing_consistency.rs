//! What the mode drawings show matches the motion (issue 36): checked on
//! the report's own SVG output (pixels written to 0.01 px), every frame of
//! every animation.
//!
//! - Every joint marker lies within 0.5 px of both points it joins, each
//!   moved by its own linearization p(q₀) + c·(∂p/∂q)·φ, the derivative
//!   taken here by central finite differences of the anchors' positions
//!   (independent of the drawing's analytic map). A slider's marker sits on
//!   point b and on its drawn rail.
//! - Every vertex of a rigid body's outline at offset d = A(θ₀)ℓ from the
//!   body's reference point is drawn at P + c·(φ_x + φ_θ ẑ×d).
//!
//! Models: every shipped model, the slider-crank of tests/data, and
//! generated assemblies (proptest, fixed seed; DRAWING_SEED=N explores):
//! a beam clamped or pinned at its root, a rigid body pinned (with a torsion
//! spring) or welded at a node or inside an element through an offset
//! point, optionally held by a slider on a ground rail at another offset, or
//! by a spring to the ground.

mod common;

use ancf_modal::analysis::{modal, ModalSettings};
use ancf_modal::model::ValidModel;
use ancf_modal::output::figures::{assembly_geometry, ModeShapeSettings};
use ancf_modal::output::report::animate::{animated_svg, mode_frames, PHASES};
use ancf_modal::output::report::svg::View;
use ancf_modal::{Model, System};
use common::{model, pixels};
use nalgebra::Vector2;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use serde_json::json;

/// The largest distance allowed between a drawn joint and the point it
/// joins [px].
const TOLERANCE_PX: f64 = 0.5;

/// The values of `attribute` of `node` in each frame: its `<animate>`'s
/// (PHASES of them) or the static attribute repeated.
fn frames_of(node: roxmltree::Node, attribute: &str) -> Vec<String> {
    let animated = node
        .children()
        .find(|c| c.has_tag_name("animate") && c.attribute("attributeName") == Some(attribute));
    match animated {
        Some(a) => {
            let v: Vec<String> = a
                .attribute("values")
                .unwrap()
                .split(';')
                .map(String::from)
                .collect();
            assert_eq!(v.len(), PHASES + 1, "a period and the first frame again");
            v[..PHASES].to_vec()
        }
        None => vec![node.attribute(attribute).unwrap().to_string(); PHASES],
    }
}

fn distance(a: [f64; 2], b: (f64, f64)) -> f64 {
    (a[0] - b.0).hypot(a[1] - b.1)
}

/// Distance from `p` to the line through `a` and `b` [px].
fn to_line(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    ((p[0] - a[0]) * dy - (p[1] - a[1]) * dx).abs() / dx.hypot(dy)
}

/// Checks every elastic mode's animation of `m` (at most six modes).
fn check_model(m: &ValidModel) -> Result<(), String> {
    let system = System::new(m);
    let result = modal(
        &system,
        &system.reference(),
        &ModalSettings {
            modes: Some(8),
            ..ModalSettings::default()
        },
    )
    .map_err(|e| format!("modal: {e}"))?;
    let settings = ModeShapeSettings {
        points_per_element: 8,
        ..ModeShapeSettings::default()
    };
    let q0 = &system.q0;
    let origin = system.origin;
    let undeformed = assembly_geometry(&system, q0, settings.points_per_element);
    for mode in result.modes.iter().filter(|m| !m.kind.is_zero()).take(6) {
        let frames = mode_frames(&system, q0, mode, &settings);
        let points = frames.frames.iter().flat_map(|f| f.points());
        let view = View::fit(points.chain(undeformed.points()), 600.0, 12.0);
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\">{}</svg>",
            animated_svg(&view, &frames)
        );
        let doc = roxmltree::Document::parse(&svg).map_err(|e| e.to_string())?;
        let a = frames.amplitude;
        let phase = |k: usize| a * (2.0 * std::f64::consts::PI * k as f64 / PHASES as f64).cos();
        let phi = &mode.shape;
        let scale = phi.iter().fold(0.0f64, |s, p| s.max(p.abs()));
        let h = 1e-6 / scale.max(1e-300);
        let moved =
            |sign: f64| -> Vec<f64> { q0.iter().zip(phi).map(|(q, p)| q + sign * h * p).collect() };
        let (plus, minus) = (moved(1.0), moved(-1.0));
        // p(q₀) and (∂p/∂q)·φ by central differences, in the model's frame.
        let linear = |p: &dyn Fn(&[f64]) -> Vector2<f64>| {
            (p(q0) + origin, (p(&plus) - p(&minus)) / (2.0 * h))
        };
        let drawn_at = |(p, v): (Vector2<f64>, Vector2<f64>), k: usize| {
            let c = phase(k);
            view.px([p.x + c * v.x, p.y + c * v.y])
        };
        let what = |k: usize| {
            format!(
                "mode {} ({:.1} Hz), frame {k}",
                mode.index, mode.frequency_hz
            )
        };

        let rails: Vec<Vec<String>> = doc
            .descendants()
            .filter(|n| n.attribute("class") == Some("rail"))
            .map(|n| frames_of(n, "points"))
            .collect();
        let mut rail = rails.iter();
        for node in doc
            .descendants()
            .filter(|n| n.attribute("data-joint").is_some())
        {
            let i: usize = node.attribute("data-joint").unwrap().parse().unwrap();
            let joint = &system.constraints[i];
            let pair = joint.pair();
            let pa = linear(&|q| pair.a.position(q));
            let pb = linear(&|q| pair.b.position(q));
            let (cx, cy) = (frames_of(node, "cx"), frames_of(node, "cy"));
            let slider = joint.line_direction(q0).is_some();
            let rail_frames = if slider { rail.next() } else { None };
            for k in 0..PHASES {
                let marker = [cx[k].parse::<f64>().unwrap(), cy[k].parse::<f64>().unwrap()];
                let (da, db) = (
                    distance(marker, drawn_at(pa, k)),
                    distance(marker, drawn_at(pb, k)),
                );
                let label = joint.label();
                if db > TOLERANCE_PX {
                    return Err(format!(
                        "{}: joint `{label}` drawn {db:.3} px from its point b",
                        what(k)
                    ));
                }
                match rail_frames {
                    Some(r) => {
                        let ends = pixels(&r[k]);
                        let off = to_line(marker, ends[0], ends[1]);
                        if off > TOLERANCE_PX {
                            return Err(format!(
                                "{}: slider `{label}` drawn {off:.3} px off its rail",
                                what(k)
                            ));
                        }
                    }
                    None if da > TOLERANCE_PX => {
                        return Err(format!(
                            "{}: joint `{label}` drawn {da:.3} px from its point a",
                            what(k)
                        ));
                    }
                    None => {}
                }
            }
        }
        // Rigid bodies: outlines in the order of the system's bodies.
        let outlines = doc
            .descendants()
            .filter(|n| matches!(n.attribute("class"), Some("body") | Some("body link")));
        for ((body, node), reference) in system
            .rigid_bodies
            .iter()
            .zip(outlines)
            .zip(&undeformed.bodies)
        {
            if reference.len() < 2 {
                continue;
            }
            let d = body.dof0;
            let centre = Vector2::new(q0[d], q0[d + 1]) + origin;
            let (vx, vy, vt) = (phi[d], phi[d + 1], phi[d + 2]);
            let drawn = frames_of(node, "points");
            for (k, frame) in drawn.iter().enumerate() {
                let c = phase(k);
                for (j, (vertex, p)) in pixels(frame).iter().zip(reference).enumerate() {
                    let off = Vector2::new(p[0], p[1]) - centre;
                    let want =
                        view.px([p[0] + c * (vx - vt * off.y), p[1] + c * (vy + vt * off.x)]);
                    let e = distance(*vertex, want);
                    if e > TOLERANCE_PX {
                        return Err(format!(
                            "{}: body `{}` vertex {j} drawn {e:.3} px off",
                            what(k),
                            body.id
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

#[test]
fn every_shipped_model_draws_its_joints_on_both_parts() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<_> = std::fs::read_dir(root.join("models"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.push(root.join("tests/data/slider_crank.json"));
    files.sort();
    assert!(files.len() >= 6, "{files:?}");
    for path in files {
        let m = Model::from_file(&path).unwrap();
        if let Err(e) = check_model(&m) {
            panic!("{}: {e}", path.display());
        }
    }
    // The built-in paper assembly too.
    check_model(&Model::builtin()).unwrap();
}

/// A generated assembly (see the module docs).
#[derive(Debug, Clone)]
struct Design {
    elements: usize,
    length: f64,
    angle_deg: f64,
    clamped: bool,
    /// Element and fraction of it where the body is attached.
    at: (usize, f64),
    offset: [f64; 2],
    weld: bool,
    torsion: f64,
    /// A second body point on a ground rail of this direction [deg].
    rail_deg: Option<f64>,
    spring: bool,
}

fn design() -> impl Strategy<Value = Design> {
    (
        (2usize..6, 0.04f64..0.3, -60.0f64..60.0, any::<bool>()),
        (0usize..6, prop_oneof![Just(0.0), Just(1.0), 0.1f64..0.9]),
        (
            -8e-3f64..8e-3,
            -8e-3f64..8e-3,
            any::<bool>(),
            prop_oneof![Just(0.0), 0.01f64..1.0],
        ),
        (proptest::option::of(0.0f64..180.0), any::<bool>()),
    )
        .prop_map(
            |(
                (elements, length, angle_deg, clamped),
                (e, f),
                (ox, oy, weld, torsion),
                (rail_deg, spring),
            )| Design {
                elements,
                length,
                angle_deg,
                clamped,
                at: (e % elements, f),
                offset: [ox, oy],
                weld,
                torsion,
                rail_deg: if clamped {
                    rail_deg
                } else {
                    rail_deg.or(Some(30.0))
                },
                spring,
            },
        )
}

fn assembly(d: &Design) -> ValidModel {
    let (c, s) = (
        d.angle_deg.to_radians().cos(),
        d.angle_deg.to_radians().sin(),
    );
    let at_s = d.length * (d.at.0 as f64 + d.at.1) / d.elements as f64;
    let point = [at_s * c, at_s * s];
    // The body's centre sits so that its local `offset` is the beam point.
    let centre = [point[0] - d.offset[0], point[1] - d.offset[1]];
    let far = [-d.offset[1] + 3e-3, d.offset[0] - 2e-3];
    let far_at = [centre[0] + far[0], centre[1] + far[1]];
    let root = if d.clamped { "weld" } else { "pin" };
    let mut joints = vec![
        json!({"id": "root", "type": root, "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}}),
    ];
    let mut attach = json!({"id": "attach", "type": if d.weld { "weld" } else { "pin" },
        "a": {"beam": "b", "s": at_s}, "b": {"body": "block", "local": d.offset}});
    if !d.weld && d.torsion > 0.0 {
        attach["torsion_stiffness"] = json!(d.torsion);
    }
    joints.push(attach);
    if let Some(deg) = d.rail_deg {
        let r = deg.to_radians();
        joints.push(
            json!({"id": "rail", "type": "slider", "a": {"ground": far_at},
            "b": {"body": "block", "local": far}, "axis": [r.cos(), r.sin()]}),
        );
    }
    let mut m = json!({
        "name": "generated",
        "beams": [{"id": "b", "start": [0.0, 0.0], "angle_deg": d.angle_deg, "length": d.length,
            "elements": d.elements, "section": {"height": 1e-3, "width": 5e-3},
            "material": {"young": 210e9, "density": 7850.0}}],
        "rigid_bodies": [{"id": "block", "mass": 2e-3, "inertia": 2e-8, "position": centre}],
        "joints": joints,
    });
    if d.spring {
        m["springs"] = json!([{"id": "k", "a": {"ground": [far_at[0], far_at[1] + 0.02]},
            "b": {"body": "block", "local": far}, "stiffness": 500.0, "preload": 0.0}]);
    }
    model(m)
}

#[test]
fn generated_assemblies_draw_their_joints_and_bodies_by_the_one_linear_map() {
    let seed: u64 = std::env::var("DRAWING_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(36);
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 24,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &bytes),
    );
    runner
        .run(&design(), |d| {
            let m = assembly(&d);
            check_model(&m).map_err(|e| TestCaseError::fail(format!("{d:?}: {e}")))
        })
        .unwrap();
}
