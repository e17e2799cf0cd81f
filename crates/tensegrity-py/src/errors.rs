//! Errors as Python exceptions, in the caller's words.
//!
//! Every library error is [`Categorized`]; its category picks the exception class of
//! `tensegrity.errors` (Python): input → `InputError` (a `ValueError`), resource →
//! `ResourceError`, numerical → `ComputationError` (both `RuntimeError`s), interrupted →
//! `Interrupted` (a `KeyboardInterrupt`).
//!
//! The message is the library's, which names its parameters as they are named in Rust and
//! in Python (`` `dt` ``, never the command line's `--dt`): a bad keyword value reads
//! `sides = 1: …` (the [`InvalidParameter`] itself), and a refused estimate names the keyword
//! that raises the limit (`max_work=120`). The exception's `parameter` attribute gives the
//! keyword of a bad value.

use pyo3::prelude::*;
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
    /// A failure of `category` with the library's `message`.
    pub fn new(category: Category, message: impl AsRef<str>) -> Self {
        Self::raw(category, message.as_ref())
    }

    /// A failure whose message stays as the library wrote it.
    pub fn raw(category: Category, message: impl Into<String>) -> Self {
        Self {
            category,
            message: message.into(),
            parameter: None,
        }
    }

    /// A bad keyword value: the parameter's own message (`sides = 1: …`).
    pub fn invalid(p: &InvalidParameter) -> Self {
        Self {
            category: Category::Input,
            message: p.to_string(),
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

    /// An estimate over its limit, with the keyword that raises it.
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
        let named = over.estimate.parameters.to_string();
        let named = if named.is_empty() {
            named
        } else {
            format!(" ({named})")
        };
        Self::new(
            Category::Resource,
            format!("{over}; raise the limit with `{limit}` (e.g. {limit}={suggested}) or make the request smaller{named}"),
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
