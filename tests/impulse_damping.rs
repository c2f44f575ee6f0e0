//! `impulse` identifies the first bending mode's damping from its own
//! simulated force and sensor records (H1 and the LSCF fit) and compares it
//! with the model's Rayleigh ratio ζ = α/(2ω) + βω/2 plus the integrator's
//! numerical damping.

use ancf_modal::analysis::impulse::{run_impulse, ImpulseSettings};
use ancf_modal::analysis::transient::TransientSettings;
use ancf_modal::model::RayleighDamping;
use ancf_modal::model::ValidModel;
use ancf_modal::output::impulse_report::impulse_table;
use ancf_modal::results::ImpulseOutput;
use ancf_modal::Model;
use std::f64::consts::PI;

/// The built-in paper assembly with Rayleigh damping giving its first
/// bending mode (4577 Hz) the ratio `zeta`, split evenly between α and β.
fn damped_builtin(zeta: f64) -> ValidModel {
    let mut m = Model::builtin().into_model();
    let omega = 2.0 * PI * 4577.0;
    m.damping = Some(RayleighDamping {
        alpha: zeta * omega,
        beta: zeta / omega,
    });
    m.validated().expect("a valid model")
}

#[test]
fn identified_damping_matches_the_rayleigh_ratio() {
    // Tolerance 1 %: the fit itself is exact to 1e-5 on a single-mode
    // record; the other modes' tails in the band bias it by about +0.12ζ
    // relative (measured, see the damping module doc): +2.4e-3 at ζ = 2 %.
    // The integrator's numerical damping (ρ∞ = 0.9, ωh = 0.029) is 1.7e-9.
    for zeta in [0.005, 0.02] {
        let r = run_impulse(
            &damped_builtin(zeta),
            &ImpulseSettings::default(),
            &mut |_| {},
        )
        .unwrap();
        let d = r.damping.expect("the first bending pole is fitted");
        let omega = 2.0 * PI * r.first_bending.unwrap().eigen_hz;
        let model = damped_builtin(zeta).damping.unwrap();
        let expected = model.alpha / (2.0 * omega) + model.beta * omega / 2.0;
        assert!(
            (d.modal_ratio - expected).abs() < 1e-12,
            "modal ratio {} vs α/(2ω) + βω/2 = {expected}",
            d.modal_ratio
        );
        let err = (d.identified_ratio - expected - d.numerical_ratio) / expected;
        println!(
            "ζ = {zeta}: identified {} vs {expected} ({err:+.2e})",
            d.identified_ratio
        );
        assert!(
            err.abs() < 0.01,
            "ζ = {zeta}: identified {} vs model {expected} ({err:e})",
            d.identified_ratio
        );
        assert!(d.numerical_ratio.abs() < 1e-6 * expected + 1e-8);
        let doc = ImpulseOutput::new("damped", &r, None);
        let damping = doc.damping.expect("the document carries the damping check");
        assert_eq!(damping.identified_ratio, d.identified_ratio);
        assert_eq!(damping.modal_ratio, d.modal_ratio);
        assert!(impulse_table("damped", &r, None).contains("first bending damping ratio"));
    }
}

/// A pre-stressed mode is damped by the reference's stiffness: the run's
/// C = αM + βK₀ gives the mode of shape φ the ratio φᵀCφ/(2ω). A pinned
/// column on a slider under half its Euler load keeps its unloaded shapes
/// (sines), so φᵀK₀φ = ω₀² (the unloaded mode's) while ω² = ω₀²/2: with β
/// alone, ζ = βω₀²/(2ω) = βω, twice the βω/2 that was printed (the
/// second outside-eyes trial of this round: a guyed mast's check printed
/// 0.74247 % against the 0.76173 % its run damps, a "+2.60e-2 mismatch"
/// that was the tool's own). The record's fitted ratio agrees with it.
#[test]
fn a_prestressed_modes_damping_is_the_reference_stiffness() {
    let (l, h, w, e, rho) = (0.5f64, 2e-3f64, 0.01f64, 210e9f64, 7850.0f64);
    let ei = e * w * h.powi(3) / 12.0;
    let p_e = PI * PI * ei / (l * l);
    let beta = 2e-4;
    let json = serde_json::json!({
        "name": "column",
        "beams": [{"id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": l,
                   "elements": 8, "section": {"height": h, "width": w},
                   "material": {"young": e, "density": rho}}],
        "joints": [
            {"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}},
            {"type": "slider", "a": {"ground": [l, 0.0]}, "b": {"beam": "b", "s": l}, "axis": [1.0, 0.0]}
        ],
        "damping": {"alpha": 0.0, "beta": beta},
        "loads": [
            {"id": "squeeze", "at": {"beam": "b", "s": l}, "force": [-0.5 * p_e, 0.0]},
            {"id": "hammer", "at": {"beam": "b", "s": 0.3 * l}, "force": [0.0, 0.01],
             "time": {"half_sine": {"duration": 1e-3}}}
        ],
        "sensors": [{"id": "mid", "at": {"beam": "b", "s": 0.45 * l}, "quantity": "velocity",
                     "frame": "global", "direction": [0.0, 1.0]}]
    });
    let model = Model::from_json(&json.to_string(), ancf_modal::error::Source::BuiltIn).unwrap();
    let settings = ImpulseSettings {
        transient: TransientSettings {
            end_time: 2.0,
            step: 1e-4,
            ..TransientSettings::default()
        },
        sample_rate: Some(2048.0),
        ..ImpulseSettings::default()
    };
    let r = run_impulse(&model, &settings, &mut |_| {}).unwrap();
    let d = r.damping.expect("the first bending pole is fitted");
    // ω from the record's own eigen-solve at the equilibrium; ω₀² = 2ω².
    let omega = 2.0 * PI * r.first_bending.unwrap().eigen_hz;
    let expected = beta * 2.0 * omega * omega / (2.0 * omega);
    assert!(
        (d.modal_ratio / expected - 1.0).abs() < 1e-3,
        "model ratio {} against βω₀²/(2ω) = {expected} (βω/2 = {})",
        d.modal_ratio,
        beta * omega / 2.0
    );
    let err = d.relative_error().expect("a damped model");
    assert!(
        err.abs() < 0.01,
        "fitted {} ({err:+.2e})",
        d.identified_ratio
    );
}
