//! A cheap estimate of a form-finding run's memory and work, from its sizes only.
//!
//! The method estimated is the one that will run (the `choice` module: the default takes the
//! one the topology's data call for). With n nodes, m members and g force-density parameters
//! (groups and ungrouped members):
//! - dense null space (free-standing, n ≤ [`DENSE_MAX_NODES`]): the symmetric eigensolver,
//!   ≈ [`EIGEN_FLOPS`] · n³ flops and three n × n matrices;
//! - the adaptive method: that eigensolver once per iteration, for `max_iterations` (the cap:
//!   a run that does not converge takes all of them), plus the start's bisection when no
//!   force density is given ([`ADAPTIVE_START`] eigensolves) and the Cholesky factor of the
//!   g × g Gram matrix; `auto` with every force density given may fall back to it, so its
//!   estimate is the force density method's plus the adaptive method's;
//! - sparse solve (fixed nodes, or large free-standing topologies): a sparse LU of the
//!   (planar-like) D_ff, ≈ 200 n^1.5 flops, and a few hundred bytes per member; with members'
//!   self-weight, `max_iterations` more solves with the factors at most (the fixed point, the
//!   `fdm` module), ≈ 100 n flops each; with clusters, `max_iterations` sparse solves at most
//!   (the fixed point q_i ← t/l_i, the `cluster` module refactors D_ff each step);
//! - dynamic relaxation: ≈ [`DR_FLOPS_PER_MEMBER`] · m flops per step, `max_iterations` steps
//!   at most;
//! - the statics of the result (only with [`Settings::analyse`]): the core's dense statics estimate of the 3n × m equilibrium
//!   matrix up to 300 free dofs or members, beyond it the sparse QR, estimated like the sparse
//!   solve on the 3n × m matrix.
//!
//! The constants are calibrated against release timings of a zig-zag chain
//! (`cargo run --release -p formfind --example iteration_cost -- 100 200 400`), rounded up.

use crate::choice;
use crate::fdm::DENSE_MAX_NODES;
use crate::method::{Method, Settings};
use crate::topology::Topology;
use tensegrity_core::budget::{self, Estimate, Parameters, DENSE_FLOP_RATE, SCALAR_FLOP_RATE};

/// Flops of one dense symmetric eigendecomposition with eigenvectors, per n³ (at
/// [`DENSE_FLOP_RATE`]): measured 4·10⁻¹⁰ n³ s (n = 100 … 400), i.e. 2 n³ at that rate.
pub const EIGEN_FLOPS: f64 = 3.0;

/// Eigendecompositions of the adaptive method's start when no force density is given (the
/// bisection of the bars' scale: a few doublings and 60 halvings; measured ≈ 65).
pub const ADAPTIVE_START: f64 = 70.0;

/// Flops of one dynamic relaxation step per member (at [`SCALAR_FLOP_RATE`]): measured
/// 8·10⁻⁹ s per member and step (2000 members).
pub const DR_FLOPS_PER_MEMBER: f64 = 20.0;

/// The estimated memory and work of [`crate::form_find`] on `topology` with `settings`.
///
/// ```
/// let t = formfind::builtin("prism:6").unwrap();
/// let e = formfind::estimate(&t, &formfind::Settings::default());
/// assert!(e.work_s < 1.0 && e.memory_bytes < 1e8);
/// ```
pub fn estimate(topology: &Topology, settings: &Settings) -> Estimate {
    let n = topology.n_nodes;
    // the clusters' segments are elements of the methods (the statics: one column each
    // cluster, fewer)
    let m = topology.n_members() + topology.n_segments();
    // a choice the topology's data refuse fails before any work: the cheap estimate
    let chosen = choice::choose(topology, settings.method).unwrap_or(choice::Choice {
        method: Method::Fdm,
        reason: None,
        fallback: false,
    });
    let mut params = Parameters::default()
        .and("nodes", n)
        .and("members", m)
        .and("method", chosen.method);
    let weighted = !topology.fixed.is_empty()
        && topology
            .given_weights()
            .iter()
            .any(|w| w.is_some_and(|w| w > 0.0));
    let clustered = !topology.clusters.is_empty();
    if chosen.method != Method::Fdm || chosen.fallback || weighted || clustered {
        params = params.and("max_iterations", settings.max_iterations);
    }
    let find = match chosen.method {
        Method::Dr => dr(topology, settings, params.clone()),
        _ if clustered => {
            let solves = settings.max_iterations as f64 * 200.0 * (n as f64).powf(1.5);
            Estimate::new(
                "the clusters' fixed point (a sparse solve per step)",
                params.clone(),
            )
            .memory(400.0 * (n + m) as f64)
            .work(solves / SCALAR_FLOP_RATE)
        }
        Method::Adaptive => adaptive(topology, settings, params.clone()),
        _ if chosen.fallback => {
            fdm(topology, params.clone()).then(adaptive(topology, settings, params.clone()))
        }
        _ if weighted => {
            let solves = settings.max_iterations as f64 * 100.0 * n as f64;
            let iteration = Estimate::new("the self-weight's fixed point", params.clone())
                .memory(48.0 * n as f64)
                .work(solves / SCALAR_FLOP_RATE);
            fdm(topology, params.clone()).then(iteration)
        }
        _ => fdm(topology, params.clone()),
    };
    if !settings.analyse {
        return find;
    }
    let rows = 3 * n;
    let statics = if rows.min(m) < tensegrity_statics::SPARSE_MIN_SIZE {
        budget::dense_statics(rows, m, params)
    } else {
        Estimate::new("the sparse statics of the form", params)
            .memory(400.0 * (rows + m) as f64)
            .work(200.0 * (rows as f64).powf(1.5) / SCALAR_FLOP_RATE)
    };
    find.then(statics)
}

/// The force density method: a dense eigensolve, or a sparse solve.
fn fdm(topology: &Topology, params: Parameters) -> Estimate {
    let n = topology.n_nodes;
    let nf = n as f64;
    if topology.fixed.is_empty() && n <= DENSE_MAX_NODES {
        Estimate::new("the force density method (dense null space)", params)
            .memory(24.0 * nf * nf)
            .work(EIGEN_FLOPS * nf.powi(3) / DENSE_FLOP_RATE)
    } else {
        Estimate::new("the force density method (sparse solve)", params)
            .memory(400.0 * (n + topology.n_members()) as f64)
            .work(200.0 * nf.powf(1.5) / SCALAR_FLOP_RATE)
    }
}

/// The adaptive method (module docs): `max_iterations` eigensolves, the start's bisection
/// and the Gram matrix's factor.
fn adaptive(topology: &Topology, settings: &Settings, params: Parameters) -> Estimate {
    let nf = topology.n_nodes as f64;
    let given = topology.given_force_densities();
    let start = if given.iter().any(Option::is_some) {
        0.0
    } else {
        ADAPTIVE_START
    };
    let g = parameters(topology) as f64;
    let solves = start + settings.max_iterations as f64;
    Estimate::new("the adaptive force density iteration", params)
        .memory(24.0 * nf * nf + 8.0 * g * g)
        .work((solves * EIGEN_FLOPS * nf.powi(3) + g.powi(3) / 3.0) / DENSE_FLOP_RATE)
}

/// Dynamic relaxation: `max_iterations` steps over the members.
fn dr(topology: &Topology, settings: &Settings, params: Parameters) -> Estimate {
    let (n, m) = (
        topology.n_nodes,
        topology.n_members() + topology.n_segments(),
    );
    Estimate::new("dynamic relaxation", params)
        .memory(200.0 * (n + m) as f64)
        .work(DR_FLOPS_PER_MEMBER * m as f64 * settings.max_iterations as f64 / SCALAR_FLOP_RATE)
}

/// The adaptive method's force-density parameters: one per group, one per ungrouped member.
fn parameters(topology: &Topology) -> usize {
    let ungrouped = topology.members().filter(|m| m.group.is_none()).count();
    ungrouped + topology.groups.len()
}
