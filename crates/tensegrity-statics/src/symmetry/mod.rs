//! Cyclic symmetry Cₙ: the statics of a structure invariant under a rotation by 2π/n
//! (a wheel about its axle) in the symmetry-adapted (Fourier) basis.
//!
//! With the generator g (rotation R about the axis, node permutation σ, member permutation
//! π), the equilibrium matrix commutes with the group, A g = g A, so in a basis of
//! eigenvectors of g it splits into n blocks A_k, one per irreducible representation
//! k = 0..n−1 (character λ = e^{2πik/n}):
//!
//! - rank A = Σ_k rank A_k, self-stress dimension = Σ_k (members_k − rank A_k), first-order
//!   mechanisms = Σ_k (dofs_k − rank A_k), each classified by k ([`RepCounts`]);
//! - the cost is O(n·b³) for blocks of size b (the number of node and member orbits) instead
//!   of the dense O((nb)³), and the memory O(n·b²) instead of O(n²b²);
//! - the prestressability margin comes from the LP restricted to the fully symmetric
//!   self-stresses (k = 0), one variable per state of a block of b columns ([`prestress`]).
//!
//! Files: [`descriptor`] (the validated [`CyclicSymmetry`]), [`blocks`] (the block assembly,
//! nodes on the axis included), [`cyclic`] ([`CyclicStatics`]: per-block SVD, totals, rigid
//! motions, certification of the rank decision), [`prestress`] (the symmetric margin LP),
//! [`response`] (the elastic response to a load on one node, block by block, and the
//! rotation of a response to the other nodes of the orbit). [`CyclicStatics`] is one of the
//! back-ends of [`crate::StaticsBackend`].

pub mod blocks;
pub mod cyclic;
pub mod descriptor;
pub mod prestress;
pub mod response;

pub use blocks::{BlockContext, BlockLayout, BlockRow};
pub use cyclic::{CyclicStatics, RepCounts};
pub use descriptor::{
    CyclicSymmetry, MemberOrbit, NodeOrbit, Place, SymmetryError, SYMMETRY_TOLERANCE,
};
pub use response::{elastic_response, MemberRotations};
