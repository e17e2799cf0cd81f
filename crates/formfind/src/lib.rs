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
//! - [`Method::Auto`] (the default) chooses among them from what the topology gives
//!   ([`form_find`]).
//! - [`synthesize`]: rest lengths from the found geometry and self-stress scaled to a
//!   prestress level.
//!
//! Topologies come from a [`Topology`] (built in Rust, read from a TOML file by the io crate)
//! or from [`builtin`] (`prism:N`, `octahedron`, `tower:N:M`, `grid:K`, …).
//!
//! ```
//! use formfind::{form_find, synthesize, Member, Method, Settings, Synthesis, Topology};
//! use std::collections::BTreeMap;
//!
//! // The 3-bar prism from connectivity, member kinds and groups only: the adaptive method
//! // finds its force densities.
//! let n = 3;
//! let group = |name: &str| (name.to_string(), formfind::Group::default());
//! let mut bars = Vec::new();
//! let mut strings = Vec::new();
//! for i in 0..n {
//!     bars.push(Member::new(i, n + i).group("bars"));
//!     strings.push(Member::new(i, (i + 1) % n).group("bottom"));
//!     strings.push(Member::new(n + i, n + (i + 1) % n).group("top"));
//!     strings.push(Member::new(i, n + (i + n - 1) % n).group("vertical"));
//! }
//! let topology = Topology {
//!     n_nodes: 2 * n,
//!     bars,
//!     strings,
//!     groups: BTreeMap::from([group("bars"), group("bottom"), group("top"), group("vertical")]),
//!     ..Topology::default()
//! };
//! let found = form_find(&topology, &Settings::default()).unwrap();
//! assert_eq!(found.method, Method::Adaptive);
//! assert!(found.prestressable && found.prestress_stable);
//! // Bars average −1; for the symmetric prism every vertical string then carries 1.
//! let vertical = found.force_density[3 + 2]; // strings[2], the first vertical
//! assert!((vertical - 1.0).abs() < 1e-9);
//!
//! // A structure in equilibrium at t = 0 with 50 N in the most tensioned string.
//! let synthesis = Synthesis { prestress: 50.0, ..Synthesis::default() };
//! let structure = synthesize(&topology, &found, &synthesis).unwrap();
//! assert_eq!((structure.n_bars(), structure.n_strings()), (3, 9));
//! ```
#![warn(missing_docs)]
#![allow(non_snake_case)]

mod adaptive;
mod analysis;
mod builtin;
mod dr;
mod error;
mod estimate;
mod fdm;
mod method;
mod report;
mod result;
mod synth;
mod topology;

pub use analysis::{STABILITY_MAX_MEMBERS, WITNESS_TOLERANCE};
pub use builtin::{builtin, prism_twist, BUILTINS, MAX_GRID, MAX_PRISM, MAX_STAGES};
pub use error::{FormFindError, Result};
pub use estimate::estimate;
pub use fdm::{force_density_matrix, DENSE_MAX_NODES, NULL_SPACE_TOLERANCE};
pub use method::{Method, Settings, Synthesis};
pub use report::{find, scale_group, FormfindReport, Formfound};
pub use result::FormFound;
pub use synth::{rest_lengths, synthesize, synthesize_with, RestLengths};
pub use topology::{FixedNode, Group, Member, Topology};

use nalgebra::Vector3;

/// Finds the form of `topology` by the method and tolerances of `settings`.
///
/// [`Method::Auto`] takes the force density method when every member has a force density
/// (falling back to the adaptive method, started from them, when they admit no free-standing
/// form), dynamic relaxation when instead every member has a length and the topology has
/// nodes, and the adaptive method otherwise. The result's `method` is the one that found it.
pub fn form_find(topology: &Topology, settings: &Settings) -> Result<FormFound> {
    topology.validate()?;
    settings.validate()?;
    match settings.method {
        Method::Fdm => {
            let q = topology.force_densities()?;
            let nodes = fdm::geometry(topology, &q)?;
            finish(topology, Method::Fdm, nodes, q, 1)
        }
        Method::Adaptive => {
            let (nodes, q, it) = adaptive::run(topology, settings)?;
            finish(topology, Method::Adaptive, nodes, q, it)
        }
        Method::Dr => {
            let (nodes, q, it) = dr::run(topology, settings)?;
            finish(topology, Method::Dr, nodes, q, it)
        }
        Method::Auto => auto(topology, settings),
    }
}

/// [`Method::Auto`] (see [`form_find`]).
fn auto(topology: &Topology, settings: &Settings) -> Result<FormFound> {
    let with = |method| Settings {
        method,
        ..settings.clone()
    };
    let given = topology.given_force_densities();
    if given.iter().all(Option::is_some) {
        let q = topology.force_densities()?;
        return match fdm::geometry(topology, &q) {
            Ok(nodes) => finish(topology, Method::Fdm, nodes, q, 1),
            Err(FormFindError::RankDeficiency { .. })
                if topology.fixed.is_empty() && topology.n_nodes <= adaptive::MAX_NODES =>
            {
                form_find(topology, &with(Method::Adaptive))
            }
            Err(e) => Err(e),
        };
    }
    if topology.nodes.is_some() && topology.given_lengths().iter().all(Option::is_some) {
        return form_find(topology, &with(Method::Dr));
    }
    form_find(topology, &with(Method::Adaptive))
}

/// The statics of the found geometry, packed as a [`FormFound`].
fn finish(
    topology: &Topology,
    method: Method,
    nodes: Vec<Vector3<f64>>,
    q: Vec<f64>,
    iterations: usize,
) -> Result<FormFound> {
    if let Some(i) = nodes.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(FormFindError::SingularSystem {
            hint: format!("{method}: node {i} came out non-finite"),
        });
    }
    let a = analysis::analyse(topology, &nodes, &q)?;
    Ok(FormFound {
        method,
        nodes,
        force_density: q,
        self_stress_dim: a.self_stress_dim,
        prestressable: a.prestressable,
        prestress_stable: a.prestress_stable,
        residual: a.residual,
        iterations,
    })
}

/// The README's examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
