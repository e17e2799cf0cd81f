//! The dynamics of an elastic model: every node a point mass (its own and the members'
//! share, [`crate::mass`]), every member an axial spring with an optional dashpot, the
//! supports held exactly (the state lives on the free coordinates q, x = x₀ + Q q):
//!
//! > M_r q̈ = Qᵀ (P + W − R(x) − D(x, ẋ)),
//!
//! P the scene's loads (acting from t = 0: a step load), W the weights m g, R the members'
//! resisting forces ([`crate::forces`]: t_k = EA_k (L_k − L₀,k)/L₀,k) and the elastic
//! supports' k d dᵀ u ([`crate::dofs::Spring`]), and D the dashpots,
//! which add c_k L̇_k to member k's tension (L̇_k = n_kᵀ(ẋ_j − ẋ_i)). A string carries
//! max(0, t) while longer than its rest length and nothing otherwise (slack), the same law
//! as the rigid-bar dynamics' strings. Bars are elastic here: their axial modes, of
//! frequency ω ≈ √(EA/(m L)) · (a few), are resolved by the explicit methods only below
//! their stability limit (RK4: h ω_max ≤ 2√2, refused above it with the limit named) and
//! stepped over by the implicit Newmark method ([`crate::newmark`]).
//!
//! The energy E = T + U − (P + W)ᵀ(x − x₀), T = ½ ẋᵀMẋ, U = Σ ½ EA (L − L₀)²/L₀ over the
//! taut members, plus the work the dashpots dissipated, is constant along the exact
//! solution; its largest relative change is the run's `energy_drift`.
//!
//! [`ElasticDynamics`] is a [`System`] for the explicit methods of `tensegrity-dynamics`
//! ([`Rk4`], [`Dopri5`]); [`ElasticDynamics::run`] drives one of them or Newmark and
//! returns the same [`SimulationResult`] as a rigid-bar run (its bar-length and constraint
//! drifts zero: nothing is constrained but the supports, which hold exactly).

use crate::dofs::Dofs;
use crate::error::Result;
use crate::forces::{member_states, MemberState};
use crate::mass::{MassSolver, Masses};
use crate::model::{ElasticModel, MemberKind};
use crate::PathError;
use nalgebra::{DVector, Vector3};
use tensegrity_core::error::{CoreError, DynamicsError, StepHint};
use tensegrity_core::structure::MemberId;
use tensegrity_dynamics::System;

/// RK4's stability limit on the imaginary axis, h ω ≤ 2√2, with a margin.
pub const RK4_STABILITY: f64 = 2.8;

/// An elastic model set up for its dynamics (module docs).
#[derive(Debug)]
pub struct ElasticDynamics {
    model: ElasticModel,
    dofs: Dofs,
    masses: Masses,
    solver: MassSolver,
    mass_triplets: Vec<(usize, usize, f64)>,
    damping: Vec<f64>,
    applied: Vec<Vector3<f64>>,
    v0: DVector<f64>,
    /// Each member's name in the scene (bar k or string k), for errors.
    pub(crate) member_ids: Vec<MemberId>,
}

/// The buffers of the right-hand side, and its count.
#[derive(Debug, Clone, Default)]
pub struct TransientWorkspace {
    x: Vec<Vector3<f64>>,
    v: Vec<Vector3<f64>>,
    f: Vec<Vector3<f64>>,
    /// Right-hand-side (force) evaluations so far.
    pub rhs_evals: u64,
}

/// The parts of the energy at a state (J).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Energy {
    /// T = ½ ẋᵀMẋ.
    pub kinetic: f64,
    /// U = Σ ½ EA (L − L₀)²/L₀ (taut members).
    pub strain: f64,
    /// −(P + W)ᵀ(x − x₀).
    pub load: f64,
}

impl Energy {
    /// T + U + the load's potential.
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.load
    }
}

impl ElasticDynamics {
    /// Sets up the dynamics of `model` (validated here) with `masses`, member dashpots
    /// `damping` (N s/m, one per member; empty: none), the gravity `g` (weights from the
    /// masses; the model's dead load is replaced by them) and the initial node velocities
    /// (empty: at rest; a velocity along a held direction is an error naming the node).
    pub fn new(
        model: ElasticModel,
        masses: Masses,
        damping: Vec<f64>,
        gravity: Option<Vector3<f64>>,
        velocities: &[Vector3<f64>],
    ) -> Result<Self> {
        let mut model = model.validated()?;
        if !model.drivers.rest_length_changes.is_empty() || !model.drivers.displacements.is_empty()
        {
            return Err(PathError::model(
                "drivers",
                "rest-length changes and support displacements drive a load path (`solve`), not a dynamic run",
            ));
        }
        model.drivers.dead_load.clear();
        let dofs = Dofs::of(&model)?;
        let masses = masses.checked(&model, &dofs)?;
        let n = model.nodes.len();
        if !damping.is_empty() && damping.len() != model.members.len() {
            return Err(PathError::model(
                "damping",
                format!(
                    "{} dashpots for {} members",
                    damping.len(),
                    model.members.len()
                ),
            ));
        }
        if let Some(k) = damping.iter().position(|c| !(c.is_finite() && *c >= 0.0)) {
            return Err(PathError::model(
                format!("member {k}"),
                format!("damping {}: give a finite value ≥ 0 (N s/m)", damping[k]),
            ));
        }
        let weights = match gravity {
            Some(g) => masses.weights(&model, g),
            None => vec![Vector3::zeros(); n],
        };
        let applied: Vec<Vector3<f64>> = model
            .load
            .iter()
            .zip(&weights)
            .map(|(p, w)| p + w)
            .collect();
        let v0 = initial_velocities(&dofs, velocities, n)?;
        let solver = MassSolver::new(&masses, &model, &dofs)?;
        let mass_triplets = masses.triplets(&model, &dofs);
        let (mut bars, mut strings) = (0, 0);
        let member_ids = model
            .members
            .iter()
            .map(|m| match m.kind {
                MemberKind::Bar => {
                    bars += 1;
                    MemberId::Bar(bars - 1)
                }
                MemberKind::String => {
                    strings += 1;
                    MemberId::String(strings - 1)
                }
            })
            .collect();
        Ok(Self {
            model,
            dofs,
            masses,
            solver,
            mass_triplets,
            damping,
            applied,
            v0,
            member_ids,
        })
    }

    /// The model (validated).
    pub fn model(&self) -> &ElasticModel {
        &self.model
    }

    /// The free coordinates.
    pub fn dofs(&self) -> &Dofs {
        &self.dofs
    }

    /// The masses.
    pub fn masses(&self) -> &Masses {
        &self.masses
    }

    /// The reduced mass matrix's triplets ([`Masses::triplets`]).
    pub fn mass_triplets(&self) -> &[(usize, usize, f64)] {
        &self.mass_triplets
    }

    /// The dashpot of member `k` (N s/m).
    pub fn damping(&self, k: usize) -> f64 {
        self.damping.get(k).copied().unwrap_or(0.0)
    }

    /// The number of free coordinates m (the state has 2m entries: q, then q̇).
    pub fn n_free(&self) -> usize {
        self.dofs.len()
    }

    /// The initial state: q = 0 and q̇ the free components of the initial velocities.
    pub fn initial_state(&self) -> Vec<f64> {
        let m = self.n_free();
        let mut y = vec![0.0; 2 * m];
        y[m..].copy_from_slice(self.v0.as_slice());
        y
    }

    /// The node positions x = x₀ + Q q of a state.
    pub fn nodes_of(&self, y: &[f64]) -> Vec<Vector3<f64>> {
        let mut x = self.model.nodes.clone();
        self.add_expanded(&y[..self.n_free()], &mut x);
        x
    }

    /// The node velocities ẋ = Q q̇ of a state.
    pub fn velocities_of(&self, y: &[f64]) -> Vec<Vector3<f64>> {
        let mut v = vec![Vector3::zeros(); self.model.nodes.len()];
        self.add_expanded(&y[self.n_free()..], &mut v);
        v
    }

    fn add_expanded(&self, q: &[f64], out: &mut [Vector3<f64>]) {
        for ((i, e), qb) in self.dofs.free.iter().zip(q) {
            out[*i] += e * *qb;
        }
    }

    /// The members' states at positions `x` with their tensions including the dashpots
    /// (velocities `v`; a string's total tension clipped at zero, module docs).
    pub fn member_states(&self, x: &[Vector3<f64>], v: &[Vector3<f64>]) -> Vec<MemberState> {
        let mut states = member_states(&self.model, x, 0.0);
        if !self.damping.is_empty() {
            for ((s, m), &c) in states
                .iter_mut()
                .zip(&self.model.members)
                .zip(&self.damping)
            {
                if c == 0.0 || s.slack {
                    continue;
                }
                let rate = s.direction.dot(&(v[m.nodes[1]] - v[m.nodes[0]]));
                s.tension += c * rate;
                if m.kind == MemberKind::String && s.tension < 0.0 {
                    s.tension = 0.0;
                }
            }
        }
        states
    }

    /// The net force on every node (applied minus resisting and dashpot forces) at (x, v),
    /// into `f`; an error names the member whose force is not finite.
    fn net_forces(
        &self,
        t: f64,
        x: &[Vector3<f64>],
        v: &[Vector3<f64>],
        f: &mut [Vector3<f64>],
    ) -> std::result::Result<(), CoreError> {
        f.copy_from_slice(&self.applied);
        for (k, (m, s)) in self
            .model
            .members
            .iter()
            .zip(self.member_states(x, v))
            .enumerate()
        {
            let pull = s.direction * s.tension;
            if !pull.iter().all(|c| c.is_finite()) {
                return Err(DynamicsError::NonFiniteState {
                    t,
                    member: self.member_ids[k],
                    hint: StepHint::Unknown,
                }
                .into());
            }
            f[m.nodes[0]] += pull;
            f[m.nodes[1]] -= pull;
        }
        // elastic supports: −k d dᵀ u at their nodes
        for spring in &self.dofs.springs {
            let u = x[spring.node] - self.model.nodes[spring.node];
            f[spring.node] += spring.direction * spring.force(&u, 0.0);
        }
        Ok(())
    }

    /// The reduced net force Qᵀ F at the state (q, q̇) (counted as one evaluation).
    pub fn reduced_forces(
        &self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        ws: &mut TransientWorkspace,
    ) -> std::result::Result<DVector<f64>, CoreError> {
        ws.rhs_evals += 1;
        self.fill(q, qd, ws);
        let (x, v, mut f) = (
            std::mem::take(&mut ws.x),
            std::mem::take(&mut ws.v),
            std::mem::take(&mut ws.f),
        );
        let result = self.net_forces(t, &x, &v, &mut f);
        let reduced = self.dofs.reduce(&f);
        (ws.x, ws.v, ws.f) = (x, v, f);
        result.map(|()| reduced)
    }

    fn fill(&self, q: &[f64], qd: &[f64], ws: &mut TransientWorkspace) {
        let n = self.model.nodes.len();
        ws.x.clone_from(&self.model.nodes);
        ws.v.clear();
        ws.v.resize(n, Vector3::zeros());
        ws.f.resize(n, Vector3::zeros());
        self.add_expanded(q, &mut ws.x);
        self.add_expanded(qd, &mut ws.v);
    }

    /// M_r a (reduced).
    pub fn mass_times(&self, a: &[f64]) -> DVector<f64> {
        let mut out = DVector::zeros(a.len());
        for &(r, c, v) in &self.mass_triplets {
            out[r] += v * a[c];
        }
        out
    }

    /// The energy's parts at a state (module docs).
    pub fn energy(&self, y: &[f64]) -> Energy {
        let (x, v) = (self.nodes_of(y), self.velocities_of(y));
        let strain = member_states(&self.model, &x, 0.0)
            .iter()
            .zip(&self.model.members)
            .filter(|(s, _)| !s.slack)
            .map(|(s, m)| {
                let e = s.length - s.rest_length;
                0.5 * m.ea * e * e / s.rest_length
            })
            .sum::<f64>()
            + self
                .dofs
                .springs
                .iter()
                .map(|sp| {
                    let u = sp.direction.dot(&(x[sp.node] - self.model.nodes[sp.node]));
                    0.5 * sp.stiffness * u * u
                })
                .sum::<f64>();
        let load = -x
            .iter()
            .zip(&self.model.nodes)
            .zip(&self.applied)
            .map(|((x, x0), p)| p.dot(&(x - x0)))
            .sum::<f64>();
        Energy {
            kinetic: self.masses.kinetic_energy(&self.model, &v),
            strain,
            load,
        }
    }

    /// The power the dashpots dissipate at a state, Σ c_k L̇_k² (W; a slack string's none).
    pub fn dissipation(&self, y: &[f64]) -> f64 {
        if self.damping.is_empty() {
            return 0.0;
        }
        let (x, v) = (self.nodes_of(y), self.velocities_of(y));
        let states = member_states(&self.model, &x, 0.0);
        let mut p = 0.0;
        for ((s, m), &c) in states.iter().zip(&self.model.members).zip(&self.damping) {
            if c > 0.0 && !s.slack {
                let rate = s.direction.dot(&(v[m.nodes[1]] - v[m.nodes[0]]));
                let t = s.tension + c * rate;
                // a string whose dashpot would push: clipped, it dissipates only what it
                // carries
                if m.kind == MemberKind::String && t < 0.0 {
                    p += -s.tension * rate;
                } else {
                    p += c * rate * rate;
                }
            }
        }
        p
    }

    /// Every member's tension at a state (N, bars then strings in the model's order),
    /// dashpots included.
    pub fn member_forces(&self, y: &[f64]) -> Vec<f64> {
        let (x, v) = (self.nodes_of(y), self.velocities_of(y));
        self.member_states(&x, &v)
            .iter()
            .map(|s| s.tension)
            .collect()
    }

    /// The highest angular frequency ω_max of the undamped model about the start (rad/s):
    /// √ of the largest eigenvalue of M_r⁻¹ K₀ (K₀ the tangent at the initial positions,
    /// every string counted taut so that a slack one tightening is covered). Bounded from
    /// above by Gershgorin's discs on the lumped masses for more than
    /// [`crate::factor::DENSE_MAX`] free coordinates.
    pub fn highest_frequency(&self) -> f64 {
        let mut states = member_states(&self.model, &self.model.nodes, 0.0);
        for s in &mut states {
            s.slack = false;
        }
        let k = crate::tangent::tangent_triplets(&self.model, &self.dofs, &states);
        let m = self.n_free();
        if m == 0 {
            return 0.0;
        }
        let lumped = self.masses.lumped(&self.model);
        if m > crate::factor::DENSE_MAX {
            let mut rows = vec![0.0; m];
            for &(r, _, v) in &k {
                rows[r] += v.abs();
            }
            // the consistent mass matrix's smallest eigenvalue is at least a third of the
            // lumped one's (its element blocks are (m/6)[[2,1],[1,2]], eigenvalues m/6, m/2)
            let factor = match self.masses.distribution {
                crate::mass::MassDistribution::Lumped => 1.0,
                crate::mass::MassDistribution::Consistent => 3.0,
            };
            return rows
                .iter()
                .enumerate()
                .map(|(b, r)| factor * r / lumped[self.dofs.free[b].0])
                .fold(0.0, f64::max)
                .sqrt();
        }
        let mut kd = nalgebra::DMatrix::<f64>::zeros(m, m);
        for (r, c, v) in k {
            kd[(r, c)] += v;
        }
        let mut md = nalgebra::DMatrix::<f64>::zeros(m, m);
        for &(r, c, v) in &self.mass_triplets {
            md[(r, c)] += v;
        }
        let Some(chol) = md.cholesky() else {
            return f64::INFINITY;
        };
        // L⁻¹ K L⁻ᵀ: symmetric, with the eigenvalues of M⁻¹K
        let l = chol.l();
        let Some(linv) = l.clone().try_inverse() else {
            return f64::INFINITY;
        };
        let a: nalgebra::DMatrix<f64> = &linv * kd * linv.transpose();
        let a = (&a + a.transpose()) * 0.5;
        a.symmetric_eigenvalues()
            .iter()
            .fold(0.0_f64, |w, &l| w.max(l))
            .sqrt()
    }
}

/// q̇₀ = Qᵀ v₀, refusing a velocity along a held direction.
fn initial_velocities(dofs: &Dofs, velocities: &[Vector3<f64>], n: usize) -> Result<DVector<f64>> {
    if velocities.is_empty() {
        return Ok(DVector::zeros(dofs.len()));
    }
    if velocities.len() != n {
        return Err(PathError::model(
            "velocities",
            format!("{} velocities for {n} nodes", velocities.len()),
        ));
    }
    for &(i, d) in &dofs.held {
        let along = d.dot(&velocities[i]);
        if along.abs() > 1e-12 * velocities[i].norm().max(f64::MIN_POSITIVE) && along != 0.0 {
            return Err(PathError::model(
                format!("node {i}"),
                format!("its initial velocity has {along:e} m/s along a held direction: a supported node starts at rest along its supports"),
            ));
        }
    }
    Ok(dofs.reduce(velocities))
}

impl System for ElasticDynamics {
    type Workspace = TransientWorkspace;

    fn state_len(&self) -> usize {
        2 * self.n_free()
    }

    fn rhs(
        &self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        ws: &mut TransientWorkspace,
    ) -> std::result::Result<(), CoreError> {
        let m = self.n_free();
        let (q, qd) = y.split_at(m);
        let f = self.reduced_forces(t, q, qd, ws)?;
        let (dq, dqd) = dy.split_at_mut(m);
        dq.copy_from_slice(qd);
        dqd.copy_from_slice(f.as_slice());
        self.solver.solve_in_place(dqd);
        Ok(())
    }
}
