//! Data preparation in chart coordinates: splitting at unplottable values,
//! clipping to the shown box, thinning long series, and data extents.

/// A point in chart coordinates.
pub(super) type Pt = (f64, f64);

/// Axis-aligned box `[x0, x1] × [y0, y1]` in chart coordinates.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bounds {
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
}

impl Bounds {
    pub fn contains(&self, p: Pt) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }
}

/// Runs of consecutive plottable points (`None` breaks a run).
pub(super) fn runs(points: impl Iterator<Item = Option<Pt>>) -> Vec<Vec<Pt>> {
    let mut out: Vec<Vec<Pt>> = vec![Vec::new()];
    for p in points {
        match p {
            Some(p) => out.last_mut().expect("never empty").push(p),
            None if out.last().is_some_and(|r| !r.is_empty()) => out.push(Vec::new()),
            None => {}
        }
    }
    out.retain(|r| !r.is_empty());
    out
}

/// The parts of a polyline inside `b` (Liang–Barsky on each segment).
pub(super) fn clip_polyline(pts: &[Pt], b: Bounds) -> Vec<Vec<Pt>> {
    if pts.iter().all(|p| b.contains(*p)) {
        return vec![pts.to_vec()];
    }
    let mut out: Vec<Vec<Pt>> = Vec::new();
    let mut current: Vec<Pt> = Vec::new();
    for w in pts.windows(2) {
        match clip_segment(w[0], w[1], b) {
            Some((p, q)) => {
                if current.last() != Some(&p) {
                    if !current.is_empty() {
                        out.push(std::mem::take(&mut current));
                    }
                    current.push(p);
                }
                current.push(q);
            }
            None => {
                if !current.is_empty() {
                    out.push(std::mem::take(&mut current));
                }
            }
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    if pts.len() == 1 && b.contains(pts[0]) {
        out.push(pts.to_vec());
    }
    out
}

/// Whether the segment from `p` to `q` touches `b`.
pub(super) fn segment_meets(p: Pt, q: Pt, b: Bounds) -> bool {
    clip_segment(p, q, b).is_some()
}

fn clip_segment(p: Pt, q: Pt, b: Bounds) -> Option<(Pt, Pt)> {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (den, num) in [
        (-dx, p.0 - b.x0),
        (dx, b.x1 - p.0),
        (-dy, p.1 - b.y0),
        (dy, b.y1 - p.1),
    ] {
        if den == 0.0 {
            if num < 0.0 {
                return None;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| (p.0 + t * dx, p.1 + t * dy);
    Some((
        if t0 == 0.0 { p } else { at(t0) },
        if t1 == 1.0 { q } else { at(t1) },
    ))
}

/// Thins a polyline with increasing x to at most four points per pixel
/// column (first, lowest, highest, last), which draws identically.
pub(super) fn decimate(pts: &[Pt], x0: f64, x1: f64, columns: usize) -> Vec<Pt> {
    let monotone = pts.windows(2).all(|w| w[1].0 >= w[0].0);
    if pts.len() <= 4 * columns || !monotone || x1 <= x0 {
        return pts.to_vec();
    }
    let column = |x: f64| (((x - x0) / (x1 - x0)) * columns as f64).floor() as i64;
    let mut out = Vec::with_capacity(4 * columns + 4);
    let mut start = 0;
    while start < pts.len() {
        let c = column(pts[start].0);
        let mut end = start;
        while end < pts.len() && column(pts[end].0) == c {
            end += 1;
        }
        let bucket = &pts[start..end];
        let lowest = (0..bucket.len()).min_by(|&a, &b| bucket[a].1.total_cmp(&bucket[b].1));
        let highest = (0..bucket.len()).max_by(|&a, &b| bucket[a].1.total_cmp(&bucket[b].1));
        let mut keep = vec![0, bucket.len() - 1];
        keep.extend(lowest);
        keep.extend(highest);
        keep.sort_unstable();
        keep.dedup();
        out.extend(keep.into_iter().map(|i| bucket[i]));
        start = end;
    }
    out
}

/// Smallest and largest of the values seen.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Extent(Option<(f64, f64)>);

impl Extent {
    pub fn add(&mut self, v: f64) {
        if v.is_finite() {
            self.0 = Some(match self.0 {
                None => (v, v),
                Some((lo, hi)) => (lo.min(v), hi.max(v)),
            });
        }
    }

    /// The extent widened by `below`/`above` times its span; a single value
    /// is widened to a span of `empty_span`. `None` when nothing was added.
    pub fn padded(&self, below: f64, above: f64, empty_span: f64) -> Option<(f64, f64)> {
        let (lo, hi) = self.0?;
        let span = hi - lo;
        if span == 0.0 {
            let half = if lo == 0.0 {
                empty_span / 2.0
            } else {
                lo.abs() * 0.05
            };
            return Some((lo - half, hi + half));
        }
        Some((lo - below * span, hi + above * span))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_the_inside() {
        let b = Bounds {
            x0: 0.0,
            x1: 1.0,
            y0: 0.0,
            y1: 1.0,
        };
        let parts = clip_polyline(&[(-1.0, 0.5), (0.5, 0.5), (2.0, 0.5)], b);
        assert_eq!(parts, vec![vec![(0.0, 0.5), (0.5, 0.5), (1.0, 0.5)]]);
        let parts = clip_polyline(&[(0.5, 0.5), (0.5, 2.0), (0.6, 0.5)], b);
        assert_eq!(parts.len(), 2);
    }

    #[test]
    fn decimation_keeps_extremes() {
        let pts: Vec<Pt> = (0..10_000)
            .map(|i| (i as f64, ((i * 7919) % 101) as f64))
            .collect();
        let d = decimate(&pts, 0.0, 10_000.0, 100);
        assert!(d.len() <= 400);
        assert_eq!(d.first(), pts.first());
        assert_eq!(d.last(), pts.last());
        let max = d.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        assert_eq!(max, 100.0);
    }

    #[test]
    fn runs_split_at_gaps() {
        let r = runs(
            [
                Some((0.0, 0.0)),
                None,
                None,
                Some((1.0, 1.0)),
                Some((2.0, 2.0)),
            ]
            .into_iter(),
        );
        assert_eq!(r.len(), 2);
    }
}
