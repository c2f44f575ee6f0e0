//! `ancf-modal modal`: frequencies and mode shapes.

use super::args::ModalArgs;
use super::common::{load_model, print_json, source_label, write_output};
use ancf_modal::analysis::{modal_at_reference, ModalResult, ModalSettings, Mode};
use ancf_modal::measured::uff::d55::read_modes;
use ancf_modal::model::Model;
use ancf_modal::output::modal_report::{modal_csv, modal_table};
use ancf_modal::output::modal_uff::{export_nodes, modal_uff, translations};
use ancf_modal::results::modal::MacTable;
use ancf_modal::signal::mac::mac;
use ancf_modal::System;
use anyhow::{Context, Result};
use std::path::Path;

pub fn run(args: ModalArgs) -> Result<()> {
    if let Some(range) = args.sweep_load {
        return super::sweep::run_load_sweep(&args, range);
    }
    if let Some(path) = &args.mac_plot {
        ancf_modal::output::plot::Format::from_path(path)?;
    }
    let model = load_model(args.model.as_deref())?;
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(args.modes as usize),
        method: args.solver.into(),
    };
    if args.prestress {
        return super::statics::run_prestress(&args, &model, &system, &settings);
    }
    let (result, mut output) = ancf_modal::results::modal::modal(&model, &system, &settings)
        .with_context(|| source_label(args.model.as_deref()))?;
    for w in ancf_modal::results::modal::reference_warnings(&result) {
        super::common::warn(format!("{}: {w}", source_label(args.model.as_deref())));
    }
    warn_beam_theory(&result, args.model.as_deref());
    let mac = match &args.mac {
        Some(other) => Some(mac_against(&system, &result, other, &settings)?),
        None => None,
    };
    if let Some(path) = &args.output.csv {
        write_output(path, &modal_csv(&result))?;
    }
    if let Some(path) = &args.output.uff {
        let provenance = ancf_modal::results::provenance::header_lines(
            &super::common::model_sha256(args.model.as_deref())?,
        );
        write_output(path, &modal_uff(&system, &result, &provenance))?;
    }
    if let Some(path) = &args.output.plot {
        ancf_modal::output::figures::write_mode_shapes(&system, &system.q0, &result, path)?;
    }
    if let (Some(path), Some((_, _, m))) = (&args.mac_plot, &mac) {
        let other = args
            .mac
            .as_deref()
            .and_then(|p| p.file_name())
            .map_or(String::new(), |p| p.to_string_lossy().into_owned());
        let title = format!("MAC: {} vs {other}", model.name);
        ancf_modal::output::figures::write_figure(
            &ancf_modal::output::figures::mac_figure(&title, m),
            path,
            ancf_modal::output::plot::PlotSize::default(),
        )?;
    }
    let complex = output.complex_modes;
    if args.output.json {
        output.mac = mac.as_ref().map(|(rows, cols, m)| MacTable {
            rows_hz: rows.clone(),
            columns_hz: cols.clone(),
            matrix: m
                .row_iter()
                .map(|r| r.iter().copied().collect::<Vec<f64>>())
                .collect(),
        });
        print_json(&output, args.model.as_deref())?;
    } else {
        out!("{}", modal_table(&model, &result));
        if ancf_modal::analysis::shear::poisson_assumed(&model) {
            outln!(
                "shear %: Timoshenko against Euler–Bernoulli, estimated from each bending mode's shape, with ν = {} where the material gives no `poisson`",
                ancf_modal::analysis::shear::DEFAULT_POISSON
            );
        }
        let lines: Vec<String> = output
            .modes
            .iter()
            .filter_map(|m| {
                let z = format!("mode {}: {:.4} %", m.mode.index, 100.0 * m.damping_ratio?);
                Some(match (complex, m.damped_frequency_hz) {
                    (false, _) => z,
                    (true, Some(f)) => format!("{z}, f_d {f:.2} Hz"),
                    (true, None) => format!("{z}, overdamped"),
                })
            })
            .collect();
        match model.damping {
            _ if complex => outln!(
                "Complex modes (dampers{}; in the basis of the computed modes): {}",
                if model.damping.is_some() {
                    " and Rayleigh damping"
                } else {
                    ""
                },
                lines.join(", ")
            ),
            Some(d) => outln!(
                "Rayleigh damping (α = {} 1/s, β = {:e} s), ζ = α/(2ω) + βω/2: {}",
                d.alpha,
                d.beta,
                lines.join(", ")
            ),
            None => {}
        }
        if let Some((rows, cols, m)) = &mac {
            out!("{}", mac_table(rows, cols, m));
        }
    }
    Ok(())
}

type Mac = (Vec<f64>, Vec<f64>, nalgebra::DMatrix<f64>);

fn elastic(r: &ModalResult) -> Vec<&Mode> {
    r.modes.iter().filter(|m| !m.kind.is_zero()).collect()
}

/// The MAC of this model's elastic modes (rows) against `other`'s
/// (columns), on the translations at the export nodes.
fn mac_against(
    system: &System,
    result: &ModalResult,
    other: &Path,
    settings: &ModalSettings,
) -> Result<Mac> {
    let nodes = export_nodes(system);
    let mine: Vec<Vec<f64>> = elastic(result)
        .iter()
        .map(|m| translations(&nodes, &m.shape))
        .collect();
    let rows: Vec<f64> = elastic(result).iter().map(|m| m.frequency_hz).collect();
    let is_json = other
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let (cols, theirs): (Vec<f64>, Vec<Vec<f64>>) = if is_json {
        let model = Model::from_file(other)?;
        let sys = System::new(&model);
        let r = modal_at_reference(&sys, settings).with_context(|| other.display().to_string())?;
        let their_nodes = export_nodes(&sys);
        if their_nodes.len() != nodes.len() {
            anyhow::bail!(
                "{}: {} export nodes, this model has {}: the MAC needs the same nodes",
                other.display(),
                their_nodes.len(),
                nodes.len()
            );
        }
        let e = elastic(&r);
        (
            e.iter().map(|m| m.frequency_hz).collect(),
            e.iter()
                .map(|m| translations(&their_nodes, &m.shape))
                .collect(),
        )
    } else {
        // Bytes, decoded leniently: a file may also hold binary 58b records.
        let bytes = std::fs::read(other)
            .with_context(|| format!("{}: cannot read the file", other.display()))?;
        let text = String::from_utf8_lossy(&bytes);
        let (_, modes) = read_modes(other, &text)?;
        if modes.is_empty() {
            anyhow::bail!(
                "{}: no UFF dataset 55 (normal modes) in the file",
                other.display()
            );
        }
        let mut shapes = Vec::new();
        for m in &modes {
            let mut v = Vec::with_capacity(2 * nodes.len());
            for n in &nodes {
                let (_, t) = m.nodes.iter().find(|(l, _)| *l == n.label).ok_or_else(|| {
                    anyhow::anyhow!(
                        "{}: mode {} has no node {} ({})",
                        other.display(),
                        m.mode_number,
                        n.label,
                        n.name
                    )
                })?;
                v.extend([t[0], t[1]]);
            }
            shapes.push(v);
        }
        (modes.iter().map(|m| m.frequency_hz).collect(), shapes)
    };
    Ok((rows, cols, mac(&mine, &theirs)))
}

fn mac_table(rows: &[f64], cols: &[f64], m: &nalgebra::DMatrix<f64>) -> String {
    use std::fmt::Write;
    let mut s = String::from("MAC (rows: this model, columns: the other set) [Hz]\n");
    let _ = write!(s, "{:>10}", "");
    for c in cols {
        let _ = write!(s, " {c:>9.1}");
    }
    s.push('\n');
    for (i, r) in rows.iter().enumerate() {
        let _ = write!(s, "{r:>10.1}");
        for j in 0..cols.len() {
            let _ = write!(s, " {:>9.3}", m[(i, j)]);
        }
        s.push('\n');
    }
    s
}

/// A warning for each reported mode whose Euler–Bernoulli frequency is
/// more than 1 % above Timoshenko theory's (estimate of
/// [`ancf_modal::analysis::shear`]).
fn warn_beam_theory(result: &ModalResult, path: Option<&Path>) {
    for w in ancf_modal::analysis::shear::beam_theory_warnings(result) {
        super::common::warn(format!("{}: {w}", source_label(path)));
    }
}
