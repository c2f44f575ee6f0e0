//! The stages of the dense generalized eigen-solve on the built-in
//! assembly's reduced matrices (40 coordinates, 12 modes), each timed alone,
//! to show where the time of `modal` goes.
//!
//! Stages 1–3 are the envelope kernels (used above 64 coordinates or on
//! CPUs without AVX2); stage 1–3 together, as `solve_generalized` runs them
//! on this CPU (the windowed kernels on AVX2/AVX-512 up to 64
//! coordinates), is timed as "0".
//! Run: `cargo bench --bench eigen_stages`.

use ancf_modal::analysis::eigen::{tridiagonal_form, Cholesky};
use ancf_modal::analysis::small_eigen::{
    tridiagonal_eigenvectors, HouseholderTridiagonal, SturmCounts,
};
use ancf_modal::analysis::ReducedProblem;
use ancf_modal::{Model, System};
use criterion::{criterion_group, criterion_main, Criterion};

const MODES: usize = 12;

fn bench(c: &mut Criterion) {
    let system = System::new(&Model::builtin());
    let reduced = ReducedProblem::new(&system, &system.reference()).unwrap();
    let (kr, mr) = (&reduced.stiffness, &reduced.mass);
    let d = reduced.null_space.dim();

    let mut g = c.benchmark_group("eigen stages (built-in assembly, 40 x 40, 12 modes)");
    g.bench_function(
        "0 M = LL^T, C = L^-1 K_r L^-T and T, as solve_generalized",
        |b| b.iter(|| tridiagonal_form(kr, mr).unwrap()),
    );
    g.bench_function("1 Cholesky of M_r", |b| {
        b.iter(|| Cholesky::factor(mr).unwrap())
    });
    let l = Cholesky::factor(mr).unwrap();
    g.bench_function("2 C = L^-1 K_r L^-T", |b| b.iter(|| l.reduce(kr)));
    let cmat = l.reduce(kr);
    g.bench_function("3 Householder tridiagonalization", |b| {
        b.iter(|| HouseholderTridiagonal::new(cmat.clone(), d))
    });
    let h = HouseholderTridiagonal::new(cmat.clone(), d);
    g.bench_function("4 bisection: lowest 12 and the largest", |b| {
        b.iter(|| SturmCounts::new(&h.t).unwrap().lowest_and_largest(MODES))
    });
    let (values, _) = SturmCounts::new(&h.t).unwrap().lowest_and_largest(MODES);
    g.bench_function("5 inverse iteration, 12 vectors", |b| {
        b.iter(|| tridiagonal_eigenvectors(&h.t, &values).unwrap())
    });
    let y = tridiagonal_eigenvectors(&h.t, &values).unwrap();
    g.bench_function("6 back-transformation Q y", |b| {
        b.iter(|| {
            let mut v = y.clone();
            h.apply_q(&mut v, MODES);
            v
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
