//! Flags shared by more than one subcommand: `modal`'s arguments (its
//! `--prestress` variant runs in [`super::statics`], `--sweep-load` in
//! [`super::sweep`]) and the number parsers they use.

use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ModalArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// Number of modes to report, rigid ones included.
    #[arg(long, default_value_t = ancf_modal::commands::modal::ModalRequest::default().modes as u64, allow_hyphen_values = true, value_parser = super::values::at_least_one)]
    pub modes: u64,
    /// Eigensolver: dense up to 300 free coordinates and sparse
    /// shift-invert above (auto), or one of them forced.
    #[arg(long, value_enum, default_value_t = Solver::Auto)]
    pub solver: Solver,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Also print the MAC matrix against another mode set: a model file
    /// (.json) or a UFF file with datasets 55, matched by node number.
    #[arg(long, value_name = "OTHER")]
    pub mac: Option<PathBuf>,
    /// Draw the MAC matrix of --mac as a heat map with its values to FILE
    /// (.svg or .png).
    #[arg(long, value_name = "FILE", requires = "mac")]
    pub mac_plot: Option<PathBuf>,
    /// Linearize at the static equilibrium under the model's constant loads
    /// and gravity (pre-stress) and show the unstressed frequencies beside.
    #[arg(long)]
    pub prestress: bool,
    /// Factor on the applied loads for --prestress (gravity is not scaled).
    #[arg(long, value_name = "S", requires = "prestress", allow_negative_numbers = true, value_parser = finite)]
    pub load_scale: Option<f64>,
    /// Frequencies at the equilibrium for N load factors from A to B (first
    /// min(--modes, 6) elastic modes, tracked); --plot draws them, --csv
    /// writes them. Short for `sweep --param load_scale:<every load>=A:B:N
    /// --quantity frequency:1`.
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
    let from = finite(a)?;
    let to = finite(b)?;
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

/// A finite number.
pub fn finite(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|_| format!("`{s}` is not a number"))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("`{s}` is not a finite number"))
    }
}

/// `--solver` choices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Solver {
    Auto,
    Dense,
    Sparse,
}

impl From<Solver> for ancf_modal::analysis::EigenMethod {
    fn from(s: Solver) -> Self {
        match s {
            Solver::Auto => ancf_modal::analysis::EigenMethod::Auto,
            Solver::Dense => ancf_modal::analysis::EigenMethod::Dense,
            Solver::Sparse => ancf_modal::analysis::EigenMethod::Sparse,
        }
    }
}
