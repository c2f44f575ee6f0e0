//! Modal analysis speed: the built-in paper assembly, the bare 8-element
//! blade (the case Exudyn's dense eigen call is quoted for), a 2,000-element
//! cantilever (sparse path, lowest 10 modes), free square grids of
//! welded beams of 1k and 10k elements, and issue 37's 1 m steel
//! cantilever at 10k to 100k elements (12 modes).
//! Run: `cargo bench --bench modal`.

use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::error::Source;
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};
use criterion::{criterion_group, criterion_main, Criterion};

fn beam(elements: usize) -> ValidModel {
    let json = format!(
        r#"{{"name": "beam", "beams": [{{"id": "b", "start": [0, 0], "angle_deg": 0, "length": 0.025,
        "elements": {elements}, "section": {{"height": 1.1e-3, "width": 5.2e-3}},
        "material": {{"young": 127e9, "density": 8940}}}}]}}"#
    );
    Model::from_json(&json, Source::BuiltIn).unwrap()
}

fn cantilever(elements: usize) -> ValidModel {
    let json = format!(
        r#"{{"name": "cantilever", "beams": [{{"id": "b", "start": [0, 0], "angle_deg": 0, "length": 0.025,
        "elements": {elements}, "section": {{"height": 1.1e-3, "width": 5.2e-3}},
        "material": {{"young": 127e9, "density": 8940}}}}],
        "joints": [{{"type": "weld", "a": {{"ground": [0, 0]}}, "b": {{"beam": "b", "s": 0}}}}]}}"#
    );
    Model::from_json(&json, Source::BuiltIn).unwrap()
}

/// `k` horizontal and `k` vertical steel beams of 1 m, `e` elements each,
/// welded at all k² crossings (the README's scaling table).
pub fn grid(k: usize, e: usize) -> ValidModel {
    let step = 1.0 / (k - 1) as f64;
    let sec = r#""section": {"height": 5e-3, "width": 5e-3}, "material": {"young": 210e9, "density": 7850}"#;
    let mut beams = Vec::new();
    let mut joints = Vec::new();
    for i in 0..k {
        let y = i as f64 * step;
        beams.push(format!(r#"{{"id": "h{i}", "start": [0, {y}], "angle_deg": 0, "length": 1, "elements": {e}, {sec}}}"#));
        beams.push(format!(r#"{{"id": "v{i}", "start": [{y}, 0], "angle_deg": 90, "length": 1, "elements": {e}, {sec}}}"#));
    }
    for i in 0..k {
        for j in 0..k {
            let (si, sj) = (i as f64 * step, j as f64 * step);
            joints.push(format!(r#"{{"type": "weld", "a": {{"beam": "h{i}", "s": {sj}}}, "b": {{"beam": "v{j}", "s": {si}}}}}"#));
        }
    }
    let json = format!(
        r#"{{"name": "grid", "beams": [{}], "joints": [{}]}}"#,
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
    // What `modal` and Python's `Model.modal()` compute: the modes with
    // their shear estimates and damping ratios (the Python call's
    // in-process counterpart, python/benches/modal.py).
    c.bench_function(
        "modal: default model, modes + shear + damping (results::modal)",
        |b| {
            b.iter(|| {
                ancf_modal::results::modal::modal(&model, &System::new(&model), &settings).unwrap()
            })
        },
    );
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
    for (k, e) in [(10, 50), (32, 156)] {
        let frame = grid(k, e);
        let elements = 2 * k * e;
        group.bench_function(
            format!("modal: free welded grid, {elements} elements, 10 modes"),
            |b| b.iter(|| modal_at_reference(&System::new(&frame), &ten).unwrap()),
        );
    }
    group.finish();
    // Issue 37: the 1 m steel cantilever (10 × 20 mm) where a factor of
    // K − σM carries more round-off than λ₁ (refined by precise products).
    let twelve = ModalSettings {
        modes: Some(12),
        ..settings
    };
    let mut fine = c.benchmark_group("fine mesh");
    fine.sample_size(10);
    for elements in [10_000, 20_000, 50_000, 100_000] {
        let model = steel_cantilever(elements);
        fine.bench_function(
            format!("modal: 1 m steel cantilever, {elements} elements, 12 modes"),
            |b| b.iter(|| modal_at_reference(&System::new(&model), &twelve).unwrap()),
        );
    }
    fine.finish();
}

/// Issue 37's cantilever: 1 m of steel, 10 mm (bending) × 20 mm, welded to
/// the ground at s = 0.
fn steel_cantilever(elements: usize) -> ValidModel {
    let json = format!(
        r#"{{"name": "c", "beams": [{{"id": "b", "start": [0, 0], "angle_deg": 0, "length": 1.0,
        "elements": {elements}, "section": {{"height": 0.01, "width": 0.02}},
        "material": {{"young": 210e9, "density": 7850}}}}],
        "joints": [{{"type": "weld", "a": {{"ground": [0, 0]}}, "b": {{"beam": "b", "s": 0}}}}]}}"#
    );
    Model::from_json(&json, Source::BuiltIn).unwrap()
}

criterion_group!(benches, bench);
criterion_main!(benches);
