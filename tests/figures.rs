//! Figures of analysis results: mode shapes and mesh convergence.
//!
//! Rendering: each figure is a PNG of the requested size with drawn text
//! and data, and a well-formed SVG naming its title and axes. Fidelity: the
//! drawn centre lines are the ANCF interpolation S(ξ)·(e₀ + a·φ) evaluated
//! here with independently written Hermite cubics, the undeformed beam is
//! straight with its length, and the convergence points are the errors of
//! independent modal runs against Euler–Bernoulli. CLI: `--plot` writes
//! valid files, and bad paths fail with one line and no file.

mod common;

use ancf_modal::analysis::convergence::{
    euler_bernoulli_free_free, mesh_convergence, mesh_convergence_with, with_elements,
    ConvergenceData, Reference, ReferenceKind,
};
use ancf_modal::analysis::{ModalResult, ModeKind};
use ancf_modal::output::figures::*;
use ancf_modal::output::plot::{render, Figure, Format, LineFigure, ModeShapeFigure, PlotSize};
use ancf_modal::{Model, System};
use assert_cmd::Command;
use common::{euler_bernoulli_hz, free_beam, modal_all, model, FREE_FREE_BL, H, L};
use serde_json::json;

const SIZE: PlotSize = PlotSize {
    width: 1200,
    height: 800,
};

// ---------------------------------------------------------------- helpers

struct Image {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Image {
    fn decode(bytes: &[u8]) -> Image {
        let mut reader = png::Decoder::new(bytes).read_info().expect("PNG header");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("PNG data");
        assert_eq!(info.color_type, png::ColorType::Rgb, "PNG colour type");
        buf.truncate(info.buffer_size());
        Image {
            width: info.width,
            height: info.height,
            rgb: buf,
        }
    }

    /// Non-white pixels in `[x0, x1) × [y0, y1)`.
    fn ink(&self, (x0, x1): (u32, u32), (y0, y1): (u32, u32)) -> usize {
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let i = 3 * (y * self.width + x) as usize;
                self.rgb[i..i + 3] != [255, 255, 255]
            })
            .count()
    }
}

/// Decodes a PNG and checks size, drawn fraction and title ink.
fn check_png(bytes: &[u8], size: PlotSize, what: &str) {
    let img = Image::decode(bytes);
    assert_eq!(
        (img.width, img.height),
        (size.width, size.height),
        "{what}: PNG size"
    );
    let (w, h) = (img.width, img.height);
    let drawn = img.ink((0, w), (0, h)) as f64 / (w * h) as f64;
    assert!(
        drawn > 0.02,
        "{what}: only {:.2} % of the pixels drawn (expected > 2 %)",
        100.0 * drawn
    );
    let title = img.ink((w / 3, 2 * w / 3), (0, 50));
    assert!(title > 200, "{what}: {title} pixels in the title band");
}

struct Svg {
    texts: Vec<String>,
    /// (stroke colour, vertices) of every polyline.
    polylines: Vec<(String, Vec<(i32, i32)>)>,
    circles: Vec<(i32, i32)>,
}

fn parse_svg(bytes: &[u8]) -> Svg {
    let text = std::str::from_utf8(bytes).expect("SVG is UTF-8");
    let doc = roxmltree::Document::parse(text).expect("SVG is well-formed XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    let texts = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or("").trim().to_string())
        .collect();
    let polylines = doc
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .map(|n| {
            let pts = n
                .attribute("points")
                .unwrap_or("")
                .split_whitespace()
                .filter_map(|p| {
                    let (x, y) = p.split_once(',')?;
                    Some((x.parse::<f64>().ok()? as i32, y.parse::<f64>().ok()? as i32))
                })
                .collect();
            (n.attribute("stroke").unwrap_or("").to_string(), pts)
        })
        .collect();
    let circles = doc
        .descendants()
        .filter(|n| n.has_tag_name("circle"))
        .map(|n| {
            let a = |k| n.attribute(k).unwrap().parse::<f64>().unwrap() as i32;
            (a("cx"), a("cy"))
        })
        .collect();
    Svg {
        texts,
        polylines,
        circles,
    }
}

fn assert_texts(svg: &Svg, expected: &[&str], what: &str) {
    for t in expected {
        assert!(
            svg.texts.iter().any(|s| s == t),
            "{what}: text `{t}` missing in {:?}",
            svg.texts
        );
    }
}

/// Hermite cubics, written out here (not the library's), times the 8
/// element coordinates: the ANCF centre-line point r(ξ).
fn centre_line_point(e: &[f64], le: f64, xi: f64) -> [f64; 2] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    let s = [
        2.0 * x3 - 3.0 * x2 + 1.0,
        le * (x3 - 2.0 * x2 + xi),
        -2.0 * x3 + 3.0 * x2,
        le * (x3 - x2),
    ];
    let mut r = [0.0; 2];
    for i in 0..4 {
        r[0] += s[i] * e[2 * i];
        r[1] += s[i] * e[2 * i + 1];
    }
    r
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn free_beam_modes(elements: usize) -> (System, ModalResult) {
    let system = System::new(&free_beam(elements));
    let result = modal_all(&free_beam(elements));
    (system, result)
}

// -------------------------------------------------------------- mode shapes

#[test]
fn mode_shapes_render_as_png_and_svg() {
    let m = Model::builtin();
    let system = System::new(&m);
    let result = modal_all(&m);
    let fig: Figure = mode_shape_figure(&system, &result, 6).into();
    check_png(
        &render(&fig, Format::Png, SIZE).unwrap(),
        SIZE,
        "mode shapes",
    );
    let svg = parse_svg(&render(&fig, Format::Svg, SIZE).unwrap());
    // Titles from the modal result: the first elastic mode after the
    // rigid ones, its frequency to 0.1 Hz and its kind.
    let first = result.modes.iter().find(|m| !m.kind.is_zero()).unwrap();
    let subtitle = format!(
        "Mode {}: {:.1} Hz ({})",
        first.index, first.frequency_hz, first.kind
    );
    let ModeShapeFigure { title, .. } = mode_shape_figure(&system, &result, 6);
    assert_texts(
        &svg,
        &[&title, "x [mm]", "y [mm]", &subtitle],
        "mode shapes",
    );
    assert!(title.contains("rcbo_free_free"), "title names the model");
    // Data: beam centre lines in grey and in the first palette colour.
    let blue = svg
        .polylines
        .iter()
        .filter(|(s, p)| s.eq_ignore_ascii_case("#0072B2") && p.len() > 16);
    assert_eq!(
        blue.count(),
        6,
        "one deformed blade polyline per mode subplot"
    );
}

#[test]
fn rigid_modes_are_skipped_unless_asked_for() {
    let (system, result) = free_beam_modes(8);
    assert_eq!(
        result.rigid_modes, 3,
        "a free planar beam has 3 rigid modes"
    );
    let fig = mode_shape_figure(&system, &result, 4);
    let numbers: Vec<usize> = fig.modes.iter().map(|m| m.number).collect();
    assert_eq!(
        numbers,
        [4, 5, 6, 7],
        "first four elastic modes, numbered 1-based"
    );
    let settings = ModeShapeSettings {
        modes: 4,
        include_rigid: true,
        ..ModeShapeSettings::default()
    };
    let fig = mode_shape_figure_with(&system, &system.q0, &result, &settings);
    let numbers: Vec<usize> = fig.modes.iter().map(|m| m.number).collect();
    assert_eq!(numbers, [1, 2, 3, 4], "rigid modes included on request");
    assert_eq!(fig.modes[0].kind, "rigid");
}

#[test]
fn undeformed_straight_beam_is_straight_with_its_length() {
    let (x0, y0, angle) = (1e-3, -2e-3, 30f64.to_radians());
    let m = model(json!({
        "name": "tilted",
        "beams": [{
            "id": "b", "start": [x0, y0], "angle_deg": 30.0, "length": L, "elements": 5,
            "section": {"height": H, "width": 5e-3},
            "material": {"young": 127e9, "density": 8940.0}
        }]
    }));
    let system = System::new(&m);
    let g = assembly_geometry(&system, &system.q0, 16);
    assert_eq!(g.beams.len(), 1);
    let line = &g.beams[0];
    assert_eq!(
        line.len(),
        5 * 16 + 1,
        "16 samples per element, shared nodes once"
    );
    let t = [angle.cos(), angle.sin()];
    let length: f64 = line.windows(2).map(|w| dist(w[0], w[1])).sum();
    assert!(
        (length - L).abs() < 1e-12 * L,
        "polyline length {length} m, beam length {L} m"
    );
    for p in line {
        let off = -(p[0] - x0) * t[1] + (p[1] - y0) * t[0];
        assert!(
            off.abs() < 1e-15,
            "point {p:?} is {off:e} m off the beam axis"
        );
    }
    assert!(dist(line[0], [x0, y0]) < 1e-15, "starts at the beam start");
    let end = [x0 + L * t[0], y0 + L * t[1]];
    assert!(
        dist(line[line.len() - 1], end) < 1e-15,
        "ends at start + L·t"
    );
}

#[test]
fn bodies_and_joints_are_drawn_at_their_positions() {
    // The built-in assembly: slot body and pad from the model file, the
    // weld at s = 18.94 mm along the blade, the pin at its node 0.
    let m = Model::builtin();
    let system = System::new(&m);
    let g = assembly_geometry(&system, &system.q0, 16);
    let (start, angle) = (m.beams[0].start, m.beams[0].angle_deg.to_radians());
    let weld = [
        start[0] + 18.94e-3 * angle.cos(),
        start[1] + 18.94e-3 * angle.sin(),
    ];
    // Drawn where the model sits (the system works about its centre of
    // mass; the round trip costs at most an ulp of the coordinates).
    // The slot body is the outline of its centre and attachment points
    // (its centre among them, or inside); the pad, a point mass, a marker.
    assert_eq!(g.bodies.len(), 1);
    assert_eq!(g.masses.len(), 1);
    let given = m.rigid_bodies[0].position;
    let outline = &g.bodies[0];
    let on_a_vertex = outline.iter().any(|p| dist(*p, given) < 1e-15);
    let inside = outline.len() >= 3
        && (0..outline.len()).all(|i| {
            let (a, b) = (outline[i], outline[(i + 1) % outline.len()]);
            (b[0] - a[0]) * (given[1] - a[1]) - (b[1] - a[1]) * (given[0] - a[0]) >= 0.0
        });
    assert!(
        on_a_vertex || inside,
        "body at {given:?}, outline {outline:?}"
    );
    assert!(
        dist(g.masses[0], m.point_masses[0].position) < 1e-17,
        "pad at {:?}",
        g.masses[0]
    );
    assert_eq!(g.joints.len(), 2, "weld and pin");
    assert!(
        dist(g.joints[0].at, weld) < 1e-12,
        "weld at {:?}",
        g.joints[0]
    );
    assert!(
        dist(g.joints[1].at, start) < 1e-12,
        "pin at {:?}",
        g.joints[1]
    );
}

#[test]
fn deformed_centre_line_is_the_ancf_interpolation_of_the_mode() {
    // Four elements: the first bending mode visibly curves inside each.
    let (system, result) = free_beam_modes(4);
    let fig = mode_shape_figure(&system, &result, 1);
    let mode = result.first_bending().unwrap();
    assert_eq!(fig.modes[0].number, mode.index, "1-based mode number");
    let drawn = &fig.modes[0].deformed.beams[0];
    let beam = &system.beams[0];
    let le = L / 4.0;
    let e = |q: &[f64], k: usize| -> Vec<f64> { beam.element_dofs(k).map(|i| q[i]).to_vec() };
    let (q0, phi) = (&system.q0, &mode.shape);
    // The amplitude from the drawn tip: tip = S(1)(e0 + aφ) along S(1)φ.
    // Drawn in the model's frame: the system's origin added.
    let o = [system.origin.x, system.origin.y];
    let shifted = |p: [f64; 2]| [p[0] + o[0], p[1] + o[1]];
    let tip0 = shifted(centre_line_point(&e(q0, 3), le, 1.0));
    let tip_phi = centre_line_point(&e(phi, 3), le, 1.0);
    let tip = drawn[drawn.len() - 1];
    let a = ((tip[0] - tip0[0]) * tip_phi[0] + (tip[1] - tip0[1]) * tip_phi[1])
        / (tip_phi[0].powi(2) + tip_phi[1].powi(2));
    let expect = |k: usize, xi: f64| {
        let e0 = e(q0, k);
        let ep = e(phi, k);
        let ea: Vec<f64> = e0.iter().zip(&ep).map(|(x, p)| x + a * p).collect();
        shifted(centre_line_point(&ea, le, xi))
    };
    assert!(dist(tip, expect(3, 1.0)) < 1e-12 * L, "tip {tip:?}");
    // Every drawn sample j of element k is r(j/16) with the same a.
    for k in 0..4 {
        for j in 0..=16 {
            let p = drawn[16 * k + j];
            let r = expect(k, j as f64 / 16.0);
            assert!(
                dist(p, r) < 1e-12 * L,
                "element {k} ξ = {j}/16: drawn {p:?}, S(ξ)(e0 + aφ) = {r:?}"
            );
        }
    }
    // Curved, not chords: the middle of element 1 sags off its chord.
    let chord = [
        0.5 * (drawn[16][0] + drawn[32][0]),
        0.5 * (drawn[16][1] + drawn[32][1]),
    ];
    let sag = dist(drawn[24], chord);
    assert!(
        sag > 5e-3 * L,
        "element sag {sag:e} m (expected > 0.5 % of L)"
    );
    // Amplitude: the largest drawn displacement is 15 % of the assembly
    // size (the beam length), by the figure's scaling.
    let undeformed = &fig.undeformed.beams[0];
    let disp: Vec<f64> = drawn
        .iter()
        .zip(undeformed)
        .map(|(p, p0)| dist(*p, *p0))
        .collect();
    let largest = disp.iter().copied().fold(0.0, f64::max);
    assert!(
        (largest / L - 0.15).abs() < 1e-12,
        "largest displacement {largest:e} m = {:.4} L (expected 0.15 L)",
        largest / L
    );
    // The free-free tips move most, and alike to the computed mode's
    // accuracy. The exact mode is symmetric; the computed one is
    // cos θ φ* + sin θ e (‖e‖_M = 1), and a unit-M e moves a tip node by at
    // most g = √λmax((M⁻¹) at its position coordinates). Davis–Kahan:
    // sin θ ≤ ‖Kφ − λMφ‖_{M⁻¹}/δ, δ = the gap from λ to the rest of the
    // spectrum (the rigid modes at 0, the second bending mode).
    let (first, last) = (disp[0], disp[disp.len() - 1]);
    assert!(
        largest == first || largest == last,
        "tips move most: largest {largest:e} m, tips {first:e} / {last:e} m"
    );
    let bending: Vec<f64> = result
        .of_kind(ModeKind::Bending)
        .map(|m| m.eigenvalue)
        .collect();
    let gap = bending[0].min(bending[1] - bending[0]);
    let n = phi.len();
    let mass = system.mass_matrix();
    let mut k = faer::Mat::zeros(n, n);
    system.tangent_stiffness(&system.reference(), &mut k);
    let x = faer::Mat::from_fn(n, 1, |i, _| phi[i]);
    let r = &k * &x - (&mass * &x) * faer::Scale(mode.eigenvalue);
    use faer::linalg::solvers::{DenseSolveCore, Solve};
    let llt = mass
        .llt(faer::Side::Lower)
        .expect("mass is positive definite");
    let m_inv_r = llt.solve(&r);
    let sin_theta = (0..n)
        .map(|i| r[(i, 0)] * m_inv_r[(i, 0)])
        .sum::<f64>()
        .sqrt()
        / gap;
    let m_inv = llt.inverse();
    // A tip node's position coordinates are the first two of its four.
    let gain = |i: usize| {
        let (a, b, c) = (m_inv[(i, i)], m_inv[(i, i + 1)], m_inv[(i + 1, i + 1)]);
        (0.5 * (a + c) + (0.25 * (a - c).powi(2) + b * b).sqrt()).sqrt()
    };
    let tip_unit = phi[n - 4].hypot(phi[n - 3]);
    let allowance = sin_theta * (gain(0) + gain(n - 4)) / tip_unit;
    assert!(
        (first - last).abs() <= allowance * largest,
        "tips {first:e} / {last:e} m differ by more than sin θ·(g₀ + g₁)/|tip φ| = {allowance:e}"
    );
    assert!(
        allowance < 1e-6,
        "mode accuracy bound {allowance:e}: residual too large"
    );
}

#[test]
fn drawn_tip_lands_on_its_pixel_in_the_svg() {
    let (system, result) = free_beam_modes(4);
    let fig = mode_shape_figure(&system, &result, 2);
    let tip = *fig.modes[1].deformed.beams[0].last().unwrap();
    let figure: Figure = fig.into();
    let pixel = figure
        .pixel_of(SIZE, 1, tip[0], tip[1])
        .unwrap()
        .expect("tip is shown");
    let svg = parse_svg(&render(&figure, Format::Svg, SIZE).unwrap());
    let found = svg
        .polylines
        .iter()
        .filter(|(s, _)| s.eq_ignore_ascii_case("#0072B2"))
        .any(|(_, pts)| {
            pts.iter()
                .any(|&(x, y)| (x - pixel.0).abs() <= 1 && (y - pixel.1).abs() <= 1)
        });
    assert!(
        found,
        "no deformed polyline vertex at the tip pixel {pixel:?}"
    );
}

// -------------------------------------------------------------- convergence

fn euler_bernoulli() -> Vec<f64> {
    FREE_FREE_BL[..3]
        .iter()
        .map(|&bl| euler_bernoulli_hz(bl, L, H))
        .collect()
}

fn convergence_of_free_beam() -> ConvergenceData {
    mesh_convergence(|n| free_beam(n).into_model(), &euler_bernoulli()).expect("study runs")
}

#[test]
fn convergence_points_are_the_independent_errors() {
    let data = convergence_of_free_beam();
    let exact = euler_bernoulli();
    let fig: LineFigure = convergence_figure(&data);
    let panel = &fig.panels[0];
    assert_eq!(data.elements, [2, 4, 8, 16, 32, 64]);
    for (i, &n) in data.elements.iter().enumerate() {
        let r = modal_all(&free_beam(n));
        let f = common::freqs(&r, ModeKind::Bending);
        for k in 0..3 {
            let err = ((f[k] - exact[k]) / exact[k]).abs();
            let series = &panel.series[k];
            assert_eq!(series.x[i], n as f64, "x of point {i}");
            assert!(
                (series.y[i] - err).abs() <= 1e-9 * err,
                "mode {k} at {n} elements: drawn {:e}, independent {err:e}",
                series.y[i]
            );
        }
    }
    // Physics: 8 elements are high by 8.1e-5 (DESIGN, also Exudyn's
    // ANCFCable2D), and the error falls as h⁴ (ratio 16 per halving).
    let e1 = &data.errors[0];
    assert!(
        (e1[2] / 8.1e-5 - 1.0).abs() < 0.03,
        "f1 error at 8 elements {:e} (expected 8.1e-5 ± 3 %)",
        e1[2]
    );
    // (4 → 8 elements is still pre-asymptotic: 3.75; from 8 on ≥ 3.94.)
    for i in 2..5 {
        let p = data.observed_order(0, i);
        assert!(
            (p - 4.0).abs() < 0.15,
            "observed order {p} between meshes {i} and {}",
            i + 1
        );
    }
    // The O(h⁴) reference series falls 16× per doubling.
    let slope = panel.series.last().unwrap();
    assert_eq!(slope.name, "O(h⁴)");
    for w in slope.y.windows(2) {
        assert!(
            (w[0] / w[1] - 16.0).abs() < 1e-9,
            "reference slope ratio {}",
            w[0] / w[1]
        );
    }
}

#[test]
fn convergence_figure_renders_with_points_where_the_axes_put_them() {
    let data = convergence_of_free_beam();
    let fig: Figure = convergence_figure(&data).into();
    check_png(
        &render(&fig, Format::Png, SIZE).unwrap(),
        SIZE,
        "convergence",
    );
    let svg = parse_svg(&render(&fig, Format::Svg, SIZE).unwrap());
    let Figure::Line(line) = &fig else {
        unreachable!()
    };
    assert_texts(
        &svg,
        &[
            &line.title,
            "Number of elements",
            "Relative error",
            "O(h⁴)",
            &format!("bending 1: {:.1} Hz", euler_bernoulli()[0]),
        ],
        "convergence",
    );
    assert!(!svg.polylines.is_empty(), "convergence: no data polyline");
    for (i, &n) in data.elements.iter().enumerate() {
        let px = fig
            .pixel_of(SIZE, 0, n as f64, data.errors[0][i])
            .unwrap()
            .expect("error point is shown");
        assert!(
            svg.circles.contains(&px),
            "no marker at {px:?} for {n} elements"
        );
    }
}

#[test]
fn finest_mesh_reference_and_analytic_detection() {
    let builtin = Model::builtin();
    assert_eq!(
        euler_bernoulli_free_free(&builtin, 3),
        None,
        "the assembly has no analytic solution"
    );
    let eb = euler_bernoulli_free_free(&free_beam(8), 3).expect("single free beam");
    for (f, g) in eb.iter().zip(euler_bernoulli()) {
        assert!((f / g - 1.0).abs() < 1e-12, "Euler–Bernoulli {f} vs {g} Hz");
    }
    let data = mesh_convergence_with(
        |n| with_elements(&builtin, n),
        Reference::FinestMesh { modes: 2 },
        &[8, 2, 4],
    )
    .unwrap();
    assert_eq!(data.elements, [2, 4, 8], "sorted");
    assert_eq!(data.reference_kind, ReferenceKind::FinestMesh);
    let mesh = |n| {
        with_elements(&builtin, n)
            .validated()
            .expect("a valid mesh")
    };
    let finest = common::freqs(&modal_all(&mesh(8)), ModeKind::Bending);
    for (i, &n) in [2, 4].iter().enumerate() {
        let f = common::freqs(&modal_all(&mesh(n)), ModeKind::Bending);
        for k in 0..2 {
            let err = ((f[k] - finest[k]) / finest[k]).abs();
            assert!(
                (data.errors[k][i] - err).abs() <= 1e-9 * err,
                "mode {k}, {n} elements: {:e} vs {err:e}",
                data.errors[k][i]
            );
        }
    }
    assert!(
        data.errors[0][2].is_nan(),
        "finest mesh has no error of its own"
    );
}

// --------------------------------------------------------------------- CLI

fn cli() -> Command {
    Command::cargo_bin("ancf-modal").unwrap()
}

fn one_error_line(out: &std::process::Output) -> String {
    assert_eq!(out.status.code(), Some(1), "exit code");
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(err.starts_with("Error: "), "{err}");
    err
}

#[test]
fn modal_plot_writes_a_valid_png_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("modes.png");
    cli().args(["modal", "--plot"]).arg(&png).assert().success();
    check_png(&std::fs::read(&png).unwrap(), SIZE, "modal --plot");
    let svg = dir.path().join("modes.SVG");
    cli()
        .args(["modal", "--modes", "5", "--plot"])
        .arg(&svg)
        .assert()
        .success();
    let svg = parse_svg(&std::fs::read(&svg).unwrap());
    let subtitles = svg
        .texts
        .iter()
        .filter(|t| t.starts_with("Mode ") && t.ends_with("Hz (bending)"))
        .count();
    assert_eq!(
        subtitles, 2,
        "--modes 5 with 3 rigid modes leaves 2 elastic ones"
    );
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(names.len(), 2, "no temporary file left: {names:?}");
}

#[test]
fn modal_plot_with_unknown_extension_fails_without_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let bmp = dir.path().join("x.bmp");
    let out = cli().args(["modal", "--plot"]).arg(&bmp).output().unwrap();
    let err = one_error_line(&out);
    assert!(
        err.contains(&bmp.display().to_string()),
        "names the path: {err}"
    );
    assert!(err.contains("unknown plot format"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "no file");
}

#[test]
fn modal_plot_into_a_missing_directory_fails_without_a_file() {
    let path = std::path::Path::new("/nonexistent/dir/x.svg");
    let out = cli().args(["modal", "--plot"]).arg(path).output().unwrap();
    let err = one_error_line(&out);
    assert!(err.contains("/nonexistent/dir/x.svg"), "{err}");
    assert!(!path.exists());
}

#[test]
fn convergence_command_uses_euler_bernoulli_for_a_free_beam() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("conv.svg");
    let out = cli()
        .args([
            "convergence",
            "models/beam_free_free.json",
            "--max-elements",
            "16",
            "--json",
            "--plot",
        ])
        .arg(&plot)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["reference"], "exact");
    assert_eq!(doc["elements"], json!([2, 4, 8, 16]));
    let f1 = doc["reference_hz"][0].as_f64().unwrap();
    let eb = euler_bernoulli()[0];
    assert!(
        (f1 / eb - 1.0).abs() < 1e-12,
        "reference f1 {f1} vs {eb} Hz"
    );
    let e8 = doc["relative_errors"][0][2].as_f64().unwrap();
    assert!(
        (e8 / 8.1e-5 - 1.0).abs() < 0.03,
        "error at 8 elements {e8:e}"
    );
    parse_svg(&std::fs::read(&plot).unwrap());
}

#[test]
fn convergence_command_without_analytic_solution_says_so() {
    let out = cli()
        .args(["convergence", "--max-elements", "8"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("the finest mesh (8 elements)"),
        "reference named: {table}"
    );
    let out = cli()
        .args(["convergence", "--plot", "c.bmp"])
        .output()
        .unwrap();
    let err = one_error_line(&out);
    assert!(err.contains("c.bmp"), "{err}");
    assert!(!std::path::Path::new("c.bmp").exists());
}

#[test]
fn modal_plot_without_elastic_modes_fails_without_a_file() {
    // The built-in assembly has 3 rigid modes: `--modes 2` reports only
    // rigid ones, so there is no elastic shape to draw.
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("none.png");
    let out = cli()
        .args(["modal", "--modes", "2", "--plot"])
        .arg(&png)
        .output()
        .unwrap();
    let err = one_error_line(&out);
    assert!(err.contains("no elastic"), "{err}");
    assert!(!png.exists(), "no file");
}
