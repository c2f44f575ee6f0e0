//! Properties of rendered figures: PNGs decode at the requested size and
//! carry drawn text, SVGs are well-formed and name what they show, markers
//! sit where the axis mapping puts them, and errors are typed.

mod plot_common;
use plot_common as common;

use ancf_modal::output::plot::*;
use std::path::Path;

const W: u32 = 1200;
const H: u32 = 800;

struct Image {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Image {
    fn decode(bytes: &[u8]) -> Image {
        let decoder = png::Decoder::new(bytes);
        let mut reader = decoder.read_info().expect("PNG header");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("PNG data");
        assert_eq!(info.color_type, png::ColorType::Rgb);
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        buf.truncate(info.buffer_size());
        Image {
            width: info.width,
            height: info.height,
            rgb: buf,
        }
    }

    fn is_background(&self, x: u32, y: u32) -> bool {
        let i = 3 * (y * self.width + x) as usize;
        self.rgb[i..i + 3] == [255, 255, 255]
    }

    /// Pixels not of the background colour in `[x0, x1) × [y0, y1)`.
    fn ink(&self, (x0, x1): (u32, u32), (y0, y1): (u32, u32)) -> usize {
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| !self.is_background(x, y))
            .count()
    }

    fn ink_fraction(&self) -> f64 {
        self.ink((0, self.width), (0, self.height)) as f64 / (self.width * self.height) as f64
    }
}

fn png_of(figure: &Figure, size: PlotSize) -> Image {
    Image::decode(&render(figure, Format::Png, size).expect("renders as PNG"))
}

fn svg_of(figure: &Figure) -> String {
    let bytes = render(figure, Format::Svg, PlotSize::default()).expect("renders as SVG");
    String::from_utf8(bytes).expect("SVG is UTF-8")
}

/// Texts of all `<text>` elements, and the element names, of a well-formed SVG.
fn parse_svg(svg: &str) -> (Vec<String>, Vec<String>) {
    let doc = roxmltree::Document::parse(svg).expect("SVG is well-formed XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    let texts = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or("").trim().to_string())
        .collect();
    let names = doc
        .descendants()
        .filter(|n| n.is_element())
        .map(|n| n.tag_name().name().to_string())
        .collect();
    (texts, names)
}

fn all_figures() -> Vec<(&'static str, Figure, Vec<&'static str>)> {
    vec![
        (
            "Impulse response, tip sensor",
            common::impulse_response().into(),
            vec![
                "Time [ms]",
                "Acceleration [m/s²]",
                "Force [N]",
                "sensor (tip)",
            ],
        ),
        (
            "Frequency response, tip",
            common::frf(false).into(),
            vec![
                "Frequency [kHz]",
                "Magnitude [dB]",
                "experiment 4600 Hz",
                "f1 = 4577 Hz",
            ],
        ),
        (
            "Mode shapes, clamped beam with tip mass",
            common::mode_shapes(4).into(),
            vec![
                "x [mm]",
                "y [mm]",
                "Mode 1: 4577.3 Hz (bending)",
                "Mode 3: 16900.0 Hz (axial)",
            ],
        ),
        (
            "Calibration of the joint stiffness",
            common::calibration().into(),
            vec![
                "Joint stiffness [kN·m/rad]",
                "Frequency [Hz]",
                "experiment 4600 Hz",
                "4, 5",
            ],
        ),
        (
            "Mesh convergence of the eigenfrequencies",
            common::convergence().into(),
            vec!["Number of elements", "Relative error", "O(h⁴)", "10⁻⁶"],
        ),
    ]
}

#[test]
fn every_figure_renders_a_png_with_drawn_text() {
    for (title, figure, _) in all_figures() {
        let img = png_of(&figure, PlotSize::default());
        assert_eq!((img.width, img.height), (W, H), "{title}");
        let f = img.ink_fraction();
        assert!(
            f > 0.01,
            "{title}: only {:.2} % of the pixels are drawn",
            100.0 * f
        );
        // The title band (centre third of the top 50 rows) holds only the
        // title: ink there is rendered glyphs.
        let title_ink = img.ink((W / 3, 2 * W / 3), (0, 50));
        assert!(title_ink > 200, "{title}: {title_ink} pixels of title text");
        // The bottom 30 rows hold only x-axis descriptions.
        let label_ink = img.ink((0, W), (H - 30, H));
        assert!(
            label_ink > 50,
            "{title}: {label_ink} pixels of x-axis label"
        );
    }
}

#[test]
fn title_pixels_come_from_the_title_text() {
    let mut line = common::frf(false);
    let mut modes = common::mode_shapes(2);
    line.title.clear();
    modes.title.clear();
    for figure in [Figure::from(line), Figure::from(modes)] {
        let img = png_of(&figure, PlotSize::default());
        assert_eq!(
            img.ink((W / 3, 2 * W / 3), (0, 12)),
            0,
            "no title, no ink at the top"
        );
    }
}

#[test]
fn png_has_the_requested_size() {
    for size in [
        PlotSize {
            width: 640,
            height: 420,
        },
        PlotSize {
            width: 1600,
            height: 1000,
        },
    ] {
        for (title, figure, _) in all_figures() {
            let img = png_of(&figure, size);
            assert_eq!(
                (img.width, img.height),
                (size.width, size.height),
                "{title}"
            );
            assert!(img.ink_fraction() > 0.01, "{title}");
        }
    }
}

#[test]
fn every_figure_renders_a_well_formed_svg_naming_its_content() {
    for (title, figure, labels) in all_figures() {
        let svg = svg_of(&figure);
        let (texts, names) = parse_svg(&svg);
        assert!(
            texts.iter().any(|t| t == title),
            "{title}: title missing in {texts:?}"
        );
        for label in labels {
            assert!(
                texts.iter().any(|t| t == label),
                "{title}: `{label}` missing in {texts:?}"
            );
        }
        assert!(
            names.iter().any(|n| n == "polyline" || n == "path"),
            "{title}: no polyline or path"
        );
    }
}

/// The expected pixel of `v` on an axis from its pixel ends and range.
fn expected_pixel(v: f64, range: (f64, f64), pixels: (i32, i32), log: bool) -> f64 {
    let t = |v: f64| if log { v.log10() } else { v };
    let frac = (t(v) - t(range.0)) / (t(range.1) - t(range.0));
    pixels.0 as f64 + frac * (pixels.1 - pixels.0) as f64
}

fn circles(svg: &str) -> Vec<(i32, i32)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("circle"))
        .map(|n| {
            let a = |k| n.attribute(k).unwrap().parse::<f64>().unwrap() as i32;
            (a("cx"), a("cy"))
        })
        .collect()
}

fn assert_marker_at(figure: Figure, x: f64, y: f64) {
    let layout = figure.layout(PlotSize::default()).unwrap();
    let panel = &layout[0];
    let ex = expected_pixel(x, panel.x_range, panel.x_pixels, panel.x_log);
    let ey = expected_pixel(y, panel.y_range, panel.y_pixels, panel.y_log);
    let (px, py) = panel.to_pixel(x, y).expect("point is shown");
    assert!(
        (px as f64 - ex).abs() <= 1.0,
        "x pixel {px}, expected {ex:.2} ({panel:?})"
    );
    assert!(
        (py as f64 - ey).abs() <= 1.0,
        "y pixel {py}, expected {ey:.2} ({panel:?})"
    );
    let direct = figure.pixel_of(PlotSize::default(), 0, x, y).unwrap();
    assert_eq!(direct, Some((px, py)));
    let found = circles(&svg_of(&figure));
    assert!(
        found.contains(&(px, py)),
        "no marker at ({px}, {py}) in {found:?}"
    );
}

#[test]
fn marker_lands_where_the_axis_mapping_puts_it() {
    assert_marker_at(common::single_marker(6180.0, 3.0).into(), 6180.0, 3.0);
    assert_marker_at(common::single_marker(1234.5, -17.25).into(), 1234.5, -17.25);
}

#[test]
fn marker_lands_where_the_log_axis_mapping_puts_it() {
    let fig = common::frf(true);
    let p = fig.panels[0].points[0].clone();
    assert_eq!(p.x, common::PEAK_HZ);
    assert_marker_at(fig.into(), p.x, p.y);
}

#[test]
fn stacked_panels_share_the_x_axis() {
    let layout = Figure::from(common::impulse_response())
        .layout(PlotSize::default())
        .unwrap();
    assert_eq!(layout.len(), 2);
    assert_eq!(layout[0].x_pixels, layout[1].x_pixels);
    assert_eq!(layout[0].x_range, layout[1].x_range);
    assert!(
        layout[0].y_pixels.0 < layout[1].y_pixels.1,
        "top panel above bottom panel"
    );
}

#[test]
fn mode_shapes_have_equal_aspect_ratio() {
    let layout = Figure::from(common::mode_shapes(4))
        .layout(PlotSize::default())
        .unwrap();
    assert_eq!(layout.len(), 4);
    for p in &layout {
        let per_px_x = (p.x_range.1 - p.x_range.0) / (p.x_pixels.1 - p.x_pixels.0) as f64;
        let per_px_y = (p.y_range.1 - p.y_range.0) / (p.y_pixels.0 - p.y_pixels.1) as f64;
        assert!((per_px_x / per_px_y - 1.0).abs() < 1e-9, "{p:?}");
        // The tip of the undeformed beam (0.5 m, 0) is inside the subplot.
        let (px, py) = p.to_pixel(0.5, 0.0).unwrap();
        assert!(px > p.x_pixels.0 && px < p.x_pixels.1 && py < p.y_pixels.0 && py > p.y_pixels.1);
    }
}

#[test]
fn format_follows_the_extension() {
    assert_eq!(
        Format::from_path(Path::new("out/frf.svg")).unwrap(),
        Format::Svg
    );
    assert_eq!(
        Format::from_path(Path::new("FRF.PNG")).unwrap(),
        Format::Png
    );
    assert_eq!(Format::from_path(Path::new("a.Svg")).unwrap(), Format::Svg);
    for bad in ["plot.pdf", "plot", "dir.png/plot.jpeg"] {
        match Format::from_path(Path::new(bad)) {
            Err(e @ PlotError::UnknownExtension { .. }) => {
                let PlotError::UnknownExtension { path } = &e else {
                    unreachable!()
                };
                assert_eq!(path, Path::new(bad));
                assert!(e.to_string().contains(bad), "{e}");
            }
            other => panic!("{bad}: {other:?}"),
        }
    }
}

#[test]
fn write_atomic_writes_and_replaces() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("modes.svg");
    write_atomic(&path, b"first").unwrap();
    write_atomic(&path, b"second").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"second");
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        names,
        vec![std::ffi::OsString::from("modes.svg")],
        "no temporary file left"
    );
}

#[test]
fn write_atomic_into_a_missing_directory_is_a_typed_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no/such/dir/frf.png");
    match write_atomic(&path, b"data") {
        Err(e @ PlotError::Io { .. }) => {
            let text = e.to_string();
            assert!(text.contains(&path.display().to_string()), "{text}");
            assert!(text.contains("does not exist"), "{text}");
        }
        other => panic!("{other:?}"),
    }
    assert!(!path.exists());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing created"
    );
}

#[test]
fn write_atomic_failing_late_leaves_no_file_behind() {
    // The temporary file can be written, but renaming it onto a non-empty
    // directory fails: the temporary file must be gone afterwards.
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("taken.png");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("keep"), b"x").unwrap();
    let err = write_atomic(&target, &[1u8; 4096]).unwrap_err();
    assert!(matches!(err, PlotError::Io { .. }), "{err:?}");
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("taken.png")]);
    assert!(target.is_dir() && target.join("keep").exists());
}

#[test]
fn bad_data_gives_typed_errors() {
    let size = PlotSize::default();
    let empty = LineFigure::new("t", "x", Scale::none());
    assert!(matches!(
        render(&empty.into(), Format::Svg, size),
        Err(PlotError::EmptyData { .. })
    ));

    let mut fig = LineFigure::new("t", "x", Scale::none());
    let mut p = Panel::new("y", Scale::none());
    p.series.push(Series::line("s", vec![1.0, 2.0], vec![1.0]));
    fig.panels.push(p);
    match render(&fig.into(), Format::Png, size) {
        Err(PlotError::LengthMismatch {
            series,
            x_len: 2,
            y_len: 1,
        }) => assert_eq!(series, "s"),
        other => panic!("{other:?}"),
    }

    // Only non-positive values on a log axis: nothing to show.
    let mut fig = LineFigure::new("t", "x", Scale::none());
    let mut p = Panel::new("y", Scale::none());
    p.y_log = true;
    p.series
        .push(Series::line("s", vec![1.0, 2.0], vec![0.0, -1.0]));
    fig.panels.push(p);
    assert!(matches!(
        render(&fig.into(), Format::Svg, size),
        Err(PlotError::EmptyData { .. })
    ));

    let modes = ModeShapeFigure::default();
    assert!(matches!(
        render(&modes.into(), Format::Svg, size),
        Err(PlotError::EmptyData { .. })
    ));

    let tiny = PlotSize {
        width: 10,
        height: 800,
    };
    let fig: Figure = common::frf(false).into();
    assert!(matches!(
        render(&fig, Format::Png, tiny),
        Err(PlotError::InvalidSize { .. })
    ));
}

#[test]
fn gaps_and_long_series_render_compactly() {
    let n = 1_000_000;
    let x: Vec<f64> = (0..n).map(|i| i as f64 * 1e-6).collect();
    let mut y: Vec<f64> = x
        .iter()
        .map(|t| (2.0 * std::f64::consts::PI * 4600.0 * t).sin())
        .collect();
    y[1000] = f64::NAN;
    let mut fig = LineFigure::new("Long signal", "Time", Scale::ms());
    let mut p = Panel::new("Signal", Scale::none());
    p.series.push(Series::line("s", x, y));
    fig.panels.push(p);
    let fig: Figure = fig.into();
    let svg = svg_of(&fig);
    assert!(
        svg.len() < 2_000_000,
        "SVG of {} bytes: the series was not thinned",
        svg.len()
    );
    parse_svg(&svg);
    assert!(png_of(&fig, PlotSize::default()).ink_fraction() > 0.05);
}

#[test]
fn scales_pick_si_prefixes() {
    assert_eq!(Scale::si("s", 0.004), Scale::new(1e3, "ms"));
    assert_eq!(Scale::si("Hz", 12e3), Scale::new(1e-3, "kHz"));
    assert_eq!(Scale::si("Hz", 1000.0).unit, "kHz");
    assert_eq!(Scale::si("m", 2.5e-6).unit, "µm");
    assert_eq!(Scale::si("N", 0.0), Scale::unit("N"));
    assert_eq!(Scale::ms().label("Time"), "Time [ms]");
    assert_eq!(Scale::none().label("Relative error"), "Relative error");
    assert_eq!(Scale::mm().apply(0.25), 250.0);
}
