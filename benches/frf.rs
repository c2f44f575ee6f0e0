//! Speed of `frf` (issue 17 target: five 0.2 s hammer records at 51.2 kHz
//! → H1, H2, coherence and the modal fit ≤ 50 ms). The records (two modes,
//! a half-sine pulse, noise-free) are made here; CSV parsing is measured
//! separately.

use ancf_modal::measured::analysis::{analyse, AnalysisSettings};
use ancf_modal::measured::csv::parse_csv;
use ancf_modal::measured::{Channels, Measurement, TimeRecord};
use ancf_modal::signal::Window;
use criterion::{criterion_group, criterion_main, Criterion};
use std::f64::consts::PI;
use std::fmt::Write;
use std::hint::black_box;
use std::path::PathBuf;

const FS: f64 = 51_200.0;
const N: usize = 10_240; // 0.2 s

fn record(i: usize) -> TimeRecord {
    let force: Vec<f64> = (0..N)
        .map(|k| {
            let t = k as f64 / FS - 1e-4;
            if (0.0..=1e-4).contains(&t) {
                4.0 * (PI * t / 1e-4).sin() * (1.0 + 0.05 * i as f64)
            } else {
                0.0
            }
        })
        .collect();
    // Two modes by exact recursion (impulse invariance).
    let mut response = vec![0.0; N];
    for (f, z) in [(4_600.0, 0.004), (11_500.0, 0.006)] {
        let (w, t) = (2.0 * PI * f, 1.0 / FS);
        let wd = w * (1.0f64 - z * z).sqrt();
        let e = (-z * w * t).exp();
        let (a1, a2, b1) = (
            2.0 * e * (wd * t).cos(),
            -e * e,
            t * e * (wd * t).sin() / wd,
        );
        let (mut y1, mut y2, mut x1) = (0.0, 0.0, 0.0);
        for k in 0..N {
            let v = a1 * y1 + a2 * y2 + b1 * x1;
            response[k] += v;
            y2 = y1;
            y1 = v;
            x1 = force[k];
        }
    }
    TimeRecord {
        file: PathBuf::from(format!("hit{i}.csv")),
        sample_rate_hz: FS,
        force,
        response,
        force_label: "force".into(),
        response_label: "velocity".into(),
        lines: (2..N + 2).collect(),
    }
}

fn bench(c: &mut Criterion) {
    let records: Vec<TimeRecord> = (0..5).map(record).collect();
    let settings = AnalysisSettings {
        window: Window::Force { fraction: 0.01 },
        ..AnalysisSettings::default()
    };
    c.bench_function(
        "frf: 5 × 0.2 s at 51.2 kHz → H1/H2/γ² + LSCF fit",
        |b| {
            b.iter(|| {
                let m: Vec<Measurement> = records.iter().cloned().map(Measurement::Time).collect();
                analyse(black_box(m), settings).unwrap()
            })
        },
    );
    let mut text = String::from("time,force,velocity\n");
    let r = &records[0];
    for k in 0..N {
        let _ = writeln!(
            text,
            "{:.9e},{:.9e},{:.9e}",
            k as f64 / FS,
            r.force[k],
            r.response[k]
        );
    }
    c.bench_function("frf: parse one 0.2 s CSV record", |b| {
        b.iter(|| parse_csv(&r.file, black_box(&text), &Channels::default()).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
