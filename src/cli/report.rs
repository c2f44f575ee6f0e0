//! `ancf-modal report`: one self-contained HTML file with the assembly,
//! the animated modes, the impulse experiment (when the model has an
//! excitation) and the switch-off (when it releases something).

use super::common::{load_model, source_label, write_output};
use super::impulse::{experiment, ExperimentArgs};
use ancf_modal::analysis::impulse::excitation;
use ancf_modal::analysis::statics::prestress::prestressed_modal;
use ancf_modal::analysis::statics::StaticSettings;
use ancf_modal::analysis::switch_off::{run_switch_off, SwitchOffSettings};
use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::output::provenance::{model_sha256, tool_version, utc_now};
use ancf_modal::output::report::sections::{has_release, impulse_section, switch_off_section};
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
    /// Also the modes at the static equilibrium under the model's loads,
    /// beside the unstressed ones.
    #[arg(long)]
    pub prestress: bool,
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
    let prestressed = if args.prestress {
        Some(
            prestressed_modal(&system, &StaticSettings::default(), &settings)
                .with_context(|| source_label(path))?,
        )
    } else {
        None
    };
    let mut sections = Vec::new();
    if excitation(&model).is_ok() {
        let impulse = experiment(&model, path, &args.experiment)?;
        sections.push(impulse_section(&model, &impulse));
    }
    if has_release(&model) {
        let settings = SwitchOffSettings {
            compare_rigid: true,
            ..SwitchOffSettings::default()
        };
        let r = run_switch_off(&model, &settings).with_context(|| source_label(path))?;
        sections.push(switch_off_section(&r));
    }
    let mut mode_sets = vec![ModeSet {
        title: "Modes at the reference",
        system: &system,
        q: &system.q0,
        modal: &modal,
    }];
    if let Some(p) = &prestressed {
        mode_sets.push(ModeSet {
            title: "Modes at the pre-stressed equilibrium",
            system: &system,
            q: &p.equilibrium.q,
            modal: &p.prestressed,
        });
    }
    let input = ReportInput {
        provenance: Provenance {
            tool_version: tool_version().to_string(),
            model_name: model.name.clone(),
            model_sha256: model_sha256(path)?,
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
            date: utc_now(),
        },
        description: &model.description,
        mode_sets,
        sections,
    };
    write_output(&args.out, &report_html(&input)?)?;
    outln!("report written to {}", args.out.display());
    Ok(())
}
