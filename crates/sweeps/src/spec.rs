//! Sweep spec files (TOML, unknown keys rejected) and the cases they describe.
//!
//! ```toml
//! study = "michell"                 # any command of the engine's registry (toroid, roll, …)
//! [fixed]                           # one value for every case
//! beta = "pi/6"
//! spherical = "pi/48"
//! [axes]                            # the grid: lists or ranges, in this order
//! complexity = { from = 2, to = 12, step = 1 }
//! load = [500, 1000]
//! r0 = { from = 0.5, to = 8, steps = 5, log = true }
//! [derived]                         # parameters that follow others (see crate::expr)
//! phi = "pi / (2 * complexity)"
//! [output]
//! columns = ["mass_kg.yield_buckling"]   # a subset of the result columns (default: all)
//! ```
//!
//! Axes: a list of values, or `{ from, to, steps }` (`steps` points from `from` to `to`, both
//! included, the inner ones rounded to 15 significant digits; `log = true` spaces them
//! geometrically, `from`, `to` > 0), or
//! `{ from, to, step }` (`from`, `from + step`, … up to `to`, rounded to the decimals of
//! `from` and `step`). Integer `from`, `to` (and `step`) give integer values when every
//! value is whole.
//!
//! Cases are the Cartesian product of the axes in the order the spec writes them, the last
//! axis varying fastest; case `i` has the digits of `i` in the mixed radix of the axis lengths
//! (so ids are stable for a given spec). Each case's parameters are the fixed values, its axis
//! values and then the derived rules, evaluated in dependency order.

mod axes;

use crate::error::{Result, SweepError};
use crate::expr::Expr;
use crate::values::{self, from_toml, numeric};
use crate::{Column, Study};
use serde::Deserialize;
use serde_json::{Map, Value};
use std::collections::{BTreeMap, BTreeSet};
use tensegrity_core::budget::Limits;
use tensegrity_core::request::Param;

/// Largest number of cases a spec may describe.
pub use crate::limits::MAX_CASES;

/// The table's own columns: no result column takes these names.
pub const RESERVED: [&str; 3] = ["case", "status", "message"];

/// Largest spec file read (16 MiB; a larger file, or an endless stream, is refused before it
/// is read in full).
pub const MAX_SPEC_BYTES: u64 = 16 << 20;

/// One value of an axis: the value and its CSV text (as the spec writes it).
#[derive(Debug, Clone, PartialEq)]
pub struct AxisValue {
    /// The value.
    pub value: Value,
    /// The text in the axis column: a list item exactly as written (a string's contents), or
    /// a range value in Rust's shortest round-trip form.
    pub text: String,
}

/// One axis of the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The parameter.
    pub name: String,
    /// Its values, in order.
    pub values: Vec<AxisValue>,
}

/// A parsed and checked spec.
#[derive(Debug, Clone)]
pub struct Spec {
    /// The study: the registry's command of that name.
    pub study: Study,
    /// `[fixed]` values.
    pub fixed: BTreeMap<String, Value>,
    /// `[axes]`, in the spec's order.
    pub axes: Vec<Axis>,
    /// `[derived]` rules, in evaluation order.
    pub derived: Vec<(String, Expr)>,
    /// The result columns written.
    pub columns: Vec<Column>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpec {
    study: String,
    #[serde(default)]
    fixed: toml::Table,
    #[serde(default)]
    axes: toml::Table,
    #[serde(default)]
    derived: toml::Table,
    #[serde(default)]
    output: RawOutput,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawOutput {
    columns: Option<Vec<String>>,
}

/// A case: its id, axis texts and parameters (or why they could not be formed).
#[derive(Debug, Clone)]
pub struct Case {
    /// 0-based id in the full product order.
    pub id: usize,
    /// The axis texts, one per axis.
    pub axis_texts: Vec<String>,
    /// The case's values by parameter name, or the message of a derived rule that failed.
    pub params: std::result::Result<Map<String, Value>, crate::CaseError>,
}

impl Spec {
    /// Parses and checks a spec (unknown studies, parameters and columns, bad axes and
    /// derived rules are errors here, before any case runs), its axes sized before their
    /// values are made: an axis whose values would not fit the memory this process may use
    /// ([`tensegrity_engine::limits::for_this_process`]) is refused
    /// ([`SweepError::OverBudget`]); the output is not limited ([`Spec::parse_within`]
    /// limits it too).
    pub fn parse(text: &str) -> Result<Spec> {
        Self::parse_within(text, &memory_only())
    }

    /// [`Spec::parse`] under `limits`: before any axis value is made, the values of every
    /// axis (memory), the number of cases ([`MAX_CASES`]) and the sweep's CSV (output) are
    /// estimated and checked ([`crate::limits::admit_axes`]); one over a limit is
    /// [`SweepError::OverBudget`], naming the axis.
    ///
    /// ```
    /// use sweeps::{Spec, SweepError};
    /// use tensegrity_core::budget::Limits;
    /// let text = "study = \"tipover\"\n[axes]\nsigma = { from = 0.1, to = 0.9, steps = 100000000 }\n";
    /// let e = Spec::parse_within(text, &Limits::default()).unwrap_err();
    /// assert!(matches!(e, SweepError::OverBudget { .. }));
    /// assert!(e.to_string().contains("axis sigma (100000000 values)"), "{e}");
    /// ```
    pub fn parse_within(text: &str, limits: &Limits) -> Result<Spec> {
        let spec_err = |e: toml::de::Error| SweepError::Spec {
            message: e.to_string(),
        };
        let raw: RawSpec = toml::from_str(text).map_err(spec_err)?;
        let study =
            tensegrity_engine::command(&raw.study).ok_or_else(|| SweepError::UnknownStudy {
                study: raw.study.clone(),
                known: tensegrity_engine::registry::names(),
            })?;
        let fixed = fixed_values(study, &raw.fixed)?;
        let axes = axes::axes(study, text, &raw.axes, limits)?;
        for a in &axes {
            if fixed.contains_key(&a.name) {
                return Err(duplicate(&a.name, "fixed", "axes"));
            }
        }
        let derived = derived_rules(study, &raw.derived, &fixed, &axes)?;
        let spec = Spec {
            study,
            columns: columns(study, raw.output.columns, &axes)?,
            fixed,
            axes,
            derived,
        };
        spec.check_required()?;
        spec.case_count()?;
        Ok(spec)
    }

    /// Reads and parses a spec file ([`Spec::parse`]).
    pub fn read(path: &std::path::Path) -> Result<Spec> {
        Self::read_within(path, &memory_only())
    }

    /// Reads and parses a spec file under `limits` ([`Spec::parse_within`]).
    pub fn read_within(path: &std::path::Path, limits: &Limits) -> Result<Spec> {
        let text = tensegrity_io::read::read_text(path, MAX_SPEC_BYTES, "a sweep spec")?;
        Spec::parse_within(&text, limits).map_err(|e| match e {
            SweepError::Spec { message } => SweepError::Spec {
                message: format!("{}: {message}", path.display()),
            },
            other => other,
        })
    }

    fn check_required(&self) -> Result<()> {
        for p in self.study.params().into_iter().filter(|p| p.required) {
            let given = self.fixed.contains_key(p.name)
                || self.axes.iter().any(|a| a.name == p.name)
                || self.derived.iter().any(|(n, _)| n == p.name);
            if !given {
                return Err(SweepError::MissingParameter {
                    study: self.study.name,
                    name: p.name,
                });
            }
        }
        Ok(())
    }

    /// The number of cases (the product of the axis lengths).
    pub fn case_count(&self) -> Result<usize> {
        let n = self
            .axes
            .iter()
            .fold(1u128, |n, a| n.saturating_mul(a.values.len() as u128));
        if n > MAX_CASES as u128 {
            return Err(SweepError::TooManyCases {
                cases: n,
                limit: MAX_CASES,
            });
        }
        Ok(n as usize)
    }

    /// The axis value indices of case `id` (last axis fastest).
    pub fn digits(&self, id: usize) -> Vec<usize> {
        let mut rest = id;
        let mut out = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            out[k] = rest % a.values.len();
            rest /= a.values.len();
        }
        out
    }

    /// The axis column texts of case `id`.
    pub fn axis_texts(&self, id: usize) -> Vec<String> {
        let digits = self.digits(id);
        self.axes
            .iter()
            .zip(&digits)
            .map(|(a, &d)| a.values[d].text.clone())
            .collect()
    }

    /// Case `id`: fixed values, its axis values, then the derived rules.
    pub fn case(&self, id: usize) -> Case {
        let digits = self.digits(id);
        let mut values: Map<String, Value> = self.fixed.clone().into_iter().collect();
        for (a, &d) in self.axes.iter().zip(&digits) {
            values.insert(a.name.clone(), a.values[d].value.clone());
        }
        let axis_texts = self.axis_texts(id);
        let mut failed = None;
        for (name, e) in &self.derived {
            let lookup = |n: &str| {
                let p = self.study.param(n)?;
                Some(values.get(n).map_or_else(
                    || Err(format!("`{n}` has no value")),
                    |v| numeric(&p, v).map_err(|e| e.to_string()),
                ))
            };
            match e.eval(&lookup) {
                Ok(x) => {
                    values.insert(name.clone(), values::number(x));
                }
                Err(source) => {
                    failed = Some(crate::CaseError::Derived {
                        name: name.clone(),
                        source,
                    });
                    break;
                }
            }
        }
        Case {
            id,
            axis_texts,
            params: failed.map_or(Ok(values), Err),
        }
    }
}

/// The limits of [`Spec::parse`]: the memory this process may use, no output or work limit.
fn memory_only() -> Limits {
    Limits {
        output_bytes: f64::INFINITY,
        work_s: f64::INFINITY,
        ..tensegrity_engine::limits::for_this_process()
    }
}

fn duplicate(name: &str, first: &'static str, second: &'static str) -> SweepError {
    SweepError::DuplicateParameter {
        name: name.to_string(),
        first,
        second,
    }
}

/// The parameter `name` of the study, or the error naming the known ones.
fn check_name(study: Study, section: &'static str, name: &str) -> Result<Param> {
    study
        .param(name)
        .ok_or_else(|| SweepError::UnknownParameter {
            study: study.name,
            section,
            name: name.to_string(),
            known: study
                .params()
                .iter()
                .map(|p| p.name)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

fn fixed_values(study: Study, table: &toml::Table) -> Result<BTreeMap<String, Value>> {
    let mut out = BTreeMap::new();
    for (name, v) in table {
        let p = check_name(study, "fixed", name)?;
        let value = from_toml(v, p.kind.is_list()).ok_or_else(|| SweepError::InvalidValue {
            name: name.clone(),
            value: v.to_string(),
            reason: "a fixed value is a number, a string or a boolean (lists go in [axes])".into(),
        })?;
        out.insert(name.clone(), value);
    }
    Ok(out)
}

/// Parses the `[derived]` rules and orders them so that every rule comes after the rules
/// it uses.
fn derived_rules(
    study: Study,
    table: &toml::Table,
    fixed: &BTreeMap<String, Value>,
    axes: &[Axis],
) -> Result<Vec<(String, Expr)>> {
    let mut rules = BTreeMap::new();
    for (name, v) in table {
        let param = check_name(study, "derived", name)?;
        let bad = |reason: String| SweepError::InvalidDerived {
            name: name.clone(),
            reason,
        };
        if fixed.contains_key(name) {
            return Err(duplicate(name, "fixed", "derived"));
        }
        if axes.iter().any(|a| &a.name == name) {
            return Err(duplicate(name, "axes", "derived"));
        }
        if !param.kind.is_numeric() {
            return Err(bad("only numeric parameters can be derived".into()));
        }
        let e = match v {
            toml::Value::String(s) => Expr::parse(s).map_err(|e| bad(e.to_string()))?,
            toml::Value::Integer(i) => Expr::Number(*i as f64),
            toml::Value::Float(x) => Expr::Number(*x),
            _ => {
                return Err(bad(
                    "expected an expression string such as \"pi / complexity\"".into(),
                ))
            }
        };
        for n in e.names() {
            let known = study.param(&n).is_some_and(|p| p.kind.is_numeric());
            let defined = fixed.contains_key(&n)
                || axes.iter().any(|a| a.name == n)
                || table.contains_key(&n);
            if !known || !defined {
                return Err(bad(format!(
                    "`{n}` is not a numeric parameter given in [fixed], [axes] or [derived]"
                )));
            }
        }
        rules.insert(name.clone(), e);
    }
    order_rules(rules)
}

fn order_rules(rules: BTreeMap<String, Expr>) -> Result<Vec<(String, Expr)>> {
    let mut done: BTreeSet<String> = BTreeSet::new();
    let mut out = Vec::new();
    let mut pending: Vec<(String, Expr)> = rules.clone().into_iter().collect();
    while !pending.is_empty() {
        let before = pending.len();
        pending.retain(|(name, e)| {
            let ready = e
                .names()
                .iter()
                .all(|n| !rules.contains_key(n) || done.contains(n));
            if ready {
                done.insert(name.clone());
                out.push((name.clone(), e.clone()));
            }
            !ready
        });
        if pending.len() == before {
            return Err(SweepError::InvalidDerived {
                name: pending[0].0.clone(),
                reason: "the derived rules depend on each other in a cycle".into(),
            });
        }
    }
    Ok(out)
}

/// The result columns written: `[output] columns` (default: all of the study's), each name
/// once (a repeated entry is written once, at its first place), and none that repeats a
/// column the table has anyway: a result column named as an axis is left out (the axis
/// column holds that value, as the spec writes it), and so is one named `case`, `status` or
/// `message` (the table's own).
fn columns(study: Study, wanted: Option<Vec<String>>, axes: &[Axis]) -> Result<Vec<Column>> {
    let all = study.columns;
    let chosen: Vec<Column> = match wanted {
        None => all.to_vec(),
        Some(wanted) => wanted
            .iter()
            .map(|w| {
                all.iter()
                    .find(|c| c.name == w)
                    .copied()
                    .ok_or_else(|| SweepError::UnknownColumn {
                        study: study.name,
                        column: w.clone(),
                        known: all.iter().map(|c| c.name).collect::<Vec<_>>().join(", "),
                    })
            })
            .collect::<Result<_>>()?,
    };
    let mut seen: BTreeSet<&str> = RESERVED.iter().copied().collect();
    seen.extend(axes.iter().map(|a| a.name.as_str()));
    Ok(chosen.into_iter().filter(|c| seen.insert(c.name)).collect())
}

#[cfg(test)]
mod tests;
