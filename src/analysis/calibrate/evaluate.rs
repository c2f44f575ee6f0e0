//! Frequency evaluators: what one step of a calibration computes.
//!
//! [`FrequencyModel`] maps a model to the frequencies [Hz] of the tracked
//! modes (one per target). [`EigenFrequencies`] solves the eigenproblem at
//! the unstressed reference (analytic sensitivities), or, pre-stressed, at
//! the static equilibrium under the loads and gravity (as `modal
//! --prestress`; sensitivities by central differences of relative step
//! [`FD_STEP`], each a new equilibrium), and follows the modes by their shapes: at every
//! evaluation each target takes the elastic mode with the largest
//! mass-weighted modal assurance criterion
//! MAC(a, b) = (aᵀMb)² / ((aᵀMa)(bᵀMb)) against the shapes selected on the
//! starting model, so a target stays on its mode when modes cross as a
//! parameter moves. The coordinates do not change with the fitted
//! parameters (no geometry is moved), so shapes of different evaluations
//! are comparable.

use super::error::CalibrationError;
use super::params::ParameterSet;
use super::sensitivity::eigenvalue_sensitivities;
use crate::analysis::impulse::{run_impulse, ImpulseSettings};
use crate::analysis::statics::prestress::modal_at_equilibrium;
use crate::analysis::statics::start::{reference_balances, Start};
use crate::analysis::statics::{solve_equilibrium, StaticSettings};
use crate::analysis::{modal_at_reference, ModalResult, ModalSettings, ModeKind};
use crate::linalg::vector::dot;
use crate::model::{Model, ValidModel};
use crate::system::System;
use faer::Mat;
use std::f64::consts::PI;

/// Which modes the targets are matched to: the `numbers` (1-based, ascending
/// frequency) among the elastic modes of `kind`, one per target.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeSelection {
    pub kind: ModeKind,
    /// Empty = 1, 2, … (one per target).
    pub numbers: Vec<usize>,
}

impl Default for ModeSelection {
    fn default() -> Self {
        ModeSelection {
            kind: ModeKind::Bending,
            numbers: Vec::new(),
        }
    }
}

/// Frequencies and, where available, their sensitivities.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// Frequencies of the tracked modes [SI: Hz], in target order.
    pub frequencies_hz: Vec<f64>,
    /// ∂fᵢ/∂pⱼ [SI: Hz per parameter unit], row i = target, column j =
    /// parameter; `None` when the evaluator has no analytic derivatives.
    pub sensitivities: Option<Vec<Vec<f64>>>,
    /// 0-based index of each tracked mode in the modal result (rigid
    /// modes included); `None` when not known.
    pub mode_indices: Option<Vec<usize>>,
    /// MAC of each tracked mode with its starting shape.
    pub mac: Option<Vec<f64>>,
}

/// Anything that gives the frequencies of the tracked modes of a model.
pub trait FrequencyModel {
    /// Short name for reports (`eigen`, `impulse`).
    fn method(&self) -> &'static str;

    /// Frequencies [SI: Hz] of the tracked modes of `model`, in target order.
    fn frequencies(&self, model: &ValidModel) -> Result<Vec<f64>, CalibrationError>;

    /// Frequencies with ∂f/∂p for the parameters of `set`. The default has
    /// no derivatives.
    fn evaluate(
        &self,
        model: &ValidModel,
        set: &ParameterSet,
    ) -> Result<Evaluation, CalibrationError> {
        let _ = set;
        Ok(Evaluation {
            frequencies_hz: self.frequencies(model)?,
            sensitivities: None,
            mode_indices: None,
            mac: None,
        })
    }

    /// Whether [`FrequencyModel::evaluate`] gives sensitivities.
    fn has_sensitivities(&self) -> bool {
        false
    }

    /// Whether the frequencies of `model` are those of its static
    /// equilibrium under the loads and gravity (pre-stressed).
    fn prestressed(&self, model: &ValidModel) -> bool {
        let _ = model;
        false
    }
}

/// The eigenproblem at the unstressed reference, with mode tracking.
#[derive(Debug, Clone)]
pub struct EigenFrequencies {
    settings: ModalSettings,
    /// Linearize at the static equilibrium instead of the reference.
    prestress: bool,
    /// Starting shapes of the tracked modes (full coordinates).
    reference: Vec<Vec<f64>>,
    /// Their 1-based numbers among the modes of the selected kind.
    numbers: Vec<usize>,
    kind: ModeKind,
}

impl EigenFrequencies {
    /// Select the modes on the starting `model`: `targets` modes of
    /// `selection.kind`, numbered by `selection.numbers` (default 1, 2, …).
    pub fn new(
        model: &ValidModel,
        selection: &ModeSelection,
        targets: usize,
        settings: ModalSettings,
        prestress: bool,
    ) -> Result<EigenFrequencies, CalibrationError> {
        let numbers: Vec<usize> = if selection.numbers.is_empty() {
            (1..=targets).collect()
        } else {
            selection.numbers.clone()
        };
        if numbers.len() != targets {
            return Err(CalibrationError::ModeCount {
                modes: numbers.len(),
                targets,
            });
        }
        let result = solve(model, &settings, prestress, None)?;
        let of_kind: Vec<&crate::analysis::Mode> = result.of_kind(selection.kind).collect();
        let mut reference = Vec::with_capacity(targets);
        for &n in &numbers {
            let mode = n.checked_sub(1).and_then(|i| of_kind.get(i)).ok_or(
                CalibrationError::ModeNotFound {
                    kind: selection.kind,
                    number: n,
                    available: of_kind.len(),
                    unstressed_of_prestressed: false,
                },
            )?;
            reference.push(mode.shape.clone());
        }
        Ok(EigenFrequencies {
            settings,
            prestress,
            reference,
            numbers,
            kind: selection.kind,
        })
    }

    /// Kind of the tracked modes.
    pub fn kind(&self) -> ModeKind {
        self.kind
    }

    /// 1-based numbers of the tracked modes among their kind (starting model).
    pub fn numbers(&self) -> &[usize] {
        &self.numbers
    }

    /// Full evaluation: frequencies, tracked modes and (with `set`) ∂f/∂p.
    fn run(
        &self,
        model: &ValidModel,
        set: Option<&ParameterSet>,
    ) -> Result<Evaluation, CalibrationError> {
        let system = System::new(model);
        let result = linearized(&system, model, &self.settings, self.prestress, set)?;
        let mass = system.mass_matrix();
        let picked = track(&system, &mass, &result, &self.reference);
        let mut freqs = Vec::with_capacity(picked.len());
        // Analytic sensitivities at the reference; the pre-stressed ones by
        // differences below.
        let mut sens = set
            .filter(|_| !self.prestress)
            .map(|_| Vec::with_capacity(picked.len()));
        for &(i, _) in &picked {
            let mode = &result.modes[i];
            freqs.push(mode.frequency_hz);
            if let (Some(set), Some(rows)) = (set, sens.as_mut()) {
                let mut dl = vec![0.0; set.len()];
                eigenvalue_sensitivities(
                    model,
                    &system,
                    &mass,
                    set,
                    mode.eigenvalue,
                    &mode.shape,
                    &mut dl,
                );
                // λ = (2πf)²: df = dλ / (8π² f).
                let scale = 1.0 / (8.0 * PI * PI * mode.frequency_hz);
                rows.push(dl.iter().map(|d| d * scale).collect());
            }
        }
        if let (true, Some(set)) = (self.prestress, set) {
            sens = Some(self.differences(model, set)?);
        }
        Ok(Evaluation {
            frequencies_hz: freqs,
            sensitivities: sens,
            mode_indices: Some(picked.iter().map(|p| p.0).collect()),
            mac: Some(picked.iter().map(|p| p.1).collect()),
        })
    }
}

impl EigenFrequencies {
    /// ∂fᵢ/∂pⱼ by central differences of relative step [`FD_STEP`] about
    /// the parameters' values in `model` (rows: targets).
    fn differences(
        &self,
        model: &ValidModel,
        set: &ParameterSet,
    ) -> Result<Vec<Vec<f64>>, CalibrationError> {
        let values: Vec<f64> = set.params.iter().map(|p| p.target.get(model)).collect();
        let mut columns = Vec::with_capacity(values.len());
        for j in 0..values.len() {
            let h = FD_STEP * values[j].abs();
            let at = |sign: f64| -> Result<Vec<f64>, CalibrationError> {
                let mut v = values.clone();
                v[j] += sign * h;
                self.frequencies(&set.apply(&v)?)
            };
            let (up, down) = (at(1.0)?, at(-1.0)?);
            columns.push(
                up.iter()
                    .zip(&down)
                    .map(|(a, b)| (a - b) / (2.0 * h))
                    .collect::<Vec<f64>>(),
            );
        }
        let targets = columns.first().map_or(0, Vec::len);
        Ok((0..targets)
            .map(|i| columns.iter().map(|c| c[i]).collect())
            .collect())
    }
}

/// Relative step of the pre-stressed fit's central differences [–]: the
/// equilibrium converges to 1e-10 of its forces, so the frequencies carry
/// about that much noise; 1e-5 keeps its share of a derivative near 1e-5
/// and the truncation (h²) far below.
pub const FD_STEP: f64 = 1e-5;

impl FrequencyModel for EigenFrequencies {
    fn method(&self) -> &'static str {
        "eigen"
    }

    fn frequencies(&self, model: &ValidModel) -> Result<Vec<f64>, CalibrationError> {
        Ok(self.run(model, None)?.frequencies_hz)
    }

    fn evaluate(
        &self,
        model: &ValidModel,
        set: &ParameterSet,
    ) -> Result<Evaluation, CalibrationError> {
        self.run(model, Some(set))
    }

    fn has_sensitivities(&self) -> bool {
        true
    }

    fn prestressed(&self, _: &ValidModel) -> bool {
        self.prestress
    }
}

fn solve(
    model: &ValidModel,
    settings: &ModalSettings,
    prestress: bool,
    set: Option<&ParameterSet>,
) -> Result<ModalResult, CalibrationError> {
    linearized(&System::new(model), model, settings, prestress, set)
}

/// The modes at the reference, or at the static equilibrium under the
/// loads and gravity when `prestress` (as `modal --prestress`).
fn linearized(
    system: &System,
    model: &ValidModel,
    settings: &ModalSettings,
    prestress: bool,
    set: Option<&ParameterSet>,
) -> Result<ModalResult, CalibrationError> {
    let result = if prestress {
        solve_equilibrium(system, &StaticSettings::default())
            .and_then(|eq| modal_at_equilibrium(system, &eq, settings))
    } else {
        modal_at_reference(system, settings)
    };
    result.map_err(|source| CalibrationError::Analysis {
        at: describe(model, set),
        source,
    })
}

/// "blade.height = 1.1e-3, …" for error messages.
fn describe(model: &Model, set: Option<&ParameterSet>) -> String {
    match set {
        Some(set) => set
            .params
            .iter()
            .map(|p| format!("{} = {:e}", p.name, p.target.get(model)))
            .collect::<Vec<_>>()
            .join(", "),
        None => format!("model `{}`", model.name),
    }
}

/// For each reference shape, the elastic mode with the largest
/// mass-weighted MAC (greedy on the largest MAC first, each mode used once):
/// (mode index, MAC), in reference order.
fn track(
    system: &System,
    mass: &Mat<f64>,
    result: &ModalResult,
    reference: &[Vec<f64>],
) -> Vec<(usize, f64)> {
    let n = system.ndof();
    let elastic: Vec<usize> = result
        .modes
        .iter()
        .enumerate()
        .filter(|(_, m)| !m.kind.is_zero())
        .map(|(k, _)| k)
        .collect();
    // M a for each reference shape, and aᵀMa.
    let ma: Vec<Vec<f64>> = reference
        .iter()
        .map(|a| {
            (0..n)
                .map(|i| (0..n).map(|j| mass[(i, j)] * a[j]).sum())
                .collect()
        })
        .collect();
    let aa: Vec<f64> = reference.iter().zip(&ma).map(|(a, m)| dot(a, m)).collect();
    let mut table: Vec<(usize, usize, f64)> = Vec::new();
    for (r, m) in ma.iter().enumerate() {
        for &k in &elastic {
            let b = &result.modes[k].shape;
            let bb = system.mass_quadratic_form(mass, b);
            let ab = dot(m, b);
            table.push((r, k, ab * ab / (aa[r] * bb)));
        }
    }
    table.sort_by(|x, y| y.2.total_cmp(&x.2));
    let mut out: Vec<Option<(usize, f64)>> = vec![None; reference.len()];
    let mut used = vec![false; result.modes.len()];
    for (r, k, mac) in table {
        if out[r].is_none() && !used[k] {
            out[r] = Some((k, mac));
            used[k] = true;
        }
    }
    out.into_iter().map(|o| o.unwrap_or((0, 0.0))).collect()
}

/// One frequency from any function of the model, e.g. a time-domain
/// experiment with an FFT. It has no sensitivities, so it fits one parameter
/// to one target (Brent).
pub struct SingleFrequency<F> {
    method: &'static str,
    f: F,
}

impl<F> SingleFrequency<F>
where
    F: Fn(&ValidModel) -> Result<f64, CalibrationError>,
{
    /// `method` names the evaluator in reports; `f` gives the frequency [Hz].
    pub fn new(method: &'static str, f: F) -> Self {
        SingleFrequency { method, f }
    }
}

impl<F> FrequencyModel for SingleFrequency<F>
where
    F: Fn(&ValidModel) -> Result<f64, CalibrationError>,
{
    fn method(&self) -> &'static str {
        self.method
    }

    fn frequencies(&self, model: &ValidModel) -> Result<Vec<f64>, CalibrationError> {
        Ok(vec![(self.f)(model)?])
    }
}

/// The impulse experiment ([`crate::analysis::impulse`]) in the loop: each
/// evaluation integrates the pulse response, takes the sensor's spectrum
/// and returns the first bending peak, corrected for the integrator's
/// period error (so it estimates the same continuous frequency as the
/// eigenproblem). It has no sensitivities: one parameter, one target.
#[derive(Debug, Clone)]
pub struct ImpulseFrequency {
    pub settings: ImpulseSettings,
}

impl ImpulseFrequency {
    /// The experiment identifies the first bending mode only.
    pub fn new(
        selection: &ModeSelection,
        settings: ImpulseSettings,
    ) -> Result<ImpulseFrequency, CalibrationError> {
        let first = selection.numbers.is_empty() || selection.numbers == [1];
        if selection.kind != ModeKind::Bending || !first {
            return Err(CalibrationError::ImpulseMode {
                kind: selection.kind,
                numbers: selection.numbers.clone(),
            });
        }
        Ok(ImpulseFrequency { settings })
    }

    fn run(&self, model: &ValidModel, set: Option<&ParameterSet>) -> Result<f64, CalibrationError> {
        let result = run_impulse(model, &self.settings, &mut |_| {}).map_err(|source| {
            CalibrationError::Impulse {
                at: describe(model, set),
                source,
            }
        })?;
        result.first_bending.map(|f| f.corrected_hz).ok_or_else(|| {
            CalibrationError::NoImpulsePeak {
                at: describe(model, set),
            }
        })
    }
}

impl FrequencyModel for ImpulseFrequency {
    fn method(&self) -> &'static str {
        "impulse"
    }

    /// The blow strikes the static equilibrium unless the reference
    /// balances the loads ([`crate::analysis::statics::start`]).
    fn prestressed(&self, model: &ValidModel) -> bool {
        let system = System::new(model);
        self.settings.start == Start::Equilibrium
            && !(system.released.is_empty() && reference_balances(&system))
    }

    fn frequencies(&self, model: &ValidModel) -> Result<Vec<f64>, CalibrationError> {
        Ok(vec![self.run(model, None)?])
    }

    fn evaluate(
        &self,
        model: &ValidModel,
        set: &ParameterSet,
    ) -> Result<Evaluation, CalibrationError> {
        Ok(Evaluation {
            frequencies_hz: vec![self.run(model, Some(set))?],
            sensitivities: None,
            mode_indices: None,
            mac: None,
        })
    }
}
