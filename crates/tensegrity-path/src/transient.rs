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
//! taut members and Σ ½ k (L − L₀)² over the taut clusters ([`crate::clusters`]: one tension
//! along all the segments of a clustered string, its dashpot c L̇), plus the work the dashpots dissipated, is constant along the exact
//! solution; its largest relative change is the run's `energy_drift`.
//!
//! [`ElasticDynamics`] is a [`System`] for the explicit methods of `tensegrity-dynamics`
//! ([`Rk4`], [`Dopri5`]); [`ElasticDynamics::run`] drives one of them or Newmark and
//! returns the same [`SimulationResult`] as a rigid-bar run (its constraint drift zero:
//! the supports hold exactly; its bar-length drift that of the rigid bars, if any).
//!
//! Some bars may be rigid ([`ElasticDynamics::with_rigid_bars`], [`crate::rigid_bars`]): they
//! hold their length by a constraint force, their mass is consistent, and they have no axial
//! mode (no stiffness, no strain energy, no dashpot).

use crate::dofs::Dofs;
use crate::error::Result;
use crate::forces::{member_states, MemberState};
use crate::mass::{MassSolver, Masses};
use crate::model::{ElasticModel, MemberKind};
use crate::rigid_bars::RigidBars;
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
    rigid: Option<RigidBars>,
    /// The frictional clusters' segment rest lengths now ([`crate::clusters::slide`] after
    /// each step; one list per cluster, empty for a frictionless one); behind a lock, as the
    /// right-hand side only borrows the model, and reset at the start of every run.
    friction: std::sync::Mutex<Vec<Vec<f64>>>,
    /// The time tables that drive rest lengths and loads ([`crate::actuation`]).
    actuation: crate::actuation::ElasticActuation,
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
        if !model.drivers.rest_length_changes.is_empty()
            || !model.drivers.cluster_rest_length_changes.is_empty()
            || !model.drivers.displacements.is_empty()
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
        let friction = crate::clusters::friction_rest_lengths(&model);
        Ok(Self {
            model,
            dofs,
            masses,
            solver,
            mass_triplets,
            damping,
            applied,
            v0,
            friction: std::sync::Mutex::new(friction),
            actuation: Default::default(),
            member_ids,
            rigid: None,
        })
    }

    /// The same dynamics driven by the time tables of `actuation` ([`crate::actuation`]):
    /// strings' and clusters' rest lengths, extra node loads; checked against the model
    /// (errors name `actuation k`). A driven run has no energy check.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_path::actuation::{Driven, ElasticActuation, RestLengthTable};
    /// use tensegrity_path::{ElasticDynamics, ElasticMember, ElasticModel, MassDistribution,
    ///     Masses, MemberKind, Support};
    /// let string = ElasticMember { nodes: [0, 1], kind: MemberKind::String, ea: 100.0, rest_length: 1.0 };
    /// let model = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x()], members: vec![string],
    ///     clusters: Vec::new(), supports: vec![Support::pinned(0)],
    ///     load: vec![Vector3::zeros(); 2], drivers: Default::default() };
    /// let masses = Masses { members: vec![0.0], nodes: vec![0.0, 1.0],
    ///     distribution: MassDistribution::Lumped };
    /// let reel = ElasticActuation { rest_lengths: vec![RestLengthTable {
    ///     driven: Driven::Member(0), times: vec![0.0, 1.0], rest_lengths: vec![1.0, 0.5] }],
    ///     loads: vec![] };
    /// let d = ElasticDynamics::new(model, masses, vec![], None, &[]).unwrap()
    ///     .with_actuation(reel).unwrap();
    /// // at t = 0.5 the rest length is 0.75: t = EA (1 − 0.75)/0.75
    /// let f = d.member_forces_at(0.5, &d.initial_state());
    /// assert!((f[0] - 100.0 / 3.0).abs() < 1e-12);
    /// ```
    pub fn with_actuation(mut self, actuation: crate::actuation::ElasticActuation) -> Result<Self> {
        actuation.check(&self.model)?;
        self.actuation = actuation;
        Ok(self)
    }

    /// Whether time tables drive the run.
    pub fn is_actuated(&self) -> bool {
        !self.actuation.is_empty()
    }

    /// The same dynamics with the members `rigid` (bars, by their index in the model) rigid
    /// ([`crate::rigid_bars`]): each keeps the length between its nodes in the model (its
    /// rest length and EA are not read), its mass takes the consistent matrix whatever the
    /// distribution, and it may carry no dashpot. The initial velocities must keep the rigid
    /// bars' lengths (to 10⁻⁹ of the ends' speeds; then projected to round-off); errors name
    /// the bar.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_path::{ElasticDynamics, ElasticMember, ElasticModel, MassDistribution,
    ///     Masses, MemberKind};
    /// let bar = ElasticMember { nodes: [0, 1], kind: MemberKind::Bar, ea: 1.0, rest_length: 1.0 };
    /// let model = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x()], members: vec![bar],
    ///     clusters: Vec::new(),
    ///     supports: vec![], load: vec![Vector3::zeros(); 2], drivers: Default::default() };
    /// let masses = Masses { members: vec![1.0], nodes: vec![0.0; 2],
    ///     distribution: MassDistribution::Lumped };
    /// let spin = [Vector3::new(0.0, -1.0, 0.0), Vector3::new(0.0, 1.0, 0.0)];
    /// let d = ElasticDynamics::new(model, masses, vec![], None, &spin).unwrap()
    ///     .with_rigid_bars(&[0]).unwrap();
    /// // rotation about the centre at 2 rad/s with the rod's inertia m L²/12
    /// let e = d.energy(&d.initial_state());
    /// assert!((e.kinetic - 0.5 * (1.0 / 12.0) * 4.0).abs() < 1e-15);
    /// ```
    pub fn with_rigid_bars(mut self, rigid: &[usize]) -> Result<Self> {
        if rigid.is_empty() {
            return Ok(self);
        }
        let bars = RigidBars::new(&self.model, &self.dofs, rigid)?;
        for &k in rigid {
            let [i, j] = self.model.members[k].nodes;
            self.model.members[k].rest_length = (self.model.nodes[j] - self.model.nodes[i]).norm();
            if self.damping(k) != 0.0 {
                return Err(PathError::model(
                    self.member_name(k),
                    "a rigid bar has no dashpot (it does not stretch)",
                ));
            }
        }
        let consistent = self.consistent(&bars);
        self.mass_triplets = self
            .masses
            .triplets_mixed(&self.model, &self.dofs, &consistent);
        self.solver =
            MassSolver::from_triplets(self.dofs.len(), self.mass_triplets.clone(), false)?;
        let x = self.model.nodes.clone();
        let v = self.velocities_of(&self.initial_state());
        let rows = bars.rows(&self.model, &self.dofs, &x);
        for (row, &k) in rows.iter().zip(&bars.members) {
            let [i, j] = self.model.members[k].nodes;
            let rate = crate::rigid_bars::dot(row, self.v0.as_slice());
            let scale = (x[j] - x[i]).norm() * (v[i].norm() + v[j].norm());
            if rate.abs() > 1e-9 * scale {
                return Err(PathError::model(
                    self.member_name(k),
                    format!("a rigid bar whose initial velocities stretch it at {:e} m/s: give its two ends the same speed along it", rate / (x[j] - x[i]).norm()),
                ));
            }
        }
        let mut v0 = self.v0.clone();
        bars.project_velocities(&self.model, &self.dofs, &self.solver, &x, v0.as_mut_slice())
            .map_err(|e| PathError::model("rigid bars", e.to_string()))?;
        self.v0 = v0;
        self.rigid = Some(bars);
        Ok(self)
    }

    /// Whether each member takes the consistent mass matrix: the rigid bars always.
    fn consistent(&self, bars: &RigidBars) -> Vec<bool> {
        let all = self.masses.distribution == crate::mass::MassDistribution::Consistent;
        bars.is_rigid.iter().map(|&r| r || all).collect()
    }

    /// `bar k` or `string k` (the member's name in the scene).
    fn member_name(&self, k: usize) -> String {
        self.member_ids[k].to_string()
    }

    /// The rigid bars, if any ([`ElasticDynamics::with_rigid_bars`]).
    pub fn rigid_bars(&self) -> Option<&RigidBars> {
        self.rigid.as_ref()
    }

    /// Whether member `k` is a rigid bar.
    pub fn is_rigid(&self, k: usize) -> bool {
        self.rigid.as_ref().is_some_and(|r| r.is_rigid[k])
    }

    /// The node positions x = x₀ + Q q of free coordinates `q`.
    pub fn positions(&self, q: &[f64]) -> Vec<Vector3<f64>> {
        let mut x = self.model.nodes.clone();
        self.add_expanded(q, &mut x);
        x
    }

    /// Projects a state onto the rigid bars' lengths and G q̇ = 0 (nothing without rigid
    /// bars; [`RigidBars::project`]); whether it changed the state. `t`: its time, for the
    /// error of a projection that does not converge.
    pub fn project(&self, t: f64, y: &mut [f64]) -> std::result::Result<bool, CoreError> {
        let Some(bars) = self.rigid.as_ref().filter(|b| !b.is_empty()) else {
            return Ok(false);
        };
        let (q, qd) = y.split_at_mut(self.n_free());
        let converged = bars.project(
            &self.model,
            &self.dofs,
            &self.solver,
            |q| self.positions(q),
            q,
            qd,
        )?;
        if !converged {
            return Err(DynamicsError::Diverged {
                t,
                what: "the projection onto the rigid bars' lengths did not converge",
            }
            .into());
        }
        Ok(true)
    }

    /// Projects the velocities `qd` at free coordinates `q` onto G q̇ = 0 (nothing without
    /// rigid bars).
    pub fn project_velocities(
        &self,
        q: &[f64],
        qd: &mut [f64],
    ) -> std::result::Result<(), CoreError> {
        match &self.rigid {
            Some(bars) => bars.project_velocities(
                &self.model,
                &self.dofs,
                &self.solver,
                &self.positions(q),
                qd,
            ),
            None => Ok(()),
        }
    }

    /// The largest |‖x_j − x_i‖ − L_k| over the rigid bars at a state (m; 0 without one).
    pub fn bar_length_error(&self, y: &[f64]) -> f64 {
        let Some(bars) = &self.rigid else {
            return 0.0;
        };
        let x = self.positions(&y[..self.n_free()]);
        bars.members
            .iter()
            .zip(&bars.lengths)
            .map(|(&k, &l)| {
                let [i, j] = self.model.members[k].nodes;
                ((x[j] - x[i]).norm() - l).abs()
            })
            .fold(0.0, f64::max)
    }

    /// The rigid bars' multipliers μ at a state (the index-1 system of
    /// [`crate::rigid_bars`]; empty without rigid bars).
    pub fn multipliers(&self, y: &[f64]) -> std::result::Result<DVector<f64>, CoreError> {
        let Some(bars) = &self.rigid else {
            return Ok(DVector::zeros(0));
        };
        let m = self.n_free();
        let mut ws = TransientWorkspace::default();
        let f = self.reduced_forces(0.0, &y[..m], &y[m..], &mut ws)?;
        let rows = bars.rows(&self.model, &self.dofs, &ws.x);
        let bias = bars.bias(&self.model, &ws.v);
        let mut a = f.as_slice().to_vec();
        bars.accelerations(&self.solver, &rows, &bias, &mut a)
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

    /// The members' states at time `t` (the actuated rest lengths) and positions `x` without
    /// dashpots; a frictional cluster's segments at the rest lengths its material slides to
    /// at `x` from where it was at the last accepted step ([`crate::clusters::slide`]: the string is massless, so within a
    /// step the pulleys stick or slip at once, the force a continuous function of `x`).
    pub fn elastic_states(&self, t: f64, x: &[Vector3<f64>]) -> Vec<MemberState> {
        let mut states = member_states(&self.model, x, 0.0);
        self.actuation.apply(&self.model, t, &mut states);
        if self.model.has_friction() {
            let start = self.friction_rest_lengths();
            crate::clusters::apply_rest_lengths(&self.model, &mut states, &start);
            // a slide that fails (a rest length collapsing) leaves the pulleys stuck here;
            // the step's commit ([`Self::slide`]) reports it
            if let Ok(slid) = crate::clusters::slide(&self.model, &states, &start) {
                crate::clusters::apply_rest_lengths(&self.model, &mut states, &slid.rest);
            }
        }
        states
    }

    /// The frictional clusters' segment rest lengths now (one list per cluster, empty for a
    /// frictionless one).
    pub fn friction_rest_lengths(&self) -> Vec<Vec<f64>> {
        self.friction
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }

    /// Sets the frictional clusters' segment rest lengths (as [`Self::friction_rest_lengths`]
    /// gives them).
    pub fn set_friction_rest_lengths(&self, rest: Vec<Vec<f64>>) {
        *self.friction.lock().unwrap_or_else(|e| e.into_inner()) = rest;
    }

    /// Pulley friction at the end of an accepted step from the state `y0` to `y`: the
    /// material's slide there from the last step's rest lengths ([`crate::clusters::slide`])
    /// becomes the state the next step starts from. Returns the friction's work over the
    /// step, Σ_j ½ (|Δt_j(y0)| + |Δt_j(y)|) |f_j| (J: each pulley's tension difference,
    /// trapezoidal over the step, times the material f_j that passed over it), for the
    /// energy balance.
    pub fn slide(&self, y0: &[f64], y: &[f64]) -> Result<f64> {
        let start = self.friction_rest_lengths();
        let states_at = |y: &[f64]| {
            let mut states = member_states(&self.model, &self.nodes_of(y), 0.0);
            crate::clusters::apply_rest_lengths(&self.model, &mut states, &start);
            states
        };
        let before = states_at(y0);
        let mut states = states_at(y);
        let rest = crate::clusters::slide(&self.model, &states, &start)?.rest;
        crate::clusters::apply_rest_lengths(&self.model, &mut states, &rest);
        let mut work = 0.0;
        for (c, (new, old)) in rest.iter().zip(&start).enumerate() {
            let range = self.model.cluster_states(c);
            let (s0, s1) = (&before[range.clone()], &states[range]);
            // the flow over pulley j is the material segments 0..=j lost
            let mut flow = 0.0;
            for j in 0..new.len().saturating_sub(1) {
                flow += old[j] - new[j];
                let jump = |s: &[MemberState]| (s[j + 1].tension - s[j].tension).abs();
                work += 0.5 * (jump(s0) + jump(s1)) * flow.abs();
            }
        }
        self.set_friction_rest_lengths(rest);
        Ok(work)
    }

    /// The members' states at time `t` (the actuated rest lengths) and positions `x` with
    /// their tensions including the dashpots (velocities `v`; a string's total tension
    /// clipped at zero, module docs).
    pub fn member_states(
        &self,
        t: f64,
        x: &[Vector3<f64>],
        v: &[Vector3<f64>],
    ) -> Vec<MemberState> {
        let mut states = self.elastic_states(t, x);
        if let Some(bars) = &self.rigid {
            // a rigid bar acts through its constraint force alone
            for (s, &r) in states.iter_mut().zip(&bars.is_rigid) {
                if r {
                    s.tension = 0.0;
                    s.slack = true;
                }
            }
        }
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
        // a cluster's dashpot c L̇, the total clipped at zero, on all its (taut) segments
        for (c, cluster) in self.model.clusters.iter().enumerate() {
            let range = self.model.cluster_states(c);
            if cluster.damping == 0.0 || states[range.clone()].iter().all(|s| s.slack) {
                continue;
            }
            let rate = crate::clusters::cluster_rate(&self.model, c, &states, v);
            for s in states[range].iter_mut().filter(|s| !s.slack) {
                s.tension = (s.tension + cluster.damping * rate).max(0.0);
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
        self.actuation.add_loads(t, f);
        for (k, ([a, b], s)) in self
            .model
            .state_nodes()
            .zip(self.member_states(t, x, v))
            .enumerate()
        {
            let pull = s.direction * s.tension;
            if !pull.iter().all(|c| c.is_finite()) {
                return Err(match self.member_ids.get(k) {
                    Some(&member) => DynamicsError::NonFiniteState {
                        t,
                        member,
                        hint: StepHint::Unknown,
                    },
                    None => DynamicsError::Diverged {
                        t,
                        what: "a clustered string's tension is not finite",
                    },
                }
                .into());
            }
            f[a] += pull;
            f[b] -= pull;
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

    /// The energy's parts at a state (module docs), the actuation tables at t = 0
    /// ([`Self::energy_at`]).
    pub fn energy(&self, y: &[f64]) -> Energy {
        self.energy_at(0.0, y)
    }

    /// The energy's parts at time `t` (the actuated rest lengths; a driven cluster's strain
    /// energy with its rest length in the model) and state `y`.
    pub fn energy_at(&self, t: f64, y: &[f64]) -> Energy {
        let (x, v) = (self.nodes_of(y), self.velocities_of(y));
        let states = self.elastic_states(t, &x);
        let strain = states
            .iter()
            .zip(&self.model.members)
            .enumerate()
            .filter(|(k, (s, _))| !s.slack && !self.is_rigid(*k))
            .map(|(_, (s, m))| {
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
                .sum::<f64>()
            + crate::clusters::strain_energy(&self.model, &states);
        let load = -x
            .iter()
            .zip(&self.model.nodes)
            .zip(&self.applied)
            .map(|((x, x0), p)| p.dot(&(x - x0)))
            .sum::<f64>();
        let kinetic = match &self.rigid {
            Some(bars) => self
                .masses
                .kinetic_energy_mixed(&self.model, &v, &self.consistent(bars)),
            None => self.masses.kinetic_energy(&self.model, &v),
        };
        Energy {
            kinetic,
            strain,
            load,
        }
    }

    /// The power the dashpots dissipate at a state, Σ c_k L̇_k² (W; a slack string's none),
    /// the clusters' c L̇² included; the actuation tables at t = 0
    /// ([`Self::dissipation_at`]).
    pub fn dissipation(&self, y: &[f64]) -> f64 {
        self.dissipation_at(0.0, y)
    }

    /// [`Self::dissipation`] at time `t` (the actuated rest lengths).
    pub fn dissipation_at(&self, t: f64, y: &[f64]) -> f64 {
        let clustered = self.model.clusters.iter().any(|c| c.damping > 0.0);
        if self.damping.is_empty() && !clustered {
            return 0.0;
        }
        let (x, v) = (self.nodes_of(y), self.velocities_of(y));
        let states = self.elastic_states(t, &x);
        let mut p = 0.0;
        for (c, cluster) in self.model.clusters.iter().enumerate() {
            if cluster.damping == 0.0 {
                continue;
            }
            // the dashpot's added tension on each taut segment (clipped where the total
            // would push) times the segment's rate: c L̇² on frictionless pulleys
            let rate = crate::clusters::cluster_rate(&self.model, c, &states, &v);
            for ([a, b], s) in cluster
                .segments()
                .zip(&states[self.model.cluster_states(c)])
            {
                if !s.slack {
                    let added = (s.tension + cluster.damping * rate).max(0.0) - s.tension;
                    p += added * s.direction.dot(&(v[b] - v[a]));
                }
            }
        }
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

    /// Every member's tension at a state (N, bars then strings in the model's order, then
    /// one per cluster: [`crate::clusters`]), dashpots included; a rigid bar's −μ L from its
    /// constraint force (NaN where the constraint system cannot be solved); the actuation
    /// tables at t = 0 ([`Self::member_forces_at`]).
    pub fn member_forces(&self, y: &[f64]) -> Vec<f64> {
        self.member_forces_at(0.0, y)
    }

    /// [`Self::member_forces`] at time `t` (the actuated rest lengths).
    pub fn member_forces_at(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let (x, v) = (self.nodes_of(y), self.velocities_of(y));
        let tensions: Vec<f64> = self
            .member_states(t, &x, &v)
            .iter()
            .map(|s| s.tension)
            .collect();
        let mut forces = self.model.reported_tensions(&tensions);
        if let Some(bars) = &self.rigid {
            match self.multipliers(y) {
                Ok(mu) => {
                    for (k, t) in bars.tensions(&self.model, &x, &mu) {
                        forces[k] = t;
                    }
                }
                Err(_) => bars.members.iter().for_each(|&k| forces[k] = f64::NAN),
            }
        }
        forces
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
        // a rigid bar: no axial stiffness, its geometric one (t/L)(I − n nᵀ) at its start
        let mut model = std::borrow::Cow::Borrowed(&self.model);
        if let Some(bars) = &self.rigid {
            let model = model.to_mut();
            for (m, &r) in model.members.iter_mut().zip(&bars.is_rigid) {
                if r {
                    m.ea = 0.0;
                }
            }
            let y = self.initial_state();
            let forces = self.member_forces(&y);
            for (k, s) in states.iter_mut().enumerate().take(bars.is_rigid.len()) {
                if bars.is_rigid[k] {
                    s.tension = if forces[k].is_finite() {
                        forces[k]
                    } else {
                        0.0
                    };
                }
            }
        }
        let k = crate::tangent::tangent_triplets(&model, &self.dofs, &states);
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
        match &self.rigid {
            Some(bars) => {
                let rows = bars.rows(&self.model, &self.dofs, &ws.x);
                let bias = bars.bias(&self.model, &ws.v);
                bars.accelerations(&self.solver, &rows, &bias, dqd)?;
            }
            None => self.solver.solve_in_place(dqd),
        }
        Ok(())
    }
}
