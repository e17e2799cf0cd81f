//! Parameter values and their typed reading.
//!
//! A spec gives values as TOML scalars: integers, floats, strings (`"pi/8"`, `"30deg"`,
//! `"spokes,inner"`, `"rigid"`) and booleans, exactly as the single-point command's flag
//! takes them. Each study declares its parameters ([`ParamDef`]: the flag's long name with
//! `_` for `-`, and a [`Kind`]); [`Params`] reads one case's values by kind:
//!
//! - [`Kind::Count`]: a non-negative integer (an integral float, such as the value of a
//!   derived rule `2 * q`, within a relative 10⁻⁹ of an integer, is rounded to it);
//! - [`Kind::Number`]: a finite number (a string is parsed as a number);
//! - [`Kind::Angle`]: a number in radians, or a string in the angle forms of
//!   [`crate::angle::parse_angle`];
//! - [`Kind::Flag`]: `true` / `false`;
//! - [`Kind::Text`]: a string, parsed by the study (e.g. `stabilize`, `method`).

use crate::angle::parse_angle;
use crate::error::{Result, SweepError};
use std::collections::BTreeMap;

/// A parameter value as the spec gives it.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A TOML integer.
    Integer(i64),
    /// A TOML float, or the value of a derived rule.
    Float(f64),
    /// A TOML string.
    Text(String),
    /// A TOML boolean.
    Bool(bool),
}

impl Value {
    /// The value of a TOML scalar; `None` for arrays, tables and dates.
    pub fn from_toml(v: &toml::Value) -> Option<Value> {
        Some(match v {
            toml::Value::Integer(i) => Value::Integer(*i),
            toml::Value::Float(x) => Value::Float(*x),
            toml::Value::String(s) => Value::Text(s.clone()),
            toml::Value::Boolean(b) => Value::Bool(*b),
            _ => return None,
        })
    }

    /// The value written out: integers and floats in Rust's shortest round-trip form,
    /// strings as they are.
    pub fn written(&self) -> String {
        match self {
            Value::Integer(i) => i.to_string(),
            Value::Float(x) => x.to_string(),
            Value::Text(s) => s.clone(),
            Value::Bool(b) => b.to_string(),
        }
    }
}

/// How a parameter's value is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A non-negative integer (`sides`, `complexity`).
    Count,
    /// A finite number.
    Number,
    /// An angle (radians, or `30deg`, `pi/8`, …).
    Angle,
    /// A boolean switch (`prism_only`, `planar`).
    Flag,
    /// A string the study parses (`stabilize`, `fidelity`, `material`, …).
    Text,
}

impl Kind {
    /// Whether derived rules can use or set the parameter.
    pub fn is_numeric(self) -> bool {
        matches!(self, Kind::Count | Kind::Number | Kind::Angle)
    }
}

/// One parameter of a study.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParamDef {
    /// The single-point command's long flag with `_` for `-`.
    pub name: &'static str,
    /// How its value is read.
    pub kind: Kind,
    /// SI unit (`""` when dimensionless or not a number).
    pub unit: &'static str,
    /// Whether the study needs it (the flag has no default).
    pub required: bool,
}

/// A parameter with a default.
pub(crate) const fn param(name: &'static str, kind: Kind, unit: &'static str) -> ParamDef {
    ParamDef {
        name,
        kind,
        unit,
        required: false,
    }
}

/// A parameter without a default.
pub(crate) const fn required(name: &'static str, kind: Kind, unit: &'static str) -> ParamDef {
    ParamDef {
        required: true,
        ..param(name, kind, unit)
    }
}

fn invalid(name: &str, v: &Value, reason: impl Into<String>) -> SweepError {
    SweepError::InvalidValue {
        name: name.to_string(),
        value: match v {
            Value::Text(s) => format!("\"{s}\""),
            other => other.written(),
        },
        reason: reason.into(),
    }
}

/// The numeric value of `v` read as `kind` (used by the getters and by derived rules).
pub fn numeric(name: &str, kind: Kind, v: &Value) -> Result<f64> {
    let x = match (kind, v) {
        (_, Value::Bool(_)) | (Kind::Flag | Kind::Text, _) => {
            return Err(invalid(name, v, "not a number"))
        }
        (_, Value::Integer(i)) => *i as f64,
        (_, Value::Float(x)) => *x,
        (Kind::Angle, Value::Text(s)) => parse_angle(s).map_err(|e| invalid(name, v, e))?,
        (_, Value::Text(s)) => s
            .trim()
            .parse::<f64>()
            .map_err(|_| invalid(name, v, "expected a number"))?,
    };
    if x.is_finite() {
        Ok(x)
    } else {
        Err(invalid(name, v, "must be finite"))
    }
}

/// One case's parameter values, read by kind; a parameter absent from the case is `None`
/// (the study then uses the library's default).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Params {
    values: BTreeMap<String, Value>,
}

impl Params {
    /// Parameters from `(name, value)` pairs.
    pub fn new(values: BTreeMap<String, Value>) -> Self {
        Self { values }
    }

    /// The raw value.
    pub fn get(&self, name: &str) -> Option<&Value> {
        self.values.get(name)
    }

    /// Sets a value (derived rules).
    pub fn set(&mut self, name: &str, value: Value) {
        self.values.insert(name.to_string(), value);
    }

    /// A non-negative integer.
    pub fn count(&self, name: &str) -> Result<Option<usize>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        let x = numeric(name, Kind::Count, v)?;
        let r = x.round();
        if x < 0.0 || (x - r).abs() > 1e-9 * r.abs().max(1.0) || r > u32::MAX as f64 {
            return Err(invalid(name, v, "expected a non-negative integer"));
        }
        Ok(Some(r as usize))
    }

    /// A finite number.
    pub fn number(&self, name: &str) -> Result<Option<f64>> {
        self.get(name)
            .map(|v| numeric(name, Kind::Number, v))
            .transpose()
    }

    /// An angle in radians.
    pub fn angle(&self, name: &str) -> Result<Option<f64>> {
        self.get(name)
            .map(|v| numeric(name, Kind::Angle, v))
            .transpose()
    }

    /// A boolean switch.
    pub fn flag(&self, name: &str) -> Result<Option<bool>> {
        match self.get(name) {
            None => Ok(None),
            Some(Value::Bool(b)) => Ok(Some(*b)),
            Some(Value::Text(s)) if s == "true" || s == "false" => Ok(Some(s == "true")),
            Some(v) => Err(invalid(name, v, "expected true or false")),
        }
    }

    /// A string (any scalar, as written).
    pub fn text(&self, name: &str) -> Option<String> {
        self.get(name).map(Value::written)
    }

    /// Parses a string parameter with `parse`, naming the parameter in its error.
    pub fn parsed<T, E: std::fmt::Display>(
        &self,
        name: &str,
        parse: impl Fn(&str) -> std::result::Result<T, E>,
    ) -> Result<Option<T>> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        parse(&v.written())
            .map(Some)
            .map_err(|e| invalid(name, v, e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(pairs: &[(&str, Value)]) -> Params {
        Params::new(
            pairs
                .iter()
                .map(|(k, v)| (k.to_string(), v.clone()))
                .collect(),
        )
    }

    #[test]
    fn values_are_read_by_kind() {
        let p = params(&[
            ("n", Value::Integer(8)),
            ("m", Value::Float(12.0000000001)),
            ("x", Value::Text("1e5".into())),
            ("a", Value::Text("30deg".into())),
            ("b", Value::Float(0.5)),
            ("f", Value::Bool(true)),
        ]);
        assert_eq!(p.count("n").unwrap(), Some(8));
        assert_eq!(p.count("m").unwrap(), Some(12));
        assert_eq!(p.number("x").unwrap(), Some(1e5));
        assert_eq!(p.angle("a").unwrap(), Some(30f64.to_radians()));
        assert_eq!(p.angle("b").unwrap(), Some(0.5));
        assert_eq!(p.flag("f").unwrap(), Some(true));
        assert_eq!(p.count("absent").unwrap(), None);
    }

    #[test]
    fn bad_values_name_the_parameter() {
        let p = params(&[
            ("n", Value::Float(2.5)),
            ("k", Value::Integer(-3)),
            ("a", Value::Text("30 degrees".into())),
            ("f", Value::Integer(1)),
            ("x", Value::Float(f64::INFINITY)),
        ]);
        for (name, e) in [
            ("n", p.count("n").unwrap_err()),
            ("k", p.count("k").unwrap_err()),
            ("a", p.angle("a").unwrap_err()),
            ("f", p.flag("f").unwrap_err()),
            ("x", p.number("x").unwrap_err()),
        ] {
            assert!(e.to_string().contains(&format!("`{name}`")), "{e}");
        }
    }
}
