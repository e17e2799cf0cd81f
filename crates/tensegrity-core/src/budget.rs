//! Resource budget: memory, work and output estimated from a request's *sizes*, before
//! anything is allocated, and the check against limits.
//!
//! An [`Estimate`] holds three numbers for one computation: peak memory (bytes), work
//! (seconds, from a flop count over an assumed sustained rate) and output written (bytes).
//! [`Limits::check`] refuses an estimate above any limit with an [`OverBudget`] error naming
//! the parameters that drive the size ([`Parameters`]), the estimate and the limit. The estimates are
//! deliberately simple closed forms:
//!
//! * dense statics of an m × n equilibrium matrix (SVD with full U and V, the prestress LP and
//!   the flexes on top): memory [`dense_statics_bytes`], work ≈ (4 a² b + 22 b³) flops with
//!   a = max(m, n), b = min(m, n) (Golub–Van Loan's R-SVD count with U and V), times
//!   [`DENSE_OVERHEAD`] for the LP and the flexes, at [`DENSE_FLOP_RATE`];
//! * a fixed-step time integration: steps × right-hand sides per step × flops per right-hand
//!   side ([`rhs_flops`]: bars and strings linear, the Ω system r³/3 dense or ~60 r sparse),
//!   at [`SCALAR_FLOP_RATE`];
//! * output: rows × row bytes.
//!
//! The rates are conservative single-core figures: estimates are meant to be right within a
//! factor of a few, enough to tell a second from an hour. Topology crates refine the estimate
//! of what they actually run (e.g. `toroid::budget`).

use crate::request::{Categorized, Category};
use serde::Serialize;
use std::borrow::Cow;
use std::fmt;

/// Default limit on estimated work: one minute.
pub const DEFAULT_MAX_WORK_S: f64 = 60.0;
/// Default limit on estimated output: 1 GiB.
pub const DEFAULT_MAX_OUTPUT_BYTES: f64 = 1024.0 * 1024.0 * 1024.0;
/// Default limit on estimated peak memory: 8 GiB (callers lower it to what the machine has).
pub const DEFAULT_MAX_MEMORY_BYTES: f64 = 8.0 * 1024.0 * 1024.0 * 1024.0;

/// Sustained rate assumed for dense factorisations (flop/s, one core).
pub const DENSE_FLOP_RATE: f64 = 5e9;
/// Sustained rate assumed for the small, irregular kernels of one dynamics right-hand side
/// (flop/s, one core).
pub const SCALAR_FLOP_RATE: f64 = 1e9;
/// Factor on the SVD's work for the prestress LP and the flexes that follow it.
pub const DENSE_OVERHEAD: f64 = 1.5;

/// The request parameters that drive an estimate's size, by the library's names, with their
/// values as written: `t_end = 10, dt = 0.0001`. A front end writes each in its own spelling
/// ([`Parameters::write`]; the command line as `--t-end 10`). An entry without a name is a
/// note, written as it is (`10000 sweep cases`).
///
/// Built field by field ([`Parameters::and`]) or read from the text `name = value, …`
/// (`From<&str>`: each comma-separated piece of that form is a parameter, any other a note).
///
/// ```
/// use tensegrity_core::budget::Parameters;
/// let p = Parameters::default().and("t_end", 10).and("dt", 1e-4);
/// assert_eq!(p.to_string(), "t_end = 10, dt = 0.0001");
/// assert_eq!(Parameters::from("t_end = 10, dt = 0.0001"), p);
/// assert_eq!(p.write(|name, value| format!("--{name} {value}")), "--t_end 10, --dt 0.0001");
/// assert_eq!(Parameters::from("12 sweep cases").to_string(), "12 sweep cases");
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
pub struct Parameters(pub Vec<(Cow<'static, str>, String)>);

impl Parameters {
    /// With one more parameter.
    pub fn and(mut self, name: impl Into<Cow<'static, str>>, value: impl fmt::Display) -> Self {
        self.0.push((name.into(), value.to_string()));
        self
    }

    /// Each parameter written by `each(name, value)` (a note as it is), joined by `, `.
    pub fn write(&self, each: impl Fn(&str, &str) -> String) -> String {
        let parts: Vec<String> = self
            .0
            .iter()
            .map(|(name, value)| match name.as_ref() {
                "" => value.clone(),
                name => each(name, value),
            })
            .collect();
        parts.join(", ")
    }
}

impl fmt::Display for Parameters {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.write(|name, value| format!("{name} = {value}")))
    }
}

impl From<&str> for Parameters {
    fn from(text: &str) -> Self {
        let is_name = |n: &str| {
            n.starts_with(|c: char| c.is_ascii_lowercase())
                && n.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        };
        let entries = text
            .split(", ")
            .filter(|piece| !piece.trim().is_empty())
            .map(|piece| match piece.split_once(" = ") {
                Some((name, value)) if is_name(name.trim()) => (
                    Cow::Owned(name.trim().to_string()),
                    value.trim().to_string(),
                ),
                _ => (Cow::Borrowed(""), piece.trim().to_string()),
            });
        Parameters(entries.collect())
    }
}

impl From<String> for Parameters {
    fn from(text: String) -> Self {
        Parameters::from(text.as_str())
    }
}

/// The estimated cost of one computation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// The computation, e.g. `the dense statics (SVD of the 18000 × 12000 equilibrium matrix)`.
    pub what: String,
    /// The parameters that drive the size, by the library's names (`sides = 100000`).
    pub parameters: Parameters,
    /// Peak memory (bytes).
    pub memory_bytes: f64,
    /// Work (s).
    pub work_s: f64,
    /// Output written (bytes).
    pub output_bytes: f64,
}

impl Estimate {
    /// An estimate with no memory, work or output yet.
    pub fn new(what: impl Into<String>, parameters: impl Into<Parameters>) -> Self {
        Self {
            what: what.into(),
            parameters: parameters.into(),
            memory_bytes: 0.0,
            work_s: 0.0,
            output_bytes: 0.0,
        }
    }

    /// Sets the peak memory (bytes).
    pub fn memory(mut self, bytes: f64) -> Self {
        self.memory_bytes = bytes;
        self
    }

    /// Sets the work (s).
    pub fn work(mut self, seconds: f64) -> Self {
        self.work_s = seconds;
        self
    }

    /// Sets the output (bytes).
    pub fn output(mut self, bytes: f64) -> Self {
        self.output_bytes = bytes;
        self
    }

    /// Two computations that run one after the other: work and output add, memory is the
    /// larger peak; the description names both, the parameters are the first one's.
    pub fn then(self, other: Estimate) -> Estimate {
        Estimate {
            what: format!("{}, then {}", self.what, other.what),
            memory_bytes: self.memory_bytes.max(other.memory_bytes),
            work_s: self.work_s + other.work_s,
            output_bytes: self.output_bytes + other.output_bytes,
            parameters: self.parameters,
        }
    }
}

/// The resource an estimate exceeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Resource {
    /// Peak memory.
    Memory,
    /// Work (wall time).
    Work,
    /// Output written.
    Output,
}

impl std::fmt::Display for Resource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Resource::Memory => "memory",
            Resource::Work => "work",
            Resource::Output => "output",
        })
    }
}

/// Limits of one run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Limits {
    /// Largest estimated peak memory (bytes).
    pub memory_bytes: f64,
    /// Largest estimated work (s).
    pub work_s: f64,
    /// Largest estimated output (bytes).
    pub output_bytes: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            memory_bytes: DEFAULT_MAX_MEMORY_BYTES,
            work_s: DEFAULT_MAX_WORK_S,
            output_bytes: DEFAULT_MAX_OUTPUT_BYTES,
        }
    }
}

/// An estimate above a limit, refused before anything was allocated. Its message names the
/// parameters as the library does (`sides = 100000: …`); a front end writes them in its own
/// spelling with [`OverBudget::message_with`].
#[derive(Debug, Clone, PartialEq)]
pub struct OverBudget {
    /// The refused estimate.
    pub estimate: Estimate,
    /// The resource over its limit.
    pub resource: Resource,
    /// The estimated amount (bytes or s).
    pub estimated: f64,
    /// The limit (bytes or s).
    pub limit: f64,
}

impl OverBudget {
    /// The message, each parameter written by `each(name, value)`.
    pub fn message_with(&self, each: impl Fn(&str, &str) -> String) -> String {
        let parameters = self.estimate.parameters.write(each);
        let head = if parameters.is_empty() {
            String::new()
        } else {
            format!("{parameters}: ")
        };
        format!(
            "{head}{} needs an estimated {} of {}, above the limit of {}",
            self.estimate.what,
            human(self.resource, self.estimated),
            self.resource,
            human(self.resource, self.limit)
        )
    }
}

impl fmt::Display for OverBudget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message_with(|name, value| format!("{name} = {value}")))
    }
}

impl std::error::Error for OverBudget {}

impl Categorized for OverBudget {
    fn category(&self) -> Category {
        Category::Resource
    }
}

/// `amount` of `resource` for people: bytes in KiB … PiB, seconds in s, min, h, days, years.
pub fn human(resource: Resource, amount: f64) -> String {
    match resource {
        Resource::Memory | Resource::Output => human_bytes(amount),
        Resource::Work => human_seconds(amount),
    }
}

/// Bytes with a binary unit (`1.500 GiB`).
pub fn human_bytes(b: f64) -> String {
    let units = ["PiB", "TiB", "GiB", "MiB", "KiB"];
    for (k, unit) in units.iter().enumerate() {
        let scale = 1024f64.powi(5 - k as i32);
        if b >= scale {
            return format!("{:.3} {unit}", b / scale);
        }
    }
    format!("{b:.0} B")
}

/// Seconds as s, min, h, days or years.
pub fn human_seconds(s: f64) -> String {
    let units = [
        (365.25 * 86400.0, "years"),
        (86400.0, "days"),
        (3600.0, "h"),
        (60.0, "min"),
    ];
    for (scale, unit) in units {
        if s >= scale {
            return format!("{:.3} {unit}", s / scale);
        }
    }
    format!("{s:.3} s")
}

impl Limits {
    /// Refuses `estimate` if it exceeds a limit (memory first, then output, then work). A
    /// non-finite estimate (an overflowing size) is always refused.
    ///
    /// ```
    /// use tensegrity_core::budget::{Estimate, Limits, Resource};
    /// let e = Estimate::new("a run", "t_end = 1e9").work(1e9);
    /// let err = Limits::default().check(&e).unwrap_err();
    /// assert_eq!(err.resource, Resource::Work);
    /// assert!(err.to_string().starts_with("t_end = 1e9: a run needs an estimated"));
    /// assert!(Limits::default().check(&Estimate::new("a run", "t_end = 1").work(0.1)).is_ok());
    /// ```
    pub fn check(&self, estimate: &Estimate) -> Result<(), OverBudget> {
        let checks = [
            (Resource::Memory, estimate.memory_bytes, self.memory_bytes),
            (Resource::Output, estimate.output_bytes, self.output_bytes),
            (Resource::Work, estimate.work_s, self.work_s),
        ];
        for (resource, estimated, limit) in checks {
            if estimated.is_nan() || estimated > limit {
                return Err(OverBudget {
                    estimate: estimate.clone(),
                    resource,
                    estimated,
                    limit,
                });
            }
        }
        Ok(())
    }
}

/// Bytes the dense statics of an m × n equilibrium matrix holds at its peak: A, U and V
/// each in the backend, at the API and in a working copy (3mn + 3m² + 3n²), and the bases of
/// the mechanisms (m × (m − n) at least) or self-stresses (n × (n − m)) held twice, in f64 —
/// calibrated against the measured peak (`crates/tensegrity-engine/tests/statics_estimate.rs`:
/// 155 MB resident for 1800 × 1197, estimated 181 MB).
///
/// ```
/// use tensegrity_core::budget::dense_statics_bytes;
/// // 8 · 3 (1800·1197 + 1800² + 1197²) + 16 · 1800 · 603
/// assert_eq!(dense_statics_bytes(1800, 1197), 24.0 * 6_827_409.0 + 16.0 * 1_085_400.0);
/// ```
pub fn dense_statics_bytes(m: usize, n: usize) -> f64 {
    let (m, n) = (m as f64, n as f64);
    let bases = m * (m - n).max(0.0) + n * (n - m).max(0.0);
    24.0 * (m * n + m * m + n * n) + 16.0 * bases
}

/// Flops of the SVD of an m × n matrix with full U and V (Golub–Van Loan's R-SVD count).
pub fn svd_flops(m: usize, n: usize) -> f64 {
    let (a, b) = (m.max(n) as f64, m.min(n) as f64);
    4.0 * a * a * b + 22.0 * b * b * b
}

/// Estimate of the dense statics (SVD, prestress LP, flexes) of an m × n equilibrium matrix.
///
/// ```
/// use tensegrity_core::budget::dense_statics;
/// let e = dense_statics(1800, 1200, "sides = 100");
/// assert!(e.work_s > 1.0 && e.work_s < 100.0); // seconds, not hours
/// assert!(e.memory_bytes < 2e8); // 181 MB
/// ```
pub fn dense_statics(m: usize, n: usize, parameters: impl Into<Parameters>) -> Estimate {
    Estimate::new(
        format!("the dense statics (SVD of the {m} × {n} equilibrium matrix)"),
        parameters,
    )
    .memory(dense_statics_bytes(m, n))
    .work(DENSE_OVERHEAD * svd_flops(m, n) / DENSE_FLOP_RATE)
}

/// Flops of one dynamics right-hand side with `bars` bars, `strings` strings and
/// `constraint_rows` rows of N P = D: ~120 per bar (two passes of the bar accelerations),
/// ~30 per string, and the Ω system — dense Cholesky r³/3 + 2r² up to 48 rows, else a banded
/// sparse factorisation of ~60 flops a row.
pub fn rhs_flops(bars: usize, strings: usize, constraint_rows: usize) -> f64 {
    let r = constraint_rows as f64;
    let omega = if constraint_rows == 0 {
        0.0
    } else if constraint_rows <= 48 {
        r * r * r / 3.0 + 2.0 * r * r + 20.0 * r
    } else {
        60.0 * r
    };
    120.0 * bars as f64 + 30.0 * strings as f64 + omega
}

/// Estimate of a time integration of `steps` steps with `rhs_per_step` right-hand sides of
/// `flops_per_rhs` each, holding a state of `state_len` numbers.
pub fn integration(
    steps: f64,
    rhs_per_step: f64,
    flops_per_rhs: f64,
    state_len: usize,
    parameters: impl Into<Parameters>,
) -> Estimate {
    Estimate::new(
        format!("{steps:.3e} time steps of a {state_len}-number state"),
        parameters,
    )
    .memory(64.0 * state_len as f64)
    .work(steps * rhs_per_step * (flops_per_rhs + 20.0 * state_len as f64) / SCALAR_FLOP_RATE)
}

/// Estimate of `rows` output rows of `row_bytes` bytes each, kept in memory (`in_memory`)
/// or streamed to a file.
pub fn table(
    rows: f64,
    row_bytes: f64,
    in_memory: bool,
    parameters: impl Into<Parameters>,
) -> Estimate {
    let bytes = rows * row_bytes;
    Estimate::new(format!("{rows:.3e} output rows"), parameters)
        .output(bytes)
        .memory(if in_memory { bytes } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn over_budget_names_the_parameter_the_estimate_and_the_limit() {
        let e = dense_statics(
            600_000,
            1_600_000,
            Parameters::default().and("sides", 100_000),
        );
        let err = Limits::default().check(&e).unwrap_err();
        assert_eq!(err.resource, Resource::Memory);
        // 24 (m n + m² + n²) + 16 n (n − m) = 24 · 3.88e12 + 16 · 1.6e12 = 1.1872e14 B
        // = 107.975 TiB
        assert!((err.estimated - 1.1872e14).abs() < 1e9, "{}", err.estimated);
        let text = err.to_string();
        assert!(
            text.starts_with("sides = 100000: the dense statics"),
            "{text}"
        );
        let flags = err.message_with(|name, value| format!("--{name} {value}"));
        assert!(
            flags.starts_with("--sides 100000: the dense statics"),
            "{flags}"
        );
        assert!(text.contains("107.975 TiB"), "{text}");
        assert!(text.contains("8.000 GiB"), "{text}");
    }

    #[test]
    fn the_svd_count_is_golub_van_loan() {
        // square n: 4 n³ + 22 n³ = 26 n³
        assert_eq!(svd_flops(10, 10), 26_000.0);
        assert_eq!(svd_flops(20, 10), svd_flops(10, 20));
        assert_eq!(svd_flops(20, 10), 4.0 * 400.0 * 10.0 + 22_000.0);
    }

    #[test]
    fn nan_and_infinite_estimates_are_refused() {
        let e = Estimate::new("x", "n = 1").work(f64::NAN);
        assert!(Limits::default().check(&e).is_err());
        let e = Estimate::new("x", "n = 1").output(f64::INFINITY);
        assert_eq!(
            Limits::default().check(&e).unwrap_err().resource,
            Resource::Output
        );
    }

    #[test]
    fn sequential_steps_add_work_and_keep_the_peak_memory() {
        let a = Estimate::new("a", "p").memory(10.0).work(1.0).output(5.0);
        let b = Estimate::new("b", "q").memory(4.0).work(3.0).output(1.0);
        let c = a.then(b);
        assert_eq!((c.memory_bytes, c.work_s, c.output_bytes), (10.0, 4.0, 6.0));
        assert_eq!(c.what, "a, then b");
        assert_eq!(c.parameters, Parameters::from("p"));
    }

    #[test]
    fn human_units() {
        assert_eq!(human_bytes(1.5 * 1024f64.powi(3)), "1.500 GiB");
        assert_eq!(human_bytes(512.0), "512 B");
        assert_eq!(human_seconds(90.0), "1.500 min");
        assert_eq!(human_seconds(2.0), "2.000 s");
    }
}
