//! `convergence`: the mesh convergence of the first bending frequencies
//! [Hz]. Every beam is meshed with 2, 4, 8, … elements up to
//! `max_elements`; the relative errors |f(n) − f|/f [–] are taken against
//! Euler–Bernoulli's free-free beam, f = (βL)²/(2πL²)·√(EI/ρA), for a
//! model that is a single free beam, else against the finest mesh. Hermite
//! cubics converge as O(h⁴): the observed order between the finest meshes
//! should approach 4.

use super::{CommandError, ModelInput, Run};
use crate::analysis::convergence::{
    euler_bernoulli_free_free, mesh_convergence_with, with_elements, ConvergenceData, Reference,
};
use crate::error::ModelError;
use crate::output::figures::{convergence_figure, write_figure};
use crate::output::plot::PlotSize;
use crate::results::fit::{last_orders, reference_note};
use crate::results::ConvergenceOutput;
use std::fmt::Write;
use std::path::Path;

/// What `convergence` computes.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergenceRequest {
    /// The finest mesh: elements per beam 2, 4, 8, … up to this number
    /// (2 to 256) [–].
    pub max_elements: usize,
    /// The number of bending modes compared (1 to 10) [–].
    pub modes: usize,
}

impl Default for ConvergenceRequest {
    fn default() -> Self {
        ConvergenceRequest {
            max_elements: 64,
            modes: 3,
        }
    }
}

/// `convergence`'s output: the study and its document.
#[derive(Debug, Clone)]
pub struct ConvergenceRun {
    /// Frequencies and errors per mesh.
    pub data: ConvergenceData,
    /// The document with the run's warnings.
    pub document: Run<ConvergenceOutput>,
}

/// 2, 4, 8, … ≤ `max`, and `max` itself.
fn element_counts(max: usize) -> Vec<usize> {
    let mut n: Vec<usize> = std::iter::successors(Some(2), |&n| Some(2 * n))
        .take_while(|&n| n <= max)
        .collect();
    if n.last() != Some(&max) {
        n.push(max);
    }
    n
}

/// Runs `convergence` on `input`.
pub fn run(
    input: &ModelInput,
    request: &ConvergenceRequest,
) -> Result<ConvergenceRun, CommandError> {
    let (max, modes) = (request.max_elements, request.modes);
    if !(2..=256).contains(&max) {
        return Err(CommandError::argument(
            "max_elements",
            max,
            "must be a whole number from 2 to 256",
        ));
    }
    if !(1..=10).contains(&modes) {
        return Err(CommandError::argument(
            "modes",
            modes,
            "must be a whole number from 1 to 10",
        ));
    }
    let model = &input.model;
    // The finest mesh must still be a valid model (element limit).
    with_elements(model, max)
        .validate()
        .map_err(|(path, problem)| ModelError::Invalid {
            source_name: input.source.clone(),
            path,
            problem,
        })?;
    let exact = euler_bernoulli_free_free(model, modes);
    let reference = match &exact {
        Some(f) => Reference::Exact(f),
        None => Reference::FinestMesh { modes },
    };
    let data = mesh_convergence_with(|n| with_elements(model, n), reference, &element_counts(max))
        .map_err(|e| CommandError::analysis(input.label(), e))?;
    Ok(ConvergenceRun {
        document: Run::of(input, ConvergenceOutput::new(&data)),
        data,
    })
}

impl ConvergenceRun {
    /// Draws the errors against the element count (log-log) to `path`
    /// (.svg or .png).
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        write_figure(
            &convergence_figure(&self.data).into(),
            path,
            PlotSize::default(),
        )?;
        Ok(())
    }

    /// The command line's table.
    pub fn text(&self) -> String {
        table(&self.data)
    }
}

fn table(data: &ConvergenceData) -> String {
    let modes = data.reference_hz.len();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {}: mesh convergence of the first {modes} bending frequencies",
        data.model
    );
    let refs: Vec<String> = data
        .reference_hz
        .iter()
        .map(|f| format!("{f:.3}"))
        .collect();
    let _ = writeln!(
        s,
        "reference: {}\nreference frequencies [Hz]: {}",
        reference_note(data),
        refs.join(", ")
    );
    let _ = write!(s, "{:>8}  {:>11}", "elements", "coordinates");
    for k in 1..=modes {
        let _ = write!(s, "  {:>12}", format!("f{k} [Hz]"));
    }
    for k in 1..=modes {
        let _ = write!(s, "  {:>9}", format!("error {k}"));
    }
    s.push('\n');
    for (i, (n, c)) in data.elements.iter().zip(&data.coordinates).enumerate() {
        let _ = write!(s, "{n:>8}  {c:>11}");
        for f in &data.frequencies_hz {
            let _ = write!(s, "  {:>12.3}", f[i]);
        }
        for e in &data.errors {
            let cell = if e[i].is_finite() {
                format!("{:.2e}", e[i])
            } else {
                String::from("-")
            };
            let _ = write!(s, "  {cell:>9}");
        }
        s.push('\n');
    }
    let orders: Vec<String> = last_orders(data)
        .iter()
        .map(|p| format!("{p:.2}"))
        .collect();
    let _ = writeln!(
        s,
        "observed order between the finest meshes: {} (Hermite cubics: 4)",
        orders.join(", ")
    );
    s
}
