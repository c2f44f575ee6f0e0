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
    /// Linearize at the static equilibrium under the model's constant loads
    /// and gravity (pre-stress) and show the unstressed frequencies beside.
    #[arg(long)]
    pub prestress: bool,
    /// Factor on the applied loads for --prestress (gravity is not scaled).
    #[arg(long, value_name = "S", requires = "prestress", allow_negative_numbers = true, value_parser = super::statics::finite)]
    pub load_scale: Option<f64>,
    /// Frequencies at the equilibrium for N load factors from A to B (first
    /// min(--modes, 6) elastic modes); --plot draws them, --csv writes them.
    #[arg(long, value_name = "A:B:N", conflicts_with_all = ["prestress", "load_scale"], value_parser = parse_sweep, allow_hyphen_values = true)]
    pub sweep_load: Option<Sweep>,
}

/// A load-factor range `A:B:N`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sweep {
    pub from: f64,
    pub to: f64,
    pub count: usize,
}

fn parse_sweep(s: &str) -> Result<Sweep, String> {
    let parts: Vec<&str> = s.split(':').collect();
    let [a, b, n] = parts[..] else {
        return Err(format!(
            "`{s}` is not A:B:N (from, to, number of load factors)"
        ));
    };
    let from = super::statics::finite(a)?;
    let to = super::statics::finite(b)?;
    let count: usize = n
        .parse()
        .map_err(|_| format!("`{n}` is not a whole number of load factors"))?;
    if !(1..=10_000).contains(&count) {
        return Err(format!(
            "the number of load factors must be 1 to 10000, got {count}"
        ));
    }
    Ok(Sweep { from, to, count })
}

pub fn run(args: ModalArgs) -> Result<()> {
    let model = load_model(args.model.as_deref())?;
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(args.modes as usize),
        ..ModalSettings::default()
    };
    if let Some(sweep) = args.sweep_load {
        return super::statics::run_sweep(&args, &model, &system, sweep, &settings);
    }
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
