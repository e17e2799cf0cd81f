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
//! - [`Method::Given`] (the default) takes the one the topology's data call for: `fdm` for
//!   force densities on every member, `dr` for lengths on every member, `adaptive` for
//!   neither; data given is never ignored, and a failing method never silently becomes
//!   another ([`form_find`]). [`Method::Auto`] (asked for by name) may fall back from `fdm`
//!   to `adaptive`, and says so.
//! - Loads ([`Topology::loads`], members' [`Member::weight`]): the force density method with
//!   fixed nodes solves D_ff X_f = P_f − D_fx X_x, the self-weight by a fixed-point iteration,
//!   and reports the loads carried, the reactions r_i = (D X)_i − p_i at the fixed nodes and
//!   the equilibrium residual ([`FormFound::reactions`]); free-standing topologies with loads
//!   and other methods are refused (the `fdm` module docs).
//! - Clustered strings ([`Topology::clusters`]: one prescribed tension t along a string
//!   through several nodes): each segment's force density t / l_i depends on the form, so
//!   the force density method (held nodes) iterates q_i ← t / l_i to a fixed point and
//!   dynamic relaxation applies t e_i directly (the `cluster` module docs);
//!   [`FormFound::clusters`] reports each one, and the synthesis writes it as a core
//!   [`tensegrity_core::Cluster`] of rest length L / (1 + t/EA).
//! - The statics of the found form ([`Settings::analyse`], off by default: [`ANALYSE`]): the
//!   self-stress dimension, prestressability (the margin LP where no witness settles it) and
//!   prestress stability, the costly part of a large form; without them the result holds the
//!   form, its force densities and the cheap residual ‖A q + p‖ / ‖q‖, and
//!   [`FormFound::analyse`] adds them later to a form found without.
//! - [`sensitivity`]: exact derivatives of a form with held nodes — the force density
//!   method's with respect to its force densities, loads and held positions, dynamic
//!   relaxation's with respect to the rest lengths and stiffnesses — forward (one sparse
//!   solve per parameter) and adjoint (one solve per scalar objective, whatever the number of
//!   parameters), reusing the factors the form was found with.
//! - [`synthesize`]: rest lengths from the found geometry and self-stress scaled to a
//!   prestress level (a loaded form: the forces q L the loads set, and the loads kept).
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
//! // The statics of the found form (self-stress dimension, prestressability, stability) only
//! // where asked for: `analyse` (default `false`, [`ANALYSE`]).
//! let settings = Settings { analyse: true, ..Settings::default() };
//! let found = form_find(&topology, &settings).unwrap();
//! assert_eq!(found.method, Method::Adaptive);
//! assert_eq!((found.prestressable, found.prestress_stable), (Some(true), Some(true)));
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
mod choice;
mod cluster;
pub mod design;
mod dr;
mod error;
mod estimate;
mod fdm;
mod method;
mod report;
mod result;
pub mod sensitivity;
mod synth;
mod topology;

pub use analysis::{STABILITY_MAX_MEMBERS, WITNESS_TOLERANCE};
pub use builtin::{builtin, prism_twist, BUILTINS, MAX_GRID, MAX_PRISM, MAX_STAGES};
pub use cluster::ClusterState;
pub use dr::PRECISION_FLOOR;
pub use error::{FormFindError, Result};
pub use estimate::{estimate, ADAPTIVE_START, DR_FLOPS_PER_MEMBER, EIGEN_FLOPS};
pub use fdm::{force_density_matrix, DENSE_MAX_NODES, NULL_SPACE_TOLERANCE};
pub use method::{Method, Settings, Synthesis, ANALYSE};
pub use report::{find, scale_group, ClusterReport, FormfindReport, Formfound, Loading};
pub use result::{FormFound, NodeForce};
pub use synth::{rest_lengths, synthesize, synthesize_with, ClusterRest, RestLengths, MIN_STRAIN};
pub use topology::{too_many_nodes, ClusterString, FixedNode, Group, Member, NodeLoad, Topology};

use nalgebra::Vector3;

/// Finds the form of `topology` by the method and tolerances of `settings`.
///
/// The method that runs follows from the one asked for and the data the topology gives, and
/// no given data is ignored (the `choice` module docs): [`Method::Given`] (the default) takes
/// the force density method when every member has a force density, dynamic relaxation when
/// every member has a length instead, and the adaptive method when it gives neither; a
/// failure of the force density method is the error (naming `method = adaptive`), never a
/// silent switch. Only [`Method::Auto`] falls back to the adaptive method (started from the
/// given force densities, which it replaces) and says so in [`FormFound::choice`]. The
/// result's `method` is the one that found the form.
pub fn form_find(topology: &Topology, settings: &Settings) -> Result<FormFound> {
    topology.validate()?;
    settings.validate()?;
    let choice = choice::choose(topology, settings.method)?;
    let found = match choice.method {
        Method::Fdm => run_fdm(topology, settings),
        Method::Dr => {
            let (nodes, q, it, tol) = dr::run(topology, settings)?;
            finish(topology, settings, Method::Dr, nodes, q, (it, Some(tol)))
        }
        _ => run_adaptive(topology, settings),
    };
    let (found, reason) = match found {
        Err(e) if choice.fallback && falls_back(topology, &e) => {
            let reason = format!(
                "method auto chose adaptive: the force density method found no form ({}); \
                 the adaptive method replaced the given force densities",
                summary(&e)
            );
            (run_adaptive(topology, settings), Some(reason))
        }
        other => (other, choice.reason),
    };
    found.map(|f| FormFound {
        choice: reason,
        ..f
    })
}

/// The force density method's failure in a few words (the warning of `auto`'s fallback).
fn summary(e: &FormFindError) -> String {
    match e {
        FormFindError::RankDeficiency {
            found, required, ..
        } => {
            format!("the force density matrix has rank deficiency {found}, {required} is required")
        }
        e => e.to_string(),
    }
}

/// Whether `auto` falls back from the force density method's error `e` to the adaptive
/// method: a rank deficiency of a free-standing form the adaptive method can take.
fn falls_back(topology: &Topology, e: &FormFindError) -> bool {
    matches!(e, FormFindError::RankDeficiency { .. })
        && topology.fixed.is_empty()
        && topology.n_nodes <= adaptive::MAX_NODES
}

fn run_fdm(topology: &Topology, settings: &Settings) -> Result<FormFound> {
    let q = topology.force_densities()?;
    if !topology.clusters.is_empty() {
        let (nodes, loads, q, iterations) = cluster::fixed_point(topology, &q, settings)?;
        let tolerance = Some(settings.tolerance);
        return finish_loaded(
            topology,
            settings,
            nodes,
            q,
            &loads,
            (iterations, tolerance),
        );
    }
    if topology.is_loaded() && !topology.fixed.is_empty() {
        let (nodes, loads, iterations) = fdm::loaded(topology, &q, settings)?;
        let weighted = topology
            .given_weights()
            .iter()
            .any(|w| w.unwrap_or(0.0) > 0.0);
        let tolerance = weighted.then_some(settings.tolerance);
        return finish_loaded(
            topology,
            settings,
            nodes,
            q,
            &loads,
            (iterations, tolerance),
        );
    }
    let nodes = fdm::geometry(topology, &q)?;
    finish(topology, settings, Method::Fdm, nodes, q, (1, None))
}

fn run_adaptive(topology: &Topology, settings: &Settings) -> Result<FormFound> {
    let (nodes, q, it) = adaptive::run(topology, settings)?;
    let tol = Some(settings.tolerance);
    finish(topology, settings, Method::Adaptive, nodes, q, (it, tol))
}

/// The found geometry packed as a [`FormFound`] with its residual, and its statics where
/// `settings.analyse` asks for them; a non-finite node, force density or residual is refused
/// (an overflow never reaches a result). The statics take q / max|q| (they are invariant
/// under a positive scale), so force densities near the largest double do not overflow them.
fn finish(
    topology: &Topology,
    settings: &Settings,
    method: Method,
    nodes: Vec<Vector3<f64>>,
    q: Vec<f64>,
    iterations: (usize, Option<f64>),
) -> Result<FormFound> {
    finish_with(
        topology,
        settings.analyse,
        method,
        nodes,
        q,
        &[],
        iterations,
    )
}

/// [`finish`] of the force density method under `loads` (one per node, N).
fn finish_loaded(
    topology: &Topology,
    settings: &Settings,
    nodes: Vec<Vector3<f64>>,
    q: Vec<f64>,
    loads: &[Vector3<f64>],
    iterations: (usize, Option<f64>),
) -> Result<FormFound> {
    if let Some(i) = loads.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(FormFindError::NonFinite {
            method: Method::Fdm.to_string(),
            item: format!("the load on node {i}"),
        });
    }
    finish_with(
        topology,
        settings.analyse,
        Method::Fdm,
        nodes,
        q,
        loads,
        iterations,
    )
}

/// [`finish`] with the loads (`loads`: one per node in N, or empty), the reactions and the
/// equilibrium residual; the statics only when `analyse` asks for them.
fn finish_with(
    topology: &Topology,
    analyse: bool,
    method: Method,
    nodes: Vec<Vector3<f64>>,
    q: Vec<f64>,
    loads: &[Vector3<f64>],
    (iterations, tolerance): (usize, Option<f64>),
) -> Result<FormFound> {
    let non_finite = |item: String| FormFindError::NonFinite {
        method: method.to_string(),
        item,
    };
    if let Some(i) = nodes.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(non_finite(format!("node {i}")));
    }
    if let Some(k) = q.iter().position(|x| !x.is_finite()) {
        return Err(non_finite(format!(
            "{}.force_density",
            topology.member_name(k)
        )));
    }
    let scale = q.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let unit: Vec<f64> = q.iter().map(|x| x / scale.max(f64::MIN_POSITIVE)).collect();
    let unit_loads: Vec<Vector3<f64>> = loads
        .iter()
        .map(|p| p / scale.max(f64::MIN_POSITIVE))
        .collect();
    let residual = analysis::residual(topology, &nodes, &unit, &unit_loads);
    if !residual.is_finite() {
        return Err(non_finite("the residual".into()));
    }
    let (reactions, equilibrium_residual) = if topology.fixed.is_empty() {
        (Vec::new(), None)
    } else {
        let (r, relative) = analysis::reactions(topology, &nodes, &unit, &unit_loads);
        let mut reactions = Vec::with_capacity(r.len());
        for (f, r) in topology.fixed.iter().zip(r) {
            let force = r * scale;
            if !force.iter().all(|x| x.is_finite()) || !relative.is_finite() {
                return Err(non_finite(format!("the reaction at node {}", f.node)));
            }
            reactions.push(NodeForce {
                node: f.node,
                force: [force.x, force.y, force.z],
            });
        }
        (reactions, Some(relative))
    };
    let loads = loads
        .iter()
        .enumerate()
        .filter(|(i, p)| **p != Vector3::zeros() || topology.loads.iter().any(|l| l.node == *i))
        .map(|(node, p)| NodeForce {
            node,
            force: [p.x, p.y, p.z],
        })
        .collect();
    let clusters = cluster::states(topology, &nodes);
    let statics = if analyse {
        Some(analysis::analyse(topology, &nodes, &unit, &unit_loads)?)
    } else {
        None
    };
    let mut q = q;
    q.truncate(topology.n_members());
    let found = FormFound {
        method,
        clusters,
        nodes,
        force_density: q,
        self_stress_dim: None,
        prestressable: None,
        prestress_stable: None,
        residual,
        iterations,
        tolerance,
        choice: None,
        loads,
        reactions,
        equilibrium_residual,
    };
    Ok(match statics {
        Some(a) => found.with_analysis(&a),
        None => found,
    })
}

/// The README's examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
