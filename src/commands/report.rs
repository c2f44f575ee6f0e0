//! `report`: one self-contained HTML file. For any model the assembly and
//! its animated modes at the reference (frequencies in Hz, damping ratios
//! ζ [–]), with the modes at the static equilibrium under the loads beside
//! them on request (`prestress`); for a model with an excitation (a
//! half-sine or step load) everything `identify` computes (the comparison
//! of the first bending frequency [Hz] with the experiment, the impulse
//! test, the calibration [m] and the measured records); and the switch-off
//! (the tracked point's travel [m] against time [s]) when the model
//! releases something.
//!
//! The page is rendered from the commands' typed outputs: the modes are
//! `modal`'s or `identify`'s runs, whose documents pair each mode with its
//! damping ratio. [`Report::write`] writes it atomically.

use super::identify::{IdentifyRequest, IdentifyRun};
use super::modal::{run as modal, ModalRequest};
use super::{CommandError, ModelInput};
use crate::analysis::impulse::excitation;
use crate::analysis::switch_off::{run_switch_off, SwitchOffSettings};
use crate::analysis::ModalResult;
use crate::output::frf_report::ResponseQuantity;
use crate::output::report::sections::{
    calibration_section, comparison_section, has_release, impulse_section, measured_section,
    switch_off_section,
};
use crate::output::report::{report_html, ModeSet, Provenance, ReportInput, Section};
use crate::results::identify::IDENTIFY_MODES;
use crate::results::provenance::{tool_version, utc_now};
use crate::results::{ModalJson, ModelOverlay};
use crate::System;
use std::path::PathBuf;

/// What `report` shows and where it goes.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportRequest {
    /// The HTML file to write.
    pub out: PathBuf,
    /// Also the modes at the static equilibrium under the model's loads
    /// (× 1) and gravity, beside the unstressed ones.
    pub prestress: bool,
    /// The impulse experiment, the comparison and the calibration, as
    /// `identify` runs them (models with an excitation; for another model
    /// only its defaults are allowed: no `calibrate`, no `measured`).
    pub identify: IdentifyRequest,
    /// How the report was asked for, shown in its provenance (the command
    /// line, or the Python call).
    pub command_line: String,
}

impl Default for ReportRequest {
    fn default() -> Self {
        ReportRequest {
            out: PathBuf::from("report.html"),
            prestress: false,
            identify: IdentifyRequest::default(),
            command_line: String::new(),
        }
    }
}

/// Refuses a page file named `path` whose extension is not `.html` or
/// `.htm` (the page is HTML, whatever the name says); `name` is the
/// request's field (`out`).
pub fn check_out(name: &'static str, path: &std::path::Path) -> Result<(), CommandError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("html" | "htm") => Ok(()),
        _ => Err(CommandError::argument(
            name,
            path.display(),
            "must end in .html or .htm (the report is one HTML file)",
        )),
    }
}

/// `report`'s output: the page and where it goes.
#[derive(Debug, Clone)]
pub struct Report {
    /// The file it is written to.
    pub out: PathBuf,
    /// The HTML document.
    pub html: String,
    /// The run's warnings: the model's unit warnings (named by its
    /// source), then the analyses' own and what the measured records
    /// noted (named by their files).
    pub warnings: Vec<String>,
    /// How many of the first `warnings` are the model's.
    pub model_warnings: usize,
}

impl Report {
    /// Writes the page to `out`, atomically (a failed write leaves no
    /// partial file).
    pub fn write(&self) -> Result<(), CommandError> {
        crate::output::files::write_atomic(&self.out, self.html.as_bytes())?;
        Ok(())
    }

    /// The warnings of the analyses (those about the model aside).
    pub fn own_warnings(&self) -> &[String] {
        &self.warnings[self.model_warnings.min(self.warnings.len())..]
    }
}

/// Runs `report` on `input`.
pub fn run(input: &ModelInput, request: &ReportRequest) -> Result<Report, CommandError> {
    run_with_progress(input, request, &mut |_| {})
}

/// [`run`], with `progress` receiving the fraction of the impulse
/// experiment's steps done.
pub fn run_with_progress(
    input: &ModelInput,
    request: &ReportRequest,
    progress: &mut dyn FnMut(f64),
) -> Result<Report, CommandError> {
    check_out("out", &request.out)?;
    if excitation(&input.model).is_ok() {
        let id = super::identify::run_with_progress(input, &request.identify, progress)?;
        return of_identified(input, &id, request);
    }
    let asked = &request.identify;
    if asked.calibrate || !asked.measured.is_empty() {
        return Err(CommandError::NeedsImpulse {
            model: input.label(),
        });
    }
    let reference = modal(
        input,
        &ModalRequest {
            modes: IDENTIFY_MODES,
            ..ModalRequest::default()
        },
    )?;
    let page = Page {
        system: &reference.system,
        modal: reference.outcome.result(),
        damping_ratio: damping_ratios(&reference.document.output),
        sections: Vec::new(),
        warnings: reference.document.warnings.clone(),
        model_warnings: reference.document.model_warnings,
    };
    render(input, page, request)
}

/// The report of what `identify` computed (`identify --html`, and
/// `report` of a model with an excitation); `request`'s `out`,
/// `prestress` and `command_line` apply.
pub fn of_identified(
    input: &ModelInput,
    id: &IdentifyRun,
    request: &ReportRequest,
) -> Result<Report, CommandError> {
    let model = &input.model;
    let output = &id.document.output;
    let mut sections: Vec<_> = comparison_section(output, id.paper).into_iter().collect();
    sections.push(impulse_section(model, &id.impulse));
    if let Some(c) = &output.calibration {
        sections.push(calibration_section(c));
    }
    if let Some(a) = &id.measured {
        let q = ResponseQuantity::Velocity;
        let overlay = model
            .sensors
            .first()
            .and_then(|s| ModelOverlay::new(model, &s.id, q, &a.frequency_hz).ok());
        let label = format!("model {}", model.name);
        let overlay = overlay
            .as_ref()
            .map(|(_, h)| (label.as_str(), a.frequency_hz.as_slice(), h.as_slice()));
        sections.push(measured_section(a, q, overlay));
    }
    let page = Page {
        system: &id.system,
        modal: &id.modal,
        damping_ratio: output.modal.modes.iter().map(|m| m.damping_ratio).collect(),
        sections,
        warnings: id.document.warnings.clone(),
        model_warnings: id.document.model_warnings,
    };
    render(input, page, request)
}

/// What every report has: the modes at the reference, the sections before
/// the switch-off's and the warnings so far.
struct Page<'a> {
    system: &'a System,
    modal: &'a ModalResult,
    /// Each mode's damping ratio [–].
    damping_ratio: Vec<Option<f64>>,
    sections: Vec<Section>,
    warnings: Vec<String>,
    model_warnings: usize,
}

/// Each mode's damping ratio from a `modal` document.
fn damping_ratios(document: &ModalJson) -> Vec<Option<f64>> {
    match document {
        ModalJson::Reference(o) => o.modes.iter().map(|m| m.damping_ratio).collect(),
        ModalJson::Prestressed(o) => o.modes.iter().map(|m| m.damping_ratio).collect(),
        ModalJson::LoadSweep(_) => Vec::new(),
    }
}

/// Adds the pre-stressed modes and the switch-off and renders the page.
fn render(input: &ModelInput, p: Page, request: &ReportRequest) -> Result<Report, CommandError> {
    let model = &input.model;
    let prestressed = if request.prestress {
        let request = ModalRequest {
            modes: p.modal.modes.len().max(1),
            prestress: true,
            ..ModalRequest::default()
        };
        Some(modal(input, &request)?)
    } else {
        None
    };
    let mut sections = p.sections;
    if has_release(model) {
        let settings = SwitchOffSettings {
            compare_rigid: true,
            ..SwitchOffSettings::default()
        };
        let r = run_switch_off(model, &settings)
            .map_err(|e| CommandError::simulation(input.label(), e))?;
        // The paper's Fig. 10 study for the paper's model (`switch-off
        // --fig10`).
        let study = if r.builtin {
            Some(super::switch_off::fig10(input, &r)?)
        } else {
            None
        };
        sections.push(switch_off_section(&r, study.as_ref()));
    }
    let mut mode_sets = vec![ModeSet {
        title: "Modes at the reference",
        system: p.system,
        q: &p.system.q0,
        modal: p.modal,
        damping_ratio: p.damping_ratio,
    }];
    let mut warnings = p.warnings;
    if let Some(run) = &prestressed {
        mode_sets.push(ModeSet {
            title: "Modes at the pre-stressed equilibrium",
            system: &run.system,
            q: run.outcome.q(&run.system),
            modal: run.outcome.result(),
            damping_ratio: damping_ratios(&run.document.output),
        });
        warnings.extend(run.document.own_warnings().iter().cloned());
    }
    let page = ReportInput {
        provenance: Provenance {
            tool_version: tool_version().to_string(),
            model_name: model.name.clone(),
            model_sha256: input.sha256.clone(),
            command_line: request.command_line.clone(),
            date: utc_now(),
        },
        description: &model.description,
        mode_sets,
        sections,
        warnings: &warnings,
    };
    let html = report_html(&page)?;
    Ok(Report {
        out: request.out.clone(),
        html,
        warnings,
        model_warnings: p.model_warnings,
    })
}
