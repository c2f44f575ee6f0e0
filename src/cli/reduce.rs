//! `ancf-modal reduce`: maps the flags to [`ancf_modal::commands::reduce`],
//! prints the reduced body's check and writes the body to `--out`.

use super::args::finite;
use super::common::Warnings;
use ancf_modal::analysis::reduce::ReductionMethod;
use ancf_modal::commands::reduce::{run as reduce, ReduceRequest};
use ancf_modal::commands::ModelInput;
use anyhow::{anyhow, Result};
use clap::{Args, ValueEnum};
use std::path::PathBuf;

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Method {
    CraigBampton,
    FreeInterface,
}

#[derive(Debug, Args)]
pub struct ReduceArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// Interface points BEAM:S (beam id, arc length in m), comma-separated.
    #[arg(long, value_name = "BEAM:S[,BEAM:S...]", required = true)]
    pub interface: String,
    /// Component modes (fixed-interface or free).
    #[arg(long, default_value_t = ReduceRequest::default().modes, value_name = "K")]
    pub modes: usize,
    #[arg(long, value_enum, default_value = "craig-bampton")]
    pub method: Method,
    /// Reduce at the static equilibrium under the loads (the stiffening
    /// kept, the preload forces not).
    #[arg(long)]
    pub prestress: bool,
    /// Factor on the applied loads for --prestress.
    #[arg(long, default_value_t = 1.0, value_name = "S", allow_negative_numbers = true, value_parser = finite, requires = "prestress")]
    pub load_scale: f64,
    /// Keep the ground supports in the body.
    #[arg(long)]
    pub keep_supports: bool,
    /// Write the reduced body here: .json (the document) or .npz (its arrays, for numpy).
    #[arg(long, value_name = "FILE.json|FILE.npz")]
    pub out: Option<PathBuf>,
}

fn interface(text: &str) -> Result<Vec<(String, f64)>> {
    text.split(',')
        .map(|item| {
            let (beam, s) = item.rsplit_once(':').ok_or_else(|| {
                anyhow!("--interface `{item}`: expected BEAM:S (a beam id and an arc length in m)")
            })?;
            let s: f64 = s.trim().parse().map_err(|_| {
                anyhow!("--interface `{item}`: `{s}` is not a number (arc length in m)")
            })?;
            Ok((beam.trim().to_string(), s))
        })
        .collect()
}

pub fn run(args: ReduceArgs) -> Result<Warnings> {
    let request = ReduceRequest {
        interface: interface(&args.interface)?,
        modes: args.modes,
        method: match args.method {
            Method::CraigBampton => ReductionMethod::CraigBampton,
            Method::FreeInterface => ReductionMethod::FreeInterface,
        },
        prestress: args.prestress,
        load_scale: args.load_scale,
        keep_supports: args.keep_supports,
    };
    if let Some(out) = &args.out {
        if !matches!(
            out.extension().and_then(|e| e.to_str()),
            Some("json" | "npz")
        ) {
            return Err(anyhow!(
                "--out `{}`: must end in .json or .npz",
                out.display()
            ));
        }
    }
    let input = ModelInput::load(args.model.as_deref())?;
    let run = reduce(&input, &request)?;
    if let Some(out) = &args.out {
        run.write(out)?;
    }
    out!("{}", run.text());
    Ok(run.document.warnings)
}
