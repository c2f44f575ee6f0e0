//! The HTML report: well formed (every SVG part parses as XML, ids
//! unique), self-contained (no http:// or https:// outside XML namespace
//! declarations), within 2 MB for the paper's assembly; and the animated
//! mode shapes draw q₀ ± a·φ: the pixel coordinates, mapped back to the
//! model through the affine map fitted on the undeformed drawing, equal
//! the element interpolation of q₀ + a·φ at phase 0 and of q₀ − a·φ at
//! half the period, with the largest displacement 15 % of the bounding
//! box's diagonal (computed here, not by the library).

mod common;

use ancf_modal::analysis::impulse::{run_impulse, ImpulseSettings};
use ancf_modal::analysis::modal::{modal, ModalSettings};
use ancf_modal::output::figures::{assembly_geometry, response_figure, spectrum_figure};
use ancf_modal::output::plot::{Figure, PlotSize};
use ancf_modal::output::report::animate::PHASES;
use ancf_modal::output::report::{report_html, ModeSet, Provenance, ReportInput, Section};
use ancf_modal::{Model, System};
use common::pixels;

fn paper_report() -> (System, String) {
    let model = Model::builtin();
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(9),
        ..ModalSettings::default()
    };
    let r = modal(&system, &system.reference(), &settings).unwrap();
    let imp = run_impulse(&model, &ImpulseSettings::default(), &mut |_| {}).unwrap();
    let size = PlotSize {
        width: 900,
        height: 560,
    };
    let input = ReportInput {
        warnings: &[],
        provenance: Provenance {
            tool_version: "test".into(),
            model_name: model.name.clone(),
            model_sha256: "0".repeat(64),
            command_line: "ancf-modal report <&>".into(),
            date: "2026-11-25".into(),
        },
        description: &model.description,
        mode_sets: vec![ModeSet {
            title: "Modes at the reference",
            system: &system,
            q: &system.q0,
            modal: &r,
            damping_ratio: Vec::new(),
        }],
        sections: vec![Section {
            id: "impulse".into(),
            title: "Impulse test".into(),
            notes: vec!["a < b & c".into()],
            tables: Vec::new(),
            preformatted: Vec::new(),
            figures: vec![
                (response_figure(&model.name, &imp), size),
                (Figure::Line(spectrum_figure(&model, &imp)), size),
            ],
        }],
    };
    let html = report_html(&input).unwrap();
    (system, html)
}

/// Every `<svg …>…</svg>` part (none nested in this page).
fn svg_parts(html: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let mut rest = html;
    while let Some(a) = rest.find("<svg") {
        let b = a + rest[a..].find("</svg>").expect("closed") + "</svg>".len();
        parts.push(&rest[a..b]);
        rest = &rest[b..];
    }
    parts
}

#[test]
fn the_report_is_well_formed_self_contained_and_small() {
    let (_, html) = paper_report();
    assert!(html.len() <= 2 << 20, "{} bytes", html.len());
    let parts = svg_parts(&html);
    assert!(parts.len() >= 1 + 6 + 2, "{} SVG parts", parts.len());
    for p in &parts {
        roxmltree::Document::parse(p).unwrap_or_else(|e| panic!("{e}: {}", &p[..200]));
    }
    let mut ids: Vec<&str> = html
        .split(" id=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap())
        .collect();
    let n = ids.len();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), n, "duplicate ids");
    for scheme in ["http://", "https://"] {
        for (i, _) in html.match_indices(scheme) {
            let before = &html[i.saturating_sub(12)..i];
            assert!(
                before.ends_with("xmlns=\"") || before.contains("xmlns:"),
                "external reference at {i}: {}",
                &html[i.saturating_sub(40)..i + 40]
            );
        }
    }
    assert!(html.contains("ancf-modal report &lt;&amp;&gt;"), "escaped");
}

/// The pixel pairs of a `points` list.

#[test]
fn animated_modes_draw_q0_plus_and_minus_a_phi() {
    let (system, html) = paper_report();
    let r = modal(
        &system,
        &system.reference(),
        &ModalSettings {
            modes: Some(9),
            ..ModalSettings::default()
        },
    )
    .unwrap();
    let per = 8;
    let undeformed = assembly_geometry(&system, &system.q0, per);
    let beam0 = &undeformed.beams[0];
    let panels: Vec<&str> = svg_parts(&html)
        .into_iter()
        .filter(|p| p.contains("class=\"mode-shape\""))
        .collect();
    let elastic: Vec<_> = r.modes.iter().filter(|m| !m.kind.is_zero()).collect();
    assert_eq!(panels.len(), elastic.len());
    for (panel, mode) in panels.iter().zip(elastic) {
        let doc = roxmltree::Document::parse(panel).unwrap();
        let group = |class: &str| {
            doc.descendants()
                .find(|n| n.attribute("class") == Some(class))
                .unwrap()
        };
        let grey = pixels(
            group("undeformed")
                .children()
                .find(|n| n.has_tag_name("polyline"))
                .unwrap()
                .attribute("points")
                .unwrap(),
        );
        assert_eq!(grey.len(), beam0.len());
        // The affine map x' = s·x + a, y' = −s·y + b from the two ends.
        let (p0, p1) = (beam0[0], beam0[beam0.len() - 1]);
        let (g0, g1) = (grey[0], grey[grey.len() - 1]);
        let s = (g1[0] - g0[0]).hypot(g1[1] - g0[1]) / (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
        let to_model = |g: [f64; 2]| [p0[0] + (g[0] - g0[0]) / s, p0[1] - (g[1] - g0[1]) / s];
        for (g, p) in grey.iter().zip(beam0) {
            let m = to_model(*g);
            assert!(
                // Each pixel is written to 0.01 px, the map's two ends too.
                (m[0] - p[0]).hypot(m[1] - p[1]) <= 0.02 / s,
                "undeformed drawn to scale"
            );
        }
        let values = group("deformed anim")
            .descendants()
            .find(|n| n.has_tag_name("animate"))
            .unwrap()
            .attribute("values")
            .unwrap();
        let frames: Vec<Vec<[f64; 2]>> = values.split(';').map(pixels).collect();
        assert_eq!(
            frames.len(),
            PHASES + 1,
            "a period and the first frame again"
        );
        assert_eq!(frames[0], frames[PHASES]);
        // The drawn displacement at phase 0 against the interpolation of φ.
        let plus = assembly_geometry(&system, &mode.shape, per).beams[0].clone();
        let shift = [system.origin.x, system.origin.y];
        let d: Vec<[f64; 2]> = plus
            .iter()
            .map(|p| [p[0] - shift[0], p[1] - shift[1]])
            .collect();
        let (k, dk) = d
            .iter()
            .enumerate()
            .max_by(|a, b| a.1[0].hypot(a.1[1]).total_cmp(&b.1[0].hypot(b.1[1])))
            .unwrap();
        let drawn = to_model(frames[0][k]);
        let a = ((drawn[0] - beam0[k][0]) * dk[0] + (drawn[1] - beam0[k][1]) * dk[1])
            / (dk[0] * dk[0] + dk[1] * dk[1]);
        for (half, sign) in [(0, 1.0), (PHASES / 2, -1.0)] {
            for ((g, p), di) in frames[half].iter().zip(beam0).zip(&d) {
                let m = to_model(*g);
                let want = [p[0] + sign * a * di[0], p[1] + sign * a * di[1]];
                assert!(
                    (m[0] - want[0]).hypot(m[1] - want[1]) <= 0.02 / s,
                    "mode {} phase {half}: {m:?} vs {want:?}",
                    mode.index
                );
            }
        }
        // Largest displacement of a drawn point: 15 % of the diagonal.
        // Beam points and bodies move linearly in q; joint anchors by a
        // finite difference of their drawn positions.
        let eps = 1e-7;
        let q_eps: Vec<f64> = system
            .q0
            .iter()
            .zip(&mode.shape)
            .map(|(q, p)| q + eps * p)
            .collect();
        let moved = assembly_geometry(&system, &q_eps, per);
        let points = |g: &ancf_modal::output::plot::Geometry| -> Vec<[f64; 2]> {
            g.points().copied().collect()
        };
        let (before, after) = (points(&undeformed), points(&moved));
        let unit = before
            .iter()
            .zip(&after)
            .map(|(b, a)| (a[0] - b[0]).hypot(a[1] - b[1]) / eps)
            .fold(0.0f64, f64::max);
        let (lo, hi) = before.iter().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1])],
                    [hi[0].max(p[0]), hi[1].max(p[1])],
                )
            },
        );
        let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        let largest = a.abs() * unit;
        assert!(
            (largest / diagonal - 0.15).abs() < 1e-3,
            "mode {}: largest displacement {:.4} of the diagonal",
            mode.index,
            largest / diagonal
        );
    }
}

/// The `data-frequency-hz` values of the page's mode tables, in order.
fn page_frequencies(html: &str) -> Vec<f64> {
    html.split("data-frequency-hz=\"")
        .skip(1)
        .map(|rest| rest[..rest.find('"').unwrap()].parse().unwrap())
        .collect()
}

#[test]
fn the_report_command_shows_the_modal_commands_frequencies_at_both_states() {
    // The report renders `modal`'s runs: its tables hold, to the bit, the
    // frequencies `modal` and `modal --prestress` compute on their own.
    use ancf_modal::commands::modal::{run as modal_run, ModalRequest};
    use ancf_modal::commands::report::{run, ReportRequest};
    use ancf_modal::commands::{CommandError, ModelInput};
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/rcbo_prestressed.json");
    let input = ModelInput::from_file(&path).unwrap();
    let request = ReportRequest {
        prestress: true,
        ..ReportRequest::default()
    };
    let page = run(&input, &request).unwrap();
    let freqs = |prestress: bool, modes: usize| -> Vec<f64> {
        let r = ModalRequest {
            modes,
            prestress,
            ..ModalRequest::default()
        };
        modal_run(&input, &r)
            .unwrap()
            .outcome
            .result()
            .modes
            .iter()
            .map(|m| m.frequency_hz)
            .collect()
    };
    let reference = freqs(false, ancf_modal::results::identify::IDENTIFY_MODES);
    let mut expected = reference.clone();
    expected.extend(freqs(true, reference.len()));
    assert_eq!(page_frequencies(&page.html), expected);
    assert!(page.html.contains("Modes at the pre-stressed equilibrium"));
    // Without an impulse experiment there is nothing to calibrate.
    let asked = ReportRequest {
        identify: ancf_modal::commands::identify::IdentifyRequest {
            calibrate: true,
            ..Default::default()
        },
        ..ReportRequest::default()
    };
    let refused = run(&input, &asked).unwrap_err();
    assert!(
        matches!(refused, CommandError::NeedsImpulse { .. }),
        "{refused}"
    );
    assert!(refused.is_input());
}

/// The modes table's damping column: absent for an undamped model (a
/// column of "0.000 %" reads as a measured zero, issue 36), and for a
/// Rayleigh-damped one each mode's ratio as `modal` computes it.
#[test]
fn the_damping_column_is_there_only_for_a_damped_model() {
    use ancf_modal::commands::modal::{run as modal_run, ModalRequest};
    use ancf_modal::commands::report::{run, ReportRequest};
    use ancf_modal::commands::ModelInput;
    let dir = tempfile::tempdir().unwrap();
    let source = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/cantilever.json");
    let mut model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&source).unwrap()).unwrap();
    let plain = ModelInput::from_file(&source).unwrap();
    let page = run(&plain, &ReportRequest::default()).unwrap();
    assert!(!page.html.contains("damping ζ"));
    model["damping"] = serde_json::json!({"alpha": 20.0, "beta": 1e-7});
    let path = dir.path().join("damped.json");
    std::fs::write(&path, model.to_string()).unwrap();
    let damped = ModelInput::from_file(&path).unwrap();
    let page = run(&damped, &ReportRequest::default()).unwrap();
    assert!(page.html.contains("<th>damping ζ</th>"));
    let modes = modal_run(&damped, &ModalRequest::default()).unwrap();
    let first = modes.outcome.result().modes[0].frequency_hz;
    // ζ = α/(2ω) + βω/2 of the first mode, as the table prints it.
    let w = 2.0 * std::f64::consts::PI * first;
    let zeta = format!("{:.3} %", 100.0 * (20.0 / (2.0 * w) + 1e-7 * w / 2.0));
    assert!(page.html.contains(&zeta), "{zeta}");
}

/// The cells of each `<table>` of `html`, row by row (header rows left out).
fn tables(html: &str) -> Vec<Vec<Vec<String>>> {
    html.split("<table>")
        .skip(1)
        .map(|t| {
            let body = t.split("</table>").next().unwrap();
            let body = body.split("<tbody>").nth(1).unwrap_or("");
            body.split("<tr>")
                .skip(1)
                .map(|row| {
                    row.split("<td")
                        .skip(1)
                        .map(|c| {
                            let c = &c[c.find('>').unwrap() + 1..];
                            c.split("</td>").next().unwrap().trim().to_string()
                        })
                        .collect()
                })
                .collect()
        })
        .collect()
}

#[test]
fn no_section_or_table_column_is_empty() {
    use ancf_modal::commands::report::{run, ReportRequest};
    use ancf_modal::commands::ModelInput;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    // The cantilever has no `reference`: no comparison with an experiment.
    let cantilever = ModelInput::from_file(&root.join("models/cantilever.json")).unwrap();
    let builtin = ModelInput::load(None).unwrap();
    for (input, comparison) in [(cantilever, false), (builtin, true)] {
        let html = run(&input, &ReportRequest::default()).unwrap().html;
        assert_eq!(
            html.contains("<section id=\"comparison\""),
            comparison,
            "{}",
            input.model.name
        );
        for section in html.split("<section").skip(1) {
            let section = section.split("</section>").next().unwrap();
            let after_title = section.split("</h2>").nth(1).unwrap_or("");
            assert!(
                after_title.contains("<table")
                    || after_title.contains("<svg")
                    || after_title.contains("<li>")
                    || after_title.contains("<p"),
                "empty section: {}",
                &section[..section.len().min(120)]
            );
        }
        for t in tables(&html) {
            let columns = t.iter().map(|r| r.len()).max().unwrap_or(0);
            for c in 0..columns {
                assert!(
                    t.iter().any(|r| r.get(c).is_some_and(|v| !v.is_empty())),
                    "{}: a table with an empty column {c}: {t:?}",
                    input.model.name
                );
            }
        }
    }
}

#[test]
fn every_drawn_point_lies_inside_its_panel() {
    // The slider-crank has a ground pin (a triangle on hatched ground) and
    // a rail: every point of every SVG element, symbols too, inside its
    // panel's viewBox (outside-eyes trial of issue 36: a ground pin's
    // hatching was cut off below the mode panels).
    use ancf_modal::commands::report::{run, ReportRequest};
    use ancf_modal::commands::ModelInput;
    // A simply supported beam: the pin's triangle is the lowest thing drawn.
    let beam = serde_json::json!({
        "name": "simply supported",
        "beams": [{"id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.5,
            "elements": 8, "section": {"height": 0.005, "width": 0.02},
            "material": {"young": 210e9, "density": 7850.0}}],
        "joints": [
            {"id": "pin", "type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}},
            {"id": "roller", "type": "slider", "a": {"ground": [0.5, 0.0]},
                "b": {"beam": "b", "s": 0.5}, "axis": [1.0, 0.0]}]
    });
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/slider_crank.json");
    let inputs = [
        ModelInput::from_file(&path).unwrap(),
        ModelInput::parse(&beam.to_string(), ancf_modal::error::Source::BuiltIn).unwrap(),
    ];
    let pages: Vec<String> = inputs
        .iter()
        .map(|i| run(i, &ReportRequest::default()).unwrap().html)
        .collect();
    let panels: Vec<&str> = pages
        .iter()
        .flat_map(|html| svg_parts(html))
        .filter(|p| p.contains("class=\"mode-shape\"") || p.contains("class=\"assembly\""))
        .collect();
    assert!(panels.len() > 2);
    for panel in panels {
        let doc = roxmltree::Document::parse(panel).unwrap();
        let root = doc.root_element();
        let v: Vec<f64> = root
            .attribute("viewBox")
            .unwrap()
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        let inside = |p: [f64; 2]| p[0] >= v[0] && p[0] <= v[2] && p[1] >= v[1] && p[1] <= v[3];
        for n in doc.descendants() {
            let mut points = Vec::new();
            if let Some(p) = n.attribute("points") {
                points.extend(pixels(p));
            }
            if n.has_tag_name("animate") && n.attribute("attributeName") == Some("points") {
                for frame in n.attribute("values").unwrap().split(';') {
                    points.extend(pixels(frame));
                }
            }
            if let (Some(x), Some(y)) = (n.attribute("cx"), n.attribute("cy")) {
                points.push([x.parse().unwrap(), y.parse().unwrap()]);
            }
            for p in points {
                assert!(
                    inside(p),
                    "{:?} at {p:?} outside {v:?}",
                    n.attribute("class")
                );
            }
        }
    }
}

#[test]
fn the_report_gives_the_impulse_and_modal_warnings_their_commands_give() {
    // The outside-eyes trial's gripper finger with its height typed as 2.0
    // (millimetres meant): `impulse` warns that the first bending mode
    // lies above the pass band and that the step is too coarse for it;
    // the report (identify's run) gave neither.
    use assert_cmd::cargo::cargo_bin_cmd;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let model = root.join("tests/data/gripper_height_in_mm.json");
    let dir = tempfile::tempdir().unwrap();
    let flags = [
        "--end-time",
        "0.05",
        "--step",
        "2e-5",
        "--sample-rate",
        "10000",
    ];
    let warnings = |command: &str, extra: &[&str]| -> Vec<String> {
        let out = cargo_bin_cmd!("ancf-modal")
            .arg(command)
            .arg(&model)
            .args(flags)
            .args(extra)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stderr)
            .lines()
            .filter(|l| l.starts_with("warning: "))
            .map(String::from)
            .collect()
    };
    let impulse = warnings("impulse", &[]);
    let report = warnings("report", &["--out", "r.html"]);
    assert!(impulse.len() >= 3, "{impulse:?}");
    for w in &impulse {
        assert!(report.contains(w), "report lacks {w}: {report:?}");
    }
    let html = std::fs::read_to_string(dir.path().join("r.html")).unwrap();
    assert!(
        html.contains("above the acquisition&#39;s pass band"),
        "the page lists it"
    );
}
