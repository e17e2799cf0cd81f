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
    /// A topology file parsed, but the connectivity it describes is invalid.
    #[error("{file}{}: {source}", line_suffix(*.line))]
    InvalidTopology {
        /// The file name.
        file: String,
        /// 1-based line of the offending item, when the error names one.
        line: Option<usize>,
        /// The form-finding crate's error (names the item; boxed: it is large).
        #[source]
        source: Box<formfind::FormFindError>,
    },
    /// A matrix of a MOTES/TsgFEM model (N, C_b, C_s, a per-member list) that does not fit
    /// ([`crate::matrices`]).
    #[error("{matrix}: {reason}")]
    InvalidMatrix {
        /// The matrix, e.g. `C_s` or `bar masses`.
        matrix: String,
        /// What is wrong, naming the row.
        reason: String,
    },
    /// A JSON scene whose values do not fit the scene description (an unknown key, a wrong
    /// type, a `null`): the key path and the reason.
    #[error("{file}: {message}")]
    InvalidJsonScene {
        /// The file name.
        file: String,
        /// What does not fit, and where.
        message: String,
    },
    /// Another code's model file that does not fit ([`crate::ntrt`]): the item it names.
    #[error("{file}: {item}: {reason}")]
    InvalidModel {
        /// The file name.
        file: String,
        /// The item, e.g. `node top1` or `builder rod`.
        item: String,
        /// What is wrong.
        reason: String,
    },
    /// A `[[supports]]` entry gives both `directions` and `fixed`.
    #[error(
        "{file}{}: support {support}: give either `directions` or `fixed`, not both",
        line_suffix(*.line)
    )]
    ConflictingSupport {
        /// The file name.
        file: String,
        /// 1-based line of the entry (`None`: structure data, which has no lines).
        line: Option<usize>,
        /// Index of the support.
        support: usize,
    },
    /// A support giving `along` (directions of any orientation, which replace its x, y, z
    /// ones) beside `directions` or `fixed`.
    #[error(
        "{file}{}: support {support}: give either along (any orientation) or directions/fixed (x, y, z), not both",
        line_suffix(*.line)
    )]
    AmbiguousSupport {
        /// The file name.
        file: String,
        /// 1-based line of the entry (`None`: structure data, which has no lines).
        line: Option<usize>,
        /// Index of the support.
        support: usize,
    },
    /// A file over the size limit of its kind (refused before it is read in full).
    #[error("{}: {} bytes, over the limit of {limit} bytes for {what}", path.display(), size_text(*.size, *.limit))]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size, when the file system tells it (a regular file); `None` for a stream
        /// (a device, a pipe) that gave more than the limit.
        size: Option<u64>,
        /// The limit (bytes).
        limit: u64,
        /// What the file was read as, e.g. `a scene file`.
        what: &'static str,
    },
    /// A `[[bars]]` or `[[strings]]` entry whose `nodes` does not hold exactly two indices.
    #[error("{file}{}: {member}: `nodes` must hold exactly two node indices, got {count} ({nodes:?})", line_suffix(*.line))]
    NodeCount {
        /// The file name.
        file: String,
        /// 1-based line of the entry (`None`: structure data, which has no lines).
        line: Option<usize>,
        /// The member, e.g. `bar 2`.
        member: String,
        /// How many indices were given.
        count: usize,
        /// The indices given.
        nodes: Vec<usize>,
    },
    /// A node index of structure data ([`crate::scene::SceneArrays`]) that is negative.
    #[error("{file}: {item}: node index {index} is out of range (the structure has {n_nodes} nodes, 0-based)")]
    NegativeIndex {
        /// The name labelling the data.
        file: String,
        /// The item holding the index, e.g. `bar 3` or `support 0`.
        item: String,
        /// The index given.
        index: i64,
        /// Number of nodes of the structure.
        n_nodes: usize,
    },
    /// A per-member column of structure data ([`crate::scene::SceneArrays`]) that does not
    /// hold one entry per member.
    #[error("{file}: {column}: expected one entry per {member} ({expected}), got {got}")]
    ColumnLength {
        /// The name labelling the data.
        file: String,
        /// The column, e.g. `bar_mass`.
        column: &'static str,
        /// `bar`, `string` or `support`.
        member: &'static str,
        /// The number of members.
        expected: usize,
        /// The number of entries given.
        got: usize,
    },
    /// A dynamics table of a scene file is invalid; the line of the item it names.
    #[error("{file}{}: {source}", line_suffix(*.line))]
    InScene {
        /// The file name.
        file: String,
        /// 1-based line of the offending item, where known.
        line: Option<usize>,
        /// What is wrong.
        #[source]
        source: Box<IoError>,
    },
    /// Two `[[actuation]]` tables drive the rest length of one string.
    #[error("{table}: string {string} already has a rest-length table ({first}); give one table per string")]
    DuplicateActuation {
        /// The second table, e.g. `actuation 1`.
        table: String,
        /// The string both drive.
        string: usize,
        /// The first table, e.g. `actuation 0`.
        first: String,
    },
    /// A node that can touch the ground starts below its plane by more than the tolerance.
    #[error("ground: node {node} starts {depth} m below the ground plane (more than the tolerance of {tolerance} m); move the structure up or the plane down")]
    BelowGround {
        /// The node.
        node: usize,
        /// How far below the plane it starts (m, > 0).
        depth: f64,
        /// The tolerance (m).
        tolerance: f64,
    },
    /// Kinetic friction above static friction.
    #[error("ground: mu_kinetic ({mu_kinetic}) exceeds mu_static ({mu_static}); kinetic friction must not exceed static friction")]
    FrictionOrder {
        /// μ_s.
        mu_static: f64,
        /// μ_k.
        mu_kinetic: f64,
    },
    /// A key the table's chosen model does not read (it would be ignored silently).
    #[error("{table}: `{key}` is not read by the {model} model; remove it or choose the model that uses it")]
    IgnoredKey {
        /// The table.
        table: String,
        /// The key.
        key: &'static str,
        /// The model chosen.
        model: &'static str,
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
    /// A file type that is known but not written, e.g. an `.mp4` animation: why, and what to
    /// write instead.
    #[error("{}: {reason}", path.display())]
    UnwrittenFormat {
        /// The file.
        path: PathBuf,
        /// Why it is not written and what is.
        reason: &'static str,
    },
    /// A figure has nothing to draw or a bad size.
    #[error("figure: {reason}")]
    InvalidFigure {
        /// What is wrong.
        reason: &'static str,
    },
    /// A figure size or resolution that cannot be used, e.g. `12x` or a dpi of 0.
    #[error("figure size `{text}`: {reason}")]
    InvalidFigureSize {
        /// The text given.
        text: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// The renderer failed (its error types are generic, so the message is kept).
    #[error("drawing the figure: {message}")]
    Drawing {
        /// The backend's message.
        message: String,
    },
    /// An error of the core model.
    #[error(transparent)]
    Core(#[from] CoreError),
}

fn size_text(size: Option<u64>, limit: u64) -> String {
    size.map_or_else(|| format!("more than {limit}"), |s| s.to_string())
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
            IoError::InScene { source, .. } => {
                tensegrity_core::request::Categorized::category(source.as_ref())
            }
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
