//! The command layer's join of shards computed elsewhere
//! (`SweepJob::join`, what Python's `sweep(..., client=...)` uses): the
//! shards of a sweep, carried as JSON text, joined to the run one process
//! gives — document, warnings in index order, provenance; a saved run read
//! back (`SweepRun::unstamped`) is unchanged.

use ancf_modal::analysis::sweep::{Quantity, Shard, SweepDocument};
use ancf_modal::commands::sweep::{prepare, run, SweepRequest, SweepRun};
use ancf_modal::commands::sweep_merge::{self, SweepMergeRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use serde_json::json;
use std::path::PathBuf;

/// A cantilever (the paper's blade welded at s = 0) and, uncoupled beside
/// it, a 1 g mass on a spring k whose frequency crosses the cantilever's.
fn crossing() -> ModelInput {
    let v = json!({"name": "crossing",
        "beams": [{"id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.025,
            "elements": 8, "section": {"height": 1.1e-3, "width": 5.2e-3},
            "material": {"young": 127e9, "density": 8940.0}}],
        "point_masses": [{"id": "m", "mass": 1e-3, "position": [0.1, 0.1]}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "blade", "s": 0.0}},
            {"id": "guide", "type": "slider", "a": {"ground": [0.1, 0.1]}, "b": {"body": "m"}, "axis": [1.0, 0.0]}
        ],
        "springs": [{"id": "k", "a": {"ground": [0.09, 0.1]}, "b": {"body": "m"},
            "stiffness": 1e4, "free_length": 0.01}]});
    let source = Source::File(PathBuf::from("crossing.json"));
    ModelInput::parse(&serde_json::to_string_pretty(&v).unwrap(), source).unwrap()
}

/// frequency:2 over k and the blade's height (fastest), whose last value
/// (h/L = 0.12) warns at points 2, 5, 8 and 11: shards 3, 2, 1 and 4 of 4.
fn sweep_request(heights: &str) -> SweepRequest {
    SweepRequest {
        params: vec![
            String::from("springs[k].stiffness=1e4:4e6:4:log"),
            format!("blade.height={heights}"),
        ],
        quantity: Some(Quantity::parse("frequency:2").unwrap()),
        modes: 3,
        threads: Some(1),
        ..SweepRequest::default()
    }
}

/// The shards `k/n` of `request`, each through its JSON text.
fn shards(input: &ModelInput, request: &SweepRequest, n: usize) -> Vec<(String, SweepDocument)> {
    (1..=n)
        .map(|k| {
            let r = SweepRequest {
                shard: Some(Shard { index: k, count: n }),
                ..request.clone()
            };
            let done = run(input, &r, &|| {}).unwrap();
            let text = serde_json::to_string(&done.stamped()).unwrap();
            (
                format!("{k}/{n}"),
                sweep_merge::parse("shard", &text).unwrap(),
            )
        })
        .collect()
}

fn assert_same(a: &SweepRun, b: &SweepRun) {
    assert_eq!(a.document.output, b.document.output);
    assert_eq!(a.document.warnings, b.document.warnings);
    assert_eq!(a.document.model_sha256, b.document.model_sha256);
    assert_eq!(a.document.model_warnings, b.document.model_warnings);
    assert_eq!(a.stamped(), b.stamped());
    assert_eq!(a.text(), b.text());
}

#[test]
fn joined_shards_are_the_single_run_in_any_order() {
    let input = crossing();
    let request = sweep_request("1.1e-3:3e-3:3");
    let whole = run(&input, &request, &|| {}).unwrap();
    let warned: Vec<&str> = whole
        .document
        .warnings
        .iter()
        .map(|w| w.split(": ").nth(1).unwrap())
        .collect();
    assert_eq!(warned, ["point 2", "point 5", "point 8", "point 11"]);
    let parts = shards(&input, &request, 4);
    let job = prepare(&input, &request).unwrap();
    assert_same(&job.join(&parts).unwrap(), &whole);
    // The shards in any order join the same.
    let reversed: Vec<_> = parts.iter().rev().cloned().collect();
    assert_same(&job.join(&reversed).unwrap(), &whole);
    // sweep-merge has the same points, tracked, and the same warnings (in
    // the order of the shards that hold them; it has no model to count
    // the model's).
    let merged = sweep_merge::run(&SweepMergeRequest {
        shards: parts.clone(),
    })
    .unwrap();
    assert_eq!(merged.document.output, whole.document.output);
    let mut warnings = merged.document.warnings.clone();
    warnings.sort_by_key(|w| {
        w.split("point ")
            .nth(1)
            .map(|i| i.split(':').next().unwrap().parse::<usize>().unwrap())
    });
    assert_eq!(warnings, whole.document.warnings);
    // Shards of another sweep (other heights) are refused by its id.
    let other = shards(&input, &sweep_request("1.1e-3:2.9e-3:3"), 4);
    let err = job.join(&other).unwrap_err().to_string();
    assert!(
        err.contains("1/4 belongs to a different sweep") && err.contains("the sweep asked for"),
        "{err}"
    );
    // A missing shard is refused as sweep-merge refuses it.
    let err = job.join(&parts[..3]).unwrap_err().to_string();
    assert!(
        err.contains("missing") && err.contains("shards 4 of 4"),
        "{err}"
    );
}

#[test]
fn a_run_read_back_from_its_document_is_unchanged() {
    let input = crossing();
    let request = sweep_request("1.1e-3:3e-3:3");
    for shard in [None, Some(Shard { index: 2, count: 3 })] {
        let done = run(
            &input,
            &SweepRequest {
                shard,
                ..request.clone()
            },
            &|| {},
        )
        .unwrap();
        let text = serde_json::to_string(&done.stamped()).unwrap();
        let doc = sweep_merge::parse("saved", &text).unwrap();
        assert_same(
            &SweepRun::unstamped(doc, done.document.model_warnings),
            &done,
        );
    }
}
