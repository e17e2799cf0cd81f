//! IMEX: a fixed-step splitting for stiff ground contact. The smooth forces (strings,
//! gravity, loads, the rigid-bar inertia and joint terms) go with classic RK4; the penalty
//! contact (normal spring–damper, friction) goes with a linearly implicit ROS2 step on the
//! few contact nodes.
//!
//! **Splitting** (Strang, order 2). Write y' = f(y) = f_A(y) + f_B(y) with y = (x, v) and
//!
//! * f_A = (v, a(x, v; F_c = 0)): the rigid-bar dynamics N̈M + NK = W + ΩPᵀ of
//!   [`Model::rhs`](super::Model::rhs) without the ground's forces F_c;
//! * f_B = (0, P_C(x) F_c(x, v)): the ground's forces alone, where P_C(x) (3 n₁ × 3m) is the
//!   acceleration response of every class-1 node to a unit force on a coordinate of one of
//!   the m contact nodes (the rigid-bar dynamics with the joint multipliers Ω at x: linear in
//!   the force, one sparse solve with the Ω factorisation per response).
//!
//! One step of size h is B(h/2) ∘ A(h) ∘ B(h/2): A by one RK4 step of f_A (four evaluations;
//! f_A is not stiff: the explicit step is bound by the strings, ω_max h < 2.8), B by one ROS2
//! step (below), with the step's starting damping force held in A and taken out of B ("The
//! held force" below). The ground's *stiffness* (the position-only force F_c(x, 0): the normal
//! spring k δ and the stick law's anchor spring) stays in A, integrated by RK4 with the rest;
//! its *damping* (the normal damper c,
//! the tangential damper c_t, the regularised friction's viscous slope μ f_n / v_reg) is
//! what makes explicit steps tiny, and B treats it implicitly.
//!
//! **B: ROS2 on the contact.** In B the positions are frozen, so v' = P_C F_c(v_C) (F_c of the
//! contact velocities v_C only). ROS2 (Verwer, Spee, Blom & Hundsdorfer 1999; γ = 1 + 1/√2,
//! L-stable with the exact Jacobian, order 2 for any approximation W of it):
//!
//! W k₁ = f_B(v₀),   W k₂ = f_B(v₀ + τ k₁) − 2 k₁,   v₁ = v₀ + τ (3/2 k₁ + 1/2 k₂),
//!
//! W = I − γτ P̃_C K_v S_C, with K_v = ∂F_c/∂v_C block-diagonal per node
//! ([`ContactSystem::contact_damping`]) and P̃_C the response
//! columns, refreshed when the set of loaded contact nodes changes and at least every
//! [`REFRESH`] substeps (a W-method: a stale P̃ costs no order). W k = r reduces to the
//! 3m × 3m system (I − γτ P̃_CC K_v) k_C = r_C, then k = r + γτ P̃_C K_v k_C; each stage's
//! r = P_C F_c is one response of the stage's contact forces. So a step costs four smooth
//! right-hand sides plus, while a node touches, two Ω factorisations, four responses and two
//! 3m × 3m LUs. Of the six Ω factorisations this makes two are saved: A's first stage is at
//! the positions of the opening B, and the opening B finds Ω factored where the previous
//! step's closing B left it (the projection between them moves the bar directions by at most
//! 10⁻⁸ there), so such a step factors Ω four times.
//!
//! **Work of the contact** ([`super::Sample::contact_work`]). The sink of an explicit method
//! integrates the contact's non-conservative work from the forces and velocities at the step
//! ends; here that rule is wrong by O(1) wherever B changes a contact node's velocity within
//! the step (a damped node stops in a fraction of it), and a run's energy budget missed by
//! 2·10⁻² at every step size on the hopping n = 24 wheel. So the integrator counts the work
//! itself: B's is its exact change of kinetic energy (the positions are frozen, its velocity
//! change is a constrained response, the constraint forces do no work), split into normal and
//! tangential parts in the proportion of the stages' powers; A's (the held force F* below and
//! the tangential part of the position-only force F_c(x, 0), the stick law's anchor spring) is
//! RK4's own quadrature of its power over the four stages. The budget residual then measures
//! A's error alone (3·10⁻⁴ at 2.5·10⁻⁴ s, 8·10⁻³ at 5·10⁻⁴ s on that wheel).
//!
//! **The held force.** Where B is stiff (a contact node's damping rate c/m_node, or the
//! regularised friction's μ f_n/(v_reg m_node), far above 1/h) a node's motion is slaved to its
//! forces: its velocity is what the damper needs to balance them. A splitting whose A leaves
//! the damper out moves the node by h v + ½ h² F/m, overshooting that slaved motion by the
//! factor c h / (2m) in every step, and its error is first order in h however accurate A
//! and B are. So the split is shifted by a constant: with F* = F_c(x_n, v_n) − F_c(x_n, 0),
//! the velocity-dependent contact force at the step's start (zero off the ground), A
//! integrates f_A + P_C F* and B integrates P_C (F_c(x, v) − F_c(x, 0) − F*). The sum is
//! unchanged, so the scheme is consistent. A then moves a slaved node with its balancing
//! force, and B corrects only what changed within the step. Measured on the reference
//! wheel's first pivot (stick contact) at t = 0.3 s, against RK4 at 2.5·10⁻⁵ s: 6.6·10⁻⁷,
//! 4.1·10⁻⁶ and 1.4·10⁻⁵ m at h = 10⁻⁴, 2.5·10⁻⁴ and 5·10⁻⁴ s (second order), against 4.3·10⁻⁵,
//! 1.6·10⁻⁴ and 3.8·10⁻⁴ m without F*. On the default 50° run (penalty contact) the first
//! impact comes at 0.7405 s at 5·10⁻⁴ s, against RK4's 0.7404 s, where it had come at 0.805 s
//! without F*. Test: `dynamics_stick::imex_follows_the_slaved_creep_of_the_regularised_friction`
//! (the creep speed within 0.3 %; without F* it is 13 % too fast at 2.5·10⁻⁴ s).
//!
//! **The held force at a landing.** A node that touches at a step's start but did not at the
//! previous step's start has just landed: it still moves at its impact speed, so its F* would
//! be the damper's force at that speed, held over the whole of A (an impulse of about c h v,
//! several times the node's momentum on the default ground at 5·10⁻⁴ s), and the last B would
//! then let it go: a restitution the model does not have. Such a node holds no force for that
//! step (F* = 0), and B damps the landing implicitly; from the next step on it holds its F*.
//! The landing stays first order, like every fixed step's here (the node's damping time m/c is
//! not resolved). Test: `dynamics_stick::imex_damps_a_landing_on_an_overdamped_ground_without_a_held_impulse`
//! (deepest penetration of a dropped bar within 23 % and 41 % of RK4's at 2.5·10⁻⁴ and
//! 5·10⁻⁴ s, against 35 % and 60 % when the landing holds its F*). Retaking a landing step as
//! two, split at the interpolated touch-down, did not reduce the error on the reference wheel.
//!
//! **A limit: creep under regularised friction.** On the penalty ground a loaded node below
//! the regularisation velocity creeps (v = v_reg artanh(F_t / μ f_n)). The splitting resolves
//! that creep at steps up to about 5·10⁻⁵ s on the reference wheel (second order there); at
//! 10⁻⁴ s and above the creeping pivot chatters at 3–50 mm/s and the axle runs ahead by up to
//! 1.1·10⁻² m in 0.95 s at 5·10⁻⁴ s, while the budget closes. Solving B exactly (Newton on
//! an L-stable SDIRK) does not help: the error is the splitting's. For m v̇ = L − β v the
//! step maps the creep error by 1 − 2|z| R(z), z = −β h/(2m), R the stability function of
//! B: ROS2's R(z) → 0.828/|z| gives −0.657 in the stiff limit where the exact map gives 0, so
//! the error flips sign every step. The stick ground, whose anchor spring sits in A, has no
//! such creep. Measurements: docs/notes/ROLLING.md, "Work–precision on the default (penalty)
//! ground".
//!
//! **Detecting the chatter** ([`Integrator::contact_chatter`]). Nothing else flags the bias:
//! the budget closes and halving the step does not move it. So the integrator counts it. For
//! each contact node that touches the ground (h < 0) at a step's start and end, the step's
//! increment of its tangential velocity u_t = u − (n̂·u) n̂ is Δ = u_t(t + h) − u_t(t); when the
//! node also touched through the previous step, this is a *contact node-step*, and it
//! *chatters* when the two increments point against each other (Δ·Δ_prev < 0) and both exceed
//! [`CHATTER_RATIO`] (a quarter) of the node's largest tangential speed at the three step ends
//! (and [`CHATTER_FLOOR`]). In the linear model above the error e flips by −0.657 every step,
//! so the increments are −1.657 e and then 1.09 e, each larger than half the speed |v_s| + |e|
//! once the chatter is as large as the creep (the tanh law sustains it only then). Smooth
//! motion reverses its increment only at an extremum of the velocity, where both increments
//! are small against the speed. The test is relative to the node's own speed, not to g h: it
//! needs no scale from the model, and it does not change with the step. The fraction of
//! chattering node-steps above [`DriftLimits::contact_chatter`](super::DriftLimits::contact_chatter)
//! is a drift warning naming IMEX-ARK. Measured (docs/notes/ROLLING.md, "Detecting the split's
//! chatter"): 58 % of the node-steps at 5·10⁻⁴ s on the reference pivot, 3.4 % at 10⁻⁵ s where
//! the split has converged; the same count on IMEX-ARK's steps 0–1.5 %. Test:
//! `dynamics_chatter`.
//!
//! The bar constraints are kept as for RK4: the driver projects every accepted state back
//! onto the bar lengths and N P = D ([`super::SimulationSettings::project`]). The thesis ground
//! (whose reaction needs all contact nodes at once) stays in f_A.
//!
//! The method is written against [`ContactSystem`]: f_A is its
//! [`rhs_explicit`](ContactSystem::rhs_explicit), P_C its [`respond`](ContactSystem::respond),
//! F_c its [`contact_force`](ContactSystem::contact_force) (the model's side:
//! `contact_split.rs`). RK4's coefficients are [`RK4`]'s.

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::system::{vec3, ContactSystem};
use super::tableau::{Tableau, RK4};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use tensegrity_core::error::{CoreError, DynamicsError};

/// γ = 1 + 1/√2 of ROS2.
const GAMMA: f64 = 1.0 + std::f64::consts::FRAC_1_SQRT_2;

/// The coefficients of A's RK4 step.
const TAB: Tableau<4> = RK4;
/// 1/b₁ and b₂/b₁: A's update is y + (h/6)(k₁ + 2(k₂ + k₃) + k₄).
const WEIGHT_DIVISOR: f64 = 1.0 / TAB.b[0];
/// b₂/b₁.
const MIDDLE_WEIGHT: f64 = TAB.b[1] / TAB.b[0];
const _: () = assert!(WEIGHT_DIVISOR == 6.0 && MIDDLE_WEIGHT == 2.0);

/// Contact substeps after which the response columns P̃_C are recomputed even if the set of
/// loaded contact nodes did not change.
pub const REFRESH: u32 = 8;

/// The IMEX stepper (module docs).
#[derive(Debug, Clone)]
pub struct Imex {
    k: [Vec<f64>; 4],
    tmp: Vec<f64>,
    /// Loaded contact nodes of the substep: (contact index, class-1 node, ∂F/∂v).
    active: Vec<(usize, usize, Matrix3<f64>)>,
    /// Class-1 nodes of the cached columns.
    cached: Vec<usize>,
    /// Substeps since the columns were computed.
    age: u32,
    /// Response columns P̃_C (3m of length 3 n₁).
    cols: Vec<Vec<f64>>,
    /// P_C of the contact forces (`response.forces`) into `response.out`.
    response: Response,
    /// Per contact node: the velocity-dependent contact force at the step's start, held in A
    /// and taken out of B (module docs).
    frozen: Vec<Vector3<f64>>,
    /// Per contact node: whether it touched the ground at the previous step's start (a node
    /// that has just landed holds no force: module docs, "The held force at a landing").
    touched_before: Vec<bool>,
    stage: Vec<f64>,
    /// The chatter count's per-node memory (module docs, "Detecting the chatter").
    chatter: ChatterCount,
    /// Contact substeps taken and response-column refreshes (work counters).
    pub contact_substeps: u64,
    /// Times the response columns were recomputed.
    pub refreshes: u64,
}

impl Imex {
    /// Buffers for `system`.
    pub fn new<S: ContactSystem>(system: &S) -> Self {
        let n = system.state_len();
        Self {
            k: std::array::from_fn(|_| vec![0.0; n]),
            tmp: vec![0.0; n],
            active: Vec::new(),
            cached: Vec::new(),
            age: 0,
            cols: Vec::new(),
            response: Response::new(n / 6),
            frozen: Vec::new(),
            touched_before: vec![false; system.contact_points()],
            stage: Vec::new(),
            chatter: ChatterCount::default(),
            contact_substeps: 0,
            refreshes: 0,
        }
    }
}

/// Smallest ratio of a chattering velocity increment to the node's tangential speed (module
/// docs, "Detecting the chatter"). Smooth motion reverses its increment only at an extremum
/// of the velocity, where the increment is a small part of the speed (IMEX-ARK at 10⁻⁴ s on
/// the reference pivot: no reversal above 0.32 of the speed); the split's chatter about the
/// slaved creep swings by more than the creep itself (most of its reversals above 0.32 of the
/// speed, many above 1).
pub const CHATTER_RATIO: f64 = 0.25;

/// Smallest chattering velocity increment (m/s): a thousandth of the rolling model's
/// regularisation velocity (10⁻³ m/s) and far above round-off, so that a node at rest, whose
/// increments are round-off and reverse at random (the ratio test alone would count them),
/// is not counted.
pub const CHATTER_FLOOR: f64 = 1e-6;

/// The chatter count (module docs, "Detecting the chatter"): per contact node its tangential
/// velocity at the step's start and its previous step's increment.
#[derive(Debug, Default, Clone)]
struct ChatterCount {
    /// Per contact node: its tangential velocity at the step's start, `None` off the ground.
    start: Vec<Option<Vector3<f64>>>,
    /// Per contact node: the previous step's tangential increment and the larger tangential
    /// speed at its ends, `None` unless the node touched the ground at both.
    last: Vec<Option<(Vector3<f64>, f64)>>,
    /// Scratch: the tangential velocities at the step's end.
    end: Vec<Option<Vector3<f64>>>,
    /// Contact node-steps: a contact node touching the ground at three consecutive step ends
    /// (two increments to compare).
    node_steps: u64,
    /// Those whose increments chattered.
    chattering: u64,
}

impl ChatterCount {
    /// The tangential velocity of every contact node of `y` that touches the ground (`None`
    /// for one that does not) into `out`.
    fn tangential<S: ContactSystem>(system: &S, y: &[f64], out: &mut Vec<Option<Vector3<f64>>>) {
        let (x, v) = y.split_at(y.len() / 2);
        let normal = system.ground_normal();
        out.clear();
        out.extend((0..system.contact_points()).map(|k| {
            let c = system.contact_node(k);
            (system.ground_height(&vec3(x, c)) < 0.0).then(|| {
                let u = vec3(v, c);
                u - normal * normal.dot(&u)
            })
        }));
    }

    /// Takes note of the step's starting state `y`.
    fn begin<S: ContactSystem>(&mut self, system: &S, y: &[f64]) {
        Self::tangential(system, y, &mut self.start);
        self.last.resize(self.start.len(), None);
    }

    /// Counts the step that ended at `y` (module docs, "Detecting the chatter").
    fn end<S: ContactSystem>(&mut self, system: &S, y: &[f64]) {
        let mut end = std::mem::take(&mut self.end);
        Self::tangential(system, y, &mut end);
        for ((start, end), last) in self.start.iter().zip(&end).zip(&mut self.last) {
            let (Some(u0), Some(u1)) = (start, end) else {
                *last = None;
                continue;
            };
            let increment = u1 - u0;
            let speed = u0.norm().max(u1.norm());
            if let Some((previous, previous_speed)) = *last {
                self.node_steps += 1;
                // both increments large against the node's speed over the two steps: a
                // reversal at a smooth extremum has small increments on both sides of it
                let smaller = increment.norm().min(previous.norm());
                if increment.dot(&previous) < 0.0
                    && smaller > CHATTER_FLOOR
                    && smaller > CHATTER_RATIO * speed.max(previous_speed)
                {
                    self.chattering += 1;
                }
            }
            *last = Some((increment, speed));
        }
        self.end = end;
    }
}

/// The velocity-dependent part F_c(x, v) − F_c(x, 0) of contact point `k`'s force: what B
/// integrates (the rest is A's).
fn velocity_dependent<S: ContactSystem>(
    system: &S,
    ws: &S::Workspace,
    k: usize,
    x: &Vector3<f64>,
    v: &Vector3<f64>,
) -> Vector3<f64> {
    system.contact_force(ws, k, x, v) - system.contact_force(ws, k, x, &Vector3::zeros())
}

/// The constrained response P_C F of forces on contact nodes (module docs), with its
/// buffers; shared by [`Imex`] and [`ImexArk`](super::ImexArk).
#[derive(Debug, Clone)]
pub(super) struct Response {
    /// The forces per node, nonzero on the contact nodes only; [`Response::respond`] leaves
    /// the joint forces that keep N P = D added to them.
    pub(super) forces: Vec<Vector3<f64>>,
    /// The accelerations P_C F of every node (3 per node).
    pub(super) out: Vec<f64>,
}

impl Response {
    /// Buffers for `nodes` nodes.
    pub(super) fn new(nodes: usize) -> Self {
        Self {
            forces: vec![Vector3::zeros(); nodes],
            out: vec![0.0; 3 * nodes],
        }
    }

    /// `self.out` = P_C F: the accelerations of `self.forces` (on the contact nodes
    /// `touched`) at positions `x` and zero velocities ([`ContactSystem::respond`]; prepared
    /// at x).
    pub(super) fn respond<S: ContactSystem>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        x: &[f64],
        touched: &[usize],
    ) {
        system.respond(ws, x, &mut self.forces, touched, &mut self.out);
    }
}

impl Imex {
    /// The contact forces F_c at positions `x` and velocities `v` of the active nodes into
    /// `self.response.forces` (zero elsewhere).
    fn contact_forces<S: ContactSystem>(
        &mut self,
        system: &S,
        ws: &S::Workspace,
        x: &[f64],
        v: &[f64],
    ) {
        self.response.forces.fill(Vector3::zeros());
        for &(k, c, _) in &self.active {
            self.response.forces[c] =
                velocity_dependent(system, ws, k, &vec3(x, c), &vec3(v, c)) - self.frozen[k];
        }
    }

    /// The velocity-dependent contact forces F_c(x, v) − F_c(x, 0) of the state `y`, per
    /// contact node, into `self.frozen`: zero off the ground and for a node that was off it at
    /// the previous step's start.
    fn freeze<S: ContactSystem>(&mut self, system: &S, ws: &S::Workspace, y: &[f64]) {
        self.frozen.clear();
        let (x, v) = y.split_at(y.len() / 2);
        let m = system.contact_points();
        self.touched_before.resize(m, false);
        for k in 0..m {
            let c = system.contact_node(k);
            let xc = vec3(x, c);
            let touching = system.ground_height(&xc) < 0.0;
            // a node that has just landed still moves at its impact speed: holding its damping
            // force through A would act as a restitution
            let hold = touching && self.touched_before[k];
            self.touched_before[k] = touching;
            let f = if hold {
                velocity_dependent(system, ws, k, &xc, &vec3(v, c))
            } else {
                Vector3::zeros()
            };
            self.frozen.push(f);
        }
    }

    /// The power of `self.response.forces` at the active nodes' velocities `v`, split into its
    /// normal and tangential parts.
    fn split_power(&self, normal: &Vector3<f64>, v: &[f64]) -> (f64, f64) {
        self.active.iter().fold((0.0, 0.0), |(pn, pt), &(_, c, _)| {
            let (f, vc) = (self.response.forces[c], vec3(v, c));
            let fn_ = f.dot(normal);
            let along = fn_ * vc.dot(normal);
            (pn + along, pt + f.dot(&vc) - along)
        })
    }

    /// B(τ): the ROS2 contact substep on the velocities of `y` (module docs). Returns its
    /// work (normal, tangential): the exact change of kinetic energy (the positions are
    /// frozen), split in the proportion of the stages' normal and tangential powers.
    fn contact_substep<S: ContactSystem>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        y: &mut [f64],
        tau: f64,
    ) -> Result<(f64, f64), CoreError> {
        let n3 = y.len() / 2;
        let normal = system.ground_normal();
        self.active.clear();
        {
            let (x, v) = y.split_at(n3);
            for k in 0..system.contact_points() {
                let c = system.contact_node(k);
                let xc = vec3(x, c);
                if system.ground_height(&xc) < 0.0 || self.frozen[k] != Vector3::zeros() {
                    let kv = system.contact_damping(ws, k, &xc, &vec3(v, c));
                    self.active.push((k, c, kv));
                }
            }
        }
        if self.active.is_empty() {
            return Ok((0.0, 0.0));
        }
        self.contact_substeps += 1;
        let kinetic_before = system.kinetic_energy(y);
        let touched: Vec<usize> = self.active.iter().map(|a| a.1).collect();
        let x = y[..n3].to_vec();
        system.prepare_response(ws, &x)?;
        // the response columns P̃_C
        let m3 = 3 * touched.len();
        if touched != self.cached || self.age >= REFRESH {
            self.cols.resize_with(m3, Vec::new);
            for j in 0..m3 {
                self.response.forces.fill(Vector3::zeros());
                self.response.forces[touched[j / 3]][j % 3] = 1.0;
                self.response.respond(system, ws, &x, &touched);
                self.cols[j].clear();
                self.cols[j].extend_from_slice(&self.response.out);
            }
            self.cached.clone_from(&touched);
            self.age = 0;
            self.refreshes += 1;
        }
        self.age += 1;
        let gt = GAMMA * tau;
        let pcc = DMatrix::from_fn(m3, m3, |i, j| self.cols[j][3 * touched[i / 3] + i % 3]);
        let mut kv = DMatrix::zeros(m3, m3);
        for (i, a) in self.active.iter().enumerate() {
            kv.fixed_view_mut::<3, 3>(3 * i, 3 * i).copy_from(&a.2);
        }
        let w = DMatrix::identity(m3, m3) - &pcc * &kv * gt;
        let lu = w.lu();
        // stage 1: r = P_C F(v₀)
        let v0 = y[n3..].to_vec();
        self.contact_forces(system, ws, &x, &v0);
        let (n1, t1) = self.split_power(&normal, &v0);
        self.response.respond(system, ws, &x, &touched);
        let k1 = self.solve_stage(&lu, &kv, gt, &touched)?;
        // stage 2 at v₀ + τ k₁: r = P_C F(v₀ + τ k₁) − 2 k₁
        self.stage.clear();
        self.stage
            .extend(v0.iter().zip(&k1).map(|(a, b)| a + tau * b));
        let stage = std::mem::take(&mut self.stage);
        self.contact_forces(system, ws, &x, &stage);
        let (n2, t2) = self.split_power(&normal, &stage);
        self.stage = stage;
        self.response.respond(system, ws, &x, &touched);
        for (r, a) in self.response.out.iter_mut().zip(&k1) {
            *r -= 2.0 * a;
        }
        let k2 = self.solve_stage(&lu, &kv, gt, &touched)?;
        for ((o, a), b) in y[n3..].iter_mut().zip(&k1).zip(&k2) {
            *o += tau * (1.5 * a + 0.5 * b);
        }
        let work = system.kinetic_energy(y) - kinetic_before;
        let (wn, wt) = ((n1 + n2).abs(), (t1 + t2).abs());
        let normal_share = if wn + wt > 0.0 { wn / (wn + wt) } else { 1.0 };
        Ok((work * normal_share, work * (1.0 - normal_share)))
    }

    /// k = W⁻¹ r for r in `self.response.out` (module docs).
    fn solve_stage(
        &self,
        lu: &nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
        kv: &DMatrix<f64>,
        gt: f64,
        touched: &[usize],
    ) -> Result<Vec<f64>, CoreError> {
        let m3 = 3 * touched.len();
        let r_c = DVector::from_fn(m3, |i, _| self.response.out[3 * touched[i / 3] + i % 3]);
        let k_c = lu.solve(&r_c).ok_or(DynamicsError::Diverged {
            t: f64::NAN,
            what: "the implicit contact system is singular",
        })?;
        let z = kv * k_c * gt;
        let mut k = self.response.out.clone();
        for (j, col) in self.cols.iter().enumerate().take(m3) {
            let s = z[j];
            if s != 0.0 {
                for (o, p) in k.iter_mut().zip(col) {
                    *o += s * p;
                }
            }
        }
        Ok(k)
    }
}

impl<S: ContactSystem> Integrator<S> for Imex {
    fn boxed_clone(&self) -> Option<Box<dyn Integrator<S>>> {
        Some(Box::new(self.clone()))
    }

    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Imex
    }

    /// Advances `y` from `t` to `t + h` in place: B(h/2), RK4 on f_A, B(h/2).
    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        let split = system.splits_contact();
        let mut work = system.contact_work(ws).unwrap_or_default();
        self.frozen.clear();
        if split {
            self.chatter.begin(system, y);
            self.freeze(system, ws, y);
            let (wn, wt) = self.contact_substep(system, ws, y, 0.5 * h)?;
            work.0 += wn;
            work.1 += wt;
        }
        let (a, c) = (&TAB.a, &TAB.c);
        let mut power = [(0.0, 0.0); 4];
        let frozen = std::mem::take(&mut self.frozen);
        let mut k = std::mem::take(&mut self.k);
        let result = (|| {
            let n = y.len();
            power[0] = system.rhs_explicit(t, y, &mut k[0], ws, &frozen)?;
            for i in 0..n {
                self.tmp[i] = y[i] + a[1][0] * h * k[0][i];
            }
            power[1] = system.rhs_explicit(t + c[1] * h, &self.tmp, &mut k[1], ws, &frozen)?;
            for i in 0..n {
                self.tmp[i] = y[i] + a[2][1] * h * k[1][i];
            }
            power[2] = system.rhs_explicit(t + c[2] * h, &self.tmp, &mut k[2], ws, &frozen)?;
            for i in 0..n {
                self.tmp[i] = y[i] + a[3][2] * h * k[2][i];
            }
            power[3] = system.rhs_explicit(t + c[3] * h, &self.tmp, &mut k[3], ws, &frozen)?;
            let h6 = h / WEIGHT_DIVISOR;
            for i in 0..n {
                y[i] += h6 * (k[0][i] + MIDDLE_WEIGHT * (k[1][i] + k[2][i]) + k[3][i]);
            }
            Ok::<(), CoreError>(())
        })();
        self.k = k;
        self.frozen = frozen;
        result?;
        if split {
            // A's non-conservative contact work by RK4's own quadrature of its power
            let rk4 =
                |p: [f64; 4]| h / WEIGHT_DIVISOR * (p[0] + MIDDLE_WEIGHT * (p[1] + p[2]) + p[3]);
            work.0 += rk4(power.map(|p| p.0));
            work.1 += rk4(power.map(|p| p.1));
            let (wn, wt) = self.contact_substep(system, ws, y, 0.5 * h)?;
            work.0 += wn;
            work.1 += wt;
            system.set_contact_work(ws, work);
            self.chatter.end(system, y);
        }
        Ok(StepOutcome::fixed(h))
    }

    fn contact_chatter(&self) -> (u64, u64) {
        (self.chatter.node_steps, self.chatter.chattering)
    }
}
