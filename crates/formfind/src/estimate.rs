//! A cheap estimate of a form-finding run's memory and work, from its sizes only.
//!
//! With n nodes and m members:
//! - dense null space (free-standing, n ≤ [`DENSE_MAX_NODES`]): the symmetric eigensolver,
//!   ≈ 9 n³ flops and three n × n matrices; the adaptive method repeats it per iteration
//!   (estimated at 50 iterations);
//! - sparse solve (fixed nodes, or large free-standing topologies): a sparse LU of the
//!   (planar-like) D_ff, ≈ 200 n^1.5 flops, and a few hundred bytes per member;
//! - dynamic relaxation: ≈ 60 m flops per step, `max_iterations` steps at most;
//! - the statics of the result: the core's dense statics estimate of the 3n × m equilibrium
//!   matrix up to 300 free dofs or members, beyond it the sparse QR, estimated like the sparse
//!   solve on the 3n × m matrix.

use crate::fdm::DENSE_MAX_NODES;
use crate::method::{Method, Settings};
use crate::topology::Topology;
use tensegrity_core::budget::{self, Estimate, Parameters, DENSE_FLOP_RATE, SCALAR_FLOP_RATE};

/// The estimated memory and work of [`crate::form_find`] on `topology` with `settings`.
///
/// ```
/// let t = formfind::builtin("prism:6").unwrap();
/// let e = formfind::estimate(&t, &formfind::Settings::default());
/// assert!(e.work_s < 1.0 && e.memory_bytes < 1e8);
/// ```
pub fn estimate(topology: &Topology, settings: &Settings) -> Estimate {
    let n = topology.n_nodes;
    let m = topology.n_members();
    let params = Parameters::default()
        .and("nodes", n)
        .and("members", m)
        .and("method", settings.method);
    let nf = n as f64;
    let dense = topology.fixed.is_empty() && n <= DENSE_MAX_NODES;
    let find = match settings.method {
        Method::Dr => Estimate::new("dynamic relaxation", params.clone())
            .memory(200.0 * (n + m) as f64)
            .work(60.0 * m as f64 * settings.max_iterations as f64 / SCALAR_FLOP_RATE),
        Method::Adaptive => Estimate::new("the adaptive force density iteration", params.clone())
            .memory(24.0 * nf * nf)
            .work(50.0 * 9.0 * nf.powi(3) / DENSE_FLOP_RATE),
        _ if dense => Estimate::new(
            "the force density method (dense null space)",
            params.clone(),
        )
        .memory(24.0 * nf * nf)
        .work(9.0 * nf.powi(3) / DENSE_FLOP_RATE),
        _ => Estimate::new("the force density method (sparse solve)", params.clone())
            .memory(400.0 * (n + m) as f64)
            .work(200.0 * nf.powf(1.5) / SCALAR_FLOP_RATE),
    };
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
