//! The cyclic symmetry of the T-bar wheel: tread k is tread 0 rotated by 2kφ about ι̂₁ (the x
//! axis), so the wheel of n = π/φ treads (and the extended wheel, both copies alike) is
//! invariant under the rotation by 2π/n = 2φ about ι̂₁ through the origin. The node
//! permutation is found by position (nodes are merged by position when the wheel is built)
//! and the member permutation from it; the core validates both
//! ([`CyclicSymmetry::from_positions`]). The rim supports are pinned nodes, carried onto
//! pinned nodes.
//!
//! [`find_symmetry`] is what [`crate::tbar_report`] uses: the descriptor of a wheel (n ≥ 3
//! treads), nothing for a tread or a wheel of fewer treads. [`symmetric_statics_summary`]
//! gives [`crate::statics::statics_summary`]'s numbers from the symmetry-adapted blocks,
//! without the dense SVD (and without its size limit).

use crate::error::{Result, TbarError};
use crate::geometry::TbarGeometry;
use crate::params::Layout;
use crate::statics::{summarise, StaticsSummary};
use nalgebra::Vector3;
use tensegrity_core::Warning;
use tensegrity_core::{CoreError, StaticsError, Structure};
use tensegrity_statics::symmetry::{CyclicStatics, CyclicSymmetry, SymmetryError};

/// The Cₙ descriptor (n = π/φ) of a wheel or extended wheel and its structure; a single tread
/// has no rotational symmetry (`SymmetryError::TooFewSides` with n = 1).
///
/// ```
/// use michell3d::MichellParams;
/// use tbar_wheel::{symmetry::wheel_symmetry, Layout, TbarGeometry, TbarParams};
/// let m = MichellParams::cylindrical(1, 1.0, 0.5, std::f64::consts::PI / 8.0, 0.25);
/// let g = TbarGeometry::new(TbarParams::tread(m).with_layout(Layout::Wheel)).unwrap();
/// let sym = wheel_symmetry(&g, &g.structure().unwrap()).unwrap();
/// assert_eq!(sym.order(), 8);
/// ```
pub fn wheel_symmetry(geometry: &TbarGeometry, structure: &Structure) -> Result<CyclicSymmetry> {
    let n = match geometry.params.layout {
        Layout::Tread => {
            return Err(
                tensegrity_core::CoreError::from(SymmetryError::TooFewSides { n: 1 }).into(),
            )
        }
        _ => geometry.params.treads_per_wheel()?,
    };
    Ok(CyclicSymmetry::from_positions(
        structure,
        n,
        Vector3::x(),
        Vector3::zeros(),
    )?)
}

/// The Cₙ descriptor of a wheel or extended wheel with n ≥ 3 treads per wheel; `None` for a
/// tread, a wheel of one or two treads, or (with a warning pushed on `warnings`) a wheel
/// whose descriptor does not validate, which then takes the dense path.
pub fn find_symmetry(
    geometry: &TbarGeometry,
    structure: &Structure,
    warnings: &mut Vec<Warning>,
) -> Option<CyclicSymmetry> {
    if geometry.params.layout == Layout::Tread {
        return None;
    }
    match wheel_symmetry(geometry, structure) {
        Ok(sym) => Some(sym),
        Err(TbarError::Core(CoreError::Statics(StaticsError::Symmetry(e))))
            if matches!(*e, SymmetryError::TooFewSides { .. }) =>
        {
            None
        }
        Err(e) => {
            warnings.push(Warning::NoCyclicSymmetry {
                reason: e.to_string(),
            });
            None
        }
    }
}

/// The statics summary of a wheel or extended wheel through the symmetry-adapted path.
///
/// ```
/// use michell3d::MichellParams;
/// use tbar_wheel::{statics::statics_summary, symmetry::symmetric_statics_summary};
/// use tbar_wheel::{Layout, TbarGeometry, TbarParams};
/// let m = MichellParams::cylindrical(1, 1.0, 0.5, std::f64::consts::PI / 8.0, 0.25);
/// let g = TbarGeometry::new(TbarParams::tread(m).with_layout(Layout::Wheel)).unwrap();
/// let sym = symmetric_statics_summary(&g).unwrap();
/// let dense = statics_summary(&g.structure().unwrap()).unwrap();
/// assert_eq!((sym.rank, sym.self_stress_dim), (dense.rank, dense.self_stress_dim));
/// ```
pub fn symmetric_statics_summary(geometry: &TbarGeometry) -> Result<StaticsSummary> {
    let structure = geometry.structure()?;
    let sym = wheel_symmetry(geometry, &structure)?;
    summarise(&CyclicStatics::new(&structure, &sym)?)
}
