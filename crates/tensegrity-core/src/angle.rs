//! Angles as every front end writes them (DESIGN.md): `22.5deg`, `pi/8`, `3pi/4`, `-pi/4`,
//! `pi`, `2*pi/3`, or a bare number in radians (`0.5`). The command-line flags, the sweep
//! specs, the Python keywords and the requests' serde form all read angles here, so a value
//! means the same wherever it is written.
//!
//! [`serde_angle`] and [`serde_angle_option`] deserialise an angle field from a number
//! (radians) or a string in these forms; it serialises as the number in radians.

use std::f64::consts::PI;
use thiserror::Error;

/// An angle that [`parse_angle`] cannot read; the text is kept as written.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum AngleError {
    /// Not one of the accepted forms (or not finite).
    #[error("invalid angle \"{text}\": expected e.g. `22.5deg`, `pi/8`, `3pi/4`, `-pi/4` or radians `0.5`")]
    Malformed {
        /// The text given.
        text: String,
    },
    /// A `pi/d` form with d = 0.
    #[error("invalid angle \"{text}\": division by zero")]
    DivisionByZero {
        /// The text given.
        text: String,
    },
}

/// Parses an angle and returns it in radians.
///
/// Accepted forms: `<x>deg` (degrees), `[<k>][*]pi[/<d>]` with an optional sign (k·π/d), and
/// a bare number (radians). Non-finite values and zero denominators are rejected.
pub fn parse_angle(s: &str) -> Result<f64, AngleError> {
    let bad = || AngleError::Malformed {
        text: s.to_string(),
    };
    let number = |t: &str| -> Result<f64, AngleError> {
        let t = t.trim();
        // Rust parses "inf"/"nan"; an angle must be a plain finite number.
        if t.is_empty()
            || t.chars()
                .any(|c| c.is_ascii_alphabetic() && c != 'e' && c != 'E')
        {
            return Err(bad());
        }
        t.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(bad)
    };
    let t = s.trim().to_ascii_lowercase();
    if t.is_empty() {
        return Err(bad());
    }
    let value = if let Some(deg) = t.strip_suffix("deg") {
        number(deg)?.to_radians()
    } else if let Some(at) = t.find("pi") {
        let coef = t[..at].trim().trim_end_matches('*').trim();
        let k = match coef {
            "" | "+" => 1.0,
            "-" => -1.0,
            c => number(c)?,
        };
        let rest = t[at + 2..].trim();
        let d = if rest.is_empty() {
            1.0
        } else {
            let d = number(rest.strip_prefix('/').ok_or_else(bad)?)?;
            if d == 0.0 {
                return Err(AngleError::DivisionByZero {
                    text: s.to_string(),
                });
            }
            d
        };
        k * PI / d
    } else {
        number(&t)?
    };
    if value.is_finite() {
        Ok(value)
    } else {
        Err(bad())
    }
}

/// `#[serde(with = "tensegrity_core::angle::serde_angle")]`: an `f64` angle read from radians or
/// from any form [`parse_angle`] accepts, written in radians.
///
/// ```
/// #[derive(serde::Deserialize)]
/// struct Slope {
///     #[serde(with = "tensegrity_core::angle::serde_angle")]
///     incline: f64,
/// }
/// let s: Slope = serde_json::from_str(r#"{"incline": "30deg"}"#).unwrap();
/// assert!((s.incline - 30f64.to_radians()).abs() < 1e-15);
/// let s: Slope = serde_json::from_str(r#"{"incline": 0.5}"#).unwrap();
/// assert_eq!(s.incline, 0.5);
/// ```
pub mod serde_angle {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes the angle in radians.
    pub fn serialize<S: Serializer>(value: &f64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(*value)
    }

    /// Reads radians or an angle string.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        match super::AngleValue::deserialize(d)? {
            super::AngleValue::Number(x) => Ok(x),
            super::AngleValue::Text(t) => super::parse_angle(&t).map_err(serde::de::Error::custom),
        }
    }
}

/// As [`serde_angle`], for an optional angle (`null` or absent is `None`).
pub mod serde_angle_option {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes the angle in radians, or `null`.
    pub fn serialize<S: Serializer>(value: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        match value {
            Some(x) => s.serialize_some(x),
            None => s.serialize_none(),
        }
    }

    /// Reads `null`, radians or an angle string.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        match Option::<super::AngleValue>::deserialize(d)? {
            None => Ok(None),
            Some(super::AngleValue::Number(x)) => Ok(Some(x)),
            Some(super::AngleValue::Text(t)) => super::parse_angle(&t)
                .map(Some)
                .map_err(serde::de::Error::custom),
        }
    }
}

#[derive(serde::Deserialize)]
#[serde(untagged)]
enum AngleValue {
    Number(f64),
    Text(String),
}

#[cfg(test)]
mod tests {
    use super::parse_angle;
    use std::f64::consts::PI;

    fn close(s: &str, want: f64) {
        let got = parse_angle(s).unwrap_or_else(|e| panic!("{s}: {e}"));
        assert!((got - want).abs() < 1e-15, "{s}: {got} vs {want}");
    }

    #[test]
    fn accepted_forms() {
        close("22.5deg", PI / 8.0);
        close("-45deg", -PI / 4.0);
        close(" 90 deg ", PI / 2.0);
        close("pi", PI);
        close("-pi", -PI);
        close("pi/8", PI / 8.0);
        close("3pi/4", 3.0 * PI / 4.0);
        close("-pi/4", -PI / 4.0);
        close("2*pi/3", 2.0 * PI / 3.0);
        close("0.5pi", PI / 2.0);
        close("PI/2", PI / 2.0);
        close("0.5", 0.5);
        close("-1.25", -1.25);
        close("1e-1", 0.1);
        close("0", 0.0);
    }

    #[test]
    fn errors_keep_the_text_and_name_the_problem() {
        assert_eq!(
            parse_angle("pi/0"),
            Err(super::AngleError::DivisionByZero {
                text: "pi/0".into()
            })
        );
        let e = parse_angle("north").unwrap_err();
        assert!(e
            .to_string()
            .starts_with("invalid angle \"north\": expected e.g."));
    }

    #[test]
    fn rejected_forms() {
        for s in [
            "", "deg", "abc", "pi/0", "pi/", "pi*2", "3pi4", "inf", "nan", "-inf", "1e999",
            "22.5rad", "pi/x", "1/2",
        ] {
            let e = parse_angle(s).expect_err(s);
            assert!(e.to_string().contains("invalid angle"), "{s}: {e}");
        }
    }
}
