//! Is a state an equilibrium? The force balance a linearization needs
//! before its eigenvalues mean vibration (ω² > 0) or instability (ω² < 0).
//!
//! At a state (q, λ) the unbalanced generalized force is
//!
//! ```text
//! r = Q_int(q) − Q_ext(q, t) + C_qᵀ(q) λ        [SI: N at positions, N m at slopes and angles]
//! ```
//!
//! with Q_int the beams' elastic forces, the springs (preloads included),
//! torsion springs and contacts, Q_ext the applied loads × `load_scale` at
//! time `t` plus gravity. Without given multipliers, λ are the
//! least-squares ones: r is then the part of Q_int − Q_ext that no joint can
//! carry, its projection on the free motions null(C_q).
//!
//! **Units.** Generalized forces on slopes and angles are moments [N m];
//! they are divided by the model's size L ([`System::length_scale`]) so
//! that every entry is a force [N] and one norm weighs them alike (the
//! projection is taken in that metric: the free motions are those of
//! [`NullSpace::scaled`] with positions in units of L).
//!
//! **Free fall.** An assembly that no joint, spring or contact ties to the
//! ground can translate as a whole; under uniform gravity it falls without
//! deforming, and in the falling frame it is in equilibrium. (A translation
//! the joints allow but a grounded spring resists is no free fall: a mass
//! held only by preloaded springs was called balanced, its 50 N preload
//! fitted away as an acceleration.) The uniform acceleration
//! a (the force M·(a along x and y) on every mass) is fitted with λ and not
//! counted as unbalance. A free rigid rotation is not fitted (it is not a
//! steady motion).
//!
//! **The reference.** The beams are straight and stress-free at the
//! reference q₀ by definition, so at q = q₀ their elastic forces are zero
//! and are not summed: their stored nodes are rounded to ε|r|, and on a
//! beam turned off the axes (or far from the origin) the forces computed
//! from them are that rounding times EI/Le³ at every node (a 20,000-element
//! hanger at 250 m from the origin: a resultant of 47.5 kN), which hid
//! real loads of 500 N.
//!
//! **Verdict.** The state is balanced when the resultant |r|²/‖r‖∞ (the
//! unbalance of parts that move together, summed back from the
//! coordinates the projection spreads it over) is ≤ `tolerance` · F + noise
//! and ‖C(q)‖∞ ≤ `tolerance` · L, with F ([`Balance::scale`]) the largest
//! entry of Q_int, Q_ext and the joint forces C_qᵀλ, of any one member's
//! force (two opposed springs preloaded to 50 N cancel in Q_int: judged
//! against the assembled 4e-14 N they were "not an equilibrium"), and of
//! the springs' and contacts' at the reference (a spring's preload is the
//! model's force even where the equilibrium relaxes it: without it,
//! springs relaxed to 1e-9 N were judged against 1e-9 N). The noise is
//! the larger of 256 ε · max EA, the rounding a straight, stress-free
//! beam's elastic forces carry ([`NOISE_FACTOR`]), and 8 ε k L for the
//! stiffest spring or contact k ([`MEMBER_ROUNDING`]); away from the
//! reference (a state the statics found) also twice the resultant of the
//! beams' elastic forces at the reference, their storage's rounding,
//! which a state's forces carry too ([`REFERENCE_ROUNDING`]), and the
//! force a displacement of [`STEP_RESOLUTION`] × L makes in the stiffest
//! element, EA/Le (the statics' Newton iteration stops on a step that
//! small, so it does not resolve a smaller unbalance: a 25 mm cantilever
//! of 8 elements, 0.1 N at 9.4 mm, stops at 3.5e-7 N).

use crate::linalg::null_space::NullSpace;
use crate::linalg::vector::dot;
use crate::linalg::Triplets;
use crate::system::{ForceParts, System};

/// Relative tolerance of the force balance and of the constraints
/// [`Balance::is_balanced`] uses (the static solver converges to 1e-10 of
/// its force scale; 1e-8 leaves room for a state written to a file).
pub const BALANCE_TOLERANCE: f64 = 1e-8;

/// Multiple of ε · max EA below which an unbalanced force is round-off.
pub const NOISE_FACTOR: f64 = 256.0;

/// Multiple of ε k L below which an unbalanced force is a spring's or a
/// contact's round-off (k(l − l₀) loses ε k l: two springs of 1e5 and
/// 3e5 N/m preloaded to 1 mN, 1 and 1.3 m long, leave 1.1e-11 N at their
/// exact equilibrium, 1.1e-8 of their force).
pub const MEMBER_ROUNDING: f64 = 8.0;

/// The statics' smallest resolved step, relative to the assembly's size L
/// (its Newton iteration stops on a step below it).
pub const STEP_RESOLUTION: f64 = 1e-10;

/// Multiple of the resultant of the beams' elastic forces at the reference
/// below which an unbalanced force away from it is their round-off. A beam
/// is straight and stress-free there by definition, but its nodes are
/// stored rounded to ε|r|: on a beam not along an axis they zigzag by that
/// much, and its elements bend by ε|r|/Le², a force of ε|r| EI/Le³ at every
/// node (a 1.5 m ruler turned 30°, 20,000 elements: a resultant of 7.1 N).
/// A state near the reference carries another sample of the same rounding;
/// twice the reference's allows for that.
pub const REFERENCE_ROUNDING: f64 = 2.0;

/// The resultant of a (weighted) force along its own motion, |r|²/max|rᵢ|,
/// and the coordinate of its largest entry. The unbalance of parts that
/// move together is spread over their coordinates by the projection (two
/// masses pinned together carry half each; a mass pinned under an unbalance
/// of 0.01 N read 5e-3 N), and summed back here; on one coordinate it is
/// that entry.
fn resultant(r: &[f64]) -> (f64, usize) {
    let (mut worst, mut largest, mut squares) = (0, 0.0, 0.0);
    for (i, ri) in r.iter().enumerate() {
        squares += ri * ri;
        if ri.abs() > largest {
            (worst, largest) = (i, ri.abs());
        }
    }
    let resultant = if largest > 0.0 {
        squares / largest
    } else {
        0.0
    };
    (resultant, worst)
}

/// The force of a displacement of [`STEP_RESOLUTION`] × L in the stiffest
/// element, max EA/Le × 1e-10 L [SI: N].
pub fn resolution_force(system: &System) -> f64 {
    let length = system.length_scale();
    system
        .beams
        .iter()
        .flat_map(|b| b.elements.iter().map(move |e| b.section.ea / e.le))
        .fold(0.0, f64::max)
        * STEP_RESOLUTION
        * length
}

/// The force balance at one state.
#[derive(Debug, Clone, PartialEq)]
pub struct Balance {
    /// The unbalanced force r (moments divided by the model's size) as the
    /// resultant along its own motion, |r|²/max|rᵢ| (the largest entry when
    /// it acts on one coordinate) [SI: N].
    pub unbalanced: f64,
    /// Largest entry of Q_int, Q_ext and C_qᵀλ, the same units [SI: N].
    pub scale: f64,
    /// The rounding a balanced state may leave (module doc) [SI: N].
    pub noise: f64,
    /// Coordinate where the largest unbalanced entry acts.
    pub worst_dof: usize,
    /// That entry of r as it acts on the coordinate [SI: N or N m].
    pub worst_force: f64,
    /// ‖C(q)‖∞ [SI: m, –].
    pub constraint_violation: f64,
    /// The model's size L the moments and the violation are measured
    /// against [SI: m].
    pub length: f64,
    /// Whether a uniform acceleration of the whole assembly (free fall)
    /// was fitted with the multipliers.
    pub free_fall: bool,
}

impl Balance {
    /// `unbalanced / scale` [–] (0 when nothing acts at all).
    pub fn relative(&self) -> f64 {
        if self.scale > 0.0 {
            self.unbalanced / self.scale
        } else {
            0.0
        }
    }

    /// Force balance and constraints hold to `tolerance` (module doc).
    pub fn is_balanced(&self, tolerance: f64) -> bool {
        self.unbalanced <= tolerance * self.scale + self.noise
            && self.constraint_violation <= tolerance * self.length
    }
}

/// The unbalanced force at (q, λ) with the loads × `load_scale` at `time`;
/// least-squares multipliers when `lambda` is `None` (module doc).
pub fn unbalanced_force(
    system: &System,
    q: &[f64],
    lambda: Option<&[f64]>,
    time: f64,
    load_scale: f64,
) -> Balance {
    let n = system.ndof();
    let m = system.constraint_count();
    let length = system.length_scale();
    // w: 1 on positions, 1/L on slopes and angles (moments to forces).
    let mut w = vec![1.0 / length; n];
    for i in system.point_coordinates() {
        w[i] = 1.0;
        w[i + 1] = 1.0;
    }
    // The beams are straight and stress-free at the reference by
    // definition: their forces there are zero, and what their rounded
    // storage gives is round-off ([`REFERENCE_ROUNDING`]), not counted.
    let at_reference = q == system.q0.as_slice();
    let parts = if at_reference {
        ForceParts::Members
    } else {
        ForceParts::All
    };
    let mut internal = vec![0.0; n];
    system.internal_force_of(parts, q, &mut internal);
    let mut external = vec![0.0; n];
    system.external_force(q, time, load_scale, &mut external);
    let f: Vec<f64> = internal.iter().zip(&external).map(|(a, b)| a - b).collect();
    let weighted_max = |v: &[f64]| {
        v.iter()
            .zip(&w)
            .map(|(x, wi)| (x * wi).abs())
            .fold(0.0, f64::max)
    };
    let mut scale = weighted_max(&internal)
        .max(weighted_max(&external))
        .max(system.largest_member_force(parts, q, &w));
    let mut noise = (NOISE_FACTOR * f64::EPSILON * system.stiffest_ea())
        .max(MEMBER_ROUNDING * f64::EPSILON * system.stiffest_member(q) * length);
    // Away from the reference: the members' forces there (their preloads)
    // too, the statics' resolution, and the beams' rounding at the
    // reference, which another state's forces carry as well.
    let mut reference_rounding = Vec::new();
    if !at_reference {
        let mut members = vec![0.0; n];
        system.internal_force_of(ForceParts::Members, &system.q0, &mut members);
        scale = scale
            .max(weighted_max(&members))
            .max(system.largest_member_force(ForceParts::Members, &system.q0, &w));
        noise = noise.max(resolution_force(system));
        let mut beams = vec![0.0; n];
        system.internal_force_of(ForceParts::Beams, &system.q0, &mut beams);
        reference_rounding = beams.iter().zip(&w).map(|(x, wi)| x * wi).collect();
    }
    let mut cq = Triplets::new(m, n);
    system.add_constraint_jacobian(q, &mut cq);
    let mut free_fall = false;
    let r: Vec<f64> = match lambda {
        Some(lambda) => {
            if !reference_rounding.is_empty() {
                noise = noise.max(REFERENCE_ROUNDING * resultant(&reference_rounding).0);
            }
            let mut joint = vec![0.0; n];
            system.add_constraint_forces(q, lambda, &mut joint);
            scale = scale.max(weighted_max(&joint));
            f.iter().zip(&joint).map(|(a, b)| a + b).collect()
        }
        None => {
            // N: orthonormal basis of null(C_q D), D = L W (positions in
            // units of L). The least-squares residual of W(f + C_qᵀλ) is
            // N Nᵀ W f; `restrict` gives Nᵀ D⁻¹ v and `expand` D N x.
            let d: Vec<f64> = w.iter().map(|wi| wi * length).collect();
            let ns = NullSpace::scaled(m, n, cq.entries(), &d);
            let project = |v: &[f64]| -> Vec<f64> {
                // v is a weighted force W f: N Nᵀ v = D⁻¹ expand(restrict(D v)).
                let dv: Vec<f64> = v.iter().zip(&d).map(|(x, di)| x * di).collect();
                let full = ns.expand(&ns.restrict(&dv));
                full.iter().zip(&d).map(|(x, di)| x / di).collect()
            };
            if ns.dim() > 0 && !reference_rounding.is_empty() {
                let rounding = resultant(&project(&reference_rounding)).0;
                noise = noise.max(REFERENCE_ROUNDING * rounding);
            }
            let g: Vec<f64> = f.iter().zip(&w).map(|(x, wi)| x * wi).collect();
            let mut rw = if ns.dim() == 0 {
                vec![0.0; n]
            } else {
                project(&g)
            };
            let translates = |t: &[f64]| {
                // Internal forces unchanged by a translation by L (to the
                // noise of the forces at hand; a grounded spring k changes
                // them by k L): nothing grounded resists.
                let step = length;
                let moved: Vec<f64> = q.iter().zip(t).map(|(qi, ti)| qi + step * ti).collect();
                // The members' alone: a beam's forces do not change under a
                // translation but for their rounding.
                let (mut before, mut after) = (vec![0.0; n], vec![0.0; n]);
                system.internal_force_of(ForceParts::Members, q, &mut before);
                system.internal_force_of(ForceParts::Members, &moved, &mut after);
                let change: Vec<f64> = after.iter().zip(&before).map(|(a, b)| a - b).collect();
                weighted_max(&change) <= 1e-9 * scale + noise
            };
            free_fall = remove_free_fall(system, &cq, &w, &project, &translates, &mut rw);
            let joint: Vec<f64> = g.iter().zip(&rw).map(|(gi, ri)| ri - gi).collect();
            scale = scale.max(joint.iter().map(|x| x.abs()).fold(0.0, f64::max));
            rw.iter().zip(&w).map(|(x, wi)| x / wi).collect()
        }
    };
    let weighted: Vec<f64> = r.iter().zip(&w).map(|(ri, wi)| ri * wi).collect();
    let (unbalanced, worst_dof) = resultant(&weighted);
    let mut c = vec![0.0; m];
    system.constraint_residual(q, &mut c);
    Balance {
        unbalanced,
        scale,
        noise,
        worst_dof,
        worst_force: r.get(worst_dof).copied().unwrap_or(0.0),
        constraint_violation: c.iter().map(|x| x.abs()).fold(0.0, f64::max),
        length,
        free_fall,
    }
}

/// Removes from the projected weighted residual `rw` its components along
/// the forces of a uniform acceleration, when the constraints let the whole
/// assembly translate and nothing grounded resists it (`translates`);
/// returns whether they did.
fn remove_free_fall(
    system: &System,
    cq: &Triplets,
    w: &[f64],
    project: &dyn Fn(&[f64]) -> Vec<f64>,
    translates: &dyn Fn(&[f64]) -> bool,
    rw: &mut [f64],
) -> bool {
    let n = system.ndof();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for axis in 0..2 {
        let mut t = vec![0.0; n];
        for i in system.point_coordinates() {
            t[i + axis] = 1.0;
        }
        // Admissible: C_q t = 0 to round-off of the rows' own sizes.
        let mut ct = vec![0.0; cq.nrows()];
        let mut size = vec![0.0f64; cq.nrows()];
        for (i, j, v) in cq.entries() {
            ct[i] += v * t[j];
            size[i] = size[i].max(v.abs());
        }
        let admissible = ct
            .iter()
            .zip(&size)
            .all(|(c, s)| c.abs() <= 1e-12 * s.max(f64::MIN_POSITIVE));
        if !admissible || !translates(&t) {
            return false;
        }
        let mut mt = vec![0.0; n];
        system.mass().mul_vec(&t, &mut mt);
        let weighted: Vec<f64> = mt.iter().zip(w).map(|(x, wi)| x * wi).collect();
        let mut b = project(&weighted);
        for e in &basis {
            let c = dot(e, &b);
            b.iter_mut().zip(e).for_each(|(bi, ei)| *bi -= c * ei);
        }
        let norm = dot(&b, &b).sqrt();
        if norm > 0.0 {
            b.iter_mut().for_each(|x| *x /= norm);
            basis.push(b);
        }
    }
    for e in &basis {
        let c = dot(e, rw);
        rw.iter_mut().zip(e).for_each(|(ri, ei)| *ri -= c * ei);
    }
    !basis.is_empty()
}
