//! Speed of `calibrate` on the built-in assembly (targets: ≤ 20 ms for one
//! parameter, ≤ 100 ms for two).

use ancf_modal::analysis::calibrate::{
    calibrate, CalibrationRequest, CalibrationSettings, ModeSelection, ParameterSpec,
};
use ancf_modal::Model;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn request(params: &[&str], targets: &[f64]) -> CalibrationRequest {
    CalibrationRequest {
        parameters: params.iter().map(|p| ParameterSpec::named(*p)).collect(),
        targets_hz: targets.to_vec(),
        modes: ModeSelection::default(),
        keep_mass: false,
        prestress: false,
    }
}

fn bench(c: &mut Criterion) {
    let model = Model::builtin();
    let settings = CalibrationSettings::default();
    let one = request(&["height"], &[4600.0]);
    c.bench_function("calibrate height to 4600 Hz (built-in)", |b| {
        b.iter(|| calibrate(black_box(&model), &one, &settings).unwrap())
    });
    let two = request(&["height", "width"], &[4600.0, 11600.0]);
    c.bench_function("calibrate height+width to 4600/11600 Hz (built-in)", |b| {
        b.iter(|| calibrate(black_box(&model), &two, &settings).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
