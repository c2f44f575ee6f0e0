//! Parameter-study speed: 1,000 modal points of the built-in assembly
//! (first bending frequency over the blade height), and a 12 × 12 grid
//! (height × Young's modulus) of tracked frequencies, on all cores and on
//! one. Run: `cargo bench --bench sweep`.
//!
//! The CPU use of a parallel sweep (CPU time / wall time, ≥ 1.5 on two
//! cores) is measured on the command line, e.g.
//! `/usr/bin/time -f '%e s wall, %U+%S s CPU' ancf-modal sweep --param
//! height=0.9e-3:1.3e-3:1000 --quantity first_bending_hz > /dev/null`.

use ancf_modal::analysis::sweep::{Execution, Quantity, Sweep, SweepSettings};
use ancf_modal::Model;
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let model = Model::builtin();
    let points = Sweep::new(
        &model,
        &[String::from("height=0.9e-3:1.3e-3:1000")],
        SweepSettings::new(Quantity::FirstBendingHz),
    )
    .unwrap();
    let grid = Sweep::new(
        &model,
        &[
            String::from("height=0.9e-3:1.3e-3:12"),
            String::from("young=100e9:150e9:12"),
        ],
        SweepSettings::new(Quantity::Frequency { mode: 1 }),
    )
    .unwrap();
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10);
    g.bench_function("1000 points, first_bending_hz, parallel", |b| {
        b.iter(|| points.run(None, Execution::Parallel, &|| {}))
    });
    g.bench_function("1000 points, first_bending_hz, serial", |b| {
        b.iter(|| points.run(None, Execution::Serial, &|| {}))
    });
    g.bench_function("12x12 grid, frequency:1 tracked, parallel", |b| {
        b.iter(|| grid.run(None, Execution::Parallel, &|| {}).document())
    });
    g.bench_function("12x12 grid, frequency:1 tracked, serial", |b| {
        b.iter(|| grid.run(None, Execution::Serial, &|| {}).document())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
