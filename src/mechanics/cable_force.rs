//! The elastic force `Q_s = ∂U/∂e` of a cable element (see
//! [`super::element`] for the element, its energy and units [SI: N]).
//!
//! Point by point in arrays (the slopes r' at the quadrature points, their
//! lengths, the tensions; the curvatures κ = (r' × r'')/|r'|² and their
//! gradients): the operations of [`super::element`]'s `axial_strain` and
//! `BendingPoint` on the same values in the same order, bit for bit. The
//! nodes' sizes |nodeᵢ| of the strain's snapping threshold are formed once
//! for all points. The bulk of a transient step of a bare beam.
//!
//! One code for one element and for several elements side by side
//! ([`CableElement::elastic_forces_into`]): it is written over a number
//! type [`Lane`], a plain `f64` or [`Wide`], a value per element in a
//! vector register, whose every operation is the `f64` one lane by lane
//! (IEEE: the same bits), so the vector units take four elements' square
//! roots and divisions at once (AVX2), each with its own constants (shape tables, weights, EA, EI)
//! in its lane.

use super::element::{CableElement, Vec8, AXIAL_POINTS, BENDING_POINTS};
use pulp::Simd;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// The shape derivatives of an element's quadrature points, indexed
/// [shape function][point] (the arrays the force runs over).
#[derive(Debug, Clone)]
pub(super) struct ForceTables {
    pub(super) axial_d1: [[f64; AXIAL_POINTS]; 4],
    pub(super) bending_d1: [[f64; BENDING_POINTS]; 4],
    pub(super) bending_d2: [[f64; BENDING_POINTS]; 4],
}

/// The most elements [`CableElement::elastic_forces_into`] takes at once
/// (eight `f64` fill a 512-bit vector register).
pub const MAX_LANES: usize = 8;

/// A number the force is computed in: every operation IEEE `f64`
/// arithmetic on each lane alone (no fused multiply–add), so that a lane
/// holds the bits a plain `f64` computation gives.
pub trait Lane:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// x in every lane (`self` only lends its kind).
    fn splat(self, x: f64) -> Self;
    /// f of element j in lane j (one element per lane).
    fn gather(self, elements: &[CableElement], f: impl Fn(&CableElement) -> f64) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    /// 0 in the lanes where |self| ≤ bound, self elsewhere.
    fn zero_within(self, bound: Self) -> Self;
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(self, x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn gather(self, elements: &[CableElement], f: impl Fn(&CableElement) -> f64) -> Self {
        f(&elements[0])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn zero_within(self, bound: Self) -> Self {
        if self.abs() <= bound {
            0.0
        } else {
            self
        }
    }
}

/// One `f64` per element in a vector register of `S` (`pulp`'s
/// instruction set chosen at run time): its arithmetic, square root,
/// absolute value and comparison are IEEE lane by lane.
#[derive(Clone, Copy)]
pub struct Wide<S: Simd> {
    simd: S,
    v: S::f64s,
}

impl<S: Simd> Wide<S> {
    /// How many lanes `S` has.
    pub const LANES: usize = std::mem::size_of::<S::f64s>() / std::mem::size_of::<f64>();

    /// f(j) in lane j. Four lanes (AVX2) are put together in registers: a
    /// vector load of values just stored one by one waits for the stores.
    #[inline(always)]
    fn from_fn(simd: S, f: impl Fn(usize) -> f64) -> Self {
        let v = if Self::LANES == 4 {
            pulp::bytemuck::cast([f(0), f(1), f(2), f(3)])
        } else {
            let mut lanes = [0.0; MAX_LANES];
            for (j, l) in lanes[..Self::LANES].iter_mut().enumerate() {
                *l = f(j);
            }
            load::<S>(&lanes)
        };
        Wide { simd, v }
    }
}

/// The first `Wide::<S>::LANES` values of `a` in a register (a whole
/// vector load: `pulp`'s partial loads go through a table of jumps).
#[inline(always)]
fn load<S: Simd>(a: &[f64; MAX_LANES]) -> S::f64s {
    S::as_simd_f64s(a).0[0]
}

macro_rules! lanewise {
    ($trait:ident, $method:ident, $simd:ident) => {
        impl<S: Simd> $trait for Wide<S> {
            type Output = Wide<S>;
            #[inline(always)]
            fn $method(self, other: Wide<S>) -> Wide<S> {
                Wide {
                    simd: self.simd,
                    v: self.simd.$simd(self.v, other.v),
                }
            }
        }
    };
}
lanewise!(Add, add, add_f64s);
lanewise!(Sub, sub, sub_f64s);
lanewise!(Mul, mul, mul_f64s);
lanewise!(Div, div, div_f64s);

impl<S: Simd> Neg for Wide<S> {
    type Output = Wide<S>;
    #[inline(always)]
    fn neg(self) -> Wide<S> {
        Wide {
            simd: self.simd,
            v: self.simd.neg_f64s(self.v),
        }
    }
}

impl<S: Simd> Lane for Wide<S> {
    #[inline(always)]
    fn splat(self, x: f64) -> Self {
        Wide {
            simd: self.simd,
            v: self.simd.splat_f64s(x),
        }
    }
    #[inline(always)]
    fn gather(self, elements: &[CableElement], f: impl Fn(&CableElement) -> f64) -> Self {
        Wide::from_fn(self.simd, |j| f(&elements[j]))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Wide {
            simd: self.simd,
            v: self.simd.sqrt_f64s(self.v),
        }
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Wide {
            simd: self.simd,
            v: self.simd.abs_f64s(self.v),
        }
    }
    #[inline(always)]
    fn zero_within(self, bound: Self) -> Self {
        let s = self.simd;
        let within = s.less_than_or_equal_f64s(s.abs_f64s(self.v), bound.v);
        Wide {
            simd: s,
            v: s.select_f64s(within, s.splat_f64s(0.0), self.v),
        }
    }
}

/// Σᵢ xᵢ dᵢ in the order of the element's `combine`: one component of r'
/// or r'' at a point from the nodes' components x and the shape
/// derivatives d there.
#[inline(always)]
fn at<T: Lane>(d: &[T; 4], x: &[T; 4]) -> T {
    x[0] * d[0] + x[1] * d[1] + x[2] * d[2] + x[3] * d[3]
}

/// One of an element's constants the force reads: its stiffnesses, its
/// quadrature weights and its shape derivatives (table, shape function i,
/// point k).
#[derive(Clone, Copy)]
enum Pick {
    Ea,
    Ei,
    AxialW(usize),
    BendingW(usize),
    AxialD1(usize, usize),
    BendingD1(usize, usize),
    BendingD2(usize, usize),
}

/// A shape-derivative table's [`Pick`] of (shape function, point).
type Table = fn(usize, usize) -> Pick;

/// How many constants [`Pick`] names.
const PICKS: usize = 2 + 5 * AXIAL_POINTS + 9 * BENDING_POINTS;

impl Pick {
    /// The constant's value for element `e`.
    #[inline(always)]
    fn value(self, e: &CableElement) -> f64 {
        match self {
            Pick::Ea => e.section.ea,
            Pick::Ei => e.section.ei,
            Pick::AxialW(k) => e.axial[k].w,
            Pick::BendingW(k) => e.bending[k].w,
            Pick::AxialD1(i, k) => e.tables.axial_d1[i][k],
            Pick::BendingD1(i, k) => e.tables.bending_d1[i][k],
            Pick::BendingD2(i, k) => e.tables.bending_d2[i][k],
        }
    }

    /// Its row in [`PackedElements`].
    #[inline(always)]
    fn index(self) -> usize {
        const A: usize = AXIAL_POINTS;
        const B: usize = BENDING_POINTS;
        match self {
            Pick::Ea => 0,
            Pick::Ei => 1,
            Pick::AxialW(k) => 2 + k,
            Pick::BendingW(k) => 2 + A + k,
            Pick::AxialD1(i, k) => 2 + A + B + A * i + k,
            Pick::BendingD1(i, k) => 2 + 5 * A + B + B * i + k,
            Pick::BendingD2(i, k) => 2 + 5 * A + 5 * B + B * i + k,
        }
    }

    /// Every constant once.
    fn all() -> impl Iterator<Item = Pick> {
        let tables: [(Table, usize); 3] = [
            (Pick::AxialD1, AXIAL_POINTS),
            (Pick::BendingD1, BENDING_POINTS),
            (Pick::BendingD2, BENDING_POINTS),
        ];
        [Pick::Ea, Pick::Ei]
            .into_iter()
            .chain((0..AXIAL_POINTS).map(Pick::AxialW))
            .chain((0..BENDING_POINTS).map(Pick::BendingW))
            .chain(tables.into_iter().flat_map(|(table, points)| {
                (0..4).flat_map(move |i| (0..points).map(move |k| table(i, k)))
            }))
    }
}

/// The constants of [`MAX_LANES`] consecutive elements stored lane by lane
/// (row [`Pick::index`], column the element), so that elements side by
/// side load each constant as one vector instead of gathering it from the
/// elements a lane at a time (a fifth of a small beam's force). 54 rows of
/// 8 `f64`: 432 bytes an element.
#[derive(Debug, Clone)]
pub struct PackedElements {
    rows: [[f64; MAX_LANES]; PICKS],
}

impl PackedElements {
    /// The constants of `elements` (at most [`MAX_LANES`]; missing lanes
    /// repeat the last element).
    pub fn new(elements: &[CableElement]) -> Self {
        let last = elements.len().min(MAX_LANES) - 1;
        let mut rows = [[0.0; MAX_LANES]; PICKS];
        for pick in Pick::all() {
            for (j, v) in rows[pick.index()].iter_mut().enumerate() {
                *v = pick.value(&elements[j.min(last)]);
            }
        }
        PackedElements { rows }
    }

    /// A beam's elements in groups of [`MAX_LANES`].
    pub fn of_beam(elements: &[CableElement]) -> Vec<Self> {
        elements.chunks(MAX_LANES).map(Self::new).collect()
    }
}

/// Where the force reads each lane's constants.
trait Constants<T: Lane> {
    fn of(&self, pick: Pick) -> T;
}

/// Gathered from the elements themselves, one lane at a time (`kind`
/// only lends its number type).
struct Gathered<'a, T> {
    elements: &'a [CableElement],
    kind: T,
}

impl<T: Lane> Constants<T> for Gathered<'_, T> {
    #[inline(always)]
    fn of(&self, pick: Pick) -> T {
        self.kind.gather(self.elements, |e| pick.value(e))
    }
}

/// Loaded from a [`PackedElements`], lanes `first..first + LANES`.
struct Packed<'a, S: Simd> {
    simd: S,
    packed: &'a PackedElements,
    first: usize,
}

impl<S: Simd> Constants<Wide<S>> for Packed<'_, S> {
    #[inline(always)]
    fn of(&self, pick: Pick) -> Wide<S> {
        let row = &self.packed.rows[pick.index()][self.first..][..Wide::<S>::LANES];
        Wide {
            simd: self.simd,
            v: S::as_simd_f64s(row).0[0],
        }
    }
}

impl CableElement {
    /// Elastic force `Q_s = ∂U/∂e`, added into `out`.
    #[inline(always)]
    pub fn elastic_force_into(&self, e: &Vec8, out: &mut Vec8) {
        let ex = [e[0], e[2], e[4], e[6]];
        let ey = [e[1], e[3], e[5], e[7]];
        let mut f: [f64; 8] = std::array::from_fn(|i| out[i]);
        let constants = Gathered {
            elements: std::slice::from_ref(self),
            kind: 0.0,
        };
        force_lanes(&constants, &ex, &ey, &mut f);
        out.copy_from_slice(&f);
    }
}

/// The elastic forces of `Wide::<S>::LANES` (at most [`MAX_LANES`])
/// consecutive elements of a beam side by side in `simd`'s vector
/// registers: element j's coordinates `q[4j..4j + 8]`, its force written to
/// `out[c][j]` (c = 0..8); each bit for bit what
/// [`CableElement::elastic_force_into`] gives from zero. The constants come
/// from `packed` when given (the group that holds these elements and the
/// first one's lane in it), else from the elements.
#[inline(always)]
pub fn elastic_forces_into<S: Simd>(
    simd: S,
    elements: &[CableElement],
    packed: Option<(&PackedElements, usize)>,
    q: &[f64],
    out: &mut [[f64; MAX_LANES]; 8],
) {
    let lanes = Wide::<S>::LANES;
    assert!(elements.len() == lanes && lanes <= MAX_LANES && q.len() >= 4 * lanes + 4);
    let load = |c: usize| Wide::from_fn(simd, |j| q[4 * j + c]);
    let ex = [load(0), load(2), load(4), load(6)];
    let ey = [load(1), load(3), load(5), load(7)];
    let mut f = [ex[0].splat(0.0); 8];
    match packed {
        Some((packed, first)) => {
            assert!(first + lanes <= MAX_LANES);
            let constants = Packed {
                simd,
                packed,
                first,
            };
            force_lanes(&constants, &ex, &ey, &mut f);
        }
        None => {
            let constants = Gathered {
                elements,
                kind: ex[0],
            };
            force_lanes(&constants, &ex, &ey, &mut f);
        }
    }
    for (o, f) in out.iter_mut().zip(f) {
        S::as_mut_simd_f64s(o).0[0] = f.v;
    }
}

/// The force of the elements whose `constants` are given (one element per
/// lane of T) from the nodes' x and y components, added into `out` (x, y
/// of node 0, then node 1, …).
#[inline(always)]
fn force_lanes<T: Lane>(constants: &impl Constants<T>, ex: &[T; 4], ey: &[T; 4], out: &mut [T; 8]) {
    let lit = |v: f64| ex[0].splat(v);
    let of = |pick| constants.of(pick);
    let (ea, ei) = (of(Pick::Ea), of(Pick::Ei));
    let node_size: [T; 4] = std::array::from_fn(|i| (ex[i] * ex[i] + ey[i] * ey[i]).sqrt());
    const A: usize = AXIAL_POINTS;
    let zero = lit(0.0);
    let (mut fx, mut fy) = ([zero; A], [zero; A]);
    let four = |table: Table, k: usize| -> [T; 4] {
        [
            of(table(0, k)),
            of(table(1, k)),
            of(table(2, k)),
            of(table(3, k)),
        ]
    };
    let d1: [[T; 4]; A] = [
        four(Pick::AxialD1, 0),
        four(Pick::AxialD1, 1),
        four(Pick::AxialD1, 2),
        four(Pick::AxialD1, 3),
        four(Pick::AxialD1, 4),
    ];
    for k in 0..A {
        let (x, y) = (at(&d1[k], ex), at(&d1[k], ey));
        let l = (x * x + y * y).sqrt();
        let size = d1[k][0].abs() * node_size[0]
            + d1[k][1].abs() * node_size[1]
            + d1[k][2].abs() * node_size[2]
            + d1[k][3].abs() * node_size[3];
        let eps = l - lit(1.0);
        let eps = eps.zero_within(lit(4.0 * f64::EPSILON) * size);
        let s = of(Pick::AxialW(k)) * ea * eps / l;
        (fx[k], fy[k]) = (x * s, y * s);
    }
    for k in 0..A {
        for i in 0..4 {
            out[2 * i] = out[2 * i] + d1[k][i] * fx[k];
            out[2 * i + 1] = out[2 * i + 1] + d1[k][i] * fy[k];
        }
    }
    const B: usize = BENDING_POINTS;
    let d1: [[T; 4]; B] = [
        four(Pick::BendingD1, 0),
        four(Pick::BendingD1, 1),
        four(Pick::BendingD1, 2),
    ];
    let d2: [[T; 4]; B] = [
        four(Pick::BendingD2, 0),
        four(Pick::BendingD2, 1),
        four(Pick::BendingD2, 2),
    ];
    // κ = c/g and its gradients p = ∂κ/∂r', q = ∂κ/∂r'' per point.
    let (mut px, mut py, mut qx, mut qy) = ([zero; B], [zero; B], [zero; B], [zero; B]);
    let mut cc = [zero; B];
    for k in 0..B {
        let (r1x, r1y) = (at(&d1[k], ex), at(&d1[k], ey));
        let (r2x, r2y) = (at(&d2[k], ex), at(&d2[k], ey));
        let g = r1x * r1x + r1y * r1y;
        let c = r1x * r2y + r1y * -r2x;
        let kappa = c / g;
        let t = lit(2.0) * c / (g * g);
        cc[k] = of(Pick::BendingW(k)) * ei * kappa;
        (px[k], py[k]) = (r2y / g - r1x * t, -r2x / g - r1y * t);
        (qx[k], qy[k]) = (-r1y / g, r1x / g);
    }
    for k in 0..B {
        for i in 0..4 {
            let (a, b) = (d1[k][i], d2[k][i]);
            out[2 * i] = out[2 * i] + cc[k] * (px[k] * a + qx[k] * b);
            out[2 * i + 1] = out[2 * i + 1] + cc[k] * (py[k] * a + qy[k] * b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::element::CableSection;
    use nalgebra::Vector2;
    use proptest::prelude::*;

    /// Elements side by side give each element's force bit for bit, in
    /// AVX2 registers (where the CPU has them) and in plain `f64`s: a beam
    /// of `MAX_LANES` elements of lengths off by `jitter` (as a mesh's
    /// differences of node positions are), bent and stretched by `bend`
    /// and `stretch`; with zero of both, straight and unstretched, the
    /// strain-snapping branch is taken. Their constants gathered from the
    /// elements and loaded from [`PackedElements`] alike.
    fn lanes_match<S: Simd>(simd: S, jitter: &[f64], bend: f64, stretch: f64) {
        let lanes = Wide::<S>::LANES;
        let section = CableSection::rectangle(127e9, 8940.0, 1.1e-3, 5.2e-3);
        let elements: Vec<CableElement> = jitter[..MAX_LANES]
            .iter()
            .map(|j| CableElement::new(3.125e-3 * (1.0 + j), section))
            .collect();
        // Nodes along the elements, the slopes turned and stretched.
        let mut q = Vec::new();
        let mut x = 0.0;
        for k in 0..=MAX_LANES {
            let angle = bend * (k as f64 * 0.7).sin();
            let slope = Vector2::new(angle.cos(), angle.sin()) * (1.0 + stretch);
            q.extend_from_slice(&[x, bend * 1e-3 * k as f64, slope.x, slope.y]);
            x += elements.get(k).map_or(0.0, |e| e.le) * (1.0 + stretch);
        }
        let packed = PackedElements::new(&elements);
        // Every group of `lanes` elements the packed constants hold, with
        // the constants gathered and loaded.
        for first in (0..=MAX_LANES - lanes).step_by(lanes) {
            let group = &elements[first..first + lanes];
            for source in [None, Some((&packed, first))] {
                let mut out = [[0.0; MAX_LANES]; 8];
                elastic_forces_into(simd, group, source, &q[4 * first..], &mut out);
                for (j, e) in group.iter().enumerate() {
                    let d0 = 4 * (first + j);
                    let mut f = Vec8::zeros();
                    e.elastic_force_into(&Vec8::from_column_slice(&q[d0..d0 + 8]), &mut f);
                    for c in 0..8 {
                        assert_eq!(
                            out[c][j].to_bits(),
                            f[c].to_bits(),
                            "element {}, entry {c}, packed {}: {:e} side by side, {:e} alone",
                            first + j,
                            source.is_some(),
                            out[c][j],
                            f[c]
                        );
                    }
                }
            }
        }
    }

    proptest! {
        #[test]
        fn elements_side_by_side_are_each_element_bit_for_bit(
            jitter in prop_oneof![
                Just(vec![0.0; MAX_LANES]),
                proptest::collection::vec(-1e-12..1e-12f64, MAX_LANES),
            ],
            bend in prop_oneof![Just(0.0), -0.3..0.3f64],
            stretch in prop_oneof![Just(0.0), -1e-3..1e-3f64],
        ) {
            #[cfg(target_arch = "x86_64")]
            if let Some(simd) = pulp::x86::V3::try_new() {
                lanes_match(simd, &jitter, bend, stretch);
            }
            lanes_match(pulp::Scalar::new(), &jitter, bend, stretch);
        }
    }
}
