//! `ancf-modal report`: one self-contained HTML file with the assembly,
//! the animated modes and the impulse experiment.

use super::common::{load_model, source_label, write_output};
use super::impulse::{experiment, ExperimentArgs};
use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::output::provenance::{model_sha256, tool_version};
use ancf_modal::output::report::sections::impulse_section;
use ancf_modal::output::report::{report_html, ModeSet, Provenance, ReportInput};
use ancf_modal::System;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// The HTML file to write.
    #[arg(long, value_name = "FILE.html", default_value = "report.html")]
    pub out: PathBuf,
    /// Modes computed (rigid ones included).
    #[arg(long, value_name = "N", default_value_t = 9, value_parser = super::values::at_least_one_usize)]
    pub modes: usize,
    #[command(flatten)]
    pub experiment: ExperimentArgs,
}

pub fn run(args: ReportArgs) -> Result<()> {
    let path = args.model.as_deref();
    let model = load_model(path)?;
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(args.modes),
        ..ModalSettings::default()
    };
    let modal = modal_at_reference(&system, &settings).with_context(|| source_label(path))?;
    let impulse = experiment(&model, path, &args.experiment)?;
    let input = ReportInput {
        provenance: Provenance {
            tool_version: tool_version().to_string(),
            model_name: model.name.clone(),
            model_sha256: model_sha256(path)?,
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
            date: ancf_modal::output::provenance::utc_now(),
        },
        description: &model.description,
        mode_sets: vec![ModeSet {
            title: "Modes at the reference",
            system: &system,
            q: &system.q0,
            modal: &modal,
        }],
        sections: vec![impulse_section(&model, &impulse)],
    };
    let html = report_html(&input)?;
    write_output(&args.out, &html)?;
    outln!("report written to {}", args.out.display());
    Ok(())
}
