//! How a front end that speaks in flags writes a library's parameter names: the command line,
//! and the Python package, whose messages are the command line's word for word. Libraries name
//! their parameters in backticks (`` `dt` ``, `` `integrator = rattle` ``); a front end that
//! renames them does so here, in one place, deciding itself which names are its flags.
//!
//! ```
//! use tensegrity_engine::spelling::{flag_of, spell_flags};
//! assert_eq!(flag_of("t_end"), format!("{}{}", "--", "t-end"));
//! let text = spell_flags("use a smaller `dt` or `integrator = rk45`; no `energy_j`", |n| n != "energy_j");
//! assert_eq!(text, format!("use a smaller {0}dt or {0}integrator rk45; no `energy_j`", "--"));
//! ```

use tensegrity_core::budget::Parameters;

/// The long option of a parameter: `t_end` → `--t-end`.
pub fn flag_of(name: &str) -> String {
    format!("--{}", name.replace('_', "-"))
}

/// The flags of an estimate's named parameters: `t_end = 1e9, dt = 0.001 s` → `--t-end 1e9
/// --dt 0.001` (a note such as `10 sweep cases` names no parameter and has no flag).
pub fn parameter_flags(parameters: &Parameters) -> String {
    let flags: Vec<String> = parameters
        .0
        .iter()
        .filter(|(name, _)| {
            !name.is_empty() && name.chars().all(|c| c.is_ascii_lowercase() || c == '_')
        })
        .filter_map(|(name, value)| {
            let value = value.split_whitespace().next()?;
            Some(format!("{} {value}", flag_of(name)))
        })
        .collect();
    flags.join(" ")
}

/// `text` with every backticked parameter for which `is_flag` holds written as its flag
/// (`` `dt` `` → `--dt`, `` `integrator = rattle` `` → `--integrator rattle`); any other
/// backticked text, and an unclosed backtick, stay as they are.
pub fn spell_flags(text: &str, is_flag: impl Fn(&str) -> bool) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some((before, inner, after)) = backticked(rest) {
        out.push_str(before);
        let (name, value) = match inner.split_once(" = ") {
            Some((name, value)) => (name, Some(value.trim_matches('"'))),
            None => (inner, None),
        };
        if is_flag(name) {
            out.push_str(&flag_of(name));
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
