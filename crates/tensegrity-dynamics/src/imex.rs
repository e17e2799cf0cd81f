//! IMEX: a fixed-step splitting for stiff ground contact. The smooth forces (strings,
//! gravity, loads, the rigid-bar inertia and joint terms) go with classic RK4; the penalty
//! contact (normal spring–damper, friction) goes with a linearly implicit ROS2 step on the
//! few contact nodes.
//!
//! **Splitting** (Strang, order 2). Write y' = f(y) = f_A(y) + f_B(y) with y = (x, v) and
//!
//! * f_A = (v, a(x, v; F_c = 0)): the rigid-bar dynamics N̈M + NK = W + ΩPᵀ of [`Model::rhs`]
//!   without the ground's forces F_c;
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
//! ([`Ground::contact_jacobian`](super::Ground::contact_jacobian)) and P̃_C the response
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
//! The bar constraints are kept as for RK4: the driver projects every accepted state back
//! onto the bar lengths and N P = D ([`super::SimulationSettings::project`]). The thesis ground
//! (whose reaction needs all contact nodes at once) stays in f_A.

use super::forces::{Ground, GroundModel};
use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::model::{vec3, BarTerms, Model, Workspace};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use tensegrity_core::error::{CoreError, DynamicsError, StepHint};
use tensegrity_core::structure::MemberId;

/// γ = 1 + 1/√2 of ROS2.
const GAMMA: f64 = 1.0 + std::f64::consts::FRAC_1_SQRT_2;

/// Contact substeps after which the response columns P̃_C are recomputed even if the set of
/// loaded contact nodes did not change.
pub const REFRESH: u32 = 8;

/// The IMEX stepper (module docs).
#[derive(Debug)]
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
    /// Joint multipliers of A's right-hand sides.
    multipliers: Vec<f64>,
    stage: Vec<f64>,
    /// Contact substeps taken and response-column refreshes (work counters).
    pub contact_substeps: u64,
    /// Times the response columns were recomputed.
    pub refreshes: u64,
}

impl Imex {
    /// Buffers for `model`.
    pub fn new(model: &Model) -> Self {
        let n = model.state_len();
        Self {
            k: std::array::from_fn(|_| vec![0.0; n]),
            tmp: vec![0.0; n],
            active: Vec::new(),
            cached: Vec::new(),
            age: 0,
            cols: Vec::new(),
            response: Response::new(model),
            frozen: Vec::new(),
            touched_before: vec![false; model.contact.len()],
            multipliers: vec![0.0; model.linear_rows.len()],
            stage: Vec::new(),
            contact_substeps: 0,
            refreshes: 0,
        }
    }
}

/// Whether the ground's forces are split off into B (penalty and stick grounds).
pub(super) fn splits(model: &Model) -> bool {
    model.ground.as_ref().is_some_and(|g| {
        matches!(
            g.model,
            GroundModel::Penalty { .. } | GroundModel::Stick { .. }
        )
    })
}

/// f_A: [`Model::rhs`] without the ground's forces (when they are split off), plus the held
/// force `frozen` (per contact node). Returns the power (normal, tangential) of A's
/// non-conservative contact forces: the held force and the tangential part of the
/// position-only force F_c(x, 0) (the stick law's anchor spring; zero for the penalty law),
/// whose normal part k δ is the ground spring of the energy budget.
pub(super) fn rhs_smooth(
    model: &Model,
    t: f64,
    y: &[f64],
    dy: &mut [f64],
    ws: &mut Workspace,
    multipliers: &mut [f64],
    frozen: &[Vector3<f64>],
) -> Result<(f64, f64), CoreError> {
    if !splits(model) {
        model.rhs(t, y, dy, ws)?;
        return Ok((0.0, 0.0));
    }
    ws.rhs_evals += 1;
    let n3 = 3 * model.n1;
    let (x, v) = y.split_at(n3);
    let (dx, dv) = dy.split_at_mut(n3);
    dx.copy_from_slice(v);
    model.applied_forces(t, x, v, ws);
    let (mut normal_power, mut tangential_power) = (0.0, 0.0);
    if let Some(g) = &model.ground {
        for (k, &(_, c)) in model.contact.iter().enumerate() {
            let spring = g.stick_force(&vec3(x, c), &Vector3::zeros(), ws.anchors[k].as_ref());
            let held = frozen.get(k).copied().unwrap_or_default();
            ws.f[c] += spring - ws.contact_f[k] + held;
            if spring != Vector3::zeros() || held != Vector3::zeros() {
                let vc = vec3(v, c);
                // the spring's normal part k δ is the budget's ground spring
                let non_conservative = spring - g.normal * spring.dot(&g.normal) + held;
                let along = non_conservative.dot(&g.normal) * vc.dot(&g.normal);
                normal_power += along;
                tangential_power += non_conservative.dot(&vc) - along;
            }
        }
    }
    if let Some(i) = ws.f.iter().position(|f| !f.iter().all(|c| c.is_finite())) {
        return Err(DynamicsError::NonFiniteState {
            t,
            member: MemberId::Bar(i / 2),
            hint: StepHint::Unknown,
        }
        .into());
    }
    bar_accelerations(model, x, v, &ws.f, dv, None);
    if ws.omega.is_some() {
        // the first stage sits where the opening contact substep factored Ω
        factor_omega_unless_current(model, x, ws)?;
        constrain(model, ws, multipliers, dv);
        bar_accelerations(model, x, v, &ws.f, dv, Some(&model.constrained_bars));
    }
    Ok((normal_power, tangential_power))
}

/// The velocity-dependent part F_c(x, v) − F_c(x, 0) of a contact node's force: what B
/// integrates (the rest is A's).
pub(super) fn velocity_dependent(
    g: &Ground,
    x: &Vector3<f64>,
    v: &Vector3<f64>,
    anchor: Option<&super::anchor::Anchor>,
) -> Vector3<f64> {
    g.stick_force(x, v, anchor) - g.stick_force(x, &Vector3::zeros(), anchor)
}

/// Refactors Ω at positions `x` unless it is factored at bar directions within
/// [`OMEGA_REUSE`] of those of `x`. Ω depends on the positions only through the bar directions
/// b̂, and two evaluations of a step share them: the contact substep that opens a step sits
/// where the one that closed the previous step was (moved only by the driver's projection onto
/// the bar constraints), and A's first stage where the opening substep was (B moves no node).
pub(super) fn factor_omega_unless_current(
    model: &Model,
    x: &[f64],
    ws: &mut Workspace,
) -> Result<(), CoreError> {
    if let Some(om) = ws.omega.as_ref() {
        let current = om.is_factored()
            && ws.bhat.iter().enumerate().all(|(k, bh)| {
                let b = vec3(x, 2 * k + 1) - vec3(x, 2 * k);
                (b * (1.0 / b.norm()) - bh).amax() <= OMEGA_REUSE
            });
        if current {
            return Ok(());
        }
    }
    factor_omega(model, x, ws)
}

/// Largest change of a bar direction's component at which a factored Ω is kept
/// ([`factor_omega_unless_current`]). On the hopping n = 24 wheel at 5·10⁻⁴ s the projection moves the directions by
/// 10⁻¹⁵ … 10⁻⁸ (the response's relative error, far below the step's), a step by 10⁻⁶ and more.
const OMEGA_REUSE: f64 = 1e-8;

/// Refactors Ω at positions `x`.
fn factor_omega(model: &Model, x: &[f64], ws: &mut Workspace) -> Result<(), CoreError> {
    let Workspace { omega, bhat, .. } = ws;
    let Some(om) = omega.as_mut() else {
        return Ok(());
    };
    for (k, bh) in bhat.iter_mut().enumerate() {
        let b = vec3(x, 2 * k + 1) - vec3(x, 2 * k);
        *bh = b * (1.0 / b.norm());
    }
    om.assemble_and_factor(bhat, &model.inv_mass)
}

/// Adds the joint forces Gᵀω that make the accelerations `dv` (of the forces `ws.f`) keep
/// N P = D (Ω factored).
fn constrain(model: &Model, ws: &mut Workspace, multipliers: &mut [f64], dv: &[f64]) {
    let Workspace { omega, f, .. } = ws;
    let Some(om) = omega.as_mut() else {
        return;
    };
    model.constraint_rhs(dv, multipliers);
    om.solve_in_place(multipliers);
    model.add_constraint_forces(multipliers, f);
}

/// The constrained response P_C F of forces on contact nodes (module docs), with its
/// buffers; shared by [`Imex`] and [`ImexArk`](super::ImexArk).
#[derive(Debug)]
pub(super) struct Response {
    /// The forces per class-1 node, nonzero on the contact nodes only; [`Response::respond`]
    /// leaves the joint forces that keep N P = D added to them.
    pub(super) forces: Vec<Vector3<f64>>,
    multipliers: Vec<f64>,
    /// The accelerations P_C F of every class-1 node (3 n₁).
    pub(super) out: Vec<f64>,
}

impl Response {
    /// Buffers for `model`.
    pub(super) fn new(model: &Model) -> Self {
        Self {
            forces: vec![Vector3::zeros(); model.n1],
            multipliers: vec![0.0; model.linear_rows.len()],
            out: vec![0.0; 3 * model.n1],
        }
    }

    /// `self.out` = P_C F: the accelerations of `self.response.forces` (on the contact nodes
    /// `touched`) at positions `x` and zero velocities (Ω factored at x).
    pub(super) fn respond(
        &mut self,
        model: &Model,
        ws: &mut Workspace,
        x: &[f64],
        touched: &[usize],
    ) {
        let Self {
            forces,
            multipliers,
            out,
        } = self;
        out.fill(0.0);
        let zero = [0.0; 3];
        let bar = |k: usize, f: &[Vector3<f64>], out: &mut [f64]| {
            let xk = &x[6 * k..6 * k + 6];
            let t = BarTerms::of(&xk[..3], &xk[3..], &zero, &zero);
            t.accel(
                &model.bars[k],
                &f[2 * k],
                &f[2 * k + 1],
                &mut out[6 * k..6 * k + 6],
            );
        };
        for &c in touched {
            bar(c / 2, forces, out);
        }
        if ws.omega.is_none() {
            return;
        }
        std::mem::swap(&mut ws.f, forces);
        constrain(model, ws, multipliers, out);
        std::mem::swap(&mut ws.f, forces);
        for &c in touched {
            bar(c / 2, forces, out);
        }
        for &k in &model.constrained_bars {
            bar(k, forces, out);
        }
    }
}

impl Imex {
    /// The contact forces F_c at positions `x` and velocities `v` of the active nodes into
    /// `self.response.forces` (zero elsewhere).
    fn contact_forces(&mut self, model: &Model, ws: &Workspace, x: &[f64], v: &[f64]) {
        self.response.forces.fill(Vector3::zeros());
        let Some(g) = &model.ground else {
            return;
        };
        for &(k, c, _) in &self.active {
            let anchor = ws.anchors[k].as_ref();
            self.response.forces[c] =
                velocity_dependent(g, &vec3(x, c), &vec3(v, c), anchor) - self.frozen[k];
        }
    }

    /// The velocity-dependent contact forces F_c(x, v) − F_c(x, 0) of the state `y`, per
    /// contact node, into `self.frozen`: zero off the ground and for a node that was off it at
    /// the previous step's start.
    fn freeze(&mut self, model: &Model, ws: &Workspace, y: &[f64]) {
        self.frozen.clear();
        let Some(g) = &model.ground else {
            return;
        };
        let (x, v) = y.split_at(3 * model.n1);
        self.touched_before.resize(model.contact.len(), false);
        for (k, &(_, c)) in model.contact.iter().enumerate() {
            let xc = vec3(x, c);
            let touching = g.height(&xc) < 0.0;
            // a node that has just landed still moves at its impact speed: holding its damping
            // force through A would act as a restitution
            let hold = touching && self.touched_before[k];
            self.touched_before[k] = touching;
            let f = if hold {
                velocity_dependent(g, &xc, &vec3(v, c), ws.anchors[k].as_ref())
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
    fn contact_substep(
        &mut self,
        model: &Model,
        ws: &mut Workspace,
        y: &mut [f64],
        tau: f64,
    ) -> Result<(f64, f64), CoreError> {
        let Some(g) = &model.ground else {
            return Ok((0.0, 0.0));
        };
        let n3 = 3 * model.n1;
        self.active.clear();
        {
            let (x, v) = y.split_at(n3);
            for (k, &(_, c)) in model.contact.iter().enumerate() {
                let xc = vec3(x, c);
                if g.height(&xc) < 0.0 || self.frozen[k] != Vector3::zeros() {
                    let kv = g
                        .contact_jacobian(&xc, &vec3(v, c), ws.anchors[k].as_ref())
                        .map_or_else(Matrix3::zeros, |(_, kv)| kv);
                    self.active.push((k, c, kv));
                }
            }
        }
        if self.active.is_empty() {
            return Ok((0.0, 0.0));
        }
        self.contact_substeps += 1;
        let kinetic_before = model.kinetic_energy(y);
        let touched: Vec<usize> = self.active.iter().map(|a| a.1).collect();
        let x = y[..n3].to_vec();
        factor_omega_unless_current(model, &x, ws)?;
        // the response columns P̃_C
        let m3 = 3 * touched.len();
        if touched != self.cached || self.age >= REFRESH {
            self.cols.resize_with(m3, Vec::new);
            for j in 0..m3 {
                self.response.forces.fill(Vector3::zeros());
                self.response.forces[touched[j / 3]][j % 3] = 1.0;
                self.response.respond(model, ws, &x, &touched);
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
        self.contact_forces(model, ws, &x, &v0);
        let (n1, t1) = self.split_power(&g.normal, &v0);
        self.response.respond(model, ws, &x, &touched);
        let k1 = self.solve_stage(&lu, &kv, gt, &touched)?;
        // stage 2 at v₀ + τ k₁: r = P_C F(v₀ + τ k₁) − 2 k₁
        self.stage.clear();
        self.stage
            .extend(v0.iter().zip(&k1).map(|(a, b)| a + tau * b));
        let stage = std::mem::take(&mut self.stage);
        self.contact_forces(model, ws, &x, &stage);
        let (n2, t2) = self.split_power(&g.normal, &stage);
        self.stage = stage;
        self.response.respond(model, ws, &x, &touched);
        for (r, a) in self.response.out.iter_mut().zip(&k1) {
            *r -= 2.0 * a;
        }
        let k2 = self.solve_stage(&lu, &kv, gt, &touched)?;
        for ((o, a), b) in y[n3..].iter_mut().zip(&k1).zip(&k2) {
            *o += tau * (1.5 * a + 0.5 * b);
        }
        let work = model.kinetic_energy(y) - kinetic_before;
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

impl Integrator for Imex {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Imex
    }

    /// Advances `y` from `t` to `t + h` in place: B(h/2), RK4 on f_A, B(h/2).
    fn step(
        &mut self,
        model: &Model,
        ws: &mut Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        let split = splits(model);
        let mut work = ws.contact_work.unwrap_or_default();
        self.frozen.clear();
        if split {
            self.freeze(model, ws, y);
            let (wn, wt) = self.contact_substep(model, ws, y, 0.5 * h)?;
            work.0 += wn;
            work.1 += wt;
        }
        let mut power = [(0.0, 0.0); 4];
        let frozen = std::mem::take(&mut self.frozen);
        let mut k = std::mem::take(&mut self.k);
        let mut mult = std::mem::take(&mut self.multipliers);
        let result = (|| {
            let n = y.len();
            power[0] = rhs_smooth(model, t, y, &mut k[0], ws, &mut mult, &frozen)?;
            for i in 0..n {
                self.tmp[i] = y[i] + 0.5 * h * k[0][i];
            }
            power[1] = rhs_smooth(
                model,
                t + 0.5 * h,
                &self.tmp,
                &mut k[1],
                ws,
                &mut mult,
                &frozen,
            )?;
            for i in 0..n {
                self.tmp[i] = y[i] + 0.5 * h * k[1][i];
            }
            power[2] = rhs_smooth(
                model,
                t + 0.5 * h,
                &self.tmp,
                &mut k[2],
                ws,
                &mut mult,
                &frozen,
            )?;
            for i in 0..n {
                self.tmp[i] = y[i] + h * k[2][i];
            }
            power[3] = rhs_smooth(model, t + h, &self.tmp, &mut k[3], ws, &mut mult, &frozen)?;
            let h6 = h / 6.0;
            for i in 0..n {
                y[i] += h6 * (k[0][i] + 2.0 * (k[1][i] + k[2][i]) + k[3][i]);
            }
            Ok::<(), CoreError>(())
        })();
        self.k = k;
        self.multipliers = mult;
        self.frozen = frozen;
        result?;
        if split {
            // A's non-conservative contact work by RK4's own quadrature of its power
            let rk4 = |p: [f64; 4]| h / 6.0 * (p[0] + 2.0 * (p[1] + p[2]) + p[3]);
            work.0 += rk4(power.map(|p| p.0));
            work.1 += rk4(power.map(|p| p.1));
            let (wn, wt) = self.contact_substep(model, ws, y, 0.5 * h)?;
            work.0 += wn;
            work.1 += wt;
            ws.contact_work = Some(work);
        }
        Ok(StepOutcome::fixed(h))
    }
}

/// The free-bar accelerations ([`BarTerms`]) of every bar of the model (or the listed ones),
/// written into `dv`.
fn bar_accelerations(
    model: &Model,
    x: &[f64],
    v: &[f64],
    f: &[Vector3<f64>],
    dv: &mut [f64],
    only: Option<&[usize]>,
) {
    let mut one = |k: usize| {
        let (xk, vk) = (&x[6 * k..6 * k + 6], &v[6 * k..6 * k + 6]);
        let t = BarTerms::of(&xk[..3], &xk[3..], &vk[..3], &vk[3..]);
        t.accel(
            &model.bars[k],
            &f[2 * k],
            &f[2 * k + 1],
            &mut dv[6 * k..6 * k + 6],
        );
    };
    match only {
        Some(list) => list.iter().for_each(|&k| one(k)),
        None => (0..model.bars.len()).for_each(one),
    }
}
