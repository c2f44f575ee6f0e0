//! Speed of `reduce`: a 2,000-element cantilever reduced by Craig–Bampton
//! with root and tip as interface and k = 20 fixed-interface modes,
//! including the check against the full model and the 3D node form
//! (target: ≤ 0.3 s).

use ancf_modal::commands::reduce::{run, ReduceRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let text = r#"{"name":"cantilever_2000","gravity":[0,0],
        "beams":[{"id":"blade","start":[0,0],"angle_deg":0,"length":1.0,"elements":2000,
          "section":{"height":1e-2,"width":1e-2},"material":{"young":2.1e11,"density":7850}}],
        "joints":[{"type":"weld","a":{"ground":[0,0]},"b":{"beam":"blade","s":0}}]}"#;
    let input = ModelInput::parse(text, Source::BuiltIn).expect("valid model");
    let request = ReduceRequest {
        interface: vec![("blade".into(), 0.0), ("blade".into(), 1.0)],
        modes: 20,
        ..ReduceRequest::default()
    };
    let mut group = c.benchmark_group("reduce");
    group.sample_size(10);
    group.bench_function("craig-bampton, 2000 elements, k = 20, with check", |b| {
        b.iter(|| run(black_box(&input), &request).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
