//! Dense against sparse factorization of the integrator's iteration matrix:
//! the cantilever of `models/cantilever.json` (tip step load) meshed with
//! more and more elements, 2000 steps of 1 µs on each path. Where the sparse
//! path overtakes the dense one is `transient::SPARSE_THRESHOLD`. Run:
//! `cargo bench --bench transient_solver`.

use ancf_modal::analysis::transient::{Integrator, LinearSolver, TransientSettings};
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

fn cantilever(elements: usize) -> ValidModel {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/models/cantilever.json");
    let mut model = Model::from_file(std::path::Path::new(path))
        .unwrap()
        .into_model();
    model.beams[0].elements = elements;
    model.validated().unwrap()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("transient solver");
    group.sample_size(10);
    for elements in [8, 24, 28, 32, 40, 64, 96] {
        let sys = System::new(&cantilever(elements));
        let unknowns = sys.ndof() + sys.constraint_count();
        for (name, solver) in [
            ("dense", LinearSolver::Dense),
            ("sparse", LinearSolver::Sparse),
        ] {
            let settings = TransientSettings {
                step: 1e-6,
                end_time: 2000e-6,
                solver,
                ..TransientSettings::default()
            };
            group.bench_function(BenchmarkId::new(name, unknowns), |b| {
                b.iter(|| {
                    let mut integ = Integrator::new(&sys, settings).unwrap();
                    let mut st = integ.initial_state().unwrap();
                    integ.run(&mut st, |_| {}).unwrap()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
