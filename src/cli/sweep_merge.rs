//! `ancf-modal sweep-merge`: joins the shard documents of `sweep --shard
//! K/N --json` into the document (and table, CSV, plot) a single run gives.

use super::output::OutputArgs;
use super::sweep::{emit, SWEEP_OUTPUTS};
use ancf_modal::analysis::sweep::{merge, SweepDocument, SweepError};
use ancf_modal::output::figures::sweep::check_plottable;
use ancf_modal::results::provenance::tool_version;
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

pub fn run(args: SweepMergeArgs) -> Result<()> {
    args.outputs.only("sweep-merge", SWEEP_OUTPUTS)?;
    let mut docs = Vec::with_capacity(args.shards.len());
    for path in &args.shards {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path)
            .map_err(|e| anyhow!("{file}: cannot read the file: {e}"))?;
        let doc: SweepDocument =
            serde_json::from_str(&text).map_err(|e| SweepError::NotADocument {
                file: file.clone(),
                message: e.to_string(),
            })?;
        docs.push((file, doc));
    }
    let run = merge(&docs)?;
    if let Some(path) = &args.outputs.plot {
        check_plottable(path, run.header.parameters.len()).map_err(|e| anyhow!("--plot: {e}"))?;
    }
    let doc = SweepDocument {
        tool_version: Some(tool_version().to_string()),
        model_sha256: docs[0].1.model_sha256.clone(),
        warnings: shard_warnings(&docs),
        ..run.document()
    };
    emit(&doc, &args.outputs)
}

/// The shards' warnings, each once, in the order of the shards.
fn shard_warnings(docs: &[(String, SweepDocument)]) -> Vec<String> {
    let mut all: Vec<String> = Vec::new();
    for w in docs.iter().flat_map(|(_, d)| &d.warnings) {
        if !all.contains(w) {
            all.push(w.clone());
        }
    }
    all
}
