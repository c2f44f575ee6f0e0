//! The impulse experiment's list of spectrum peaks, for any scale: a
//! clamped steel cantilever from 1 mm (kHz … MHz) to 3 m (a few Hz), struck
//! at its tip by a short half-sine, with the time step, the record and the
//! pulse scaled to its first bending period. Whatever the scale:
//! - every listed peak lies between half the lowest elastic
//!   eigenfrequency and Nyquist (a pole inside its band);
//! - the first bending mode is listed, within a bin of its
//!   Euler–Bernoulli frequency (1.8751²/(2πL²)·√(EI/ρA), computed here).
//!
//! A fixed lower limit of 100 Hz once hid a 2 Hz diving board's peak and
//! listed the integrator's noise above it instead.

use ancf_modal::analysis::impulse::{run_impulse, ImpulseSettings};
use ancf_modal::analysis::transient::dispersion::GenAlpha;
use ancf_modal::analysis::ModeKind;
use ancf_modal::error::Source;
use ancf_modal::Model;
use proptest::prelude::*;

mod common;
use std::f64::consts::PI;

/// Euler–Bernoulli first bending frequency of a clamped-free beam [Hz].
fn first_bending_hz(length: f64, height: f64, young: f64, density: f64) -> f64 {
    let beta = 1.875_104_068_711_961;
    beta * beta / (2.0 * PI * length * length) * (young * height * height / (12.0 * density)).sqrt()
}

fn cantilever(length: f64, height: f64, pulse: f64) -> String {
    format!(
        r#"{{"name": "scaled cantilever",
  "beams": [{{"id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": {length:e}, "elements": 8,
     "section": {{"height": {height:e}, "width": {height:e}}},
     "material": {{"young": 2.1e11, "density": 7850.0}}}}],
  "joints": [{{"id": "clamp", "type": "weld", "a": {{"ground": [0.0, 0.0]}}, "b": {{"beam": "b", "s": 0.0}}}}],
  "loads": [{{"id": "hit", "at": {{"beam": "b", "s": {length:e}}}, "frame": "global",
     "force": [0.0, {force:e}], "time": {{"half_sine": {{"duration": {pulse:e}}}}}}}],
  "sensors": [{{"id": "tip", "at": {{"beam": "b", "s": {length:e}}}, "quantity": "velocity",
     "frame": "global", "direction": [0.0, 1.0]}}]}}"#,
        force = 1e-3 * 2.1e11 * height.powi(4) / length.powi(2),
    )
}

proptest! {
    #![proptest_config(common::fixed_cases(8, "IMPULSE_PEAKS_SEED", 35))]

    #[test]
    fn the_first_bending_peak_is_listed_at_any_scale(
        log_length in -3.0f64..0.5,
        slenderness in 30.0f64..100.0,
    ) {
        let length = 10f64.powf(log_length);
        let height = length / slenderness;
        let f1 = first_bending_hz(length, height, 2.1e11, 7850.0);
        let period = 1.0 / f1;
        let model = Model::from_json(&cantilever(length, height, 0.05 * period), Source::BuiltIn).unwrap();
        let mut settings = ImpulseSettings::default();
        settings.transient.step = period / 200.0;
        settings.transient.end_time = 40.0 * period;
        settings.sample_rate = None;
        let r = run_impulse(&model, &settings, &mut |_| {}).unwrap();
        let lowest = r.modal.modes.iter().filter(|m| !m.kind.is_zero())
            .map(|m| m.frequency_hz).fold(f64::INFINITY, f64::min);
        let nyquist = 0.5 * r.sample_rate_hz;
        prop_assert!(!r.peaks.is_empty());
        for p in &r.peaks {
            prop_assert!(p.frequency_hz >= 0.5 * lowest && p.frequency_hz <= nyquist,
                "peak {} Hz outside [{}, {}]", p.frequency_hz, 0.5 * lowest, nyquist);
        }
        let bin = r.spectrum.resolution_hz;
        prop_assert!(r.peaks.iter().any(|p| (p.frequency_hz - f1).abs() < bin + 1e-3 * f1),
            "no peak near f1 = {f1} Hz (bin {bin} Hz): {:?}",
            r.peaks.iter().map(|p| p.frequency_hz).collect::<Vec<_>>());
    }
}

/// A pinned string of 0.65 m, 0.4 mm square steel, tensioned by 80 N at
/// its sliding end and plucked at a fifth of its length, where its
/// velocity is read: a spectrum with dozens of modes.
fn plucked_string() -> String {
    let l = 0.65;
    serde_json::json!({
        "name": "plucked_string",
        "beams": [{"id": "s", "start": [0, 0], "angle_deg": 0, "length": l, "elements": 40,
                   "section": {"height": 4e-4, "width": 4e-4},
                   "material": {"young": 2e11, "density": 7850}}],
        "joints": [
            {"id": "nut", "type": "pin", "a": {"ground": [0, 0]}, "b": {"beam": "s", "s": 0}},
            {"id": "bridge", "type": "slider", "a": {"ground": [l, 0]},
             "b": {"beam": "s", "s": l}, "axis": [1, 0]}],
        "loads": [
            {"id": "T", "at": {"beam": "s", "s": l}, "force": [80, 0]},
            {"id": "pluck", "at": {"beam": "s", "s": l / 5.0}, "force": [0, 0.5],
             "time": {"half_sine": {"duration": 2e-4}}}],
        "sensors": [{"id": "p", "at": {"beam": "s", "s": l / 5.0}, "quantity": "velocity",
                     "frame": "global", "direction": [0, 1]}]
    })
    .to_string()
}

/// The peak list is the spectrum's own peaks, and all of them: every
/// bending mode the sensor sees (mode n of a pinned string vanishes at a
/// fifth of its length when 5 divides n) up to 5 kHz is listed within a
/// bin of its eigenfrequency, and every listed peak is an eigenfrequency
/// where the integrator puts it (no window side lobe, no harmonic). The list once kept the 16
/// strongest, and a velocity sensor's weak first mode (194 Hz) went
/// behind the stronger high ones.
#[test]
fn the_peak_list_holds_every_mode_the_sensor_sees() {
    let model = Model::from_json(&plucked_string(), Source::BuiltIn).unwrap();
    let mut settings = ImpulseSettings::default();
    settings.transient.end_time = 0.2;
    let r = run_impulse(&model, &settings, &mut |_| {}).unwrap();
    let bin = r.spectrum.resolution_hz;
    let bending: Vec<f64> = r
        .modal
        .modes
        .iter()
        .filter(|m| m.kind == ModeKind::Bending)
        .map(|m| m.frequency_hz)
        .collect();
    let listed: Vec<f64> = r.peaks.iter().map(|p| p.frequency_hz).collect();
    let mut seen = 0;
    for (i, &f) in bending.iter().enumerate().filter(|&(_, &f)| f < 5e3) {
        if (i + 1) % 5 == 0 {
            continue;
        }
        seen += 1;
        assert!(
            listed.iter().any(|p| (p - f).abs() <= bin),
            "mode {} at {f:.3} Hz is not listed: {listed:?}",
            i + 1
        );
    }
    assert!(seen > 16, "{seen} modes seen");
    // Where the integrator puts each mode: its period error moves the
    // 12 kHz modes by more than a bin.
    let scheme = GenAlpha::from_spectral_radius(settings.transient.spectral_radius).unwrap();
    let h = settings.transient.step;
    let simulated: Vec<f64> = r
        .modal
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero() && m.frequency_hz < 0.5 / h)
        .map(|m| {
            scheme
                .numerical_frequency(2.0 * PI * m.frequency_hz, h)
                .unwrap()
                .omega
                / (2.0 * PI)
        })
        .collect();
    for p in &listed {
        assert!(
            simulated.iter().any(|f| (p - f).abs() <= bin),
            "peak {p:.3} Hz is no eigenfrequency"
        );
    }
}
