//! `ancf-modal modal`: maps the flags to [`ancf_modal::commands::modal`]
//! and renders its output (`--sweep-load` is a sweep: [`super::sweep`]).

use super::args::ModalArgs;
use super::common::{print_document, write_output, Warnings};
use super::output::Output;
use ancf_modal::commands::modal::{run as modal, ModalRequest};
use ancf_modal::commands::ModelInput;
use anyhow::Result;

pub fn run(args: ModalArgs) -> Result<Warnings> {
    if let Some(range) = args.sweep_load {
        return super::sweep::run_load_sweep(&args, range);
    }
    if args.prestress {
        args.output.only(
            "modal --prestress",
            &[Output::Json, Output::Csv, Output::Plot],
        )?;
    }
    if let Some(path) = &args.mac_plot {
        ancf_modal::output::plot::Format::from_path(path)?;
    }
    let input = ModelInput::load(args.model.as_deref())?;
    let request = ModalRequest {
        modes: args.modes as usize,
        solver: args.solver.into(),
        prestress: args.prestress,
        load_scale: args
            .load_scale
            .unwrap_or(ModalRequest::default().load_scale),
        mac: args.mac.clone(),
    };
    let run = modal(&input, &request)?;
    if let Some(path) = &args.output.csv {
        write_output(path, &run.csv())?;
    }
    if let Some(path) = &args.output.uff {
        write_output(path, &run.uff())?;
    }
    if let Some(path) = &args.output.plot {
        run.write_plot(path)?;
    }
    if let (Some(path), Some(mac)) = (&args.mac_plot, run.mac()) {
        let other = args
            .mac
            .as_deref()
            .and_then(|p| p.file_name())
            .map_or(String::new(), |p| p.to_string_lossy().into_owned());
        let title = format!("MAC: {} vs {other}", input.model.name);
        let m = nalgebra::DMatrix::from_fn(mac.rows_hz.len(), mac.columns_hz.len(), |i, j| {
            mac.matrix[i][j]
        });
        ancf_modal::output::figures::write_figure(
            &ancf_modal::output::figures::mac_figure(&title, &m),
            path,
            ancf_modal::output::plot::PlotSize::default(),
        )?;
    }
    if args.output.json {
        print_document(&run.document)?;
    } else {
        out!("{}", run.text());
    }
    Ok(run.document.warnings)
}
