//! `ancf-modal static`: the static equilibrium under the model's loads
//! (node positions, joint reactions, spring forces).

//!
//! Also the pre-stressed variant of `modal` (`--prestress`), which shares
//! the statics settings (`--sweep-load` is a sweep: [`super::sweep`]).

use super::args::{finite, ModalArgs};
use super::common::{load_model, print_json, source_label, write_output};
use super::output::Output;
use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::analysis::ModalSettings;
use ancf_modal::output::figures::{write_figure, write_mode_shapes};
use ancf_modal::output::modal_report::modal_csv;
use ancf_modal::output::plot::PlotSize;
use ancf_modal::output::static_report::{
    equilibrium_figure, prestress_table, static_report, static_table,
};
use ancf_modal::{Model, System};
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct StaticArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Factor on the applied loads (gravity is not scaled). Loads act with
    /// their value at t = 0: constant loads and steps from 0 in full,
    /// half-sine pulses not at all.
    #[arg(long, default_value_t = 1.0, value_name = "S", allow_negative_numbers = true, value_parser = finite)]
    pub load_scale: f64,
}

pub fn run(args: StaticArgs) -> Result<()> {
    args.output.only("static", &[Output::Json, Output::Plot])?;
    let model = load_model(args.model.as_deref())?;
    let system = System::new(&model);
    let settings = StaticSettings {
        load_scale: args.load_scale,
        ..StaticSettings::default()
    };
    let eq = solve_equilibrium(&system, &settings)
        .with_context(|| source_label(args.model.as_deref()))?;
    if let Some(path) = &args.output.plot {
        let figure = equilibrium_figure(&system, &eq);
        let size = PlotSize {
            width: 900,
            height: 900,
        };
        write_figure(&figure.into(), path, size)?;
    }
    let report = static_report(&model, &system, &eq);
    if args.output.json {
        print_json(&report, args.model.as_deref())?;
    } else {
        out!("{}", static_table(&report));
    }
    Ok(())
}

/// `modal --prestress [--load-scale S]`.
pub fn run_prestress(
    args: &ModalArgs,
    model: &Model,
    system: &System,
    settings: &ModalSettings,
) -> Result<()> {
    args.output.only(
        "modal --prestress",
        &[Output::Json, Output::Csv, Output::Plot],
    )?;
    let statics = StaticSettings {
        load_scale: args.load_scale.unwrap_or(1.0),
        ..StaticSettings::default()
    };
    let (result, output) =
        ancf_modal::results::modal::prestressed(model, system, &statics, settings)
            .with_context(|| source_label(args.model.as_deref()))?;
    for w in ancf_modal::results::modal::prestressed_warnings(&result) {
        super::common::warn(format!("{}: {w}", source_label(args.model.as_deref())));
    }
    if let Some(path) = &args.output.csv {
        write_output(path, &modal_csv(&result.prestressed))?;
    }
    if let Some(path) = &args.output.plot {
        write_mode_shapes(system, &result.equilibrium.q, &result.prestressed, path)?;
    }
    if args.output.json {
        print_json(&output, args.model.as_deref())?;
    } else {
        out!("{}", prestress_table(&model.name, &result));
    }
    Ok(())
}
