//! Exit codes (DESIGN.md, Outputs): 0 success, 1 failure of the computation, 2 bad input or
//! usage (clap's own errors exit 2 as well).

use michell3d::MichellError;
use tensegrity_core::request::{Categorized, Category};
use tensegrity_core::CoreError;
use tensegrity_io::interrupt::Interrupted;
use tensegrity_io::IoError;
use toroid::ToroidError;

/// Success.
pub const OK: i32 = 0;
/// The computation failed (not prestressable, diverged, load not carried, …).
pub const FAILURE: i32 = 1;
/// Bad input: a parameter out of range, an unreadable or invalid file.
pub const BAD_INPUT: i32 = 2;
/// Interrupted by SIGINT/SIGTERM (128 + 2, the shell's convention for Ctrl-C).
pub const INTERRUPTED: i32 = 130;

/// Installs the SIGINT/SIGTERM handler of [`tensegrity_io::interrupt`]: a command that polls
/// the stop flag finishes its outputs as incomplete and exits [`INTERRUPTED`]; any other is
/// ended by the handler, which keeps the rows so far of its open sinks.
pub fn install_interrupt_handler() {
    tensegrity_io::interrupt::install(|kept| {
        let kept: Vec<String> = kept.iter().map(|p| p.display().to_string()).collect();
        if kept.is_empty() {
            eprintln!("error: interrupted");
        } else {
            eprintln!(
                "error: interrupted; kept, marked incomplete: {}",
                kept.join(", ")
            );
        }
    });
}

/// The exit code of a failed command: [`OK`] for a closed stdout (`… | head`), [`BAD_INPUT`]
/// when any error in the chain is about the input, else [`FAILURE`].
pub fn code(e: &anyhow::Error) -> i32 {
    let broken_pipe = e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    });
    if broken_pipe {
        OK
    } else if e.chain().any(is_interrupted) {
        INTERRUPTED
    } else if e.chain().any(is_bad_input) {
        BAD_INPUT
    } else {
        FAILURE
    }
}

fn is_interrupted(e: &(dyn std::error::Error + 'static)) -> bool {
    e.is::<Interrupted>()
        || e.downcast_ref::<sweeps::SweepError>()
            .is_some_and(|s| s.is_interrupted())
}

fn is_bad_input(e: &(dyn std::error::Error + 'static)) -> bool {
    // a request over the resource limits is refused like a bad value
    if e.is::<super::guard::Refused>() || e.is::<tensegrity_core::budget::OverBudget>() {
        return true;
    }
    // a flag value a request refuses
    if e.is::<tensegrity_core::request::InvalidParameter>() {
        return true;
    }
    if let Some(e) = e.downcast_ref::<CoreError>() {
        return matches!(
            e,
            CoreError::InvalidParameter { .. } | CoreError::TooLarge { .. }
        );
    }
    if let Some(e) = e.downcast_ref::<ToroidError>() {
        return matches!(
            e,
            ToroidError::InvalidParameter { .. } | ToroidError::UnknownStabilizeOption { .. }
        ) || matches!(
            e,
            ToroidError::Core(CoreError::InvalidParameter { .. } | CoreError::TooLarge { .. })
        );
    }
    if let Some(e) = e.downcast_ref::<MichellError>() {
        return matches!(
            e,
            MichellError::InvalidParameter { .. }
                | MichellError::Core(CoreError::InvalidParameter { .. })
        );
    }
    if let Some(e) = e.downcast_ref::<tbar_wheel::TbarError>() {
        use tbar_wheel::TbarError as T;
        return matches!(
            e,
            T::InvalidParameter { .. }
                | T::TooLarge { .. }
                | T::Michell(MichellError::InvalidParameter { .. })
                | T::Core(CoreError::InvalidParameter { .. })
        );
    }
    if let Some(e) = e.downcast_ref::<sweeps::SweepError>() {
        return e.is_input_error();
    }
    if let Some(e) = e.downcast_ref::<tensegrity_engine::SceneError>() {
        return e.category() == Category::Input;
    }
    e.downcast_ref::<IoError>()
        .is_some_and(|e| e.category() == Category::Input)
}

/// The error and its causes joined by `: `, leaving out a cause its parent's message
/// already quotes (many errors print their source).
pub fn message(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if !parts.last().is_some_and(|p| p.contains(&text)) {
            parts.push(text);
        }
    }
    parts.join(": ")
}
