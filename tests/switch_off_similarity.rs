//! Similarity of `switch-off` (issue 35, `DESIGN.md` §10): the paper's
//! switch-off scaled by λ — lengths ×λ, masses ×λ³, inertias ×λ⁵, forces
//! and preloads ×λ², spring stiffness ×λ, Hertz stiffness K [N/m^n]
//! ×λ^(2−n) (so that K δⁿ scales as a force), gravity ×1/λ, the step, end
//! time and distance ×λ and the sample rate ×1/λ; Young's modulus,
//! density, restitution and angles unchanged. Newton's second law then
//! holds for x(t) = λ·x₁(t/λ): the time to the distance scales by λ, the
//! tracked point's path by λ, the contact forces by λ², the energies by
//! λ³ — through the ON state's continuation, the release, the impacts and
//! their step control. The pin strikes its slot 17 times, and each impact
//! amplifies the scaling's round-off in the contact force: 1.4e-8 of it at
//! λ = 1.1e-3 (measured), so the forces are held to 1e-7, the path and the
//! times to 1e-9.

use ancf_modal::commands::switch_off::{run, SwitchOffRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use proptest::prelude::*;
use serde_json::Value;
use std::path::Path;

mod common;

/// `v` multiplied by `factor`, recursively through arrays.
fn scale(v: &mut Value, factor: f64) {
    match v {
        Value::Number(n) => *v = Value::from(n.as_f64().unwrap() * factor),
        Value::Array(items) => items.iter_mut().for_each(|x| scale(x, factor)),
        _ => {}
    }
}

/// The model file scaled by λ: each key by its unit. `contact_law` says
/// whether `stiffness` is a Hertz law's (×λ^(2−n)) or a spring's (×λ).
fn scale_model(v: &mut Value, lambda: f64, contact_law: bool) {
    let Value::Object(map) = v else {
        if let Value::Array(items) = v {
            items
                .iter_mut()
                .for_each(|x| scale_model(x, lambda, contact_law));
        }
        return;
    };
    let exponent = map.get("exponent").and_then(Value::as_f64);
    for (key, value) in map.iter_mut() {
        let power = match key.as_str() {
            "position" | "start" | "length" | "height" | "width" | "local" | "ground" | "s"
            | "from" | "to" | "pin_radius" | "radius" | "free_length" | "duration" | "until" => {
                Some(1.0)
            }
            "mass" => Some(3.0),
            "inertia" => Some(5.0),
            "force" | "preload" | "damping" => Some(2.0),
            "torsion_stiffness" => Some(3.0),
            "torsion_damping" => Some(4.0),
            "gravity" => Some(-1.0),
            "stiffness" if contact_law => Some(2.0 - exponent.expect("a Hertz law's exponent")),
            "stiffness" => Some(1.0),
            _ => None,
        };
        match power {
            Some(p) if !value.is_object() => scale(value, lambda.powf(p)),
            _ => scale_model(value, lambda, contact_law || key == "law"),
        }
    }
}

fn switch_off_model(lambda: f64) -> ModelInput {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/rcbo_switch_off.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    scale_model(&mut v, lambda, false);
    ModelInput::parse(&v.to_string(), Source::BuiltIn).unwrap()
}

/// The switch-off at scale λ, with its settings scaled.
fn switch_off_at(lambda: f64) -> ancf_modal::analysis::switch_off::SwitchOffResult {
    let d = SwitchOffRequest::default();
    let request = SwitchOffRequest {
        end_time: d.end_time * lambda,
        step: d.step * lambda,
        distance: d.distance * lambda,
        sample_rate: d.sample_rate / lambda,
        no_step_check: true,
        ..d
    };
    run(&switch_off_model(lambda), &request).unwrap().result
}

proptest! {
    #![proptest_config(common::fixed_cases(3, "SWITCH_OFF_SIMILARITY_SEED", 35))]

    #[test]
    fn a_scaled_switch_off_is_the_same_opening(log_lambda in -4.0f64..3.0) {
        let lambda = 10f64.powf(log_lambda);
        let (one, r) = (switch_off_at(1.0).flexible, switch_off_at(lambda).flexible);
        let (t1, t) = (one.time_to_distance_s.unwrap(), r.time_to_distance_s.unwrap());
        prop_assert!((t - t1 * lambda).abs() <= 1e-9 * t1 * lambda, "{t:e} s against {:e} s", t1 * lambda);
        prop_assert_eq!(r.steps, one.steps);
        prop_assert_eq!(r.time_s.len(), one.time_s.len());
        prop_assert!(common::scaled_off(&r.time_s, &one.time_s, lambda) < 1e-12);
        for (a, b) in [(&r.x_m, &one.x_m), (&r.y_m, &one.y_m)] {
            prop_assert!(common::scaled_off(a, b, lambda) < 1e-9, "path off by {:e}", common::scaled_off(a, b, lambda));
        }
        for (c, c1) in r.contacts.iter().zip(&one.contacts) {
            let f = common::scaled_off(&c.force_n, &c1.force_n, lambda * lambda);
            prop_assert!(f < 1e-7, "contact {} force off by {:e}", c.id, f);
        }
        let (e, e1) = (&r.energy, &one.energy);
        let stored = |x: &ancf_modal::analysis::simulate::Energies| x.kinetic_j + x.strain_j + x.spring_j;
        prop_assert!((stored(&e.end) - stored(&e1.end) * lambda.powi(3)).abs() <= 1e-9 * stored(&e1.end) * lambda.powi(3));
    }
}
