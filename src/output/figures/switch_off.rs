//! Figures of the switch-off experiment ([`crate::analysis::switch_off`]),
//! in the style of the paper's Figs. 7–9: the tracked point's x(t) with the
//! travel distance as a reference line (Fig. 7) and y(t) (Fig. 8) as two
//! panels over time [SI: s, shown in ms], and its trajectory y against x
//! (Fig. 9); the flexible run and, when computed, the rigid one overlaid.
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

/// x(t) and y(t) of the tracked point (Figs. 7 and 8).
pub fn time_figure(result: &SwitchOffResult) -> LineFigure {
    let mut x = Panel::new("Displacement x", Scale::mm());
    let mut y = Panel::new("Displacement y", Scale::mm());
    for (i, (name, run)) in runs(result).into_iter().enumerate() {
        let mut sx = Series::line(name, run.time_s.clone(), displacement(&run.x_m));
        let mut sy = Series::line(name, run.time_s.clone(), displacement(&run.y_m));
        // The same colour for a run in both panels.
        sx.colour = Some(i);
        sy.colour = Some(i);
        x.series.push(sx);
        y.series.push(sy);
    }
    let d = result.settings.distance;
    x.hlines
        .push(Guide::reference(d, format!("{:.3} mm", d * 1e3)));
    if let Some(t) = result.flexible.time_to_distance_s {
        x.vlines.push(Guide::new(t, format!("{:.3} ms", t * 1e3)));
    }
    x.legend = Legend::UpperLeft;
    y.legend = Legend::UpperLeft;
    let mut fig = LineFigure::new(
        format!("Switch-off: {}, node 0", result.model),
        "Time",
        Scale::ms(),
    );
    fig.panels = vec![x, y];
    fig
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
    p.vlines.push(Guide::reference(
        result.settings.distance,
        format!("{:.3} mm", result.settings.distance * 1e3),
    ));
    p.legend = Legend::UpperLeft;
    let mut fig = LineFigure::new(
        format!("Switch-off trajectory: {}, node 0", result.model),
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
