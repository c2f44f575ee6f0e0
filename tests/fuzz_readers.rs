//! Fuzzed readers: the model JSON reader, the measurement reader (CSV, UFF
//! 58 ASCII and 58b binary) and the `frf` analysis of whatever they accept
//! return an error or a result for any input — never a panic.
//!
//! Inputs: arbitrary bytes, and valid files mutated (bytes overwritten,
//! deleted, inserted, chunks repeated, the file cut; for the model also
//! numbers replaced by edge values such as 0, −1, 1e308, 5e-324). The valid
//! files are the shipped models, a hammer record written here as CSV and as
//! UFF 58 by the library's writer, and pyuff's binary 58b and ASCII 58
//! samples. Fixed seeds and a fixed budget of cases per property (the
//! `CASES` constant), so a run is reproducible and short.

use ancf_modal::error::Source;
use ancf_modal::measured::analysis::{analyse, AnalysisSettings};
use ancf_modal::measured::{parse_measurement, Channels, Measurement};
use ancf_modal::Model;
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, RngSeed};
use std::f64::consts::PI;
use std::path::Path;

/// Cases per property.
const CASES: u32 = 256;

fn config(seed: u64) -> Config {
    Config {
        cases: CASES,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::Off)),
        ..Config::default()
    }
}

/// One edit of a file: (where, what, byte).
type Edit = (usize, u8, u8);

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    prop::collection::vec((any::<usize>(), 0u8..16, any::<u8>()), 1..4)
}

/// Bytes that keep a number or a table a number or a table more often than
/// a random byte does.
const PLAUSIBLE: &[u8] = b"0123456789-+.eE ,\n";

/// `bytes` with the edits applied: mostly one byte overwritten (half of
/// the time by a plausible one), else bytes deleted, inserted, a chunk
/// repeated, or (rarely) the file cut.
fn mutate(bytes: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for &(at, kind, byte) in edits {
        if b.is_empty() {
            b.push(byte);
            continue;
        }
        let i = at % b.len();
        let new = if byte < 128 {
            PLAUSIBLE[byte as usize % PLAUSIBLE.len()]
        } else {
            byte
        };
        match kind {
            0..=8 => b[i] = new,
            9 | 10 => {
                let end = (i + 1 + byte as usize % 16).min(b.len());
                b.drain(i..end);
            }
            11 | 12 => b.insert(i, new),
            13 | 14 => {
                let end = (i + 1 + byte as usize).min(b.len());
                let chunk = b[i..end].to_vec();
                b.splice(i..i, chunk);
            }
            _ => b.truncate(i),
        }
    }
    b
}

/// Edge values a number of a model may be replaced by.
const EDGE_NUMBERS: [&str; 12] = [
    "0",
    "-0",
    "-1",
    "1e308",
    "-1e308",
    "5e-324",
    "1e-300",
    "0.5",
    "3",
    "18446744073709551616",
    "1e999",
    "123456789",
];

/// `text` with its `k`-th number (mod their count) replaced by `value`.
fn replace_number(text: &str, k: usize, value: &str) -> String {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = (bytes[i].is_ascii_digit() || bytes[i] == b'-')
            && i > 0
            && matches!(bytes[i - 1], b':' | b'[' | b',' | b' ');
        if starts {
            let j = i + bytes[i..]
                .iter()
                .take_while(|c| c.is_ascii_digit() || matches!(c, b'-' | b'+' | b'.' | b'e' | b'E'))
                .count();
            spans.push((i, j));
            i = j;
        } else {
            i += 1;
        }
    }
    match spans.get(k % spans.len().max(1)) {
        Some(&(a, b)) => format!("{}{value}{}", &text[..a], &text[b..]),
        None => text.to_string(),
    }
}

fn shipped_models() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let mut texts: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    texts.sort();
    texts
}

/// Reads a model; a model that reads is also asked for its warnings.
fn read_model(text: &str) {
    if let Ok(m) = Model::from_json(text, Source::BuiltIn) {
        let _ = m.unit_warnings();
    }
}

/// A hammer hit written here: 512 samples at 10.24 kHz, a half-sine of
/// 0.3 ms and a 900 Hz mode at 2 % damping.
fn hit() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let fs = 10_240.0;
    let t: Vec<f64> = (0..512).map(|k| k as f64 / fs).collect();
    let force = t
        .iter()
        .map(|&t| if t < 3e-4 { (PI * t / 3e-4).sin() } else { 0.0 })
        .collect();
    let w = 2.0 * PI * 900.0;
    let response = t
        .iter()
        .map(|&t| (-0.02 * w * t).exp() * (w * t).sin() * 1e-3)
        .collect();
    (t, force, response)
}

fn hit_csv() -> Vec<u8> {
    use std::fmt::Write;
    let (t, f, x) = hit();
    let mut s = String::from("time,force,response\n");
    for k in 0..t.len() {
        let _ = writeln!(s, "{:.9e},{:.9e},{:.9e}", t[k], f[k], x[k]);
    }
    s.into_bytes()
}

fn hit_uff() -> Vec<u8> {
    let (t, f, x) = hit();
    ancf_modal::output::records_uff::time_records_uff(
        &t,
        &f,
        &x,
        "tip",
        ancf_modal::model::SensorQuantity::Velocity,
        &[String::from("fuzz"), String::from("fuzz")],
    )
    .into_bytes()
}

fn pyuff(name: &str) -> Vec<u8> {
    std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/pyuff")
            .join(name),
    )
    .unwrap()
}

/// Reads a measurement file's bytes (and its UFF datasets, whether or not
/// they make a measurement); what reads is analysed as `frf` would.
fn read_measurement(bytes: &[u8]) {
    let _ = ancf_modal::measured::uff::read_functions_bytes(Path::new("fuzz.uff"), bytes);
    let channels = Channels::default();
    if let Ok(m) = parse_measurement(Path::new("fuzz.dat"), bytes, &channels) {
        let small = match &m {
            Measurement::Time(r) => r.force.len() <= 4096,
            Measurement::Frf(f) => f.frequency_hz.len() <= 4096,
        };
        if small {
            let _ = analyse(vec![m], AnalysisSettings::default());
        }
    }
}

proptest! {
    #![proptest_config(config(23))]

    #[test]
    fn model_reader_takes_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        read_model(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn model_reader_takes_mutated_models(which in 0usize..8, e in edits()) {
        let models = shipped_models();
        let text = &models[which % models.len()];
        read_model(&String::from_utf8_lossy(&mutate(text.as_bytes(), &e)));
    }

    #[test]
    fn model_reader_takes_edge_numbers(which in 0usize..8, k in any::<usize>(), v in 0usize..EDGE_NUMBERS.len()) {
        let models = shipped_models();
        let text = &models[which % models.len()];
        read_model(&replace_number(text, k, EDGE_NUMBERS[v]));
    }

    #[test]
    fn measurement_reader_takes_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        read_measurement(&bytes);
        // The same bytes behind a UFF start, so the UFF reader sees them.
        let mut uff = b"    -1\n    58\n".to_vec();
        uff.extend(&bytes);
        read_measurement(&uff);
    }

    #[test]
    fn csv_reader_takes_mutated_records(e in edits()) {
        read_measurement(&mutate(&hit_csv(), &e));
    }

    #[test]
    fn uff58_reader_takes_mutated_records(which in 0usize..3, e in edits()) {
        let file = match which {
            0 => hit_uff(),
            1 => pyuff("time-history-not-all-columns-filled.uff"),
            _ => pyuff("Sample_UFF58_ascii.uff"),
        };
        read_measurement(&mutate(&file, &e));
    }

    #[test]
    fn uff58b_reader_takes_mutated_records(which in 0usize..2, e in edits()) {
        let file = match which {
            0 => pyuff("binary8byte.uff"),
            _ => pyuff("Sample_UFF58b_bin.uff"),
        };
        read_measurement(&mutate(&file, &e));
    }
}

#[test]
fn the_seeds_are_valid_files() {
    // The unmutated seeds read (so the mutations start from valid input).
    for text in shipped_models() {
        assert!(Model::from_json(&text, Source::BuiltIn).is_ok());
    }
    let channels = Channels::default();
    for bytes in [hit_csv(), hit_uff()] {
        let m = parse_measurement(Path::new("seed"), &bytes, &channels);
        assert!(matches!(m, Ok(Measurement::Time(_))), "{m:?}");
    }
    for name in [
        "binary8byte.uff",
        "Sample_UFF58b_bin.uff",
        "Sample_UFF58_ascii.uff",
    ] {
        let m = ancf_modal::measured::uff::read_functions_bytes(Path::new(name), &pyuff(name));
        assert!(m.is_ok_and(|f| !f.is_empty()), "{name}");
    }
}
