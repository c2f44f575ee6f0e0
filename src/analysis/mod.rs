//! Analyses on an assembled [`crate::System`].

mod back_transform;
pub mod band;
pub mod bisection;
pub mod calibrate;
pub mod dispersion;
pub mod eigen;
pub mod frame;
mod fused;
pub mod householder;
pub mod impulse;
pub mod inverse_iteration;
pub mod lanczos;
use crate::linalg::sparse as lu; // band.rs orders by super::lu::rcm_order
pub mod modal;
pub mod prestress;
pub mod reduce;
mod reduced_tangent;
pub mod sensor;
mod simd;
pub mod small_eigen;
pub mod spectrum;
#[cfg(target_arch = "x86_64")]
mod standard_form;
pub mod statics;
pub mod transient;

pub use modal::{
    modal, modal_at_reference, EigenMethod, ModalResult, ModalSettings, Mode, ModeKind,
    ReducedProblem,
};
