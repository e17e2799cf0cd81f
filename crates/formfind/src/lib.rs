//! # formfind
//!
//! Form-finding of tensegrity structures: from a connectivity (bars and strings, optional
//! groups, fixed nodes and target lengths) to a geometry in equilibrium with a self-stress,
//! and from there to a [`tensegrity_core::Structure`] whose string rest lengths realise a
//! chosen prestress, so that every other analysis starts from equilibrium.
//!
//! - [`Method::Fdm`]: the force density method. With force densities q (tension-positive,
//!   bars negative) the force density matrix is D = Cᵀ diag(q) C; a free-standing geometry
//!   lies in the null space of D (rank deficiency ≥ d + 1 = 4 in 3-D), with fixed nodes the
//!   free coordinates solve D_ff N_fᵀ = −D_fx N_xᵀ.
//! - [`Method::Adaptive`]: adaptive force density: force densities iterated on the spectral
//!   decomposition of D until the required rank deficiency is reached, with a prestressable,
//!   prestress-stable self-stress; reported when none exists.
//! - [`Method::Dr`]: dynamic relaxation with kinetic damping from rest lengths and axial
//!   stiffnesses.
//! - [`synthesize`]: rest lengths from the found geometry and self-stress scaled to a
//!   prestress level.
//!
//! Topologies come from a [`Topology`] (built in Rust, read from a TOML file by the io crate)
//! or from [`builtin`] (`prism:N`, `octahedron`, `tower:N:M`, `grid:K`, …).
#![warn(missing_docs)]
#![allow(non_snake_case)]

mod builtin;
mod error;
mod method;
mod result;
mod topology;

pub use builtin::{builtin, BUILTINS};
pub use error::{FormFindError, Result};
pub use method::{Method, Settings, Synthesis};
pub use result::FormFound;
pub use topology::{FixedNode, Group, Member, Topology};

use tensegrity_core::Structure;

/// Finds the form of `topology` by the method and tolerances of `settings`.
pub fn form_find(topology: &Topology, settings: &Settings) -> Result<FormFound> {
    topology.validate()?;
    let _ = settings;
    Err(FormFindError::Unsupported {
        what: "form-finding (not built yet)".into(),
    })
}

/// The structure realising `found`: its geometry, its self-stress scaled to the prestress
/// level of `synthesis`, and for each string the rest length that gives that tension at the
/// given axial stiffness (bars carry their compression as rigid members).
pub fn synthesize(
    topology: &Topology,
    found: &FormFound,
    synthesis: &Synthesis,
) -> Result<Structure> {
    let _ = (topology, found, synthesis);
    Err(FormFindError::Unsupported {
        what: "rest-length synthesis (not built yet)".into(),
    })
}
