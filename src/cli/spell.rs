//! The one place where the libraries' parameter names become the command line's flags.
//!
//! A library message names a parameter as the library does, in backticks: `` `dt` ``,
//! `` `integrator = rattle` ``. [`flags`] writes each one that is a flag of this tool as that
//! flag (`--dt`, `--integrator rattle`, by [`flag_of`]); any other backticked text stays.

use super::request_args::flag_of;
use clap::CommandFactory;
use std::collections::HashSet;
use std::sync::OnceLock;

/// `text` with every backticked parameter that is a flag of the command line written as that
/// flag: `` `dt` `` → `--dt`, `` `integrator = rattle` `` → `--integrator rattle`.
pub fn flags(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some((before, inner, after)) = backticked(rest) {
        out.push_str(before);
        let (name, value) = match inner.split_once(" = ") {
            Some((name, value)) => (name, Some(value.trim_matches('"'))),
            None => (inner, None),
        };
        let flag = flag_of(name);
        if long_flags().contains(&flag) {
            out.push_str(&flag);
            if let Some(value) = value {
                out.push(' ');
                out.push_str(value);
            }
        } else {
            out.push('`');
            out.push_str(inner);
            out.push('`');
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

/// The text before the first `` `…` ``, its contents, and the text after it.
fn backticked(text: &str) -> Option<(&str, &str, &str)> {
    let (before, tail) = text.split_once('`')?;
    let (inner, after) = tail.split_once('`')?;
    Some((before, inner, after))
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
