//! The single error type of the core crate, the dynamics included.
//!
//! Every variant carries structured fields naming the offending item, so a caller can both print
//! a clear message and react programmatically. The enum is `#[non_exhaustive]`: other crates
//! match it with a wildcard arm, so that new conditions can be added without breaking them.

use crate::member_id::MemberId;
use thiserror::Error;

/// Result alias used throughout the core.
pub type Result<T, E = CoreError> = std::result::Result<T, E>;

/// Everything that can go wrong when building, analysing or simulating a structure.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CoreError {
    /// A member, support or load refers to a node that does not exist.
    #[error(
        "{item}: node index {node} is out of range (the structure has {n_nodes} nodes, 0-based)"
    )]
    NodeIndexOutOfRange {
        /// The item holding the bad index, e.g. `bar 2` or `support 0`.
        item: String,
        /// The offending index.
        node: usize,
        /// Number of nodes in the structure.
        n_nodes: usize,
    },
    /// A member joins a node to itself.
    #[error("{member}: joins node {node} to itself")]
    SelfLoop {
        /// The offending member.
        member: MemberId,
        /// The repeated node.
        node: usize,
    },
    /// Two members join the same pair of nodes.
    #[error("{member}: duplicates {other} (both join nodes {a} and {b})")]
    DuplicateMember {
        /// The later member.
        member: MemberId,
        /// The earlier member joining the same nodes.
        other: MemberId,
        /// First node of the pair.
        a: usize,
        /// Second node of the pair.
        b: usize,
    },
    /// A member whose end nodes coincide.
    #[error("{member}: has zero length (nodes {a} and {b} coincide, length {length:e} m)")]
    ZeroLengthMember {
        /// The offending member.
        member: MemberId,
        /// Start node.
        a: usize,
        /// End node.
        b: usize,
        /// The computed length.
        length: f64,
    },
    /// A node coordinate (or velocity, load, gravity component) is NaN or infinite.
    #[error("{item}: component {axis} is not finite ({value})")]
    NonFinite {
        /// The offending item, e.g. `node 3`.
        item: String,
        /// Axis name (`x`, `y` or `z`).
        axis: char,
        /// The value found.
        value: f64,
    },
    /// A physical constant that must be strictly positive is not.
    #[error("{item}: {name} must be positive and finite, got {value}")]
    NonPositiveConstant {
        /// The item holding the constant, e.g. `string 4` or `material \"alu\"`.
        item: String,
        /// The constant's name, e.g. `stiffness`.
        name: &'static str,
        /// The value found.
        value: f64,
    },
    /// A physical constant that must be non-negative is negative.
    #[error("{item}: {name} must be non-negative and finite, got {value}")]
    NegativeConstant {
        /// The item holding the constant.
        item: String,
        /// The constant's name, e.g. `damping`.
        name: &'static str,
        /// The value found.
        value: f64,
    },
    /// A member names a material that is neither user-defined nor built in.
    #[error("{item}: unknown material \"{name}\" (known: {known})")]
    UnknownMaterial {
        /// The member naming the material.
        item: String,
        /// The unknown name.
        name: String,
        /// Comma-separated list of the known materials.
        known: String,
    },
    /// A node that no member touches.
    #[error("node {node} is isolated: no bar or string is attached to it")]
    IsolatedNode {
        /// The isolated node.
        node: usize,
    },
    /// The same node is supported twice.
    #[error("support {support}: node {node} is already supported by support {other}")]
    DuplicateSupport {
        /// Index of the later support.
        support: usize,
        /// Index of the earlier support.
        other: usize,
        /// The node.
        node: usize,
    },
    /// A support that fixes no direction.
    #[error("support {support}: fixes no direction")]
    EmptySupport {
        /// Index of the support.
        support: usize,
    },
    /// A list whose length must match the number of nodes or members does not.
    #[error("{what}: expected {expected} entries, got {found}")]
    LengthMismatch {
        /// What the list is.
        what: String,
        /// The required length.
        expected: usize,
        /// The length found.
        found: usize,
    },
    /// A structure without any member.
    #[error("the structure has no members")]
    NoMembers,
    /// An analysis needs a property that a member does not have.
    #[error("{member}: {analysis} needs its {property}, which is not given")]
    MissingProperty {
        /// The member lacking the property.
        member: MemberId,
        /// The analysis asking for it.
        analysis: &'static str,
        /// The missing property, e.g. `material` or `stiffness`.
        property: &'static str,
    },
    /// Sizing asked of a string that would have to carry compression.
    #[error(
        "{member}: a string cannot carry compression (force {force:.6e} N); sizing is undefined"
    )]
    StringInCompression {
        /// The string.
        member: MemberId,
        /// Its (negative) axial force.
        force: f64,
    },
    /// A node needs mass for modal analysis but has none.
    #[error("node {node}: has no lumped mass, modal analysis needs mass at every free node")]
    NoLumpedMass {
        /// The node.
        node: usize,
    },
    /// The structure cannot carry its loads: the least-squares force densities leave an
    /// equilibrium residual (the loads drive a mechanism).
    #[error("the loads cannot be carried: equilibrium residual {residual:.6e} N ({relative_residual:.3e} of the load) at nodes {nodes:?}; the structure is a mechanism for these loads (add members or supports, or ask for the least-squares answer)")]
    LoadNotCarried {
        /// ‖A q − w‖₂ (N).
        residual: f64,
        /// The residual relative to ‖w‖₂.
        relative_residual: f64,
        /// The unbalanced nodes.
        nodes: Vec<usize>,
    },
    /// The run was interrupted (a sample sink asked to stop, e.g. on Ctrl-C).
    #[error("interrupted at t = {t:?} s")]
    Interrupted {
        /// Time of the last sample handed out (s).
        t: f64,
    },
    /// A cyclic-symmetry descriptor that does not describe the structure (boxed: the
    /// variant names nodes, members and positions).
    #[error(transparent)]
    Symmetry(Box<crate::statics::symmetry::SymmetryError>),
    /// A statics back-end was asked for something it does not compute (e.g. the load solve of
    /// the cyclic back-end, whose loads need not be symmetric).
    #[error("{analysis} is not available from the {backend} statics")]
    Unsupported {
        /// What was asked, e.g. `the load solve`.
        analysis: &'static str,
        /// The back-end, e.g. `cyclic (symmetry-adapted blocks)`.
        backend: &'static str,
    },
    /// A problem too large for the memory budget, refused before allocating.
    #[error("{what} ({rows} × {cols}) needs about {:.1} GiB, above the limit of {:.1} GiB: use a smaller structure (e.g. fewer --sides or a lower --complexity)", bytes / 1073741824.0, limit / 1073741824.0)]
    TooLarge {
        /// The computation refused.
        what: &'static str,
        /// Rows of the matrix.
        rows: usize,
        /// Columns of the matrix.
        cols: usize,
        /// Estimated peak memory (bytes).
        bytes: f64,
        /// The budget (bytes).
        limit: f64,
    },
    /// A numerical kernel failed to converge.
    #[error("{operation} did not converge")]
    NoConvergence {
        /// The operation, e.g. `SVD of the equilibrium matrix`.
        operation: &'static str,
    },
    /// The optimisation solver failed.
    #[error("{problem}: the LP solver stopped with status {status}")]
    SolverFailed {
        /// The problem solved.
        problem: &'static str,
        /// The solver's status, as text.
        status: String,
    },
    /// An invalid analysis parameter.
    #[error("{0}")]
    InvalidParameter(#[from] crate::request::InvalidParameter),
    /// Dynamics: a node that no bar touches and that is not fixed in all three directions. It
    /// would be a massless free point (all mass is in the bars), which rigid-bar dynamics
    /// cannot integrate.
    #[error("node {node}: no bar ends at it and it is not fixed in all three directions (massless free node)")]
    FreeNodeWithoutBar {
        /// The node.
        node: usize,
    },
    /// Dynamics: the initial velocities violate a constraint (a fixed direction moves, or a
    /// bar changes length).
    #[error("{item}: initial velocity is inconsistent with the constraints ({reason}, residual {residual:e})")]
    InconsistentVelocity {
        /// The offending node or bar, e.g. `node 3` or `bar 1`.
        item: String,
        /// What is violated.
        reason: &'static str,
        /// The size of the violation.
        residual: f64,
    },
    /// Dynamics: the adaptive integrator needed a step smaller than its minimum.
    #[error("step size fell below the minimum {h_min:e} s at t = {t:?} s")]
    StepSizeTooSmall {
        /// Time at which the step was rejected.
        t: f64,
        /// The minimum step size.
        h_min: f64,
    },
    /// Dynamics: the run needed more accepted steps than allowed.
    #[error("more than {max_steps} steps needed: stopped at t = {t:?} s")]
    MaxStepsExceeded {
        /// Time reached when the limit was hit.
        t: f64,
        /// The limit on accepted steps.
        max_steps: u64,
    },
    /// Dynamics: a NaN or infinity appeared in the state or the forces.
    #[error("non-finite state at t = {t:?} s in {member}")]
    NonFiniteState {
        /// Time of the step that produced it.
        t: f64,
        /// The bar owning the offending node.
        member: MemberId,
    },
    /// Dynamics: a node moved implausibly far (the run diverged).
    #[error("blow-up at t = {t:?} s: {member} moved {distance:e} m (limit {limit:e} m)")]
    BlowUp {
        /// Time of detection.
        t: f64,
        /// The bar owning the offending node.
        member: MemberId,
        /// Distance from the initial position.
        distance: f64,
        /// The blow-up limit.
        limit: f64,
    },
    /// Dynamics: the constraint (Ω or RATTLE) system is singular: redundant or conflicting
    /// constraints, e.g. a bar pinned at both ends.
    #[error("the constraint system is singular: pivot {rank} of {expected} is not positive (redundant constraints, e.g. a bar fixed at both ends?)")]
    SingularConstraint {
        /// Number of pivots that succeeded (a lower bound on the numerical rank).
        rank: usize,
        /// The size of the system.
        expected: usize,
    },
    /// Dynamics: the state ran away during the run (a constraint system that factored at the
    /// start became singular, or the RATTLE iteration failed): the step is too large for the
    /// stiffness.
    #[error("the integration diverged at t = {t:?} s ({what}): the step is too large for the stiffness of the strings or the ground; use a smaller --dt, the adaptive rk45, or the implicit sdirk for stiff strings and contact")]
    Diverged {
        /// Time of the last accepted state (s).
        t: f64,
        /// What failed.
        what: &'static str,
    },
    /// Dynamics: the RATTLE position solve did not converge.
    #[error("RATTLE constraint iteration did not converge at t = {t:?} s (residual {residual:e})")]
    ConstraintNotConverged {
        /// Time of the step.
        t: f64,
        /// Remaining constraint residual.
        residual: f64,
    },
    /// Dynamics: rigid-bar dynamics needs at least one bar (all the mass is in the bars).
    #[error("structure: rigid-bar dynamics needs at least one bar (all mass is in the bars)")]
    NoBars,
    /// Dynamics: a ground contact candidate names a node that does not exist.
    #[error("ground node {index}: node {node} does not exist ({n_nodes} nodes)")]
    GroundNodeOutOfRange {
        /// Position in the list of contact candidates.
        index: usize,
        /// The node named.
        node: usize,
        /// Number of nodes of the structure.
        n_nodes: usize,
    },
    /// Dynamics: the ground's normal is zero or not finite.
    #[error("ground: normal must be a finite non-zero vector, got [{x}, {y}, {z}]")]
    InvalidGroundNormal {
        /// x component.
        x: f64,
        /// y component.
        y: f64,
        /// z component.
        z: f64,
    },
    /// A dense or sparse factorisation of [`crate::linalg`] failed.
    #[error("{operation} failed: {reason}")]
    Factorization {
        /// The factorisation, e.g. `SVD` or `sparse LU (numeric)`.
        operation: &'static str,
        /// Why it failed.
        reason: FactorizationFailure,
    },
}

/// Why a factorisation of [`crate::linalg`] failed (the reason of [`CoreError::Factorization`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum FactorizationFailure {
    /// An iterative kernel (SVD, eigensolver) reached its iteration limit.
    #[error("the iteration did not converge")]
    NoConvergence,
    /// A Cholesky pivot is zero, negative or NaN: the matrix is not (numerically) positive
    /// definite.
    #[error("pivot {pivot} of {dim} is not positive (matrix not positive definite)")]
    NonPositivePivot {
        /// Number of pivots that succeeded (0-based index of the failing one).
        pivot: usize,
        /// The order of the matrix.
        dim: usize,
    },
    /// No pivot could be found in a column: the matrix is structurally singular.
    #[error("no pivot in step {step} of {dim} (matrix structurally singular)")]
    StructurallySingular {
        /// The elimination step that found no pivot.
        step: usize,
        /// The order of the matrix.
        dim: usize,
    },
    /// A sparse entry lies outside the matrix.
    #[error("entry ({row}, {col}) lies outside the {nrows}×{ncols} matrix")]
    EntryOutOfBounds {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        col: usize,
        /// Rows of the matrix.
        nrows: usize,
        /// Columns of the matrix.
        ncols: usize,
    },
    /// A compressed-column pattern is malformed: column pointers not non-decreasing, or the
    /// row indices of a column out of range or not strictly increasing.
    #[error("column {column} of the sparse pattern is malformed")]
    InvalidPattern {
        /// The first malformed column.
        column: usize,
    },
    /// A right-hand side or value array has the wrong length.
    #[error("expected {expected} values, got {found}")]
    DimensionMismatch {
        /// The required length.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// The workspace could not be allocated.
    #[error("out of memory")]
    OutOfMemory,
    /// A sparse index overflowed the index type.
    #[error("sparse index overflow")]
    IndexOverflow,
}

/// A number as a person reads it: plain decimals for ordinary magnitudes, scientific
/// notation for tiny or huge ones (`1e-300`, not three hundred zeros).
///
/// ```
/// use tensegrity_core::error::short_number;
/// assert_eq!(short_number(-5.0), "-5");
/// assert_eq!(short_number(1.5), "1.5");
/// assert_eq!(short_number(1e-300), "1e-300");
/// assert_eq!(short_number(f64::NAN), "NaN");
/// ```
pub fn short_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

impl CoreError {
    /// Shorthand for [`CoreError::InvalidParameter`].
    ///
    /// ```
    /// use tensegrity_core::CoreError;
    /// let e = CoreError::invalid_parameter("dt", -1.0, "must be positive and finite");
    /// assert_eq!(e.to_string(), "dt = -1: must be positive and finite");
    /// ```
    pub fn invalid_parameter(name: &'static str, value: f64, reason: impl Into<String>) -> Self {
        Self::InvalidParameter(crate::request::InvalidParameter::new(name, value, reason))
    }
}

impl From<crate::statics::symmetry::SymmetryError> for CoreError {
    fn from(e: crate::statics::symmetry::SymmetryError) -> Self {
        CoreError::Symmetry(Box::new(e))
    }
}
