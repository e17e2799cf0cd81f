//! [`InvalidParameter`]: the one shape of a bad parameter value in every crate of the
//! workspace (the core, the topology crates, io, sweeps and the front ends).

use std::borrow::Cow;
use std::fmt;

/// A parameter whose value breaks its rule: the parameter's name as the library knows it
/// (the request field, e.g. `t_end`), the value as given, and why it is invalid.
///
/// Libraries name their own parameters, never a command-line flag: a front end maps the
/// name to its own spelling (the CLI to `--t-end`, Python to the keyword `t_end`).
///
/// ```
/// use tensegrity_core::request::InvalidParameter;
/// let e = InvalidParameter::new("dt", -1.0, "must be finite and positive");
/// assert_eq!(e.to_string(), "dt = -1: must be finite and positive");
/// let e = InvalidParameter::text("stabilize", "wheels", "unknown option");
/// assert_eq!(e.to_string(), "stabilize = \"wheels\": unknown option");
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InvalidParameter {
    /// The parameter (a request field, `snake_case`).
    pub name: Cow<'static, str>,
    /// The value as given, written out (numbers in [`crate::number::short_number`] form,
    /// text quoted).
    pub value: String,
    /// Why it is invalid: the rule it breaks.
    pub reason: String,
}

impl InvalidParameter {
    /// A numeric parameter `name = value` breaking a rule.
    pub fn new(name: impl Into<Cow<'static, str>>, value: f64, reason: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            value: crate::number::short_number(value),
            reason: reason.into(),
        }
    }

    /// A text parameter (quoted in the message).
    pub fn text(
        name: impl Into<Cow<'static, str>>,
        value: impl fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Self {
            name: name.into(),
            value: format!("\"{value}\""),
            reason: reason.into(),
        }
    }

    /// A parameter whose value is written as given (a count, a list, a boolean).
    pub fn raw(
        name: impl Into<Cow<'static, str>>,
        value: impl fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Self {
            name: name.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// The same error under another parameter name (a request that forwards a field to a
    /// nested one under its own name).
    pub fn renamed(self, name: impl Into<Cow<'static, str>>) -> Self {
        Self {
            name: name.into(),
            ..self
        }
    }
}

impl fmt::Display for InvalidParameter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {}: {}", self.name, self.value, self.reason)
    }
}

impl std::error::Error for InvalidParameter {}

impl super::Categorized for InvalidParameter {
    fn category(&self) -> super::Category {
        super::Category::Input
    }
}
