//! The one place where the libraries' parameter names become the command line's flags.
//!
//! A library message names a parameter as the library does, in backticks: `` `dt` ``,
//! `` `integrator = rattle` ``. [`flags`] writes each one that is a flag of this tool as that
//! flag (`--dt`, `--integrator rattle`, by [`flag_of`]); any other backticked text stays.

use clap::CommandFactory;
use std::collections::HashSet;
use std::sync::OnceLock;
use tensegrity_engine::spelling::{flag_of, spell_flags};

/// `text` with every backticked parameter that is a flag of the command line written as that
/// flag: `` `dt` `` → `--dt`, `` `integrator = rattle` `` → `--integrator rattle`.
pub fn flags(text: &str) -> String {
    spell_flags(text, |name| long_flags().contains(&flag_of(name)))
}

/// Every long flag of every subcommand (`--dt`, `--sides`, …).
fn long_flags() -> &'static HashSet<String> {
    static FLAGS: OnceLock<HashSet<String>> = OnceLock::new();
    FLAGS.get_or_init(|| {
        let mut flags = HashSet::new();
        let mut stack = vec![crate::Cli::command()];
        while let Some(command) = stack.pop() {
            flags.extend(
                command
                    .get_arguments()
                    .filter_map(|a| a.get_long())
                    .map(|l| format!("--{l}")),
            );
            stack.extend(command.get_subcommands().cloned());
        }
        flags
    })
}

#[cfg(test)]
mod tests {
    use super::flags;

    #[test]
    fn backticked_parameters_become_flags_and_other_text_stays() {
        assert_eq!(
            flags("use a smaller `dt`, `integrator = rk45` or `t_end = 1`"),
            "use a smaller --dt, --integrator rk45 or --t-end 1"
        );
        assert_eq!(
            flags("no column `energy_j`; `unclosed"),
            "no column `energy_j`; `unclosed"
        );
    }
}
