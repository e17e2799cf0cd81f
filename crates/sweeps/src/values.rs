//! A case's values as JSON ([`serde_json::Value`]), as every request reads them
//! ([`tensegrity_core::request::Request::from_values`]): a spec gives TOML scalars — integers,
//! floats, strings (`"pi/8"`, `"30deg"`, `"spokes,inner"`, `"rigid"`) and booleans — exactly as
//! the single-point command's flag takes them, and each is read by its parameter's
//! [`Kind`](tensegrity_core::request::Kind) ([`Param::normalize`]) when the case runs.
//!
//! A non-finite float (`nan`, `inf`, or a derived value such as `pi / 0`) has no JSON number:
//! it is kept as its text, which every numeric kind refuses as not finite.

use crate::error::{Result, SweepError};
use serde_json::Value;
use tensegrity_core::request::{InvalidParameter, Param};

impl From<InvalidParameter> for SweepError {
    fn from(e: InvalidParameter) -> Self {
        SweepError::InvalidValue {
            name: e.name.into_owned(),
            value: e.value,
            reason: e.reason,
        }
    }
}

/// A number as JSON (a non-finite one as its text).
pub fn number(x: f64) -> Value {
    serde_json::Number::from_f64(x).map_or_else(|| Value::String(x.to_string()), Value::Number)
}

/// The value of a TOML scalar (and, with `lists`, of an array of scalars); `None` for tables,
/// dates and (without `lists`) arrays.
pub fn from_toml(v: &toml::Value, lists: bool) -> Option<Value> {
    Some(match v {
        toml::Value::Integer(i) => Value::from(*i),
        toml::Value::Float(x) => number(*x),
        toml::Value::String(s) => Value::String(s.clone()),
        toml::Value::Boolean(b) => Value::Bool(*b),
        toml::Value::Array(items) if lists => Value::Array(
            items
                .iter()
                .map(|i| from_toml(i, false))
                .collect::<Option<_>>()?,
        ),
        _ => return None,
    })
}

/// The value written out: numbers in Rust's shortest round-trip form, strings as they are,
/// lists comma-separated.
pub fn written(v: &Value) -> String {
    match v {
        Value::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.to_string(),
            (None, Some(x)) => x.to_string(),
            _ => n.to_string(),
        },
        Value::String(s) => s.clone(),
        Value::Array(items) => items.iter().map(written).collect::<Vec<_>>().join(","),
        other => other.to_string(),
    }
}

/// The numeric value of `v` read as parameter `p` (angles in radians): what derived rules
/// compute with.
pub fn numeric(p: &Param, v: &Value) -> Result<f64> {
    let x = p.normalize(v)?;
    x.as_f64()
        .ok_or_else(|| SweepError::from(InvalidParameter::raw(p.name, written(v), "not a number")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn toml_scalars_become_json_and_are_written_as_given() {
        let t: toml::Table =
            toml::from_str("a = 8\nb = 0.5\nc = \"30deg\"\nd = true\ne = nan\nf = [1, 2]").unwrap();
        let v = |k: &str, lists| from_toml(&t[k], lists);
        assert_eq!(v("a", false), Some(json!(8)));
        assert_eq!(v("b", false), Some(json!(0.5)));
        assert_eq!(v("c", false), Some(json!("30deg")));
        assert_eq!(v("d", false), Some(json!(true)));
        assert_eq!(v("e", false), Some(json!("NaN")));
        assert_eq!(v("f", false), None);
        assert_eq!(v("f", true), Some(json!([1, 2])));
        assert_eq!(written(&json!(12.0)), "12");
        assert_eq!(written(&json!([8, 12])), "8,12");
    }

    #[test]
    fn numbers_are_read_by_kind_and_bad_values_name_the_parameter() {
        let angle = Param::angle("incline", "");
        let x = numeric(&angle, &json!("30deg")).unwrap();
        assert!((x - 30f64.to_radians()).abs() < 1e-15);
        let count = Param::count("sides", "");
        assert_eq!(numeric(&count, &json!(12.0000000001)).unwrap(), 12.0);
        for (p, v) in [
            (&count, json!(2.5)),
            (&angle, json!("30 degrees")),
            (&count, json!("NaN")),
        ] {
            let e = numeric(p, &v).unwrap_err().to_string();
            assert!(e.contains(&format!("`{}`", p.name)), "{e}");
        }
    }
}
