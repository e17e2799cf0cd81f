//! [`ModelError`]: a structure (nodes, members, supports, materials) that is not a valid model,
//! or that lacks what an analysis needs. Always bad input ([`Category::Input`]).

use crate::member_id::MemberId;
use crate::request::{Categorized, Category};
use thiserror::Error;

/// An invalid structure, found when it is built or when an analysis reads it.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ModelError {
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
    /// A member whose length overflows double precision (coordinates beyond about 10¹⁵⁴ m,
    /// whose squares overflow).
    #[error("{member}: its length between nodes {a} and {b} overflows double precision (coordinates beyond about 1e154 m, whose squares overflow): scale the structure down")]
    MemberLengthOverflow {
        /// The offending member.
        member: MemberId,
        /// Start node.
        a: usize,
        /// End node.
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
    #[error("node {node} is isolated: no bar, string or cluster is attached to it")]
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
    #[error("support {support}: holds no direction (no axis fixed, no `along` direction)")]
    EmptySupport {
        /// Index of the support.
        support: usize,
    },
    /// A support whose held directions are not usable: a direction not finite, not a unit
    /// vector, or dependent on the others.
    #[error("support {support}: {reason}")]
    InvalidSupport {
        /// Index of the support.
        support: usize,
        /// What is wrong, naming the direction.
        reason: String,
    },
    /// A clustered string that cannot be built: too few nodes, a segment of zero length, a
    /// friction coefficient per pulley missing or extra, or a segment that duplicates a
    /// member.
    #[error("cluster {cluster}: {reason}")]
    InvalidCluster {
        /// Index of the cluster.
        cluster: usize,
        /// What is wrong, naming the segment or node.
        reason: String,
    },
    /// A structure with clustered strings given to an analysis that does not model them
    /// (rather than leave them out).
    #[error("cluster {cluster}: clustered strings are not modelled by {analysis}: give its segments as [[strings]] there, or use an analysis that models clusters")]
    ClustersNotModelled {
        /// The first cluster.
        cluster: usize,
        /// The analysis, e.g. `the rigid-bar dynamics`.
        analysis: &'static str,
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
    /// A node needs mass for modal analysis but has none.
    #[error("node {node}: has no lumped mass, modal analysis needs mass at every free node")]
    NoLumpedMass {
        /// The node.
        node: usize,
    },
}

impl ModelError {
    /// The numbered item the error names, as the model writes it (`bar 2`, `node 3`,
    /// `support 0`), when it names one: a front end points at its place in the input.
    ///
    /// ```
    /// use tensegrity_core::error::ModelError;
    /// let e = ModelError::IsolatedNode { node: 4 };
    /// assert_eq!(e.item().as_deref(), Some("node 4"));
    /// assert_eq!(ModelError::NoMembers.item(), None);
    /// ```
    pub fn item(&self) -> Option<String> {
        match self {
            Self::NodeIndexOutOfRange { item, .. }
            | Self::NonFinite { item, .. }
            | Self::NonPositiveConstant { item, .. }
            | Self::NegativeConstant { item, .. }
            | Self::UnknownMaterial { item, .. } => Some(item.clone()),
            Self::SelfLoop { member, .. }
            | Self::DuplicateMember { member, .. }
            | Self::ZeroLengthMember { member, .. } => Some(member.to_string()),
            Self::IsolatedNode { node } => Some(format!("node {node}")),
            Self::DuplicateSupport { support, .. }
            | Self::EmptySupport { support }
            | Self::InvalidSupport { support, .. } => Some(format!("support {support}")),
            Self::InvalidCluster { cluster, .. } | Self::ClustersNotModelled { cluster, .. } => {
                Some(format!("cluster {cluster}"))
            }
            _ => None,
        }
    }
}

impl Categorized for ModelError {
    fn category(&self) -> Category {
        Category::Input
    }
}
