//! Statics of a T-bar structure through the core's [`Statics`]: with the rim supports removed
//! from the degrees of freedom, the equilibrium matrix A (free dofs × members, force
//! densities, A q = w) is factored once by SVD; its rank r gives the self-stress dimension
//! members − r and the first-order mechanisms dofs − r. Internal mechanisms are the flexes
//! left after the rigid-body motions the supports allow (none with a rigid rim), and the
//! prestressability margin is the core's LP: the largest t such that some self-stress with
//! max|q| = 1 has every string q ≥ t and every bar q ≤ −t.

use crate::error::{Result, TbarError};
use serde::Serialize;
use tensegrity_core::{Statics, Structure};

/// Largest number of free degrees of freedom of the dense statics (SVD of A).
pub const MAX_DENSE_DOFS: usize = 6000;

/// The statics summary of a T-bar structure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StaticsSummary {
    /// Free degrees of freedom (rows of A).
    pub free_dofs: usize,
    /// Rank of A.
    pub rank: usize,
    /// Dimension of the self-stress space.
    pub self_stress_dim: usize,
    /// First-order mechanisms (free dofs − rank).
    pub mechanisms: usize,
    /// Mechanisms left after the rigid-body motions the supports allow.
    pub internal_mechanisms: usize,
    /// Whether some self-stress has strings in tension and bars in compression.
    pub prestressable: bool,
    /// The prestressability margin t ∈ [0, 1] of the core's LP.
    pub prestress_margin: f64,
}

/// Refuses structures too large for the dense analyses, naming the count and the limit.
pub fn check_size(structure: &Structure) -> Result<()> {
    let dofs = 3 * structure.n_nodes();
    if dofs > 3 * MAX_DENSE_DOFS {
        return Err(TbarError::TooLarge {
            what: "degrees of freedom (3 × nodes)",
            size: dofs,
            limit: 3 * MAX_DENSE_DOFS,
        });
    }
    Ok(())
}

/// Factors the equilibrium matrix of `structure` and summarises it.
///
/// ```
/// use michell3d::MichellParams;
/// use tbar_wheel::{statics::statics_summary, TbarGeometry, TbarParams};
/// let m = MichellParams::cylindrical(1, 1.0, 0.5, std::f64::consts::PI / 8.0, 0.25);
/// let s = TbarGeometry::new(TbarParams::tread(m)).unwrap().structure().unwrap();
/// let sum = statics_summary(&s).unwrap();
/// assert_eq!((sum.self_stress_dim, sum.internal_mechanisms), (2, 0));
/// assert!(sum.prestressable);
/// ```
pub fn statics_summary(structure: &Structure) -> Result<StaticsSummary> {
    check_size(structure)?;
    let statics = Statics::new(structure)?;
    summarise(&statics)
}

/// Summarises an already factored structure.
pub fn summarise(statics: &Statics<'_>) -> Result<StaticsSummary> {
    let flexes = statics.flexes()?;
    let pre = statics.prestressability()?;
    Ok(StaticsSummary {
        free_dofs: statics.dofs().len(),
        rank: statics.rank(),
        self_stress_dim: statics.self_stress_dim(),
        mechanisms: statics.mechanisms(),
        internal_mechanisms: flexes.internal.ncols(),
        prestressable: pre.prestressable,
        prestress_margin: pre.margin,
    })
}
