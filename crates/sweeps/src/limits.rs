//! The resource limits of a sweep: every case is estimated before it runs (the registry's
//! [`tensegrity_engine::Command::estimate`], the same estimate as the single-point command's)
//! and a case over the limits of [`crate::RunOptions::limits`] is refused — an `error` row
//! that names the parameter, the estimate and the limit — instead of allocating what it
//! cannot finish; the other cases run. [`output`] estimates the sweep's own file.
//!
//! Before that, when the spec is read ([`crate::Spec::parse_within`]), [`admit_axes`]
//! checks what the axes themselves cost before any of their values is made: the values of
//! each axis ([`axis`], memory), the number of cases ([`crate::MAX_CASES`]) and the CSV of
//! their product ([`product`], output), each refusal naming the axes.

use crate::error::SweepError;
use crate::Study;
use serde_json::{Map, Value};
use tensegrity_core::budget::{self, Estimate, Limits, Parameters};

/// Largest number of cases a spec may describe.
pub const MAX_CASES: u64 = 100_000_000;

/// Bytes a CSV row of a case takes, about.
pub const ROW_BYTES: f64 = 200.0;

/// Bytes one axis value holds once made: its JSON value (32 B), its CSV text (24 B and a heap
/// block of at least 32 B), the range's number (8 B) and the vectors' slack, rounded up.
pub const AXIS_VALUE_BYTES: f64 = 128.0;

/// The memory of the `values` values of the axis `name`, named by a note
/// (`axis sigma (100000000 values)`: the name as the spec writes it, unquoted, so that a
/// front end does not take it for a flag of its own).
///
/// ```
/// let e = sweeps::limits::axis("sigma", 100_000_000);
/// assert_eq!(e.memory_bytes, 1.28e10);
/// assert_eq!(e.parameters.to_string(), "axis sigma (100000000 values)");
/// ```
pub fn axis(name: &str, values: usize) -> Estimate {
    Estimate::new(
        "the axis's value list",
        Parameters::default().and("", format!("axis {name} ({values} values)")),
    )
    .memory(values as f64 * AXIS_VALUE_BYTES)
}

/// The sweep's CSV for the product of `axes` (name, number of values): one row of
/// ~[`ROW_BYTES`] per case, named by the axes and the number of cases.
///
/// ```
/// let e = sweeps::limits::product(&[("sides", 10_000), ("outer_radius", 1_000)]);
/// assert_eq!(e.output_bytes, 2e9);
/// assert_eq!(
///     e.parameters.to_string(),
///     "axes sides (10000 values) × outer_radius (1000 values): 10000000 sweep cases"
/// );
/// ```
pub fn product(axes: &[(&str, usize)]) -> Estimate {
    let cases = axes
        .iter()
        .fold(1u128, |n, &(_, len)| n.saturating_mul(len as u128));
    let named: Vec<String> = axes
        .iter()
        .map(|(name, len)| format!("{name} ({len} values)"))
        .collect();
    let head = match named.len() {
        0 => String::new(),
        1 => format!("axis {}: ", named[0]),
        _ => format!("axes {}: ", named.join(" × ")),
    };
    Estimate {
        parameters: Parameters::default().and("", format!("{head}{cases} sweep cases")),
        ..budget::table(cases as f64, ROW_BYTES, false, "")
    }
}

/// Checks the axes of a spec before their values are made: each axis's values
/// against the memory limit ([`axis`]), their product against [`crate::MAX_CASES`], the CSV
/// of the product against the output limit ([`product`]). `axes`: name and number of values,
/// in the spec's order.
///
/// ```
/// use tensegrity_core::budget::Limits;
/// let e = sweeps::limits::admit_axes(&[("sigma", 100_000_000)], &Limits::default()).unwrap_err();
/// let text = e.to_string();
/// assert!(text.starts_with("axis sigma (100000000 values): the axis's value list needs"), "{text}");
/// assert!(sweeps::limits::admit_axes(&[("sigma", 3), ("epsilon", 5)], &Limits::default()).is_ok());
/// ```
pub fn admit_axes(axes: &[(&str, usize)], limits: &Limits) -> Result<(), SweepError> {
    let over = |over| SweepError::OverBudget {
        over: Box::new(over),
    };
    for &(name, len) in axes {
        limits.check(&axis(name, len)).map_err(over)?;
    }
    let cases = axes
        .iter()
        .fold(1u128, |n, &(_, len)| n.saturating_mul(len as u128));
    if cases > MAX_CASES as u128 {
        return Err(SweepError::TooManyCases {
            cases,
            limit: MAX_CASES,
        });
    }
    limits.check(&product(axes)).map_err(over)
}

/// Whether a case of `study` with `values` fits `limits`: `Err` with the message of its row
/// when its estimate is over a limit. A case whose estimate cannot be made (a value the
/// request refuses, an unreadable scene) is admitted: its run reports why.
///
/// ```
/// use serde_json::json;
/// use tensegrity_core::budget::Limits;
/// let toroid = tensegrity_engine::command("toroid").unwrap();
/// let values = |n: u64| json!({ "sides": n }).as_object().unwrap().clone();
/// assert!(sweeps::limits::admit(toroid, &values(8), &Limits::default()).is_ok());
/// let e = sweeps::limits::admit(toroid, &values(100_000_000), &Limits::default()).unwrap_err();
/// let e = e.to_string();
/// assert!(e.contains("sides = 100000000") && e.contains("above the limit"), "{e}");
/// ```
pub fn admit(study: Study, values: &Map<String, Value>, limits: &Limits) -> Result<(), Refused> {
    match study.estimate(values.clone()) {
        Ok(Some(estimate)) => limits
            .check(&estimate)
            .map_err(|over| Refused(Box::new(over))),
        Ok(None) | Err(_) => Ok(()),
    }
}

/// A case refused before it ran: its estimate is above a limit.
#[derive(Debug, Clone, thiserror::Error)]
#[error("refused before running: {0}")]
pub struct Refused(pub Box<tensegrity_core::budget::OverBudget>);

/// The sweep's own output: one CSV row of ~[`ROW_BYTES`] per case, streamed (the work is
/// not estimated: a sweep shows its progress and can be resumed).
///
/// ```
/// let e = sweeps::limits::output(10_000_000);
/// assert_eq!((e.output_bytes, e.memory_bytes), (2e9, 0.0));
/// assert_eq!(e.parameters.to_string(), "10000000 sweep cases");
/// ```
pub fn output(cases: usize) -> Estimate {
    budget::table(
        cases as f64,
        ROW_BYTES,
        false,
        format!("{cases} sweep cases"),
    )
}
