//! Unit sanity warnings (DESIGN §10): a beam with h/L > 0.1, E outside
//! 1e5–1e13 Pa, ρ outside 10–25,000 kg/m³ or √(E/ρ) outside 5–20,000 m/s
//! gives one `warning:` line on stderr and an entry of the JSON document's
//! `warnings`, and never changes the exit code; a sweep records them per
//! point. The shipped models give none.
//!
//! The cases are the issue's: a relay leaf of L = 18 mm, h = 0.3 mm,
//! E = 127 GPa, ρ = 8940 kg/m³ (copper alloy) with the height typed as
//! 0.3 (millimetres meant: h/L = 16.7), E typed in megapascals
//! (127e3, caught by its wave speed) and ρ in g/cm³ (8.94).

use assert_cmd::cargo::cargo_bin_cmd;
use serde_json::{json, Value};
use std::path::Path;

/// The leaf, clamped at s = 0, with the height, E and ρ given.
fn leaf(height: f64, young: f64, density: f64) -> Value {
    json!({
        "name": "leaf",
        "beams": [{
            "id": "leaf", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.018,
            "elements": 6,
            "section": {"height": height, "width": 3e-3},
            "material": {"young": young, "density": density}
        }],
        "joints": [{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "leaf", "s": 0.0}}]
    })
}

/// Runs the tool on `model` written to a temp dir; (exit code, stdout,
/// stderr).
fn run(model: &Value, args: &[&str]) -> (Option<i32>, String, String) {
    let dir = tempfile::tempdir().expect("a temp dir");
    let path = dir.path().join("leaf.json");
    std::fs::write(&path, model.to_string()).unwrap();
    run_on(&path, args)
}

fn run_on(path: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let out = cargo_bin_cmd!("ancf-modal")
        .args(&args[..1])
        .arg(path)
        .args(&args[1..])
        .output()
        .expect("the binary runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `modal --json` of `model`: asserts exit 0 and returns the `warnings`
/// of the document and the `warning:` lines of stderr.
fn modal_warnings(model: &Value) -> (Vec<String>, Vec<String>) {
    let (code, stdout, stderr) = run(model, &["modal", "--json", "--modes", "3"]);
    assert_eq!(code, Some(0), "a warning never fails the run: {stderr}");
    let doc: Value = serde_json::from_str(&stdout).expect("JSON on stdout");
    let in_json = doc["warnings"]
        .as_array()
        .expect("`warnings` is an array in every --json")
        .iter()
        .map(|w| w.as_str().expect("warnings are text").to_string())
        .collect();
    let lines = stderr
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .map(String::from)
        .collect();
    (in_json, lines)
}

#[test]
fn a_plausible_leaf_gives_no_warning() {
    let (json, lines) = modal_warnings(&leaf(0.3e-3, 127e9, 8940.0));
    assert!(json.is_empty(), "no warning: {json:?}");
    assert!(lines.is_empty(), "no warning line: {lines:?}");
}

#[test]
fn the_height_in_millimetres_asks_for_metres() {
    let (json, lines) = modal_warnings(&leaf(0.3, 127e9, 8940.0));
    assert_eq!(json.len(), 1, "one warning: {json:?}");
    assert_eq!(lines.len(), 1, "one line on stderr: {lines:?}");
    let w = &json[0];
    // h/L = 0.3 / 0.018.
    let ratio = format!("{:.3}", 0.3 / 0.018);
    assert!(
        w.contains("beams[0].section.height") && w.contains(&ratio) && w.contains("metres"),
        "names the beam's height, h/L = {ratio} and asks for metres: {w}"
    );
    assert!(lines[0].contains(w.as_str()), "the same text on stderr");
}

#[test]
fn young_in_kilopascal_scale_and_density_in_grams_ask_for_si_units() {
    // E = 127e3 Pa (MPa meant) is inside 1e5–1e13 Pa, but √(E/ρ) =
    // 3.769 m/s is below 10 m/s.
    let (json, _) = modal_warnings(&leaf(0.3e-3, 127e3, 8940.0));
    let speed = format!("{:.3}", (127e3_f64 / 8940.0).sqrt());
    assert_eq!(json.len(), 1, "{json:?}");
    assert!(
        json[0].contains("wave speed") && json[0].contains(&speed) && json[0].contains("SI units"),
        "{json:?}"
    );
    // Steel in MPa (210,000 at 7850 kg/m³): √(E/ρ) = 5.17 m/s is below
    // 10 m/s, the softest solid's (a gel, 1e5 Pa at 1000 kg/m³).
    let (json, _) = modal_warnings(&leaf(0.3e-3, 210e3, 7850.0));
    assert_eq!(json.len(), 1, "{json:?}");
    assert!(json[0].contains("wave speed"), "{json:?}");
    // E = 5e4 Pa is below 1e5 Pa (and √(E/ρ) = 2.4 m/s below 10 m/s).
    let (json, _) = modal_warnings(&leaf(0.3e-3, 5e4, 8940.0));
    assert_eq!(json.len(), 2, "{json:?}");
    assert!(json[0].contains("beams[0].material.young") && json[0].contains("SI units"));
    let (json, _) = modal_warnings(&leaf(0.3e-3, 127e9, 8.94));
    // ρ = 8.94 is below 10 kg/m³; √(E/ρ) = 119,000 m/s is above 20,000.
    assert_eq!(json.len(), 2, "{json:?}");
    assert!(json[0].contains("beams[0].material.density") && json[0].contains("SI units"));
    assert!(json[1].contains("wave speed"), "{json:?}");
}

#[test]
fn every_shipped_model_is_plausible() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let (code, stdout, stderr) = run_on(&path, &["modal", "--json", "--modes", "4"]);
        assert_eq!(code, Some(0), "{}: {stderr}", path.display());
        // Unit warnings ask about metres or SI units (the beam-theory
        // warning of a mode is another matter).
        let unit = |w: &str| w.contains("metres?") || w.contains("SI units?");
        assert!(!stderr.lines().any(unit), "{}: {stderr}", path.display());
        let doc: Value = serde_json::from_str(&stdout).unwrap();
        let warnings = doc["warnings"].as_array().expect("a warnings array");
        assert!(
            !warnings.iter().any(|w| unit(w.as_str().unwrap())),
            "{}: {warnings:?}",
            path.display()
        );
        seen += 1;
    }
    assert!(seen >= 5, "the shipped models were found ({seen})");
}

#[test]
fn a_sweep_records_the_warnings_per_point() {
    // Heights 0.3 mm, 1.2 mm, 2.1 mm: h/L = 0.017, 0.067, 0.117; only the
    // last is above 0.1.
    let (code, stdout, stderr) = run(
        &leaf(0.3e-3, 127e9, 8940.0),
        &[
            "sweep",
            "--param",
            "height=0.3e-3:2.1e-3:3",
            "--quantity",
            "first_bending_hz",
            "--json",
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
    let doc: Value = serde_json::from_str(&stdout).unwrap();
    let points = doc["points"].as_array().unwrap();
    let counts: Vec<usize> = points
        .iter()
        .map(|p| p["warnings"].as_array().expect("per-point warnings").len())
        .collect();
    assert_eq!(counts, [0, 0, 1], "{points:?}");
    assert_eq!(
        stderr
            .lines()
            .filter(|l| l.starts_with("warning: "))
            .count(),
        1,
        "one line for the one point: {stderr}"
    );
}

/// The micrometre assembly: a 200 µm base clamped at the ground, a
/// 150 µm arm welded to its tip and a 200 µm mass (√(I/m) = 200 µm) welded
/// to the arm's tip without `local`, every length in metres, with the
/// arm's length given by `arm` (150e-6, or 150 when typed in micrometres)
/// and the mass at 350 µm.
fn micro(arm: f64) -> Value {
    let beam = |id: &str, start: f64, length: f64| {
        json!({
            "id": id, "start": [start, 0.0], "angle_deg": 0.0, "length": length, "elements": 4,
            "section": {"height": 5e-6, "width": 10e-6},
            "material": {"young": 160e9, "density": 2330.0}
        })
    };
    json!({
        "name": "micro",
        "beams": [beam("base", 0.0, 200e-6), beam("arm", 200e-6, arm)],
        "rigid_bodies": [{"id": "mass", "mass": 1e-9, "inertia": 4e-17, "position": [350e-6, 0.0]}],
        "joints": [
            {"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "base", "s": 0.0}},
            {"type": "weld", "a": {"beam": "base", "s": 200e-6}, "b": {"beam": "arm", "s": 0.0}},
            {"type": "weld", "a": {"beam": "arm", "s": arm}, "b": {"body": "mass"}}
        ]
    })
}

#[test]
fn a_length_typed_in_micrometres_names_the_part_and_the_lever_arm() {
    let (json, lines) = modal_warnings(&micro(150e-6));
    assert!(json.is_empty() && lines.is_empty(), "{json:?} {lines:?}");
    let (json, lines) = modal_warnings(&micro(150.0));
    // The arm and the mass; since issue 37 the sparse solve's refinement
    // certifies the modes their sizes used to spoil (no accuracy warning).
    assert_eq!(json.len(), 2, "the arm, the mass: {json:?}");
    assert_eq!(lines.len(), 2, "{lines:?}");
    assert!(
        json.iter()
            .all(|w| !w.contains("the eigen-solve certifies")),
        "{json:?}"
    );
    // 150 m against the 200 µm base: 750,000 times; the mass's point is the
    // arm's tip, (200e-6 + 150) − 350e-6 = 149.99985 m from its centre,
    // 749,999 times its 200 µm.
    assert!(
        json[0].contains("beams[1].length: beam `arm` (length 150 m) is 750000 times the size of beam `base` (length 0.0002 m), joined to it by joints[1]")
            && json[0].ends_with("metres?"),
        "{}",
        json[0]
    );
    assert!(
        json[1].contains("joints[2].b: this point is 150 m from the centre of rigid body `mass`, 750000 times its radius of gyration √(I/m) = 0.0002 m")
            && json[1].contains("`local` missing"),
        "{}",
        json[1]
    );
    for (w, l) in json.iter().zip(&lines) {
        assert!(l.contains(w.as_str()), "the same text on stderr: {l}");
    }
}

#[test]
fn parts_whose_sizes_disagree_no_longer_spoil_the_default_solve() {
    // The run (8 elements in all): the dense solve cannot resolve
    // the modes (bounds ~1e6); since issue 37 it refuses them instead of
    // printing them, and the default solver refines them by shift-invert
    // with precise products, certifying them.
    let (code, stdout, stderr) = run(&micro(150.0), &["modal", "--modes", "3"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        !stdout.contains("warning:"),
        "warnings go to stderr: {stdout}"
    );
    assert!(!stderr.contains("eigen-solve certifies"), "{stderr}");
    let (code, _, stderr) = run(
        &micro(150.0),
        &["modal", "--modes", "3", "--solver", "dense"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains("mode 1 is not reported as a frequency")
            && stderr.contains("the dense solve's round-off limits it"),
        "{stderr}"
    );
    // The same assembly in consistent units certifies its frequencies.
    let (_, stdout, stderr) = run(&micro(150e-6), &["modal", "--modes", "3"]);
    assert!(!stdout.contains("warning:"), "{stdout}");
    assert!(!stderr.contains("eigen-solve certifies"), "{stderr}");
}

#[test]
fn a_very_fine_mesh_is_certified() {
    // The README's case: the 25 mm cantilever in 2,000 elements, whose
    // bound was ~5e-6 with an accuracy warning before issue 37; the
    // refined solve certifies it.
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("models/cantilever.json"),
    )
    .unwrap();
    let mut model: Value = serde_json::from_str(&text).unwrap();
    model["beams"][0]["elements"] = json!(2000);
    let (code, stdout, stderr) = run(&model, &["modal", "--modes", "1", "--json"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(!stderr.contains("eigen-solve certifies"), "{stderr}");
    // And right: Euler–Bernoulli's f₁ (the mesh's own error is ~1e-13).
    let v: Value = serde_json::from_str(&stdout).unwrap();
    let f1 = v["modes"][0]["frequency_hz"].as_f64().expect("f1");
    let (l, h, w, e, rho) = (25e-3f64, 1.1e-3f64, 5.2e-3f64, 127e9f64, 8940.0f64);
    let ei = e * w * h.powi(3) / 12.0;
    let beta = 1.875_104_068_711_961f64;
    let exact = beta * beta / (2.0 * std::f64::consts::PI * l * l) * (ei / (rho * w * h)).sqrt();
    assert!((f1 / exact - 1.0).abs() < 1e-7, "{f1} Hz vs {exact} Hz");
}

/// An aluminium ruler (0.3 m, 30 × `height` mm... in metres) on two foam
/// springs of 50 N/m, the right one anchored at `anchor` (outside-eyes
/// trial of issue 33).
fn ruler_on_foam(height: f64, anchor: [f64; 2]) -> Value {
    json!({
        "name": "ruler",
        "beams": [{
            "id": "ruler", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.3,
            "elements": 20,
            "section": {"height": height, "width": 0.03},
            "material": {"young": 70e9, "density": 2700.0}
        }],
        "springs": [
            {"id": "foamL", "a": {"beam": "ruler", "s": 0.0672},
             "b": {"ground": [0.0672, -0.02]}, "stiffness": 50.0, "free_length": 0.02},
            {"id": "foamR", "a": {"beam": "ruler", "s": 0.2328},
             "b": {"ground": anchor}, "stiffness": 50.0, "free_length": 0.02}
        ]
    })
}

#[test]
fn a_spring_point_in_millimetres_names_the_spring() {
    // The anchor typed in millimetres: the spring runs from (0.2328, 0)
    // to (232.8, -20).
    let (in_json, on_stderr) = modal_warnings(&ruler_on_foam(1e-3, [232.8, -20.0]));
    let length = (232.8_f64 - 0.2328).hypot(20.0);
    let said: Vec<&String> = in_json
        .iter()
        .filter(|w| w.contains("springs[1]: the spring is"))
        .collect();
    assert_eq!(said.len(), 1, "{in_json:?}");
    let expected = format!(
        "springs[1]: the spring is {} m long at the reference, {} times the length 0.3 m of beam `ruler` it holds",
        ancf_modal::model::number::significant(length, 3),
        ancf_modal::model::number::significant(length / 0.3, 3)
    );
    assert!(said[0].contains(&expected), "{} lacks {expected}", said[0]);
    assert!(on_stderr.iter().any(|l| l.contains(&expected)));
    // In metres, nothing is said.
    let (in_json, _) = modal_warnings(&ruler_on_foam(1e-3, [0.2328, -0.02]));
    assert!(in_json.is_empty(), "{in_json:?}");
}

#[test]
fn a_value_in_other_units_no_longer_spoils_the_default_solve() {
    // The height typed in millimetres (1.0 for 1 mm): the 0.3 m ruler is
    // a metre-high block on 50 N/m springs; before issue 37 the table's
    // bound was loose and warned; the refined solve certifies it.
    let (code, _, stderr) = run(
        &ruler_on_foam(1.0, [0.2328, -0.02]),
        &["modal", "--modes", "3"],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(!stderr.contains("eigen-solve certifies"), "{stderr}");
}

#[test]
fn a_slow_elastic_mode_prints_its_digits_not_zero() {
    // A 3 m steel cantilever typed as 3000 (millimetres meant): its first
    // bending mode, Euler–Bernoulli (1.8751²/2πL²)·√(EI/ρA) = 4.6e-6 Hz,
    // printed with four significant digits, not as `0.000` beside "0
    // zero-frequency modes" (second outside-eyes trial of issue 33).
    let (l, h, e, rho) = (3000.0_f64, 0.05_f64, 210e9_f64, 7850.0_f64);
    let model = json!({
        "name": "long",
        "beams": [{
            "id": "board", "start": [0.0, 0.0], "angle_deg": 0.0, "length": l,
            "elements": 20,
            "section": {"height": h, "width": 0.5},
            "material": {"young": e, "density": rho}
        }],
        "joints": [{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "board", "s": 0.0}}]
    });
    let (code, stdout, stderr) = run(&model, &["modal", "--modes", "2"]);
    assert_eq!(code, Some(0), "{stderr}");
    let beta_l = 1.875_104_068_711_961_f64;
    let f1 =
        beta_l * beta_l / (2.0 * std::f64::consts::PI * l * l) * (e * h * h / (12.0 * rho)).sqrt();
    let row = stdout
        .lines()
        .find(|r| r.trim_start().starts_with("1 "))
        .unwrap_or_else(|| panic!("mode 1 in {stdout}"));
    assert!(row.contains(&format!("{f1:.3e}")), "{row} lacks {f1:.3e}");
    assert!(stdout.contains("0 zero-frequency modes"), "{stdout}");
}
