//! The impulse experiment: 100 ms at h = 1 µs (100 000 steps) on the
//! built-in assembly, and the same at larger steps. Run:
//! `cargo bench --bench impulse`.

use ancf_modal::analysis::impulse::{run_impulse, ImpulseSettings};
use ancf_modal::Model;
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let model = Model::builtin();
    let mut group = c.benchmark_group("impulse");
    group.sample_size(10);
    for step in [1e-6, 5e-6] {
        let mut settings = ImpulseSettings::default();
        settings.transient.step = step;
        group.bench_function(format!("default model, 100 ms at h = {step:e} s"), |b| {
            b.iter(|| run_impulse(&model, &settings, &mut |_| {}).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
