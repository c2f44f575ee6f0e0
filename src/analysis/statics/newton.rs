//! Newton's method at one load level: the damped iteration on the
//! equilibrium residual and the constraints, and the reduced tangent it
//! solves with at each step (the module doc of [`super`] gives the
//! equations and units).

use super::*;

impl Solver<'_> {
    /// Newton iterations at the state's load level; returns the iteration count.
    ///
    /// [`Damping::Full`] takes whole Newton steps: a slender beam's
    /// transverse Newton step stretches its axis to second order and
    /// multiplies ‖r‖ by EA/P for one iteration, yet the next step (with the
    /// tangent there, which carries that axial force geometrically) recovers
    /// quadratically; any merit function along the straight step would
    /// reject it. [`Damping::LineSearch`] backtracks on the merit
    /// ‖r‖ + ‖C‖/length (Armijo), for problems where whole steps overshoot
    /// (rigid rotations, mechanisms with springs); the continuation tries it
    /// before it cuts the load increment. `contacts` says which contacts'
    /// regularizing stiffness the Newton matrix gets (see
    /// [`crate::mechanics::contact::ContactElement::regularization`]). A
    /// stall says whether every iterate's Newton matrix would have been the
    /// same with the regularization `also` (then a solve with it repeats
    /// this one).
    pub(crate) fn newton(
        &self,
        state: &mut State,
        mode: Damping,
        contacts: Regularize,
        also: Option<Regularize>,
    ) -> Result<usize, NewtonFailure> {
        let (g, l) = (state.gravity, state.loads);
        let mut snap = self.snapshot(&state.q, g, l);
        let f_ref = self.force_reference(&snap, &state.q, g, l);
        let c_tol = 1e-11 * self.length;
        let mut iterations = 0;
        // Whether the reduced tangent's eigenvalues were found clear of
        // zero in this solve.
        let mut clear = false;
        let mut repeats = also.is_some();
        loop {
            let r = norm_inf(&snap.r);
            if norm_inf(&snap.c) <= c_tol && r <= self.settings.tolerance * f_ref {
                break;
            }
            if iterations >= self.settings.max_iterations {
                return Err(NewtonFailure::Stalled {
                    iterations,
                    residual: r,
                    repeats,
                });
            }
            iterations += 1;
            repeats = repeats
                && also.is_some_and(|b| {
                    self.system
                        .contacts_regularized_alike(&state.q, contacts, b)
                });
            let step = self.tangent_solver(&state.q, &snap, l, contacts, &mut clear)?;
            let dq = step.correction(&snap, f_ref, true, self)?;
            let size = self.scaled_norm(&dq);
            let mut alpha = 1.0;
            let mut accepted = None;
            while alpha >= 1.0 / 1024.0 {
                let trial: Vec<f64> = state
                    .q
                    .iter()
                    .zip(&dq)
                    .map(|(q, d)| q + alpha * d)
                    .collect();
                let s = self.snapshot(&trial, g, l);
                let ok = match mode {
                    Damping::Full => s.merit.is_finite(),
                    Damping::LineSearch => s.merit < (1.0 - 1e-4 * alpha) * snap.merit,
                };
                if ok || size <= 1e-10 {
                    accepted = Some((trial, s));
                    break;
                }
                alpha *= 0.5;
            }
            let Some((q, s)) = accepted else {
                return Err(NewtonFailure::Stalled {
                    iterations,
                    residual: r,
                    repeats,
                });
            };
            state.q = q;
            snap = s;
            if alpha == 1.0 && size <= 1e-10 && norm_inf(&snap.c) <= c_tol {
                break;
            }
        }
        state.lambda.clone_from(&snap.lambda);
        state.iterations += iterations;
        state.residual = norm_inf(&snap.r);
        state.violation = norm_inf(&snap.c);
        Ok(iterations)
    }

    /// max |Δq_i| / scale_i.
    fn scaled_norm(&self, dq: &[f64]) -> f64 {
        dq.iter()
            .zip(&self.scales)
            .map(|(d, s)| (d / s).abs())
            .fold(0.0, f64::max)
    }

    /// The tangent at q with the snapshot's multipliers, reduced and factored.
    ///
    /// A small reduced tangent that is not definite is factored by LU when
    /// its eigenvalues are clear of zero ([`Solver::nonsingular_lu`]), by
    /// its modes otherwise (a mechanism: a motion without stiffness, which
    /// the constraints' layout gives at every iterate alike). The
    /// eigenvalues cost several times the LU: once they were clear in a
    /// Newton solve (`clear`), its next iterations take the LU without
    /// them. A solve that meets a tangent turning singular (a limit point)
    /// stalls and the continuation retries it with a shorter increment or
    /// another mode, each retry starting with the test again; the
    /// converged states' stability is checked on its own
    /// ([`Solver::lowest_mode`]).
    fn tangent_solver(
        &self,
        q: &[f64],
        snap: &Snapshot,
        loads: f64,
        contacts: Regularize,
        clear: &mut bool,
    ) -> Result<TangentSolver, NewtonFailure> {
        let sys = self.system;
        let n = sys.ndof();
        let at = Linearization {
            q,
            lambda: Some(&snap.lambda),
            time: self.settings.time,
            load_scale: loads,
        };
        let mut k = Triplets::new(n, n);
        sys.add_tangent_stiffness(&at, &mut k);
        sys.add_contact_regularization(q, contacts, &mut k);
        let d = snap.ns.dim();
        let factor = if d == 0 {
            Factor::Empty
        } else if d > crate::analysis::modal::DENSE_MAX {
            let mut kr = Triplets::new(d, d);
            project(&k, &snap.ns, &mut kr);
            // Large: the reduced tangent stays sparse; Cholesky when it is
            // definite, LU past a loss of stability (the stability check
            // then finds the critical load), an error when it is singular
            // (a mechanism: only the dense path resolves its free motion).
            let sparse = kr.to_sparse();
            match sparse.sp_cholesky(Side::Lower) {
                Ok(llt) => Factor::Sparse(llt),
                Err(_) => match sparse.sp_lu() {
                    Ok(lu) => Factor::SparseLu(Box::new(lu)),
                    Err(_) => {
                        return Err(NewtonFailure::Fatal(
                            AnalysisError::IndefiniteLargeTangent {
                                size: d,
                                max: crate::analysis::modal::DENSE_MAX,
                            },
                        ))
                    }
                },
            }
        } else {
            let mut kr = Mat::zeros(d, d);
            project(&k, &snap.ns, &mut kr);
            symmetrize(&mut kr);
            if let Some(llt) = definite_factor(&kr) {
                Factor::Cholesky(llt)
            } else if *clear {
                Factor::Lu(kr.partial_piv_lu())
            } else if let Some(lu) = self.nonsingular_lu(&kr, &snap.ns) {
                *clear = true;
                Factor::Lu(lu)
            } else {
                Factor::Modes(
                    self.reduced_modes(&kr, &snap.ns)
                        .map_err(NewtonFailure::Fatal)?,
                )
            }
        };
        Ok(TangentSolver {
            k: k.to_sparse(),
            ns: snap.ns.clone(),
            factor,
        })
    }
}

/// NᵀKN added into `out` from K's entries as assembled, in their order: the
/// same sums as projecting the assembly itself, without a second assembly.
fn project(k: &Triplets, ns: &NullSpace, out: &mut impl Scatter) {
    let mut p = Projected::new(ns, out);
    k.entries().for_each(|(i, j, v)| p.add(i, j, v));
}
