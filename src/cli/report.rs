//! `ancf-modal report`: one self-contained HTML file. For a model with an
//! excitation, everything `identify` computes (comparison, impulse,
//! calibration, measured records); for any model the assembly and the
//! animated modes, the pre-stressed modes beside them (`--prestress`) and
//! the switch-off when the model releases something.

use super::common::{source_label, write_output, Warnings};
use super::identify::{compute, request, ComparisonArgs};
use super::impulse::ExperimentArgs;
use ancf_modal::analysis::impulse::excitation;
use ancf_modal::analysis::statics::StaticSettings;
use ancf_modal::analysis::switch_off::{run_switch_off, SwitchOffSettings};
use ancf_modal::analysis::{ModalResult, ModalSettings};
use ancf_modal::model::ValidModel;
use ancf_modal::output::frf_report::ResponseQuantity;
use ancf_modal::output::report::sections::{
    calibration_section, comparison_section, has_release, impulse_section, measured_section,
    switch_off_section,
};
use ancf_modal::output::report::{report_html, ModeSet, Provenance, ReportInput, Section};
use ancf_modal::results::identify::IDENTIFY_MODES;
use ancf_modal::results::provenance::{model_sha256, tool_version, utc_now};
use ancf_modal::results::ModelOverlay;
use ancf_modal::System;
use anyhow::{Context, Result};
use clap::Args;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// The HTML file to write.
    #[arg(long, value_name = "FILE.html", default_value = "report.html")]
    pub out: PathBuf,
    /// Also the modes at the static equilibrium under the model's loads,
    /// beside the unstressed ones.
    #[arg(long)]
    pub prestress: bool,
    #[command(flatten)]
    pub experiment: ExperimentArgs,
    #[command(flatten)]
    pub comparison: ComparisonArgs,
}

pub fn run(args: ReportArgs) -> Result<Warnings> {
    let path = args.model.clone();
    let out = args.out.clone();
    let prestress = args.prestress;
    let input = ancf_modal::commands::ModelInput::load(path.as_deref())?;
    let model = &*input.model;
    let mut warnings = input.unit_warnings();
    if excitation(model).is_ok() {
        let id = compute(&input, &request(&args.experiment, &args.comparison))?;
        warnings.extend(id.document.own_warnings().iter().cloned());
        write_report(&out, &id, path.as_deref(), prestress)?;
    } else {
        if args.comparison.calibrate || !args.comparison.measured.is_empty() {
            anyhow::bail!(
                "{}: --calibrate and --measured need the impulse experiment, and the model has no half-sine or step load",
                source_label(path.as_deref())
            );
        }
        let system = System::new(model);
        let settings = ModalSettings {
            modes: Some(IDENTIFY_MODES),
            ..ModalSettings::default()
        };
        let (modal, output) = ancf_modal::results::modal::modal(model, &system, &settings)
            .with_context(|| source_label(path.as_deref()))?;
        let parts = Parts {
            model,
            system: &system,
            modal: &modal,
            damping_ratio: output.modes.iter().map(|m| m.damping_ratio).collect(),
            sections: Vec::new(),
        };
        write(&out, parts, path.as_deref(), prestress)?;
    }
    outln!("report written to {}", out.display());
    Ok(warnings)
}

/// The report of what `identify` computed (`identify --html`, `report`).
pub fn write_report(
    out: &Path,
    id: &ancf_modal::commands::identify::IdentifyRun,
    path: Option<&Path>,
    prestress: bool,
) -> Result<()> {
    let mut sections = vec![
        comparison_section(&id.document.output, id.paper),
        impulse_section(&id.model, &id.impulse),
    ];
    if let Some(c) = &id.document.output.calibration {
        sections.push(calibration_section(c));
    }
    if let Some(a) = &id.measured {
        let q = ResponseQuantity::Velocity;
        let overlay = id
            .model
            .sensors
            .first()
            .and_then(|s| ModelOverlay::new(&id.model, &s.id, q, &a.frequency_hz).ok());
        let label = format!("model {}", id.model.name);
        let overlay = overlay
            .as_ref()
            .map(|(_, h)| (label.as_str(), a.frequency_hz.as_slice(), h.as_slice()));
        sections.push(measured_section(a, q, overlay));
    }
    let parts = Parts {
        model: &id.model,
        system: &id.system,
        modal: &id.modal,
        damping_ratio: id
            .document
            .output
            .modal
            .modes
            .iter()
            .map(|m| m.damping_ratio)
            .collect(),
        sections,
    };
    write(out, parts, path, prestress)
}

/// What every report has.
struct Parts<'a> {
    model: &'a ValidModel,
    system: &'a System,
    modal: &'a ModalResult,
    /// Each mode's damping ratio [–].
    damping_ratio: Vec<Option<f64>>,
    sections: Vec<Section>,
}

/// Adds the pre-stressed modes and the switch-off, renders and writes.
fn write(out: &Path, p: Parts, path: Option<&Path>, prestress: bool) -> Result<()> {
    let label = || source_label(path);
    let settings = ModalSettings {
        modes: Some(p.modal.modes.len().max(1)),
        ..ModalSettings::default()
    };
    let prestressed = if prestress {
        Some(
            ancf_modal::results::modal::prestressed(
                p.model,
                p.system,
                &StaticSettings::default(),
                &settings,
            )
            .with_context(label)?,
        )
    } else {
        None
    };
    let mut sections = p.sections;
    if has_release(p.model) {
        let settings = SwitchOffSettings {
            compare_rigid: true,
            ..SwitchOffSettings::default()
        };
        let r = run_switch_off(p.model, &settings).with_context(label)?;
        sections.push(switch_off_section(&r));
    }
    let mut mode_sets = vec![ModeSet {
        title: "Modes at the reference",
        system: p.system,
        q: &p.system.q0,
        modal: p.modal,
        damping_ratio: p.damping_ratio,
    }];
    if let Some((e, output)) = &prestressed {
        mode_sets.push(ModeSet {
            title: "Modes at the pre-stressed equilibrium",
            system: p.system,
            q: &e.equilibrium.q,
            modal: &e.prestressed,
            damping_ratio: output.modes.iter().map(|m| m.damping_ratio).collect(),
        });
    }
    let input = ReportInput {
        provenance: Provenance {
            tool_version: tool_version().to_string(),
            model_name: p.model.name.clone(),
            model_sha256: model_sha256(path)?,
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
            date: utc_now(),
        },
        description: &p.model.description,
        mode_sets,
        sections,
    };
    write_output(out, &report_html(&input)?)
}
