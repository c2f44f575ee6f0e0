//! `frf` reads the columns a CSV names (issue 33: `impulse --csv` writes
//! `time_s, <sensor>, force_n`, and `frf` took column 2, the response, for
//! the force). Records with known modes (tests/measured_support), written
//! with the force in the last column under a name holding `force` (quoted
//! or not): the modes come out as with the force in column 2; without such
//! a name, column 2 is still the force. Two `force` columns, the time
//! column or one column for both are errors naming the file, the line and
//! the columns (found by the outside-eyes trial of this change).

mod measured_support;

use std::fmt::Write;
use std::path::Path;

use ancf_modal::measured::analysis::{analyse, AnalysisSettings};
use ancf_modal::measured::{csv::parse_csv, Channels, Measurement};
use measured_support::{hammer_records, two_modes};

/// The records as CSV with the header `header` and columns (time, a, b).
fn csv(header: &str, force_last: bool) -> String {
    let r = &hammer_records(&two_modes(), 10_240.0, 5_120, 1, 0.0, 0.0, 5)[0];
    let mut s = format!("{header}\n");
    for k in 0..r.force.len() {
        let (a, b) = if force_last {
            (r.response[k], r.force[k])
        } else {
            (r.force[k], r.response[k])
        };
        let _ = writeln!(s, "{:.9e},{a:.12e},{b:.12e}", k as f64 / 10_240.0);
    }
    s
}

fn modes(text: &str) -> Vec<f64> {
    let r = parse_csv(Path::new("hit.csv"), text, &Channels::default()).unwrap();
    let a = analyse(vec![Measurement::Time(r)], AnalysisSettings::default()).unwrap();
    a.fit.modes.iter().map(|m| m.frequency_hz).collect()
}

#[test]
fn a_force_named_column_is_the_force_wherever_it_stands() {
    let truth: Vec<f64> = two_modes().iter().map(|m| m.f).collect();
    for text in [
        csv("time_s,tip_displacement,force_n", true),
        csv("time,Force,response", false),
        csv("t,a,b", false),
        csv("time,vel,hammer_force", true),
        csv("\"time_s\",\"vel\",\"force_n\"", true),
    ] {
        let found = modes(&text);
        assert_eq!(found.len(), truth.len(), "{found:?}");
        for (f, t) in found.iter().zip(&truth) {
            assert!((f - t).abs() < 1e-4 * t, "{f} Hz, truth {t} Hz");
        }
    }
}

#[test]
fn the_response_label_is_the_other_column() {
    let text = csv("time_s,tip_velocity,force_n", true);
    let r = parse_csv(Path::new("hit.csv"), &text, &Channels::default()).unwrap();
    assert_eq!(r.response_label, "tip_velocity");
}

fn error(text: &str, channels: Channels) -> String {
    parse_csv(Path::new("hit.csv"), text, &channels)
        .unwrap_err()
        .to_string()
}

#[test]
fn ambiguous_or_misused_columns_are_errors() {
    use ancf_modal::measured::Channel;
    let two = "time,vel,force_hammer,force_ref\n0,0,0,0\n";
    assert_eq!(
        error(two, Channels::default()),
        "hit.csv:1: the columns `force_hammer`, `force_ref` all name a force: give the force column (its name or 1-based index)"
    );
    let text = csv("time_s,tip_velocity,force_n", true);
    let same = Channels {
        force: Some(Channel::Index(3)),
        response: Some(Channel::Index(3)),
    };
    assert_eq!(
        error(&text, same),
        "hit.csv:1: column 3 (`force_n`) cannot be the response: it is the force column too"
    );
    let time = Channels {
        force: Some(Channel::Index(1)),
        response: None,
    };
    assert_eq!(
        error(&text, time),
        "hit.csv:1: column 1 (`time_s`) cannot be the force: the first column is time"
    );
}

/// A time column named in milliseconds or microseconds is read in that
/// unit: the record sampled at 10,240 Hz written as `time_ms` (t·1e3) or
/// `t [us]` (t·1e6) gives the sample rate and the modes it gives in
/// seconds; names that only contain the letters (`terms`, `bus`) stay
/// seconds (found by the outside-eyes trial of issue 33: `time_ms` was
/// read as seconds, a 10 Hz record).
#[test]
fn a_time_column_in_ms_or_us_is_read_in_that_unit() {
    let seconds = csv("time_s,vel,force_n", true);
    let truth = parse_csv(Path::new("hit.csv"), &seconds, &Channels::default()).unwrap();
    assert!((truth.sample_rate_hz - 10_240.0).abs() < 1e-6 * 10_240.0);
    for (header, scale) in [
        ("time_ms", 1e3),
        ("t [ms]", 1e3),
        ("time (us)", 1e6),
        ("t_µs", 1e6),
    ] {
        let mut text = format!("{header},vel,force_n\n");
        for line in seconds.lines().skip(1) {
            let (t, rest) = line.split_once(',').unwrap();
            let t: f64 = t.parse().unwrap();
            let _ = writeln!(text, "{:.9e},{rest}", t * scale);
        }
        let r = parse_csv(Path::new("hit.csv"), &text, &Channels::default()).unwrap();
        let rel = (r.sample_rate_hz - truth.sample_rate_hz).abs() / truth.sample_rate_hz;
        assert!(rel < 1e-9, "{header}: {} Hz", r.sample_rate_hz);
        let (a, b) = (modes(&text), modes(&seconds));
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-9 * y, "{header}: {x} Hz against {y} Hz");
        }
    }
    for name in ["terms", "bus", "time", "time_s", "t [s]"] {
        assert_eq!(ancf_modal::measured::csv::time_scale(name), 1.0, "{name}");
    }
}

/// A time column in ms under a plain name is read as seconds, a record
/// sampled at 10.24 Hz: that is said (outside-eyes trial of issue 33,
/// second round: modes at 0.058 Hz were reported without a word). In
/// seconds, nothing is said.
#[test]
fn a_record_sampled_slower_than_any_hammer_test_asks_for_the_time_unit() {
    let seconds = csv("time,vel,force_n", true);
    let mut ms = String::from("time,vel,force_n\n");
    for line in seconds.lines().skip(1) {
        let (t, rest) = line.split_once(',').unwrap();
        let t: f64 = t.parse().unwrap();
        let _ = writeln!(ms, "{:.9e},{rest}", t * 1e3);
    }
    let said = |text: &str| -> Vec<String> {
        analysed(text, &Channels::default())
            .warnings()
            .into_iter()
            .filter(|w| w.contains("is the time in ms or µs?"))
            .collect()
    };
    let slow = said(&ms);
    assert_eq!(slow.len(), 1, "{slow:?}");
    assert!(
        slow[0].contains("sampled at 10.24 Hz, below the 20 Hz"),
        "{}",
        slow[0]
    );
    assert!(said(&seconds).is_empty());
}

fn analysed(text: &str, channels: &Channels) -> ancf_modal::measured::analysis::FrfAnalysis {
    let r = parse_csv(Path::new("hit.csv"), text, channels).unwrap();
    analyse(vec![Measurement::Time(r)], AnalysisSettings::default()).unwrap()
}

/// Channels given the wrong way round (the response named as the force)
/// are said: the blow holds its energy over a shorter span than the
/// ringing response, and here the "force" does not (found by the
/// outside-eyes trial of issue 33: swapped channels gave "no stable mode"
/// and nothing else). Given the right way, nothing is said.
#[test]
fn swapped_channels_are_said() {
    use ancf_modal::measured::Channel;
    let text = csv("time_s,vel,force_n", true);
    let swapped = Channels {
        force: Some(Channel::Name("vel".into())),
        response: Some(Channel::Name("force_n".into())),
    };
    let said = |a: &ancf_modal::measured::analysis::FrfAnalysis| {
        a.warnings().iter().any(|w| w.contains("swapped"))
    };
    assert!(
        said(&analysed(&text, &swapped)),
        "{:?}",
        analysed(&text, &swapped).warnings()
    );
    assert!(!said(&analysed(&text, &Channels::default())));
}
