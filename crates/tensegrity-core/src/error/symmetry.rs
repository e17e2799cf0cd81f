//! [`SymmetryError`]: a cyclic-symmetry descriptor that does not describe its structure (the
//! descriptor itself is `tensegrity_statics::symmetry::CyclicSymmetry`).

use crate::member_id::MemberId;
use thiserror::Error;

/// Why a cyclic-symmetry descriptor does not describe a structure.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SymmetryError {
    /// The group order is below 3.
    #[error("cyclic symmetry of order {n}: the symmetry-adapted statics needs n ≥ 3")]
    TooFewSides {
        /// The order given.
        n: usize,
    },
    /// The axis or the centre is not a finite non-zero vector.
    #[error("cyclic symmetry: the {what} {value:?} is not a finite (non-zero) vector")]
    BadAxis {
        /// `"axis"` or `"centre"`.
        what: &'static str,
        /// The value given.
        value: [f64; 3],
    },
    /// A permutation has the wrong length.
    #[error("cyclic symmetry: the {which} permutation has {found} entries, the structure has {expected} {which}s")]
    PermutationLength {
        /// `"node"` or `"member"`.
        which: &'static str,
        /// Entries expected.
        expected: usize,
        /// Entries given.
        found: usize,
    },
    /// A permutation maps out of range or maps two items to one.
    #[error("cyclic symmetry: the {which} permutation is not a permutation: {which} {item} maps to {image}, {reason}")]
    NotAPermutation {
        /// `"node"` or `"member"`.
        which: &'static str,
        /// The offending item.
        item: usize,
        /// Its image.
        image: usize,
        /// What is wrong with the image.
        reason: &'static str,
    },
    /// The rotation does not carry a node onto its image.
    #[error("cyclic symmetry: the rotation carries node {node} to {rotated:?}, but its image node {image} is at {image_position:?} (distance {distance:.3e})")]
    NodeNotMapped {
        /// The node.
        node: usize,
        /// Its image under σ.
        image: usize,
        /// R (x − c) + c.
        rotated: [f64; 3],
        /// Where the image node is.
        image_position: [f64; 3],
        /// The distance between the two.
        distance: f64,
    },
    /// A node orbit has neither n nodes nor one node on the axis.
    #[error("cyclic symmetry: the orbit of node {node} under σ has {length} nodes; it must have n = {n} (off the axis) or 1 (a node on the axis)")]
    BadNodeOrbit {
        /// A node of the orbit.
        node: usize,
        /// The orbit length.
        length: usize,
        /// The group order.
        n: usize,
    },
    /// A member's image does not join the images of its nodes, or changes kind.
    #[error("cyclic symmetry: {member} joins nodes {nodes:?}, so its image must join {expected:?} and be a {kind}; the member permutation gives {image} joining {found:?}")]
    MemberNotMapped {
        /// The member.
        member: MemberId,
        /// Its nodes.
        nodes: [usize; 2],
        /// The nodes its image must join.
        expected: [usize; 2],
        /// Its kind, `"bar"` or `"string"`.
        kind: &'static str,
        /// The image given.
        image: MemberId,
        /// The nodes the image joins.
        found: [usize; 2],
    },
    /// A member orbit length does not divide n.
    #[error("cyclic symmetry: the orbit of {member} under π has {length} members, which does not divide n = {n}")]
    BadMemberOrbit {
        /// A member of the orbit.
        member: MemberId,
        /// The orbit length.
        length: usize,
        /// The group order.
        n: usize,
    },
    /// A support is not carried onto the support of the image node.
    #[error("cyclic symmetry: the supports are not symmetric: node {node} (fixed {fixed:?}) maps to node {image} (fixed {image_fixed:?}) but the rotation does not carry one's free directions onto the other's")]
    SupportNotSymmetric {
        /// The node.
        node: usize,
        /// Its fixed directions.
        fixed: [bool; 3],
        /// Its image.
        image: usize,
        /// The image's fixed directions.
        image_fixed: [bool; 3],
    },
    /// No node lies at the rotated position of a node (building σ from positions).
    #[error("cyclic symmetry: no node lies at the rotated position {rotated:?} of node {node}")]
    NoImageNode {
        /// The node.
        node: usize,
        /// R (x − c) + c.
        rotated: [f64; 3],
    },
    /// No member joins the images of a member's nodes (building π from σ).
    #[error("cyclic symmetry: {member} joins nodes {nodes:?} but no {kind} joins their images {expected:?}")]
    NoImageMember {
        /// The member.
        member: MemberId,
        /// Its nodes.
        nodes: [usize; 2],
        /// The images.
        expected: [usize; 2],
        /// `"bar"` or `"string"`.
        kind: &'static str,
    },
}
