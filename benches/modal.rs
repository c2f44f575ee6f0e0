//! Modal analysis speed: the built-in paper assembly, the bare 8-element
//! blade (the case Exudyn's dense eigen call is quoted for) and a
//! 500-element beam.
//! Run: `cargo bench --bench modal`.
//!
//! For the built-in assembly the generalized eigen-solve alone (reduced K
//! and M given, 12 modes) is timed too, to show its share of the modal call.

use ancf_modal::analysis::eigen::solve_generalized;
use ancf_modal::analysis::{modal_at_reference, ModalSettings, ReducedProblem};
use ancf_modal::error::Source;
use ancf_modal::{Model, System};
use criterion::{criterion_group, criterion_main, Criterion};

fn beam(elements: usize) -> Model {
    let json = format!(
        r#"{{"name": "beam", "beams": [{{"id": "b", "start": [0, 0], "angle_deg": 0, "length": 0.025,
        "elements": {elements}, "section": {{"height": 1.1e-3, "width": 5.2e-3}},
        "material": {{"young": 127e9, "density": 8940}}}}]}}"#
    );
    Model::from_json(&json, Source::BuiltIn).unwrap()
}

fn bench(c: &mut Criterion) {
    let model = Model::builtin();
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(12),
        ..ModalSettings::default()
    };
    c.bench_function("modal: default model (assembled system)", |b| {
        b.iter(|| modal_at_reference(&system, &settings).unwrap())
    });
    c.bench_function("modal: default model (from parsed model)", |b| {
        b.iter(|| modal_at_reference(&System::new(&model), &settings).unwrap())
    });
    let reduced = ReducedProblem::new(&system, &system.reference()).unwrap();
    let (kr, mr) = (&reduced.stiffness, &reduced.mass);
    c.bench_function("modal: default model, eigen-solve only (12 of 40)", |b| {
        b.iter(|| solve_generalized(kr, mr, 12).unwrap())
    });
    // The bare 8-element blade, free-free: Exudyn's dense-call comparison case.
    let bare = System::new(&beam(8));
    c.bench_function(
        "modal: bare 8-element beam (36 coordinates, 12 modes)",
        |b| b.iter(|| modal_at_reference(&bare, &settings).unwrap()),
    );
    let all = ModalSettings {
        modes: None,
        ..settings
    };
    c.bench_function("modal: bare 8-element beam, all 36 modes", |b| {
        b.iter(|| modal_at_reference(&bare, &all).unwrap())
    });
    let big = System::new(&beam(500));
    let mut group = c.benchmark_group("large");
    group.sample_size(10);
    group.bench_function("modal: 500-element beam (2004 coordinates)", |b| {
        b.iter(|| modal_at_reference(&big, &settings).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
