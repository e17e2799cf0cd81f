//! Requests as data: every analysis a front end can ask for is a plain `serde` struct with
//! documented defaults, one validation, and one description per field ([`Param`]).
//!
//! The description serves every front end: the command line builds its flags from
//! [`Params::params`] (`--name-with-hyphens`), a sweep reads its axes by the same names, and
//! Python takes them as keyword arguments (its signatures, stubs and docstrings too). It is
//! declared once, on the fields: `#[derive(Params)]` of `tensegrity-derive` (its crate docs
//! give the attributes). A field added to a request (with its `#[param(…)]`) is therefore
//! settable from the command line and sweepable without a second table.
//!
//! Values arrive as JSON values from any front end ([`Request::from_values`]): each is
//! normalised by its [`Kind`] (angle strings to radians, integral floats to counts,
//! comma-separated lists to arrays), laid over the request's [`Default`], deserialised, and
//! the result validated ([`Request::validate`]: the per-field [`Rule`]s, then the request's
//! cross-field [`Request::check`]). Every failure is an [`InvalidParameter`] naming the
//! field.
//!
//! ```
//! use serde::{Deserialize, Serialize};
//! use tensegrity_core::request::{Param, Params, Request};
//! use tensegrity_derive::Params;
//!
//! #[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
//! #[serde(default, deny_unknown_fields)]
//! struct Drop {
//!     #[param(number, unit = "m", help = "Drop height", positive)]
//!     height: f64,
//!     #[param(count, help = "Bounces to follow")]
//!     bounces: usize,
//! }
//! impl Default for Drop {
//!     fn default() -> Self { Drop { height: 1.0, bounces: 3 } }
//! }
//! impl Request for Drop {
//!     const NAME: &'static str = "drop";
//! }
//! assert_eq!(
//!     Drop::params(),
//!     [
//!         Param::number("height", "m", "Drop height").positive(),
//!         Param::count("bounces", "Bounces to follow"),
//!     ]
//! );
//! let d = Drop::from_values([("height".to_string(), serde_json::json!("2.5"))]).unwrap();
//! assert_eq!(d, Drop { height: 2.5, bounces: 3 });
//! let e = Drop::from_values([("height".to_string(), serde_json::json!(-1))]).unwrap_err();
//! assert_eq!(e.to_string(), "height = -1: must be finite and positive");
//! assert!(Drop::from_values([("bogus".to_string(), serde_json::json!(1))]).is_err());
//! tensegrity_core::request::check_description::<Drop>().unwrap();
//! ```

mod category;
mod checks;
mod floats;
mod invalid;
mod param;

pub use category::{Categorized, Category};
pub use checks::RunChecks;
pub use floats::floats;
pub use invalid::InvalidParameter;
pub use param::{arrange, Kind, Param, Params, Rule};

use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::{Map, Value};

/// A request of a library analysis: plain data with defaults, one validation and a
/// description of every field (module docs).
///
/// Its description, [`Params::params`] (one [`Param`] per field, in the order front ends list
/// them), is derived from the fields: `#[derive(Params)]` of `tensegrity-derive`.
pub trait Request:
    Params + Serialize + DeserializeOwned + Default + Clone + Send + Sync + 'static
{
    /// The command's and the sweep study's name (`roll`, `tbar_roll`, …).
    const NAME: &'static str;

    /// Checks across fields, beyond each field's [`Rule`] (e.g. μ_k ≤ μ_s).
    fn check(&self) -> Result<(), InvalidParameter> {
        Ok(())
    }

    /// The per-field rules (a [`Param::required`] field must be set, a field that is not
    /// [`Param::optional`] must not be unset, and no number may be NaN or infinite), then
    /// [`Request::check`].
    ///
    /// The numbers are read from the request itself ([`floats`]), not from its JSON form,
    /// where NaN and ±∞ would be `null`: a request built in Rust with `t_end = f64::NAN`, or
    /// an optional `Some(f64::INFINITY)`, is refused naming the field.
    fn validate(&self) -> Result<(), InvalidParameter> {
        let values = self.values();
        let numbers = floats(self);
        for p in Self::params() {
            if let Some((_, x)) = numbers.iter().find(|(k, x)| k == p.name && !x.is_finite()) {
                return Err(InvalidParameter::new(p.name, *x, p.rule.describe()));
            }
            match values.get(p.name) {
                Some(Value::Null) | None if p.required => {
                    return Err(InvalidParameter::raw(p.name, "(unset)", "must be given"))
                }
                Some(Value::Null) if !p.optional => {
                    return Err(InvalidParameter::raw(
                        p.name,
                        "(unset)",
                        "must be given (it has no unset state)",
                    ))
                }
                Some(v) => p.check(v)?,
                None => {}
            }
        }
        self.check()
    }

    /// The request as named values (its serde form).
    fn values(&self) -> Map<String, Value> {
        match serde_json::to_value(self) {
            Ok(Value::Object(map)) => map,
            _ => Map::new(),
        }
    }

    /// The default of every field, by name.
    fn defaults() -> Map<String, Value> {
        Self::default().values()
    }

    /// The description of the field `name`.
    fn param(name: &str) -> Option<Param> {
        Self::params().into_iter().find(|p| p.name == name)
    }

    /// The request from named values over the defaults: unknown names refused, each value
    /// normalised by its kind, the result validated.
    fn from_values<I, K>(values: I) -> Result<Self, InvalidParameter>
    where
        I: IntoIterator<Item = (K, Value)>,
        K: AsRef<str>,
    {
        let params = Self::params();
        let defaults = Self::defaults();
        let mut map = defaults.clone();
        for (name, value) in values {
            let name = name.as_ref();
            let Some(p) = params.iter().find(|p| p.name == name) else {
                let known: Vec<&str> = params.iter().map(|p| p.name).collect();
                return Err(InvalidParameter::raw(
                    name.to_string(),
                    value,
                    format!(
                        "`{}` has no parameter of this name (known: {})",
                        Self::NAME,
                        known.join(", ")
                    ),
                ));
            };
            map.insert(name.to_string(), p.normalize(&value)?);
        }
        let request: Self = serde_json::from_value(Value::Object(map.clone()))
            .map_err(|e| unreadable::<Self>(&defaults, &map, e))?;
        request.validate()?;
        Ok(request)
    }
}

/// The error of values that do not deserialise (a text field the request parses itself, such
/// as `stabilize = "wheels"`): the first field that fails alone over the defaults, named.
fn unreadable<R: Request>(
    defaults: &Map<String, Value>,
    map: &Map<String, Value>,
    e: serde_json::Error,
) -> InvalidParameter {
    for (name, value) in map.iter().filter(|(k, v)| defaults.get(*k) != Some(*v)) {
        let mut one = defaults.clone();
        one.insert(name.clone(), value.clone());
        if let Err(e) = serde_json::from_value::<R>(Value::Object(one)) {
            return match value {
                Value::String(s) => InvalidParameter::text(name.clone(), s, e.to_string()),
                other => InvalidParameter::raw(name.clone(), other, e.to_string()),
            };
        }
    }
    InvalidParameter::raw(R::NAME, "(request)", format!("does not read: {e}"))
}

/// Checks that the description of `R` matches its fields: every serialised field has exactly
/// one [`Param`] of the same name and every [`Param`] a field, and the defaults pass the
/// validation (a request with [`Param::required`] fields has no complete default: then each
/// set default passes its field's rule, and the required ones default to `null`). Each
/// request's tests call it, so a field cannot be added without its description.
pub fn check_description<R: Request>() -> Result<(), DescriptionMismatch> {
    let request = R::NAME;
    let fields: Vec<String> = R::defaults().keys().cloned().collect();
    let params = R::params();
    let mut names: Vec<&str> = params.iter().map(|p| p.name).collect();
    names.sort_unstable();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        let field = w[0].to_string();
        return Err(DescriptionMismatch::Twice { request, field });
    }
    if let Some(f) = fields.iter().find(|f| !names.contains(&f.as_str())) {
        let field = f.clone();
        return Err(DescriptionMismatch::Undescribed { request, field });
    }
    if let Some(n) = names.iter().find(|n| !fields.iter().any(|f| f == *n)) {
        let field = n.to_string();
        return Err(DescriptionMismatch::NoField { request, field });
    }
    let defaults = R::defaults();
    for p in &params {
        let v = &defaults[p.name];
        let field = p.name.to_string();
        if v.is_null() && !p.optional {
            return Err(DescriptionMismatch::NullNotOptional { request, field });
        }
        if p.required && !v.is_null() {
            return Err(DescriptionMismatch::RequiredWithDefault { request, field });
        }
        p.check(v)
            .map_err(|e| DescriptionMismatch::InvalidDefault { request, error: e })?;
    }
    if params.iter().any(|p| p.required) {
        return Ok(());
    }
    R::default()
        .validate()
        .map_err(|e| DescriptionMismatch::InvalidDefaults { request, error: e })
}

/// How a request's description ([`Params::params`]) and its fields disagree
/// ([`check_description`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DescriptionMismatch {
    /// Two descriptions of one name.
    #[error("{request}: `{field}` is described twice")]
    Twice {
        /// The request.
        request: &'static str,
        /// The field.
        field: String,
    },
    /// A field without a description.
    #[error("{request}: field `{field}` has no description")]
    Undescribed {
        /// The request.
        request: &'static str,
        /// The field.
        field: String,
    },
    /// A description without a field.
    #[error("{request}: `{field}` is described but is no field")]
    NoField {
        /// The request.
        request: &'static str,
        /// The described name.
        field: String,
    },
    /// A field that defaults to null but is not optional.
    #[error("{request}: `{field}` defaults to null but is not optional")]
    NullNotOptional {
        /// The request.
        request: &'static str,
        /// The field.
        field: String,
    },
    /// A required field with a default.
    #[error("{request}: `{field}` is required but has a default")]
    RequiredWithDefault {
        /// The request.
        request: &'static str,
        /// The field.
        field: String,
    },
    /// A default that fails its own rule.
    #[error("{request}: the default is invalid: {error}")]
    InvalidDefault {
        /// The request.
        request: &'static str,
        /// The rule's refusal.
        error: InvalidParameter,
    },
    /// Defaults that fail the request's validation.
    #[error("{request}: the defaults are invalid: {error}")]
    InvalidDefaults {
        /// The request.
        request: &'static str,
        /// The validation's refusal.
        error: InvalidParameter,
    },
}

/// The one rule of mutually exclusive fields (`planar`, `cylindrical`, `spherical`): at most
/// one of `given` (each field's name and, when it is set, its value as text) may be set, and
/// with `needed` exactly one. The error names both fields set, or all when none is.
///
/// ```
/// use tensegrity_core::request::exclusive;
/// let set = |x: &str| Some(x.to_string());
/// assert!(exclusive(&[("planar", None), ("cylindrical", set("0.25"))], true).is_ok());
/// let e = exclusive(&[("planar", set("true")), ("cylindrical", set("0.25"))], true);
/// assert_eq!(
///     e.unwrap_err().to_string(),
///     "planar = true: excludes cylindrical = 0.25 (give one of planar, cylindrical)"
/// );
/// let e = exclusive(&[("planar", None), ("cylindrical", None)], true).unwrap_err();
/// assert_eq!(e.to_string(), "planar = (unset): give one of planar, cylindrical");
/// assert!(exclusive(&[("planar", None), ("cylindrical", None)], false).is_ok());
/// ```
pub fn exclusive(
    given: &[(&'static str, Option<String>)],
    needed: bool,
) -> Result<(), InvalidParameter> {
    let names: Vec<&str> = given.iter().map(|(n, _)| *n).collect();
    let set: Vec<(&'static str, &String)> = given
        .iter()
        .filter_map(|(n, v)| v.as_ref().map(|v| (*n, v)))
        .collect();
    match set.as_slice() {
        [(first, value), (second, other), ..] => Err(InvalidParameter::raw(
            *first,
            value,
            format!(
                "excludes {second} = {other} (give one of {})",
                names.join(", ")
            ),
        )),
        [] if needed => Err(InvalidParameter::raw(
            given.first().map_or("", |g| g.0),
            "(unset)",
            format!("give one of {}", names.join(", ")),
        )),
        _ => Ok(()),
    }
}
