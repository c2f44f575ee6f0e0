//! The tool reads what it writes (issue 35): the records `impulse` and
//! `transient` write as CSV and as UFF 58, from every shipped model, are
//! read back by `frf` with its default options, and give the H1 of the
//! same records held in memory (the arrays path).
//!
//! The reference is the run's own force and response, passed as arrays:
//! the files carry their digits, so H1 agrees to 1e-8 (CSV) and 1e-9 (UFF) of its largest
//! magnitude in the band the hammer excites (the force within 20 dB of
//! its peak; outside it H1 divides by a force the digits do not resolve).

use ancf_modal::analysis::statics::start::Start;
use ancf_modal::commands::frf::{run as frf, FrfRecords, FrfRequest};
use ancf_modal::commands::impulse::{run as impulse, ImpulseRequest};
use ancf_modal::commands::transient::{run as transient, TransientRequest};
use ancf_modal::commands::ModelInput;
use realfft::num_complex::Complex64;
use std::path::{Path, PathBuf};

fn shipped(name: &str) -> ModelInput {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("models/{name}.json"));
    ModelInput::from_file(&path).unwrap()
}

const MODELS: [&str; 5] = [
    "beam_free_free",
    "cantilever",
    "rcbo_free_free",
    "rcbo_prestressed",
    "rcbo_switch_off",
];

/// H1 of `files` read with the defaults.
fn h1_of(files: Vec<PathBuf>) -> (Vec<[String; 2]>, Vec<Complex64>) {
    let request = FrfRequest {
        records: FrfRecords::Files(files),
        ..FrfRequest::default()
    };
    let run = frf(None, &request).unwrap();
    (run.analysis.channels, run.analysis.h1)
}

/// H1 of the arrays, in the band the hammer excites (the force within
/// 20 dB of its peak, `frf`'s fit band): outside it H1 divides by a force
/// the files' digits do not resolve.
fn h1_of_arrays(force: &[f64], response: &[f64], fs: f64) -> Memory {
    let request = FrfRequest {
        records: FrfRecords::Arrays {
            force: vec![force.to_vec()],
            response: vec![response.to_vec()],
            fs,
        },
        ..FrfRequest::default()
    };
    let a = frf(None, &request).unwrap().analysis;
    let (lo, hi) = a.band;
    let in_band: Vec<bool> = a
        .frequency_hz
        .iter()
        .zip(&a.h1)
        .map(|(f, h)| (lo..=hi).contains(f) && h.re.is_finite())
        .collect();
    Memory { h1: a.h1, in_band }
}

struct Memory {
    h1: Vec<Complex64>,
    in_band: Vec<bool>,
}

/// H1 read back against H1 in memory, within `tolerance` of the largest
/// magnitude in the band; whether the band held a bin to compare (a step
/// load's record excites none: its H1 is below the force floor).
fn assert_same(label: &str, read: &[Complex64], memory: &Memory, tolerance: f64) -> bool {
    assert_eq!(read.len(), memory.h1.len(), "{label}: bins");
    if !memory.in_band.contains(&true) {
        return false;
    }
    let band = || {
        read.iter()
            .zip(&memory.h1)
            .zip(&memory.in_band)
            .filter(|(_, &b)| b)
            .map(|(p, _)| p)
    };
    let scale = band().fold(0.0f64, |m, (_, h)| m.max(h.norm()));
    assert!(scale > 0.0, "{label}: an FRF");
    let worst = band().fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
    assert!(
        worst <= tolerance * scale,
        "{label}: H1 read back differs by {:.2e} of its largest magnitude",
        worst / scale
    );
    true
}

/// CSV: 10 significant digits per sample (measured: 1.3e-9 on the free
/// beam's hammer record).
const CSV_TOLERANCE: f64 = 1e-8;
/// UFF 58 (measured: 1.3e-11).
const UFF_TOLERANCE: f64 = 1e-9;

#[test]
fn impulse_records_read_back_as_they_were_in_memory() {
    let dir = tempfile::tempdir().unwrap();
    let request = ImpulseRequest {
        end_time: 0.02,
        ..ImpulseRequest::default()
    };
    let mut struck = 0;
    for name in MODELS {
        // A model whose time-varying loads are releases has no hammer.
        let Ok(run) = impulse(&shipped(name), &request) else {
            continue;
        };
        struck += 1;
        let csv = dir.path().join(format!("{name}.csv"));
        let uff = dir.path().join(format!("{name}.uff"));
        run.write_csv(&csv).unwrap();
        std::fs::write(&uff, run.uff()).unwrap();
        let r = &run.result;
        let memory = h1_of_arrays(&r.force, &r.signal, r.sample_rate_hz);
        let (channels, h) = h1_of(vec![csv]);
        assert_eq!(
            channels[0][0], "force_n",
            "{name}: the force found by its name"
        );
        assert!(assert_same(
            &format!("{name} CSV"),
            &h,
            &memory,
            CSV_TOLERANCE
        ));
        let (_, h) = h1_of(vec![uff]);
        assert!(assert_same(
            &format!("{name} UFF"),
            &h,
            &memory,
            UFF_TOLERANCE
        ));
    }
    assert_eq!(struck, 3, "the shipped models with a hammer or a step");
}

#[test]
fn transient_records_read_back_as_they_were_in_memory() {
    let dir = tempfile::tempdir().unwrap();
    let mut compared = 0;
    for name in MODELS {
        let request = TransientRequest {
            end_time: 5e-3,
            start: Start::Equilibrium,
            ..TransientRequest::default()
        };
        let run = transient(&shipped(name), &request).unwrap();
        let sim = &run.simulation;
        let loads = ancf_modal::mechanics::load::load_magnitudes(&sim.loads, &sim.time);
        let Some((label, force)) = loads.first() else {
            // Nothing varies in time: no force to read back.
            continue;
        };
        if force.iter().all(|&f| f == 0.0) {
            continue;
        }
        let csv = dir.path().join(format!("{name}.csv"));
        let uff = dir.path().join(format!("{name}.uff"));
        std::fs::write(&csv, run.csv()).unwrap();
        std::fs::write(&uff, run.uff().unwrap()).unwrap();
        let (_, response) = &sim.sensors[0];
        let memory = h1_of_arrays(force, response, request.sample_rate);
        if loads.len() == 1 {
            let (channels, h) = h1_of(vec![csv]);
            assert_eq!(channels[0][0], format!("load_{label}_force_n"), "{name}");
            assert_same(&format!("{name} CSV"), &h, &memory, CSV_TOLERANCE);
        }
        let (_, h) = h1_of(vec![uff]);
        compared += usize::from(assert_same(
            &format!("{name} UFF"),
            &h,
            &memory,
            UFF_TOLERANCE,
        ));
    }
    assert!(compared >= 2, "the hammered models compared");
}

/// What the response measures is read back too: `impulse` names its CSV
/// column `<sensor>_<quantity>` and writes the UFF record's ordinate type,
/// and `frf` with default options takes the FRF's unit from them (the
/// trial's acceleration records were labelled m/s/N).
#[test]
fn the_response_quantity_is_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("models/cantilever.json"),
    )
    .unwrap();
    for (quantity, unit) in [
        ("displacement", "m/N"),
        ("velocity", "m/s/N"),
        ("acceleration", "m/s²/N"),
    ] {
        let mut model: serde_json::Value = serde_json::from_str(&text).unwrap();
        model["loads"][0]["time"] = serde_json::json!({"half_sine": {"duration": 1e-4}});
        model["sensors"][0]["quantity"] = serde_json::json!(quantity);
        let input =
            ModelInput::parse(&model.to_string(), ancf_modal::error::Source::BuiltIn).unwrap();
        let run = impulse(
            &input,
            &ImpulseRequest {
                end_time: 0.02,
                ..ImpulseRequest::default()
            },
        )
        .unwrap();
        let csv = dir.path().join(format!("{quantity}.csv"));
        let uff = dir.path().join(format!("{quantity}.uff"));
        run.write_csv(&csv).unwrap();
        std::fs::write(&uff, run.uff()).unwrap();
        for file in [csv, uff] {
            let request = FrfRequest {
                records: FrfRecords::Files(vec![file.clone()]),
                ..FrfRequest::default()
            };
            let read = frf(None, &request).unwrap();
            assert_eq!(read.quantity.name(), quantity, "{}", file.display());
            assert_eq!(read.document.document()["frf_unit"], unit);
        }
    }
}
