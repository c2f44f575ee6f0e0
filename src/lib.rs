//! # ancf-modal
//!
//! Modal and frequency-response analysis of planar rigid-flexible assemblies
//! whose flexible parts are ANCF cable beams (absolute nodal coordinate
//! formulation, Euler–Bernoulli, gradient-deficient).
//!
//! Data flows one way: model file ([`model`]) → assembled system
//! ([`system`]) → analysis ([`analysis`]) → outputs ([`output`]).
//! All quantities are SI unless a name says otherwise (`_deg`, `_hz`).

#![forbid(unsafe_code)]

pub mod analysis;
pub mod commands;
pub mod error;
pub mod linalg;
pub mod measured;
pub mod mechanics;
pub mod model;
pub mod output;
pub mod results;
pub mod signal;
pub mod system;

pub use error::{AnalysisError, ModelError};
pub use model::Model;
pub use system::System;
