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

use crate::error::{Result, SweepError};
use crate::expr::Expr;
use crate::values::{self, from_toml, numeric, written};
use crate::{Column, Study};
use serde::Deserialize;
use serde_json::{Map, Value};
use std::collections::{BTreeMap, BTreeSet};
use tensegrity_core::request::Param;

/// Largest number of cases a spec may describe.
pub const MAX_CASES: u64 = 100_000_000;

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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRange {
    from: toml::Value,
    to: toml::Value,
    steps: Option<i64>,
    step: Option<toml::Value>,
    #[serde(default)]
    log: bool,
}

/// A case: its id, axis texts and parameters (or why they could not be formed).
#[derive(Debug, Clone)]
pub struct Case {
    /// 0-based id in the full product order.
    pub id: usize,
    /// The axis texts, one per axis.
    pub axis_texts: Vec<String>,
    /// The case's values by parameter name, or the message of a derived rule that failed.
    pub params: std::result::Result<Map<String, Value>, String>,
}

impl Spec {
    /// Parses and checks a spec (unknown studies, parameters and columns, bad axes and
    /// derived rules are errors here, before any case runs).
    pub fn parse(text: &str) -> Result<Spec> {
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
        let axes = axes(study, text, &raw.axes)?;
        for a in &axes {
            if fixed.contains_key(&a.name) {
                return Err(duplicate(&a.name, "fixed", "axes"));
            }
        }
        let derived = derived_rules(study, &raw.derived, &fixed, &axes)?;
        let spec = Spec {
            study,
            columns: columns(study, raw.output.columns)?,
            fixed,
            axes,
            derived,
        };
        spec.check_required()?;
        spec.case_count()?;
        Ok(spec)
    }

    /// Reads and parses a spec file.
    pub fn read(path: &std::path::Path) -> Result<Spec> {
        let text = tensegrity_io::read::read_text(path, MAX_SPEC_BYTES, "a sweep spec")?;
        Spec::parse(&text).map_err(|e| match e {
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
                Err(msg) => {
                    failed = Some(format!("derived `{name}`: {msg}"));
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

/// The `[axes]` entries in document order, with the source text of every list item.
fn axes(study: Study, text: &str, table: &toml::Table) -> Result<Vec<Axis>> {
    let spans = axis_spans(text)?;
    let mut out = Vec::new();
    for (name, item_spans) in spans {
        let p = check_name(study, "axes", &name)?;
        let v = table.get(&name).ok_or_else(|| SweepError::Spec {
            message: format!("axis `{name}` not found"),
        })?;
        let values = match v {
            toml::Value::Array(items) => {
                list_values(&name, items, &item_spans, text, p.kind.is_list())?
            }
            toml::Value::Table(t) => {
                let r: RawRange = t.clone().try_into().map_err(|e: toml::de::Error| {
                    axis_err(
                        &name,
                        format!("a range is {{ from, to, steps | step, log }}: {e}"),
                    )
                })?;
                range_values(&name, &r)?
            }
            _ => return Err(axis_err(&name, "expected a list or a range table".into())),
        };
        if values.is_empty() {
            return Err(axis_err(&name, "no values".into()));
        }
        out.push(Axis { name, values });
    }
    Ok(out)
}

fn axis_err(axis: &str, reason: String) -> SweepError {
    SweepError::InvalidAxis {
        axis: axis.to_string(),
        reason,
    }
}

/// Axis names in document order, each with the byte spans of its list items (empty for a
/// range).
fn axis_spans(text: &str) -> Result<Vec<(String, Vec<std::ops::Range<usize>>)>> {
    use toml::de::{DeTable, DeValue};
    let doc = DeTable::parse(text).map_err(|e| SweepError::Spec {
        message: e.to_string(),
    })?;
    let Some(axes) = doc.get_ref().get("axes") else {
        return Ok(Vec::new());
    };
    let DeValue::Table(axes) = axes.get_ref() else {
        return Ok(Vec::new());
    };
    let mut entries: Vec<(usize, String, Vec<std::ops::Range<usize>>)> = axes
        .iter()
        .map(|(k, v)| {
            let items = match v.get_ref() {
                DeValue::Array(a) => a.iter().map(|item| item.span()).collect(),
                _ => Vec::new(),
            };
            (k.span().start, k.get_ref().to_string(), items)
        })
        .collect();
    entries.sort_by_key(|e| e.0);
    Ok(entries.into_iter().map(|(_, k, v)| (k, v)).collect())
}

fn list_values(
    name: &str,
    items: &[toml::Value],
    spans: &[std::ops::Range<usize>],
    text: &str,
    lists: bool,
) -> Result<Vec<AxisValue>> {
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let value = from_toml(item, lists).ok_or_else(|| {
                axis_err(
                    name,
                    format!("item {} is not a number, string or boolean", i + 1),
                )
            })?;
            let text = match (&value, spans.get(i)) {
                (Value::String(s), _) => s.clone(),
                (_, Some(span)) => text
                    .get(span.clone())
                    .map_or_else(|| written(&value), |t| t.trim().to_string()),
                (_, None) => written(&value),
            };
            Ok(AxisValue { value, text })
        })
        .collect()
}

fn number(name: &str, what: &str, v: &toml::Value) -> Result<f64> {
    let x = match v {
        toml::Value::Integer(i) => *i as f64,
        toml::Value::Float(x) => *x,
        _ => return Err(axis_err(name, format!("`{what}` must be a number"))),
    };
    if x.is_finite() {
        Ok(x)
    } else {
        Err(axis_err(name, format!("`{what}` must be finite")))
    }
}

/// Decimals of `x` in its shortest round-trip form (`0.25` → 2, `3` → 0).
fn decimals(x: f64) -> usize {
    let s = x.to_string();
    s.split_once('.').map_or(0, |(_, d)| d.len())
}

fn range_values(name: &str, r: &RawRange) -> Result<Vec<AxisValue>> {
    let (from, to) = (number(name, "from", &r.from)?, number(name, "to", &r.to)?);
    let xs: Vec<f64> = match (r.steps, &r.step) {
        (Some(n), None) => {
            if n < 1 || n as u64 > MAX_CASES {
                return Err(axis_err(
                    name,
                    format!("`steps` must be in 1..={MAX_CASES}"),
                ));
            }
            if r.log && !(from > 0.0 && to > 0.0) {
                return Err(axis_err(name, "a log range needs from, to > 0".into()));
            }
            let n = n as usize;
            // interior points rounded to 15 significant digits: 1e-5, not 1.0000000000000003e-5
            let round = |x: f64| format!("{x:.14e}").parse().unwrap_or(x);
            (0..n)
                .map(|i| match (i, n) {
                    (0, _) => from,
                    (i, n) if i == n - 1 => to,
                    _ if r.log => round(from * (to / from).powf(i as f64 / (n - 1) as f64)),
                    _ => round(from + (to - from) * i as f64 / (n - 1) as f64),
                })
                .collect()
        }
        (None, Some(step)) if !r.log => {
            let h = number(name, "step", step)?;
            let count = (to - from) / h;
            if h == 0.0 || count < -1e-9 {
                return Err(axis_err(
                    name,
                    "`step` must be non-zero and point from `from` to `to`".into(),
                ));
            }
            let count = (count + 1e-9).floor() + 1.0;
            if count > MAX_CASES as f64 {
                return Err(axis_err(name, format!("more than {MAX_CASES} values")));
            }
            let d = decimals(from).max(decimals(h));
            (0..count as usize)
                .map(|i| {
                    let x = from + i as f64 * h;
                    format!("{x:.d$}").parse().unwrap_or(x)
                })
                .collect()
        }
        (None, Some(_)) => {
            return Err(axis_err(
                name,
                "a log range takes `steps`, not `step`".into(),
            ))
        }
        _ => {
            return Err(axis_err(
                name,
                "give exactly one of `steps` and `step`".into(),
            ))
        }
    };
    let integers = matches!(r.from, toml::Value::Integer(_))
        && matches!(r.to, toml::Value::Integer(_))
        && r.step
            .as_ref()
            .is_none_or(|s| matches!(s, toml::Value::Integer(_)))
        && xs.iter().all(|x| x.fract() == 0.0 && x.abs() < 9e15);
    Ok(xs
        .into_iter()
        .map(|x| {
            let value = if integers {
                Value::from(x as i64)
            } else {
                values::number(x)
            };
            AxisValue {
                text: written(&value),
                value,
            }
        })
        .collect())
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

fn columns(study: Study, wanted: Option<Vec<String>>) -> Result<Vec<Column>> {
    let all = study.columns;
    let Some(wanted) = wanted else {
        return Ok(all.to_vec());
    };
    wanted
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
        .collect()
}

#[cfg(test)]
mod tests;
