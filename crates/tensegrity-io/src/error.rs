//! The error type of the io crate.
//!
//! Every variant names the file, the item or the table concerned, and its line where the scene
//! file gives one, so that a message points the user at the place to fix.

use std::path::PathBuf;
use tensegrity_core::CoreError;
use thiserror::Error;

/// Result alias of the io crate.
pub type Result<T, E = IoError> = std::result::Result<T, E>;

/// Everything that can go wrong when reading a scene or writing a table, a VTK series or a
/// figure.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum IoError {
    /// A file could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A file or directory could not be created or written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file or directory.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// Another run holds the lock of an output path.
    #[error("{}: another run ({holder}) is writing this output; wait for it to end or choose another path", path.display())]
    Busy {
        /// The output path.
        path: PathBuf,
        /// Who holds it, as its lock file says (`pid 1234`).
        holder: String,
    },
    /// A write to an output that was already finished (by an interrupt).
    #[error("{}: the output was already closed (interrupted)", path.display())]
    Closed {
        /// The output path.
        path: PathBuf,
    },
    /// Writing a table or picture to a stream (not yet tied to a file) failed.
    #[error("writing {what}: {source}")]
    Stream {
        /// What was being written, e.g. `trajectory CSV`.
        what: &'static str,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The scene text is not valid TOML or does not match the schema (unknown key, wrong
    /// type, unknown variant).
    #[error("{file}: line {line}, column {column}: {message}")]
    Parse {
        /// The file name given to the parser.
        file: String,
        /// 1-based line of the offending text.
        line: usize,
        /// 1-based column (in characters) of the offending text.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// The scene parsed, but the structure it describes is invalid.
    #[error("{file}{}: {source}", line_suffix(*.line))]
    InvalidStructure {
        /// The file name.
        file: String,
        /// 1-based line of the offending item, when the error names one.
        line: Option<usize>,
        /// The core's validation error (names the item).
        #[source]
        source: CoreError,
    },
    /// A `[[supports]]` entry gives both `directions` and `fixed`.
    #[error(
        "{file} (line {line}): support {support}: give either `directions` or `fixed`, not both"
    )]
    ConflictingSupport {
        /// The file name.
        file: String,
        /// 1-based line of the entry.
        line: usize,
        /// Index of the support.
        support: usize,
    },
    /// A table lacks a column asked for.
    #[error("{}: no column `{column}`", path.display())]
    MissingColumn {
        /// The table.
        path: PathBuf,
        /// The column asked for.
        column: String,
    },
    /// A dynamics table (`[ground]`, `[[actuation]]`) holds an invalid value.
    #[error("{table}: {reason}")]
    InvalidTable {
        /// The table, e.g. `ground` or `actuation 2`.
        table: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// A number of a dynamics table is negative or not finite.
    #[error("{table}: {name} must be non-negative and finite, got {value}")]
    NegativeValue {
        /// The table, e.g. `ground`.
        table: String,
        /// The key.
        name: &'static str,
        /// The value found.
        value: f64,
    },
    /// A dynamics table refers to a string or node that does not exist.
    #[error("{table}: {kind} {index} does not exist (the structure has {count})")]
    UnknownIndex {
        /// The table, e.g. `actuation 0`.
        table: String,
        /// `string` or `node`.
        kind: &'static str,
        /// The index given.
        index: usize,
        /// How many there are.
        count: usize,
    },
    /// A figure or VTK file name whose extension the writer does not know.
    #[error("{}: unknown file type (expected one of: {expected})", path.display())]
    UnsupportedFormat {
        /// The file.
        path: PathBuf,
        /// The extensions understood, e.g. `svg, png`.
        expected: &'static str,
    },
    /// A figure has nothing to draw or a bad size.
    #[error("figure: {reason}")]
    InvalidFigure {
        /// What is wrong.
        reason: &'static str,
    },
    /// The plotting backend failed (its error types are generic, so the message is kept).
    #[error("drawing the figure: {message}")]
    Drawing {
        /// The backend's message.
        message: String,
    },
    /// An error of the core model.
    #[error(transparent)]
    Core(#[from] CoreError),
}

fn line_suffix(line: Option<usize>) -> String {
    line.map(|l| format!(" (line {l})")).unwrap_or_default()
}

impl tensegrity_core::request::Categorized for IoError {
    /// Every io error is about the input (a file, a path, a format) except a write cut short
    /// by an interrupt; an error of the core keeps its own category.
    fn category(&self) -> tensegrity_core::request::Category {
        use tensegrity_core::request::Category;
        match self {
            IoError::Closed { .. } => Category::Interrupted,
            IoError::Core(e) => tensegrity_core::request::Categorized::category(e),
            _ => Category::Input,
        }
    }
}

impl IoError {
    /// Ties a [`IoError::Stream`] error to the file being written.
    pub(crate) fn at(self, path: &std::path::Path) -> Self {
        match self {
            IoError::Stream { source, .. } => IoError::Write {
                path: path.to_path_buf(),
                source,
            },
            other => other,
        }
    }

    /// A stream error while writing `what`.
    pub fn stream(what: &'static str) -> impl Fn(std::io::Error) -> IoError {
        move |source| IoError::Stream { what, source }
    }
}
