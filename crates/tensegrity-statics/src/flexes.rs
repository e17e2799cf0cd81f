//! First-order flexes: the motions δn of the free degrees of freedom with Aᵀ δn = 0 (no member
//! changes length to first order), i.e. the null space of Aᵀ from the SVD of A.
//!
//! Rigid-body motions δn_i = a + ω × n_i that the supports allow
//! ([`rigid_body_motions`](crate::stiffness::rigid_body_motions)) are trivial flexes; the
//! component of the flex space orthogonal to them spans the internal mechanisms.

use super::Statics;
use crate::stiffness;
use nalgebra::DMatrix;
use tensegrity_core::error::Result;
use tensegrity_linalg as linalg;

/// First-order flexes split into trivial (rigid-body) and internal ones.
#[derive(Debug, Clone)]
pub struct Flexes {
    /// Orthonormal basis of the internal mechanisms (free dofs × count).
    pub internal: DMatrix<f64>,
    /// Number of rigid-body motions the supports allow.
    pub rigid_body: usize,
}

impl Statics<'_> {
    /// The first-order flexes, split into rigid-body motions and internal mechanisms.
    pub fn flexes(&self) -> Result<Flexes> {
        let motions = self.motion_basis();
        let rigid = stiffness::rigid_body_motions(self.structure(), self.dofs())?;
        let n_rigid = rigid.ncols();
        let projected = &motions - &rigid * (rigid.transpose() * &motions);
        let internal_dim = motions.ncols().saturating_sub(n_rigid);
        let internal = if internal_dim == 0 {
            DMatrix::zeros(motions.nrows(), 0)
        } else {
            let d = linalg::svd(&projected)?;
            d.u.columns(0, internal_dim).into_owned()
        };
        Ok(Flexes {
            internal,
            rigid_body: n_rigid,
        })
    }
}
