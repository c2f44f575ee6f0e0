//! Calibration results as a table, a JSON document and a figure.
//!
//! Units: parameters in SI (their unit is printed beside them), frequencies
//! in Hz, sensitivities ∂f/∂ln p in Hz per unit relative change.

use crate::analysis::calibrate::{Algorithm, CalibrationResult, FittedParameter};
use crate::output::plot::Calibration;
use crate::output::plot::Scale;
use std::fmt::Write;

fn algorithm_name(a: Algorithm) -> &'static str {
    match a {
        Algorithm::Brent => "Brent root bracketing",
        Algorithm::LevenbergMarquardt => "Levenberg-Marquardt",
    }
}

fn parameter_row(s: &mut String, p: &FittedParameter, bounds: bool) {
    let range = if bounds {
        format!("[{:.4e}, {:.4e}]", p.lower, p.upper)
    } else {
        String::from("(follows the section: beam mass kept)")
    };
    let _ = writeln!(
        s,
        "  {:<24} {:>13.6e} {:>15.9e} {:>10}  {:<8} {range}",
        p.name,
        p.initial,
        p.fitted,
        p.change_percent
            .map_or_else(|| String::from("—"), |c| format!("{c:+.4}")),
        p.unit
    );
}

/// Readable report: parameters, targets vs achieved, sensitivities,
/// conditioning and the iteration history.
pub fn calibrate_table(model_name: &str, r: &CalibrationResult) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {model_name}: calibration by {} on the {} frequencies {}{}",
        algorithm_name(r.algorithm),
        r.method,
        if r.prestressed {
            "at the static equilibrium (pre-stressed)"
        } else {
            "at the reference (unstressed)"
        },
        if r.keep_mass { " (beam mass kept)" } else { "" }
    );
    let _ = writeln!(
        s,
        "  {:<24} {:>13} {:>15} {:>10}  {:<8} bounds",
        "parameter", "initial", "fitted", "change %", "unit"
    );
    for p in &r.parameters {
        parameter_row(&mut s, p, true);
    }
    for p in &r.derived {
        parameter_row(&mut s, p, false);
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "  {:<12} {:>14} {:>14} {:>16} {:>13}",
        "mode", "target [Hz]", "initial [Hz]", "achieved [Hz]", "error [Hz]"
    );
    for (i, t) in r.targets_hz.iter().enumerate() {
        let _ = writeln!(
            s,
            "  {:<12} {:>14.3} {:>14.3} {:>16.6} {:>13.3e}",
            format!("{} {}", r.mode_kind, r.mode_numbers[i]),
            t,
            r.initial_hz[i],
            r.achieved_hz[i],
            r.residuals_hz[i]
        );
    }
    if r.least_squares {
        let _ = writeln!(
            s,
            "  more targets than parameters: the fit minimizes the sum of squared relative errors"
        );
    }
    if let Some(sens) = &r.sensitivities_hz {
        let _ = writeln!(s);
        let _ = writeln!(s, "  sensitivities at the fit, ∂f/∂ln p [Hz]:");
        for (i, row) in sens.iter().enumerate() {
            let cols: Vec<String> = r
                .parameters
                .iter()
                .zip(row)
                .map(|(p, d)| format!("{}: {:.4e}", p.name, d))
                .collect();
            let _ = writeln!(
                s,
                "    {} {}: {}",
                r.mode_kind,
                r.mode_numbers[i],
                cols.join(", ")
            );
        }
    }
    if let Some(c) = &r.conditioning {
        let sv: Vec<String> = c
            .singular_values
            .iter()
            .map(|v| format!("{v:.4e}"))
            .collect();
        let _ = writeln!(
            s,
            "  singular values of ∂ln f/∂ln p: {}; condition number {:.4e}",
            sv.join(", "),
            c.condition_number
        );
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "  {} iterations, {} evaluations:",
        r.iterations, r.evaluations
    );
    let mut head = format!("  {:>4} ", "#");
    for p in &r.parameters {
        let _ = write!(head, " {:>18}", p.name);
    }
    for (kind_no, _) in r.mode_numbers.iter().zip(&r.targets_hz) {
        let _ = write!(
            head,
            " {:>18}",
            format!("f {} {} [Hz]", r.mode_kind, kind_no)
        );
    }
    let _ = writeln!(s, "{head}");
    for (k, h) in r.history.iter().enumerate() {
        let mut line = format!("  {:>4}{}", k + 1, if h.accepted { " " } else { "x" });
        for v in &h.parameters {
            let _ = write!(line, " {v:>18.10e}");
        }
        for f in &h.frequencies_hz {
            let _ = write!(line, " {f:>18.6}");
        }
        let _ = writeln!(s, "{line}");
    }
    if r.history.iter().any(|h| !h.accepted) {
        let _ = writeln!(s, "  (x: trial step rejected)");
    }
    s
}

/// How a parameter of this SI unit is shown on an axis.
fn parameter_scale(unit: &str, value: f64) -> (Scale, bool) {
    match unit {
        "m" => (Scale::mm(), false),
        "Pa" => (Scale::new(1e-9, "GPa"), false),
        "kg" => (Scale::new(1e3, "g"), false),
        "N/m" | "N m/rad" => (Scale::unit(unit), true),
        _ => (Scale::si(unit, value), false),
    }
}

/// The calibration figure's data for the first parameter and first target:
/// the model sweep (`sweep` = parameter values and frequencies), the target,
/// the path of the evaluations and the fit.
pub fn calibration_plot(
    model_name: &str,
    r: &CalibrationResult,
    sweep: (Vec<f64>, Vec<f64>),
) -> Calibration {
    let p = &r.parameters[0];
    let (scale, log) = parameter_scale(p.unit, p.fitted);
    let target = r.targets_hz[0];
    Calibration {
        title: format!(
            "{model_name}: {} fitted to {} {} = {} Hz",
            p.name, r.mode_kind, r.mode_numbers[0], target
        ),
        parameter_label: p.name.clone(),
        parameter_scale: scale,
        parameter_log: log,
        frequency_scale: Scale::hz(),
        sweep_parameter: sweep.0,
        sweep_frequency: sweep.1,
        target_hz: target,
        target_label: format!("target {target} Hz"),
        iterations: r
            .history
            .iter()
            .map(|h| (h.parameters[0], h.frequencies_hz[0]))
            .collect(),
        fitted: Some((p.fitted, r.achieved_hz[0])),
    }
}
