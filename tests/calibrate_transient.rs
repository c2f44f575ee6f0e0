//! Calibration to a transient (`calibrate --quantity time_to_distance_s`):
//! the switch-off of the built-in assembly with the spring's housing end
//! moved by a known amount is simulated (fixed step); calibrating that
//! coordinate back from the unmoved model to the simulated time recovers
//! the known position. Independent source: the known design (a round trip
//! through the simulation, the fit never sees the value).

use ancf_modal::analysis::calibrate::transient::{
    calibrate_transient, TransientFit, TransientParameter, TransientTarget,
};
use ancf_modal::analysis::switch_off::{run_switch_off, SwitchOffSettings};
use ancf_modal::Model;

#[test]
fn time_fit_recovers_the_spring_housing() {
    let base = Model::switch_off_builtin();
    let y0 = base.springs[0].a.ground.unwrap()[1];
    let truth = y0 + 0.4e-3;
    let mut moved = base.to_model();
    moved.springs[0].a.ground = Some([moved.springs[0].a.ground.unwrap()[0], truth]);
    let moved = moved.validated().unwrap();
    let settings = SwitchOffSettings {
        fixed_step: true,
        sample_rate: 0.0,
        ..SwitchOffSettings::default()
    };
    let t = run_switch_off(&moved, &settings)
        .unwrap()
        .flexible
        .time_to_distance_s
        .unwrap();
    let fit = TransientFit {
        parameters: vec![TransientParameter {
            name: String::from("springs[helical_spring].a.ground[1]"),
            bounds: Some((y0 - 1e-3, y0 + 1e-3)),
        }],
        target: TransientTarget::TimeToDistance {
            seconds: t,
            source: String::from("simulated"),
        },
        balance: None,
        experiment: SwitchOffSettings::default(),
        tolerance_s: 1e-12 * t,
        max_evaluations: 40,
    };
    let r = calibrate_transient(&base, &fit).unwrap();
    let fitted = r.parameters[0].fitted;
    assert!(
        ((fitted - truth) / truth).abs() < 1e-6,
        "fitted {fitted:e}, truth {truth:e}, {} runs",
        r.history.len()
    );
    // What was fitted is said: name, target, achieved.
    assert_eq!(r.calibrated.len(), 1);
    assert!(r.calibrated[0].target.contains("time_to_distance_s"));
}
