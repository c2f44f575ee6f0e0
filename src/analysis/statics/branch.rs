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

/// How an equilibrium was reached.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Branch {
    /// Load stepping from the design's own reference.
    Reference { path: LoadPath },
    /// Continued along the straight path of designs from the equilibrium
    /// of design `from`, in `steps` steps.
    Continued { from: String, steps: usize },
    /// The continuation from `from` did not reach the design (`reason`);
    /// solved from the design's own reference instead.
    ReferenceAfterContinuation {
        from: String,
        reason: String,
        path: LoadPath,
    },
}

impl fmt::Display for Branch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Branch::Reference { path } => {
                write!(f, "solved from the reference, load path: {path}")
            }
            Branch::Continued { from, steps } => write!(
                f,
                "continued from the equilibrium of design `{from}` ({steps} path steps)"
            ),
            Branch::ReferenceAfterContinuation { from, reason, path } => write!(
                f,
                "solved from the reference (load path: {path}) because the continuation from design `{from}` failed: {reason}"
            ),
        }
    }
}
