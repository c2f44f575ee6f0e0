//! Subcommands. Each file parses its flags, validates them, calls the
//! library and prints; nothing numerical lives here.

/// `print!` to standard output through [`common::emit`] (a closed pipe,
/// as in `| head`, ends the program quietly instead of panicking); in a
/// function returning `anyhow::Result`.
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::common::emit(&format!($($arg)*))?
    };
}

/// `println!` through [`common::emit`], as [`out!`].
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::cli::common::emit(&format!("{}\n", format_args!($($arg)*)))?
    };
}

mod args;
mod calibrate;
mod common;
mod convergence;
mod frf;
mod identify;
mod impulse;
mod modal;
mod output;
mod reduce;
mod report;
mod statics;
mod sweep;
mod sweep_merge;
mod switch_off;
mod transient;
mod values;

use anyhow::Result;
use clap::{Parser, Subcommand};

/// Modal and frequency-response analysis of planar rigid-flexible
/// assemblies with ANCF beams.
#[derive(Debug, Parser)]
#[command(name = "ancf-modal", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// The main job: modal analysis, the impulse experiment and the paper's Table 3.
    Identify(identify::IdentifyArgs),
    /// The paper's time-domain test: half-sine pulse, sensor, spectrum, first bending peak.
    Impulse(impulse::ImpulseArgs),
    /// Natural frequencies and mode shapes of the linearized assembly.
    Modal(args::ModalArgs),
    /// Fit model parameters (equivalent geometry) to measured frequencies.
    Calibrate(calibrate::CalibrateArgs),
    /// Mesh convergence of the first bending frequencies (log-log errors, O(h⁴)).
    Convergence(convergence::ConvergenceArgs),
    /// Static equilibrium under the model's constant loads and gravity.
    Static(statics::StaticArgs),
    /// A quantity over a grid of model parameters (parallel; --shard for job arrays).
    Sweep(sweep::SweepArgs),
    /// Join the JSON documents of `sweep --shard K/N` into the complete sweep.
    SweepMerge(sweep_merge::SweepMergeArgs),
    /// Time integration with sensors, contacts and the energy balance.
    Transient(transient::TransientArgs),
    /// The paper's switch-off: pre-stressed equilibrium, release, node-0 travel (Figs. 7–9).
    SwitchOff(switch_off::SwitchOffArgs),
    /// One self-contained HTML file: the assembly, animated modes, the impulse test.
    Report(report::ReportArgs),
    /// Print the JSON Schema of the model file, or with --output that of a
    /// command's --json document.
    Schema(SchemaArgs),
    /// Measured hammer records (CSV, UFF 58) in: H1, H2, coherence, and the
    /// modes' frequencies and damping ratios (LSCF fit).
    Frf(frf::FrfArgs),
    /// The assembly as a reduced flexible body (Craig–Bampton or
    /// free-interface) for a multibody code such as Exudyn, with its check.
    #[command(
        override_usage = "ancf-modal reduce [OPTIONS] --interface <BEAM:S[,BEAM:S...]> [MODEL]"
    )]
    Reduce(reduce::ReduceArgs),
}

pub use common::print_warnings;

#[derive(Debug, clap::Args)]
pub struct SchemaArgs {
    /// Print the schema of this command's --json document (result and
    /// provenance) instead of the model file's.
    #[arg(long, value_name = "COMMAND", value_parser = clap::builder::PossibleValuesParser::new(ancf_modal::results::COMMANDS))]
    pub output: Option<String>,
}

/// Runs the command; its warnings, to print after a success.
pub fn run(cli: Cli) -> Result<common::Warnings> {
    match cli.command {
        Command::Identify(a) => identify::run(a),
        Command::Report(a) => report::run(a),
        Command::Impulse(a) => impulse::run(a),
        Command::Modal(a) => modal::run(a),
        Command::Calibrate(a) => calibrate::run(a),
        Command::Convergence(a) => convergence::run(a),
        Command::Static(a) => statics::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::SweepMerge(a) => sweep_merge::run(a),
        Command::Transient(a) => transient::run(a),
        Command::SwitchOff(a) => switch_off::run(a),
        Command::Schema(a) => {
            let schema = match &a.output {
                Some(command) => ancf_modal::results::output_schema(command)
                    .ok_or_else(|| anyhow::anyhow!("--output `{command}`: no such command"))?,
                None => ancf_modal::Model::json_schema(),
            };
            outln!("{}", serde_json::to_string_pretty(&schema)?);
            Ok(Vec::new())
        }
        Command::Frf(a) => frf::run(a),
        Command::Reduce(a) => reduce::run(a),
    }
}
