//! Requests as data: every analysis a front end can ask for is a plain `serde` struct with
//! documented defaults, one validation, and one description per field ([`Param`]).
//!
//! The description serves every front end: the command line builds its flags from
//! [`Request::params`] (`--name-with-hyphens`), a sweep reads its axes by the same names, and
//! Python takes them as keyword arguments. A field added to a request (with its [`Param`])
//! is therefore settable from the command line and sweepable without a second table.
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
//! use tensegrity_core::request::{InvalidParameter, Param, Request};
//!
//! #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
//! #[serde(default, deny_unknown_fields)]
//! struct Drop { height: f64, bounces: usize }
//! impl Default for Drop {
//!     fn default() -> Self { Drop { height: 1.0, bounces: 3 } }
//! }
//! impl Request for Drop {
//!     const NAME: &'static str = "drop";
//!     fn params() -> Vec<Param> {
//!         vec![
//!             Param::number("height", "m", "Drop height").positive(),
//!             Param::count("bounces", "Bounces to follow"),
//!         ]
//!     }
//! }
//! let d = Drop::from_values([("height".to_string(), serde_json::json!("2.5"))]).unwrap();
//! assert_eq!(d, Drop { height: 2.5, bounces: 3 });
//! let e = Drop::from_values([("height".to_string(), serde_json::json!(-1))]).unwrap_err();
//! assert_eq!(e.to_string(), "height = -1: must be finite and positive");
//! assert!(Drop::from_values([("bogus".to_string(), serde_json::json!(1))]).is_err());
//! tensegrity_core::request::check_description::<Drop>().unwrap();
//! ```

mod category;
mod invalid;
mod param;

pub use category::{Categorized, Category};
pub use invalid::InvalidParameter;
pub use param::{Kind, Param, Rule};

use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::{Map, Value};

/// A request of a library analysis: plain data with defaults, one validation and a
/// description of every field (module docs).
pub trait Request: Serialize + DeserializeOwned + Default + Clone + Send + Sync + 'static {
    /// The command's and the sweep study's name (`roll`, `tbar_roll`, …).
    const NAME: &'static str;

    /// One description per field, in the order front ends list them.
    fn params() -> Vec<Param>;

    /// Checks across fields, beyond each field's [`Rule`] (e.g. μ_k ≤ μ_s).
    fn check(&self) -> Result<(), InvalidParameter> {
        Ok(())
    }

    /// The per-field rules, then [`Request::check`].
    fn validate(&self) -> Result<(), InvalidParameter> {
        let values = self.values();
        for p in Self::params() {
            if let Some(v) = values.get(p.name) {
                p.check(v)?;
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
        let mut map = Self::defaults();
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
        let request: Self = serde_json::from_value(Value::Object(map)).map_err(|e| {
            InvalidParameter::raw(Self::NAME, "(request)", format!("does not read: {e}"))
        })?;
        request.validate()?;
        Ok(request)
    }
}

/// Checks that the description of `R` matches its fields: every serialised field has exactly
/// one [`Param`] of the same name and every [`Param`] a field, and the defaults pass the
/// validation. Each request's tests call it, so a field cannot be added without its
/// description.
pub fn check_description<R: Request>() -> Result<(), String> {
    let fields: Vec<String> = R::defaults().keys().cloned().collect();
    let params = R::params();
    let mut names: Vec<&str> = params.iter().map(|p| p.name).collect();
    names.sort_unstable();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!("{}: `{}` is described twice", R::NAME, w[0]));
    }
    if let Some(f) = fields.iter().find(|f| !names.contains(&f.as_str())) {
        return Err(format!("{}: field `{f}` has no description", R::NAME));
    }
    if let Some(n) = names.iter().find(|n| !fields.iter().any(|f| f == *n)) {
        return Err(format!("{}: `{n}` is described but is no field", R::NAME));
    }
    for p in &params {
        let v = &R::defaults()[p.name];
        if v.is_null() && !p.optional {
            return Err(format!(
                "{}: `{}` defaults to null but is not optional",
                R::NAME,
                p.name
            ));
        }
    }
    R::default()
        .validate()
        .map_err(|e| format!("{}: the defaults are invalid: {e}", R::NAME))
}
