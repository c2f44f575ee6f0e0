//! The integrator's own dissipation is a term of the energy balance,
//! computed, not lumped into the error (issue 35).
//!
//! Layers:
//! - a conservation law: with every term booked (load work, the model's
//!   damping, the integrator's dissipation), the balance of a beam with
//!   no energy sink but the integrator closes over 1e5 steps, at any
//!   spectral radius, while the dissipation booked spans orders;
//! - an analytic reference: at a spectral radius of 1 (the trapezoidal
//!   rule) the integrator removes nothing;
//! - the dispersion analysis: on a linear oscillator the energy booked as
//!   the integrator's is the free vibration's decay ρ^(2N) its principal
//!   eigenvalue predicts;
//! - generated damped assemblies: the balance closes for any spectral
//!   radius, damping and step (the terms are the scheme's own discrete
//!   work, exact for linear forces).

use ancf_modal::analysis::simulate::EnergyBalance;
use ancf_modal::analysis::transient::dispersion::GenAlpha;
use ancf_modal::commands::transient::{run, TransientRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use proptest::prelude::*;
use serde_json::{json, Value};

fn input(model: &Value) -> ModelInput {
    ModelInput::parse(&model.to_string(), Source::BuiltIn).unwrap()
}

/// The run's energy balance and warnings.
fn books(model: &Value, end_time: f64, step: f64, rho: f64) -> (EnergyBalance, Vec<String>) {
    let request = TransientRequest {
        end_time,
        step,
        spectral_radius: rho,
        ..TransientRequest::default()
    };
    let r = run(&input(model), &request).unwrap();
    (r.simulation.energy, r.document.warnings.clone())
}

/// The paper's blade clamped (25 mm, 8 elements), struck at its tip by
/// `force` [N] as a half-sine of `duration` [s]; no damping, no contact.
fn struck_cantilever(force: f64, duration: f64) -> Value {
    json!({
        "name": "struck_cantilever",
        "beams": [{"id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.025,
                   "elements": 8, "section": {"height": 1.1e-3, "width": 5.2e-3},
                   "material": {"young": 127e9, "density": 8940.0}}],
        "joints": [{"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]},
                    "b": {"beam": "blade", "s": 0.0}}],
        "loads": [{"id": "tap", "at": {"beam": "blade", "s": 0.025}, "force": [0.0, force],
                   "time": {"half_sine": {"duration": duration}}}],
        "sensors": [{"id": "tip", "at": {"beam": "blade", "s": 0.025},
                     "quantity": "displacement", "frame": "global", "direction": [0.0, 1.0]}]
    })
}

#[test]
fn a_conservative_beam_over_1e5_steps_closes_its_balance_once_the_integrators_share_is_booked() {
    let beam = struck_cantilever(0.1, 1e-4);
    let (step, end) = (1e-6, 0.1);
    let mut booked = Vec::new();
    for rho in [1.0, 0.9, 0.5] {
        let (e, warnings) = books(&beam, end, step, rho);
        let put_in = e.put_in_j();
        // Nothing is stored at the start: what went in is the tap's work.
        assert!(e.load_work_j > 0.0 && (put_in - e.load_work_j).abs() <= 1e-15 * put_in);
        assert!(
            e.error_j.abs() <= 1e-6 * put_in,
            "ρ∞ = {rho}: error {:.3e} of {put_in:.4e} J, integrator {:.3e} J",
            e.error_j,
            e.numerical_dissipation_j
        );
        assert_eq!(e.damping_dissipation_j, 0.0);
        assert!(warnings.iter().all(|w| !w.contains("energy balance")));
        booked.push(e.numerical_dissipation_j / put_in);
    }
    // The trapezoidal rule removes nothing; below a spectral radius of 1
    // the integrator removes more the lower it is, and at 0.5 a
    // thousand times what the balance would tolerate as an error.
    assert!(booked[0].abs() <= 1e-9, "{booked:?}");
    assert!(booked[1] > 0.0 && booked[2] > booked[1], "{booked:?}");
    assert!(booked[2] > 1e-3, "{booked:?}");
}

/// A 10 g point mass on a spring of `stiffness` [N/m] along x, kicked
/// along the spring by a 1 N half-sine of 1 ms: a linear oscillator.
fn kicked_oscillator(stiffness: f64) -> Value {
    json!({
        "name": "oscillator",
        "point_masses": [{"id": "m", "mass": 0.01, "position": [0.0, 0.0]}],
        "springs": [{"id": "k", "a": {"ground": [-0.05, 0.0]}, "b": {"body": "m"},
                     "stiffness": stiffness, "free_length": 0.05}],
        "loads": [{"id": "kick", "at": {"body": "m"}, "force": [1.0, 0.0],
                   "time": {"half_sine": {"duration": 1e-3}}}],
        "sensors": [{"id": "x", "at": {"body": "m"}, "quantity": "displacement",
                     "frame": "global", "direction": [1.0, 0.0]}]
    })
}

#[test]
fn the_integrators_share_is_the_decay_its_dispersion_predicts() {
    // T + U of a discrete oscillation varies within a cycle, so the two
    // states compared are a whole number of the integrator's own
    // half-periods apart: the spring is tuned so that the simulation
    // oscillates at exactly 20 steps a half-period.
    let (h, mass, half_period_steps) = (5e-5, 0.01, 20.0);
    let (settle, free) = (420.0, 19_600.0);
    for rho in [0.0, 0.5] {
        let scheme = GenAlpha::from_spectral_radius(rho).unwrap();
        let omega = scheme
            .true_frequency_from_observed(std::f64::consts::PI / (half_period_steps * h), h)
            .unwrap();
        let model = kicked_oscillator(mass * omega * omega);
        // The kick's 20 steps and 400 more (the spurious root dies out),
        // then 980 half-periods of free vibration.
        let (settled, _) = books(&model, settle * h, h, rho);
        let (long, _) = books(&model, (settle + free) * h, h, rho);
        let stored = |e: &EnergyBalance| e.end.kinetic_j + e.end.spring_j;
        let booked = long.numerical_dissipation_j - settled.numerical_dissipation_j;
        // Free vibration: the amplitude shrinks by the principal
        // eigenvalue's modulus every step, the energy by its square.
        let mode = scheme.numerical_frequency(omega, h).unwrap();
        let predicted = stored(&settled) * (1.0 - mode.rho.powf(2.0 * free));
        assert!(
            (booked - predicted).abs() <= 1e-9 * predicted,
            "ρ∞ = {rho}: booked {booked:.9e} J, the dispersion's {predicted:.9e} J"
        );
        // And the balance closes to round-off: the forces are linear.
        assert!(long.error_j.abs() <= 1e-9 * long.put_in_j(), "{long:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Any spectral radius, Rayleigh damping, a damped spring and a tip
    /// mass: with every term booked the balance closes (the nonlinearity
    /// of a tap's micrometres leaves ~1e-9).
    #[test]
    fn the_balance_of_damped_assemblies_closes_at_any_spectral_radius(
        rho in 0.0f64..=1.0,
        alpha in 0.0f64..200.0,
        beta in 0.0f64..2e-6,
        dashpot in 0.0f64..0.5,
        tip_mass in 1e-4f64..2e-3,
        pulse_steps in 1.0f64..50.0,
        step in 2e-7f64..4e-6,
    ) {
        let mut model = struck_cantilever(0.1, pulse_steps * step);
        model["damping"] = json!({"alpha": alpha, "beta": beta});
        model["point_masses"] = json!([{"id": "tip", "mass": tip_mass, "position": [0.025, 0.0]}]);
        model["joints"].as_array_mut().unwrap().push(json!(
            {"id": "carry", "type": "pin", "a": {"body": "tip"}, "b": {"beam": "blade", "s": 0.025}}));
        model["springs"] = json!([{"id": "stay", "a": {"beam": "blade", "s": 0.0125},
            "b": {"ground": [0.0125, -0.01]}, "stiffness": 500.0, "free_length": 0.01,
            "damping": dashpot}]);
        let (e, warnings) = books(&model, 2000.0 * step, step, rho);
        let put_in = e.put_in_j();
        prop_assert!(e.error_j.abs() <= 1e-6 * put_in,
            "error {:.3e} of {put_in:.4e} J (integrator {:.3e}, damping {:.3e})",
            e.error_j, e.numerical_dissipation_j, e.damping_dissipation_j);
        prop_assert!(e.numerical_dissipation_j >= -1e-9 * put_in);
        prop_assert!(e.damping_dissipation_j >= 0.0);
        prop_assert!(!warnings.iter().any(|w| w.contains("energy balance")));
    }
}
