//! Statics of a T-bar structure through the core's statics front
//! ([`StaticsBackend`]): with the rim supports removed from the degrees of freedom, the
//! equilibrium matrix A (free dofs × members, force densities, A q = w) is factored once; its
//! rank r gives the self-stress dimension members − r and the first-order mechanisms
//! dofs − r. Internal mechanisms are the mechanisms left after the rigid-body motions the
//! supports allow (none with a rigid rim, six with the free rim body), and the
//! prestressability margin is the core's LP: the largest t such that some self-stress with
//! max|q| = 1 has every string q ≥ t and every bar q ≤ −t.
//!
//! The back-end ([`backend`]): a wheel or extended wheel with its Cₙ descriptor
//! ([`crate::symmetry`]) goes through the symmetry-adapted blocks ([`CyclicStatics`],
//! O(n)); when their rank decision is not certified it falls back to the dense SVD if the
//! structure is within [`MAX_DENSE_DOFS`], and otherwise keeps the cyclic answer (the
//! report then says so). A single tread (no rotational symmetry) takes the dense SVD.
//!
//! [`CyclicStatics`]: tensegrity_statics::symmetry::CyclicStatics

use crate::error::{Result, TbarError};
use serde::Serialize;
use tensegrity_core::Structure;
use tensegrity_statics::symmetry::CyclicSymmetry;
use tensegrity_statics::Statics;
use tensegrity_statics::{cyclic_backend, StaticsBackend, StaticsSettings, DEFAULT_MEMORY_LIMIT};

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

/// The statics back-end of `structure` (see the module docs): the cyclic blocks when
/// `symmetry` is given, else the dense SVD (size-checked by [`check_size`]).
pub fn backend<'a>(
    structure: &'a Structure,
    symmetry: Option<&'a CyclicSymmetry>,
) -> Result<Box<dyn StaticsBackend + 'a>> {
    backend_with(structure, symmetry, StaticsSettings::default())
}

/// [`backend`] with the core's statics settings (rank tolerance, LP solver); the memory
/// limit of the dense fallback is that of [`check_size`].
pub fn backend_with<'a>(
    structure: &'a Structure,
    symmetry: Option<&'a CyclicSymmetry>,
    settings: StaticsSettings,
) -> Result<Box<dyn StaticsBackend + 'a>> {
    match symmetry {
        Some(sym) => {
            // the dense fallback of an uncertified block rank decision only within the size
            // limit of the dense analyses
            let limit = if check_size(structure).is_ok() {
                DEFAULT_MEMORY_LIMIT
            } else {
                0.0
            };
            let settings = StaticsSettings {
                memory_limit: Some(limit),
                ..settings
            };
            Ok(cyclic_backend(structure, sym, settings)?)
        }
        None => {
            check_size(structure)?;
            Ok(Box::new(Statics::with_settings(structure, settings)?))
        }
    }
}

/// Factors the equilibrium matrix of `structure` by the dense SVD and summarises it.
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

/// Summarises an already factored structure (any back-end).
pub fn summarise(statics: &dyn StaticsBackend) -> Result<StaticsSummary> {
    let pre = statics.prestressability()?;
    Ok(StaticsSummary {
        free_dofs: statics.free_dofs(),
        rank: statics.rank(),
        self_stress_dim: statics.self_stress_dim(),
        mechanisms: statics.mechanisms(),
        internal_mechanisms: statics.internal_mechanisms()?,
        prestressable: pre.prestressable,
        prestress_margin: pre.margin,
    })
}
