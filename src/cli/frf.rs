//! `ancf-modal frf`: maps the flags to [`ancf_modal::commands::frf`] and
//! renders its output: measured hammer records (CSV or UFF 58) or a
//! measured FRF in, H1/H2/coherence and the identified modes out.

use super::common::{print_document, write_output, Warnings};
use ancf_modal::commands::frf::{run as frf, FrfRecords, FrfRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::measured::analysis::Estimator;
use ancf_modal::measured::Channel;
use ancf_modal::output::frf_report::ResponseQuantity;
use ancf_modal::output::plot::Format;
use ancf_modal::signal::Window;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct FrfArgs {
    /// Measurement files: CSV (header row; time in the first column) or UFF
    /// 58 (time records, or an FRF). Several hits are averaged.
    #[arg(required = true, value_name = "SIGNALS")]
    pub files: Vec<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Force channel: CSV column name or 1-based index (default the one
    /// column whose name holds `force`, else 2), UFF record label or index (default
    /// the force record).
    #[arg(long, value_name = "COL")]
    pub force: Option<Channel>,
    /// Response channel: CSV column name or 1-based index (default the
    /// first column after time that is not the force).
    #[arg(long, value_name = "COL")]
    pub response: Option<Channel>,
    /// What the response measures (the FRF's unit) (default: what the
    /// response column's name ends with, as `impulse --csv` writes it, or a
    /// UFF FRF's ordinate type, else velocity).
    #[arg(long, value_enum)]
    pub response_quantity: Option<Quantity>,
    /// rect, hann, flattop, blackman, force:P (keep the first fraction P of
    /// the force record), exponential:P (decay to P at the end; its damping
    /// is removed).
    #[arg(long, default_value_t = FrfRequest::default().window)]
    pub window: Window,
    /// FRF estimator the modal fit uses.
    #[arg(long, value_enum, default_value_t = FrfRequest::default().estimator.into())]
    pub estimator: EstimatorArg,
    /// Fit band LO:HI in Hz (default: where the hammer excited the
    /// structure, up to 0.8 × Nyquist).
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true, value_parser = parse_band)]
    pub band: Option<(f64, f64)>,
    /// Highest model order of the stabilization diagram.
    #[arg(long, default_value_t = FrfRequest::default().max_order as u64, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 2, Some(200)))]
    pub max_order: u64,
    /// Overlay this model's FRF (modal superposition, its Rayleigh damping
    /// or 0.5 % if it has none) at the sensor --at, per newton of its first
    /// load.
    #[arg(long, value_name = "MODEL.json", requires = "at")]
    pub model: Option<PathBuf>,
    /// The model's sensor for --model.
    #[arg(long, value_name = "SENSOR", requires = "model")]
    pub at: Option<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Quantity {
    Displacement,
    Velocity,
    Acceleration,
}

impl From<Quantity> for ResponseQuantity {
    fn from(q: Quantity) -> Self {
        match q {
            Quantity::Displacement => ResponseQuantity::Displacement,
            Quantity::Velocity => ResponseQuantity::Velocity,
            Quantity::Acceleration => ResponseQuantity::Acceleration,
        }
    }
}

impl From<ResponseQuantity> for Quantity {
    fn from(q: ResponseQuantity) -> Self {
        match q {
            ResponseQuantity::Displacement => Quantity::Displacement,
            ResponseQuantity::Velocity => Quantity::Velocity,
            ResponseQuantity::Acceleration => Quantity::Acceleration,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum EstimatorArg {
    H1,
    H2,
}

impl From<EstimatorArg> for Estimator {
    fn from(e: EstimatorArg) -> Self {
        match e {
            EstimatorArg::H1 => Estimator::H1,
            EstimatorArg::H2 => Estimator::H2,
        }
    }
}

impl From<Estimator> for EstimatorArg {
    fn from(e: Estimator) -> Self {
        match e {
            Estimator::H1 => EstimatorArg::H1,
            Estimator::H2 => EstimatorArg::H2,
        }
    }
}

/// `LO:HI` [Hz] with 0 ≤ LO < HI.
pub fn parse_band(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once(':')
        .ok_or_else(|| format!("`{s}` is not LO:HI (Hz)"))?;
    let lo = super::args::finite(a)?;
    let hi = super::args::finite(b)?;
    if lo >= 0.0 && hi > lo {
        Ok((lo, hi))
    } else {
        Err(format!("the band needs 0 ≤ LO < HI, got {lo}:{hi}"))
    }
}

pub fn run(args: FrfArgs) -> Result<Warnings> {
    let model = match &args.model {
        Some(path) => Some(ModelInput::from_file(path)?),
        None => None,
    };
    let request = FrfRequest {
        records: FrfRecords::Files(args.files),
        force: args.force,
        response: args.response,
        response_quantity: args.response_quantity.map(Into::into),
        window: args.window,
        estimator: args.estimator.into(),
        band: args.band,
        max_order: args.max_order as usize,
        at: args.at,
    };
    let run = frf(model.as_ref(), &request)?;
    // Everything is rendered before anything is written: an error leaves
    // no output file behind.
    let plot = match &args.output.plot {
        Some(p) => Some((p, run.plot(Format::from_path(p)?)?)),
        None => None,
    };
    let csv = args.output.csv.as_ref().map(|p| (p, run.csv()));
    let uff = args.output.uff.as_ref().map(|p| (p, run.uff()));
    if let Some((p, bytes)) = plot {
        ancf_modal::output::files::write_atomic(p, &bytes)?;
    }
    if let Some((p, text)) = csv {
        write_output(p, &text)?;
    }
    if let Some((p, text)) = uff {
        write_output(p, &text)?;
    }
    if args.output.json {
        print_document(&run.document)?;
    } else {
        out!("{}", run.text());
    }
    Ok(run.document.warnings)
}
