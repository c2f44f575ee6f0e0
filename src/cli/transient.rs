//! `ancf-modal transient`: the general time integration of a model, with
//! its sensors, contact statistics and energy balance.

use super::common::{load_model, print_json, source_label, write_output};
use ancf_modal::analysis::simulate::{simulate, SimulationSettings};
use ancf_modal::analysis::transient::TransientSettings;
use ancf_modal::output::figures::write_figure;
use ancf_modal::output::plot::{Format, PlotSize};
use ancf_modal::output::transient_report::{
    transient_csv, transient_figure, transient_table, transient_uff,
};
use ancf_modal::System;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct TransientArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// End time [s].
    #[arg(long, value_name = "S", default_value_t = 0.01, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub end_time: f64,
    /// Time step [s] (shortened automatically at contact onsets).
    #[arg(long, value_name = "S", default_value_t = 1e-6, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub step: f64,
    /// Spectral radius at infinity of generalized-α (1 = no numerical damping).
    #[arg(long, value_name = "R", default_value_t = 0.9, allow_hyphen_values = true, value_parser = super::values::unit_interval)]
    pub spectral_radius: f64,
    /// Start from the static equilibrium under the loads at t = 0 (else at
    /// rest in the reference configuration).
    #[arg(long)]
    pub from_equilibrium: bool,
    /// Output sample rate [Hz]; 0 keeps every step.
    #[arg(long, value_name = "HZ", default_value_t = 51_200.0, allow_hyphen_values = true, value_parser = super::values::non_negative)]
    pub sample_rate: f64,
    /// Model every beam as a rigid body.
    #[arg(long)]
    pub rigid_beams: bool,
}

pub fn run(args: TransientArgs) -> Result<()> {
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    if args.output.uff.is_some() && args.sample_rate <= 0.0 {
        anyhow::bail!(
            "--uff needs --sample-rate above 0 (UFF 58 time data are evenly sampled), got {}",
            args.sample_rate
        );
    }
    let mut model = load_model(args.model.as_deref())?;
    if args.rigid_beams {
        model = model
            .all_beams_rigid()
            .validated()
            .context("the model with every beam rigid")?;
    }
    let settings = SimulationSettings {
        transient: TransientSettings {
            step: args.step,
            end_time: args.end_time,
            spectral_radius: args.spectral_radius,
            damping: model.damping,
            ..TransientSettings::default()
        },
        from_equilibrium: args.from_equilibrium,
        sample_rate: args.sample_rate,
        keep_partial: false,
    };
    settings.transient.validate()?;
    let system = System::new(&model);
    let sim = simulate(system, &[], &settings)
        .map_err(|e| match e {
            ancf_modal::error::SimulationError::ReleaseNeedsEquilibrium { .. } => {
                anyhow::anyhow!("{e} (--from-equilibrium)")
            }
            e => super::common::simulation_error(e),
        })
        .with_context(|| source_label(args.model.as_deref()))?;
    if let Some(path) = &args.output.csv {
        write_output(path, &transient_csv(&sim))?;
    }
    if let Some(path) = &args.output.uff {
        let provenance = ancf_modal::results::provenance::header_lines(
            &super::common::model_sha256(args.model.as_deref())?,
        );
        write_output(path, &transient_uff(&sim, &provenance))?;
    }
    if let Some(path) = &args.output.plot {
        write_figure(
            &transient_figure(&model.name, &sim).into(),
            path,
            PlotSize::default(),
        )?;
    }
    if args.output.json {
        print_json(
            ancf_modal::results::TransientOutput::new(&model.name, &settings, &sim),
            args.model.as_deref(),
        )?;
    } else {
        out!("{}", transient_table(&model.name, &settings, &sim));
    }
    Ok(())
}
