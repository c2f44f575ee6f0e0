//! The points of a sweep: one axis per parameter (`LO:HI:N`, linear,
//! `LO:HI:N:log`, geometric, or the values listed, `V1,V2,…`), their full grid in row-major order of the
//! parameters (the first parameter varies slowest), and shards of it.
//!
//! A point's index `i` and its grid coordinates `(i₁, …, i_d)` are related
//! by `i = ((i₁ n₂ + i₂) n₃ + i₃) …`. Shard `K/N` (1-based) holds the points
//! with `i ≡ K − 1 (mod N)`, so N shards cover the grid exactly once and
//! each gets an even share of every region of it.

use super::error::SweepError;

/// Most values on one axis.
pub const MAX_AXIS_VALUES: usize = 1_000_000;
/// Most points of a grid.
pub const MAX_POINTS: usize = 10_000_000;

/// The values of one parameter: a range, or the values listed.
#[derive(Debug, Clone, PartialEq)]
pub enum Axis {
    /// `LO:HI:N[:log]`: N values from LO to HI.
    Range {
        lo: f64,
        hi: f64,
        count: usize,
        /// Geometric spacing (equal ratios) instead of equal steps.
        log: bool,
    },
    /// `V1,V2,…`: these values, in this order.
    List(Vec<f64>),
}

impl Axis {
    /// Parses `LO:HI:N`, `LO:HI:N:log` or `V1,V2,…` (one value alone is
    /// a list of one); `given` names the whole flag value in errors.
    pub fn parse(text: &str, given: &str) -> Result<Axis, SweepError> {
        let number = |what: &'static str, t: &str| {
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| SweepError::NotANumber {
                    given: given.to_string(),
                    what,
                    text: t.to_string(),
                })
        };
        if !text.contains(':') {
            let values = text
                .split(',')
                .map(|t| number("a value", t.trim()))
                .collect::<Result<Vec<f64>, _>>()?;
            if values.len() > MAX_AXIS_VALUES {
                return Err(SweepError::BadCount {
                    given: given.to_string(),
                    text: values.len().to_string(),
                    max: MAX_AXIS_VALUES,
                });
            }
            return Ok(Axis::List(values));
        }
        let parts: Vec<&str> = text.split(':').map(str::trim).collect();
        let (lo, hi, n, spacing) = match parts[..] {
            [lo, hi, n] => (lo, hi, n, None),
            [lo, hi, n, s] => (lo, hi, n, Some(s)),
            _ => {
                return Err(SweepError::ParamSyntax {
                    given: given.to_string(),
                })
            }
        };
        let (lo, hi) = (number("LO", lo)?, number("HI", hi)?);
        let count = n
            .parse::<usize>()
            .ok()
            .filter(|c| (1..=MAX_AXIS_VALUES).contains(c))
            .ok_or_else(|| SweepError::BadCount {
                given: given.to_string(),
                text: n.to_string(),
                max: MAX_AXIS_VALUES,
            })?;
        let log = match spacing {
            None => false,
            Some(s) if s.eq_ignore_ascii_case("log") => true,
            Some(s) => {
                return Err(SweepError::BadSpacing {
                    given: given.to_string(),
                    text: s.to_string(),
                })
            }
        };
        if log && !(lo > 0.0 && hi > 0.0) {
            return Err(SweepError::LogNotPositive {
                given: given.to_string(),
                lo,
                hi,
            });
        }
        Ok(Axis::Range { lo, hi, count, log })
    }

    /// Whether the values are spaced geometrically.
    pub fn is_log(&self) -> bool {
        matches!(self, Axis::Range { log: true, .. })
    }

    /// The first value.
    pub fn first(&self) -> f64 {
        match self {
            Axis::Range { lo, .. } => *lo,
            Axis::List(v) => v.first().copied().unwrap_or(f64::NAN),
        }
    }

    /// The values: a range's LO first and HI last exactly (one value: LO);
    /// a list's as given.
    pub fn values(&self) -> Vec<f64> {
        let (lo, hi, n, log) = match self {
            Axis::List(v) => return v.clone(),
            Axis::Range { lo, hi, count, log } => (*lo, *hi, *count, *log),
        };
        (0..n)
            .map(|i| {
                if i == 0 {
                    return lo;
                }
                if i + 1 == n {
                    return hi;
                }
                let (a, b, m) = ((n - 1 - i) as f64, i as f64, (n - 1) as f64);
                let v = if log {
                    ((a * lo.ln() + b * hi.ln()) / m).exp()
                } else {
                    (a * lo + b * hi) / m
                };
                // 15 significant digits, so that a decimal range stays
                // decimal (1e-3:1.2e-3:3 gives 1.1e-3, not
                // 1.0999999999999998e-3); a change of at most 5e-16.
                format!("{v:.14e}").parse().unwrap_or(v)
            })
            .collect()
    }
}

impl std::fmt::Display for Axis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Axis::Range { lo, hi, count, log } => {
                write!(f, "{lo:?}:{hi:?}:{count}")?;
                if *log {
                    f.write_str(":log")?;
                }
                Ok(())
            }
            Axis::List(values) => {
                let text: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
                f.write_str(&text.join(","))
            }
        }
    }
}

/// The full grid of several axes, row-major.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The values of each axis.
    pub axes: Vec<Vec<f64>>,
}

impl Grid {
    pub fn new(axes: Vec<Vec<f64>>) -> Result<Grid, SweepError> {
        let total = axes.iter().map(|a| a.len() as u128).product::<u128>();
        if total > MAX_POINTS as u128 {
            return Err(SweepError::TooManyPoints {
                total,
                max: MAX_POINTS,
            });
        }
        Ok(Grid { axes })
    }

    /// Number of values of each axis.
    pub fn shape(&self) -> Vec<usize> {
        self.axes.iter().map(Vec::len).collect()
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.axes.iter().map(Vec::len).product()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Grid coordinates of point `index`.
    pub fn coordinates(&self, index: usize) -> Vec<usize> {
        coordinates(&self.shape(), index)
    }

    /// Parameter values of point `index`.
    pub fn values(&self, index: usize) -> Vec<f64> {
        self.coordinates(index)
            .iter()
            .zip(&self.axes)
            .map(|(&i, a)| a[i])
            .collect()
    }
}

/// Grid coordinates of point `index` in a grid of `shape`, row-major.
pub fn coordinates(shape: &[usize], mut index: usize) -> Vec<usize> {
    let mut c = vec![0; shape.len()];
    for (slot, &n) in c.iter_mut().zip(shape).rev() {
        *slot = index % n;
        index /= n;
    }
    c
}

/// The neighbour a point's mode identities come from: the point one step
/// back along the last axis on which this point is not at the start. Every
/// point but the first has one, earlier in row-major order, so following
/// parents always ends at point 0 (a spanning tree of the grid: each row is
/// followed along its fast axis, row starts along the slower ones).
pub fn parent(shape: &[usize], index: usize) -> Option<usize> {
    let c = coordinates(shape, index);
    let axis = c.iter().rposition(|&i| i > 0)?;
    let stride: usize = shape[axis + 1..].iter().product();
    Some(index - stride)
}

/// Shard `index`/`count` (1-based) of a grid: every `count`-th point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Parses `K/N`.
    pub fn parse(text: &str) -> Result<Shard, SweepError> {
        let bad = || SweepError::BadShard {
            given: text.to_string(),
        };
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if k == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { index: k, count: n })
    }

    /// Whether point `i` belongs to this shard.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index - 1
    }

    /// The shard (1-based) that point `i` belongs to among `count`.
    pub fn of(i: usize, count: usize) -> usize {
        i % count + 1
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_hit_their_ends_and_log_has_equal_ratios() {
        let a = Axis::parse("1e3:1e5:3:log", "k=1e3:1e5:3:log").unwrap();
        let v = a.values();
        assert_eq!(v[0], 1e3);
        assert_eq!(v[2], 1e5);
        assert!((v[1] / 1e4 - 1.0).abs() < 1e-15);
        let b = Axis::parse("0:1:5", "x").unwrap().values();
        assert_eq!(b, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(Axis::parse("2:3:1", "x").unwrap().values(), vec![2.0]);
        assert_eq!(
            Axis::parse("1e-3:1.2e-3:3", "x").unwrap().values()[1],
            1.1e-3
        );
        for bad in [
            "1:2",
            "1:2:0",
            "1:2:x",
            "a:2:3",
            "1:2:3:lin",
            "0:1:3:log",
            "1:inf:2",
            "1,,2",
            "1,x",
            "",
            "1,nan",
        ] {
            assert!(Axis::parse(bad, bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_list_is_its_values_in_order_and_prints_back() {
        let a = Axis::parse("1.1e-3, 1e-3,1.3e-3", "h=…").unwrap();
        assert_eq!(a.values(), vec![1.1e-3, 1e-3, 1.3e-3]);
        assert_eq!(a.first(), 1.1e-3);
        assert!(!a.is_log());
        assert_eq!(Axis::parse(&a.to_string(), "h").unwrap(), a);
        assert_eq!(Axis::parse("-2", "x").unwrap().values(), vec![-2.0]);
    }

    #[test]
    fn row_major_order_and_parents() {
        let shape = [2, 3];
        assert_eq!(coordinates(&shape, 4), vec![1, 1]);
        assert_eq!(parent(&shape, 0), None);
        assert_eq!(parent(&shape, 1), Some(0));
        assert_eq!(
            parent(&shape, 3),
            Some(0),
            "row start follows the slow axis"
        );
        assert_eq!(parent(&shape, 5), Some(4));
    }

    #[test]
    fn shards_partition_the_grid() {
        let shards: Vec<Shard> = (1..=3)
            .map(|k| Shard::parse(&format!("{k}/3")).unwrap())
            .collect();
        for i in 0..20 {
            assert_eq!(shards.iter().filter(|s| s.contains(i)).count(), 1);
            assert!(shards[Shard::of(i, 3) - 1].contains(i));
        }
        for bad in ["0/3", "4/3", "3", "a/b", "1/0"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
    }
}
