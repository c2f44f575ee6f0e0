//! Switch-off speed: the built-in assembly, equilibrium + release + 3 ms,
//! flexible and rigid (`switch-off --compare-rigid --no-step-check`).
//! Run: `cargo bench --bench switch_off`.

use ancf_modal::analysis::switch_off::{run_switch_off, SwitchOffSettings};
use ancf_modal::Model;
use criterion::{criterion_group, criterion_main, Criterion};

fn bench(c: &mut Criterion) {
    let model = Model::switch_off_builtin();
    let settings = SwitchOffSettings {
        compare_rigid: true,
        ..SwitchOffSettings::default()
    };
    let mut group = c.benchmark_group("switch-off");
    group.sample_size(20);
    group.bench_function("built-in, flexible + rigid, 3 ms each", |b| {
        b.iter(|| run_switch_off(&model, &settings).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
