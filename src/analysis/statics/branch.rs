//! Which equilibrium a static solve reports, and how it was reached.
//!
//! A pre-stressed assembly held by contacts can have several equilibria
//! for one design (the contact closed or open, a lever on either side of
//! its stop). The one a solve reports depends on how it got there: load
//! stepping from the design's own reference along a [`LoadPath`], or a
//! continuation in the design from a known design's equilibrium
//! ([`super::design_path`]). Every output that shows an equilibrium names
//! its branch.

use super::LoadPath;
use std::fmt;

/// How an equilibrium was reached: one of three kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BranchKind {
    /// Load stepping from the design's own reference.
    Reference,
    /// Continued along the straight path of designs from the equilibrium
    /// of another design.
    Continued,
    /// The continuation from another design did not reach this one; solved
    /// from the design's own reference instead.
    ReferenceAfterContinuation,
}

/// How an equilibrium was reached, with what its kind needs.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct Branch {
    /// `reference` (load stepping from the design's own reference),
    /// `continued` (continuation in the design from another design's
    /// equilibrium) or `reference_after_continuation` (the continuation
    /// failed; solved from the design's own reference).
    pub kind: BranchKind,
    /// The load path from the reference; null for a continuation.
    pub path: Option<LoadPath>,
    /// The design the continuation started from; null when solved from the
    /// reference alone.
    pub from: Option<String>,
    /// Steps of the continuation in the design; null when it did not
    /// reach the design.
    pub steps: Option<usize>,
    /// Why the continuation did not reach the design; null otherwise.
    pub reason: Option<String>,
}

impl Branch {
    /// Solved from the reference along `path`.
    pub fn reference(path: LoadPath) -> Branch {
        Branch {
            kind: BranchKind::Reference,
            path: Some(path),
            from: None,
            steps: None,
            reason: None,
        }
    }

    /// Continued from design `from` in `steps` steps.
    pub fn continued(from: &str, steps: usize) -> Branch {
        Branch {
            kind: BranchKind::Continued,
            path: None,
            from: Some(from.to_string()),
            steps: Some(steps),
            reason: None,
        }
    }

    /// Solved from the reference along `path` after the continuation from
    /// `from` failed for `reason`.
    pub fn after_continuation(from: &str, reason: String, path: LoadPath) -> Branch {
        Branch {
            kind: BranchKind::ReferenceAfterContinuation,
            path: Some(path),
            from: Some(from.to_string()),
            steps: None,
            reason: Some(reason),
        }
    }
}

impl fmt::Display for Branch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let path = self.path.unwrap_or(LoadPath::GravityFirst);
        let from = self.from.as_deref().unwrap_or("?");
        match self.kind {
            BranchKind::Reference => write!(f, "solved from the reference, load path: {path}"),
            BranchKind::Continued => write!(
                f,
                "continued from the equilibrium of design `{from}` ({} path steps)",
                self.steps.unwrap_or(0)
            ),
            BranchKind::ReferenceAfterContinuation => write!(
                f,
                "solved from the reference (load path: {path}) because the continuation from design `{from}` failed: {}",
                self.reason.as_deref().unwrap_or("?")
            ),
        }
    }
}
