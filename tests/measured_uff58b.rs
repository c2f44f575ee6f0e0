//! UFF dataset 58b (binary 58): pyuff's binary sample equals its ASCII twin
//! (pyuff's `test_read_58b_binary_vs_58_ascii`), `binary8byte.uff` parses
//! to the values at its documented byte offsets, records synthesized here
//! (little and big endian, single and double, real and complex, even and
//! uneven, with line ends and a `    -1` line among the binary bytes) read
//! back exactly, a wrong byte count is one error naming file and record,
//! and `ancf-modal frf` takes a hammer test stored as 58b records.

mod measured_support;

use std::f64::consts::PI;
use std::fmt::Write;
use std::path::{Path, PathBuf};

use ancf_modal::measured::uff::{self, FunctionType, Ordinate, SpecDataType};
use ancf_modal::measured::MeasuredError;
use assert_cmd::Command;
use measured_support::hammer_records;
use realfft::num_complex::Complex64;

fn sample(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/pyuff")
        .join(name)
}

/// Byte offset just after the `n`-th `\n` of `bytes`.
fn after_lines(bytes: &[u8], n: usize) -> usize {
    bytes
        .iter()
        .enumerate()
        .filter(|(_, &c)| c == b'\n')
        .nth(n - 1)
        .map(|(k, _)| k + 1)
        .unwrap()
}

#[test]
fn binary_sample_equals_its_ascii_twin() {
    let bin_path = sample("Sample_UFF58b_bin.uff");
    let bytes = std::fs::read(&bin_path).unwrap();
    let b = uff::read_functions_bytes(&bin_path, &bytes).unwrap();
    // The path the command line takes: the file read as (lossy) text.
    let lossy = String::from_utf8_lossy(&bytes);
    assert!(lossy.contains(char::REPLACEMENT_CHARACTER));
    assert_eq!(uff::read_functions(&bin_path, &lossy).unwrap(), b);
    let ascii_path = sample("Sample_UFF58_ascii.uff");
    let text = std::fs::read_to_string(&ascii_path).unwrap();
    let a = uff::read_functions(&ascii_path, &text).unwrap();
    assert_eq!((a.len(), b.len()), (1, 1));
    let (a, b) = (&a[0], &b[0]);
    assert_eq!(b.id[0], "Mic 01.0Scalar");
    assert_eq!(a.id, b.id);
    assert_eq!(b.id[2], "18-Apr-16 13:49:58");
    assert_eq!((b.response_node, b.response_direction), (0, 1));
    assert_eq!(a.response_direction, b.response_direction);
    assert_eq!(b.function_type, FunctionType::Time);
    assert_eq!(b.abscissa_type, SpecDataType::TIME);
    assert_eq!(b.ordinate_type, SpecDataType(21));
    assert_eq!(
        (b.ordinate_label.as_str(), b.ordinate_units.as_str()),
        ("Pressure", "Pa")
    );
    assert!(b.even && a.even);
    assert_eq!((b.x_min, b.dx), (0.0, 1.52588e-5));
    assert_eq!(b.abscissa(), a.abscissa());
    let (Ordinate::Real(av), Ordinate::Real(bv)) = (&a.ordinate, &b.ordinate) else {
        panic!("real ordinates expected");
    };
    assert_eq!((av.len(), bv.len()), (79_292, 79_292));
    // The binary holds 4-byte floats (ordinate type 2); the ASCII file
    // prints them as %13.5e: 6 significant digits, half a unit of the
    // last one is 5e-6 of the value at most.
    let mut worst_rel: f64 = 0.0;
    for (k, (x, y)) in av.iter().zip(bv).enumerate() {
        assert_eq!(f64::from(*y as f32), *y, "point {k} is a float");
        assert!((x - y).abs() < 1.5e-6, "point {k}: {x} vs {y}"); // pyuff: decimal=6
        assert!(
            (x - y).abs() <= 5.0e-6 * y.abs() + 1e-12,
            "point {k}: {x} vs {y}"
        );
        if *y != 0.0 {
            worst_rel = worst_rel.max((x - y).abs() / y.abs());
        }
    }
    assert!(worst_rel > 1e-7, "the ASCII twin is rounded: {worst_rel:e}");
    // First values, as printed in the ASCII file.
    assert!((bv[0] - -1.47553e-2).abs() < 5e-8);
    assert!((bv[5] - -1.53669e-2).abs() < 5e-8);
    assert!((bv[79_291] - -4.31469e-3).abs() < 5e-9);
}

#[test]
fn binary8byte_parses_to_the_values_at_their_offsets() {
    let p = sample("binary8byte.uff");
    let bytes = std::fs::read(&p).unwrap();
    let f = uff::read_functions_bytes(&p, &bytes).unwrap();
    assert_eq!(f.len(), 1);
    let f = &f[0];
    // Type line `58b 1 2 11 2000`: little endian, IEEE, 11 ASCII lines,
    // 2000 bytes; record 7: type 4 (real double), 250 points, even, 0, 0.01.
    assert_eq!(f.function_type, FunctionType::Time);
    assert_eq!(f.response_entity, "sine 5 Hz");
    assert_eq!((f.response_node, f.response_direction), (1, 0));
    assert_eq!(f.abscissa_type, SpecDataType::TIME);
    assert_eq!(f.ordinate_type, SpecDataType::ACCELERATION);
    assert_eq!(
        (f.ordinate_label.as_str(), f.ordinate_units.as_str()),
        ("acc (g)", "g")
    );
    assert!(f.even);
    assert_eq!((f.x_min, f.dx), (0.0, 0.01));
    let x = f.abscissa();
    assert_eq!(x.len(), 250);
    assert_eq!(x[249], 249.0 * 0.01);
    // The binary data start after the 13 lines `-1`, `58b …` and records
    // 1–11 (each ending in CR LF): byte 928; then 2000 bytes and `    -1`.
    let start = after_lines(&bytes, 13);
    assert_eq!(start, 928);
    assert_eq!(bytes.len(), start + 2000 + b"    -1\r\n".len());
    assert_eq!(&bytes[start + 2000..], b"    -1\r\n");
    let Ordinate::Real(v) = &f.ordinate else {
        panic!("real ordinate expected");
    };
    assert_eq!(v.len(), 250);
    for (k, value) in v.iter().enumerate() {
        let at = start + 8 * k;
        let expected = f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
        assert_eq!(value.to_bits(), expected.to_bits(), "point {k}");
        // The file's content: a unit 5 Hz sine sampled at 100 Hz, computed
        // in single precision (every value is a float; the phase error of
        // a float time grows to 7.4e-6 at point 240).
        assert_eq!(f64::from(*value as f32), *value, "point {k}");
        let sine = (2.0 * PI * 5.0 * k as f64 * 0.01).sin();
        assert!((value - sine).abs() < 1e-5, "point {k}: {value} vs {sine}");
    }
    assert_eq!(v[0], 0.0);
    // Messages about a point name its record's `58b` line (line 2); the
    // data start on line 14.
    assert_eq!(f.lines, vec![2; 250]);
    assert_eq!(f.data_line, 14);
}

/// Ordinate data types of record 7.
#[derive(Clone, Copy)]
enum Kind {
    RealSingle = 2,
    RealDouble = 4,
    ComplexSingle = 5,
    ComplexDouble = 6,
}

/// One 58b block: the type line declaring `big` endian or little and
/// `n_bytes` (the data's length unless given), records 1–11, `values` (the
/// stored sequence) in binary, the closing `-1`. `points` is written into
/// record 7.
struct Synth<'a> {
    name: &'a str,
    function_type: u32,
    ordinate_type: u32,
    kind: Kind,
    big: bool,
    even: bool,
    points: usize,
    dx: f64,
    values: &'a [f64],
    n_bytes: Option<usize>,
}

impl Synth<'_> {
    fn data(&self) -> Vec<u8> {
        let double = matches!(self.kind, Kind::RealDouble | Kind::ComplexDouble);
        let mut out = Vec::new();
        for v in self.values {
            match (double, self.big) {
                (true, false) => out.extend(v.to_le_bytes()),
                (true, true) => out.extend(v.to_be_bytes()),
                (false, false) => out.extend((*v as f32).to_le_bytes()),
                (false, true) => out.extend((*v as f32).to_be_bytes()),
            }
        }
        out
    }

    fn write(&self, out: &mut Vec<u8>) {
        let data = self.data();
        let mut h = String::new();
        let order = if self.big { 2 } else { 1 };
        let n_bytes = self.n_bytes.unwrap_or(data.len());
        let _ = writeln!(h, "    -1");
        let _ = writeln!(
            h,
            "    58b{order:>6}{:>6}{:>12}{n_bytes:>12}{:>6}{:>6}{:>12}{:>12}",
            2, 11, 0, 0, 0, 0
        );
        for id in [self.name, "NONE", "23-Nov-26 19:30:00", "NONE", "NONE"] {
            let _ = writeln!(h, "{id:<80}");
        }
        let _ = writeln!(
            h,
            "{:>5}{:>10}{:>5}{:>10} {:<10}{:>10}{:>4} {:<10}{:>10}{:>4}",
            self.function_type, 0, 0, 0, self.name, 7, 3, "NONE", 1, 3
        );
        let _ = writeln!(
            h,
            "{:>10}{:>10}{:>10}{:>13}{:>13}{:>13}",
            self.kind as u32,
            self.points,
            u32::from(self.even),
            "0.00000e+00",
            format!("{:.5e}", self.dx).replace("e-", "e-0"),
            "0.00000e+00"
        );
        for (t, label, unit) in [
            (17, "time", "s"),
            (self.ordinate_type, self.name, "unit"),
            (0, "NONE", "NONE"),
            (0, "NONE", "NONE"),
        ] {
            let _ = writeln!(h, "{t:>10}{:>5}{:>5}{:>5} {label:<20} {unit:<20}", 0, 0, 0);
        }
        // CR LF line ends, as acquisition software on Windows writes them.
        out.extend(h.replace('\n', "\r\n").into_bytes());
        out.extend(data);
        out.extend(b"    -1\r\n");
    }
}

fn sine(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| 0.75 * (2.0 * PI * 37.0 * k as f64 / 1000.0 + 0.3).sin())
        .collect()
}

/// An 8-byte value whose little-endian bytes hold a whole `    -1` line.
fn delimiter_double() -> f64 {
    f64::from_le_bytes(*b"    -1\n?")
}

fn base<'a>(name: &'a str, kind: Kind, big: bool, points: usize, values: &'a [f64]) -> Synth<'a> {
    Synth {
        name,
        function_type: 1,
        ordinate_type: 12,
        kind,
        big,
        even: true,
        points,
        dx: 1e-3,
        values,
        n_bytes: None,
    }
}

#[test]
fn synthesized_records_read_back_exactly() {
    let n = 1000;
    let mut s = sine(n);
    s[10] = delimiter_double();
    assert!(s[10].is_finite());
    let complex: Vec<Complex64> = (0..n)
        .map(|k| Complex64::from_polar(1.0 + k as f64 / n as f64, 0.01 * k as f64))
        .collect();
    let interleaved: Vec<f64> = complex.iter().flat_map(|c| [c.re, c.im]).collect();
    let uneven_x: Vec<f64> = (0..50).map(|k| (k * k) as f64 * 1e-3).collect();
    let uneven: Vec<f64> = uneven_x
        .iter()
        .zip(sine(50))
        .flat_map(|(x, y)| [*x, y])
        .collect();
    let mut frf = base("frf", Kind::ComplexDouble, true, n, &interleaved);
    frf.function_type = 4;
    let mut uneven_rec = base("uneven", Kind::RealSingle, false, 50, &uneven);
    uneven_rec.even = false;
    let records = [
        base("le double", Kind::RealDouble, false, n, &s),
        base("be double", Kind::RealDouble, true, n, &s),
        base("be single", Kind::RealSingle, true, n, &s),
        base("le single", Kind::ComplexSingle, false, n, &interleaved),
        frf,
        uneven_rec,
    ];
    let mut file = Vec::new();
    for r in &records {
        r.write(&mut file);
    }
    // The binary bytes hold line ends and a whole delimiter line.
    let le = records[0].data();
    assert!(le.windows(7).any(|w| w == b"    -1\n"));
    let p = Path::new("synth.uff");
    let f = uff::read_functions_bytes(p, &file).unwrap();
    assert_eq!(f.len(), records.len());
    for (g, r) in f.iter().zip(&records) {
        assert_eq!(g.id[0], r.name);
        assert_eq!(g.response_entity, r.name);
        assert_eq!((g.response_node, g.response_direction), (7, 3));
        assert_eq!((g.reference_node, g.reference_direction), (1, 3));
        assert_eq!(g.ordinate_type, SpecDataType::ACCELERATION);
        assert_eq!(g.dx, r.dx);
        assert_eq!(g.even, r.even);
    }
    let real = |k: usize| f[k].ordinate.real_parts();
    assert_eq!(real(0), s);
    assert_eq!(real(1), s);
    let single: Vec<f64> = s.iter().map(|v| f64::from(*v as f32)).collect();
    assert_eq!(real(2), single);
    let Ordinate::Complex(c) = &f[3].ordinate else {
        panic!("complex expected")
    };
    for (a, b) in c.iter().zip(&complex) {
        assert_eq!(a.re, f64::from(b.re as f32));
        assert_eq!(a.im, f64::from(b.im as f32));
    }
    assert_eq!(f[4].function_type, FunctionType::Frf);
    assert_eq!(f[4].ordinate, Ordinate::Complex(complex.clone()));
    assert_eq!(
        f[5].x,
        uneven_x
            .iter()
            .map(|v| f64::from(*v as f32))
            .collect::<Vec<_>>()
    );
    assert_eq!(f[5].abscissa(), f[5].x);
    let ys: Vec<f64> = sine(50).iter().map(|v| f64::from(*v as f32)).collect();
    assert_eq!(real(5), ys);
    // Text read lossily (what the command line hands over) reads the file
    // again as bytes.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("synth.uff");
    std::fs::write(&path, &file).unwrap();
    let text = String::from_utf8_lossy(&file);
    assert_eq!(uff::read_functions(&path, &text).unwrap(), f);
    // One line end before the closing `-1` (written by some software) is
    // accepted.
    let mut crlf = Vec::new();
    records[1].write(&mut crlf);
    let end = crlf.len() - b"    -1\r\n".len();
    crlf.splice(end..end, *b"\r\n");
    assert_eq!(
        uff::read_functions_bytes(p, &crlf).unwrap()[0].ordinate,
        Ordinate::Real(s)
    );
}

fn err(file: &[u8]) -> MeasuredError {
    uff::read_functions_bytes(Path::new("bad.uff"), file).unwrap_err()
}

#[test]
fn wrong_byte_counts_name_the_file_and_the_record() {
    let s = sine(100);
    let good = base("acc", Kind::RealDouble, false, 100, &s);
    let mut head = Vec::new();
    good.write(&mut head); // record 1 is fine; the faults are in record 2.
    let lines_before = head.iter().filter(|&&c| c == b'\n').count();
    let type_line = lines_before + 2;
    let with = |r: &Synth, edit: &dyn Fn(&mut Vec<u8>)| {
        let mut rec = Vec::new();
        r.write(&mut rec);
        edit(&mut rec);
        let mut file = head.clone();
        file.extend(rec);
        file
    };
    // Bytes missing from the binary block, the closing `-1` present.
    let cut = with(&good, &|v| {
        let end = v.len() - b"    -1\r\n".len();
        v.drain(end - 16..end);
    });
    let e = err(&cut);
    assert!(
        matches!(e, MeasuredError::UffBinaryLength { record: 2, found: 784, expected: 800, line, .. } if line == type_line),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        format!(
            "bad.uff:{type_line}: UFF 58b record 2: 784 bytes of binary data before the closing `    -1`, but its header announces 800"
        )
    );
    // The file ends inside the binary block.
    let short = with(&good, &|v| v.truncate(v.len() - 500));
    let e = err(&short).to_string();
    assert_eq!(
        e,
        format!(
            "bad.uff:{type_line}: UFF 58b record 2: 308 bytes of binary data before the end of the file, but its header announces 800"
        )
    );
    // The header announces fewer bytes than the block holds.
    let mut fewer = base("acc", Kind::RealDouble, false, 100, &s);
    fewer.n_bytes = Some(792);
    let e = err(&with(&fewer, &|_| {})).to_string();
    assert!(
        e.contains("record 2: 800 bytes of binary data before the closing"),
        "{e}"
    );
    assert!(e.ends_with("announces 792"), "{e}");
    // Byte count and block agree, but not with record 7's points.
    let points = base("acc", Kind::RealDouble, false, 99, &s);
    let e = err(&with(&points, &|_| {}));
    assert!(
        matches!(
            e,
            MeasuredError::UffBinarySize {
                record: 2,
                announced: 800,
                needed: 792,
                ..
            }
        ),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        format!(
            "bad.uff:{type_line}: UFF 58b record 2: its header announces 800 bytes of binary data, but 99 points × 1 values × 8 bytes make 792"
        )
    );
    // A floating-point format other than IEEE 754.
    let vms = with(&good, &|v| {
        let k = v.windows(4).position(|w| w == b"58b ").unwrap();
        v[k + 14] = b'1';
    });
    let e = err(&vms).to_string();
    assert!(
        e.contains("58b floating-point format = 1 is not supported"),
        "{e}"
    );
}

fn bin() -> Command {
    Command::cargo_bin("ancf-modal").unwrap()
}

#[test]
fn frf_reads_a_hammer_test_stored_as_58b() {
    let modes = measured_support::two_modes();
    let (fs, n) = (10_240.0, 5_120);
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for (i, r) in hammer_records(&modes, fs, n, 3, 1e-3, 1e-9, 5)
        .iter()
        .enumerate()
    {
        // Force little endian, response big endian, as two records.
        let mut force = base("force", Kind::RealDouble, false, n, &r.force);
        force.ordinate_type = 13;
        force.dx = 1.0 / fs;
        let mut resp = base("response", Kind::RealDouble, true, n, &r.response);
        resp.ordinate_type = 8;
        resp.dx = 1.0 / fs;
        let mut bytes = Vec::new();
        force.write(&mut bytes);
        resp.write(&mut bytes);
        let p = dir.path().join(format!("hit{i}.uff"));
        std::fs::write(&p, bytes).unwrap();
        files.push(p);
    }
    let out = bin()
        .arg("frf")
        .args(&files)
        .args([
            "--window",
            "force:0.02",
            "--response-quantity",
            "displacement",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["averages"], 3);
    let peaks = doc["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 2, "{peaks:?}");
    for (p, m) in peaks.iter().zip(&modes) {
        let f = p["frequency_hz"].as_f64().unwrap();
        let z = p["damping_ratio"].as_f64().unwrap();
        assert!((f - m.f).abs() < 3e-4 * m.f, "f = {f}");
        assert!((z - m.zeta).abs() < 0.05 * m.zeta, "ζ = {z}");
    }
    // A truncated binary block: exit 1, one line naming file and record.
    let bad = dir.path().join("cut.uff");
    let mut bytes = std::fs::read(&files[0]).unwrap();
    bytes.truncate(bytes.len() - 100);
    std::fs::write(&bad, bytes).unwrap();
    let out = bin().arg("frf").arg(&bad).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("cut.uff:") && stderr.contains("UFF 58b record 2: "),
        "{stderr}"
    );
    assert!(stderr.contains("before the end of the file"), "{stderr}");
}
