//! Value parsers of the command-line flags: the core's shared validation rules
//! ([`tensegrity_core::validate`]) applied at parse time, so a bad flag is a usage error
//! (exit code 2) naming the flag, judged exactly as the same value in a request or a scene.

use tensegrity_core::validate;

fn number(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .map_err(|_| format!("`{s}` is not a number"))
}

fn rule(r: tensegrity_core::Result<f64>) -> Result<f64, String> {
    // the flag is named by clap; keep only the rule
    r.map_err(|e| match e {
        tensegrity_core::CoreError::InvalidParameter(p) => p.reason,
        other => other.to_string(),
    })
}

/// A finite, strictly positive number (lengths, stiffnesses, steps, times).
pub fn positive(s: &str) -> Result<f64, String> {
    rule(validate::positive("value", number(s)?))
}

/// A count of at least 2 (grid points).
pub fn at_least_two(s: &str) -> Result<usize, String> {
    let n: usize = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a whole number"))?;
    validate::count_at_least("value", n, 2).map_err(|_| "must be at least 2".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rules_of_the_core_decide() {
        assert_eq!(positive("2e4"), Ok(2e4));
        assert_eq!(positive("0").unwrap_err(), "must be finite and positive");
        assert!(positive("-1").is_err() && positive("inf").is_err() && positive("nan").is_err());
        assert!(positive("abc").unwrap_err().contains("not a number"));
        assert_eq!(at_least_two("2"), Ok(2));
        assert!(at_least_two("0").is_err() && at_least_two("-1").is_err());
    }
}
