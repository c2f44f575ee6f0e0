//! Unit sanity of a model: values that are valid numbers but not a
//! plausible engineering solid in SI units, or beams outside the beam
//! theory the elements implement. These are warnings, never errors: an
//! unusual material or a stubby beam may be meant.
//!
//! - **Slenderness**: Euler–Bernoulli theory (the ANCF cable elements)
//!   leaves out shear deformation and rotary inertia, whose relative effect
//!   on a bending frequency grows as (h/L)². Above h/L ≈ 0.05 it is a few
//!   per cent; above h/L = 0.1 the model is no longer a beam (and a height
//!   typed in millimetres into a metre field looks exactly like this).
//! - **Material**: engineering solids have Young's modulus E from about
//!   1e5 Pa (soft rubber) to 1e13 Pa (beyond diamond's 1.2e12), density ρ
//!   from 10 kg/m³ (light foams) to 25,000 kg/m³ (beyond osmium's 22,600),
//!   and bar-wave speed √(E/ρ) from about 10 m/s (a soft gel, E = 1e5 Pa at
//!   1000 kg/m³) to 20,000 m/s. E typed in MPa or ρ in g/cm³ falls outside:
//!   steel in MPa is 5.2 m/s, aluminium 5.1 m/s, copper 3.8 m/s.
//! - **Sizes that disagree**: a part whose size is over [`MAX_SIZE_RATIO`]
//!   times that of a part it is joined to (by a joint or a spring), or
//!   whose lever arm is, is named. A beam's size is its length L, a rigid
//!   body's its radius of gyration √(I/m) [SI: m]; a point mass (and a
//!   rigid body with I = 0) has no size of its own, so only the lever arms
//!   at it count. A lever arm is the distance from a rigid body's centre to
//!   a point it is joined at (`local`, or for a joint point without
//!   `local` the partner's point), compared with the body's own size and
//!   with the joined part's. One length in another unit (150 written for a
//!   150 µm beam among micrometre parts) looks exactly like this, and it
//!   costs accuracy: the stiffness and mass entries then span (L_max/L_min)⁴
//!   and more, and the eigen-solve certifies the lowest frequencies to a
//!   fraction of what the arithmetic gives a consistent model. Each part is
//!   named once, for its largest ratio. So is a spring over that many
//!   times as long, at the reference, as the largest part it holds (a
//!   point of it in millimetres).

use super::number::significant;
use super::validate::PointTarget;
use super::{Model, PointSpec};

/// h/L above which a beam is reported (module doc).
pub const MAX_SLENDERNESS: f64 = 0.1;
/// Plausible Young's modulus [SI: Pa].
pub const YOUNG_RANGE: (f64, f64) = (1e5, 1e13);
/// Plausible density [SI: kg/m³].
pub const DENSITY_RANGE: (f64, f64) = (10.0, 25_000.0);
/// Plausible bar-wave speed √(E/ρ) [SI: m/s].
pub const WAVE_SPEED_RANGE: (f64, f64) = (10.0, 20_000.0);
/// Ratio of sizes (or of a lever arm to a size) of joined parts above
/// which a part is reported (module doc).
pub const MAX_SIZE_RATIO: f64 = 100.0;

/// One implausible value, with the JSON path of the value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitWarning {
    #[error("{path}: height/length = {ratio:.3} is above {max} (beam `{beam}`): Euler–Bernoulli beam theory no longer holds and the frequencies come out high; is the height in metres?", max = MAX_SLENDERNESS)]
    Slender {
        path: String,
        beam: String,
        ratio: f64,
    },
    #[error("{path}: Young's modulus {value:e} Pa is outside {:e}–{:e} Pa: is the model in SI units?", YOUNG_RANGE.0, YOUNG_RANGE.1)]
    Young { path: String, value: f64 },
    #[error("{path}: density {value} kg/m³ is outside {}–{} kg/m³: is the model in SI units?", DENSITY_RANGE.0, DENSITY_RANGE.1)]
    Density { path: String, value: f64 },
    #[error("{path}: the wave speed √(E/ρ) = {} m/s is outside {}–{} m/s: is the model in SI units?", crate::model::number::significant(*value, 4), WAVE_SPEED_RANGE.0, WAVE_SPEED_RANGE.1)]
    WaveSpeed { path: String, value: f64 },
    #[error("{path}: {part} ({size}) is {} times the size of {other} ({other_size}), joined to it by {by}: are all lengths in metres?", significant(*ratio, 3))]
    Size {
        path: String,
        /// The part reported (`beam `arm``, `rigid body `hub``).
        part: String,
        /// Its size as text (`length 150 m`).
        size: String,
        other: String,
        other_size: String,
        /// The joint or spring (`joints[0]`).
        by: String,
        ratio: f64,
    },
    #[error("{path}: this point is {} m from the centre of {part}, {} times {reference}: is `local` missing, or in other units than metres?", significant(*arm, 3), significant(*ratio, 3))]
    LeverArm {
        path: String,
        part: String,
        /// The distance [SI: m].
        arm: f64,
        /// What it is compared with (`its radius of gyration √(I/m) = 2e-4 m`).
        reference: String,
        ratio: f64,
    },
    #[error("calibrated[{index}]: `{name}` was calibrated to {value:e} ({target}), but the model has {}: it is no longer the calibrated model, and the record is left out of the outputs", match now { Some(v) if v == value => String::from("other numbers than the fitted model elsewhere"), Some(v) => format!("{v:e}"), None => String::from("no number there") })]
    StaleCalibration {
        index: usize,
        name: String,
        value: f64,
        target: String,
        now: Option<f64>,
    },
    #[error("{path}: the spring is {} m long at the reference, {} times the {part_size} of {part} it holds: are all its points in metres?", significant(*length, 3), significant(*ratio, 3))]
    SpringLength {
        /// The spring (`springs[0]`).
        path: String,
        /// Distance between its ends [SI: m].
        length: f64,
        part: String,
        /// The part's size as text (`length 0.3 m`).
        part_size: String,
        ratio: f64,
    },
}

impl UnitWarning {
    /// Whether this is a disagreement of sizes ([`UnitWarning::Size`],
    /// [`UnitWarning::LeverArm`]), which costs the eigen-solve accuracy.
    pub fn is_size(&self) -> bool {
        matches!(
            self,
            UnitWarning::Size { .. }
                | UnitWarning::LeverArm { .. }
                | UnitWarning::SpringLength { .. }
        )
    }
}

fn outside(value: f64, (lo, hi): (f64, f64)) -> bool {
    !(lo..=hi).contains(&value)
}

impl Model {
    /// The unit-sanity warnings of this model (module doc), in the order of
    /// its beams.
    pub fn unit_warnings(&self) -> Vec<UnitWarning> {
        let mut warnings = Vec::new();
        for (i, b) in self.beams.iter().enumerate() {
            let ratio = b.section.height / b.length;
            if ratio > MAX_SLENDERNESS {
                warnings.push(UnitWarning::Slender {
                    path: format!("beams[{i}].section.height"),
                    beam: b.id.clone(),
                    ratio,
                });
            }
            let (e, rho) = (b.material.young, b.material.density);
            let material = format!("beams[{i}].material");
            if outside(e, YOUNG_RANGE) {
                warnings.push(UnitWarning::Young {
                    path: format!("{material}.young"),
                    value: e,
                });
            }
            if outside(rho, DENSITY_RANGE) {
                warnings.push(UnitWarning::Density {
                    path: format!("{material}.density"),
                    value: rho,
                });
            }
            let c = (e / rho).sqrt();
            if outside(c, WAVE_SPEED_RANGE) {
                warnings.push(UnitWarning::WaveSpeed {
                    path: material,
                    value: c,
                });
            }
        }
        warnings.extend(self.size_warnings());
        warnings.extend(
            self.stale_calibrations()
                .into_iter()
                .map(|(index, r, now)| UnitWarning::StaleCalibration {
                    index,
                    name: r.name,
                    value: r.value,
                    target: r.target,
                    now,
                }),
        );
        warnings
    }

    /// The parts whose size or lever arm is over [`MAX_SIZE_RATIO`] times
    /// that of a part they are joined to (module doc): one warning per
    /// part, for its largest ratio, beams first, then rigid bodies.
    pub fn size_warnings(&self) -> Vec<UnitWarning> {
        let mut worst: Vec<Option<UnitWarning>> =
            vec![None; self.beams.len() + self.rigid_bodies.len()];
        let joints = self
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| (format!("joints[{i}]"), &j.a, &j.b, true));
        let springs = self
            .springs
            .iter()
            .enumerate()
            .map(|(i, s)| (format!("springs[{i}]"), &s.a, &s.b, false));
        for (by, a, b, joint) in joints.chain(springs) {
            let (Some(a_end), Some(b_end)) = (
                self.end(a, &format!("{by}.a")),
                self.end(b, &format!("{by}.b")),
            ) else {
                continue;
            };
            for (this, that) in [(&a_end, &b_end), (&b_end, &a_end)] {
                for w in self.end_warnings(this, that, &by, joint) {
                    let k = match this.target {
                        PointTarget::Beam { index, .. } => index,
                        PointTarget::Rigid { index, .. } => self.beams.len() + index,
                        _ => continue,
                    };
                    if worst[k].as_ref().is_none_or(|o| ratio(o) < ratio(&w)) {
                        worst[k] = Some(w);
                    }
                }
            }
        }
        let mut out: Vec<UnitWarning> = worst.into_iter().flatten().collect();
        out.extend(self.spring_length_warnings());
        out
    }

    /// The springs over [`MAX_SIZE_RATIO`] times as long, at the
    /// reference, as the largest part they hold (module doc): a point typed
    /// in millimetres into a metre model (a ground point at 232.8 for
    /// 0.2328) makes a spring hundreds of metres long.
    fn spring_length_warnings(&self) -> Vec<UnitWarning> {
        let mut out = Vec::new();
        for (i, spring) in self.springs.iter().enumerate() {
            let path = format!("springs[{i}]");
            let (Some(a), Some(b)) = (
                self.end(&spring.a, &format!("{path}.a")),
                self.end(&spring.b, &format!("{path}.b")),
            ) else {
                continue;
            };
            let (pa, pb) = (a.target.position_or_centre(), b.target.position_or_centre());
            let length = (pa[0] - pb[0]).hypot(pa[1] - pb[1]);
            let largest = [&a.target, &b.target]
                .into_iter()
                .filter_map(|t| Some((size(t)?, t)))
                .max_by(|x, y| x.0.total_cmp(&y.0));
            let Some((held, target)) = largest else {
                continue;
            };
            let Some((part, _)) = part_name(target) else {
                continue;
            };
            if length > MAX_SIZE_RATIO * held {
                out.push(UnitWarning::SpringLength {
                    path,
                    length,
                    part,
                    part_size: size_text(target, held),
                    ratio: length / held,
                });
            }
        }
        out
    }

    /// A joint's or spring's end, resolved; `None` when it does not
    /// resolve (a model that failed validation).
    fn end<'m>(&'m self, p: &PointSpec, path: &str) -> Option<End<'m>> {
        let target = self.resolve(p, path).ok()?;
        Some(End {
            target,
            path: path.to_string(),
        })
    }

    /// What is wrong with end `this` of `by`, joined to `that`: its size
    /// against `that`'s, its lever arm against its own size and `that`'s.
    fn end_warnings(&self, this: &End, that: &End, by: &str, joint: bool) -> Vec<UnitWarning> {
        let mut out = Vec::new();
        let Some((part, path)) = part_name(&this.target) else {
            return out;
        };
        let own = size(&this.target);
        let other = size(&that.target);
        if let (Some(s), Some(o), Some((other_part, _))) = (own, other, part_name(&that.target)) {
            if s > MAX_SIZE_RATIO * o {
                out.push(UnitWarning::Size {
                    path,
                    part: part.clone(),
                    size: size_text(&this.target, s),
                    other: other_part,
                    other_size: size_text(&that.target, o),
                    by: by.to_string(),
                    ratio: s / o,
                });
            }
        }
        let PointTarget::Rigid { body, local, .. } = this.target else {
            return out;
        };
        // The point: `local`, else in a joint the partner's point, else the
        // centre (no arm).
        let point = match (local, joint) {
            (Some(l), _) => body.point_at(l),
            (None, true) => match that.target.explicit_position() {
                Some(p) => p,
                None => return out,
            },
            (None, false) => return out,
        };
        let arm = (point[0] - body.position[0]).hypot(point[1] - body.position[1]);
        let references = [
            own.map(|s| {
                (
                    s,
                    format!("its radius of gyration √(I/m) = {} m", significant(s, 3)),
                )
            }),
            other.zip(part_name(&that.target)).map(|(o, (name, _))| {
                (
                    o,
                    format!(
                        "the {} of {name} it is joined to",
                        size_text(&that.target, o)
                    ),
                )
            }),
        ];
        let worst = references
            .into_iter()
            .flatten()
            .filter(|(s, _)| arm > MAX_SIZE_RATIO * s)
            .max_by(|x, y| (arm / x.0).total_cmp(&(arm / y.0)));
        if let Some((s, reference)) = worst {
            out.push(UnitWarning::LeverArm {
                path: this.path.clone(),
                part,
                arm,
                reference,
                ratio: arm / s,
            });
        }
        out
    }
}

/// One end of a joint or spring.
struct End<'m> {
    target: PointTarget<'m>,
    /// Its JSON path (`joints[0].b`).
    path: String,
}

/// A part's own size [SI: m]: a beam's length, a rigid body's radius of
/// gyration √(I/m); `None` for a point mass, a rigid body with I = 0 and
/// the ground.
fn size(t: &PointTarget) -> Option<f64> {
    match t {
        PointTarget::Beam { beam, .. } => Some(beam.length),
        PointTarget::Rigid { body, .. } => {
            let r = (body.inertia / body.mass).sqrt();
            (r > 0.0 && r.is_finite()).then_some(r)
        }
        _ => None,
    }
}

/// `length 150 m` or `radius of gyration √(I/m) = 2e-4 m`.
fn size_text(t: &PointTarget, s: f64) -> String {
    let what = match t {
        PointTarget::Beam { .. } => "length",
        _ => "radius of gyration √(I/m) =",
    };
    format!("{what} {} m", significant(s, 3))
}

/// The part a point is on (`beam `arm``) and the JSON path of the value
/// that gives its size; `None` for the ground.
fn part_name(t: &PointTarget) -> Option<(String, String)> {
    match t {
        PointTarget::Beam { beam, index, .. } => Some((
            format!("beam `{}`", beam.id),
            format!("beams[{index}].length"),
        )),
        PointTarget::Rigid { body, index, .. } => Some((
            format!("rigid body `{}`", body.id),
            format!("rigid_bodies[{index}].inertia"),
        )),
        PointTarget::PointMass { mass, index } => Some((
            format!("point mass `{}`", mass.id),
            format!("point_masses[{index}]"),
        )),
        PointTarget::Ground { .. } => None,
    }
}

fn ratio(w: &UnitWarning) -> f64 {
    match w {
        UnitWarning::Size { ratio, .. }
        | UnitWarning::LeverArm { ratio, .. }
        | UnitWarning::SpringLength { ratio, .. } => *ratio,
        _ => 0.0,
    }
}
