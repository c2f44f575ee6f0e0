//! Mode tracking across the points of a sweep by the modal assurance
//! criterion
//!
//! ```text
//! MAC(φ, ψ) = (φᵀψ)² / ((φᵀφ)(ψᵀψ))  ∈ [0, 1],
//! ```
//!
//! 1 for parallel shapes, 0 for orthogonal ones, independent of scale and
//! sign. Sorting by frequency swaps two modes where their frequencies
//! cross; their shapes do not swap, so matching shapes between neighbouring
//! points keeps each mode's identity.
//!
//! The modes tracked are the lowest `n` elastic modes of the sweep's first
//! point (in ascending order there). Every other point takes its identities
//! from its parent ([`super::grid::parent`]: the previous point of its row,
//! or for a row start the start of the previous row) or, if that point
//! failed, from the parent's nearest successful ancestor: the pairs
//! (tracked mode, computed mode) are assigned greedily in descending MAC.
//! A point without a successful ancestor, or whose coordinates differ in
//! number from its ancestor's (a changed mesh), starts afresh in ascending
//! order (MAC not defined there). Points are processed in index order, so
//! the outcome depends only on the points, not on how they were computed
//! (in parallel, or in shards).

use super::grid::parent;
use super::quantity::RawMode;
use crate::signal::mac::mac_pair;

/// A tracked mode at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackedMode {
    /// [SI: Hz]
    pub frequency_hz: f64,
    /// MAC with the same tracked mode at the ancestor point; `None` where
    /// tracking starts.
    pub mac: Option<f64>,
    /// Position among the point's computed elastic modes (ascending).
    pub raw: usize,
}

/// Tracks `n` modes over the points of a grid of `shape` (row-major;
/// `None` = a failed point). Per point: `None` if it failed, else one entry
/// per tracked mode (`None` where no computed mode was left for it).
pub fn track(
    shape: &[usize],
    points: &[Option<&[RawMode]>],
    n: usize,
) -> Vec<Option<Vec<Option<TrackedMode>>>> {
    let mut out: Vec<Option<Vec<Option<TrackedMode>>>> = Vec::with_capacity(points.len());
    for (i, modes) in points.iter().enumerate() {
        let Some(modes) = modes else {
            out.push(None);
            continue;
        };
        let mut a = parent(shape, i);
        while let Some(p) = a {
            if out[p].is_some() {
                break;
            }
            a = parent(shape, p);
        }
        let ancestor = a.and_then(|p| Some((points[p]?, out[p].as_ref()?)));
        let dims = |m: &[RawMode]| m.first().map(|x| x.shape.len());
        let tracked = match ancestor {
            Some((pm, pt)) if dims(pm) == dims(modes) => follow(pm, pt, modes),
            _ => fresh(modes, n),
        };
        out.push(Some(tracked));
    }
    out
}

/// The lowest `n` modes in ascending order.
fn fresh(modes: &[RawMode], n: usize) -> Vec<Option<TrackedMode>> {
    (0..n)
        .map(|j| {
            modes.get(j).map(|m| TrackedMode {
                frequency_hz: m.frequency_hz,
                mac: None,
                raw: j,
            })
        })
        .collect()
}

/// Each tracked mode of the ancestor matched to a computed mode here,
/// greedily by descending MAC (ties: lower tracked, then lower computed
/// index first).
fn follow(
    ancestor_modes: &[RawMode],
    ancestor: &[Option<TrackedMode>],
    modes: &[RawMode],
) -> Vec<Option<TrackedMode>> {
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (j, t) in ancestor.iter().enumerate() {
        let Some(t) = t else { continue };
        let shape = &ancestor_modes[t.raw].shape;
        for (r, m) in modes.iter().enumerate() {
            pairs.push((mac_pair(shape, &m.shape), j, r));
        }
    }
    pairs.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut tracked: Vec<Option<TrackedMode>> = vec![None; ancestor.len()];
    let mut used = vec![false; modes.len()];
    for (value, j, r) in pairs {
        if tracked[j].is_none() && !used[r] {
            used[r] = true;
            tracked[j] = Some(TrackedMode {
                frequency_hz: modes[r].frequency_hz,
                mac: Some(value),
                raw: r,
            });
        }
    }
    tracked
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mode(f: f64, shape: [f64; 2]) -> RawMode {
        RawMode {
            frequency_hz: f,
            shape: shape.to_vec(),
        }
    }

    #[test]
    fn crossing_modes_keep_their_shapes() {
        // Two uncoupled modes, x rising through y.
        let p: Vec<Vec<RawMode>> = vec![
            vec![mode(1.0, [1.0, 0.0]), mode(2.0, [0.0, 1.0])],
            vec![mode(2.0, [0.0, -1.0]), mode(2.5, [1.0, 0.0])],
            vec![mode(2.0, [0.0, 1.0]), mode(3.0, [2.0, 0.0])],
        ];
        let refs: Vec<Option<&[RawMode]>> = p.iter().map(|m| Some(m.as_slice())).collect();
        let t = track(&[3], &refs, 2);
        let x: Vec<f64> = t
            .iter()
            .map(|p| p.as_ref().unwrap()[0].unwrap().frequency_hz)
            .collect();
        assert_eq!(x, vec![1.0, 2.5, 3.0]);
        assert_eq!(t[1].as_ref().unwrap()[1].unwrap().mac, Some(1.0));
        // A failed point is bridged by its ancestor.
        let refs = vec![refs[0], None, refs[2]];
        let t = track(&[3], &refs, 2);
        assert!(t[1].is_none());
        assert_eq!(t[2].as_ref().unwrap()[0].unwrap().frequency_hz, 3.0);
    }

    #[test]
    fn mac_is_scale_and_sign_free() {
        assert_eq!(mac_pair(&[1.0, 2.0], &[-2.0, -4.0]), 1.0);
        assert_eq!(mac_pair(&[1.0, 0.0], &[0.0, 3.0]), 0.0);
    }
}
