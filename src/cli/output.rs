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
        verdict.push_str(&format!(
            "; chaotic (a start turned by 1e-6 moves them: single draws, see --ensemble): {}",
            chaotic.join(", ")
        ));
    }
    println!(
        "convergence ({}; order {}; cost {} runs): {verdict}",
        c.refinement, c.order, c.cost
    );
}

/// Prints a report as pretty JSON with the conventional keys added beside its own
/// ([`tensegrity_engine::keys`]).
pub fn print_json(report: &impl serde::Serialize) -> Result<()> {
    let value = tensegrity_engine::keys::conventional(serde_json::to_value(report)?);
    println!("{}", serde_json::to_string_pretty(&value)?);
    Ok(())
}
