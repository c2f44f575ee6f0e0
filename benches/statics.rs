//! Speed of the pre-stress analysis on `models/rcbo_prestressed.json`
//! (target: equilibrium + pre-stressed modal ≤ 5 ms).

use ancf_modal::analysis::prestress::{modal_at_equilibrium, prestressed_modal};
use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::analysis::ModalSettings;
use ancf_modal::{Model, System};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::path::Path;

fn bench(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/rcbo_prestressed.json");
    let model = Model::from_file(&path).expect("models/rcbo_prestressed.json is valid");
    let system = System::new(&model);
    let statics = StaticSettings::default();
    let modal = ModalSettings::default();
    c.bench_function("equilibrium (rcbo_prestressed)", |b| {
        b.iter(|| solve_equilibrium(black_box(&system), &statics).unwrap())
    });
    c.bench_function("equilibrium + pre-stressed modal (rcbo_prestressed)", |b| {
        b.iter(|| {
            let eq = solve_equilibrium(black_box(&system), &statics).unwrap();
            modal_at_equilibrium(&system, &eq, &modal).unwrap()
        })
    });
    c.bench_function(
        "model → equilibrium + pre-stressed and unstressed modal (rcbo_prestressed)",
        |b| {
            b.iter(|| {
                let system = System::new(black_box(&model));
                prestressed_modal(&system, &statics, &modal).unwrap()
            })
        },
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
