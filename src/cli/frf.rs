//! `ancf-modal frf`: measured hammer records (CSV or UFF 58) or a measured
//! FRF in, H1/H2/coherence and the identified modes out.

use super::common::write_output;
use ancf_modal::measured::analysis::{analyse, AnalysisSettings, Estimator, FrfAnalysis};
use ancf_modal::measured::window::Window;
use ancf_modal::measured::{read_measurement, Channel, Channels};
use ancf_modal::output::frf_report::{
    frf_csv, frf_figure, frf_json, frf_table, frf_uff, ResponseQuantity,
};
use ancf_modal::output::plot::{render, Figure, Format, PlotSize};
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
    pub measured: MeasuredArgs,
    /// Print one JSON document instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Also write frequency, H1, H2, coherence and the fitted FRF as CSV.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Also draw the FRF with the fitted modes, the coherence and the
    /// stabilization diagram (.svg or .png).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Also write H1 and the coherence as UFF 58 (complex double).
    #[arg(long, value_name = "FILE")]
    pub uff: Option<PathBuf>,
}

/// How measurement files are read and analysed (shared with `identify
/// --measured`).
#[derive(Debug, Args, Clone)]
pub struct MeasuredArgs {
    /// Force channel: CSV column name or 1-based index (default 2), UFF
    /// record label or index (default the force record).
    #[arg(long, value_name = "COL")]
    pub force: Option<Channel>,
    /// Response channel: CSV column name or 1-based index (default 3).
    #[arg(long, value_name = "COL")]
    pub response: Option<Channel>,
    /// What the response measures (the FRF's unit).
    #[arg(long, value_enum, default_value_t = Quantity::Velocity)]
    pub response_quantity: Quantity,
    /// rect, hann, force:P (keep the first fraction P of the force record),
    /// exponential:P (decay to P at the end; its damping is removed).
    #[arg(long, default_value = "rect", value_parser = parse_window)]
    pub window: Window,
    /// FRF estimator the modal fit uses.
    #[arg(long, value_enum, default_value_t = EstimatorArg::H1)]
    pub estimator: EstimatorArg,
    /// Fit band LO:HI in Hz (default: where the hammer excited the
    /// structure, up to 0.8 × Nyquist).
    #[arg(long, value_name = "LO:HI", value_parser = parse_band)]
    pub band: Option<(f64, f64)>,
    /// Highest model order of the stabilization diagram.
    #[arg(long, default_value_t = 40, value_parser = clap::value_parser!(u64).range(2..=200))]
    pub max_order: u64,
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

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum EstimatorArg {
    H1,
    H2,
}

fn parse_window(s: &str) -> Result<Window, String> {
    s.parse()
}

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

impl MeasuredArgs {
    /// Reads the files and runs the analysis.
    pub fn analyse(&self, files: &[PathBuf]) -> Result<FrfAnalysis> {
        let channels = Channels {
            force: self.force.clone(),
            response: self.response.clone(),
        };
        let measurements = files
            .iter()
            .map(|f| read_measurement(f, &channels))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(analyse(
            measurements,
            AnalysisSettings {
                window: self.window,
                estimator: match self.estimator {
                    EstimatorArg::H1 => Estimator::H1,
                    EstimatorArg::H2 => Estimator::H2,
                },
                band: self.band,
                max_order: self.max_order as usize,
            },
        )?)
    }
}

pub fn run(args: FrfArgs) -> Result<()> {
    let a = args.measured.analyse(&args.files)?;
    let q: ResponseQuantity = args.measured.response_quantity.into();
    // Everything is rendered before anything is written: an error leaves
    // no output file behind.
    let plot = match &args.plot {
        Some(p) => {
            let fig: Figure = frf_figure(&a, q, None).into();
            let size = PlotSize {
                height: 1100,
                ..PlotSize::default()
            };
            Some((p, render(&fig, Format::from_path(p)?, size)?))
        }
        None => None,
    };
    let csv = args.csv.as_ref().map(|p| (p, frf_csv(&a)));
    let uff = args.uff.as_ref().map(|p| (p, frf_uff(&a, q, None)));
    if let Some((p, bytes)) = plot {
        ancf_modal::output::files::write_atomic(p, &bytes)?;
    }
    if let Some((p, text)) = csv {
        write_output(p, &text)?;
    }
    if let Some((p, text)) = uff {
        write_output(p, &text)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&frf_json(&a, q, None))?);
    } else {
        print!("{}", frf_table(&a, q));
    }
    Ok(())
}
