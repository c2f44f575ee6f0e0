//! Figures of the switch-off experiment ([`crate::analysis::switch_off`]),
//! in the style of the paper's Figs. 7–9: the tracked point's x(t) with the
//! travel distance as a reference line (Fig. 7) and y(t) (Fig. 8) as two
//! panels over time [SI: s, shown in ms], and its trajectory y against x
//! (Fig. 9); the flexible run and, when computed, the rigid one overlaid.
//! The distance line and the time marker sit on the panel of the travel
//! direction; a last panel shows the contacts' normal forces and the
//! released loads [SI: N] against time (what the paper's force sensors
//! measured). Titles name the tracked point and the direction.
//! Positions are displacements from each run's own ON state [SI: m, shown
//! in mm], as the paper plots them.

use super::impulse::response_path;
use super::write::write_figure;
use crate::analysis::switch_off::{SwitchOffResult, SwitchOffRun};
use crate::output::plot::{Guide, Legend, LineFigure, Panel, PlotError, PlotSize, Scale, Series};
use std::path::{Path, PathBuf};

fn displacement(v: &[f64]) -> Vec<f64> {
    let v0 = v.first().copied().unwrap_or(0.0);
    v.iter().map(|x| x - v0).collect()
}

fn runs(result: &SwitchOffResult) -> Vec<(&'static str, &SwitchOffRun)> {
    let mut r = vec![("flexible", &result.flexible)];
    if let Some(rigid) = &result.rigid {
        r.push(("rigid", rigid));
    }
    r
}

/// The unit travel direction, and which displacement panel it is: 0 (x),
/// 1 (y) or `None` (oblique: a panel of the displacement along it).
fn travel_axis(result: &SwitchOffResult) -> ([f64; 2], Option<usize>) {
    let [dx, dy] = result.settings.direction;
    let n = dx.hypot(dy);
    let dir = [dx / n, dy / n];
    let axis = if dir[1] == 0.0 {
        Some(0)
    } else if dir[0] == 0.0 {
        Some(1)
    } else {
        None
    };
    (dir, axis)
}

/// Where the travel distance lies on the panel `axis` of
/// [`travel_axis`] [SI: m]: the distance times the direction's component
/// on x or y (−5 mm for a travel along (−1, 0)), or the distance along an
/// oblique direction.
fn distance_coordinate(result: &SwitchOffResult, axis: Option<usize>) -> f64 {
    let (dir, _) = travel_axis(result);
    result.settings.distance * axis.map_or(1.0, |k| dir[k])
}

/// x(t) and y(t) of the tracked point (Figs. 7 and 8), with the travel
/// distance and the time it is reached on the panel of the travel
/// direction (a third panel of the displacement along an oblique
/// direction), and the contact forces and released loads against time.
pub fn time_figure(result: &SwitchOffResult) -> LineFigure {
    let (dir, axis) = travel_axis(result);
    let mut x = Panel::new("Displacement x", Scale::mm());
    let mut y = Panel::new("Displacement y", Scale::mm());
    let mut along = Panel::new(
        format!("Displacement along ({:.3}, {:.3})", dir[0], dir[1]),
        Scale::mm(),
    );
    for (i, (name, run)) in runs(result).into_iter().enumerate() {
        let (ux, uy) = (displacement(&run.x_m), displacement(&run.y_m));
        let u: Vec<f64> = ux
            .iter()
            .zip(&uy)
            .map(|(a, b)| a * dir[0] + b * dir[1])
            .collect();
        for (panel, v) in [(&mut x, ux), (&mut y, uy), (&mut along, u)] {
            let mut series = Series::line(name, run.time_s.clone(), v);
            // The same colour for a run in every panel.
            series.colour = Some(i);
            panel.series.push(series);
        }
    }
    let d = distance_coordinate(result, axis);
    let mut panels = vec![x, y];
    let travel = match axis {
        Some(k) => k,
        None => {
            panels.push(along);
            2
        }
    };
    let p = &mut panels[travel];
    p.hlines
        .push(Guide::reference(d, format!("{:.3} mm", d * 1e3)));
    if let Some(t) = result.flexible.time_to_distance_s {
        p.vlines.push(Guide::new(t, format!("{:.3} ms", t * 1e3)));
    }
    for p in &mut panels {
        p.legend = Legend::UpperLeft;
    }
    if let Some(forces) = force_panel(&result.flexible) {
        panels.push(forces);
    }
    let mut fig = LineFigure::new(
        format!(
            "Switch-off: {}, {} along ({}, {})",
            result.model,
            result.point_label,
            result.settings.direction[0],
            result.settings.direction[1]
        ),
        "Time",
        Scale::ms(),
    );
    fig.panels = panels;
    fig
}

/// The flexible run's contact forces and released loads against time
/// [SI: N]; `None` when it has neither.
fn force_panel(run: &SwitchOffRun) -> Option<Panel> {
    let contacts = run
        .contacts
        .iter()
        .map(|c| (format!("contact {}", c.id), &c.force_n));
    let loads = run
        .released_loads
        .iter()
        .map(|(label, v)| (format!("released {label}"), v));
    let all: Vec<(String, &Vec<f64>)> = contacts.chain(loads).collect();
    if all.is_empty() {
        return None;
    }
    let max = all
        .iter()
        .flat_map(|(_, v)| v.iter())
        .fold(0.0f64, |m, f| m.max(f.abs()));
    let mut p = Panel::new("Force (flexible)", Scale::si("N", max));
    for (name, v) in all {
        p.series
            .push(Series::line(name, run.time_s.clone(), v.clone()));
    }
    p.legend = Legend::UpperRight;
    Some(p)
}

/// The trajectory y(x) of the tracked point (Fig. 9).
pub fn trajectory_figure(result: &SwitchOffResult) -> LineFigure {
    let mut p = Panel::new("Displacement y", Scale::mm());
    for (name, run) in runs(result) {
        p.series.push(Series::line(
            name,
            displacement(&run.x_m),
            displacement(&run.y_m),
        ));
    }
    // The distance line where it is a coordinate: along x a vertical
    // line, along y a horizontal one.
    let (_, axis) = travel_axis(result);
    let d = distance_coordinate(result, axis);
    let guide = Guide::reference(d, format!("{:.3} mm", d * 1e3));
    match axis {
        Some(0) => p.vlines.push(guide),
        Some(_) => p.hlines.push(guide),
        None => {}
    }
    p.legend = Legend::UpperLeft;
    let mut fig = LineFigure::new(
        format!(
            "Switch-off trajectory: {}, {}",
            result.model, result.point_label
        ),
        "Displacement x",
        Scale::mm(),
    );
    fig.panels = vec![p];
    fig
}

/// `switch.svg` → `switch.trajectory.svg`.
pub fn trajectory_path(plot: &Path) -> PathBuf {
    let response = response_path(plot);
    let name = response
        .file_name()
        .map(|n| n.to_string_lossy().replace(".response", ".trajectory"));
    match name {
        Some(n) => plot.with_file_name(n),
        None => plot.to_path_buf(),
    }
}

/// Writes the time figure to `path` and the trajectory beside it.
pub fn write_switch_off_figures(
    result: &SwitchOffResult,
    path: &Path,
    size: PlotSize,
) -> Result<(), PlotError> {
    write_figure(&time_figure(result).into(), path, size)?;
    write_figure(
        &trajectory_figure(result).into(),
        &trajectory_path(path),
        size,
    )
}
