//! Exit codes (DESIGN.md, Outputs): 0 success, 1 failure of the computation, 2 bad input or
//! usage (clap's own errors exit 2 as well).

use michell3d::MichellError;
use sweeps::SweepError;
use tbar_wheel::TbarError;
use tensegrity_core::budget::OverBudget;
use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;
use tensegrity_engine::formfind::FormfindFailure;
use tensegrity_engine::{RunError, SceneError};
use tensegrity_io::interrupt::Interrupted;
use tensegrity_io::IoError;
use toroid::ToroidError;
use wheel_rolling::RollingError;

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

/// The exit code of a failed command: [`OK`] for a closed stdout (`… | head`), else by the
/// [`Category`] of the error ([`category`]): [`INTERRUPTED`] when any error in the chain was
/// interrupted, [`BAD_INPUT`] for input and resource refusals, [`FAILURE`] for a failed
/// computation or an error without a category.
pub fn code(e: &anyhow::Error) -> i32 {
    let broken_pipe = e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    });
    if broken_pipe {
        return OK;
    }
    let categories: Vec<Category> = e.chain().filter_map(category).collect();
    if categories.contains(&Category::Interrupted) {
        return INTERRUPTED;
    }
    match categories.first() {
        Some(Category::Input | Category::Resource) => BAD_INPUT,
        _ => FAILURE,
    }
}

/// The [`Category`] of one error of the chain, when it is a [`Categorized`] error of a
/// library (each wraps its sources' errors and asks them for theirs), or the CLI's refusal.
fn category(e: &(dyn std::error::Error + 'static)) -> Option<Category> {
    macro_rules! first_of {
        ($($t:ty),*) => {
            None $(.or_else(|| e.downcast_ref::<$t>().map(Categorized::category)))*
        };
    }
    if e.is::<super::guard::Refused>() {
        return Some(Category::Resource);
    }
    first_of!(
        InvalidParameter,
        OverBudget,
        CoreError,
        IoError,
        Interrupted,
        RollingError,
        ToroidError,
        MichellError,
        TbarError,
        SweepError,
        RunError,
        SceneError,
        FormfindFailure
    )
}

/// The error and its causes joined by `: `, leaving out a cause its parent's message
/// already quotes (many errors print their source); the parameters it names written as flags
/// ([`super::spell::flags`]), except in a sweep's errors, which name them as its spec does.
pub fn message(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if !parts.last().is_some_and(|p| p.contains(&text)) {
            parts.push(text);
        }
    }
    let text = parts.join(": ");
    // a sweep's errors name its spec's keys, a scene file's parse errors the file's keys
    // (`missing field `mass``): neither is a flag
    let file_keys = |c: &(dyn std::error::Error + 'static)| {
        let parse = |e: Option<&IoError>| matches!(e, Some(IoError::Parse { .. }));
        c.is::<SweepError>()
            || parse(c.downcast_ref::<IoError>())
            // a transparent wrapper hides the io error from the chain
            || matches!(c.downcast_ref::<SceneError>(), Some(SceneError::Io(e)) if parse(Some(e)))
    };
    if e.chain().any(file_keys) {
        text
    } else {
        super::spell::flags(&text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::DynamicsError;

    #[test]
    fn the_exit_code_follows_the_category_of_the_first_categorized_error() {
        let bad = InvalidParameter::new("dt", -1.0, "must be positive");
        let with_context = anyhow::Error::new(bad.clone()).context("invalid value for --dt");
        assert_eq!(code(&with_context), BAD_INPUT);
        let diverged = CoreError::from(DynamicsError::Diverged { t: 1.0, what: "Ω" });
        assert_eq!(
            code(&anyhow::Error::new(ToroidError::Core(diverged))),
            FAILURE
        );
        let too_large = TbarError::TooLarge {
            what: "free degrees of freedom",
            size: 10,
            limit: 5,
        };
        assert_eq!(code(&anyhow::Error::new(too_large)), BAD_INPUT);
        let stopped = RollingError::Core(CoreError::Interrupted { t: 0.5 });
        assert_eq!(code(&anyhow::Error::new(stopped)), INTERRUPTED);
        assert_eq!(code(&anyhow::anyhow!("no category")), FAILURE);
    }

    /// A scene file's parse error names the file's key (`mass`), which is not the flag
    /// `--mass` of another command.
    #[test]
    fn a_scene_files_parse_error_keeps_its_keys() {
        let parse = IoError::Parse {
            file: "s.toml".into(),
            line: 69,
            column: 1,
            message: "missing field `mass`".into(),
        };
        let text = message(&anyhow::Error::new(SceneError::Io(parse)).context("simulating s.toml"));
        assert!(text.ends_with("missing field `mass`"), "{text}");
    }

    #[test]
    fn messages_write_parameters_as_flags_except_in_sweeps() {
        let diverged = CoreError::from(DynamicsError::Diverged { t: 1.0, what: "Ω" });
        let text = message(&anyhow::Error::new(diverged));
        assert!(
            text.contains("use a smaller --dt, --integrator rk45"),
            "{text}"
        );
        let sweep = SweepError::MissingParameter {
            study: "roll",
            name: "t_end",
        };
        assert!(message(&anyhow::Error::new(sweep)).contains("`t_end`"));
    }
}
