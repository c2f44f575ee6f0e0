//! Parameter studies (`ancf-modal sweep`, `sweep-merge`): physics of the
//! swept quantities, mode tracking across a crossing, determinism of the
//! parallel, serial and sharded runs, and the command line's errors.

use ancf_modal::analysis::sweep::{
    merge, Execution, Quantity, Shard, Sweep, SweepDocument, SweepSettings,
};
use ancf_modal::error::Source;
use ancf_modal::model::ValidModel;
use ancf_modal::Model;
use assert_cmd::cargo::cargo_bin_cmd;
use serde_json::{json, Value};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

const L: f64 = 0.025;
const H: f64 = 1.1e-3;
const W: f64 = 5.2e-3;
const E: f64 = 127e9;
const RHO: f64 = 8940.0;

/// Free-free βL of the first bending mode (Euler–Bernoulli).
const BETA_L_FREE_1: f64 = 4.730_040_744_862_704;

fn model(v: &Value) -> ValidModel {
    Model::from_json(&v.to_string(), Source::BuiltIn).expect("valid model")
}

/// The bare free-free blade, 8 elements.
fn blade() -> Value {
    json!({"name": "blade", "beams": [{"id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0,
        "length": L, "elements": 8, "section": {"height": H, "width": W},
        "material": {"young": E, "density": RHO}}]})
}

/// A cantilever (the blade welded to the ground at s = 0) and, beside it
/// and uncoupled, a 1 g point mass on a slider along x held by a spring
/// `k`: its frequency √(k/m)/2π crosses the cantilever's bending
/// frequencies (≈1.07 kHz, ≈6.7 kHz) as k rises.
const MASS: f64 = 1e-3;
fn cantilever_and_oscillator() -> Value {
    json!({"name": "crossing",
        "beams": [{"id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0, "length": L,
            "elements": 8, "section": {"height": H, "width": W},
            "material": {"young": E, "density": RHO}}],
        "point_masses": [{"id": "m", "mass": MASS, "position": [0.1, 0.1]}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}},
            {"id": "guide", "type": "slider", "a": {"ground": [0.1, 0.1]}, "b": {"body": "m"}, "axis": [1.0, 0.0]}
        ],
        "springs": [{"id": "k", "a": {"ground": [0.09, 0.1]}, "b": {"body": "m"},
            "stiffness": 1e4, "free_length": 0.01}]})
}

fn sweep(m: &ValidModel, params: &[&str], quantity: &str, tracked: usize) -> Sweep {
    let settings = SweepSettings {
        tracked_modes: tracked,
        ..SweepSettings::new(Quantity::parse(quantity).unwrap())
    };
    let specs: Vec<String> = params.iter().map(|s| s.to_string()).collect();
    Sweep::new(m, &specs, settings).unwrap()
}

fn complete(s: &Sweep) -> SweepDocument {
    s.run(None, Execution::Parallel, &|| {}).document()
}

fn results(d: &SweepDocument) -> Vec<f64> {
    d.points
        .iter()
        .map(|p| p.result.expect("a result"))
        .collect()
}

#[test]
fn first_bending_is_proportional_to_height() {
    // EI/(ρA) = E h²/(12ρ): f₁ ∝ h exactly, also for the discretized beam
    // (bending and axial motions of a straight beam decouple).
    let d = complete(&sweep(
        &model(&blade()),
        &["height=0.5e-3:2e-3:7"],
        "first_bending_hz",
        6,
    ));
    assert_eq!(d.failed_points, 0);
    let f = results(&d);
    let h = &d.parameters[0].values;
    let ratio0 = f[0] / h[0];
    for (fi, hi) in f.iter().zip(h) {
        let r = fi / hi;
        assert!(
            ((r - ratio0) / ratio0).abs() < 1e-9,
            "f₁/h = {r} vs {ratio0}"
        );
        // And the Euler–Bernoulli value (8 Hermite elements: +8.1e-5).
        let exact =
            BETA_L_FREE_1.powi(2) / (2.0 * PI * L * L) * (E * hi * hi / (12.0 * RHO)).sqrt();
        let err = (fi - exact) / exact;
        assert!(
            (0.0..2e-4).contains(&err),
            "h = {hi}: f₁ = {fi}, exact {exact}, error {err:e}"
        );
    }
}

#[test]
fn listed_values_are_swept_in_their_order() {
    // `height=V1,V2,…` (issue 34): the points are the values as listed,
    // f₁ ∝ h holds across them, and the values a range also holds give
    // that range's results to the bit.
    let listed = complete(&sweep(
        &model(&blade()),
        &["height=1.5e-3,0.5e-3,1.25e-3"],
        "first_bending_hz",
        6,
    ));
    assert_eq!(listed.parameters[0].values, vec![1.5e-3, 0.5e-3, 1.25e-3]);
    let f = results(&listed);
    for (fi, hi) in f.iter().zip(&listed.parameters[0].values) {
        let r = fi / hi / (f[0] / 1.5e-3);
        assert!(
            (r - 1.0).abs() < 1e-9,
            "h = {hi}: f₁/h off by {:e}",
            r - 1.0
        );
    }
    let range = complete(&sweep(
        &model(&blade()),
        &["height=0.5e-3:2e-3:7"],
        "first_bending_hz",
        6,
    ));
    // 0.5e-3 and 1.25e-3 are the range's 1st and 4th values.
    assert_eq!(f[1], results(&range)[0]);
    assert_eq!(f[2], results(&range)[3]);
}

#[test]
fn first_bending_scales_with_wave_speed_over_an_e_rho_grid() {
    let d = complete(&sweep(
        &model(&blade()),
        &[
            "blade.young=100e9:200e9:3",
            "beams[blade].material.density=7000:9000:4:log",
        ],
        "first_bending_hz",
        6,
    ));
    assert_eq!(d.points.len(), 12);
    let c = |p: &ancf_modal::analysis::sweep::PointRecord| {
        // Row-major: the first parameter (E) varies slowest.
        let (e, rho) = (p.values[0], p.values[1]);
        p.result.unwrap() / (e / rho).sqrt()
    };
    let c0 = c(&d.points[0]);
    for p in &d.points {
        assert!(
            ((c(p) - c0) / c0).abs() < 1e-9,
            "point {}: {} vs {c0}",
            p.index,
            c(p)
        );
    }
    assert_eq!(d.points[5].values, vec![150e9, d.parameters[1].values[1]]);
}

#[test]
fn tracked_modes_keep_their_identity_through_a_crossing() {
    let s = sweep(
        &model(&cantilever_and_oscillator()),
        &["springs[k].stiffness=1e4:4e6:25:log"],
        "frequency:1",
        3,
    );
    let d = complete(&s);
    assert_eq!(d.failed_points, 0);
    let k = &d.parameters[0].values;
    let tracked: Vec<Vec<f64>> = d
        .points
        .iter()
        .map(|p| {
            p.frequencies_hz
                .as_ref()
                .unwrap()
                .iter()
                .map(|f| f.unwrap())
                .collect()
        })
        .collect();
    for (i, p) in d.points.iter().enumerate() {
        // Mode 1 is the oscillator everywhere: √(k/m)/2π.
        let exact = (k[i] / MASS).sqrt() / (2.0 * PI);
        let f1 = tracked[i][0];
        assert!(
            ((f1 - exact) / exact).abs() < 1e-9,
            "k = {}: {f1} vs {exact}",
            k[i]
        );
        assert_eq!(p.result, Some(f1), "frequency:1 is tracked mode 1");
        // Modes 2 and 3 are the cantilever's, which the spring does not touch.
        for (j, (f, f0)) in tracked[i].iter().zip(&tracked[0]).enumerate().skip(1) {
            let rel = (f - f0) / f0;
            assert!(
                rel.abs() < 1e-9,
                "mode {} moved by {rel:e} at k = {}",
                j + 1,
                k[i]
            );
        }
        if i > 0 {
            for (j, mac) in p.mac.as_ref().unwrap().iter().enumerate() {
                let mac = mac.unwrap();
                assert!(mac >= 0.9, "point {i}, mode {}: MAC {mac}", j + 1);
            }
            assert!(tracked[i][0] > tracked[i - 1][0], "mode 1 rises with k");
        }
    }
    // The sorted order swaps: at the start the oscillator is the lowest
    // mode, at the end the highest of the three.
    let first = &tracked[0];
    let last = tracked.last().unwrap();
    assert!(first[0] < first[1] && first[1] < first[2], "{first:?}");
    assert!(last[1] < last[2] && last[2] < last[0], "{last:?}");
}

#[test]
fn serial_parallel_and_merged_shards_agree_exactly() {
    let s = sweep(
        &model(&cantilever_and_oscillator()),
        &[
            "springs[k].stiffness=1e4:4e6:8:log",
            "blade.height=1e-3:1.2e-3:3",
        ],
        "frequency:2",
        3,
    );
    let parallel = complete(&s);
    let serial = s.run(None, Execution::Serial, &|| {}).document();
    assert_eq!(parallel, serial);
    assert_eq!(
        serde_json::to_string(&parallel).unwrap(),
        serde_json::to_string(&serial).unwrap()
    );
    // Shards through their JSON text, as files carry them.
    let shards: Vec<(String, SweepDocument)> = (1..=3)
        .map(|k| {
            let doc = s
                .run(
                    Some(Shard { index: k, count: 3 }),
                    Execution::Parallel,
                    &|| {},
                )
                .document();
            assert!(doc.points.iter().all(|p| p.index % 3 == k - 1));
            let text = serde_json::to_string(&doc).unwrap();
            (
                format!("shard{k}.json"),
                serde_json::from_str(&text).unwrap(),
            )
        })
        .collect();
    let merged = merge(&shards).unwrap().document();
    assert_eq!(merged, parallel);
    // Refusals: a missing shard, a duplicate, another sweep.
    let err = merge(&shards[..2]).unwrap_err().to_string();
    assert!(
        err.contains("missing") && err.contains("shards 3 of 3"),
        "{err}"
    );
    let dup = vec![shards[0].clone(), shards[0].clone()];
    assert!(merge(&dup)
        .unwrap_err()
        .to_string()
        .contains("point 0 is in shard1.json and again"));
    let other = sweep(
        &model(&cantilever_and_oscillator()),
        &[
            "springs[k].stiffness=1e4:4e6:8:log",
            "blade.height=1e-3:1.3e-3:3",
        ],
        "frequency:2",
        3,
    );
    let foreign = other
        .run(
            Some(Shard { index: 3, count: 3 }),
            Execution::Serial,
            &|| {},
        )
        .document();
    let mixed = vec![
        shards[0].clone(),
        shards[1].clone(),
        ("other.json".into(), foreign),
    ];
    let err = merge(&mixed).unwrap_err().to_string();
    assert!(
        err.contains("other.json belongs to a different sweep"),
        "{err}"
    );
}

#[test]
fn a_failing_point_is_recorded_and_the_sweep_goes_on() {
    let d = complete(&sweep(
        &model(&blade()),
        &["height=-1e-3:1e-3:3"],
        "first_bending_hz",
        6,
    ));
    assert_eq!(d.failed_points, 2);
    assert!(d.points[0]
        .error
        .as_deref()
        .unwrap()
        .contains("beams[0].section.height: must be positive"));
    assert_eq!(d.points[0].result, None);
    assert!(d.points[2].result.unwrap() > 0.0);
    assert_eq!(d.points[2].error, None);
}

// ------------------------------------------------------------------ CLI

fn write(dir: &Path, name: &str, v: &Value) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, v.to_string()).unwrap();
    p
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = cargo_bin_cmd!("ancf-modal").args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn cli_merge_of_three_shards_prints_the_single_run() {
    let dir = tempfile::tempdir().unwrap();
    let m = write(dir.path(), "crossing.json", &cantilever_and_oscillator());
    let m = m.to_str().unwrap();
    let base = [
        "sweep",
        m,
        "--param",
        "springs[k].stiffness=1e4:4e6:7:log",
        "--quantity",
        "frequency:1",
        "--modes",
        "3",
    ];
    let (code, single, stderr) = run(&[&base[..], &["--json"]].concat());
    assert_eq!(code, 0, "{stderr}");
    let mut files = Vec::new();
    for k in 1..=3 {
        let shard = format!("{k}/3");
        let (code, out, stderr) = run(&[&base[..], &["--json", "--shard", &shard]].concat());
        assert_eq!(code, 0, "{stderr}");
        let f = dir.path().join(format!("s{k}.json"));
        std::fs::write(&f, out).unwrap();
        files.push(f.to_str().unwrap().to_string());
    }
    let csv = dir.path().join("merged.csv");
    let svg = dir.path().join("campbell.svg");
    let mut merge_args = vec!["sweep-merge"];
    merge_args.extend(files.iter().map(String::as_str));
    merge_args.extend([
        "--json",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]);
    let (code, merged, stderr) = run(&merge_args);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(merged, single, "the merged document is the single run's");
    let v: Value = serde_json::from_str(&single).unwrap();
    for key in [
        "model",
        "quantity",
        "sweep_id",
        "total_points",
        "parameters",
        "points",
    ] {
        assert!(v.get(key).is_some(), "key {key}");
    }
    assert_eq!(v["total_points"], 7);
    // Provenance: this build and the SHA-256 of the model file's bytes.
    use sha2::Digest;
    let sha: String = sha2::Sha256::digest(std::fs::read(m).unwrap())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert_eq!(v["model_sha256"], sha.as_str());
    assert_eq!(v["tool_version"], env!("CARGO_PKG_VERSION"));
    let csv = std::fs::read_to_string(csv).unwrap();
    assert_eq!(csv.lines().count(), 8);
    assert!(csv
        .starts_with("index,springs[k].stiffness,frequency:1,mode_1_hz,mode_2_hz,mode_3_hz,error"));
    let svg = std::fs::read_to_string(svg).unwrap();
    roxmltree::Document::parse(&svg).expect("valid SVG");
    assert!(svg.contains("mode 1 (frequency:1)"));
    // Threads do not change the result.
    let (code, serial, _) = run(&[&base[..], &["--json", "--threads", "1"]].concat());
    assert_eq!(code, 0);
    assert_eq!(serial, single);
}

#[test]
fn cli_grid_heat_map_and_failed_points() {
    let dir = tempfile::tempdir().unwrap();
    let m = write(dir.path(), "blade.json", &blade());
    let png = dir.path().join("map.png");
    let (code, out, stderr) = run(&[
        "sweep",
        m.to_str().unwrap(),
        "--param",
        "young=100e9:200e9:4",
        "--param",
        "height=-1e-3:2e-3:4",
        "--quantity",
        "first_bending_hz",
        "--json",
        "--plot",
        png.to_str().unwrap(),
    ]);
    // height −1 mm and 0 fail: 8 of 16 points; everything is still written.
    assert_eq!(code, 1, "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("Error: 8 of 16 points failed"),
        "{stderr}"
    );
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["points"].as_array().unwrap().len(), 16);
    assert!(v["points"][0]["error"]
        .as_str()
        .unwrap()
        .contains("must be positive"));
    assert!(v["points"][3]["result"].as_f64().unwrap() > 0.0);
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

#[test]
fn cli_bad_flags_are_one_line_errors_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let a = write(dir.path(), "s1.json", &json!({"not": "a sweep"}));
    let cases: &[(&[&str], &str)] = &[
        (&["sweep", "--param", "height=1e-3:2e-3", "--quantity", "first_bending_hz"], "--param: `height=1e-3:2e-3` is not NAME=LO:HI:N[:log]"),
        (&["sweep", "--param", "height", "--quantity", "first_bending_hz"], "--param: `height` is not NAME=LO:HI:N"),
        (&["sweep", "--param", "height=1e-3:2e-3:0", "--quantity", "first_bending_hz"], "--param: `height=1e-3:2e-3:0`: the number of values"),
        (&["sweep", "--param", "beams[blade].colour=1:2:3", "--quantity", "first_bending_hz"], "--param: `beams[blade].colour`: `beams[0].colour` cannot take a number"),
        (&["sweep", "--param", "beams[wing].section.height=1:2:3", "--quantity", "first_bending_hz"], "--param: `beams[wing].section.height`: the model has no `beams[wing]` (there: [blade])"),
        (&["sweep", "--param", "colour=1:2:3", "--quantity", "first_bending_hz"], "--param: unknown parameter `colour`"),
        (&["sweep", "--param", "load_scale:nope=0:1:3", "--quantity", "first_bending_hz"], "--param: `load_scale:nope`: the model has no load `nope`"),
        (&["sweep", "--param", "height=1e-3:2e-3:3", "--quantity", "peak"], "--quantity: unknown quantity `peak`; available: first_bending_hz, frequency:K"),
        (&["sweep", "--param", "height=1e-3:2e-3:3"], "--quantity is required"),
        (&["sweep", "--param", "height=1e-3:2e-3:3", "--quantity", "first_bending_hz", "--shard", "4/3"], "--shard: `4/3`: the shard must be K/N"),
        (&["sweep", "--param", "height=1e-3:2e-3:3", "--quantity", "first_bending_hz", "--shard", "0/3"], "--shard: `0/3`"),
        (&["sweep", "--param", "height=1e-3:2e-3:3", "--quantity", "first_bending_hz", "--plot", "x.pdf"], "--plot: x.pdf: unknown plot format"),
        (&["sweep-merge", a.to_str().unwrap()], "not a sweep document"),
    ];
    for (args, expected) in cases {
        let (code, out, stderr) = run(args);
        assert_eq!(code, 1, "{args:?}: {stderr}");
        assert!(out.is_empty(), "{args:?}: {out}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(
            stderr.starts_with("Error: ") && stderr.contains(expected),
            "{args:?}: expected `{expected}` in {stderr}"
        );
    }
}

/// Fig. 10's first panel: a larger pre-stress (the released F_x² and the
/// spring's preload, scaled together; the contact force follows from the
/// ON-state balance) opens the contact faster.
#[test]
fn switch_off_time_falls_with_rising_prestress() {
    let m = Model::switch_off_builtin();
    let s = sweep(
        &m,
        &["load_scale:F_x2,helical_spring=1:2:3"],
        "time_to_distance_s",
        1,
    );
    let t = results(&complete(&s));
    assert_eq!(t.len(), 3);
    assert!(
        t[1] < t[0] && t[2] < t[1],
        "time to 2 mm falls with the pre-stress: {t:?}"
    );
}

/// A one-parameter switch-off sweep carries node 0's x(t) per point
/// (Fig. 10's panels): each trace crosses the 2 mm line at the point's
/// time to distance, the merge of shards keeps the traces, and the plot
/// draws one line per point; a two-parameter grid carries none.
#[test]
fn switch_off_sweeps_carry_node0_traces_that_cross_2_mm_at_their_time() {
    let m = Model::switch_off_builtin();
    let s = sweep(
        &m,
        &["joints[hybrid].torsion_stiffness=2:8:3"],
        "time_to_distance_s",
        1,
    );
    let d = complete(&s);
    for p in &d.points {
        let trace = p
            .node0
            .as_ref()
            .expect("a 1-D switch-off sweep keeps node 0");
        let t = p.result.expect("2 mm reached");
        assert_eq!(trace.time_s.len(), trace.x_m.len());
        // Linear interpolation of the 67.2 kHz samples at the reported time.
        let k = trace.time_s.iter().position(|&s| s > t).unwrap();
        let (t0, t1) = (trace.time_s[k - 1], trace.time_s[k]);
        let x = trace.x_m[k - 1] + (t - t0) / (t1 - t0) * (trace.x_m[k] - trace.x_m[k - 1]);
        let travel = x - trace.x_m[0];
        // Between samples 15 µs apart the interpolation's error is about
        // ẍΔt²/8, ẍΔt² the trace's second difference there (large where
        // the pin strikes its slot): twice that, and 1e-7 m.
        let second = |j: usize| (trace.x_m[j + 1] - 2.0 * trace.x_m[j] + trace.x_m[j - 1]).abs();
        let bound = 2.0 * second(k - 1).max(second(k)) / 8.0 + 1e-7;
        assert!(
            (travel - 2e-3).abs() < bound,
            "point {}: node 0 travelled {travel:.6e} m at its time {t:.6e} s, not 2 mm",
            p.index
        );
    }
    let shards: Vec<(String, SweepDocument)> = (1..=2)
        .map(|k| {
            let shard = Shard::parse(&format!("{k}/2")).unwrap();
            let doc = s.run(Some(shard), Execution::Parallel, &|| {}).document();
            (format!("shard {k}"), doc)
        })
        .collect();
    assert_eq!(merge(&shards).unwrap().document(), d, "merged = single run");
    let svg = ancf_modal::output::plot::render(
        &ancf_modal::output::figures::sweep::sweep_figure(&d).unwrap(),
        ancf_modal::output::plot::Format::Svg,
        ancf_modal::output::plot::PlotSize::default(),
    )
    .unwrap();
    let svg = String::from_utf8(svg).unwrap();
    for p in &d.points {
        let label = format!("{:.3} ms", p.result.unwrap() * 1e3);
        assert!(svg.contains(&label), "legend entry `{label}` missing");
    }
    let grid = sweep(
        &m,
        &[
            "joints[hybrid].torsion_stiffness=2:8:2",
            "load_scale:F_x2,helical_spring=1:1.5:2",
        ],
        "time_to_distance_s",
        1,
    );
    let g = complete(&grid);
    assert!(g
        .points
        .iter()
        .all(|p| p.node0.is_none() && p.result.is_some()));
}

#[test]
fn a_model_warning_is_given_once_and_a_point_says_only_what_its_values_add() {
    // The blade's height typed as 1.1 (millimetres meant): the model warns
    // of height/length = 44 once, not again at each of the three points.
    let dir = tempfile::tempdir().unwrap();
    let mut thick = blade();
    thick["beams"][0]["section"]["height"] = json!(1.1);
    let m = write(dir.path(), "thick.json", &thick);
    let args = [
        "sweep",
        m.to_str().unwrap(),
        "--param",
        "beams[blade].material.young=1e11:2e11:3",
        "--quantity",
        "first_bending_hz",
    ];
    let (code, _, stderr) = run(&args);
    assert_eq!(code, 0, "{stderr}");
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(
        lines.iter().filter(|l| l.contains("height/length")).count(),
        1,
        "{stderr}"
    );
    assert!(!stderr.contains("point "), "{stderr}");
    // A sweep whose last value makes the height suspicious says so for
    // that point alone.
    let m = write(dir.path(), "blade.json", &blade());
    let args = [
        "sweep",
        m.to_str().unwrap(),
        "--param",
        "beams[blade].section.height=1.1e-3:1.1:2",
        "--quantity",
        "first_bending_hz",
    ];
    let (code, _, stderr) = run(&args);
    assert_eq!(code, 0, "{stderr}");
    let points: Vec<&str> = stderr
        .lines()
        .filter(|l| l.contains("height/length"))
        .collect();
    assert_eq!(points.len(), 1, "{stderr}");
    assert!(points[0].contains("point 1: "), "{stderr}");
}
