//! Analyses on an assembled [`crate::System`]: each states its problem and
//! leaves the matrix algorithms to [`crate::linalg`].

pub mod calibrate;
pub mod convergence;
pub mod damped_modes;
pub mod impulse;
pub mod modal;
pub mod model_frf;
pub mod moment_balance;
pub mod reduce;
pub mod shear;
pub mod simulate;
pub mod statics;
pub mod sweep;
pub mod switch_off;
pub mod switch_off_study;
pub mod transient;
pub mod zero_modes;

pub use impulse::sensor;
pub use statics::prestress;
pub use transient::{dispersion, frame};

pub use modal::{
    modal, modal_at_reference, EigenMethod, ModalResult, ModalSettings, Mode, ModeKind,
};
