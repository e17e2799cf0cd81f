//! Dynamic relaxation with kinetic damping (Barnes), from rest lengths and axial stiffnesses.
//!
//! Member k with rest length s0_k (its `length`, or its group's) and axial stiffness EA_k
//! (its `stiffness`, else [`crate::Settings::stiffness`]) at current length L carries
//!
//! T_k = EA_k (L − s0_k) / s0_k   (strings: max(T_k, 0), slack below their rest length),
//!
//! and node i the out-of-balance force R_i = Σ_k T_k/L_k (n_other − n_i) (zero at fixed
//! nodes). With the time step Δt = 1 and fictitious masses m_i = Σ_k (EA_k/s0_k + |T_k|/L_k)
//! over the members at i (twice the Gershgorin bound Δt²/2 · Σ stiffness, so the explicit
//! scheme is stable), the leapfrog steps
//!
//! v ← v + Δt R / m,   x ← x + Δt v
//!
//! run until the kinetic energy Σ m ‖v‖² drops; then the nodes go back to the energy peak,
//! x ← x − 1.5 Δt v + Δt² R / (2m) (R the force of the step that overshot), the velocities
//! are reset to zero and the masses recomputed. It stops when max_i ‖R_i‖ ≤ tolerance ·
//! max_k |T_k| ([`crate::Settings::tolerance`]), from the topology's nodes as the start, and
//! fails with [`FormFindError::NotConverged`] after `max_iterations` steps. The force
//! densities reported are T_k / L_k.

use crate::error::{FormFindError, Result};
use crate::method::Settings;
use crate::topology::Topology;
use nalgebra::Vector3;

/// Member forces and nodal residuals at `x`.
struct State {
    tension: Vec<f64>,
    length: Vec<f64>,
    residual: Vec<Vector3<f64>>,
}

struct Problem {
    pairs: Vec<[usize; 2]>,
    rest: Vec<f64>,
    ea: Vec<f64>,
    nb: usize,
    fixed: Vec<bool>,
}

impl Problem {
    fn state(&self, x: &[Vector3<f64>]) -> State {
        let m = self.pairs.len();
        let mut s = State {
            tension: Vec::with_capacity(m),
            length: Vec::with_capacity(m),
            residual: vec![Vector3::zeros(); x.len()],
        };
        for (k, &[i, j]) in self.pairs.iter().enumerate() {
            let d = x[j] - x[i];
            let l = d.norm();
            let mut t = self.ea[k] * (l - self.rest[k]) / self.rest[k];
            if k >= self.nb {
                t = t.max(0.0);
            }
            let f = d * (t / l);
            s.residual[i] += f;
            s.residual[j] -= f;
            s.tension.push(t);
            s.length.push(l);
        }
        for (r, &fx) in s.residual.iter_mut().zip(&self.fixed) {
            if fx {
                *r = Vector3::zeros();
            }
        }
        s
    }

    fn masses(&self, s: &State, n: usize) -> Vec<f64> {
        let mut m = vec![0.0; n];
        for (k, &[i, j]) in self.pairs.iter().enumerate() {
            let stiff = self.ea[k] / self.rest[k] + s.tension[k].abs() / s.length[k];
            m[i] += stiff;
            m[j] += stiff;
        }
        m
    }
}

/// Runs dynamic relaxation: nodes, force densities, iterations.
pub(crate) fn run(
    topology: &Topology,
    settings: &Settings,
) -> Result<(Vec<Vector3<f64>>, Vec<f64>, usize)> {
    let mut x = topology
        .initial_nodes()
        .ok_or_else(|| FormFindError::InvalidTopology {
            item: "nodes".into(),
            reason: "dynamic relaxation starts from the topology's nodes: give them".into(),
        })?;
    let rest = topology
        .given_lengths()
        .into_iter()
        .enumerate()
        .map(|(k, l)| {
            l.ok_or_else(|| FormFindError::InvalidTopology {
                item: format!("{}.length", topology.member_name(k)),
                reason: "dynamic relaxation needs a rest length for every member (on the \
                         member or its group)"
                    .into(),
            })
        })
        .collect::<Result<Vec<f64>>>()?;
    let ea: Vec<f64> = topology
        .members()
        .map(|m| m.stiffness.unwrap_or(settings.stiffness))
        .collect();
    let mut fixed = vec![false; topology.n_nodes];
    for f in &topology.fixed {
        fixed[f.node] = true;
        x[f.node] = Vector3::from(f.position);
    }
    let pb = Problem {
        pairs: topology.member_nodes(),
        rest,
        ea,
        nb: topology.bars.len(),
        fixed,
    };
    relax(&pb, x, settings)
}

fn relax(
    pb: &Problem,
    mut x: Vec<Vector3<f64>>,
    settings: &Settings,
) -> Result<(Vec<Vector3<f64>>, Vec<f64>, usize)> {
    let n = x.len();
    let mut v = vec![Vector3::zeros(); n];
    let mut s = pb.state(&x);
    let mut mass = pb.masses(&s, n);
    let mut ke_prev = 0.0;
    let mut fresh = true;
    let mut err = f64::INFINITY;
    for it in 0..settings.max_iterations {
        let tmax = s.tension.iter().fold(0.0f64, |a, t| a.max(t.abs()));
        let rmax = s.residual.iter().fold(0.0f64, |a, r| a.max(r.norm()));
        err = if tmax > 0.0 { rmax / tmax } else { 0.0 };
        if !err.is_finite() {
            break;
        }
        if err <= settings.tolerance {
            let q = s
                .tension
                .iter()
                .zip(&s.length)
                .map(|(t, l)| t / l)
                .collect();
            return Ok((x, q, it.max(1)));
        }
        let half = if fresh { 0.5 } else { 1.0 };
        for i in 0..n {
            if mass[i] > 0.0 && !pb.fixed[i] {
                v[i] += s.residual[i] * (half / mass[i]);
            }
        }
        let ke: f64 = v
            .iter()
            .zip(&mass)
            .map(|(vi, m)| m * vi.norm_squared())
            .sum();
        if !fresh && ke < ke_prev {
            // The peak lies between the last two positions: go back to it and restart.
            for i in 0..n {
                if mass[i] > 0.0 && !pb.fixed[i] {
                    // x* = x_{t+1} − 1.5 v + R/(2m) with x_{t+1} = x_t + v.
                    x[i] += s.residual[i] * (0.5 / mass[i]) - v[i] * 0.5;
                }
            }
            v.iter_mut().for_each(|vi| *vi = Vector3::zeros());
            s = pb.state(&x);
            mass = pb.masses(&s, n);
            ke_prev = 0.0;
            fresh = true;
            continue;
        }
        for i in 0..n {
            x[i] += v[i];
        }
        ke_prev = ke;
        fresh = false;
        s = pb.state(&x);
    }
    Err(FormFindError::NotConverged {
        method: "dr".into(),
        iterations: settings.max_iterations,
        residual: err,
    })
}
