//! Outputs: human-readable tables, JSON documents, CSV files, atomic writes.

pub mod calibrate_report;
pub mod figures;
pub mod files;
pub mod frf_report;
pub mod impulse_report;
pub mod modal_report;
pub mod modal_uff;
pub mod npz;
pub mod plot;
pub mod records_uff;
pub mod reduce_report;
pub mod report;
pub mod static_report;
pub mod sweep_report;
pub mod switch_off_report;
pub mod transient_report;
