//! Sample figures with realistic data, shared by the tests and the
//! `samples` example.
#![allow(dead_code)]

use ancf_modal::output::plot::*;
use std::f64::consts::PI;

/// Sensor acceleration over the force pulse, 0–5 ms.
pub fn impulse_response() -> LineFigure {
    let fs = 200e3;
    let t: Vec<f64> = (0..1000).map(|i| i as f64 / fs).collect();
    let modes = [
        (4577.3, 0.02, 120.0),
        (12_640.0, 0.015, 45.0),
        (24_100.0, 0.01, 20.0),
    ];
    let acc = t
        .iter()
        .map(|&t| {
            modes
                .iter()
                .map(|&(f, z, a)| {
                    let w = 2.0 * PI * f;
                    a * (-z * w * t).exp() * (w * t).sin()
                })
                .sum()
        })
        .collect();
    let force = t
        .iter()
        .map(|&t| {
            if t < 50e-6 {
                100.0 * (PI * t / 50e-6).sin()
            } else {
                0.0
            }
        })
        .collect();
    let mut sensor = Panel::new("Acceleration", Scale::unit("m/s²"));
    sensor
        .series
        .push(Series::line("sensor (tip)", t.clone(), acc));
    let mut pulse = Panel::new("Force", Scale::unit("N"));
    pulse.series.push(Series::line("hammer pulse", t, force));
    LineFigure {
        panels: vec![sensor, pulse],
        ..LineFigure::new("Impulse response, tip sensor", "Time", Scale::ms())
    }
}

pub const PEAK_HZ: f64 = 4581.0;

/// Receptance magnitude in dB over frequency, eigenfrequency markers, the
/// 4600 Hz experiment as reference, identified peaks.
pub fn frf(log_x: bool) -> LineFigure {
    let modes = [
        (4577.3, 0.01, 1.0),
        (12_640.0, 0.012, 0.6),
        (16_900.0, 0.02, 0.3),
    ];
    let f: Vec<f64> = (1..=4000).map(|i| i as f64 * 5.0).collect();
    let db = |f: f64| {
        let (mut re, mut im) = (0.0, 0.0);
        for &(fn_, z, a) in &modes {
            let r = f / fn_;
            let den = (1.0 - r * r).powi(2) + (2.0 * z * r).powi(2);
            re += a * (1.0 - r * r) / den;
            im -= a * 2.0 * z * r / den;
        }
        20.0 * (re * re + im * im).sqrt().log10()
    };
    let mag: Vec<f64> = f.iter().map(|&f| db(f)).collect();
    let mut p = Panel::new("Magnitude", Scale::unit("dB"));
    p.series.push(Series::line("|H(f)| model", f.clone(), mag));
    let smooth: Vec<f64> = f.iter().map(|&f| db(f) - 6.0).collect();
    p.series.push(Series::line("|H(f)| measured", f, smooth));
    for (k, &(fr, _, _)) in modes.iter().enumerate() {
        p.vlines
            .push(Guide::new(fr, format!("f{} = {:.0} Hz", k + 1, fr)));
    }
    p.vlines
        .push(Guide::reference(4600.0, "experiment 4600 Hz"));
    p.points.push(PointMarker::new(
        PEAK_HZ,
        db(PEAK_HZ),
        format!("{:.0} Hz, {:.1} dB", PEAK_HZ, db(PEAK_HZ)),
    ));
    p.points.push(PointMarker::new(
        12_640.0,
        db(12_640.0),
        format!("12640 Hz, {:.1} dB", db(12_640.0)),
    ));
    let mut fig = LineFigure::new("Frequency response, tip", "Frequency", Scale::khz());
    fig.panels.push(p);
    if log_x {
        fig.x_log = true;
        fig.x_scale = Scale::hz();
        fig.x_range = Some((100.0, 20e3));
    }
    fig
}

/// A line figure with one peak marker at a known point (for the fidelity test).
pub fn single_marker(x: f64, y: f64) -> LineFigure {
    let mut p = Panel::new("Level", Scale::unit("dB"));
    p.series.push(Series::line(
        "curve",
        vec![0.0, 10_000.0],
        vec![-20.0, 20.0],
    ));
    p.points.push(PointMarker::new(x, y, "peak"));
    LineFigure {
        panels: vec![p],
        ..LineFigure::new("Marker fidelity", "Frequency", Scale::khz())
    }
}

/// Deformed position of the beam point at x.
type Shape<'a> = dyn Fn(f64) -> [f64; 2] + 'a;

/// A weld at `at` (a clamp when `ground`), its part along +x.
fn weld(at: [f64; 2], ground: bool) -> JointMark {
    JointMark {
        kind: JointKind::Weld,
        at,
        ground,
        rail: None,
        toward: [1.0, 0.0],
    }
}

/// Two beams joined at mid-span, a point mass at the tip, four modes.
pub fn mode_shapes(n_modes: usize) -> ModeShapeFigure {
    let l = 0.5;
    let xs: Vec<f64> = (0..=20).map(|i| l * i as f64 / 20.0).collect();
    let beam = |x0: f64, x1: f64, f: &dyn Fn(f64) -> [f64; 2]| -> Vec<[f64; 2]> {
        xs.iter()
            .filter(|&&x| x >= x0 - 1e-12 && x <= x1 + 1e-12)
            .map(|&x| f(x))
            .collect()
    };
    let undeformed = Geometry {
        beams: vec![
            beam(0.0, l / 2.0, &|x| [x, 0.0]),
            beam(l / 2.0, l, &|x| [x, 0.0]),
        ],
        masses: vec![[l, 0.0]],
        joints: vec![weld([l / 2.0, 0.0], false), weld([0.0, 0.0], true)],
        ..Geometry::default()
    };
    let shapes: [(f64, &str, &Shape<'_>); 4] = [
        (4577.3, "bending", &|x: f64| {
            [x, 0.04 * (1.0 - (PI * x / (2.0 * l)).cos())]
        }),
        (12_640.0, "bending", &|x: f64| {
            [x, 0.04 * (1.5 * PI * x / l).sin()]
        }),
        (16_900.0, "axial", &|x: f64| {
            [x + 0.03 * (PI * x / (2.0 * l)).sin(), 0.0]
        }),
        (24_100.0, "bending", &|x: f64| {
            [x, 0.04 * (2.5 * PI * x / l).sin()]
        }),
    ];
    let modes = shapes
        .iter()
        .take(n_modes)
        .enumerate()
        .map(|(k, (f, kind, shape))| ModeShape {
            number: k + 1,
            frequency_hz: *f,
            kind: kind.to_string(),
            deformed: Geometry {
                beams: vec![beam(0.0, l / 2.0, shape), beam(l / 2.0, l, shape)],
                masses: vec![shape(l)],
                joints: vec![weld(shape(l / 2.0), false), weld(shape(0.0), true)],
                ..Geometry::default()
            },
        })
        .collect();
    ModeShapeFigure {
        title: "Mode shapes, clamped beam with tip mass".into(),
        undeformed,
        modes,
        ..ModeShapeFigure::default()
    }
}

pub fn calibration() -> LineFigure {
    let k: Vec<f64> = (0..=60)
        .map(|i| 10f64.powf(3.0 + 2.0 * i as f64 / 60.0))
        .collect();
    let f = |k: f64| 4000.0 + 900.0 * k / (k + 8e3);
    calibration_figure(&Calibration {
        title: "Calibration of the joint stiffness".into(),
        parameter_label: "Joint stiffness".into(),
        parameter_scale: Scale::new(1e-3, "kN·m/rad"),
        parameter_log: true,
        frequency_scale: Scale::hz(),
        sweep_parameter: k.clone(),
        sweep_frequency: k.iter().map(|&k| f(k)).collect(),
        target_hz: 4600.0,
        target_label: "experiment 4600 Hz".into(),
        iterations: [5e3, 4e4, 1.9e4, 1.6e4, 1.6e4]
            .iter()
            .map(|&k| (k, f(k)))
            .collect(),
        fitted: Some((16e3, f(16e3))),
    })
}

pub fn convergence() -> LineFigure {
    let n = vec![2.0, 4.0, 8.0, 16.0, 32.0, 64.0];
    let e1 = n
        .iter()
        .map(|n: &f64| 0.3 * n.powi(-4) * (1.0 + 0.3 / n))
        .collect();
    let e2 = n
        .iter()
        .map(|n: &f64| 2.0 * n.powi(-4) * (1.0 + 1.0 / n))
        .collect();
    convergence_figure(&Convergence {
        title: "Mesh convergence of the eigenfrequencies".into(),
        elements: n,
        errors: vec![("mode 1".into(), e1), ("mode 2".into(), e2)],
        order: 4,
    })
}
