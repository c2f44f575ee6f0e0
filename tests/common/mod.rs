//! Shared builders for the verification tests: the paper's blade (Table 2)
//! and analytic Euler–Bernoulli frequencies.
#![allow(dead_code)]

use ancf_modal::analysis::{modal_at_reference, ModalResult, ModalSettings, ModeKind};
use ancf_modal::error::Source;
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};
use serde_json::{json, Value};
use std::f64::consts::PI;

/// Paper Table 2.
pub const L: f64 = 25e-3;
pub const H: f64 = 1.1e-3;
pub const W: f64 = 5.2e-3;
pub const RHO: f64 = 8940.0;
pub const E: f64 = 127e9;

/// Free-free βL (DESIGN §3, standard tables).
pub const FREE_FREE_BL: [f64; 4] = [
    4.730_040_744_862_704,
    7.853_204_624_095_838,
    10.995_607_838_001_671,
    14.137_165_491_257_464,
];
/// Cantilever βL.
pub const CANTILEVER_BL: [f64; 4] = [1.875104069, 4.694091133, 7.854757438, 10.99554073];

/// Euler–Bernoulli frequency [Hz] of a beam for a given βL.
pub fn euler_bernoulli_hz(bl: f64, l: f64, h: f64) -> f64 {
    let ei = E * W * h.powi(3) / 12.0;
    let rho_a = RHO * W * h;
    bl * bl / (2.0 * PI * l * l) * (ei / rho_a).sqrt()
}

/// First free-free axial frequency [Hz]: 1/(2L) √(E/ρ).
pub fn axial_hz(k: usize, l: f64) -> f64 {
    k as f64 / (2.0 * l) * (E / RHO).sqrt()
}

/// The blade as a JSON beam, on the x axis from the origin.
pub fn blade(elements: usize) -> Value {
    json!({
        "id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0, "length": L,
        "elements": elements, "nodes_at_attachments": false,
        "section": {"height": H, "width": W},
        "material": {"young": E, "density": RHO}
    })
}

pub fn model(v: Value) -> ValidModel {
    Model::from_json(&v.to_string(), Source::BuiltIn).expect("test model is valid")
}

pub fn modal_all(m: &ValidModel) -> ModalResult {
    modal_at_reference(&System::new(m), &ModalSettings::default()).expect("modal analysis succeeds")
}

pub fn free_beam(elements: usize) -> ValidModel {
    model(json!({"name": "free", "beams": [blade(elements)]}))
}

pub fn cantilever(elements: usize) -> ValidModel {
    model(json!({
        "name": "cantilever", "beams": [blade(elements)],
        "joints": [{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}}]
    }))
}

/// Frequencies [Hz] of the elastic modes of a kind, ascending.
pub fn freqs(r: &ModalResult, kind: ModeKind) -> Vec<f64> {
    r.of_kind(kind).map(|m| m.frequency_hz).collect()
}

pub fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b
}

/// Runs `ancf-modal` with `args`, asserts that it succeeds (its standard
/// error in the message) and returns its standard output.
pub fn run_ok<I, S>(args: I) -> Vec<u8>
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let out = assert_cmd::Command::cargo_bin("ancf-modal")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// Writes `model` to a temporary file, runs `impulse` on it with
/// `impulse_args` (end time, step, sample rate...) into a CSV record, and
/// returns `frf --json` of that record.
#[allow(dead_code)]
pub fn impulse_then_frf(model: &Value, impulse_args: &[&str]) -> Value {
    impulse_then_frfs(model, impulse_args, &[&[]]).remove(0)
}

/// As [`impulse_then_frf`], with one `frf --json` per set of extra
/// arguments in `frf_args`, on the same record.
#[allow(dead_code)]
pub fn impulse_then_frfs(model: &Value, impulse_args: &[&str], frf_args: &[&[&str]]) -> Vec<Value> {
    let dir = tempfile::tempdir().unwrap();
    let (json, csv) = (dir.path().join("model.json"), dir.path().join("imp.csv"));
    std::fs::write(&json, model.to_string()).unwrap();
    let mut args: Vec<&std::ffi::OsStr> = vec!["impulse".as_ref(), json.as_os_str()];
    args.extend(impulse_args.iter().map(std::ffi::OsStr::new));
    args.extend([std::ffi::OsStr::new("--csv"), csv.as_os_str()]);
    run_ok(args);
    frf_args
        .iter()
        .map(|extra| {
            let mut args: Vec<&std::ffi::OsStr> = vec!["frf".as_ref(), csv.as_os_str()];
            args.extend(extra.iter().map(std::ffi::OsStr::new));
            args.push("--json".as_ref());
            serde_json::from_slice(&run_ok(args)).unwrap()
        })
        .collect()
}

/// A property test's configuration: `cases` drawn from a fixed seed
/// (`default`), so that every run draws the same cases and a failure is
/// reproducible; the environment variable `var` = N explores others.
pub fn fixed_cases(cases: u32, var: &str, default: u64) -> proptest::prelude::ProptestConfig {
    let seed = std::env::var(var)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default);
    proptest::prelude::ProptestConfig {
        cases,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        ..proptest::prelude::ProptestConfig::default()
    }
}

/// Largest |a − b·scale| against the largest |b·scale|: how far a record
/// is from a scaled one (similarity tests).
pub fn scaled_off(a: &[f64], b: &[f64], scale: f64) -> f64 {
    let peak = b.iter().fold(0.0f64, |m, v| m.max((v * scale).abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y * scale).abs()))
        / peak
}

/// The points of an SVG `points` attribute ("x,y x,y …") [px].
pub fn pixels(points: &str) -> Vec<[f64; 2]> {
    points
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            [x.parse().unwrap(), y.parse().unwrap()]
        })
        .collect()
}
