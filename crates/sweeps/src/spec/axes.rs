//! The `[axes]` of a spec: each axis read as the spec writes it and sized ([`AxisSource`]:
//! a list's items, or a range's plan — its length known without its values), the sizes
//! checked against the resource limits ([`crate::limits::admit_axes`]), and only then the
//! values made ([`Axis`]).

use super::{check_name, Axis, AxisValue, MAX_CASES};
use crate::error::{Result, SweepError};
use crate::values::{self, from_toml, written};
use crate::Study;
use serde::Deserialize;
use serde_json::Value;
use std::ops::Range;
use tensegrity_core::budget::Limits;

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

/// How a range's values are spaced.
#[derive(Debug, Clone, Copy)]
enum Spacing {
    /// `steps` points from `from` to `to`, both included (geometric with `log`).
    Steps { n: usize, log: bool },
    /// `from`, `from + step`, … up to `to`, rounded to `decimals` decimals.
    Step {
        h: f64,
        count: usize,
        decimals: usize,
    },
}

/// A checked range: its length is known before any value is made.
#[derive(Debug, Clone, Copy)]
struct RangePlan {
    from: f64,
    to: f64,
    spacing: Spacing,
    /// Integer `from`, `to` (and `step`): the values are integers when every one is whole.
    integer_bounds: bool,
}

impl RangePlan {
    fn len(&self) -> usize {
        match self.spacing {
            Spacing::Steps { n, .. } => n,
            Spacing::Step { count, .. } => count,
        }
    }

    /// Value `i` of the range.
    fn value(&self, i: usize) -> f64 {
        let (from, to) = (self.from, self.to);
        match self.spacing {
            Spacing::Steps { n, log } => {
                // interior points rounded to 15 significant digits: 1e-5, not 1.0000000000000003e-5
                let round = |x: f64| format!("{x:.14e}").parse().unwrap_or(x);
                let t = i as f64 / (n.max(2) - 1) as f64;
                match i {
                    0 => from,
                    i if i == n - 1 => to,
                    _ if log => round(from * (to / from).powf(t)),
                    _ => round(from + (to - from) * t),
                }
            }
            Spacing::Step { h, decimals, .. } => {
                let x = from + i as f64 * h;
                format!("{x:.decimals$}").parse().unwrap_or(x)
            }
        }
    }
}

/// An axis as the spec writes it, sized but not yet made.
enum AxisSource<'a> {
    /// A list: its items and their byte spans in the spec.
    List(&'a [toml::Value], Vec<Range<usize>>),
    /// A range.
    Range(RangePlan),
}

impl AxisSource<'_> {
    fn len(&self) -> usize {
        match self {
            AxisSource::List(items, _) => items.len(),
            AxisSource::Range(plan) => plan.len(),
        }
    }
}

/// The `[axes]` entries in document order, with the source text of every list item; their
/// sizes are checked against `limits` ([`crate::limits::admit_axes`]: the values of each
/// axis, the number of cases, the sweep's output) before any value is made.
pub(super) fn axes(
    study: Study,
    text: &str,
    table: &toml::Table,
    limits: &Limits,
) -> Result<Vec<Axis>> {
    let mut sources = Vec::new();
    for (name, item_spans) in axis_spans(text)? {
        let p = check_name(study, "axes", &name)?;
        let v = table.get(&name).ok_or_else(|| SweepError::Spec {
            message: format!("axis `{name}` not found"),
        })?;
        let source = match v {
            toml::Value::Array(items) if items.is_empty() => {
                return Err(axis_err(&name, "no values".into()))
            }
            toml::Value::Array(items) => AxisSource::List(items, item_spans),
            toml::Value::Table(t) => {
                let r: RawRange = t.clone().try_into().map_err(|e: toml::de::Error| {
                    axis_err(
                        &name,
                        format!("a range is {{ from, to, steps | step, log }}: {e}"),
                    )
                })?;
                AxisSource::Range(range_plan(&name, &r)?)
            }
            _ => return Err(axis_err(&name, "expected a list or a range table".into())),
        };
        sources.push((name, p.kind.is_list(), source));
    }
    let sizes: Vec<(&str, usize)> = sources
        .iter()
        .map(|(name, _, s)| (name.as_str(), s.len()))
        .collect();
    crate::limits::admit_axes(&sizes, limits)?;
    sources
        .into_iter()
        .map(|(name, lists, source)| {
            let values = match source {
                AxisSource::List(items, spans) => list_values(&name, items, &spans, text, lists)?,
                AxisSource::Range(plan) => range_values(&plan),
            };
            Ok(Axis { name, values })
        })
        .collect()
}

pub(super) fn axis_err(axis: &str, reason: String) -> SweepError {
    SweepError::InvalidAxis {
        axis: axis.to_string(),
        reason,
    }
}

/// Axis names in document order, each with the byte spans of its list items (empty for a
/// range).
fn axis_spans(text: &str) -> Result<Vec<(String, Vec<Range<usize>>)>> {
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
    let mut entries: Vec<(usize, String, Vec<Range<usize>>)> = axes
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
    spans: &[Range<usize>],
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

/// The checked range of `r`, its length known (no value made).
fn range_plan(name: &str, r: &RawRange) -> Result<RangePlan> {
    let (from, to) = (number(name, "from", &r.from)?, number(name, "to", &r.to)?);
    let spacing = match (r.steps, &r.step) {
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
            Spacing::Steps {
                n: n as usize,
                log: r.log,
            }
        }
        (None, Some(step)) if !r.log => step_spacing(name, from, to, step)?,
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
    let integer_bounds = matches!(r.from, toml::Value::Integer(_))
        && matches!(r.to, toml::Value::Integer(_))
        && r.step
            .as_ref()
            .is_none_or(|s| matches!(s, toml::Value::Integer(_)));
    Ok(RangePlan {
        from,
        to,
        spacing,
        integer_bounds,
    })
}

/// The spacing `{ from, to, step }`: its number of values, counted without making them.
fn step_spacing(name: &str, from: f64, to: f64, step: &toml::Value) -> Result<Spacing> {
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
    Ok(Spacing::Step {
        h,
        count: count as usize,
        decimals: decimals(from).max(decimals(h)),
    })
}

/// The values of a checked range (integers when its bounds are and every value is whole).
fn range_values(plan: &RangePlan) -> Vec<AxisValue> {
    let xs: Vec<f64> = (0..plan.len()).map(|i| plan.value(i)).collect();
    let integers = plan.integer_bounds && xs.iter().all(|x| x.fract() == 0.0 && x.abs() < 9e15);
    xs.into_iter()
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
        .collect()
}
