//! Which modes a sensor sees.
//!
//! A sensor reads one material point along one direction. A mode whose
//! shape does not move that point along that direction leaves no peak in
//! its record, whatever the hammer does: a slider does not move in a
//! coupler's symmetric bending, a sensor on a node line of a plate-like
//! mode reads nothing of it. The impulse then finds the nearest other peak
//! in the band of the mode and reports it as the mode.
//!
//! The sensor's sight of a mode φ is the reading of its velocity channel at
//! the state struck with the velocities φ (the linear part of every
//! quantity and frame a sensor has: displacement, velocity and
//! acceleration of a mode differ by factors ω and ω²), relative to the
//! mode's largest translation at a node, a rigid body's centre or a point
//! mass [–]. Below [`BLIND_RATIO`] the sensor is blind to the mode, and the
//! point of that largest translation, with its direction, would see it.
//!
//! The hammer's reach of a mode is its sight from the other end: the work
//! of the hammer's forces (their amplitudes) on the mode's motion, φᵀQ,
//! over the forces' magnitude times the mode's largest translation [–]. A
//! hammer at mid-span of a symmetric portal does not excite its sway mode
//! (reach ~1e-16), and a sensor that sees the sway then records the next
//! peak in the band (the trial's portal: 21.9 Hz reported for 11.2 Hz, with
//! no word). Below [`BLIND_RATIO`] the mode is not identified either, and
//! the same point would be the place to strike.

use super::sensor::SensorProbe;
use crate::analysis::transient::State;
use crate::mechanics::load::PointLoad;
use crate::model::SensorQuantity;
use crate::system::System;

/// A sensor that reads less than this fraction of a mode's largest
/// translation does not see the mode [–].
pub const BLIND_RATIO: f64 = 1e-3;

/// A sensor's sight of one mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Sight {
    /// The sensor's reading of the mode over the mode's largest
    /// translation [–] (about 1 at the antinode, 0 on a node line).
    pub ratio: f64,
    /// Where the mode moves most: "beam `coupler` at s = 5.000e-2 m",
    /// "rigid body `mass` (its centre)", "point mass `tip`".
    pub best_point: String,
    /// The unit direction it moves there (global frame).
    pub best_direction: [f64; 2],
    /// The hammer's reach of the mode (module doc) [–]: about 1 struck at
    /// the antinode along its motion, 0 on a node or across the motion.
    pub reach: f64,
}

impl Sight {
    /// Whether the sensor does not see the mode.
    pub fn sensor_blind(&self) -> bool {
        self.ratio.is_nan() || self.ratio < BLIND_RATIO
    }

    /// Whether the hammer does not excite the mode.
    pub fn out_of_reach(&self) -> bool {
        self.reach.is_nan() || self.reach < BLIND_RATIO
    }

    /// Whether the record cannot show the mode: the sensor does not see it
    /// or the hammer does not excite it.
    pub fn blind(&self) -> bool {
        self.sensor_blind() || self.out_of_reach()
    }
}

/// The sight of the mode `shape` (full coordinates) by `probe`, and its
/// reach by the `hammer` loads, at the state struck `q`.
pub fn sight(
    system: &System,
    probe: &SensorProbe,
    hammer: &[&PointLoad],
    q: &[f64],
    shape: &[f64],
) -> Sight {
    let n = q.len();
    let state = State {
        t: 0.0,
        q: q.to_vec(),
        v: shape.to_vec(),
        a: vec![0.0; n],
        abar: vec![0.0; n],
        lambda: Vec::new(),
    };
    let seen = probe.read_as(&state, SensorQuantity::Velocity).abs();
    let mut best = (0.0f64, String::new(), [0.0, 0.0]);
    let mut consider = |i: usize, label: &dyn Fn() -> String| {
        let (x, y) = (shape[i], shape[i + 1]);
        let amp = x.hypot(y);
        if amp > best.0 {
            best = (amp, label(), [x / amp, y / amp]);
        }
    };
    for b in &system.beams {
        for (k, &s) in b.node_s.iter().enumerate() {
            consider(b.dof0 + 4 * k, &|| {
                format!("beam `{}` at s = {s:.4e} m", b.id)
            });
        }
    }
    for r in &system.rigid_bodies {
        consider(r.dof0, &|| format!("rigid body `{}` (its centre)", r.id));
    }
    for p in &system.point_masses {
        consider(p.dof0, &|| format!("point mass `{}`", p.id));
    }
    let ratio = if best.0 > 0.0 { seen / best.0 } else { 0.0 };
    let mut force = vec![0.0; n];
    for l in hammer {
        l.add_amplitude_force(q, &mut force);
    }
    let work: f64 = force.iter().zip(shape).map(|(f, v)| f * v).sum();
    let magnitude: f64 = hammer.iter().map(|l| l.force.norm()).sum();
    let reach = if best.0 > 0.0 && magnitude > 0.0 {
        work.abs() / (magnitude * best.0)
    } else {
        0.0
    };
    Sight {
        ratio,
        best_point: best.1,
        best_direction: best.2,
        reach,
    }
}
