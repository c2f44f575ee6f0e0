//! A fit band given past the data (issue 33, outside-eyes trial: a band of
//! 100–2000 Hz on a record sampled at 2048 Hz was fitted and printed as
//! "over 100.0–2000.0 Hz"). A band that ends past the last line is cut
//! there, said in a warning, and fits exactly as the cut band given by
//! hand; a band that starts past it is an error naming the file.

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
