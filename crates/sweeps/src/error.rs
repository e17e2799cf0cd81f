//! The crate's one error type.
//!
//! Spec errors (unknown study or parameter, a bad axis, a derived rule that does not parse,
//! an unknown output column) stop a sweep before any case runs. Errors of one case (a value
//! the parameter does not take, a failing analysis) never stop it: they become that case's
//! `error` row, with the error's message.

use std::path::PathBuf;

/// Everything that can go wrong in a sweep.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    /// The spec file is not valid TOML or does not have the spec's shape.
    #[error("invalid sweep spec: {message}")]
    Spec {
        /// The parser's message (with line and column).
        message: String,
    },
    /// `study` names no known study.
    #[error("unknown study `{study}` (known: {known})")]
    UnknownStudy {
        /// The name in the spec.
        study: String,
        /// The known studies.
        known: String,
    },
    /// A parameter name the study does not know.
    #[error("unknown parameter `{name}` in [{section}] of a `{study}` sweep (known: {known})")]
    UnknownParameter {
        /// The study.
        study: &'static str,
        /// `fixed`, `axes` or `derived`.
        section: &'static str,
        /// The unknown name.
        name: String,
        /// The study's parameters.
        known: String,
    },
    /// A parameter set in two sections.
    #[error("parameter `{name}` is given in both [{first}] and [{second}]")]
    DuplicateParameter {
        /// The parameter.
        name: String,
        /// The first section.
        first: &'static str,
        /// The second section.
        second: &'static str,
    },
    /// A parameter the study cannot do without.
    #[error("the `{study}` study needs the parameter `{name}` (in [fixed], [axes] or [derived])")]
    MissingParameter {
        /// The study.
        study: &'static str,
        /// The parameter.
        name: &'static str,
    },
    /// An axis that is not a non-empty list or a valid range.
    #[error("axis `{axis}`: {reason}")]
    InvalidAxis {
        /// The axis.
        axis: String,
        /// What is wrong.
        reason: String,
    },
    /// A derived rule that does not parse or refers to what it cannot use.
    #[error("derived `{name}`: {reason}")]
    InvalidDerived {
        /// The derived parameter.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// An `[output] columns` entry that is not a result column of the study.
    #[error("[output] columns: `{column}` is not a result column of the `{study}` study (known: {known})")]
    UnknownColumn {
        /// The study.
        study: &'static str,
        /// The unknown column.
        column: String,
        /// The study's result columns.
        known: String,
    },
    /// More cases than the sweep accepts.
    #[error(
        "the sweep has {cases} cases, more than the limit of {limit}: split it into several specs"
    )]
    TooManyCases {
        /// Product of the axis lengths (saturating).
        cases: u128,
        /// [`crate::MAX_CASES`].
        limit: u64,
    },
    /// The axes of a spec, estimated before their values are made, over a resource limit:
    /// the values of one axis (memory) or the CSV of their product (output)
    /// ([`crate::limits::admit_axes`]); the estimate names the axes.
    #[error("{over}")]
    OverBudget {
        /// The estimate over its limit.
        over: Box<tensegrity_core::budget::OverBudget>,
    },
    /// A `--shard K/N` that is not 1 ≤ K ≤ N.
    #[error("invalid shard `{shard}`: {reason}")]
    InvalidShard {
        /// As given.
        shard: String,
        /// What is wrong.
        reason: String,
    },
    /// A value a parameter does not take (one case).
    #[error("parameter `{name}` = {value}: {reason}")]
    InvalidValue {
        /// The parameter.
        name: String,
        /// The value as written.
        value: String,
        /// What is wrong.
        reason: String,
    },
    /// An existing output file that `--resume` cannot continue.
    #[error("cannot resume {path}: {reason}")]
    Resume {
        /// The output file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// Shard files that do not merge.
    #[error("cannot merge {path}: {reason}")]
    Merge {
        /// The offending input.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// An output that cannot be opened: an unwritable path, or another run writing it.
    #[error(transparent)]
    Output(#[from] tensegrity_io::IoError),
    /// Stopped by an interrupt: the rows so far are in the file, which ends with an
    /// `# incomplete` line and continues with `resume`.
    #[error("interrupted after {done} of {total} cases: the rows so far are in {}, marked incomplete (run the sweep again with resume to continue it)", path.display())]
    Interrupted {
        /// The output file.
        path: PathBuf,
        /// Cases whose rows are in the file.
        done: usize,
        /// Cases of the shard.
        total: usize,
    },
    /// Reading or writing a file failed.
    #[error("{what} {path}: {source}")]
    Io {
        /// `reading`, `writing`, …
        what: &'static str,
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

impl SweepError {
    /// True for errors of the user's input (spec, shard, files that do not resume or merge),
    /// as opposed to failures to read or write.
    pub fn is_input_error(&self) -> bool {
        !matches!(self, SweepError::Io { .. } | SweepError::Interrupted { .. })
    }

    /// True when the sweep was stopped by an interrupt.
    pub fn is_interrupted(&self) -> bool {
        matches!(self, SweepError::Interrupted { .. })
    }

    pub(crate) fn io(
        what: &'static str,
        path: &std::path::Path,
    ) -> impl FnOnce(std::io::Error) -> Self + use<> {
        let path = path.to_path_buf();
        move |source| SweepError::Io { what, path, source }
    }
}

/// The crate's result type.
pub type Result<T, E = SweepError> = std::result::Result<T, E>;

impl tensegrity_core::request::Categorized for SweepError {
    /// A spec, shard or file that does not fit is bad input (an output keeps its own
    /// category), an interrupt is interrupted, a failure to read or write a computation's
    /// failure.
    fn category(&self) -> tensegrity_core::request::Category {
        use tensegrity_core::request::Category;
        match self {
            SweepError::Output(e) => tensegrity_core::request::Categorized::category(e),
            SweepError::Interrupted { .. } => Category::Interrupted,
            SweepError::OverBudget { .. } => Category::Resource,
            SweepError::Io { .. } => Category::Numerical,
            _ => Category::Input,
        }
    }
}
