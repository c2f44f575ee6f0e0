//! `ancf-modal modal`: frequencies and mode shapes.

use super::{load_model, source_label, write_output};
use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::output::modal_report::{modal_csv, modal_json, modal_table};
use ancf_modal::System;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ModalArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// Number of modes to report, rigid ones included.
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u64).range(1..))]
    pub modes: u64,
    /// Print one JSON document instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Also write the modes as CSV to this file.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Also draw the first six elastic mode shapes (of those reported) to this file (.svg or .png).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
}

pub fn run(args: ModalArgs) -> Result<()> {
    let model = load_model(args.model.as_deref())?;
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(args.modes as usize),
        ..ModalSettings::default()
    };
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
