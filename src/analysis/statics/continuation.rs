//! Load stepping (continuation): a ramp of gravity's fraction or of the
//! applied-load factor, in adaptive increments, each solved by Newton's
//! method ([`super::newton`]) from the last converged state (the module
//! doc of [`super`] gives the equations and units).
//!
//! **Step control.** An increment that converged in at most 4 Newton
//! iterations doubles the next one; one that stalled in every Newton mode
//! ([`NEWTON_MODES`]) is quartered, down to
//! [`StaticSettings::min_increment`](super::StaticSettings).
//!
//! **No repeated solves.** The modes differ in their damping and in which
//! contacts the Newton matrix regularizes. A stalled solve whose every
//! iterate would have had the same Newton matrix under a later mode's
//! regularization (the same contacts open, closed and barely closed) is
//! what that mode's solve would be, step by step: it is not solved again.
//!
//! **A ramp starts from an equilibrium.** Cutting the increment brings the
//! target towards the ramp's start; that helps only when the start is an
//! equilibrium, or is near one. When the first increment stalls, the
//! start's own level is solved (it converges at once when the start is an
//! equilibrium): when no equilibrium is found there either (a pre-stressed
//! mechanism that only its loads hold, under gravity alone), the ramp
//! fails there instead of cutting the increment down to its smallest. The
//! state found at the start level is not kept: the ramp goes on from where
//! it started, as it would without the check.

use super::{Damping, NewtonFailure, Ramp, Solver, State, CONFIRM_STEP};
use crate::error::{AnalysisError, LoadPath};
use crate::mechanics::contact::Regularize;

/// The Newton solves a load step tries, in turn, while the previous one
/// stalls: whole steps, then a line search, then a line search with the
/// closed contacts' exact tangents (a stiff contact closed at a small
/// force, where the regularized matrix converges only linearly), then,
/// where there are contacts, whole steps with the open contacts far from
/// touching left unregularized (their regularization can swamp a soft
/// structure's stiffness); that last solve's outcome counts only when it
/// converges.
const NEWTON_MODES: [(Damping, Regularize); 4] = [
    (Damping::Full, Regularize::OpenOnly),
    (Damping::LineSearch, Regularize::OpenOnly),
    (Damping::LineSearch, Regularize::OpenAndBarelyClosed),
    (Damping::Full, Regularize::NearOnly),
];

impl Solver<'_> {
    /// Ramp gravity (to fraction `target`) or the applied loads (to factor
    /// `target`) with adaptive increments.
    ///
    /// `path` is the load path the ramp is part of (for the messages).
    pub(crate) fn ramp(
        &self,
        state: &mut State,
        which: Ramp,
        target: f64,
        path: LoadPath,
    ) -> Result<(), AnalysisError> {
        let start = which.param(state);
        let span = target - start;
        let at = |t: f64| start + t * span;
        let mut t = 0.0;
        let mut dt = self.settings.initial_increment.clamp(1e-12, 1.0);
        let mut tried = 0usize;
        let mut first = true;
        let mut start_checked = false;
        while first || t < 1.0 {
            first = false;
            tried += 1;
            let t_try = (t + dt).min(1.0);
            let (trial, outcome) = self.solve_at(state, which, at(t_try));
            match outcome {
                Ok(iterations) => {
                    let mut trial = trial;
                    trial.steps += 1;
                    if self.settings.check_stability {
                        if let Some(low) = self.indefinite(&trial)? {
                            // Confirmed only from a short step: a long one
                            // may have jumped to another branch.
                            if span != 0.0
                                && t_try - t > CONFIRM_STEP
                                && tried < self.settings.max_steps
                            {
                                dt = 0.25 * (t_try - t);
                                continue;
                            }
                            return Err(self.locate_instability(state, &trial, low, which, path));
                        }
                    }
                    *state = trial;
                    t = t_try;
                    if iterations <= 4 {
                        dt = (2.0 * dt).min(1.0);
                    }
                }
                Err(NewtonFailure::Fatal(e)) => return Err(e),
                Err(NewtonFailure::Stalled {
                    iterations,
                    residual,
                    ..
                }) => {
                    dt *= 0.25;
                    // With nothing to ramp a smaller increment changes
                    // nothing: the state did not converge where it is.
                    if span == 0.0
                        || dt < self.settings.min_increment
                        || tried >= self.settings.max_steps
                    {
                        return Err(AnalysisError::NotConverged {
                            load_factor: which.load_factor(at(t_try)),
                            iterations,
                            residual,
                        });
                    }
                    if t == 0.0 && !start_checked {
                        start_checked = true;
                        // Smaller increments lead towards the start: no
                        // equilibrium there, none on the way (module doc).
                        if let (_, Err(failure)) = self.solve_at(state, which, at(0.0)) {
                            return Err(match failure {
                                NewtonFailure::Fatal(e) => e,
                                NewtonFailure::Stalled {
                                    iterations,
                                    residual,
                                    ..
                                } => AnalysisError::NotConverged {
                                    load_factor: which.load_factor(at(0.0)),
                                    iterations,
                                    residual,
                                },
                            });
                        }
                    }
                }
            }
            if span == 0.0 {
                break;
            }
        }
        Ok(())
    }

    /// Newton's method from `state` with ramp `which`'s parameter at
    /// `value`, in each of [`NEWTON_MODES`] in turn until one does not
    /// stall; the state it ended in and its outcome (a stall: the last
    /// counted mode's).
    fn solve_at(
        &self,
        state: &State,
        which: Ramp,
        value: f64,
    ) -> (State, Result<usize, NewtonFailure>) {
        let mut trial = state.clone();
        let mut outcome = Err(NewtonFailure::Stalled {
            iterations: 0,
            residual: f64::INFINITY,
            repeats: false,
        });
        // Modes a stalled solve showed would repeat it (module doc).
        let mut repeated: Vec<(Damping, Regularize)> = Vec::new();
        for (i, &(damping, contacts)) in NEWTON_MODES.iter().enumerate() {
            let last = contacts == Regularize::NearOnly;
            if last && self.system.contacts.is_empty() {
                break;
            }
            if repeated.contains(&(damping, contacts)) {
                if last {
                    break;
                }
                continue;
            }
            // The next mode with the same damping: would it repeat this one?
            let also = NEWTON_MODES[i + 1..]
                .iter()
                .find(|(d, _)| *d == damping)
                .map(|&(_, c)| c);
            let mut attempt = state.clone();
            which.set(&mut attempt, value);
            let result = self.newton(&mut attempt, damping, contacts, also);
            if let (Err(NewtonFailure::Stalled { repeats: true, .. }), Some(c)) = (&result, also) {
                repeated.push((damping, c));
            }
            if last && result.is_err() {
                break;
            }
            (trial, outcome) = (attempt, result);
            if !matches!(outcome, Err(NewtonFailure::Stalled { .. })) {
                break;
            }
        }
        (trial, outcome)
    }
}
