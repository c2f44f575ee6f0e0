//! `frf` over a wide band where one mode's peak stands orders above the
//! others (the second outside-eyes trial of this round: a guyed mast,
//! sampled at 500 Hz, its automatic band 0–126 Hz). The whole band's
//! refinement bent the weaker modes' poles to absorb the strong peaks'
//! misfit (36.73 Hz: ζ 1.48 % for the model's 1.19 %), and could not add
//! the two strongest modes, 1.125 and 5.22 Hz, which were listed as
//! unfitted. Each pole is now refined again in a zoom band around it.
//!
//! Independent source: the model's pre-stressed eigenvalue problem
//! (`modal --prestress`, its Rayleigh ratio φᵀ(αM + βK₀)φ/(2ω) per mode)
//! with the integrator's period elongation (ωΔt)²/12.

mod common;

use serde_json::{json, Value};
use std::f64::consts::PI;

/// The trial's mast: 10 m steel, 60 × 60 mm, pinned at its base, two
/// guys preloaded to 5 kN, a 20 kg antenna on top, struck at 4 m and
/// measured (velocity, horizontal) at 7 m.
fn mast() -> Value {
    json!({
        "name": "mast",
        "beams": [{"id": "mast", "start": [0, 0], "angle_deg": 90, "length": 10.0,
                   "elements": 10, "section": {"height": 0.06, "width": 0.06},
                   "material": {"young": 210e9, "density": 7850}}],
        "point_masses": [{"id": "antenna", "mass": 20.0, "position": [0, 10.0]}],
        "joints": [
            {"id": "base", "type": "pin", "a": {"ground": [0, 0]}, "b": {"beam": "mast", "s": 0}},
            {"id": "mount", "type": "pin", "a": {"beam": "mast", "s": 10.0}, "b": {"body": "antenna"}}
        ],
        "springs": [
            {"id": "guyL", "a": {"beam": "mast", "s": 10.0}, "b": {"ground": [-7.5, 0]},
             "stiffness": 450000.0, "preload": 5000.0},
            {"id": "guyR", "a": {"beam": "mast", "s": 10.0}, "b": {"ground": [7.5, 0]},
             "stiffness": 450000.0, "preload": 5000.0}
        ],
        "loads": [{"id": "hammer", "at": {"beam": "mast", "s": 4.0}, "force": [200.0, 0],
                   "time": {"half_sine": {"duration": 0.01}}}],
        "sensors": [{"id": "s7", "at": {"beam": "mast", "s": 7.0}, "quantity": "velocity",
                     "frame": "global", "direction": [1, 0]}],
        "damping": {"alpha": 0.1, "beta": 1e-4}
    })
}

const STEP: f64 = 2e-4;

#[test]
fn every_mode_of_a_wide_band_is_found_with_its_damping() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mast.json");
    std::fs::write(&path, mast().to_string()).unwrap();
    let modal: Value = serde_json::from_slice(&common::run_ok([
        "modal".as_ref(),
        path.as_os_str(),
        "--prestress".as_ref(),
        "--json".as_ref(),
    ]))
    .unwrap();
    let doc = common::impulse_then_frf(
        &mast(),
        &["--end-time", "10", "--step", "2e-4", "--sample-rate", "500"],
    );
    let band_end = doc["band_hz"][1].as_f64().unwrap();
    assert!(band_end > 120.0, "band {}", doc["band_hz"]);
    let peaks = doc["peaks"].as_array().unwrap();
    let mut checked = 0;
    for m in modal["modes"].as_array().unwrap() {
        let f0 = m["frequency_hz"].as_f64().unwrap();
        // The horizontal sensor does not see the axial mode.
        if f0 >= band_end || m["kind"] == "axial" {
            continue;
        }
        let wdt = 2.0 * PI * f0 * STEP;
        let f = f0 * (1.0 - wdt * wdt / 12.0);
        let zeta = m["damping_ratio"].as_f64().unwrap();
        let p = peaks
            .iter()
            .find(|p| (p["frequency_hz"].as_f64().unwrap() / f - 1.0).abs() < 1e-3)
            .unwrap_or_else(|| panic!("mode at {f} Hz not found in {peaks:#?}"));
        let (got_f, got_z) = (
            p["frequency_hz"].as_f64().unwrap(),
            p["damping_ratio"].as_f64().unwrap(),
        );
        println!("{f:.4} Hz ζ {zeta:.5}: {got_f:.4} Hz ζ {got_z:.5}");
        // The tolerances for `impulse` records: f 1e-4, ζ 2 %.
        assert!((got_f / f - 1.0).abs() < 1e-4, "{f} Hz: found {got_f}");
        assert!(
            (got_z / zeta - 1.0).abs() < 0.02,
            "{f} Hz: ζ {got_z} against {zeta}"
        );
        checked += 1;
    }
    assert_eq!(checked, 10);
    assert_eq!(peaks.len(), 10, "{peaks:#?}");
}

/// The third trial's heavy cantilever (200 × 20 × 2 mm steel, a 50 g tip
/// mass on a pin, a light 40 × 5 × 0.3 mm strip welded on beyond it),
/// struck and measured at its tip.
fn heavy_light() -> Value {
    json!({
        "name": "heavy_light",
        "beams": [
            {"id": "main", "start": [0, 0], "angle_deg": 0, "length": 0.2, "elements": 10,
             "section": {"height": 0.002, "width": 0.02},
             "material": {"young": 210e9, "density": 7850}},
            {"id": "tail", "start": [0.2, 0], "angle_deg": 0, "length": 0.04, "elements": 4,
             "section": {"height": 0.0003, "width": 0.005},
             "material": {"young": 210e9, "density": 7850}}
        ],
        "point_masses": [{"id": "tipmass", "mass": 0.05, "position": [0.2, 0]}],
        "joints": [
            {"type": "weld", "a": {"ground": [0, 0]}, "b": {"beam": "main", "s": 0}},
            {"type": "weld", "a": {"beam": "main", "s": 0.2}, "b": {"beam": "tail", "s": 0}},
            {"type": "pin", "a": {"beam": "main", "s": 0.2}, "b": {"body": "tipmass"}}
        ],
        "damping": {"alpha": 0.1, "beta": 2e-5},
        "loads": [{"id": "hammer", "at": {"beam": "main", "s": 0.2}, "frame": "global",
                   "force": [0, 5], "time": {"half_sine": {"duration": 2e-4}}}],
        "sensors": [{"id": "tipv", "at": {"beam": "main", "s": 0.2}, "quantity": "velocity",
                     "frame": "global", "direction": [0, 1]}]
    })
}

/// A mode near a combination of two others is no combination tone unless
/// it decays as one: the 155.9 Hz mode of this record, decaying at
/// 9.7 1/s, sits 0.3 Hz from 196.5 − 2 × 20.1 Hz, whose cubic term decays
/// at 15.7 1/s, and was set apart as a harmonic (2e37dc1).
#[test]
fn a_mode_beside_a_cubic_combination_is_a_mode() {
    let model = heavy_light();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.json");
    std::fs::write(&path, model.to_string()).unwrap();
    let modal: Value = serde_json::from_slice(&common::run_ok([
        "modal".as_ref(),
        path.as_os_str(),
        "--json".as_ref(),
    ]))
    .unwrap();
    let docs = common::impulse_then_frfs(
        &model,
        &[
            "--end-time",
            "2",
            "--step",
            "1e-5",
            "--spectral-radius",
            "1",
            "--sample-rate",
            "10240",
        ],
        &[&[], &["--band", "100:1500"], &["--band", "400:3000"]],
    );
    let (doc, zoomed, above) = (&docs[0], &docs[1], &docs[2]);
    let said = |d: &Value| {
        d["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| w.as_str().unwrap().contains("outside the fit band"))
    };
    // The 20.1 Hz mode, 655 × the band's largest |H| and still ringing at
    // the record's end, left out of a band of the user's: its tail enters
    // through the residual terms alone (the trial: 155.9 Hz lost, ζ of
    // 196.5 Hz −2.5 %), which is said; the automatic band holds it.
    assert!(said(zoomed), "{}", zoomed["warnings"]);
    assert!(!said(doc), "{}", doc["warnings"]);
    // Where such a band finds nothing, that mode is the cause said, not
    // the records' line spacing (0.5 Hz against modes 46–200 Hz wide).
    assert!(said(above), "{}", above["warnings"]);
    let blamed = above["warnings"].as_array().unwrap().iter();
    assert!(
        !blamed
            .into_iter()
            .any(|w| w.as_str().unwrap().contains("lines are")),
        "{}",
        above["warnings"]
    );
    let peaks = doc["peaks"].as_array().unwrap();
    // Modes 1–4 of the model (20.1, 155.9, 196.5, 607.3 Hz); 2πfΔt ≤ 0.04.
    for m in &modal["modes"].as_array().unwrap()[..4] {
        let (f, zeta) = (
            m["frequency_hz"].as_f64().unwrap(),
            m["damping_ratio"].as_f64().unwrap(),
        );
        let p = peaks
            .iter()
            .find(|p| (p["frequency_hz"].as_f64().unwrap() / f - 1.0).abs() < 1e-3)
            .unwrap_or_else(|| panic!("mode at {f} Hz not reported: {peaks:#?}"));
        let got = p["damping_ratio"].as_f64().unwrap();
        assert!(
            (got / zeta - 1.0).abs() < 0.02,
            "{f} Hz: ζ {got} against {zeta}"
        );
    }
}
