//! `static`: the static equilibrium under the model's loads × `load_scale`
//! [–] (their values at t = 0: constant loads and steps from 0 in full,
//! half-sine pulses not at all) and gravity: node positions [m], joint
//! reactions [N, N m], spring forces [N].

use super::{CommandError, ModelInput, Run};
use crate::analysis::statics::{solve_equilibrium, Equilibrium, StaticSettings};
use crate::output::figures::write_figure;
use crate::output::plot::PlotSize;
use crate::output::static_report::{equilibrium_figure, static_table};
use crate::results::{static_report, StaticReport};
use crate::System;
use std::path::Path;

/// What `static` computes.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticRequest {
    /// Factor on the applied loads (gravity is not scaled) [–].
    pub load_scale: f64,
}

impl Default for StaticRequest {
    fn default() -> Self {
        StaticRequest { load_scale: 1.0 }
    }
}

/// `static`'s output.
#[derive(Debug)]
pub struct StaticRun {
    /// The assembled system.
    pub system: System,
    /// The equilibrium: coordinates, multipliers, solver statistics.
    pub equilibrium: Equilibrium,
    /// The document with the run's warnings.
    pub document: Run<StaticReport>,
}

/// Runs `static` on `input`.
pub fn run(input: &ModelInput, request: &StaticRequest) -> Result<StaticRun, CommandError> {
    if !request.load_scale.is_finite() {
        return Err(CommandError::argument(
            "load_scale",
            request.load_scale,
            "must be a finite number",
        ));
    }
    let system = System::new(&input.model);
    let settings = StaticSettings {
        load_scale: request.load_scale,
        ..StaticSettings::default()
    };
    let equilibrium = solve_equilibrium(&system, &settings)
        .map_err(|e| CommandError::analysis(input.label(), e))?;
    let report = static_report(&input.model, &system, &equilibrium);
    Ok(StaticRun {
        document: Run::of(input, report),
        system,
        equilibrium,
    })
}

impl StaticRun {
    /// The command line's table.
    pub fn text(&self) -> String {
        static_table(&self.document.output)
    }

    /// Draws the deformed assembly over the reference to `path` (.svg or
    /// .png).
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        let figure = equilibrium_figure(&self.system, &self.equilibrium);
        let size = PlotSize {
            width: 900,
            height: 900,
        };
        write_figure(&figure.into(), path, size)?;
        Ok(())
    }
}
