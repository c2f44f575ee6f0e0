//! A fit band given past the data (issue 33, outside-eyes trial: a band of
//! 100–2000 Hz on a record sampled at 2048 Hz was fitted and printed as
//! "over 100.0–2000.0 Hz"). A band that ends past the last line is cut
//! there, said in a warning, and fits exactly as the cut band given by
//! hand; a band that starts past it is an error naming the file.

mod common;
mod measured_support;

use ancf_modal::measured::analysis::{analyse, AnalysisSettings};
use ancf_modal::measured::Measurement;
use measured_support::{hammer_records, two_modes};

const FS: f64 = 10_240.0;

fn run(band: (f64, f64)) -> Result<ancf_modal::measured::analysis::FrfAnalysis, String> {
    let records = hammer_records(&two_modes(), FS, 5_120, 2, 0.0, 0.0, 7);
    analyse(
        records.into_iter().map(Measurement::Time).collect(),
        AnalysisSettings {
            band: Some(band),
            ..AnalysisSettings::default()
        },
    )
    .map_err(|e| e.to_string())
}

#[test]
fn a_band_past_the_last_line_is_cut_there_and_said() {
    let nyquist = FS / 2.0;
    let past = run((500.0, 2.0 * FS)).unwrap();
    let cut = run((500.0, nyquist)).unwrap();
    assert_eq!(past.band, (500.0, nyquist));
    let modes = |a: &ancf_modal::measured::analysis::FrfAnalysis| -> Vec<(f64, f64)> {
        a.fit
            .modes
            .iter()
            .map(|m| (m.frequency_hz, m.damping_ratio))
            .collect()
    };
    assert_eq!(modes(&past), modes(&cut));
    // Both true modes (800 and 2100 Hz) lie inside the cut band.
    let truth: Vec<f64> = two_modes().iter().map(|m| m.f).collect();
    assert_eq!(past.fit.modes.len(), truth.len());
    for (m, f) in past.fit.modes.iter().zip(&truth) {
        assert!(
            (m.frequency_hz - f).abs() < 1e-5 * f,
            "{} Hz against {f} Hz",
            m.frequency_hz
        );
    }
    let said: Vec<String> = past
        .warnings()
        .into_iter()
        .filter(|w| w.contains("past the data's last line"))
        .collect();
    assert_eq!(said.len(), 1, "{:?}", past.warnings());
    assert!(
        said[0].contains(&format!("fitted over 500.0–{nyquist:.1} Hz")),
        "{}",
        said[0]
    );
    assert!(cut.warnings().iter().all(|w| !w.contains("last line")));
}

#[test]
fn a_band_starting_past_the_last_line_is_an_error() {
    let e = run((6_000.0, 8_000.0)).unwrap_err();
    assert!(
        e.contains("the fit band starts at 6000 Hz, at or past the data's last line, 5120 Hz"),
        "{e}"
    );
}

/// A tail that still rings is no noise floor (the second outside-eyes
/// trial of this round: an undamped steel cantilever, 60 × 8 × 0.8 mm
/// with a 1 g tip mass, struck at 42 mm; its 0.2 s `impulse` record had
/// the automatic band cut at 1.16 kHz "where the response reaches the
/// noise floor of the record's quiet tail", while its modes ring to
/// 14.6 kHz and its 0.05 s and 0.5 s records got 13 kHz). The band now
/// ends at the force drop, past the third bending mode (2768 Hz).
#[test]
fn a_ringing_tail_sets_no_noise_floor() {
    let model = serde_json::json!({
        "name": "cant_a0",
        "beams": [{"id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.06,
                   "elements": 10, "section": {"height": 0.0008, "width": 0.008},
                   "material": {"young": 210e9, "density": 7850.0}}],
        "point_masses": [{"id": "tipm", "mass": 0.001, "position": [0.06, 0.0]}],
        "joints": [{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}},
                   {"type": "pin", "a": {"beam": "b", "s": 0.06}, "b": {"body": "tipm"}}],
        "loads": [{"id": "hammer", "at": {"beam": "b", "s": 0.042}, "force": [0.0, 1.0],
                   "time": {"half_sine": {"duration": 0.0001}}}],
        "sensors": [{"id": "tip", "at": {"beam": "b", "s": 0.06}, "quantity": "velocity",
                     "frame": "global", "direction": [0.0, 1.0]}]
    });
    let doc = common::impulse_then_frf(&model, &["--end-time", "0.2"]);
    assert_ne!(doc["band_end"], "noise_floor", "{}", doc["band_hz"]);
    assert!(
        doc["band_hz"][1].as_f64().unwrap() > 2768.0,
        "{}",
        doc["band_hz"]
    );
}
