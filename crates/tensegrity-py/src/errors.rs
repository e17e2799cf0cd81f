//! Errors as Python exceptions, with the command line's text.
//!
//! Every library error is [`Categorized`]; its category picks the exception class of
//! `tensegrity.errors` (Python): input → `InputError` (a `ValueError`), resource →
//! `ResourceError`, numerical → `ComputationError` (both `RuntimeError`s), interrupted →
//! `Interrupted` (a `KeyboardInterrupt`).
//!
//! The message is the command line's, word for word, so one text serves both front ends: a
//! bad keyword value reads `invalid value for --sides: sides = 1: …` (the CLI's
//! `usage_message`), a library message names its parameters as flags (`` `dt` `` → `--dt`, as
//! the CLI's `spell::flags` writes every backticked name that is a flag), and a refused
//! estimate names the limit's flag (`--max-work`). The flag of a keyword is the keyword in
//! kebab-case; the exception's `parameter` attribute gives the keyword itself.

use pyo3::prelude::*;
use std::collections::HashSet;
use std::sync::OnceLock;
use tensegrity_core::budget::{OverBudget, Resource};
use tensegrity_core::request::{Category, InvalidParameter};
use tensegrity_engine::RunError;

/// An error on its way to Python: the category, the message and the parameter it names.
#[derive(Debug, Clone)]
pub struct Failure {
    /// Which exception class.
    pub category: Category,
    /// The message (the command line's text).
    pub message: String,
    /// The keyword it names, when a bad value.
    pub parameter: Option<String>,
}

impl Failure {
    /// A failure of `category` with `message` spelled as the command line spells it.
    pub fn new(category: Category, message: impl AsRef<str>) -> Self {
        Self {
            category,
            message: flags(message.as_ref()),
            parameter: None,
        }
    }

    /// A failure whose message stays as the library wrote it (a sweep's errors name the
    /// parameters as its spec does, as on the command line).
    pub fn raw(category: Category, message: impl Into<String>) -> Self {
        Self {
            category,
            message: message.into(),
            parameter: None,
        }
    }

    /// A bad keyword value, as the command line's usage error.
    pub fn invalid(p: &InvalidParameter) -> Self {
        Self {
            category: Category::Input,
            message: format!("invalid value for {}: {p}", flag_of(&p.name)),
            parameter: Some(p.name.to_string()),
        }
    }

    /// The error of a registry run.
    pub fn run(e: RunError) -> Self {
        use tensegrity_core::request::Categorized;
        match e {
            RunError::InvalidParameter(p) => Self::invalid(&p),
            other => Self::new(other.category(), other.to_string()),
        }
    }

    /// The error of `context` (the command line's context of a failed library call, e.g.
    /// `michell truss analysis failed`) around this one.
    pub fn context(mut self, context: &str) -> Self {
        if self.parameter.is_none() && !context.is_empty() {
            self.message = format!("{context}: {}", self.message);
        }
        self
    }

    /// An estimate over its limit, with the flag that raises it (the CLI's `guard::Refused`).
    pub fn over_budget(over: &OverBudget) -> Self {
        let (limit, suggested) = match over.resource {
            Resource::Memory => (
                "max_memory",
                tensegrity_engine::limits::suggest_size(over.estimated),
            ),
            Resource::Output => (
                "max_output",
                tensegrity_engine::limits::suggest_size(over.estimated),
            ),
            Resource::Work => ("max_work", format!("{:.0}", over.estimated.ceil())),
        };
        let flag = flag_of(limit);
        let named = parameter_flags(&over.estimate.parameters);
        let named = if named.is_empty() {
            named
        } else {
            format!(" ({named})")
        };
        Self::new(
            Category::Resource,
            format!("{over}; raise the limit with {flag} (e.g. {flag} {suggested}) or make the request smaller{named}"),
        )
    }

    /// The Python exception: `tensegrity.errors.<class>(message)`, its `parameter` set.
    pub fn into_pyerr(self, py: Python<'_>) -> PyErr {
        self.make(py).unwrap_or_else(|e| e)
    }

    fn make(&self, py: Python<'_>) -> PyResult<PyErr> {
        let class = match self.category {
            Category::Input => "InputError",
            Category::Resource => "ResourceError",
            Category::Interrupted => "Interrupted",
            _ => "ComputationError",
        };
        let value = py
            .import("tensegrity.errors")?
            .getattr(class)?
            .call1((self.message.as_str(),))?;
        value.setattr("parameter", self.parameter.as_deref())?;
        Ok(PyErr::from_value(value))
    }
}

pub use tensegrity_engine::spelling::flag_of;
use tensegrity_engine::spelling::parameter_flags;

/// `text` with every backticked parameter that is a flag of the command line written as that
/// flag (the CLI's `spell::flags`): `` `dt` `` → `--dt`, `` `integrator = rattle` `` →
/// `--integrator rattle`; other backticked text stays.
pub fn flags(text: &str) -> String {
    tensegrity_engine::spelling::spell_flags(text, |name| known_flags().contains(name))
}

/// The options of the command line that are no request's parameter but may be named in a
/// message (its outputs, modes and limits).
const FRONT_END_OPTIONS: &[&str] = &[
    "json",
    "out",
    "svg",
    "vtk",
    "frames",
    "grid",
    "grid_points",
    "eps_max",
    "dynamic",
    "rolling",
    "export_scene",
    "sign_map",
    "map_members",
    "map_grid",
    "gamma_sweep",
    "loop_study",
    "mass_sweep",
    "threads",
    "shard",
    "resume",
    "units",
    "quiet",
    "max_memory",
    "max_work",
    "max_output",
];

/// Every name that is a flag of the command line: the parameters of every registered
/// command (a positional scene excepted) and the front-end options.
fn known_flags() -> &'static HashSet<String> {
    static FLAGS: OnceLock<HashSet<String>> = OnceLock::new();
    FLAGS.get_or_init(|| {
        let mut set: HashSet<String> = tensegrity_engine::commands()
            .iter()
            .flat_map(|c| c.params())
            .filter(|p| p.name != "scene")
            .map(|p| p.name.to_string())
            .collect();
        set.extend(FRONT_END_OPTIONS.iter().map(|s| s.to_string()));
        set
    })
}
