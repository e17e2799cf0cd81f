//! The resource limits of a sweep: every case is estimated before it runs (the registry's
//! [`tensegrity_engine::Command::estimate`], the same estimate as the single-point command's)
//! and a case over the limits of [`crate::RunOptions::limits`] is refused — an `error` row
//! that names the parameter, the estimate and the limit — instead of allocating what it
//! cannot finish; the other cases run. [`output`] estimates the sweep's own file.

use crate::Study;
use serde_json::{Map, Value};
use tensegrity_core::budget::{self, Estimate, Limits};

/// Bytes a CSV row of a case takes, about.
pub const ROW_BYTES: f64 = 200.0;

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
