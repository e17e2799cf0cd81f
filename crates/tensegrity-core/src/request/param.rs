//! [`Param`]: the one description of a request field (name, kind, unit, rule, help), read by
//! every front end: the command line builds its flags from it, a sweep reads its axes by it,
//! Python its keyword arguments.

use super::InvalidParameter;
use serde_json::Value;

/// How a parameter's value is written and read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A non-negative integer (`sides`, `complexity`); an integral float (a derived sweep
    /// value `2 * q`) within a relative 10⁻⁹ of an integer is rounded to it.
    Count,
    /// A finite number (a string is parsed as one).
    Number,
    /// An angle in radians, or a string in the forms of [`crate::angle::parse_angle`].
    Angle,
    /// A switch: `true` / `false` (on the command line, a flag without a value).
    Flag,
    /// One of a fixed set of names (`rigid`, `full`, `auto`).
    Choice(&'static [&'static str]),
    /// A string the request parses itself (`spokes,inner`, a file path); an object (data a
    /// front end holds, such as a scene's arrays) is handed to the request as it is, for its
    /// own deserialisation to read or refuse.
    Text,
    /// A list of counts (`8,12,16` or an array).
    Counts,
    /// A list of numbers (`0,1.5,3` or an array).
    Numbers,
}

impl Kind {
    /// Whether values of this kind are numbers (sweep rules may compute them).
    pub fn is_numeric(self) -> bool {
        matches!(self, Kind::Count | Kind::Number | Kind::Angle)
    }

    /// Whether the value is a list.
    pub fn is_list(self) -> bool {
        matches!(self, Kind::Counts | Kind::Numbers)
    }
}

/// The range rule of a numeric parameter (each element of a list).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rule {
    /// Any value of the kind (numbers must still be finite).
    Any,
    /// Finite and > 0.
    Positive,
    /// Finite and ≥ 0.
    NonNegative,
    /// In the closed interval [lo, hi].
    Closed(f64, f64),
    /// In the half-open interval [lo, hi).
    HalfOpen(f64, f64),
    /// At least this much (counts: `sides ≥ 3`).
    AtLeast(f64),
}

impl Rule {
    /// The rule's text, as errors and help messages state it.
    pub fn describe(self) -> String {
        match self {
            Rule::Any => "must be finite".into(),
            Rule::Positive => "must be finite and positive".into(),
            Rule::NonNegative => "must be finite and non-negative".into(),
            Rule::Closed(lo, hi) => format!("must lie in [{lo}, {hi}]"),
            Rule::HalfOpen(lo, hi) => format!("must lie in [{lo}, {hi})"),
            Rule::AtLeast(lo) => format!("must be at least {lo}"),
        }
    }

    /// Whether `x` satisfies the rule.
    pub fn admits(self, x: f64) -> bool {
        x.is_finite()
            && match self {
                Rule::Any => true,
                Rule::Positive => x > 0.0,
                Rule::NonNegative => x >= 0.0,
                Rule::Closed(lo, hi) => (lo..=hi).contains(&x),
                Rule::HalfOpen(lo, hi) => (lo..hi).contains(&x),
                Rule::AtLeast(lo) => x >= lo,
            }
    }
}

/// One field of a request: everything a front end needs to offer it.
///
/// `name` is the serde key of the field, the sweep axis and the Python keyword; the command
/// line spells it `--name-with-hyphens`. The default is the value of the field in the
/// request's [`Default`] (see [`super::Request::defaults`]).
///
/// ```
/// use tensegrity_core::request::{Kind, Param, Rule};
/// let p = Param::number("t_end", "s", "Simulated time").rule(Rule::Positive);
/// assert_eq!((p.name, p.kind, p.unit), ("t_end", Kind::Number, "s"));
/// assert!(p.check(&serde_json::json!(2.0)).is_ok());
/// assert!(p.check(&serde_json::json!(-2.0)).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Param {
    /// The field's name (`snake_case`).
    pub name: &'static str,
    /// How its value is read.
    pub kind: Kind,
    /// SI unit (`""` when dimensionless or not a number).
    pub unit: &'static str,
    /// One line of help.
    pub help: &'static str,
    /// The range rule of a numeric value.
    pub rule: Rule,
    /// Whether the field may be left unset (`null`: the library then derives it, e.g. the
    /// ground damping from the restitution).
    pub optional: bool,
    /// Whether the field has no default: it is `null` in the request's [`Default`] and a
    /// front end must be given it (the command line makes the flag required, a sweep spec
    /// must set it). [`super::Request::validate`] refuses it unset.
    pub required: bool,
}

impl Param {
    /// A parameter of any kind.
    pub const fn new(
        name: &'static str,
        kind: Kind,
        unit: &'static str,
        help: &'static str,
    ) -> Self {
        Self {
            name,
            kind,
            unit,
            help,
            rule: Rule::Any,
            optional: false,
            required: false,
        }
    }

    /// A finite number.
    pub const fn number(name: &'static str, unit: &'static str, help: &'static str) -> Self {
        Self::new(name, Kind::Number, unit, help)
    }

    /// A non-negative integer.
    pub const fn count(name: &'static str, help: &'static str) -> Self {
        Self::new(name, Kind::Count, "", help)
    }

    /// An angle (radians, or `30deg`, `pi/8`, …).
    pub const fn angle(name: &'static str, help: &'static str) -> Self {
        Self::new(name, Kind::Angle, "rad", help)
    }

    /// A switch.
    pub const fn flag(name: &'static str, help: &'static str) -> Self {
        Self::new(name, Kind::Flag, "", help)
    }

    /// One of `choices`.
    pub const fn choice(
        name: &'static str,
        choices: &'static [&'static str],
        help: &'static str,
    ) -> Self {
        Self::new(name, Kind::Choice(choices), "", help)
    }

    /// A string the request parses.
    pub const fn text(name: &'static str, help: &'static str) -> Self {
        Self::new(name, Kind::Text, "", help)
    }

    /// With a range rule.
    pub const fn rule(self, rule: Rule) -> Self {
        Self { rule, ..self }
    }

    /// Finite and > 0.
    pub const fn positive(self) -> Self {
        self.rule(Rule::Positive)
    }

    /// Finite and ≥ 0.
    pub const fn non_negative(self) -> Self {
        self.rule(Rule::NonNegative)
    }

    /// May be left unset (`null`).
    pub const fn optional(self) -> Self {
        Self {
            optional: true,
            ..self
        }
    }

    /// Has no default: `null` in the request's [`Default`], and must be given.
    pub const fn required(self) -> Self {
        Self {
            optional: true,
            required: true,
            ..self
        }
    }

    /// A list of counts (`8,12,16`).
    pub const fn counts(name: &'static str, help: &'static str) -> Self {
        Self::new(name, Kind::Counts, "", help)
    }

    /// A list of numbers (`0.1,0.25`).
    pub const fn numbers(name: &'static str, unit: &'static str, help: &'static str) -> Self {
        Self::new(name, Kind::Numbers, unit, help)
    }

    /// The value normalised to its kind: counts as integers, numbers and angles as floats
    /// (angle strings converted to radians), switches as booleans, lists as arrays (a scalar
    /// or a comma-separated string is a list of one or more), `null` for an unset optional
    /// field. The range rule is not applied here (see [`Param::check`]).
    ///
    /// ```
    /// use serde_json::json;
    /// use tensegrity_core::request::Param;
    /// let sides = Param::count("sides", "");
    /// assert_eq!(sides.normalize(&json!(8.0)).unwrap(), json!(8));
    /// assert_eq!(sides.normalize(&json!("12")).unwrap(), json!(12));
    /// assert!(sides.normalize(&json!(2.5)).is_err());
    /// let incline = Param::angle("incline", "");
    /// let x = incline.normalize(&json!("90deg")).unwrap().as_f64().unwrap();
    /// assert!((x - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    /// let treads = Param::new("treads", tensegrity_core::request::Kind::Counts, "", "");
    /// assert_eq!(treads.normalize(&json!("8,12")).unwrap(), json!([8, 12]));
    /// assert_eq!(treads.normalize(&json!(8)).unwrap(), json!([8]));
    /// ```
    pub fn normalize(&self, v: &Value) -> Result<Value, InvalidParameter> {
        if v.is_null() {
            return if self.optional {
                Ok(Value::Null)
            } else {
                Err(self.bad(v, "must be given (it has no unset state)"))
            };
        }
        match self.kind {
            Kind::Count => self.count_of(v).map(Value::from),
            Kind::Number | Kind::Angle => self.number_of(v).map(Value::from),
            Kind::Flag => match v {
                Value::Bool(b) => Ok(Value::Bool(*b)),
                Value::String(s) if s == "true" || s == "false" => Ok(Value::Bool(s == "true")),
                _ => Err(self.bad(v, "expected true or false")),
            },
            Kind::Choice(choices) => {
                let s = scalar_text(v);
                if choices.contains(&s.as_str()) {
                    Ok(Value::String(s))
                } else {
                    Err(self.bad(v, format!("expected one of {}", choices.join(", "))))
                }
            }
            Kind::Text => match v {
                Value::Array(_) => Err(self.bad(v, "expected a string")),
                Value::Object(_) => Ok(v.clone()),
                other => Ok(Value::String(scalar_text(other))),
            },
            Kind::Counts | Kind::Numbers => {
                let items: Vec<Value> = match v {
                    Value::Array(a) => a.clone(),
                    Value::String(s) => s
                        .split(',')
                        .map(str::trim)
                        .filter(|t| !t.is_empty())
                        .map(|t| Value::String(t.to_string()))
                        .collect(),
                    other => vec![other.clone()],
                };
                if items.is_empty() {
                    return Err(self.bad(v, "expected at least one value"));
                }
                items
                    .iter()
                    .map(|x| match self.kind {
                        Kind::Counts => self.count_of(x).map(Value::from),
                        _ => self.number_of(x).map(Value::from),
                    })
                    .collect::<Result<Vec<_>, _>>()
                    .map(Value::Array)
            }
        }
    }

    /// Checks a normalised value against the range rule (every element of a list).
    pub fn check(&self, v: &Value) -> Result<(), InvalidParameter> {
        let numbers: Vec<f64> = match v {
            Value::Number(n) => n.as_f64().into_iter().collect(),
            Value::Array(a) => a.iter().filter_map(Value::as_f64).collect(),
            _ => return Ok(()),
        };
        match numbers.iter().find(|x| !self.rule.admits(**x)) {
            Some(x) => Err(InvalidParameter::new(self.name, *x, self.rule.describe())),
            None => Ok(()),
        }
    }

    fn bad(&self, v: &Value, reason: impl Into<String>) -> InvalidParameter {
        match v {
            Value::String(s) => InvalidParameter::text(self.name, s, reason),
            other => InvalidParameter::raw(self.name, other, reason),
        }
    }

    fn number_of(&self, v: &Value) -> Result<f64, InvalidParameter> {
        let x = match (self.kind, v) {
            (_, Value::Number(n)) => n.as_f64(),
            (Kind::Angle, Value::String(s)) => {
                Some(crate::angle::parse_angle(s).map_err(|e| self.bad(v, e.to_string()))?)
            }
            (_, Value::String(s)) => s.trim().parse::<f64>().ok(),
            _ => None,
        };
        match x {
            Some(x) if x.is_finite() => Ok(x),
            Some(_) => Err(self.bad(v, "must be finite")),
            None => Err(self.bad(v, "expected a number")),
        }
    }

    fn count_of(&self, v: &Value) -> Result<u64, InvalidParameter> {
        // every count is at most u32::MAX, from a flag or a JSON/Python integer alike (the
        // estimates multiply counts in usize)
        if let Some(i) = v.as_u64() {
            if i > u64::from(u32::MAX) {
                return Err(self.bad(v, format!("must be at most {}", u32::MAX)));
            }
            return Ok(i);
        }
        let x = match v {
            Value::String(s) => s.trim().parse::<f64>().ok(),
            other => other.as_f64(),
        };
        match x {
            Some(x) if x.is_finite() => {
                let r = x.round();
                if r < 0.0 || (x - r).abs() > 1e-9 * r.abs().max(1.0) {
                    Err(self.bad(v, "expected a non-negative integer"))
                } else if r > u32::MAX as f64 {
                    Err(self.bad(v, format!("must be at most {}", u32::MAX)))
                } else {
                    Ok(r as u64)
                }
            }
            _ => Err(self.bad(v, "expected a non-negative integer")),
        }
    }
}

/// A scalar written as text (strings as they are, numbers and booleans in their JSON form).
fn scalar_text(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// The description of a request's fields (or of a part flattened into requests): one
/// [`Param`] per field, in the order front ends list them. Derived from the fields,
/// `#[derive(Params)]` of `tensegrity-derive`; [`super::check_description`] checks it against
/// the fields and the defaults.
pub trait Params {
    /// One description per field, in the order front ends list them.
    fn params() -> Vec<Param>;
}

/// `params` with the ones named in `order` put in that order, in the places they take
/// together; the others stay where they are (`#[params(order = "…")]` of the derive, for a
/// request that lists the fields of a flattened part among its own).
///
/// ```
/// use tensegrity_core::request::{arrange, Param};
/// let p = ["a", "b", "c", "d"].map(|n| Param::flag(n, "")).to_vec();
/// let names: Vec<&str> = arrange(p, &["c", "b"]).iter().map(|p| p.name).collect();
/// assert_eq!(names, ["a", "c", "b", "d"]);
/// ```
///
/// # Panics
/// When a name of `order` is no parameter, or named twice (a programming error of the
/// declaration).
pub fn arrange(params: Vec<Param>, order: &[&str]) -> Vec<Param> {
    let slots: Vec<usize> = (0..params.len())
        .filter(|&i| order.contains(&params[i].name))
        .collect();
    assert_eq!(
        slots.len(),
        order.len(),
        "the order {order:?} names a parameter twice or one that is not there"
    );
    let mut out = params.clone();
    for (slot, name) in slots.into_iter().zip(order) {
        out[slot] = *params.iter().find(|p| p.name == *name).expect("counted");
    }
    out
}
