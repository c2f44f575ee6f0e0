//! `transient --uff`: the run's sensors and time-varying loads as UFF 58
//! time data. Read back with the UFF reader: one dataset per load and
//! sensor, the sample grid of the run (t₀ = 0, Δt = 1/f_s to the 6 digits
//! UFF 58 record 7 holds), the sensor
//! samples equal to the `--csv` samples of the same run (CSV: 10
//! significant digits), the forces equal to the model's |F₀|·f(t).

mod common;
use ancf_modal::measured::uff::d58::SpecDataType;
use ancf_modal::measured::uff::read_functions;
use assert_cmd::Command;
use common::run_ok;
use std::f64::consts::PI;
use std::ffi::OsString;
use std::path::Path;

fn run(model: &str, dir: &Path) -> (Vec<ancf_modal::measured::uff::Function>, Vec<Vec<f64>>) {
    let uff = dir.join("run.uff");
    let csv = dir.join("run.csv");
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models")
        .join(model);
    let mut args: Vec<OsString> = vec!["transient".into(), path.into()];
    args.extend(["--end-time", "0.002", "--uff"].map(OsString::from));
    args.extend([uff.clone().into(), "--csv".into(), csv.clone().into()]);
    run_ok(args);
    let text = std::fs::read_to_string(&uff).unwrap();
    let functions = read_functions(&uff, &text).unwrap();
    let rows: Vec<Vec<f64>> = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    (functions, rows)
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs() + 1e-12 * scale
}

#[test]
fn sensors_and_forces_read_back() {
    let dir = tempfile::tempdir().unwrap();
    // Cantilever: a 0.1 N step load at t = 0 and a tip displacement sensor;
    // free beam: a 4 N half-sine of 0.1 ms and a tip velocity sensor.
    for (model, force) in [
        (
            "cantilever.json",
            (|t: f64| if t >= 0.0 { 0.1 } else { 0.0 }) as fn(f64) -> f64,
        ),
        ("beam_free_free.json", |t: f64| {
            if t <= 1e-4 {
                4.0 * (PI * t / 1e-4).sin()
            } else {
                0.0
            }
        }),
    ] {
        let (f, rows) = run(model, dir.path());
        assert_eq!(f.len(), 2, "{model}: one force and one sensor dataset");
        assert_eq!(f[0].ordinate_type, SpecDataType::FORCE);
        let n = rows.len();
        for g in &f {
            assert_eq!(g.ordinate.len(), n, "{model}: {} samples", g.id[0]);
            assert!(g.even && g.x_min == 0.0);
            // Record 7 writes Δx as %13.5e: 6 significant digits, rounding ≤ 5e-6.
            assert!(((g.dx - 1.0 / 51_200.0) * 51_200.0).abs() <= 5e-6);
        }
        let forces = f[0].ordinate.real_parts();
        let sensor = f[1].ordinate.real_parts();
        let scale = sensor.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, row) in rows.iter().enumerate() {
            let t = f[0].x_min + k as f64 * f[0].dx;
            assert!(
                (t - row[0]).abs() <= 5e-6 * row[0] + 1e-15,
                "{model}: time {t} vs CSV {}",
                row[0]
            );
            assert!(
                close(sensor[k], row[1], scale),
                "{model}: sample {k}: UFF {} vs CSV {}",
                sensor[k],
                row[1]
            );
            assert!(
                (forces[k] - force(row[0])).abs() <= 1e-10 * 4.0,
                "{model}: force at {} s: {} vs {}",
                row[0],
                forces[k],
                force(row[0])
            );
        }
    }
}

#[test]
fn uff_without_a_sample_rate_is_a_one_line_error() {
    let dir = tempfile::tempdir().unwrap();
    let uff = dir.path().join("run.uff");
    let out = Command::cargo_bin("ancf-modal")
        .unwrap()
        .arg("transient")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("models/cantilever.json"))
        .args(["--end-time", "0.001", "--sample-rate", "0", "--uff"])
        .arg(&uff)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("Error: ") && stderr.contains("--sample-rate"));
    assert!(!uff.exists());
}
