//! The output flags every command that writes files shares: `--json`,
//! `--csv`, `--plot`, `--uff`. A command refuses the ones it has nothing
//! for, naming the flag and what it writes instead.

use anyhow::{bail, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Clone, Default, Args)]
pub struct OutputArgs {
    /// Print the result as one JSON document instead of the report (its
    /// schema: `ancf-modal schema --output COMMAND`).
    #[arg(long)]
    pub json: bool,
    /// Also write the data as CSV to FILE: modal the modes, impulse the
    /// signal (and the spectrum as FILE's stem + `.spectrum.csv` beside
    /// it), transient and switch-off the samples, sweep the points, frf
    /// frequency, H1, H2, coherence and the fit.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Also draw the result to FILE (.svg or .png); impulse adds the
    /// response as FILE's stem + `.response.<ext>`, switch-off the
    /// trajectory as FILE's stem + `.trajectory.<ext>` beside it.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Also write UFF to FILE: modal the nodes and elastic modes (15, 55),
    /// impulse and transient the time records (58), frf H1 and the
    /// coherence (58).
    #[arg(long, value_name = "FILE")]
    pub uff: Option<PathBuf>,
}

/// One of the outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Output {
    Json,
    Csv,
    Plot,
    Uff,
}

impl Output {
    fn flag(self) -> &'static str {
        match self {
            Output::Json => "--json",
            Output::Csv => "--csv",
            Output::Plot => "--plot",
            Output::Uff => "--uff",
        }
    }
}

impl OutputArgs {
    fn given(&self) -> Vec<Output> {
        let mut out = Vec::new();
        if self.json {
            out.push(Output::Json);
        }
        if self.csv.is_some() {
            out.push(Output::Csv);
        }
        if self.plot.is_some() {
            out.push(Output::Plot);
        }
        if self.uff.is_some() {
            out.push(Output::Uff);
        }
        out
    }

    /// Refuses an output `command` does not write (one line naming the
    /// flag and the outputs it has).
    pub fn only(&self, command: &str, allowed: &[Output]) -> Result<()> {
        if let Some(bad) = self.given().into_iter().find(|o| !allowed.contains(o)) {
            let has: Vec<&str> = allowed.iter().map(|o| o.flag()).collect();
            bail!(
                "{}: `{command}` writes no such output (it has {})",
                bad.flag(),
                has.join(", ")
            );
        }
        Ok(())
    }
}
