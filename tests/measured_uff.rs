//! UFF datasets 15, 55 and 58: pyuff's sample files (tests/data/pyuff,
//! MIT licence) parse to the numbers they hold, a record written by hand
//! from the published layout parses to its values, and what we write reads
//! back to the same numbers at the written precision.

mod measured_support;

use std::path::Path;

use ancf_modal::measured::uff::d55::{read_modes, write_mode, write_nodes};
use ancf_modal::measured::uff::{self, d58, FunctionType, Ordinate, SpecDataType};
use ancf_modal::measured::uff::{NodeCoordinates, NormalMode};
use realfft::num_complex::Complex64;

fn data(name: &str) -> (std::path::PathBuf, String) {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/pyuff")
        .join(name);
    let text = std::fs::read_to_string(&p).unwrap();
    (p, text)
}

#[test]
fn pyuff_sample_time_history_58() {
    let (p, text) = data("time-history-not-all-columns-filled.uff");
    let f = uff::read_functions(&p, &text).unwrap();
    assert_eq!(f.len(), 1);
    let f = &f[0];
    assert_eq!(f.id[0].trim(), "1x : m/s²");
    assert_eq!(f.function_type, FunctionType::Time);
    assert_eq!(f.abscissa_type, SpecDataType::TIME);
    assert_eq!(
        (f.abscissa_label.as_str(), f.abscissa_units.as_str()),
        ("Time", "s")
    );
    assert_eq!(
        (f.ordinate_label.as_str(), f.ordinate_units.as_str()),
        ("1x", "m/s²")
    );
    assert!(f.even);
    assert_eq!(f.dx, 5e-5);
    let Ordinate::Real(v) = &f.ordinate else {
        panic!("real data expected")
    };
    assert_eq!(v.len(), 13);
    assert_eq!(v[0], -3.81956);
    assert_eq!(v[5], -3.63712);
    assert_eq!(v[12], -5.84096);
    // The 13th value sits alone on the third data line (file line 16).
    assert_eq!(f.lines[12], 16);
}

#[test]
fn pyuff_sample_modes_55() {
    let (p, text) = data("uff55_translation.uff");
    let (nodes, modes) = read_modes(&p, &text).unwrap();
    assert!(nodes.is_empty());
    assert_eq!(modes.len(), 3);
    let f: Vec<f64> = modes.iter().map(|m| m.frequency_hz).collect();
    assert_eq!(f, [10.0, 12.0, 13.0]);
    assert_eq!(modes[0].mode_number, 1);
    assert_eq!(modes[2].mode_number, 3);
    assert_eq!(modes[0].nodes.len(), 4);
    assert_eq!(modes[0].nodes[0], (1, [-1.46518; 3]));
    assert_eq!(modes[1].nodes[3], (4, [1.98289; 3]));
    assert_eq!(modes[2].nodes[1], (2, [-6.62803e-1; 3]));
}

/// An FRF record written by hand after the published layout (records 1–11
/// and complex-double data, 2 points a line).
const HAND_WRITTEN: &str = "    -1
    58
FRF point 3 / point 1
NONE
23-Nov-26 12:00:00
NONE
NONE
    4         1    1         0 beam               3   2 beam               1   2
         6         3         1  1.00000E+02  5.00000E+00  0.00000E+00
        18    0    0    0 Frequency            Hz
        11    0    0    0 Velocity             m/s
        13    0    0    0 Force                N
         0    0    0    0 NONE                 NONE
  1.50000000000E-03 -2.00000000000E-04  1.25000000000E-03 -4.00000000000E-04
 -3.00000000000E-05  7.50000000000E-04
    -1
";

#[test]
fn hand_written_frf_record() {
    let f = uff::read_functions(Path::new("hand.uff"), HAND_WRITTEN).unwrap();
    let f = &f[0];
    assert_eq!(f.function_type, FunctionType::Frf);
    assert_eq!(
        (
            f.response_entity.as_str(),
            f.response_node,
            f.response_direction
        ),
        ("beam", 3, 2)
    );
    assert_eq!((f.reference_node, f.reference_direction), (1, 2));
    assert_eq!(f.ordinate_type, SpecDataType::VELOCITY);
    assert_eq!(f.denominator_type, SpecDataType::FORCE);
    assert_eq!(f.abscissa(), vec![100.0, 105.0, 110.0]);
    assert_eq!(
        f.ordinate,
        Ordinate::Complex(vec![
            Complex64::new(1.5e-3, -2e-4),
            Complex64::new(1.25e-3, -4e-4),
            Complex64::new(-3e-5, 7.5e-4),
        ])
    );
}

#[test]
fn written_58_reads_back_at_the_written_precision() {
    let h: Vec<Complex64> = (0..101)
        .map(|k| {
            let x = k as f64 * 0.37;
            Complex64::new(x.sin() * 1.234_567_890_123e-3, -x.cos() / 7.0)
        })
        .collect();
    let mut f =
        measured_support::frf_function(h.clone(), 5.0, (SpecDataType::VELOCITY, "Velocity", "m/s"));
    f.id[1] = "ancf-modal".into();
    f.response_node = 7;
    let mut text = String::new();
    d58::write(&mut text, &f);
    // The layout of DESIGN §9: record 6 and 7 widths, 4 values a line
    // (record 7's step with seven digits in its 13 columns, so 1/51,200 s
    // is written exactly).
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "    -1");
    assert_eq!(lines[1], "    58");
    assert_eq!(lines[7].len(), 80);
    assert_eq!(
        lines[8],
        "         6       101         1  0.00000e+00 5.000000e+00  0.00000e+00"
    );
    assert_eq!(lines[13].len(), 80);
    let back = uff::read_functions(Path::new("w.uff"), &text).unwrap();
    let b = &back[0];
    assert_eq!(b.id[0].trim(), "H1 tip / hammer");
    assert_eq!(
        (b.response_node, b.response_direction, b.reference_node),
        (7, 2, 1)
    );
    assert_eq!(b.abscissa(), f.abscissa());
    let Ordinate::Complex(hb) = &b.ordinate else {
        panic!()
    };
    for (a, b) in h.iter().zip(hb) {
        // %20.11e: 12 significant digits.
        assert!(
            (a - b).norm() <= 5e-12 * a.norm().max(1e-300) * 2.0,
            "{a} vs {b}"
        );
    }
}

#[test]
fn written_15_and_55_read_back() {
    let nodes = vec![
        NodeCoordinates {
            label: 1,
            xyz: [-5.6e-3, -15.4e-3, 0.0],
        },
        NodeCoordinates {
            label: 2,
            xyz: [1.234_56e-2, 7.0e-4, 0.0],
        },
    ];
    let mode = NormalMode {
        id: "mode 4: 4577.3 Hz".into(),
        mode_number: 4,
        frequency_hz: 4577.312,
        modal_mass: 1.0,
        damping_ratio: 0.0123,
        nodes: vec![(1, [0.25, -1.0, 0.0]), (2, [3.3e-2, 0.987_654_3, 0.0])],
    };
    let mut text = String::new();
    write_nodes(&mut text, &nodes);
    write_mode(&mut text, &mode);
    let (n2, m2) = read_modes(Path::new("m.uff"), &text).unwrap();
    assert_eq!(n2.len(), 2);
    for (a, b) in nodes.iter().zip(&n2) {
        assert_eq!(a.label, b.label);
        for k in 0..3 {
            assert!((a.xyz[k] - b.xyz[k]).abs() <= 5e-6 * a.xyz[k].abs());
        }
    }
    let b = &m2[0];
    assert_eq!(b.mode_number, 4);
    assert!((b.frequency_hz - 4577.3).abs() < 0.01 + 1e-12); // %13.5e: 6 digits
    assert!((b.damping_ratio - 0.0123).abs() < 1e-9);
    assert!((b.nodes[1].1[1] - 0.987_654).abs() < 1e-6);
}

#[test]
fn a_dataset_of_an_unknown_type_is_skipped_and_listed() {
    // A made-up 9999 after the hand-written record (17 lines): skipped by
    // its framing, named with its type line (18), the record unchanged.
    let text = format!("{HAND_WRITTEN}    -1\n  9999\n  1 2 3\n    -1\n");
    let (f, skipped) = uff::read_functions_noted(Path::new("x.uff"), text.as_bytes()).unwrap();
    assert_eq!(
        f,
        uff::read_functions(Path::new("x.uff"), HAND_WRITTEN).unwrap()
    );
    assert_eq!(
        skipped,
        [uff::Skipped {
            kind: "9999".into(),
            line: 18
        }]
    );
    assert_eq!(
        uff::skipped_note(Path::new("x.uff"), &skipped).as_deref(),
        Some("x.uff: 1 UFF dataset this tool does not use was skipped: 9999 (line 18)")
    );
}

/// An FRF file says what its response measures (outside-eyes trial of
/// issue 33: an accelerance, ordinate type 12, was labelled m/s/N): `frf`
/// takes the unit from the ordinate type, unless told otherwise.
#[test]
fn an_frf_files_ordinate_type_is_its_unit() {
    // One mode, 100 Hz at 1 %, as an accelerance on 1 Hz lines.
    let h: Vec<Complex64> = (0..400)
        .map(|k| {
            let (w, wr) = (
                2.0 * std::f64::consts::PI * k as f64,
                2.0 * std::f64::consts::PI * 100.0,
            );
            -w * w / Complex64::new(wr * wr - w * w, 0.02 * wr * w)
        })
        .collect();
    let f = measured_support::frf_function(
        h,
        1.0,
        (SpecDataType::ACCELERATION, "Acceleration", "m/s^2"),
    );
    let mut text = String::new();
    d58::write(&mut text, &f);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("acc.uff");
    std::fs::write(&path, text).unwrap();
    let run = |extra: &[&str]| -> serde_json::Value {
        let o = assert_cmd::Command::cargo_bin("ancf-modal")
            .unwrap()
            .arg("frf")
            .arg(&path)
            .arg("--json")
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let doc = run(&[]);
    assert_eq!(
        doc["response_quantity"], "acceleration",
        "{}",
        doc["frf_unit"]
    );
    let told = run(&["--response-quantity", "velocity"]);
    assert_eq!(told["response_quantity"], "velocity");
    // Overriding the file's own ordinate is said; agreeing with it is not.
    let said = |d: &serde_json::Value| {
        d["warnings"].as_array().unwrap().iter().any(|w| {
            w.as_str()
                .unwrap()
                .contains("the file's units are overridden")
        })
    };
    assert!(said(&told), "{}", told["warnings"]);
    assert!(!said(&run(&["--response-quantity", "acceleration"])));
    assert!(!said(&doc));
    // The mode is the file's, whatever its unit is called.
    let f0 = doc["peaks"][0]["frequency_hz"].as_f64().unwrap();
    assert!((f0 - 100.0).abs() < 1e-6, "{f0}");
}
