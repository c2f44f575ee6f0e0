//! The sampled hammer record of `impulse` against the blow it records.
//!
//! The force record is the half-sine load behind the anti-aliasing
//! low-pass, which has unit gain at 0 Hz: the record's Σ F Δt must equal the
//! pulse's impulse 2 F₀ T/π (the built-in model: 4 N over 0.1 ms) whatever
//! the sample rate, to 1e-3: the steps' own quadrature of the half-sine
//! ((πh/T)²/12 ≈ 8e-5 at h = 1 µs) and the filter's finite stop band leave
//! 3e-4 at 10,240 Hz. Cut at t = 0, the filter's ringing ahead of the blow
//! took 5.7 % off it at 51.2 kHz; the record now starts a pre-trigger ahead
//! of the blow, at rest.

use ancf_modal::analysis::impulse::{run_impulse, ImpulseSettings};
use ancf_modal::Model;

#[test]
fn force_record_holds_the_whole_impulse_of_the_blow() {
    let model = Model::builtin();
    let (f0, duration) = (4.0, 1e-4);
    let impulse = 2.0 * f0 * duration / std::f64::consts::PI;
    for rate in [51_200.0, 20_000.0, 10_240.0] {
        let mut settings = ImpulseSettings::default();
        settings.transient.end_time = 5e-3;
        settings.sample_rate = Some(rate);
        let r = run_impulse(&model, &settings, &mut |_| {}).unwrap();
        let dt = r.time[1] - r.time[0];
        assert!((dt * rate - 1.0).abs() < 1e-9);
        // Before the blow the record is at rest: the first sample is that
        // far from the low-pass's reach, so it holds nothing of it.
        assert!(r.time[0] < 0.0, "a pre-trigger at {rate} Hz");
        assert!(
            r.force[0].abs() < 1e-6 * f0,
            "force at rest: {}",
            r.force[0]
        );
        // And the response: nothing arrives before the blow beyond the
        // filter's reach ahead of it (its stated half-length), on either
        // channel.
        let reach = ancf_modal::signal::resample::AntiAlias::default().half_length(rate);
        let peak = r.signal.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, &t) in r.time.iter().enumerate().filter(|&(_, &t)| t <= -reach) {
            assert!(
                r.signal[k].abs() <= 1e-9 * peak && r.force[k].abs() < 1e-6 * f0,
                "{rate} Hz: response {} at t = {t:e} s, ahead of the filter's reach {reach:e} s",
                r.signal[k]
            );
        }
        assert!(r.time[0] <= -reach, "the record starts beyond the reach");
        let sum: f64 = r.force.iter().sum::<f64>() * dt;
        assert!(
            (sum - impulse).abs() <= 1e-3 * impulse,
            "{rate} Hz: Σ F Δt = {sum:e} N s vs 2 F₀T/π = {impulse:e} N s"
        );
    }
}

mod common;

proptest::proptest! {
    #![proptest_config(common::fixed_cases(8, "IMPULSE_RECORD_SEED", 35))]

    /// Pulses from half a sample to twenty samples long: the record's
    /// Σ F Δt is the impulse the integrator applied, the steps' own
    /// quadrature h Σ F(t_k) of the half-sine, to 1e-3 (the low-pass has
    /// unit gain at 0 Hz and the record holds the whole blow).
    #[test]
    fn force_record_integrates_to_the_applied_impulse(
        samples in 0.5f64..20.0,
        rate in proptest::sample::select(vec![10_240.0, 25_600.0, 51_200.0]),
    ) {
        let model = Model::builtin();
        let f0 = 4.0;
        let h = 1e-6;
        let duration = samples / rate;
        // The record runs well past the low-pass's reach (29 samples each
        // side of the blow), so its ringing after the pulse is inside.
        let mut settings = ImpulseSettings::default();
        settings.transient.end_time = 0.02;
        settings.sample_rate = Some(rate);
        settings.duration = Some(duration);
        let r = run_impulse(&model, &settings, &mut |_| {}).unwrap();
        let dt = r.time[1] - r.time[0];
        let recorded: f64 = r.force.iter().sum::<f64>() * dt;
        let applied: f64 = (0..)
            .map(|k| k as f64 * h)
            .take_while(|&t| t <= duration)
            .map(|t| f0 * (std::f64::consts::PI * t / duration).sin())
            .sum::<f64>()
            * h;
        proptest::prop_assert!(
            (recorded - applied).abs() <= 1e-3 * applied,
            "{} samples at {} Hz: Σ F Δt = {:e} N s vs h Σ F(t_k) = {:e} N s",
            samples, rate, recorded, applied
        );
    }
}
