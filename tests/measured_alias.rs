//! The simulated measurement behaves like a real one: the sensor is
//! low-pass filtered before it is resampled to 51.2 kHz, so the paper's
//! modes 6 and 7 (29.3 and 30.6 kHz, above the 25.6 kHz Nyquist frequency)
//! leave no folded peak below it (without the filter they appeared at
//! 20.7 and 22.0 kHz).

use assert_cmd::Command;
use serde_json::Value;

#[test]
fn modes_above_nyquist_leave_no_peak_below_it() {
    let out = Command::cargo_bin("ancf-modal")
        .unwrap()
        .args(["impulse", "--end-time", "0.02", "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: Value = serde_json::from_slice(&out.stdout).unwrap();
    let peaks: Vec<(f64, f64)> = doc["peaks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            (
                p["frequency_hz"].as_f64().unwrap(),
                p["magnitude"].as_f64().unwrap(),
            )
        })
        .collect();
    let strongest = peaks.iter().map(|p| p.1).fold(0.0, f64::max);
    // The folding frequencies of 29.3 and 30.6 kHz about 25.6 kHz, with the
    // integrator's period error: 20.3–22.5 kHz. Anything left there is the
    // stop band's (−90 dB) leakage at most.
    for (f, m) in &peaks {
        if (20_000.0..23_000.0).contains(f) {
            assert!(
                m / strongest < 1e-3,
                "a folded peak at {f} Hz ({:.1} dB)",
                20.0 * (m / strongest).log10()
            );
        }
    }
    // The first bending mode is still found.
    let fb = doc["first_bending_hz"].as_f64().unwrap();
    assert!((fb - doc["eigen_first_bending_hz"].as_f64().unwrap()).abs() < 1.0);
}
