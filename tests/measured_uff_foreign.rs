//! UFF datasets the tool does not use are skipped by their framing alone,
//! whatever their number, and listed; a dataset it uses but cannot parse is
//! still an error naming its line.
//!
//! The foreign datasets are real exports from pyuff's sample files
//! (tests/data/pyuff, MIT licence): Simcenter Testlab's 1858 qualifiers
//! (`1858.uff`), a result file's 151, 164, 2411, 2412 and 2414
//! (`heat_engine_housing.uff`), and two made up here: an ASCII 9999 and a
//! binary 9999b whose bytes hold line ends and `    -1` lines (so only its
//! byte count frames it). The dataset-58 records are an ASCII 58 and a
//! binary 58b of pyuff's (`time-history-not-all-columns-filled.uff`,
//! `binary8byte.uff`) and an FRF written here. Generated files put the
//! records between, before and after foreign datasets in every order; each
//! must read as the records alone do, every number equal, the line of each
//! point moved by exactly the lines put before it, and the skipped list
//! naming each foreign dataset's type and type line, counted here.

use std::path::{Path, PathBuf};

mod measured_support;

use ancf_modal::measured::uff::{self, d58, Function, SpecDataType};
use ancf_modal::measured::{parse_measurement_noted, Channels, MeasuredError, Measurement};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, RngSeed};
use realfft::num_complex::Complex64;

fn pyuff(name: &str) -> Vec<u8> {
    std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/pyuff")
            .join(name),
    )
    .unwrap()
}

/// The blocks of an ASCII UFF file, each from its opening to its closing
/// `-1` line with their line ends (one added after the last line of a file
/// that ends without): split by lines, not by the reader.
fn ascii_blocks(bytes: &[u8]) -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    let mut current: Option<Vec<u8>> = None;
    for line in bytes.split_inclusive(|&c| c == b'\n') {
        let delimiter = line.trim_ascii() == b"-1";
        match current.as_mut() {
            None if delimiter => current = Some(line.to_vec()),
            None => assert!(line.trim_ascii().is_empty(), "text between blocks"),
            Some(b) => {
                b.extend_from_slice(line);
                if delimiter {
                    if !b.ends_with(b"\n") {
                        b.push(b'\n');
                    }
                    out.extend(current.take());
                }
            }
        }
    }
    assert!(current.is_none(), "an unclosed block");
    out
}

/// A foreign dataset: its bytes and its type as the reader names it.
#[derive(Debug, Clone)]
struct Foreign {
    bytes: Vec<u8>,
    kind: &'static str,
}

/// The foreign datasets: 1858 ×2, 151, 164, 2411, 2412, 2414, 9999, 9999b.
fn foreign() -> Vec<Foreign> {
    let mut out = Vec::new();
    for (name, kinds) in [
        ("1858.uff", &["1858", "1858"][..]),
        (
            "heat_engine_housing.uff",
            &["151", "164", "2411", "2412", "2414"][..],
        ),
    ] {
        let blocks = ascii_blocks(&pyuff(name));
        assert_eq!(blocks.len(), kinds.len(), "{name}");
        for (bytes, kind) in blocks.into_iter().zip(kinds) {
            out.push(Foreign { bytes, kind });
        }
    }
    out.push(Foreign {
        bytes: b"    -1\n  9999\n     1     2     3\nsome text\n    -1\n".to_vec(),
        kind: "9999",
    });
    // Binary: 3 ASCII lines, then 42 bytes holding `    -1` lines and
    // line ends, then the closing `-1`.
    let mut bin = b"    -1\n  9999b     1     2           3          42\nA\nB\nC\n".to_vec();
    let data = b"\n    -1\n  58\n\r\n    -1\r\n\x00\xff-1\n    -1\n    -1\n";
    bin.extend_from_slice(&data[..]);
    assert_eq!(data.len(), 42);
    bin.extend_from_slice(b"    -1\n");
    out.push(Foreign {
        bytes: bin,
        kind: "9999b",
    });
    out
}

/// An FRF of one mode, H = 1/(k − mω² + icω), as dataset 58.
fn frf_record() -> Vec<u8> {
    let (m, c, k) = (0.02, 0.4, 8.0e4);
    let h: Vec<Complex64> = (0..64)
        .map(|i| {
            let w = 2.0 * std::f64::consts::PI * 5.0 * i as f64;
            Complex64::new(1.0, 0.0) / Complex64::new(k - m * w * w, c * w)
        })
        .collect();
    let f = measured_support::frf_function(h, 5.0, (SpecDataType::DISPLACEMENT, "tip", "m"));
    let mut text = String::new();
    d58::write(&mut text, &f);
    text.into_bytes()
}

/// The dataset-58 records, in the order they must come back.
fn records() -> Vec<Vec<u8>> {
    vec![
        pyuff("time-history-not-all-columns-filled.uff"),
        pyuff("binary8byte.uff"),
        frf_record(),
    ]
}

fn newlines(b: &[u8]) -> usize {
    b.iter().filter(|&&c| c == b'\n').count()
}

/// A file of `records` with the foreign datasets `inserts` (index into
/// `foreign`, slot 0..=records.len(): before record `slot`, or after the
/// last), in order within a slot; with the skipped datasets the reader must
/// list (type, line of the type line) and the lines put before each record.
fn assemble(
    records: &[Vec<u8>],
    foreign: &[Foreign],
    inserts: &[(usize, usize)],
) -> (Vec<u8>, Vec<(String, usize)>, Vec<usize>) {
    let mut file = Vec::new();
    let mut skipped = Vec::new();
    let mut shifts = Vec::new();
    let mut shift = 0;
    for slot in 0..=records.len() {
        for &(which, _) in inserts.iter().filter(|(_, s)| *s == slot) {
            let f = &foreign[which];
            // The type line is the line after the opening `-1`.
            skipped.push((f.kind.to_string(), newlines(&file) + 2));
            file.extend_from_slice(&f.bytes);
            shift += newlines(&f.bytes);
        }
        if let Some(r) = records.get(slot) {
            shifts.push(shift);
            file.extend_from_slice(r);
            if !r.ends_with(b"\n") {
                file.push(b'\n');
                shift += 1;
            }
        }
    }
    (file, skipped, shifts)
}

/// `a` and `b` hold the same numbers and labels; each point's line in `b`
/// is its line in `a` plus `shift`.
fn same_but_moved(a: &Function, b: &Function, shift: usize) {
    let moved = |f: &Function, by: usize| Function {
        data_line: f.data_line + by,
        lines: f.lines.iter().map(|l| l + by).collect(),
        ..f.clone()
    };
    assert_eq!(&moved(a, shift), b);
}

/// The records alone, each read from a file of its own and from all
/// together: what every mixed file must give.
fn alone() -> Vec<Function> {
    let records = records();
    let (file, skipped, _) = assemble(&records, &foreign(), &[]);
    assert!(skipped.is_empty());
    let (f, s) = uff::read_functions_noted(Path::new("alone.uff"), &file).unwrap();
    assert!(s.is_empty(), "{s:?}");
    assert_eq!(f.len(), records.len());
    // Each record read from a file of its own is the same record.
    for (k, r) in records.iter().enumerate() {
        let own = uff::read_functions_bytes(Path::new("own.uff"), r).unwrap();
        let shift = f[k].data_line - own[0].data_line;
        same_but_moved(&own[0], &f[k], shift);
    }
    f
}

fn config(seed: u64) -> Config {
    Config {
        cases: 96,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::Off)),
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(33))]

    /// Any foreign datasets, in any number (0–12) and order, before,
    /// between and after the records.
    #[test]
    fn records_among_foreign_datasets_read_as_alone(
        inserts in prop::collection::vec((0usize..9, 0usize..4), 0..12),
    ) {
        let records = records();
        let foreign = foreign();
        let expected = alone();
        let (file, skipped, shifts) = assemble(&records, &foreign, &inserts);
        let (f, s) = uff::read_functions_noted(Path::new("mixed.uff"), &file).unwrap();
        prop_assert_eq!(f.len(), expected.len());
        for k in 0..f.len() {
            same_but_moved(&expected[k], &f[k], shifts[k]);
        }
        let s: Vec<(String, usize)> = s.into_iter().map(|s| (s.kind, s.line)).collect();
        prop_assert_eq!(s, skipped);
    }
}

#[test]
fn every_foreign_dataset_between_every_record() {
    // The cases the issue names, all at once: each foreign dataset before
    // the first record, between each two and after the last.
    let records = records();
    let foreign = foreign();
    let inserts: Vec<(usize, usize)> = (0..=records.len())
        .flat_map(|slot| (0..foreign.len()).map(move |w| (w, slot)))
        .collect();
    let (file, skipped, shifts) = assemble(&records, &foreign, &inserts);
    let (f, s) = uff::read_functions_noted(Path::new("all.uff"), &file).unwrap();
    let expected = alone();
    for k in 0..f.len() {
        same_but_moved(&expected[k], &f[k], shifts[k]);
    }
    assert_eq!(s.len(), 4 * 9);
    let s: Vec<(String, usize)> = s.into_iter().map(|s| (s.kind, s.line)).collect();
    assert_eq!(s, skipped);
}

/// Reads `file` (bytes) as `frf` does: the measurement and its notes.
fn measurement(name: &str, file: &[u8]) -> (Measurement, Vec<String>) {
    parse_measurement_noted(Path::new(name), file, &Channels::default()).unwrap()
}

#[test]
fn an_frf_beside_testlab_qualifiers_is_read_and_the_note_lists_them() {
    // The file: an FRF (58) and Testlab's 1858 records.
    let alone = measurement("h.uff", &frf_record());
    assert!(alone.1.is_empty(), "nothing skipped: {:?}", alone.1);
    let mut file = frf_record();
    file.extend(pyuff("1858.uff"));
    let (m, notes) = measurement("h.uff", &file);
    assert_eq!(m, alone.0);
    let Measurement::Frf(_) = m else {
        panic!("an FRF")
    };
    // The first 1858's type line follows the FRF's lines and its `-1`.
    let first = newlines(&frf_record()) + 2;
    assert_eq!(
        notes,
        [format!(
            "h.uff: 2 UFF datasets this tool does not use were skipped: 1858 ×2 (first at line {first})"
        )]
    );
}

#[test]
fn one_skipped_dataset_is_named_alone() {
    let mut file = ascii_blocks(&pyuff("1858.uff"))[0].clone();
    file.extend(frf_record());
    let (_, notes) = measurement("q.uff", &file);
    assert_eq!(
        notes,
        ["q.uff: 1 UFF dataset this tool does not use was skipped: 1858 (line 2)"]
    );
}

#[test]
fn a_file_of_foreign_datasets_only_has_no_record() {
    let err = parse_measurement_noted(
        Path::new("mesh.uff"),
        &pyuff("heat_engine_housing.uff"),
        &Channels::default(),
    )
    .unwrap_err();
    assert_eq!(err.to_string(), "mesh.uff: the file holds no dataset 58");
}

fn read_err(file: &[u8]) -> MeasuredError {
    uff::read_functions_bytes(&PathBuf::from("bad.uff"), file).unwrap_err()
}

#[test]
fn a_record_that_does_not_parse_among_foreign_ones_is_an_error_naming_its_line() {
    // The FRF after two 1858s, its record 6 (line 8 of the block) spoiled.
    let mut file = ascii_blocks(&pyuff("1858.uff")).concat();
    let before = newlines(&file);
    let frf = String::from_utf8(frf_record()).unwrap();
    let mut lines: Vec<&str> = frf.lines().collect();
    lines[7] = "    x";
    file.extend(lines.join("\n").into_bytes());
    file.push(b'\n');
    let err = read_err(&file);
    let line = before + 8;
    assert!(
        err.to_string()
            .starts_with(&format!("bad.uff:{line}: UFF 58")),
        "names line {line}: {err}"
    );
}

#[test]
fn a_foreign_dataset_without_its_closing_line_is_an_error() {
    // The 2414 of the result file without its closing `-1`: nothing after
    // it can be framed.
    let blocks = ascii_blocks(&pyuff("heat_engine_housing.uff"));
    let mut file = frf_record();
    let open = newlines(&file) + 1;
    let b = &blocks[4];
    let cut = b.len() - b"    -1\n".len();
    assert_eq!(&b[cut..], b"    -1\n");
    file.extend_from_slice(&b[..cut]);
    assert_eq!(
        read_err(&file).to_string(),
        format!(
            "bad.uff:{}: UFF block has no closing `    -1` line",
            open + 1
        )
    );
}

#[test]
fn a_foreign_binary_dataset_of_the_wrong_length_is_an_error() {
    // 9999b announcing 50 bytes where 42 stand before its `-1` (and 49
    // to the end of the file).
    let f = foreign().pop().unwrap();
    let text = f.bytes.clone();
    let spoiled = String::from_utf8_lossy(&text).replacen("          42", "          50", 1);
    let mut file = frf_record();
    let type_line = newlines(&file) + 2;
    file.extend(spoiled.into_bytes());
    let err = read_err(&file);
    assert!(
        err.to_string().starts_with(&format!(
            "bad.uff:{type_line}: UFF dataset `9999b` (not used, skipped by its framing)"
        )),
        "{err}"
    );
}
