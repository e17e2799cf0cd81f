//! Output flags: each opens its io sink ([`tensegrity_io::sink`]) before the command's work,
//! so a bad path fails at once, naming the flag and the path (exit code 2).

use anyhow::{Context, Result};
use std::path::Path;

/// Opens the sink of the output flag `flag` (e.g. `--out`) when a path was given.
pub fn open<T>(
    flag: &str,
    path: Option<&Path>,
    open: impl FnOnce(&Path) -> tensegrity_io::Result<T>,
) -> Result<Option<T>> {
    path.map(|p| open(p).with_context(|| flag.to_string()))
        .transpose()
}

/// Opens the sink of an output flag that always has a path (a default value).
pub fn open_required<T>(
    flag: &str,
    path: &Path,
    open: impl FnOnce(&Path) -> tensegrity_io::Result<T>,
) -> Result<T> {
    open(path).with_context(|| flag.to_string())
}

/// The end of a text headline: ` — INVALID (see the warnings)` for a result that is not valid.
pub fn invalid_mark(valid: bool) -> &'static str {
    if valid {
        ""
    } else {
        " — INVALID (see the warnings)"
    }
}

/// One line on the convergence check: what the companion run changed, which quantities
/// held, which are chaotic (single draws), and the check's cost in runs of work.
pub fn print_convergence(c: Option<&tensegrity_dynamics::Convergence>) {
    use tensegrity_dynamics::convergence::Status;
    let Some(c) = c else {
        return println!("convergence: not checked");
    };
    let named = |status: Status| -> Vec<&str> {
        c.quantities
            .iter()
            .filter(|q| q.status == status)
            .map(|q| q.name.as_str())
            .collect()
    };
    let (moved, chaotic) = (named(Status::NotConverged), named(Status::Chaotic));
    let held = c.quantities.len() - moved.len() - chaotic.len();
    let mut verdict = match (c.converged, moved.is_empty()) {
        (true, _) => format!(
            "{held} of {} headline quantities converged",
            c.quantities.len()
        ),
        (false, true) => "not converged".to_string(),
        (false, false) => format!("not converged: {}", moved.join(", ")),
    };
    if !chaotic.is_empty() {
        let ranged: Vec<String> = c
            .quantities
            .iter()
            .filter(|q| q.status == Status::Chaotic)
            .map(|q| match q.interval {
                Some([lo, hi]) => format!("{} {} … {}", q.name, short(lo), short(hi)),
                None => q.name.clone(),
            })
            .collect();
        verdict.push_str(&format!(
            "; chaotic (a start turned by 1e-6 moves them: single draws, each with the 95 % interval of another run from these three runs): {}",
            ranged.join(", ")
        ));
    }
    println!(
        "convergence ({}; order {}; cost {} runs): {verdict}",
        c.refinement, c.order, c.cost
    );
}

/// A number to 4 significant digits, without an exponent in the usual range.
fn short(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else if (1e-3..1e5).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

/// A number as given (every digit that round-trips), with an exponent outside 10⁻⁴ … 10¹⁵
/// so that `1e300` does not print as 301 digits.
pub fn exact(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
        v.to_string()
    } else {
        format!("{v:e}")
    }
}

/// Prints a report as pretty JSON with the conventional keys added beside its own
/// ([`tensegrity_engine::keys`]).
pub fn print_json(report: &impl serde::Serialize) -> Result<()> {
    let value = tensegrity_engine::keys::conventional(serde_json::to_value(report)?);
    println!("{}", serde_json::to_string_pretty(&value)?);
    Ok(())
}

#[cfg(test)]
mod tests {
    /// Four significant digits in the usual range, an exponent outside it, and zero (whose
    /// logarithm has no digits) as `0`.
    /// Every digit in the usual range, an exponent beyond it.
    #[test]
    fn exact_numbers_keep_every_digit_and_an_exponent_when_huge() {
        use super::exact;
        assert_eq!(exact(107.99708115084809), "107.99708115084809");
        assert_eq!(exact(-1e6), "-1000000");
        assert_eq!(exact(1e300), "1e300");
        assert_eq!(exact(-2.5e-7), "-2.5e-7");
        assert_eq!(exact(0.0), "0");
    }

    #[test]
    fn short_numbers_keep_four_digits() {
        use super::short;
        assert_eq!(short(24.8123), "24.81");
        assert_eq!(short(0.0647339), "0.06473");
        assert_eq!(short(188.21), "188.2");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(-0.3), "-0.3000");
        assert_eq!(short(2.5e-7), "2.500e-7");
    }
}
