//! The range checks of the settings every integrating command takes
//! (`impulse`, `identify`, `transient`, `switch-off`): each names the
//! request's field (`end_time`), which the front ends show as their flag
//! or keyword.

use super::CommandError;

/// `end_time` [s] and `step` [s]: both finite and positive, and the run
/// at least one step long.
pub fn time_span(end_time: f64, step: f64) -> Result<(), CommandError> {
    positive("end_time", end_time)?;
    positive("step", step)?;
    if end_time <= step {
        return Err(CommandError::argument(
            "end_time",
            end_time,
            format!("must be longer than one step ({step} s)"),
        ));
    }
    Ok(())
}

/// A finite number > 0.
pub fn positive(name: &'static str, v: f64) -> Result<(), CommandError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(CommandError::argument(name, v, "must be a number > 0"))
    }
}

/// The generalized-α spectral radius ρ∞ [–], 0 … 1.
pub fn spectral_radius(rho: f64) -> Result<(), CommandError> {
    if (0.0..=1.0).contains(&rho) {
        Ok(())
    } else {
        Err(CommandError::argument(
            "spectral_radius",
            rho,
            "must be a number from 0 to 1",
        ))
    }
}

/// A sensor's sample rate [Hz], 0 for every step.
pub fn sample_rate(rate: f64) -> Result<(), CommandError> {
    if rate.is_finite() && rate >= 0.0 {
        Ok(())
    } else {
        Err(CommandError::argument(
            "sample_rate",
            rate,
            "must be a number ≥ 0",
        ))
    }
}

/// A sensor's sample rate [Hz] that the integration's `step` [s] can
/// give: at most 1/step, or 0 for every step.
pub fn sample_rate_for_step(rate: f64, step: f64) -> Result<(), CommandError> {
    sample_rate(rate)?;
    if rate * step > 1.0 + 1e-12 {
        return Err(CommandError::argument(
            "sample_rate",
            rate,
            format!(
                "must be at most 1/step = {} Hz (or 0 to record every step)",
                crate::model::number::significant(1.0 / step, 6)
            ),
        ));
    }
    Ok(())
}

/// `modes` [–] ≥ 1 and `load_scale` [–] finite: the checks of the
/// commands that linearize (`modal`, `reduce`).
pub fn modes_and_load_scale(modes: usize, load_scale: f64) -> Result<(), CommandError> {
    if modes < 1 {
        return Err(CommandError::argument(
            "modes",
            modes,
            "must be a whole number ≥ 1",
        ));
    }
    if !load_scale.is_finite() {
        return Err(CommandError::argument(
            "load_scale",
            load_scale,
            "must be a finite number",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_shorter_than_its_step_names_the_end_time() {
        let e = time_span(1e-6, 1e-5).unwrap_err();
        assert!(
            matches!(
                e,
                CommandError::Argument {
                    name: "end_time",
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string().contains("longer than one step (0.00001 s)"),
            "{e}"
        );
        assert!(time_span(2e-5, 1e-5).is_ok());
        for (end, step, name) in [(0.0, 1e-6, "end_time"), (1.0, f64::NAN, "step")] {
            let e = time_span(end, step).unwrap_err();
            assert!(
                matches!(e, CommandError::Argument { name: n, .. } if n == name),
                "{e}"
            );
        }
    }
}
