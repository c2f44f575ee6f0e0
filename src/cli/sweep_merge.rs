//! `ancf-modal sweep-merge`: maps the shard files to
//! [`ancf_modal::commands::sweep_merge`] and renders the merged sweep as
//! `sweep` renders one run (table or JSON, CSV, plot).

use super::common::Warnings;
use super::output::OutputArgs;
use super::sweep::{emit, SWEEP_OUTPUTS};
use ancf_modal::commands::sweep_merge::{run as sweep_merge, SweepMergeRequest};
use anyhow::{anyhow, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SweepMergeArgs {
    /// The shards' JSON documents (`sweep --shard K/N --json > FILE`).
    #[arg(value_name = "SHARD.json", required = true)]
    pub shards: Vec<PathBuf>,
    #[command(flatten)]
    pub outputs: OutputArgs,
}

pub fn run(args: SweepMergeArgs) -> Result<Warnings> {
    args.outputs.only("sweep-merge", SWEEP_OUTPUTS)?;
    let request = SweepMergeRequest::from_files(&args.shards)?;
    let run = sweep_merge(&request)?;
    if let Some(path) = &args.outputs.plot {
        run.check_plot(path).map_err(|e| anyhow!("--plot: {e}"))?;
    }
    emit(&run, &args.outputs)?;
    // The document keeps the shards' warnings; they were printed when the
    // shards ran.
    Ok(Vec::new())
}
