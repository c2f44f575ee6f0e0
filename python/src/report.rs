//! `Model.report(...)` (the command line's `report`): one self-contained
//! HTML file. A front end over [`ancf::commands::report`]: keyword
//! arguments → request → `run` → write.

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use ancf::commands::report::{run as report, ReportRequest};
use pyo3::prelude::*;
use std::path::PathBuf;

/// The provenance's "command line" of a report asked for from Python:
/// the call and the package's version.
pub fn provenance(call: &str) -> String {
    format!(
        "{call} (Python package ancf_modal {})",
        ancf::results::provenance::tool_version()
    )
}

/// `Model.report(...)` with the keyword arguments that differ from their
/// defaults, as Python would spell them, so that the page says how to
/// make it again.
fn call_text(r: &ReportRequest) -> String {
    let d = ReportRequest::default();
    let (e, de) = (&r.identify.experiment, &d.identify.experiment);
    let text = |s: &str| format!("{s:?}");
    let float = |v: f64| format!("{v:?}");
    let pair = |(a, b): (f64, f64)| format!("({a:?}, {b:?})");
    let mut args: Vec<String> = Vec::new();
    let mut add = |name: &str, differs: bool, value: String| {
        if differs {
            args.push(format!("{name}={value}"));
        }
    };
    add("out", r.out != d.out, text(&r.out.display().to_string()));
    add("prestress", r.prestress, "True".into());
    add(
        "amplitude",
        e.amplitude.is_some(),
        e.amplitude.map_or_else(String::new, float),
    );
    add(
        "duration",
        e.duration.is_some(),
        e.duration.map_or_else(String::new, float),
    );
    add("end_time", e.end_time != de.end_time, float(e.end_time));
    add("step", e.step != de.step, float(e.step));
    add(
        "spectral_radius",
        e.spectral_radius != de.spectral_radius,
        float(e.spectral_radius),
    );
    add(
        "sample_rate",
        e.sample_rate != de.sample_rate,
        float(e.sample_rate),
    );
    add(
        "sensor",
        e.sensor.is_some(),
        e.sensor.as_deref().map_or_else(String::new, text),
    );
    add("window", e.window != de.window, text(&e.window.to_string()));
    add("from_reference", e.start != de.start, "True".into());
    let c = &r.identify;
    add("calibrate", c.calibrate, "True".into());
    let files: Vec<String> = c
        .measured
        .iter()
        .map(|p| text(&p.display().to_string()))
        .collect();
    add(
        "measured",
        !files.is_empty(),
        format!("[{}]", files.join(", ")),
    );
    let window = c.measured_window.to_string();
    add(
        "measured_window",
        c.measured_window != d.identify.measured_window,
        text(&window),
    );
    add(
        "measured_band",
        c.measured_band.is_some(),
        c.measured_band.map_or_else(String::new, pair),
    );
    format!("Model.report({})", args.join(", "))
}

/// Writes the report of `model` to `out`; `identify` holds the impulse
/// experiment's and the comparison's keyword arguments.
pub fn run(
    model: &PyModel,
    py: Python<'_>,
    out: PathBuf,
    prestress: bool,
    identify: crate::identify::Request<'_>,
) -> PyResult<()> {
    let mut request = ReportRequest {
        out,
        prestress,
        identify: identify.into_request()?,
        command_line: String::new(),
    };
    request.command_line = provenance(&call_text(&request));
    let input = model.input();
    let page = compute(py, || {
        let page = report(&input, &request).map_err(Failure::from)?;
        page.write().map_err(Failure::from)?;
        Ok(page)
    })?;
    crate::warn(py, page.own_warnings())
}
