//! Error categories: what kind of failure an error is, independent of which crate raised it.
//! A front end decides its reaction from the category alone (the CLI's exit code, the Python
//! exception class), never by matching every variant of every crate's error.

/// The kind of a failure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Category {
    /// Bad input: a parameter out of range, an unknown option, an invalid structure or file,
    /// an unwritable output path. The request must change.
    Input,
    /// A request over the resource limits (memory, work, output), refused before any work.
    Resource,
    /// The computation failed on valid input: not prestressable, a singular configuration,
    /// an integrator that diverged, a solver that did not converge.
    Numerical,
    /// Stopped by the user (SIGINT, SIGTERM, Ctrl-C); what was computed is kept.
    Interrupted,
}

/// An error that knows its [`Category`].
pub trait Categorized {
    /// The category of this error.
    fn category(&self) -> Category;
}
