//! `ancf-modal convergence`: mesh convergence of the first bending
//! frequencies, against Euler–Bernoulli for a single free beam, else
//! against the finest mesh of the study.

use super::common::{load_model, print_json};
use super::output::Output;
use ancf_modal::analysis::convergence::{
    euler_bernoulli_free_free, mesh_convergence_with, with_elements, ConvergenceData, Reference,
};
use ancf_modal::error::{ModelError, Source};
use ancf_modal::output::figures::{convergence_figure, write_figure};
use ancf_modal::output::plot::{Format, PlotSize};
use ancf_modal::results::fit::{last_orders, reference_note};
use ancf_modal::results::ConvergenceOutput;
use anyhow::Result;
use clap::Args;
use std::fmt::Write;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ConvergenceArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Finest mesh: elements per beam 2, 4, 8, … up to this number.
    #[arg(long, default_value_t = 64, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 2, Some(256)))]
    pub max_elements: u64,
    /// Number of bending modes compared.
    #[arg(long, default_value_t = 3, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 1, Some(10)))]
    pub modes: u64,
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

pub fn run(args: ConvergenceArgs) -> Result<()> {
    args.output
        .only("convergence", &[Output::Json, Output::Plot])?;
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    let model = load_model(args.model.as_deref())?;
    let max = args.max_elements as usize;
    let modes = args.modes as usize;
    // The finest mesh must still be a valid model (element limit).
    with_elements(&model, max)
        .validate()
        .map_err(|(path, problem)| ModelError::Invalid {
            source_name: args.model.clone().map_or(Source::BuiltIn, Source::File),
            path,
            problem,
        })?;
    let exact = euler_bernoulli_free_free(&model, modes);
    let reference = match &exact {
        Some(f) => Reference::Exact(f),
        None => Reference::FinestMesh { modes },
    };
    let data = mesh_convergence_with(
        |n| with_elements(&model, n),
        reference,
        &element_counts(max),
    )?;
    if let Some(path) = &args.output.plot {
        write_figure(&convergence_figure(&data).into(), path, PlotSize::default())?;
    }
    if args.output.json {
        print_json(ConvergenceOutput::new(&data), args.model.as_deref())?;
    } else {
        out!("{}", table(&data));
    }
    Ok(())
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
