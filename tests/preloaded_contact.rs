//! A contact closed in the initial (pre-stressed) equilibrium has had no
//! impact: it is elastic, F = Kδⁿ with no hysteresis term, until it first
//! separates; its stored energy all goes into motion. A point mass of 1 g
//! rests on a ground line (radius 0.5 mm, Lankarani–Nikravesh K = 1e9
//! N/m^1.5, c_r = 0.5), pressed by a 2 N load released at t = 0, gravity
//! off. Closed forms: the static penetration δ₀ = (P/K)^(1/n), the stored
//! energy U₀ = Kδ₀ⁿ⁺¹/(n + 1), and, elastic, the speed after separation
//! √(2U₀/m). With the hysteresis term and the law's 1 mm/s floor on δ̇⁻
//! the force would collapse as soon as the mass moves and the speed would
//! be a fraction of that.

mod common;
use ancf_modal::analysis::simulate::{simulate, SimulationSettings};
use ancf_modal::analysis::transient::TransientSettings;
use ancf_modal::System;
use common::model;
use serde_json::json;

const MASS: f64 = 1e-3;
const K: f64 = 1e9;
const N: f64 = 1.5;
const P: f64 = 2.0;
const RADIUS: f64 = 0.5e-3;

#[test]
fn a_preloaded_contact_is_elastic_until_it_separates() {
    let m = model(json!({
        "name": "preloaded_contact",
        "point_masses": [{"id": "m", "mass": MASS, "position": [0.0, RADIUS]}],
        "contacts": [{
            "id": "floor", "type": "point_line",
            "point": {"body": "m"}, "radius": RADIUS,
            "line": {"ground": true, "from": [-1e-3, 0.0], "to": [1e-3, 0.0]},
            "side": "left",
            "law": {"model": "lankarani_nikravesh", "stiffness": K, "restitution": 0.5}
        }],
        "loads": [{"id": "press", "at": {"body": "m"}, "force": [0.0, -P],
                   "time": {"until": 0.0}}]
    }));
    let sys = System::new(&m);
    let settings = SimulationSettings {
        transient: TransientSettings {
            step: 1e-7,
            end_time: 2e-4,
            spectral_radius: 1.0,
            tolerance: 1e-12,
            ..TransientSettings::default()
        },
        start: ancf_modal::analysis::statics::start::Start::Equilibrium,
        sample_rate: 0.0,
        keep_partial: false,
    };
    let anchor = sys.anchor_of(&m.resolve_point(&point(), "point").unwrap());
    let sim = simulate(sys, &[anchor], &settings).unwrap();
    let y = &sim.points[0][1];
    let c = &sim.contacts[0];
    let delta0 = (P / K).powf(1.0 / N);
    let d_start = RADIUS - y[0];
    assert!(
        ((d_start - delta0) / delta0).abs() < 1e-6,
        "ON penetration {d_start} vs (P/K)^(1/n) = {delta0}"
    );
    assert!(
        ((c.force_n[0] - P) / P).abs() < 1e-6,
        "ON contact force {} vs the load {P}",
        c.force_n[0]
    );
    let open = y
        .iter()
        .position(|&y| RADIUS - y <= 0.0)
        .expect("the mass leaves the floor");
    for (k, (&y, &f)) in y.iter().zip(&c.force_n).take(open).enumerate() {
        let elastic = K * (RADIUS - y).powf(N);
        assert!(
            (f - elastic).abs() <= 1e-9 * P,
            "sample {k}: force {f} vs Kδⁿ = {elastic}"
        );
    }
    assert!(
        c.force_n[open..].iter().all(|&f| f == 0.0),
        "no force after the separation"
    );
    assert_eq!(c.impacts, 0, "no new impact: gravity is off");
    assert_eq!(c.dissipated, 0.0, "an elastic contact dissipates nothing");
    // Energy: all of U₀ becomes motion.
    let u0 = K * delta0.powf(N + 1.0) / (N + 1.0);
    let v_expected = (2.0 * u0 / MASS).sqrt();
    let (t, yl) = (&sim.time, y);
    let last = t.len() - 1;
    let v = (yl[last] - yl[last - 1]) / (t[last] - t[last - 1]);
    assert!(
        ((v - v_expected) / v_expected).abs() < 1e-4,
        "speed after separation {v} vs √(2U₀/m) = {v_expected}"
    );
}

fn point() -> ancf_modal::model::PointSpec {
    ancf_modal::model::PointSpec {
        body: Some(String::from("m")),
        ..Default::default()
    }
}
