//! No silent loss in `frf` (issue 23): one hammer hit of a two-mode
//! structure, 180 Hz at ζ = 1 % and 1150 Hz at ζ = 2 %, sampled at
//! 10.24 kHz for 4 s, a half-sine force of 0.5 ms, Gaussian noise of 0.05 %
//! of the force peak on the force and 0.5 % of the response peak on the
//! response (fixed seed). The generator is tests/measured_support (impulse
//! invariance: its poles are exactly the continuous ones).
//!
//! With one hit the coherence is identically 1, so the automatic band must
//! end where the force spectrum has fallen 20 dB or where the response
//! reaches the noise floor of the record's quiet tail. Both modes must come
//! out within 5e-4 in frequency and 5 % in damping; a mode the band leaves
//! out is listed in `rejected` with its reason.

mod measured_support;

use ancf_modal::measured::analysis::{analyse, AnalysisSettings, BandEnd};
use ancf_modal::measured::{Measurement, TimeRecord};
use ancf_modal::signal::fit::RejectReason;
use measured_support::{peak, pulse, respond, Noise, TestMode};
use std::path::PathBuf;

const FS: f64 = 10_240.0;
/// 4 s.
const N: usize = 40_960;

fn modes() -> [TestMode; 2] {
    [
        TestMode {
            f: 180.0,
            zeta: 0.01,
            inv_mass: 1.0,
        },
        TestMode {
            f: 1_150.0,
            zeta: 0.02,
            inv_mass: 5.0,
        },
    ]
}

/// One hit: a 10 N half-sine of 0.5 ms at 10 ms, the modes' displacement,
/// noise of 0.05 % of the force peak and 0.5 % of the response peak.
fn hit(modes: &[TestMode], seed: u64) -> TimeRecord {
    let force = pulse(N, FS, 10.0, 5e-4, 0.01);
    let response = respond(modes, FS, &force);
    let (fn_, rn) = (5e-4 * peak(&force), 5e-3 * peak(&response));
    let mut noise = Noise::new(seed);
    TimeRecord {
        file: PathBuf::from("hit.csv"),
        sample_rate_hz: FS,
        force: force.iter().map(|v| v + fn_ * noise.gauss()).collect(),
        response: response.iter().map(|v| v + rn * noise.gauss()).collect(),
        force_label: "force".into(),
        response_label: "response".into(),
        lines: (2..N + 2).collect(),
    }
}

#[test]
fn one_hit_of_two_modes_finds_both() {
    let truth = modes();
    let a = analyse(
        vec![Measurement::Time(hit(&truth, 11))],
        AnalysisSettings::default(),
    )
    .unwrap();
    eprintln!(
        "band {:.1}–{:.1} Hz, ended by {:?}; rejected {:?}",
        a.band.0, a.band.1, a.band_end, a.rejected
    );
    assert!(
        matches!(a.band_end, BandEnd::ForceDrop | BandEnd::NoiseFloor),
        "the automatic band ends at the force drop or the noise floor: {:?}",
        a.band_end
    );
    assert_eq!(a.fit.modes.len(), 2, "both modes: {:?}", a.fit.modes);
    for (m, fitted) in truth.iter().zip(&a.fit.modes) {
        let ef = (fitted.frequency_hz - m.f).abs() / m.f;
        let ez = (fitted.damping_ratio - m.zeta).abs() / m.zeta;
        eprintln!(
            "{} Hz: f {:.4} ({ef:.2e}), ζ {:.5} ({ez:.2e})",
            m.f, fitted.frequency_hz, fitted.damping_ratio
        );
        assert!(
            ef < 5e-4,
            "f = {} for {} ({ef:e})",
            fitted.frequency_hz,
            m.f
        );
        assert!(
            ez < 0.05,
            "ζ = {} for {} ({ez:e})",
            fitted.damping_ratio,
            m.zeta
        );
    }
}

#[test]
fn a_mode_above_the_band_is_listed_as_rejected() {
    let truth = modes();
    // The band 20–600 Hz holds the 180 Hz mode only.
    let a = analyse(
        vec![Measurement::Time(hit(&truth, 12))],
        AnalysisSettings {
            band: Some((20.0, 600.0)),
            ..AnalysisSettings::default()
        },
    )
    .unwrap();
    assert_eq!(a.band_end, BandEnd::Given);
    assert_eq!(a.fit.modes.len(), 1, "{:?}", a.fit.modes);
    let f0 = a.fit.modes[0].frequency_hz;
    assert!((f0 - 180.0).abs() / 180.0 < 5e-4, "{f0}");
    let outside: Vec<f64> = a
        .rejected
        .iter()
        .filter(|r| r.reason == RejectReason::OutsideBand)
        .map(|r| r.frequency_hz)
        .collect();
    eprintln!("rejected {:?}", a.rejected);
    assert!(
        outside.iter().any(|f| (f - 1_150.0).abs() / 1_150.0 < 5e-3),
        "the 1150 Hz mode is listed as outside the band: {:?}",
        a.rejected
    );
}

#[test]
fn the_command_line_lists_the_rejected_pole_and_the_band_end() {
    use std::fmt::Write;
    let dir = tempfile::tempdir().unwrap();
    let r = hit(&modes(), 13);
    let mut csv = String::from("time,force,response\n");
    for k in 0..N {
        let _ = writeln!(
            csv,
            "{:.9e},{:.9e},{:.9e}",
            k as f64 / FS,
            r.force[k],
            r.response[k]
        );
    }
    let path = dir.path().join("hit.csv");
    std::fs::write(&path, csv).unwrap();
    let run = |extra: &[&str]| {
        let out = assert_cmd::cargo::cargo_bin_cmd!("ancf-modal")
            .arg("frf")
            .arg(&path)
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    let doc: serde_json::Value =
        serde_json::from_str(&run(&["--band", "20:600", "--json"])).unwrap();
    assert_eq!(doc["band_end"], "given");
    let rejected = doc["rejected"].as_array().expect("`rejected` is an array");
    assert!(
        rejected.iter().any(|r| r["reason"] == "outside_band"
            && (r["frequency_hz"].as_f64().unwrap() - 1_150.0).abs() < 6.0),
        "{rejected:?}"
    );
    let table = run(&["--band", "20:600"]);
    let line = table
        .lines()
        .find(|l| l.starts_with("not reported: a stable pole at "))
        .unwrap_or_else(|| panic!("a line for the rejected pole:\n{table}"));
    let f: f64 = line["not reported: a stable pole at ".len()..]
        .split_whitespace()
        .next()
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("a frequency in {line:?}"));
    assert!(
        (f - 1_150.0).abs() / 1_150.0 < 5e-3 && line.contains("outside the fit band"),
        "{line}"
    );
    let doc: serde_json::Value = serde_json::from_str(&run(&["--json"])).unwrap();
    assert_eq!(
        doc["peaks"].as_array().unwrap().len(),
        2,
        "{}",
        doc["peaks"]
    );
    assert!(
        ["force_drop", "noise_floor"].contains(&doc["band_end"].as_str().unwrap()),
        "{}",
        doc["band_end"]
    );
}
