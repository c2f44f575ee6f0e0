//! Mesh convergence of the first bending frequencies.
//!
//! The study solves the modal problem of one model at several numbers n of
//! elements per beam and compares the first bending frequencies f_k(n)
//! [SI: Hz] with a reference f_k: the relative error is |f_k(n) − f_k|/f_k.
//! The reference is either exact (for a free-free beam, Euler–Bernoulli:
//! f = (βL)²/(2πL²)·√(EI/ρA), [`euler_bernoulli_free_free`]) or the finest
//! mesh of the study, whose own error is then zero by definition (and NaN
//! in [`ConvergenceData::errors`]).
//!
//! Hermite cubic (ANCF cable) elements approximate the displacement with an
//! O(h³) error in slope, so a frequency (a Rayleigh quotient, stationary at
//! the exact mode) converges as O(h⁴) = O(n⁻⁴). The figure is
//! [`crate::output::figures::convergence_figure`].

use super::modal::{modal_at_reference, ModalResult, ModalSettings, ModeKind};
use crate::error::AnalysisError;
use crate::model::Model;
use crate::system::System;
use serde::Serialize;
use std::f64::consts::PI;

/// Element counts of a default study: 2, 4, …, 64.
pub const DEFAULT_ELEMENTS: [usize; 6] = [2, 4, 8, 16, 32, 64];

/// Free-free βL, the roots of cos βL · cosh βL = 1 (standard tables).
const FREE_FREE_BL: [f64; 4] = [
    4.730_040_744_862_704,
    7.853_204_624_095_838,
    10.995_607_838_001_671,
    14.137_165_491_257_464,
];

/// What the errors of a study are measured against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reference<'a> {
    /// Exact frequencies [SI: Hz] of the first bending modes, ascending.
    Exact(&'a [f64]),
    /// The first `modes` bending frequencies of the finest mesh.
    FinestMesh { modes: usize },
}

/// Kind of the reference of a finished study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceKind {
    Exact,
    FinestMesh,
}

/// Result of a mesh-convergence study.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct ConvergenceData {
    /// Name of the model.
    pub model: String,
    /// Elements per beam (the `elements` of each beam), ascending.
    pub elements: Vec<usize>,
    /// Number of coordinates of each mesh.
    pub coordinates: Vec<usize>,
    pub reference_kind: ReferenceKind,
    /// Reference frequency of each bending mode [SI: Hz].
    pub reference_hz: Vec<f64>,
    /// `frequencies_hz[k][i]`: bending mode k at mesh i [SI: Hz]; NaN when
    /// that mesh has fewer bending modes.
    pub frequencies_hz: Vec<Vec<f64>>,
    /// `errors[k][i] = |f_k(n_i) − f_k| / f_k`; NaN where undefined (and
    /// at the finest mesh when it is the reference).
    pub errors: Vec<Vec<f64>>,
}

impl ConvergenceData {
    /// Observed order p_k between meshes i and i+1:
    /// ln(e_i/e_{i+1}) / ln(n_{i+1}/n_i); NaN where an error is not positive.
    pub fn observed_order(&self, mode: usize, i: usize) -> f64 {
        let e = &self.errors[mode];
        let (n0, n1) = (self.elements[i] as f64, self.elements[i + 1] as f64);
        if e[i] > 0.0 && e[i + 1] > 0.0 {
            (e[i] / e[i + 1]).ln() / (n1 / n0).ln()
        } else {
            f64::NAN
        }
    }
}

/// `model` with every beam divided into `n` elements.
pub fn with_elements(model: &Model, n: usize) -> Model {
    let mut m = model.clone();
    for b in &mut m.beams {
        b.elements = n;
    }
    m
}

/// The first `modes` free-free Euler–Bernoulli bending frequencies [SI: Hz]
/// of `model` if it is a single free beam (no rigid body, point mass, joint
/// or spring; loads and sensors do not change the modes), else `None`.
/// βL beyond the tabulated four uses (k + ½)π, accurate to ~1e-8.
pub fn euler_bernoulli_free_free(model: &Model, modes: usize) -> Option<Vec<f64>> {
    let free = model.rigid_bodies.is_empty()
        && model.point_masses.is_empty()
        && model.joints.is_empty()
        && model.springs.is_empty();
    let [beam] = model.beams.as_slice() else {
        return None;
    };
    if !free {
        return None;
    }
    let ei = beam.section.bending_stiffness(beam.material.young);
    let rho_a = beam.section.mass_per_length(beam.material.density);
    let l = beam.length;
    let bl = |k: usize| {
        FREE_FREE_BL
            .get(k)
            .copied()
            .unwrap_or((k as f64 + 1.5) * PI)
    };
    Some(
        (0..modes)
            .map(|k| bl(k).powi(2) / (2.0 * PI * l * l) * (ei / rho_a).sqrt())
            .collect(),
    )
}

/// Study of `model_of_n(n)` for n in [`DEFAULT_ELEMENTS`] against the exact
/// frequencies `exact` of its first `exact.len()` bending modes.
pub fn mesh_convergence(
    model_of_n: impl Fn(usize) -> Model,
    exact: &[f64],
) -> Result<ConvergenceData, AnalysisError> {
    mesh_convergence_with(model_of_n, Reference::Exact(exact), &DEFAULT_ELEMENTS)
}

/// Study of `model_of_n(n)` for each n of `elements` (sorted and
/// deduplicated here) against `reference`. Each model is validated (an
/// invalid one, e.g. at 0 elements, is [`AnalysisError::InvalidMesh`]).
pub fn mesh_convergence_with(
    model_of_n: impl Fn(usize) -> Model,
    reference: Reference<'_>,
    elements: &[usize],
) -> Result<ConvergenceData, AnalysisError> {
    let mut elements = elements.to_vec();
    elements.sort_unstable();
    elements.dedup();
    let modes = match reference {
        Reference::Exact(f) => f.len(),
        Reference::FinestMesh { modes } => modes,
    };
    let mut name = String::new();
    let mut coordinates = Vec::new();
    let mut frequencies_hz = vec![Vec::with_capacity(elements.len()); modes];
    for &n in &elements {
        let model = model_of_n(n)
            .validated()
            .map_err(|source| AnalysisError::InvalidMesh {
                elements: n,
                source: Box::new(source),
            })?;
        name.clone_from(&model.name);
        let system = System::new(&model);
        coordinates.push(system.ndof());
        let result = modal_at_reference(&system, &ModalSettings::default())?;
        let f = bending(&result);
        for (k, series) in frequencies_hz.iter_mut().enumerate() {
            series.push(f.get(k).copied().unwrap_or(f64::NAN));
        }
    }
    let (reference_kind, reference_hz) = match reference {
        Reference::Exact(f) => (ReferenceKind::Exact, f.to_vec()),
        Reference::FinestMesh { .. } => {
            let last = |s: &Vec<f64>| s.last().copied().unwrap_or(f64::NAN);
            (
                ReferenceKind::FinestMesh,
                frequencies_hz.iter().map(last).collect(),
            )
        }
    };
    let errors = frequencies_hz
        .iter()
        .zip(&reference_hz)
        .map(|(series, &r)| {
            let mut e: Vec<f64> = series.iter().map(|f| ((f - r) / r).abs()).collect();
            if reference_kind == ReferenceKind::FinestMesh {
                if let Some(last) = e.last_mut() {
                    *last = f64::NAN;
                }
            }
            e
        })
        .collect();
    Ok(ConvergenceData {
        model: name,
        elements,
        coordinates,
        reference_kind,
        reference_hz,
        frequencies_hz,
        errors,
    })
}

/// Bending frequencies of a result, ascending.
fn bending(result: &ModalResult) -> Vec<f64> {
    result
        .of_kind(ModeKind::Bending)
        .map(|m| m.frequency_hz)
        .collect()
}
