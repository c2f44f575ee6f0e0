//! A sweep document ([`crate::analysis::sweep::SweepDocument`]) as a table
//! and as CSV.

use crate::analysis::sweep::{Quantity, SweepDocument};
use std::fmt::Write;

/// Readable table: one row per point, parameter values, the quantity or
/// the point's error.
pub fn sweep_table(d: &SweepDocument) -> String {
    let mut s = String::new();
    let axes: Vec<String> = d
        .parameters
        .iter()
        .map(|p| format!("{} ({} values)", p.name, p.values.len()))
        .collect();
    let _ = write!(
        s,
        "sweep of {}: {} over {}; {} points",
        d.model,
        d.quantity,
        axes.join(" × "),
        d.total_points
    );
    if let Some(sh) = d.shard {
        let _ = write!(
            s,
            ", shard {}/{} has {} of them",
            sh.index,
            sh.count,
            d.points.len()
        );
    }
    // Where each point starts: the modal quantities linearize, the
    // switch-off always starts from its ON-state equilibrium, a sensor peak
    // from the equilibrium with --prestress.
    let start = match Quantity::parse(&d.quantity) {
        Ok(Quantity::TimeToDistance) => "from the static equilibrium (ON state)",
        Ok(Quantity::Peak { .. }) if d.prestress => "from the static equilibrium",
        Ok(Quantity::Peak { .. }) => "from the reference at rest",
        _ if d.prestress => "linearized at the static equilibrium",
        _ => "linearized at the reference",
    };
    let _ = writeln!(s, "; {start}; sweep_id {}", d.sweep_id);
    let mut header = format!("{:>7}", "point");
    for p in &d.parameters {
        let _ = write!(header, "  {:>16}", truncate(&p.name, 16));
    }
    let _ = write!(header, "  {:>16}", truncate(&d.quantity, 16));
    let _ = writeln!(s, "{header}");
    for r in &d.points {
        let _ = write!(s, "{:>7}", r.index);
        for v in &r.values {
            let _ = write!(s, "  {v:>16.6e}");
        }
        match (&r.error, r.result) {
            (Some(e), _) => {
                let _ = write!(s, "  failed: {e}");
            }
            (None, Some(v)) => {
                let _ = write!(s, "  {v:>16.6}");
            }
            (None, None) if d.shard.is_some() => {
                let _ = write!(s, "  {:>16}", "(sweep-merge)");
            }
            (None, None) => {
                let _ = write!(s, "  {:>16}", "-");
            }
        }
        let _ = writeln!(s);
    }
    if d.failed_points > 0 {
        let _ = writeln!(s, "{} of {} points failed", d.failed_points, d.points.len());
    }
    if d.shard.is_some() && d.tracked_modes.is_some() {
        let _ = writeln!(
            s,
            "tracked frequencies need all points: join the shards with `ancf-modal sweep-merge`"
        );
    }
    s
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let head: String = s.chars().take(n - 1).collect();
        format!("{head}…")
    }
}

/// CSV: `index`, the parameters, the quantity, the tracked modes'
/// frequencies `mode_1_hz`… (tracked quantities), `error`.
pub fn sweep_csv(d: &SweepDocument) -> String {
    let mut s = String::from("index");
    for p in &d.parameters {
        s.push(',');
        s.push_str(&field(&p.name));
    }
    s.push(',');
    s.push_str(&field(&d.quantity));
    let tracked = if d.shard.is_none() {
        d.tracked_modes.unwrap_or(0)
    } else {
        0
    };
    for j in 1..=tracked {
        let _ = write!(s, ",mode_{j}_hz");
    }
    s.push_str(",error\n");
    let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:e}"));
    for r in &d.points {
        let _ = write!(s, "{}", r.index);
        for v in &r.values {
            let _ = write!(s, ",{v:e}");
        }
        let _ = write!(s, ",{}", num(r.result));
        for j in 0..tracked {
            let f = r
                .frequencies_hz
                .as_ref()
                .and_then(|f| f.get(j).copied().flatten());
            let _ = write!(s, ",{}", num(f));
        }
        let _ = writeln!(s, ",{}", field(r.error.as_deref().unwrap_or("")));
    }
    s
}

/// A CSV field, quoted when it holds a comma, quote or line break.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::sweep::{ParameterValues, PointRecord};

    #[test]
    fn csv_quotes_names_with_commas_and_leaves_failed_results_empty() {
        let point = |index: usize, result: Option<f64>, error: Option<&str>| PointRecord {
            index,
            values: vec![index as f64],
            result,
            error: error.map(String::from),
            frequencies_hz: None,
            mac: None,
            modes: None,
            node0: None,
            warnings: Vec::new(),
        };
        let d = SweepDocument {
            model: "m".into(),
            quantity: "first_bending_hz".into(),
            sweep_id: "0".into(),
            total_points: 2,
            parameters: vec![ParameterValues {
                name: "load_scale:a,b".into(),
                target: "load_scale:loads[0],loads[1]".into(),
                values: vec![0.0, 1.0],
                log: false,
            }],
            prestress: true,
            tracked_modes: None,
            failed_points: 1,
            shard: None,
            tool_version: None,
            model_sha256: None,
            warnings: Vec::new(),
            points: vec![
                point(0, Some(4600.0), None),
                point(1, None, Some("x, \"y\"")),
            ],
        };
        assert_eq!(
            sweep_csv(&d),
            "index,\"load_scale:a,b\",first_bending_hz,error\n0,0e0,4.6e3,\n1,1e0,,\"x, \"\"y\"\"\"\n"
        );
        assert!(sweep_table(&d).contains("1 of 2 points failed"));
    }
}
