//! `sweep-merge`: joins the shard documents of `sweep` with a shard (`K/N`)
//! into the document one run of the whole grid gives. Tracking modes by
//! MAC needs every point, so the shards carry their computed mode shapes
//! and the merge tracks them ([`crate::analysis::sweep::merge`]); the
//! values are the shards' own, unchanged (SI units, frequencies in Hz).
//!
//! No model is read: the documents name theirs by its hash, which the
//! merged document keeps (the first shard's), with the shards' warnings,
//! each once.

use super::sweep::SweepRun;
use super::{CommandError, Run};
use crate::analysis::sweep::{merge, SweepDocument, SweepError};
use std::path::Path;

/// What `sweep-merge` joins.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SweepMergeRequest {
    /// The shard documents, each with its name for messages (its file).
    pub shards: Vec<(String, SweepDocument)>,
}

impl SweepMergeRequest {
    /// The shard documents of the files `paths` (each named by its path).
    pub fn from_files(paths: &[impl AsRef<Path>]) -> Result<SweepMergeRequest, CommandError> {
        let shards = paths
            .iter()
            .map(|p| read(p.as_ref()))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(SweepMergeRequest { shards })
    }
}

/// The shard document in the file `path`, named by its path.
pub fn read(path: &Path) -> Result<(String, SweepDocument), CommandError> {
    let text = std::fs::read_to_string(path).map_err(|io| CommandError::ReadFile {
        file: path.to_path_buf(),
        io,
    })?;
    let name = path.display().to_string();
    let doc = parse(&name, &text)?;
    Ok((name, doc))
}

/// The sweep document in the JSON `text`, named `name` in messages.
pub fn parse(name: &str, text: &str) -> Result<SweepDocument, CommandError> {
    serde_json::from_str(text).map_err(|e| {
        CommandError::SweepMerge(SweepError::NotADocument {
            file: name.to_string(),
            message: e.to_string(),
        })
    })
}

/// Runs `sweep-merge`: the merged, tracked document.
pub fn run(request: &SweepMergeRequest) -> Result<SweepRun, CommandError> {
    let merged = merge(&request.shards)?;
    let first = request.shards.first().map(|(_, d)| d);
    Ok(SweepRun {
        document: Run {
            output: merged.document(),
            warnings: shard_warnings(&request.shards),
            model_sha256: first.and_then(|d| d.model_sha256.clone()),
            model_warnings: 0,
        },
    })
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
