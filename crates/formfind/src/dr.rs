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
//! are reset to zero and the masses recomputed. It starts from the topology's nodes, stops
//! when max_i ‖R_i‖ ≤ τ · max_k |T_k| and fails with [`FormFindError::NotConverged`] after
//! `max_iterations` steps. The force densities reported are T_k / L_k.
//!
//! A clustered string (the `cluster` module) acts on every segment with its prescribed
//! tension t_c: T = t_c whatever the length, its geometric stiffness t_c / l_i in the masses
//! and no axial term; its segments' force densities are reported as t_c / l_i.
//!
//! **The tolerance τ** is the one asked for ([`crate::Settings::tolerance`]) or, when that is
//! below what double precision can reach, the floor
//!
//! τ = max(tolerance, [`PRECISION_FLOOR`] · ε · max_k EA_k / max_k |T_k|)
//!
//! (ε the machine epsilon, T at the current step). A member's force T = EA (L − s0)/s0 is
//! the difference of two lengths times EA/s0, so it carries a rounding error of about ε EA,
//! and the residual, a sum of such forces, cannot fall below a few ε · max EA: relative to
//! the tensions that is ε · EA/T, 4·10⁻¹⁰ for rods of EA/T ≈ 2·10⁶ — far above the default
//! 10⁻¹². Stopping there costs nothing real: the nodes are then within about ε · (size) of
//! the equilibrium. The result reports the τ it stopped at ([`crate::FormFound::tolerance`]),
//! and so does the error of a run that does not converge.
//!
//! Stiffnesses so large that the forces would overflow (EA/s0 · L summed over the members
//! beyond the largest double) are refused before the first step, naming the member and its
//! stiffness.

use crate::error::{FormFindError, Result};
use crate::method::Settings;
use crate::topology::Topology;
use nalgebra::Vector3;
use tensegrity_core::request::InvalidParameter;

/// The factor c of the precision floor of the tolerance, c · ε · max EA / max |T| (module
/// docs): the residual of a node sums a few members' forces, each rounded to about ε EA.
pub const PRECISION_FLOOR: f64 = 8.0;

/// A found form of dynamic relaxation: nodes, force densities, steps and the tolerance it
/// stopped at.
pub(crate) type Relaxed = (Vec<Vector3<f64>>, Vec<f64>, usize, f64);

/// Member forces and nodal residuals at `x`.
struct State {
    tension: Vec<f64>,
    length: Vec<f64>,
    residual: Vec<Vector3<f64>>,
}

struct Problem {
    /// Members, then the clusters' segments.
    pairs: Vec<[usize; 2]>,
    rest: Vec<f64>,
    ea: Vec<f64>,
    nb: usize,
    /// The number of members: the elements past it are segments of constant tension.
    nm: usize,
    /// The tension of every segment (N).
    segment_tension: Vec<f64>,
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
            let t = if k >= self.nm {
                self.segment_tension[k - self.nm]
            } else if k >= self.nb {
                (self.ea[k] * (l - self.rest[k]) / self.rest[k]).max(0.0)
            } else {
                self.ea[k] * (l - self.rest[k]) / self.rest[k]
            };
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

/// Runs dynamic relaxation: nodes, force densities, iterations, the tolerance reached.
pub(crate) fn run(topology: &Topology, settings: &Settings) -> Result<Relaxed> {
    let mut x = topology
        .initial_nodes()
        .ok_or_else(|| FormFindError::InvalidTopology {
            item: "nodes".into(),
            reason: "dynamic relaxation (the method that uses the members' lengths) starts \
                     from the topology's nodes: give them"
                .into(),
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
    let mut ea: Vec<f64> = topology
        .members()
        .map(|m| m.stiffness.unwrap_or(settings.stiffness))
        .collect();
    // a segment of a cluster: a constant force (no axial stiffness, no rest length)
    let mut rest = rest;
    rest.resize(topology.n_members() + topology.n_segments(), 1.0);
    ea.resize(rest.len(), 0.0);
    let mut fixed = vec![false; topology.n_nodes];
    for f in &topology.fixed {
        fixed[f.node] = true;
        x[f.node] = Vector3::from(f.position);
    }
    let pb = Problem {
        pairs: topology.force_pairs(),
        rest,
        ea,
        nb: topology.bars.len(),
        nm: topology.n_members(),
        segment_tension: topology.segment_tensions(),
        fixed,
    };
    check_overflow(topology, &pb, &x, settings)?;
    relax(&pb, x, settings)
}

/// Refuses a member whose stiffness would overflow the forces (module docs): EA/s0 · (L + s0)
/// times the number of members (a bound of a node's sum) must stay finite.
fn check_overflow(
    topology: &Topology,
    pb: &Problem,
    x: &[Vector3<f64>],
    settings: &Settings,
) -> Result<()> {
    let m = pb.pairs.len() as f64;
    for (k, &[i, j]) in pb.pairs.iter().enumerate() {
        let l = (x[j] - x[i]).norm();
        let bound = pb.ea[k] / pb.rest[k] * (l + pb.rest[k]) * m;
        if bound.is_finite() {
            continue;
        }
        let name = topology.member_name(k);
        let reason = format!(
            "{name}'s force EA (L − s0)/s0 (rest length {:e} m) would overflow: lower the \
             stiffness",
            pb.rest[k]
        );
        return Err(
            match topology.members().nth(k).and_then(|mk| mk.stiffness) {
                Some(own) => FormFindError::InvalidTopology {
                    item: format!("{name}.stiffness"),
                    reason: format!("{own:e} N: {reason}"),
                },
                None => InvalidParameter::new("stiffness", settings.stiffness, reason).into(),
            },
        );
    }
    Ok(())
}

/// The tolerance of a step (module docs): the one asked for, or the precision floor at the
/// largest stiffness `ea_max` and tension `t_max`.
fn effective_tolerance(tolerance: f64, ea_max: f64, t_max: f64) -> f64 {
    if t_max > 0.0 {
        tolerance.max(PRECISION_FLOOR * f64::EPSILON * ea_max / t_max)
    } else {
        tolerance
    }
}

fn relax(pb: &Problem, mut x: Vec<Vector3<f64>>, settings: &Settings) -> Result<Relaxed> {
    let n = x.len();
    let ea_max = pb.ea.iter().fold(0.0f64, |a, &e| a.max(e));
    let mut tol = settings.tolerance;
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
            return Err(FormFindError::NonFinite {
                method: "dr".into(),
                item: format!("the residual at step {it}"),
            });
        }
        tol = effective_tolerance(settings.tolerance, ea_max, tmax);
        if err <= tol {
            let q = s
                .tension
                .iter()
                .zip(&s.length)
                .map(|(t, l)| t / l)
                .collect();
            return Ok((x, q, it.max(1), tol));
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
        tolerance: tol,
    })
}

#[cfg(test)]
mod tests {
    use super::PRECISION_FLOOR;
    use crate::{builtin, form_find, rest_lengths, Method, Settings, Synthesis};

    /// The 3-bar prism of the force density method, its rest lengths at a prestress of 100 N
    /// with every member's EA = 2·10⁸ N (EA/T ≈ 2·10⁶: rods, as in a rolling robot), relaxed
    /// from a start perturbed by 1 % on the default settings: the residual cannot reach the
    /// default 10⁻¹² at that stiffness ratio, the precision floor stops it, and the form is
    /// the force density method's.
    #[test]
    fn stiff_rods_converge_on_the_defaults_at_the_precision_floor() {
        let t = builtin("prism:3").unwrap();
        let fdm = Settings {
            method: Method::Fdm,
            ..Settings::default()
        };
        let found = form_find(&t, &fdm).unwrap();
        let (prestress, ea) = (100.0, 2e8);
        let syn = Synthesis {
            prestress,
            stiffness: ea,
            bar_mass: 1.0,
        };
        let r = rest_lengths(&t, &found, &syn).unwrap();
        let mut stiff = t.with_lengths(&r.rest_length, &r.stiffness);
        let start = found.nodes.iter().enumerate();
        let wobble = |i: usize, k: usize| 0.01 * ((i * 7 + k * 13) as f64 * 0.37).sin();
        let start =
            start.map(|(i, p)| [p.x + wobble(i, 0), p.y + wobble(i, 1), p.z + wobble(i, 2)]);
        stiff.nodes = Some(start.collect());
        let dr = Settings {
            method: Method::Dr,
            ..Settings::default()
        };
        let relaxed = form_find(&stiff, &dr).unwrap();
        assert_eq!(relaxed.method, Method::Dr);
        // the floor c ε EA / max |T| (the bars' compression, to the strain 10⁻⁶)
        let t_max = r.tension.iter().fold(0.0f64, |a, t| a.max(t.abs()));
        let floor = PRECISION_FLOOR * f64::EPSILON * ea / t_max;
        let tol = relaxed.tolerance.unwrap();
        assert!(
            (tol / floor - 1.0).abs() < 1e-5,
            "{tol:e} against {floor:e}"
        );
        assert!(tol > dr.tolerance);
        // every member at the length and tension of the force density form
        for (k, &[i, j]) in t.member_nodes().iter().enumerate() {
            let l = |x: &[nalgebra::Vector3<f64>]| (x[j] - x[i]).norm();
            let (l_fdm, l_dr) = (l(&found.nodes), l(&relaxed.nodes));
            assert!(
                (l_dr - l_fdm).abs() < 1e-9 * l_fdm,
                "member {k}: {l_dr} vs {l_fdm}"
            );
            let tension = relaxed.force_density[k] * l_dr;
            assert!(
                (tension - r.tension[k]).abs() < 1e-5 * prestress,
                "member {k}: {tension} vs {}",
                r.tension[k]
            );
        }
    }

    #[test]
    fn a_stiffness_that_overflows_the_forces_is_refused_by_name() {
        let t = builtin("prism:3").unwrap();
        let found = form_find(&t, &Settings::default()).unwrap();
        let syn = Synthesis::default();
        let r = rest_lengths(&t, &found, &syn).unwrap();
        let mut dr = t.with_lengths(&r.rest_length, &vec![1e307; t.n_members()]);
        dr.nodes = Some(found.node_rows());
        let settings = Settings {
            method: Method::Dr,
            ..Settings::default()
        };
        let e = form_find(&dr, &settings).unwrap_err().to_string();
        assert!(
            e.starts_with("bars[0].stiffness: 1e307 N: bars[0]'s force")
                && e.contains("would overflow"),
            "{e}"
        );
    }
}
