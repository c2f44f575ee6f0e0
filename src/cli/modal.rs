//! `ancf-modal modal`: frequencies and mode shapes.

use super::args::ModalArgs;
use super::common::{load_model, source_label, write_output};
use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::output::modal_report::{modal_csv, modal_json, modal_table};
use ancf_modal::System;
use anyhow::{Context, Result};

pub fn run(args: ModalArgs) -> Result<()> {
    if let Some(range) = args.sweep_load {
        return super::sweep::run_load_sweep(&args, range);
    }
    let model = load_model(args.model.as_deref())?;
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(args.modes as usize),
        method: args.solver.into(),
    };
    if args.prestress {
        return super::statics::run_prestress(&args, &model, &system, &settings);
    }
    let result = modal_at_reference(&system, &settings)
        .with_context(|| source_label(args.model.as_deref()))?;
    if let Some(path) = &args.csv {
        write_output(path, &modal_csv(&result))?;
    }
    if let Some(path) = &args.plot {
        ancf_modal::output::figures::write_mode_shapes(&system, &system.q0, &result, path)?;
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&modal_json(&model.name, &result))?
        );
    } else {
        print!("{}", modal_table(&model.name, &result));
    }
    Ok(())
}
