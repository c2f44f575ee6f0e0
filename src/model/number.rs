//! Numbers for people: a value rounded to the digits that carry meaning.
//! A sample rate computed as 1/Δt from a record's time column
//! (10239.999999359983 Hz) is 10240 Hz to the precision of its source.

/// `value` rounded to `digits` significant digits and printed in the
/// shortest form that reads back as the rounded value (no trailing zeros,
/// no exponent): 10239.999999359983 → `10240`, 51200 → `51200`.
pub fn significant(value: f64, digits: usize) -> String {
    if !value.is_finite() || value == 0.0 {
        return format!("{value}");
    }
    let digits = digits.clamp(1, 17);
    let rounded: f64 = format!("{:.*e}", digits - 1, value)
        .parse()
        .unwrap_or(value);
    format!("{rounded}")
}

#[cfg(test)]
mod tests {
    use super::significant;

    #[test]
    fn rounds_to_significant_digits() {
        assert_eq!(significant(10239.999999359983, 7), "10240");
        assert_eq!(significant(51200.0, 7), "51200");
        assert_eq!(significant(0.1 + 0.2, 7), "0.3");
        assert_eq!(significant(-1234.5678, 3), "-1230");
        assert_eq!(significant(0.0, 7), "0");
    }
}
