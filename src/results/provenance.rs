//! Provenance of every JSON document and exported file: the tool's version
//! and the SHA-256 of the model it describes (of the file's bytes, or of
//! the built-in model's JSON text).

use sha2::{Digest, Sha256};

/// This build's version (Cargo package version).
pub fn tool_version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

/// Lower-case hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// SHA-256 of the model a command describes: of the file's bytes, or of the
/// built-in model's JSON text when no file is given.
pub fn model_sha256(path: Option<&std::path::Path>) -> std::io::Result<String> {
    model_sha256_or(path, crate::model::DEFAULT_MODEL_JSON)
}

/// As [`model_sha256`], for a command whose built-in model is `builtin`
/// (e.g. `switch-off`'s assembly).
pub fn model_sha256_or(path: Option<&std::path::Path>, builtin: &str) -> std::io::Result<String> {
    Ok(match path {
        Some(p) => sha256_hex(&std::fs::read(p)?),
        None => sha256_hex(builtin.as_bytes()),
    })
}

/// The provenance of an exported file's header: two lines of at most 80
/// characters (UFF ID lines), `ancf-modal VERSION` and
/// `model_sha256 HEX`.
pub fn header_lines(model_sha256: &str) -> [String; 2] {
    [
        format!("ancf-modal {}", tool_version()),
        format!("model_sha256 {model_sha256}"),
    ]
}

/// The current time in UTC, ISO 8601 to the second
/// (`2026-11-25T11:52:50Z`); with `SOURCE_DATE_EPOCH` set to whole seconds
/// since 1970 (the reproducible-builds convention), that time instead, so
/// that two runs can write the same bytes.
pub fn utc_now() -> String {
    let fixed = std::env::var("SOURCE_DATE_EPOCH")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok());
    let secs = fixed.unwrap_or_else(|| {
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs())
    });
    utc_timestamp(secs)
}

/// Seconds since 1970-01-01T00:00:00Z as ISO 8601 (proleptic Gregorian
/// calendar; the civil-from-days conversion of H. Hinnant's date
/// algorithms).
pub fn utc_timestamp(secs: u64) -> String {
    let (days, rest) = ((secs / 86_400) as i64, secs % 86_400);
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}

#[cfg(test)]
mod tests {
    use super::utc_timestamp;

    #[test]
    fn timestamps_match_known_dates() {
        assert_eq!(utc_timestamp(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 (a leap day of a century leap year), 12:34:56.
        assert_eq!(utc_timestamp(951_827_696), "2000-02-29T12:34:56Z");
        // 2026-11-25T00:00:00Z = 20 782 days after the epoch.
        assert_eq!(utc_timestamp(20_782 * 86_400), "2026-11-25T00:00:00Z");
    }
}
