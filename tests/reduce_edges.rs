//! `reduce` at its edges, as a new user met them: a body that keeps its
//! supports, a compressed pre-stress, a mechanism under the held check, a
//! poor basis, and interface points that would spoil the mesh. Numbers come
//! from closed forms (Euler–Bernoulli, a rigid strip's Rayleigh quotient
//! under an end load) and from the full model's own modes.

use ancf_modal::analysis::reduce::{rigid_stiffening, ReductionMethod};
use ancf_modal::commands::reduce::{run, ReduceRequest, ReduceRun};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use std::f64::consts::PI;

/// A steel strip 0.5 m × 5 mm × 0.5 mm along x, 40 elements, with the
/// joints and loads given.
fn strip(joints: &str, loads: &str) -> ModelInput {
    let text = format!(
        r#"{{"name":"strip","gravity":[0,0],
        "beams":[{{"id":"strip","start":[0,0],"angle_deg":0,"length":0.5,"elements":40,
          "section":{{"height":5e-4,"width":5e-3}},"material":{{"young":2e11,"density":7850}}}}],
        "joints":[{joints}],"loads":[{loads}]}}"#
    );
    ModelInput::parse(&text, Source::BuiltIn).expect("valid strip")
}

const PIN_AND_ROLLER: &str = r#"{"id":"pin","type":"pin","a":{"ground":[0,0]},"b":{"beam":"strip","s":0}},
    {"id":"roller","type":"slider","a":{"ground":[0.5,0]},"b":{"beam":"strip","s":0.5},"axis":[1,0]}"#;

fn end_load(px: f64) -> String {
    format!(
        r#"{{"id":"end","at":{{"beam":"strip","s":0.5}},"frame":"global","force":[{px},0],"time":"constant"}}"#
    )
}

fn request(interface: &[(&str, f64)], modes: usize) -> ReduceRequest {
    ReduceRequest {
        interface: interface.iter().map(|(b, s)| (b.to_string(), *s)).collect(),
        modes,
        ..ReduceRequest::default()
    }
}

fn reduce(input: &ModelInput, request: &ReduceRequest) -> ReduceRun {
    run(input, request).expect("reduction")
}

#[test]
fn a_body_that_keeps_its_supports_keeps_every_mode_and_leaves_nothing_to_the_frame() {
    // The strip clamped at its root, supports kept, the tip as interface:
    // nothing is rigid, so the frame carries nothing and the cantilever's
    // first mode is compared, not set apart (a trial lost it).
    let weld = r#"{"id":"root","type":"weld","a":{"ground":[0,0]},"b":{"beam":"strip","s":0}}"#;
    let input = strip(weld, "");
    let r = reduce(
        &input,
        &ReduceRequest {
            keep_supports: true,
            ..request(&[("strip", 0.5)], 6)
        },
    );
    assert_eq!(r.reduction.rigid.ncols(), 0);
    let c = &r.document.output.check;
    assert!(c.frame_hz.is_empty(), "{:?}", c.frame_hz);
    assert_eq!(c.zero_modes, 0);
    let (ei, rho_a) = (2e11 * 5e-3 * 5e-4f64.powi(3) / 12.0, 7850.0 * 5e-3 * 5e-4);
    let f1 = 1.875_104_068_7f64.powi(2) / (2.0 * PI * 0.25) * (ei / rho_a).sqrt();
    assert!(
        (c.full_hz[0] / f1 - 1.0).abs() < 1e-5,
        "{} vs {f1}",
        c.full_hz[0]
    );
    assert!(c.relative_error[0].abs() < 1e-4, "{:?}", c.relative_error);
}

#[test]
fn a_compressed_strip_s_rotation_is_softened_and_signed() {
    // Pin and roller, pushed by 0.2 N (Euler's load π²EI/L² = 0.41 N);
    // freed of its supports the strip's rotation has the Rayleigh quotient
    // −12P/(ρAL²) (an end load P turning with an arm L against J = mL²/12),
    // and the full model's lowest mode lies below it (Ritz).
    let p = 0.2;
    let input = strip(PIN_AND_ROLLER, &end_load(-p));
    let r = reduce(
        &input,
        &ReduceRequest {
            prestress: true,
            ..request(&[("strip", 0.0), ("strip", 0.5)], 8)
        },
    );
    let quotient = -12.0 * p / (7850.0 * 5e-3 * 5e-4 * 0.25);
    let k = rigid_stiffening(&r.system, &r.linearization(), &r.reduction);
    // Within the stretch P/EA = 4e-7 and round-off.
    assert!((k / quotient - 1.0).abs() < 1e-5, "RᵀKR {k} vs {quotient}");
    let c = &r.document.output.check;
    assert_eq!(c.frame_hz.len(), 1, "{:?}", c.frame_hz);
    let f = c.frame_hz[0];
    assert!(
        f < 0.0,
        "a softened rotation is an imaginary frequency: {f}"
    );
    let w2 = -(2.0 * PI * f).powi(2);
    assert!(w2 <= k * (1.0 - 1e-9), "ω² {w2} above the quotient {k}");
}

#[test]
fn the_held_check_leaves_a_mechanism_out_on_both_sides() {
    // An arm welded to the ground with a strip pinned at its tip: held at
    // the arm's root the strip still turns on the pin, a zero mode of both
    // the full model and the body.
    let text = r#"{"name":"wiper","gravity":[0,0],
      "beams":[{"id":"arm","start":[0,0],"angle_deg":90,"length":0.4,"elements":16,
         "section":{"height":8e-3,"width":4e-3},"material":{"young":2.1e11,"density":7850}},
        {"id":"carrier","start":[-0.25,0.4],"angle_deg":0,"length":0.5,"elements":20,
         "section":{"height":2e-3,"width":6e-3},"material":{"young":2.1e11,"density":7850}}],
      "joints":[{"id":"hinge","type":"pin","a":{"beam":"arm","s":0.4},"b":{"beam":"carrier","s":0.25}}]}"#;
    let input = ModelInput::parse(text, Source::BuiltIn).expect("valid model");
    let r = reduce(
        &input,
        &ReduceRequest {
            method: ReductionMethod::FreeInterface,
            ..request(&[("arm", 0.0)], 6)
        },
    );
    let c = &r.document.output.check;
    assert_eq!(c.zero_modes, 1, "the pin's mechanism");
    assert!(c.full_hz.iter().all(|&f| f > 1.0), "{:?}", c.full_hz);
    for (i, e) in c.relative_error.iter().take(3).enumerate() {
        assert!(e.abs() < 1e-3, "mode {}: {e:e} ({:?})", i + 1, c.full_hz);
    }
}

#[test]
fn a_poor_basis_is_warned_about() {
    // One interface point and two component modes on a free strip: the
    // check's last modes are far off, and a warning says so.
    let input = strip("", "");
    let r = reduce(&input, &request(&[("strip", 0.0)], 2));
    let c = &r.document.output.check;
    let worst = c.relative_error.iter().fold(0.0f64, |a, e| a.max(e.abs()));
    let warned = r
        .document
        .warnings
        .iter()
        .any(|w| w.to_string().contains("misses the full model"));
    assert!(worst > 0.1, "this basis is poor: worst {worst:e}");
    assert!(warned, "worst {worst:e}: {:?}", r.document.warnings);
    // A basis with enough modes is not warned about.
    let good = reduce(&input, &request(&[("strip", 0.0), ("strip", 0.5)], 8));
    assert!(
        good.document.warnings.is_empty(),
        "{:?}",
        good.document.warnings
    );
}

#[test]
fn interface_points_that_repeat_or_crowd_a_node_are_refused() {
    let input = strip("", "");
    let text = |points: &[(&str, f64)]| run(&input, &request(points, 4)).unwrap_err().to_string();
    let e = text(&[("strip", 0.25), ("strip", 0.25)]);
    assert!(e.contains("strip:0.25") && e.contains("repeats"), "{e}");
    // 0.1 µm from the node at 0.25 m on 12.5 mm elements.
    let e = text(&[("strip", 0.0), ("strip", 0.250_000_1)]);
    assert!(e.contains("1.000e-7 m") && e.contains("element"), "{e}");
    // 0.5 mm away is sound.
    assert!(run(&input, &request(&[("strip", 0.0), ("strip", 0.2505)], 4)).is_ok());
    // A load factor without the pre-stress it scales.
    let e = run(
        &input,
        &ReduceRequest {
            load_scale: 2.0,
            ..request(&[("strip", 0.0)], 4)
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("load_scale") && e.contains("prestress"), "{e}");
}
