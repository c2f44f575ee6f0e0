//! Modal analysis speed: the built-in paper assembly, the bare 8-element
//! blade (the case Exudyn's dense eigen call is quoted for), a 2,000-element
//! cantilever (sparse path, lowest 10 modes) and free ladder frames of
//! welded beams from 1k to 100k elements.
//! Run: `cargo bench --bench modal`.

use ancf_modal::analysis::{modal_at_reference, ModalSettings};
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

fn cantilever(elements: usize) -> Model {
    let json = format!(
        r#"{{"name": "cantilever", "beams": [{{"id": "b", "start": [0, 0], "angle_deg": 0, "length": 0.025,
        "elements": {elements}, "section": {{"height": 1.1e-3, "width": 5.2e-3}},
        "material": {{"young": 127e9, "density": 8940}}}}],
        "joints": [{{"type": "weld", "a": {{"ground": [0, 0]}}, "b": {{"beam": "b", "s": 0}}}}]}}"#
    );
    Model::from_json(&json, Source::BuiltIn).unwrap()
}

/// Two rails (2 elements per rung spacing each, plus a node at every weld)
/// and `rungs` one-element rungs welded between them: 5 elements and 2
/// welds per rung.
pub fn ladder(rungs: usize) -> Model {
    let (span, gap) = (0.02, 0.01);
    let len = span * rungs as f64;
    let sec = r#""section": {"height": 1e-3, "width": 5e-3}, "material": {"young": 127e9, "density": 8940}"#;
    let mut beams = vec![
        format!(
            r#"{{"id": "r0", "start": [0, 0], "angle_deg": 0, "length": {len}, "elements": {}, {sec}}}"#,
            2 * rungs
        ),
        format!(
            r#"{{"id": "r1", "start": [0, {gap}], "angle_deg": 0, "length": {len}, "elements": {}, {sec}}}"#,
            2 * rungs
        ),
    ];
    let mut joints = Vec::new();
    for k in 0..rungs {
        let s = span * (k as f64 + 0.5);
        beams.push(format!(r#"{{"id": "g{k}", "start": [{s}, 0], "angle_deg": 90, "length": {gap}, "elements": 1, {sec}}}"#));
        joints.push(format!(r#"{{"type": "weld", "a": {{"beam": "r0", "s": {s}}}, "b": {{"beam": "g{k}", "s": 0}}}}"#));
        joints.push(format!(r#"{{"type": "weld", "a": {{"beam": "r1", "s": {s}}}, "b": {{"beam": "g{k}", "s": {gap}}}}}"#));
    }
    let json = format!(
        r#"{{"name": "ladder", "beams": [{}], "joints": [{}]}}"#,
        beams.join(","),
        joints.join(",")
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
    let ten = ModalSettings {
        modes: Some(10),
        ..settings
    };
    let mut group = c.benchmark_group("large");
    group.sample_size(10);
    let cantilever = cantilever(2000);
    group.bench_function(
        "modal: 2000-element cantilever, 10 modes (from parsed model)",
        |b| b.iter(|| modal_at_reference(&System::new(&cantilever), &ten).unwrap()),
    );
    for rungs in [100, 1000, 10_000] {
        let frame = ladder(rungs);
        let elements = 5 * rungs;
        group.bench_function(
            format!("modal: free ladder frame, {elements} elements, 10 modes"),
            |b| b.iter(|| modal_at_reference(&System::new(&frame), &ten).unwrap()),
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
