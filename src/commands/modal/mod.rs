//! `modal`: the natural frequencies [Hz] and mass-normalized mode shapes
//! of the assembly linearized at its reference configuration, or (with
//! `prestress`) at the static equilibrium under its loads × `load_scale`
//! and gravity, with the unstressed modes beside. Each mode's damping ζ
//! [–] comes from the Rayleigh formula, or from complex modes when the
//! model has dampers. On request, the MAC [–] of the elastic modes against
//! another mode set (a model file or UFF 55 modes).

use super::{CommandError, ModelInput, Run};
use crate::analysis::prestress::PrestressedModal;
use crate::analysis::statics::StaticSettings;
use crate::analysis::{EigenMethod, ModalResult, ModalSettings};
use crate::output::modal_report::{modal_csv, modal_table, prestress_table};
use crate::output::modal_uff::{export_nodes, modal_uff};
use crate::results::modal::MacTable;
use crate::results::ModalJson;
use crate::System;
use std::path::{Path, PathBuf};

mod mac;

pub use mac::{mac_against, mac_of};

/// What `modal` computes.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalRequest {
    /// Number of modes to report, zero-frequency ones included [–] (≥ 1).
    pub modes: usize,
    /// The eigensolver: dense up to 300 free coordinates, sparse
    /// shift-invert above ([`EigenMethod::Auto`]), or one forced.
    pub solver: EigenMethod,
    /// Linearize at the static equilibrium under the loads (pre-stress).
    pub prestress: bool,
    /// Factor on the applied loads for `prestress` (gravity is not scaled)
    /// [–].
    pub load_scale: f64,
    /// Another mode set to compare with by the MAC: a model file (`.json`)
    /// or a UFF file with datasets 55, matched by node number.
    pub mac: Option<PathBuf>,
}

impl Default for ModalRequest {
    fn default() -> Self {
        ModalRequest {
            modes: 12,
            solver: EigenMethod::Auto,
            prestress: false,
            load_scale: 1.0,
            mac: None,
        }
    }
}

/// The modes computed: at the reference, or at the equilibrium beside the
/// reference's.
#[derive(Debug, Clone)]
pub enum ModalOutcome {
    Reference(Box<ModalResult>),
    Prestressed(Box<PrestressedModal>),
}

impl ModalOutcome {
    /// The modes reported (the pre-stressed ones when pre-stressed).
    pub fn result(&self) -> &ModalResult {
        match self {
            ModalOutcome::Reference(r) => r,
            ModalOutcome::Prestressed(p) => &p.prestressed,
        }
    }

    /// The state the modes are linearized at.
    pub fn q<'a>(&'a self, system: &'a System) -> &'a [f64] {
        match self {
            ModalOutcome::Reference(_) => &system.q0,
            ModalOutcome::Prestressed(p) => &p.equilibrium.q,
        }
    }
}

/// `modal`'s output: the assembled system, the modes and the document.
#[derive(Debug)]
pub struct ModalRun {
    /// The model the modes belong to.
    pub model: std::sync::Arc<crate::model::ValidModel>,
    /// Its assembled system (for drawings and exports).
    pub system: System,
    /// The modes.
    pub outcome: ModalOutcome,
    /// The document with the run's warnings.
    pub document: Run<ModalJson>,
}

/// Runs `modal` on `input`.
pub fn run(input: &ModelInput, request: &ModalRequest) -> Result<ModalRun, CommandError> {
    super::checks::modes_and_load_scale(request.modes, request.load_scale)?;
    let model = &input.model;
    let system = System::new(model);
    let settings = ModalSettings {
        modes: Some(request.modes),
        method: request.solver,
    };
    let fail = |e| CommandError::analysis(input.label(), e);
    let (outcome, output, own) = if request.prestress {
        let statics = StaticSettings {
            load_scale: request.load_scale,
            ..StaticSettings::default()
        };
        let (r, output) = crate::results::modal::prestressed(model, &system, &statics, &settings)
            .map_err(fail)?;
        let own = crate::results::modal::prestressed_warnings(&r);
        let outcome = ModalOutcome::Prestressed(Box::new(r));
        (outcome, ModalJson::Prestressed(output), own)
    } else {
        let (r, mut output) =
            crate::results::modal::modal(model, &system, &settings).map_err(fail)?;
        let own = reference_modal_warnings(model, &system, &r);
        if let Some(other) = &request.mac {
            output.mac = Some(mac_against(&system, &r, other, &settings)?);
        }
        (
            ModalOutcome::Reference(Box::new(r)),
            ModalJson::Reference(output),
            own,
        )
    };
    let document = Run::of(input, output).warn(input, own);
    Ok(ModalRun {
        model: input.model.clone(),
        system,
        outcome,
        document,
    })
}

/// The warnings of a modal analysis at the reference (`modal`'s, and
/// those it adds to `identify` and `report`): not an equilibrium or
/// unstable, loads the reference leaves out, beam theory, the
/// eigen-solve's accuracy.
pub fn reference_modal_warnings(
    model: &crate::Model,
    system: &System,
    r: &crate::analysis::ModalResult,
) -> Vec<String> {
    let mut own = crate::results::modal::reference_warnings(r);
    own.extend(crate::results::modal::loads_left_out(system, r));
    own.extend(crate::analysis::shear::beam_theory_warnings(r));
    if let Some(worst) = r.accuracy_warning() {
        let units = model.unit_warnings();
        own.push(crate::output::modal_report::accuracy_warning_text(
            worst, &units,
        ));
    }
    own
}

impl ModalRun {
    /// The MAC table against the request's other mode set, if any.
    pub fn mac(&self) -> Option<&MacTable> {
        match &self.document.output {
            ModalJson::Reference(o) => o.mac.as_ref(),
            _ => None,
        }
    }

    /// The command line's report: the table of the modes, the damping and
    /// the MAC against the other mode set.
    pub fn text(&self) -> String {
        match (&self.outcome, &self.document.output) {
            (ModalOutcome::Reference(r), ModalJson::Reference(output)) => {
                let mut s = modal_table(&self.model, r);
                s.push_str(&notes(&self.model, output));
                if let Some(mac) = &output.mac {
                    s.push_str(&mac::mac_table(mac));
                }
                s
            }
            (ModalOutcome::Prestressed(p), _) => prestress_table(&self.model.name, p),
            (ModalOutcome::Reference(r), _) => modal_table(&self.model, r),
        }
    }

    /// The modes as CSV (`--csv`).
    pub fn csv(&self) -> String {
        modal_csv(self.outcome.result())
    }

    /// The elastic modes as UFF 15 (nodes) and 55 (mass-normalized
    /// translations), stamped with the model's hash.
    pub fn uff(&self) -> String {
        let sha = self.document.model_sha256.as_deref().unwrap_or_default();
        let provenance = crate::results::provenance::header_lines(sha);
        modal_uff(&self.system, self.outcome.result(), &provenance)
    }

    /// Draws the first six elastic mode shapes to `path` (.svg or .png).
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        crate::output::figures::write_mode_shapes(
            &self.system,
            self.outcome.q(&self.system),
            self.outcome.result(),
            path,
        )?;
        Ok(())
    }

    /// The number of export nodes (beam nodes, body points) the MAC and the
    /// UFF use.
    pub fn export_nodes(&self) -> usize {
        export_nodes(&self.system).len()
    }
}

/// The lines under the table at the reference: the Poisson ratio the shear
/// estimate assumed, and the modes' damping ratios.
fn notes(model: &crate::Model, output: &crate::results::ModalOutput) -> String {
    let mut s = String::new();
    if crate::analysis::shear::poisson_assumed(model) {
        s.push_str(&format!(
            "shear %: Timoshenko against Euler–Bernoulli, estimated from each bending mode's shape, with ν = {} where the material gives no `poisson`\n",
            crate::analysis::shear::DEFAULT_POISSON
        ));
    }
    let complex = output.complex_modes;
    let lines: Vec<String> = output
        .modes
        .iter()
        .filter_map(|m| {
            let z = format!("mode {}: {:.4} %", m.mode.index, 100.0 * m.damping_ratio?);
            Some(match (complex, m.damped_frequency_hz) {
                (false, _) => z,
                (true, Some(f)) => format!("{z}, f_d {f:.2} Hz"),
                (true, None) => format!("{z}, overdamped"),
            })
        })
        .collect();
    match model.damping {
        _ if complex => s.push_str(&format!(
            "Complex modes (dampers{}; in the basis of the computed modes): {}\n",
            if model.damping.is_some() {
                " and Rayleigh damping"
            } else {
                ""
            },
            lines.join(", ")
        )),
        Some(d) => s.push_str(&format!(
            "Rayleigh damping (α = {} 1/s, β = {:e} s), ζ = α/(2ω) + βω/2: {}\n",
            d.alpha,
            d.beta,
            lines.join(", ")
        )),
        None => {}
    }
    s
}
