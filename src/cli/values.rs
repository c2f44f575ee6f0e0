//! Number parsers for flag values. Each one accepts a negative number as a
//! value (the flags that use them set `allow_hyphen_values`), so a wrong
//! sign is reported as a range error, not as an unknown argument; `main`
//! prints the flag, the value given and the message on one line:
//! ``Error: --step `-1e-6`: must be a number > 0`` (exit code 1).

/// A number > 0 (finite).
pub fn positive(s: &str) -> Result<f64, String> {
    let v = super::args::finite(s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(String::from("must be a number > 0"))
    }
}

/// A number ≥ 0 (finite).
pub fn non_negative(s: &str) -> Result<f64, String> {
    let v = super::args::finite(s)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(String::from("must be a number ≥ 0"))
    }
}

/// A number from 0 to 1, both included (a spectral radius).
pub fn unit_interval(s: &str) -> Result<f64, String> {
    let v = super::args::finite(s)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(String::from("must be a number from 0 to 1"))
    }
}

/// A finite non-zero number (a force amplitude, either sign).
pub fn non_zero(s: &str) -> Result<f64, String> {
    let v = super::args::finite(s)?;
    if v != 0.0 {
        Ok(v)
    } else {
        Err(String::from("must be a non-zero number"))
    }
}

/// A whole number in `min..=max` (`max` = `None`: no upper bound), the
/// range stated in words.
pub fn whole(s: &str, min: u64, max: Option<u64>) -> Result<u64, String> {
    let range = match max {
        Some(max) => format!("a whole number from {min} to {max}"),
        None => format!("a whole number ≥ {min}"),
    };
    let v: u64 = s.trim().parse().map_err(|_| format!("must be {range}"))?;
    if v < min || max.is_some_and(|m| v > m) {
        return Err(format!("must be {range}"));
    }
    Ok(v)
}

/// [`whole`] ≥ 1 (a count of modes, threads).
pub fn at_least_one(s: &str) -> Result<u64, String> {
    whole(s, 1, None)
}

/// [`at_least_one`] as a `usize`.
pub fn at_least_one_usize(s: &str) -> Result<usize, String> {
    let v = at_least_one(s)?;
    usize::try_from(v).map_err(|_| String::from("must be a whole number ≥ 1 that fits memory"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_stated_in_words() {
        assert_eq!(
            whole("0", 1, None).unwrap_err(),
            "must be a whole number ≥ 1"
        );
        assert_eq!(
            whole("300", 2, Some(256)).unwrap_err(),
            "must be a whole number from 2 to 256"
        );
        assert_eq!(whole("7", 1, Some(10)), Ok(7));
        assert!(positive("-1e-6").unwrap_err().contains("> 0"));
        assert!(unit_interval("1.5").unwrap_err().contains("from 0 to 1"));
        assert_eq!(unit_interval("1"), Ok(1.0));
        assert_eq!(non_negative("0"), Ok(0.0));
    }
}
