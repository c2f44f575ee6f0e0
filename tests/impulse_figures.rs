//! Figures of the impulse experiment: response (signal over the force
//! pulse) and spectrum (peaks, eigenfrequency guides, reference line).
//!
//! Rendering: both formats decode (PNG of the requested size with drawn
//! data and a title; SVG well-formed with title, axis labels and data
//! paths). Fidelity: the marker of each identified peak is drawn at the
//! pixel of (f_peak, 20·log₁₀|X|) computed here from the panel's linear
//! axis map, and the guide of the first bending eigenfrequency (from the
//! eigenvalue problem, not the FFT) at the pixel of f₄. CLI: `--plot` and
//! `identify --out-dir` write valid files; a bad extension fails with one
//! line and writes nothing.

use ancf_modal::analysis::impulse::{run_impulse, ImpulseResult, ImpulseSettings};
use ancf_modal::model::ValidModel;
use ancf_modal::output::figures::{response_figure, response_path, spectrum_figure};
use ancf_modal::output::plot::{render, Figure, Format, PlotSize};
use ancf_modal::Model;
use assert_cmd::Command;
use std::path::Path;

const SIZE: PlotSize = PlotSize {
    width: 1200,
    height: 800,
};

fn short_run(end_time: f64) -> (ValidModel, ImpulseResult) {
    let model = Model::builtin();
    let mut s = ImpulseSettings::default();
    s.transient.end_time = end_time;
    let result = run_impulse(&model, &s, &mut |_| {}).expect("impulse run");
    (model, result)
}

/// Decodes a PNG; checks its size, the drawn fraction and title ink.
fn check_png(bytes: &[u8], size: PlotSize, what: &str) {
    let mut reader = png::Decoder::new(bytes).read_info().expect("PNG header");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb, "{what}: PNG colour");
    assert_eq!(
        (info.width, info.height),
        (size.width, size.height),
        "{what}: PNG size"
    );
    let w = info.width as usize;
    let ink = |x0: usize, x1: usize, y0: usize, y1: usize| {
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| 3 * (y * w + x)))
            .filter(|&i| buf[i..i + 3] != [255, 255, 255])
            .count()
    };
    let h = info.height as usize;
    let drawn = ink(0, w, 0, h) as f64 / (w * h) as f64;
    assert!(
        drawn > 0.01,
        "{what}: {:.2} % of the pixels drawn (expected > 1 %)",
        100.0 * drawn
    );
    let title = ink(w / 3, 2 * w / 3, 0, 50);
    assert!(title > 200, "{what}: {title} ink pixels in the title band");
}

struct Svg {
    texts: Vec<String>,
    /// (stroke, vertices) of every polyline.
    polylines: Vec<(String, Vec<(f64, f64)>)>,
    circles: Vec<(f64, f64)>,
    /// Centres of rectangles.
    rects: Vec<(f64, f64)>,
}

fn parse_svg(bytes: &[u8], what: &str) -> Svg {
    let text = std::str::from_utf8(bytes).expect("SVG is UTF-8");
    let doc = roxmltree::Document::parse(text).unwrap_or_else(|e| panic!("{what}: SVG XML: {e}"));
    let num = |n: roxmltree::Node, k: &str| {
        n.attribute(k)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    Svg {
        texts: doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .map(|n| n.text().unwrap_or("").trim().to_string())
            .collect(),
        polylines: doc
            .descendants()
            .filter(|n| n.has_tag_name("polyline"))
            .map(|n| {
                let pts = n
                    .attribute("points")
                    .unwrap_or("")
                    .split_whitespace()
                    .filter_map(|p| {
                        let (x, y) = p.split_once(',')?;
                        Some((x.parse().ok()?, y.parse().ok()?))
                    })
                    .collect();
                (n.attribute("stroke").unwrap_or("").to_string(), pts)
            })
            .collect(),
        circles: doc
            .descendants()
            .filter(|n| n.has_tag_name("circle"))
            .map(|n| (num(n, "cx"), num(n, "cy")))
            .collect(),
        rects: doc
            .descendants()
            .filter(|n| n.has_tag_name("rect"))
            .map(|n| {
                (
                    num(n, "x") + 0.5 * num(n, "width"),
                    num(n, "y") + 0.5 * num(n, "height"),
                )
            })
            .collect(),
    }
}

fn assert_texts(svg: &Svg, expected: &[&str], what: &str) {
    for t in expected {
        assert!(
            svg.texts.iter().any(|s| s.contains(t)),
            "{what}: text `{t}` missing in {:?}",
            svg.texts
        );
    }
}

/// Pixel of (x, y) by the linear map of a panel's shown ranges.
fn linear_pixel(
    l: &ancf_modal::output::plot::PanelLayout,
    x: f64,
    y: f64,
    x_factor: f64,
) -> (f64, f64) {
    let (x0, x1) = (l.x_range.0 * x_factor, l.x_range.1 * x_factor);
    let (y0, y1) = l.y_range;
    let px = l.x_pixels.0 as f64
        + (x * x_factor - x0) / (x1 - x0) * (l.x_pixels.1 - l.x_pixels.0) as f64;
    let py = l.y_pixels.0 as f64 + (y - y0) / (y1 - y0) * (l.y_pixels.1 - l.y_pixels.0) as f64;
    (px, py)
}

#[test]
fn both_figures_render_in_both_formats() {
    let (model, result) = short_run(0.02);
    let response: Figure = response_figure(&model.name, &result);
    let spectrum: Figure = spectrum_figure(&model, &result).into();
    for (fig, name, texts) in [
        (
            &response,
            "response",
            vec![
                "Impulse response: rcbo_free_free, sensor vibrometer",
                "Time [ms]",
                "Velocity [mm/s]",
                "Force [N]",
            ],
        ),
        (
            &spectrum,
            "spectrum",
            vec![
                "Spectrum: rcbo_free_free",
                "Frequency [kHz]",
                "Amplitude [dB re 1 m/s]",
                "experiment 4600 Hz",
                "1st bending",
            ],
        ),
    ] {
        let png = render(fig, Format::Png, SIZE).expect("PNG render");
        check_png(&png, SIZE, name);
        let svg = parse_svg(&render(fig, Format::Svg, SIZE).expect("SVG render"), name);
        assert_texts(&svg, &texts, name);
        let longest = svg.polylines.iter().map(|p| p.1.len()).max().unwrap_or(0);
        assert!(
            longest > 100,
            "{name}: a data path of > 100 vertices expected, longest has {longest}"
        );
    }
}

#[test]
fn response_zoom_panel_shows_the_first_ten_periods() {
    let (model, result) = short_run(0.02);
    let fig = response_figure(&model.name, &result);
    let layout = fig.layout(SIZE).expect("layout");
    assert_eq!(
        layout.len(),
        4,
        "whole record (2 panels) over the zoom (2 panels)"
    );
    // The whole record's panels span it (from its pre-trigger, ahead of
    // the blow at t = 0, to its last sample), the zoom panels its start to
    // ten periods of the first bending eigenfrequency after the blow.
    let f1 = result.modal.first_bending().unwrap().frequency_hz;
    let (t0, t1) = (result.time[0], *result.time.last().unwrap());
    assert!(t0 < 0.0 && t1 <= 0.02, "a pre-trigger: record {t0}..{t1} s");
    for (i, end) in [(0, t1), (1, t1), (2, 10.0 / f1), (3, 10.0 / f1)] {
        let (lo, hi) = layout[i].x_range;
        assert!((lo - t0).abs() < 1e-12, "panel {i} starts at {lo} s");
        assert!(
            (hi - end).abs() <= 1e-3 * end,
            "panel {i} ends at {hi} s, expected {end} s"
        );
    }
    let svg = parse_svg(&render(&fig, Format::Svg, SIZE).unwrap(), "response");
    assert_texts(
        &svg,
        &[format!(
            "{:.3} to {:.3} ms: 10 periods of the first bending mode ({f1:.1} Hz), from the blow",
            1e3 * t0,
            1e3 * 10.0 / f1
        )
        .as_str()],
        "zoom",
    );
    // Independent of the layout: the sensor curve drawn in the zoomed
    // signal panel oscillates ten times (its maxima counted on the pixels).
    let l = &layout[2];
    let (top, bottom) = (l.y_pixels.1 as f64, l.y_pixels.0 as f64);
    let curve = svg
        .polylines
        .iter()
        .filter(|(_, p)| p.len() > 50)
        .find(|(_, p)| p.iter().all(|&(_, y)| y >= top - 1.0 && y <= bottom + 1.0))
        .expect("a sensor curve inside the zoomed signal panel");
    let ys: Vec<f64> = curve.1.iter().map(|p| p.1).collect();
    let maxima = (1..ys.len() - 1)
        .filter(|&k| ys[k] < ys[k - 1] && ys[k] <= ys[k + 1])
        .count();
    assert!(
        (9..=11).contains(&maxima),
        "{maxima} maxima in the zoom (expected 10 periods)"
    );
}

#[test]
fn spectrum_markers_and_guides_sit_at_their_frequencies() {
    let (model, result) = short_run(0.02);
    let fb = result.first_bending.expect("first bending identified");
    // Independent: the FFT peak lies within one native bin of the
    // eigenvalue problem's first bending frequency.
    assert!(
        (fb.raw_hz - fb.eigen_hz).abs() < result.spectrum.resolution_hz,
        "FFT peak {} Hz vs eigen {} Hz: more than the resolution {} Hz apart",
        fb.raw_hz,
        fb.eigen_hz,
        result.spectrum.resolution_hz
    );
    let fig: Figure = spectrum_figure(&model, &result).into();
    let layout = fig.layout(SIZE).expect("layout");
    let l = &layout[0];
    let svg = parse_svg(&render(&fig, Format::Svg, SIZE).unwrap(), "spectrum");
    let tol = 1.5; // px: rounding to whole pixels
    assert!(!result.peaks.is_empty(), "peaks identified");
    for p in &result.peaks {
        let level = 20.0 * p.magnitude.log10();
        let (px, py) = linear_pixel(l, p.frequency_hz, level, 1e-3);
        let lib = fig
            .pixel_of(SIZE, 0, p.frequency_hz, level)
            .unwrap()
            .unwrap();
        assert!(
            (lib.0 as f64 - px).abs() <= tol && (lib.1 as f64 - py).abs() <= tol,
            "peak {} Hz: pixel_of {lib:?} vs linear map ({px:.1}, {py:.1})",
            p.frequency_hz
        );
        let first = (p.frequency_hz - fb.raw_hz).abs() <= 1e-9 * fb.raw_hz;
        let shapes = if first { &svg.rects } else { &svg.circles };
        let hit = shapes
            .iter()
            .any(|c| (c.0 - px).abs() <= tol && (c.1 - py).abs() <= tol);
        assert!(
            hit,
            "peak {} Hz ({}): no marker at ({px:.1}, {py:.1}) within {tol} px",
            p.frequency_hz,
            if first { "square" } else { "ring" }
        );
    }
    let eigen = result
        .modal
        .modes
        .iter()
        .find(|m| !m.kind.is_zero())
        .expect("an elastic mode")
        .frequency_hz;
    let (gx, _) = linear_pixel(l, eigen, l.y_range.0, 1e-3);
    let vertical_at = |x: f64| {
        svg.polylines.iter().any(|(_, pts)| {
            pts.len() == 2
                && (pts[0].0 - x).abs() <= tol
                && (pts[1].0 - x).abs() <= tol
                && (pts[0].1 - pts[1].1).abs() > 0.5 * (l.y_pixels.0 - l.y_pixels.1) as f64
        })
    };
    assert!(
        vertical_at(gx),
        "no vertical guide at the first bending eigenfrequency {eigen} Hz (pixel {gx:.1})"
    );
    assert_texts(&svg, &[&format!("= {eigen:.1} Hz")], "spectrum guide label");
}

fn cli() -> Command {
    Command::cargo_bin("ancf-modal").unwrap()
}

fn check_file(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let what = path.display().to_string();
    match path.extension().and_then(|e| e.to_str()) {
        Some("png") => check_png(&bytes, SIZE, &what),
        Some("svg") => {
            let svg = parse_svg(&bytes, &what);
            assert!(!svg.texts.is_empty(), "{what}: SVG without text");
        }
        other => panic!("{what}: unexpected extension {other:?}"),
    }
}

#[test]
fn impulse_plot_writes_spectrum_and_response() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("x.png");
    let out = cli()
        .args(["impulse", "--end-time", "0.01", "--plot"])
        .arg(&plot)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "impulse --plot: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(response_path(&plot), dir.path().join("x.response.png"));
    check_file(&plot);
    check_file(&dir.path().join("x.response.png"));
}

#[test]
fn identify_out_dir_writes_eight_figures() {
    let dir = tempfile::tempdir().unwrap();
    let out = cli()
        .args(["identify", "--end-time", "0.01", "--out-dir"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "identify --out-dir: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    for name in ["modes", "response", "spectrum", "convergence"] {
        for ext in ["svg", "png"] {
            check_file(&dir.path().join(format!("{name}.{ext}")));
        }
        assert!(
            stdout.contains(&format!("{name}.svg")),
            "summary line names {name}: {stdout}"
        );
    }
}

#[test]
fn unknown_plot_format_is_one_line_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("x.bmp");
    let out = cli()
        .args(["impulse", "--end-time", "0.01", "--plot"])
        .arg(&plot)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "exit code 1: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
    assert!(
        stderr.starts_with("Error: ") && stderr.contains("x.bmp"),
        "names the file: {stderr}"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "no file written: {left:?}");
}
