//! Prestress stability (Connelly–Whiteley second-order test with a given stress).
//!
//! A structure with force densities q (normally a self-stress) is prestress stable when
//! δnᵀ (Ω ⊗ I₃) δn > 0 for every internal mechanism δn, Ω = Cᵀ diag(q) C the stress matrix
//! ([`stress_matrix`](crate::stiffness::stress_matrix)); with no internal mechanism it is
//! first-order rigid. The test takes the eigenvalues of the stress matrix projected on an
//! orthonormal basis of the internal mechanisms ([`Statics::flexes`]).

use super::Statics;
use crate::stiffness;
use nalgebra::{DMatrix, DVector};
use tensegrity_core::error::Result;
use tensegrity_linalg as linalg;

/// Result of the prestress-stability test.
#[derive(Debug, Clone, PartialEq)]
pub struct PrestressStability {
    /// Number of internal mechanisms (first-order flexes beyond rigid-body motion).
    pub internal_mechanisms: usize,
    /// Eigenvalues of the stress matrix projected on the internal mechanisms, ascending
    /// (empty when there are none).
    pub eigenvalues: Vec<f64>,
    /// Whether every internal mechanism is stiffened by the stress (or there is none).
    pub stable: bool,
}

impl PrestressStability {
    /// No internal mechanism: first-order rigid, hence stable.
    pub(crate) fn rigid() -> Self {
        Self {
            internal_mechanisms: 0,
            eigenvalues: Vec::new(),
            stable: true,
        }
    }

    /// The test on Φᵀ (Ω ⊗ I₃) Φ for an orthonormal basis Φ of the internal mechanisms: its
    /// (symmetrised) eigenvalues must exceed 1e-9 · `q_max`.
    pub(crate) fn from_projected(projected: &DMatrix<f64>, q_max: f64) -> Result<Self> {
        let sym = (projected + projected.transpose()) * 0.5;
        let (w, _) = linalg::symmetric_eigen(&sym)?;
        let stable = w.first().is_some_and(|&w0| w0 > 1e-9 * q_max);
        Ok(Self {
            internal_mechanisms: projected.ncols(),
            eigenvalues: w,
            stable,
        })
    }
}

impl Statics<'_> {
    /// Tests prestress stability with force densities `q` (normally a self-stress).
    ///
    /// The eigenvalues of the stress matrix projected on the internal mechanisms must exceed
    /// 1e-9 · max|q|, a tolerance relative to the stress level.
    pub fn prestress_stability(&self, q: &DVector<f64>) -> Result<PrestressStability> {
        let flexes = self.flexes()?;
        let phi = &flexes.internal;
        if phi.ncols() == 0 {
            return Ok(PrestressStability::rigid());
        }
        let omega = stiffness::stress_matrix(self.structure(), self.dofs(), q);
        PrestressStability::from_projected(&(phi.transpose() * omega * phi), q.amax())
    }
}
