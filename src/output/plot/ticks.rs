//! Tick positions and tick labels.
//!
//! Plotters is given the ticks explicitly (`with_key_points`), so both axis
//! kinds use one coordinate type: a linear axis in display units, or a log
//! axis as log10 of the display value. Labels are made here, together with
//! the positions, so their number of decimals always fits the tick step.

/// Ticks of one axis, in coordinate space (display units, or their log10).
#[derive(Debug, Clone, Default)]
pub(super) struct AxisTicks {
    pub major: Vec<f64>,
    pub minor: Vec<f64>,
    labels: Vec<(f64, String)>,
}

impl AxisTicks {
    /// The label of the major tick nearest to `coord`.
    pub fn label(&self, coord: f64) -> String {
        self.labels
            .iter()
            .min_by(|a, b| (a.0 - coord).abs().total_cmp(&(b.0 - coord).abs()))
            .map(|l| l.1.clone())
            .unwrap_or_default()
    }

    /// All major-tick labels (to size the label area).
    pub fn labels(&self) -> impl Iterator<Item = &str> {
        self.labels.iter().map(|l| l.1.as_str())
    }
}

/// A "nice" step (1, 2, 2.5 or 5 × 10ᵏ) close to `raw`.
pub(super) fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    let m = raw / mag;
    let nice = if m < 1.5 {
        1.0
    } else if m < 2.25 {
        2.0
    } else if m < 3.5 {
        2.5
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// Linear ticks over `[lo, hi]` with about `target` major ticks.
/// At least three are made whatever the target.
pub(super) fn linear(lo: f64, hi: f64, target: usize) -> AxisTicks {
    let mut target = target.max(2);
    loop {
        let t = linear_with_step(lo, hi, nice_step((hi - lo) / target as f64));
        if t.major.len() >= 3 || target > 64 {
            return t;
        }
        target *= 2;
    }
}

/// Linear ticks over `[lo, hi]` at multiples of `step`.
pub(super) fn linear_with_step(lo: f64, hi: f64, step: f64) -> AxisTicks {
    let eps = step * 1e-9;
    let first = ((lo - eps) / step).ceil() as i64;
    let last = ((hi + eps) / step).floor() as i64;
    let major: Vec<f64> = (first..=last).map(|k| k as f64 * step).collect();
    let mantissa = step / 10f64.powf(step.log10().floor());
    let sub = if (mantissa - 2.0).abs() < 1e-6 { 4 } else { 5 };
    let minor_step = step / sub as f64;
    let first_minor = ((lo - eps) / minor_step).ceil() as i64;
    let last_minor = ((hi + eps) / minor_step).floor() as i64;
    let minor = (first_minor..=last_minor)
        .filter(|k| k % sub != 0)
        .map(|k| k as f64 * minor_step)
        .collect();

    let max_abs = major.iter().fold(0f64, |m, v| m.max(v.abs()));
    let labels = if max_abs >= 1e5 || step < 1e-4 {
        let sig = ((max_abs / step).log10().floor() as usize + 2).clamp(1, 8);
        major.iter().map(|&v| (v, pretty_sci(v, sig))).collect()
    } else {
        let d = decimals(step);
        major
            .iter()
            .map(|&v| (v, minus(format!("{:.*}", d, v))))
            .collect()
    };
    AxisTicks {
        major,
        minor,
        labels,
    }
}

/// Log ticks for display values in `[lo, hi]` (both > 0); positions are
/// log10 of the values.
pub(super) fn log(lo: f64, hi: f64) -> AxisTicks {
    let (e_lo, e_hi) = (lo.log10(), hi.log10());
    let inside = |v: f64| {
        let e = v.log10();
        e >= e_lo - 1e-9 && e <= e_hi + 1e-9
    };
    let (d0, d1) = (e_lo.floor() as i32, e_hi.ceil() as i32);
    let values = |mantissas: &[u32]| -> Vec<(u32, i32)> {
        (d0..=d1)
            .flat_map(|d| mantissas.iter().map(move |&m| (m, d)))
            .filter(|&(m, d)| inside(m as f64 * 10f64.powi(d)))
            .collect()
    };
    let all = values(&[1, 2, 3, 4, 5, 6, 7, 8, 9]);
    let decades = values(&[1]);
    // Decades alone when there are many; else 1-2-5 steps, unless those
    // are too many; 1…9 steps for narrow ranges.
    let coarse = values(&[1, 2, 5]);
    let majors: Vec<(u32, i32)> = if decades.len() >= 4 || (decades.len() >= 2 && coarse.len() > 10)
    {
        let every = decades.len().div_ceil(8);
        decades
            .iter()
            .copied()
            .filter(|&(_, d)| (d - d0).rem_euclid(every as i32) == 0)
            .collect()
    } else if coarse.len() >= 3 {
        coarse
    } else {
        all.clone()
    };
    if majors.len() < 2 {
        // Less than a factor of ~2: linear ticks placed on the log axis.
        let lin = linear(lo, hi, 4);
        return AxisTicks {
            major: lin.major.iter().map(|v| v.log10()).collect(),
            minor: lin.minor.iter().map(|v| v.log10()).collect(),
            labels: lin
                .labels
                .iter()
                .map(|(v, l)| (v.log10(), l.clone()))
                .collect(),
        };
    }
    let pos = |(m, d): (u32, i32)| (m as f64).log10() + d as f64;
    // One notation per axis: powers of ten as soon as one label needs it.
    let powers = majors.iter().any(|&(_, d)| !(-3..=4).contains(&d));
    AxisTicks {
        major: majors.iter().map(|&md| pos(md)).collect(),
        minor: all
            .iter()
            .filter(|md| !majors.contains(md))
            .map(|&md| pos(md))
            .collect(),
        labels: majors
            .iter()
            .map(|&md| (pos(md), log_label(md, powers)))
            .collect(),
    }
}

/// `m × 10ᵈ` written plainly, or with a power of ten.
fn log_label((m, d): (u32, i32), powers: bool) -> String {
    if !powers {
        let v = m as f64 * 10f64.powi(d);
        format!("{:.*}", (-d).max(0) as usize, v)
    } else if m == 1 {
        format!("10{}", superscript(d))
    } else {
        format!("{m}×10{}", superscript(d))
    }
}

/// The fewest decimals that write `step` (and its multiples) exactly.
fn decimals(step: f64) -> usize {
    (0..12)
        .find(|&d| {
            let s = step * 10f64.powi(d as i32);
            (s - s.round()).abs() < 1e-6 * s.abs().max(1.0)
        })
        .unwrap_or(12)
}

/// Unicode minus for negative numbers; never "-0".
fn minus(s: String) -> String {
    let negative_zero = s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.');
    if negative_zero {
        s[1..].to_string()
    } else if let Some(rest) = s.strip_prefix('-') {
        format!("\u{2212}{rest}")
    } else {
        s
    }
}

/// `v` as `m×10ⁿ` with `sig` significant digits (`10ⁿ` when m is 1).
pub(super) fn pretty_sci(v: f64, sig: usize) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let s = format!("{:.*e}", sig.saturating_sub(1), v);
    let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let mantissa = trim_zeros(mantissa.to_string());
    let power = format!("10{}", superscript(exp));
    match mantissa.as_str() {
        "1" => power,
        "-1" => format!("\u{2212}{power}"),
        _ => format!("{}×{power}", minus(mantissa)),
    }
}

/// Removes trailing zeros after a decimal point (and the point itself).
pub(super) fn trim_zeros(s: String) -> String {
    if s.contains('.') {
        minus(s.trim_end_matches('0').trim_end_matches('.').to_string())
    } else {
        minus(s)
    }
}

/// An integer in superscript digits: 4 → "⁴", -6 → "⁻⁶".
pub fn superscript(n: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s: String = n
        .unsigned_abs()
        .to_string()
        .chars()
        .map(|c| DIGITS[c.to_digit(10).unwrap_or(0) as usize])
        .collect();
    if n < 0 {
        s.insert(0, '⁻');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_nice_and_well_labelled() {
        let t = linear(0.0, 10.0, 5);
        assert_eq!(t.major, vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        assert_eq!(t.label(4.0), "4");
        let t = linear(-0.3, 0.3, 6);
        assert_eq!(t.label(-0.2), "\u{2212}0.2");
        assert_eq!(t.label(0.0), "0.0");
        let t = linear(0.0, 1.0, 4);
        assert_eq!(t.label(0.25), "0.25");
    }

    #[test]
    fn log_ticks_use_decades() {
        let t = log(2.0, 5000.0);
        let labels: Vec<_> = t.labels().collect();
        assert_eq!(labels, ["10", "100", "1000"]);
        let t = log(1e-9, 1e-2);
        let labels: Vec<_> = t.labels().collect();
        assert!(labels.contains(&"10⁻⁶"), "{labels:?}");
        assert!(labels.contains(&"10⁻²"), "{labels:?}");
        let labels: Vec<_> = log(1.0, 100.0).labels().map(String::from).collect();
        assert_eq!(labels, ["1", "2", "5", "10", "20", "50", "100"]);
        let t = log(3000.0, 5000.0);
        assert!(t.major.len() >= 2);
    }

    #[test]
    fn number_formats() {
        assert_eq!(superscript(-12), "⁻¹²");
        assert_eq!(pretty_sci(2.5e-7, 3), "2.5×10⁻⁷");
        assert_eq!(pretty_sci(1e8, 2), "10⁸");
        assert_eq!(trim_zeros("4577.300".into()), "4577.3");
    }
}
