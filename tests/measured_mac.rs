//! MAC and the UFF 15/55 export of model modes.

mod common;
use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::measured::uff::d55::read_modes;
use ancf_modal::output::modal_uff::{export_nodes, modal_uff, translations};
use ancf_modal::signal::mac::{mac, mac_weighted};
use ancf_modal::{Model, System};
use assert_cmd::Command;
use serde_json::Value;
use std::path::Path;

fn modes(system: &System) -> ancf_modal::analysis::ModalResult {
    modal_at_reference(
        system,
        &ModalSettings {
            modes: Some(10),
            ..ModalSettings::default()
        },
    )
    .unwrap()
}

#[test]
fn mass_weighted_mac_of_a_mode_set_with_itself_is_the_identity() {
    let system = System::new(&Model::builtin());
    let r = modes(&system);
    let shapes: Vec<Vec<f64>> = r
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero())
        .map(|m| m.shape.clone())
        .collect();
    let m = mac_weighted(&shapes, &shapes, |y| {
        let mut out = vec![0.0; y.len()];
        system.mass().mul_vec(y, &mut out);
        out
    });
    for i in 0..shapes.len() {
        for j in 0..shapes.len() {
            let expect = if i == j { 1.0 } else { 0.0 };
            assert!(
                (m[(i, j)] - expect).abs() < 1e-9,
                "MAC_M[{i}][{j}] = {}",
                m[(i, j)]
            );
        }
    }
    // The plain MAC on the exported node translations: unit diagonal, and
    // symmetric in [0, 1].
    let nodes = export_nodes(&system);
    let t: Vec<Vec<f64>> = shapes.iter().map(|s| translations(&nodes, s)).collect();
    let p = mac(&t, &t);
    for i in 0..t.len() {
        assert!((p[(i, i)] - 1.0).abs() < 1e-12);
        for j in 0..t.len() {
            assert!((0.0..=1.0 + 1e-12).contains(&p[(i, j)]));
            assert!((p[(i, j)] - p[(j, i)]).abs() < 1e-12);
        }
    }
}

#[test]
fn the_model_against_itself_translated_has_a_unit_diagonal() {
    let dir = tempfile::tempdir().unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/rcbo_free_free.json");
    let mut doc: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let shift = |v: &mut Value| {
        v[0] = (v[0].as_f64().unwrap() + 3e-3).into();
        v[1] = (v[1].as_f64().unwrap() - 7e-3).into();
    };
    for b in doc["beams"].as_array_mut().unwrap() {
        shift(&mut b["start"]);
    }
    for key in ["rigid_bodies", "point_masses"] {
        for b in doc[key].as_array_mut().unwrap() {
            shift(&mut b["position"]);
        }
    }
    let moved = dir.path().join("moved.json");
    std::fs::write(&moved, doc.to_string()).unwrap();
    let out = Command::cargo_bin("ancf-modal")
        .unwrap()
        .arg("modal")
        .arg(&path)
        .args(["--modes", "8", "--json", "--mac"])
        .arg(&moved)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let m = v["mac"]["matrix"].as_array().unwrap();
    assert_eq!(m.len(), 5);
    for (i, row) in m.iter().enumerate() {
        let d = row[i].as_f64().unwrap();
        assert!((d - 1.0).abs() < 1e-8, "MAC[{i}][{i}] = {d}");
    }
}

#[test]
fn modal_uff_export_reads_back() {
    let system = System::new(&Model::builtin());
    let r = modes(&system);
    let text = modal_uff(&system, &r, &["test".into(), String::new()]);
    let (nodes, read) = read_modes(Path::new("modes.uff"), &text).unwrap();
    let expect = export_nodes(&system);
    assert_eq!(nodes.len(), expect.len());
    let elastic: Vec<_> = r.modes.iter().filter(|m| !m.kind.is_zero()).collect();
    assert_eq!(read.len(), elastic.len());
    for (a, b) in elastic.iter().zip(&read) {
        assert_eq!(b.mode_number, a.index as i64);
        assert!((b.frequency_hz - a.frequency_hz).abs() <= 5e-6 * a.frequency_hz);
        assert_eq!(b.modal_mass, 1.0);
        let t = translations(&expect, &a.shape);
        for (k, (_, v)) in b.nodes.iter().enumerate() {
            for d in 0..2 {
                let x = t[2 * k + d];
                assert!(
                    (v[d] - x).abs() <= 5e-6 * x.abs() + 1e-300,
                    "{} vs {x}",
                    v[d]
                );
            }
            assert_eq!(v[2], 0.0);
        }
    }
}

/// `modal --mac OTHER --mac-plot F.svg`: a heat map with one labelled cell
/// per mode pair; the model against itself (plain MAC, unit diagonal) has
/// 1.00 in every diagonal cell.
#[test]
fn mac_plot_draws_one_labelled_cell_per_pair() {
    let dir = tempfile::tempdir().unwrap();
    let model = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/beam_free_free.json");
    let svg = dir.path().join("mac.svg");
    let mut args: Vec<std::ffi::OsString> = vec!["modal".into(), model.clone().into()];
    args.extend(["--modes", "9", "--mac"].map(Into::into));
    args.extend([model.into(), "--mac-plot".into(), svg.clone().into()]);
    common::run_ok(args);
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    // 9 modes of a free beam: 3 rigid, 6 elastic → 6 × 6 cells.
    let n = 6;
    let values: Vec<String> = doc
        .descendants()
        .filter(|e| e.has_tag_name("text"))
        .map(|e| e.text().unwrap_or("").trim().to_string())
        .filter(|t| t.len() == 4 && t.as_bytes()[1] == b'.' && t.parse::<f64>().is_ok())
        .collect();
    assert_eq!(values.len(), n * n, "cell labels: {values:?}");
    assert!(values
        .iter()
        .all(|v| (0.0..=1.0).contains(&v.parse::<f64>().unwrap())));
    assert!(values.iter().filter(|v| *v == "1.00").count() >= n);
    // Cells: equal rectangles (a uniform grid of mode numbers).
    let size = |e: &roxmltree::Node, k: &str| -> f64 {
        e.attribute(k).and_then(|v| v.parse().ok()).unwrap_or(0.0)
    };
    let rects: Vec<(f64, f64)> = doc
        .descendants()
        .filter(|e| e.has_tag_name("rect"))
        .map(|e| (size(&e, "width"), size(&e, "height")))
        .collect();
    let widest = rects
        .iter()
        .filter(|r| r.0 < 1000.0)
        .map(|r| r.0)
        .fold(0.0, f64::max);
    let cells = rects
        .iter()
        .filter(|r| (r.0 - widest).abs() <= 1.0 && r.1 > 20.0)
        .count();
    assert_eq!(cells, n * n, "cell rectangles of width {widest}");
}
