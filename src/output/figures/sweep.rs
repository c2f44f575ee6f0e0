//! Figures of a parameter study ([`crate::analysis::sweep`]):
//!
//! * one parameter, a tracked frequency (`frequency:K`): a Campbell-style
//!   diagram, every tracked mode's frequency against the parameter, so
//!   crossing modes show as crossing lines (not as the kinks of sorted
//!   frequencies);
//! * one parameter, another quantity: the quantity against the parameter;
//! * two parameters: a heat map of the quantity over the grid (the second
//!   parameter along x, the first along y);
//! * one parameter, `time_to_distance_s`: the tracked point's (node 0's)
//!   x displacement from its ON state against time for every point
//!   overlaid, with the travel distance as a reference line — the paper's
//!   Fig. 10 panels; each legend entry gives the value and its time.
//!
//! Failed points leave gaps (lines) or grey cells (heat map). Parameters
//! are shown in the model file's SI units; frequencies with an SI prefix.

use crate::analysis::sweep::{ParameterValues, Quantity, SweepDocument};
use crate::analysis::switch_off::SwitchOffSettings;
use crate::output::plot::{
    render, write_atomic, Figure, Format, Guide, HeatMap, Legend, LineFigure, Panel, PlotError,
    PlotSize, Scale, Series, SeriesStyle,
};
use std::path::Path;

/// Refuses, before a sweep runs, a plot file it could not draw: an unknown
/// extension, or more than two parameters.
pub fn check_plottable(path: &Path, parameters: usize) -> Result<(), PlotError> {
    Format::from_path(path)?;
    if !(1..=2).contains(&parameters) {
        return Err(PlotError::EmptyData {
            what: format!(
                "a sweep over {parameters} parameters has no figure (one parameter: lines, two: a heat map)"
            ),
        });
    }
    Ok(())
}

/// The x-axis label of a parameter.
fn axis_label(name: &str) -> String {
    if name.starts_with("load_scale:") {
        format!("Load factor ({name})")
    } else {
        name.to_string()
    }
}

/// The SI unit of the number at a model path (by its key, section 4 of
/// the design), and whether an SI prefix suits it.
fn unit_of(target: &str) -> Option<(&'static str, bool)> {
    if target.contains(".time.") {
        return Some(("s", true));
    }
    let key = target.rsplit('.').next()?;
    let key = key.split('[').next()?;
    Some(match key {
        "height" | "width" | "length" | "s" | "start" | "position" | "ground" | "local"
        | "free_length" => ("m", true),
        "young" => ("Pa", true),
        "force" | "preload" => ("N", true),
        "density" => ("kg/m³", false),
        "mass" => ("kg", false),
        "inertia" => ("kg m²", false),
        "stiffness" => ("N/m", false),
        "torsion_stiffness" => ("N m/rad", false),
        "damping" => ("N s/m", false),
        "torsion_damping" => ("N m s/rad", false),
        "angle_deg" => ("°", false),
        "gravity" => ("m/s²", false),
        _ => return None,
    })
}

/// How a parameter's values are shown.
fn parameter_scale(p: &ParameterValues) -> Scale {
    let max = p.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    match unit_of(&p.target) {
        Some((unit, true)) => Scale::si(unit, max),
        Some((unit, false)) => Scale::unit(unit),
        None => Scale::none(),
    }
}

fn nan(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}

/// A parameter value for a legend, in the axis's unit.
fn value_label(p: &ParameterValues, v: f64) -> String {
    let scale = parameter_scale(p);
    let unit = if scale.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", scale.unit)
    };
    format!("{} = {:.4}{unit}", p.name, v * scale.factor)
}

/// Node 0's x(t) of every point of a one-parameter switch-off sweep
/// (`None` when the document carries no traces).
fn trace_figure(d: &SweepDocument, p: &ParameterValues) -> Option<LineFigure> {
    if !d.points.iter().any(|r| r.node0.is_some()) {
        return None;
    }
    let mut panel = Panel::new("Displacement x of node 0", Scale::mm());
    for r in &d.points {
        let Some(t) = &r.node0 else { continue };
        let x0 = t.x_m.first().copied().unwrap_or(0.0);
        let dx = t.x_m.iter().map(|x| x - x0).collect();
        let time = match r.result {
            Some(s) => format!("{:.3} ms", s * 1e3),
            None => "not reached".to_string(),
        };
        panel.series.push(Series::line(
            format!("{}: {time}", value_label(p, r.values[0])),
            t.time_s.clone(),
            dx,
        ));
    }
    let distance = SwitchOffSettings::default().distance;
    panel.hlines.push(Guide::reference(
        distance,
        format!("{:.3} mm", distance * 1e3),
    ));
    panel.legend = Legend::UpperLeft;
    let mut fig = LineFigure::new(
        format!("{}: node 0 against time, {}", d.model, p.name),
        "Time",
        Scale::ms(),
    );
    fig.panels.push(panel);
    Some(fig)
}

/// The figure of a sweep document (complete, not a shard).
pub fn sweep_figure(d: &SweepDocument) -> Result<Figure, PlotError> {
    let fmax = d
        .points
        .iter()
        .flat_map(|p| {
            let tracked = p.frequencies_hz.iter().flatten().copied().flatten();
            p.result.into_iter().chain(tracked)
        })
        .fold(0.0, f64::max);
    // What the quantity is and its unit (frequencies in Hz, the switch-off
    // time in s, a sensor peak in the sensor's unit).
    let (z_label, unit) = match Quantity::parse(&d.quantity) {
        Ok(Quantity::FirstBendingHz | Quantity::Frequency { .. }) => {
            ("Frequency".to_string(), "Hz")
        }
        Ok(q) => (q.label(), q.unit()),
        Err(_) => (d.quantity.clone(), ""),
    };
    let z_scale = Scale::si(unit, fmax);
    match &d.parameters[..] {
        [p] => {
            if let Some(fig) = trace_figure(d, p) {
                return Ok(fig.into());
            }
            let x: Vec<f64> = d.points.iter().map(|r| r.values[0]).collect();
            let mut fig = LineFigure::new(
                format!("{}: {} against {}", d.model, d.quantity, p.name),
                axis_label(&p.name),
                parameter_scale(p),
            );
            fig.x_log = p.log;
            let mut panel = Panel::new(z_label, z_scale);
            match d.tracked_modes {
                Some(n) => {
                    let k = d
                        .quantity
                        .strip_prefix("frequency:")
                        .and_then(|k| k.parse::<usize>().ok());
                    for j in 0..n {
                        let y = d
                            .points
                            .iter()
                            .map(|r| {
                                nan(r
                                    .frequencies_hz
                                    .as_ref()
                                    .and_then(|f| f.get(j).copied().flatten()))
                            })
                            .collect();
                        let name = if k == Some(j + 1) {
                            format!("mode {} ({})", j + 1, d.quantity)
                        } else {
                            format!("mode {}", j + 1)
                        };
                        panel
                            .series
                            .push(Series::new(name, x.clone(), y, SeriesStyle::LinePoints));
                    }
                    fig.title = format!("{}: tracked elastic modes against {}", d.model, p.name);
                }
                None => {
                    let y = d.points.iter().map(|r| nan(r.result)).collect();
                    panel.series.push(Series::new(
                        d.quantity.clone(),
                        x,
                        y,
                        SeriesStyle::LinePoints,
                    ));
                }
            }
            fig.panels.push(panel);
            Ok(fig.into())
        }
        [slow, fast] => {
            let (ny, nx) = (slow.values.len(), fast.values.len());
            let z = (0..ny)
                .map(|j| {
                    (0..nx)
                        .map(|i| nan(d.points.get(j * nx + i).and_then(|r| r.result)))
                        .collect()
                })
                .collect();
            Ok(HeatMap {
                title: format!("{}: {}", d.model, d.quantity),
                x_label: axis_label(&fast.name),
                x_scale: parameter_scale(fast),
                x_log: fast.log,
                y_label: axis_label(&slow.name),
                y_scale: parameter_scale(slow),
                y_log: slow.log,
                x: fast.values.clone(),
                y: slow.values.clone(),
                z,
                z_label,
                z_scale,
            }
            .into())
        }
        other => Err(PlotError::EmptyData {
            what: format!("a sweep over {} parameters has no figure", other.len()),
        }),
    }
}

/// Renders the figure of `d` to `path` (`.svg` or `.png`), atomically.
pub fn write_sweep_figure(d: &SweepDocument, path: &Path) -> Result<(), PlotError> {
    let format = Format::from_path(path)?;
    let bytes = render(&sweep_figure(d)?, format, PlotSize::default())?;
    write_atomic(path, &bytes)
}
