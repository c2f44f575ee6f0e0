//! Analyses on an assembled [`crate::System`]: each states its problem and
//! leaves the matrix algorithms to [`crate::linalg`].

pub mod calibrate;
pub mod convergence;
pub mod dispersion;
pub mod frame;
pub mod impulse;
pub mod modal;
pub mod prestress;
mod reduced_tangent;
pub mod sensor;
pub mod spectrum;
pub mod statics;
pub mod transient;
pub mod zero_modes;

pub use modal::{
    modal, modal_at_reference, EigenMethod, ModalResult, ModalSettings, Mode, ModeKind,
};
