//! IMEX-ARK: an additive Runge–Kutta method for stiff ground contact, ARK3(2)4L\[2\]SA of
//! Kennedy & Carpenter (2003): an explicit four-stage tableau for the smooth forces and an
//! L-stable ESDIRK for the ground's damping and friction, coupled at every stage.
//!
//! **The split.** As in [`Imex`](super::Imex), y' = f_E(y) + f_I(y) with y = (x, v),
//!
//! * f_E = (v, a(x, v; F_c(x, 0))): the rigid-bar dynamics N̈M + NK = W + ΩPᵀ of
//!   [`Model::rhs`](super::Model::rhs) with the ground's position-only force F_c(x, 0) (the
//!   normal spring k δ, the stick law's anchor spring) but not its velocity-dependent part
//!   ([`ContactSystem::rhs_explicit`] without held forces);
//! * f_I = (0, P_C(x) F̃(x, v)): the velocity-dependent force F̃ = F_c(x, v) − F_c(x, 0) of
//!   the m loaded contact nodes (normal damper, tangential damper, regularised friction with
//!   its Stribeck weakening), through the constrained response P_C(x) of every class-1 node to
//!   a force on a contact node (linear in the force: one Ω solve per response).
//!
//! **A step.** With tableaux a^E, a^I (γ = a^I_ii = 0.4359, L-stable) and shared weights b
//! ([`ARK3`]),
//!
//! Y_i = y_n + h Σ_{j<i} a^E_ij f_E(Y_j) + h Σ_{j≤i} a^I_ij f_I(Y_j),   y_{n+1} = y_n + h Σ b_i (f_E + f_I)(Y_i).
//!
//! f_I moves no position, so a stage's positions x_i are explicit, and its implicit part is an
//! equation in the 3m contact velocities u alone:
//!
//! u = u_b + hγ P_CC(x_i) F̃(x_i, u),
//!
//! u_b the stage's contact velocities before its own implicit term, P_CC the 3m × 3m block of
//! P_C on the contact nodes. It is solved by Newton's method (per-node 3 × 3 Jacobians of F̃ by
//! differences, a backtracking line search on the residual; [`NEWTON_ITERATIONS`],
//! [`NEWTON_TOLERANCE`]); then f_I(Y_i) = P_C F̃(u) is one more response. The first stage is
//! explicit (a^I_11 = 0).
//!
//! **Why not the split.** The Strang split of [`Imex`](super::Imex) holds the damping force
//! through its explicit part and corrects it in ROS2 substeps; on a creeping contact
//! (regularised friction below its regularisation velocity, v = v_reg artanh(F_t / μ f_n)) it
//! maps the creep error by 1 − 2|z|R(z) → −0.657 per step in the stiff limit, and the pivot
//! chatters at steps of 10⁻⁴ s and more. Here the stiff stage equations see the explicit
//! forces of their own stage, so the slaved creep is the stage solution (L-stability: the map
//! → 0), and the method keeps its order where the contact is stiff: on the reference pivot of
//! docs/notes/ROLLING.md ("IMEX-ARK") the axle's error before the impact is 1.5·10⁻⁶, 1.7·10⁻⁷ and
//! 9·10⁻⁹ m at 2.5·10⁻⁴, 10⁻⁴ and 5·10⁻⁵ s (the split IMEX: 7.2·10⁻³, 5.9·10⁻⁴, 8.5·10⁻⁷ m).
//!
//! **Its limit.** F̃ is piecewise smooth (the max(0, ·) of the normal damper, the stick law's
//! cap) and, with Stribeck weakening, not monotone in the slip speed: for steps where
//! hγ P μ′ f_n exceeds 1 the stage equation has several roots and Newton may stall. A stage
//! whose residual stays above [`NEWTON_ACCEPT`] after Newton and the continuation
//! ([`ImexArk::unconverged`]) keeps its best iterate; more than
//! [`DriftLimits::implicit_solve`](super::DriftLimits::implicit_solve) (a tenth) of a run's
//! stages is a [`DriftWarning`](super::DriftWarning) that names the remedy (a smaller step).
//!
//! **Response columns.** P_CC is refreshed when the set of loaded contact nodes changes and
//! at least every [`REFRESH`](super::imex::REFRESH) contact stages (Newton sees a P̃_CC up to
//! that old: the bar directions, on which P_C depends, move by ω h per stage); f_I(Y_i) itself
//! always uses the exact response at x_i. So a step with contact costs four smooth right-hand
//! sides, four Ω factorisations and four responses, and 3m more responses at a refresh.
//!
//! **Work of the contact** ([`super::Sample::contact_work`]): for each node, its impulse
//! J = h Σ b_i F̃(Y_i) over the step times its mean velocity (v_n + v_{n+1})/2, split into
//! normal and tangential parts (exact for an impulse on a free mass, ½ m (v₁² − v₀²) = J·v̄,
//! however short the damping time; the constraint forces do no work), plus f_E's
//! non-conservative contact power (the stick law's anchor spring) by the weights b. The
//! quadrature Σ h b_i F̃(Y_i)·u_i of the stages' powers is not usable: where the damper acts
//! within a fraction of the step its power is not resolved, and on a bar dropped onto a
//! ground damped at 2000 N s/m the budget then missed by 1.8·10⁻² at 5·10⁻⁴ s (3.1·10⁻⁴ with
//! the impulse; test `dynamics_stick::imex_ark_reports_the_contact_work_that_closes_its_energy_budget`).
//!
//! The bar constraints are kept as for RK4: the driver projects every accepted state back
//! onto the bar lengths and N P = D. Without a penalty or stick ground there is no f_I and
//! the step is classic RK4 ([`Rk4`]). The method is written against [`ContactSystem`] (F̃ from
//! its [`contact_force`](ContactSystem::contact_force), P_C its
//! [`respond`](ContactSystem::respond)).

use super::imex::Response;
use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::rk4::Rk4;
use super::system::{vec3, ContactSystem};
use super::tableau::{Tableau, ARK3};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use tensegrity_core::error::CoreError;

/// The coefficients ([`ARK3`]).
const TAB: Tableau<4> = ARK3;

/// γ of ARK3(2)4L\[2\]SA's ESDIRK part.
const GAMMA: f64 = TAB.diagonal();

/// Explicit tableau a^E of ARK3(2)4L\[2\]SA.
const AE: [[f64; 4]; 4] = TAB.a;

/// Implicit (ESDIRK) tableau a^I of ARK3(2)4L\[2\]SA.
const AI: [[f64; 4]; 4] = TAB.implicit();

/// The weights b of both (the last row of a^I).
const B: [f64; 4] = TAB.b;

/// Abscissae c of ARK3(2)4L\[2\]SA.
const C: [f64; 4] = TAB.c;

/// Newton iterations of a stage equation at most.
pub const NEWTON_ITERATIONS: usize = 30;

/// Newton stops when the stage residual (m/s) is below this times 1 + the largest stage
/// velocity.
pub const NEWTON_TOLERANCE: f64 = 1e-10;

/// A stage whose residual ends above this times 1 + the largest stage velocity counts as
/// unconverged ([`ImexArk::unconverged`]).
pub const NEWTON_ACCEPT: f64 = 1e-6;

/// The IMEX-ARK stepper (module docs).
#[derive(Debug, Clone)]
pub struct ImexArk {
    /// Without a penalty or stick ground: plain RK4.
    rk4: Rk4,
    ke: [Vec<f64>; 4],
    /// Velocity parts of f_I(Y_i).
    ki: [Vec<f64>; 4],
    y0: Vec<f64>,
    tmp: Vec<f64>,
    /// P_C of the contact forces (`response.forces`) into `response.out`.
    response: Response,
    /// Loaded contact nodes of the stage: (contact index, class-1 node).
    active: Vec<(usize, usize)>,
    /// F_c(x, 0) of the active nodes at the stage's positions.
    rest: Vec<Vector3<f64>>,
    /// Per contact index: the contact velocity of the last solved stage (Newton's start).
    last: Vec<Option<Vector3<f64>>>,
    /// Per contact index: the step's impulse h Σ b_i F̃(Y_i) (work of the contact).
    impulse: Vec<Vector3<f64>>,
    /// P̃_CC and the nodes and age it was computed for.
    pcc: DMatrix<f64>,
    cached: Vec<usize>,
    age: u32,
    /// Implicit contact stages solved.
    pub contact_stages: u64,
    /// Newton iterations over all stages.
    pub newton_iterations: u64,
    /// Stages whose Newton residual stayed above [`NEWTON_ACCEPT`].
    pub unconverged: u64,
    /// Times P̃_CC was recomputed.
    pub refreshes: u64,
}

impl ImexArk {
    /// Buffers for `system`.
    pub fn new<S: ContactSystem>(system: &S) -> Self {
        let n = system.state_len();
        let n3 = n / 2;
        let m = system.contact_points();
        Self {
            rk4: Rk4::new(n),
            ke: std::array::from_fn(|_| vec![0.0; n]),
            ki: std::array::from_fn(|_| vec![0.0; n3]),
            y0: vec![0.0; n],
            tmp: vec![0.0; n],
            response: Response::new(n / 6),
            active: Vec::new(),
            rest: Vec::new(),
            last: vec![None; m],
            impulse: vec![Vector3::zeros(); m],
            pcc: DMatrix::zeros(0, 0),
            cached: Vec::new(),
            age: 0,
            contact_stages: 0,
            newton_iterations: 0,
            unconverged: 0,
            refreshes: 0,
        }
    }

    /// Recomputes P̃_CC at `x` for the nodes `touched` unless it is current.
    fn refresh<S: ContactSystem>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        x: &[f64],
        touched: &[usize],
    ) {
        if touched == self.cached.as_slice() && self.age < super::imex::REFRESH {
            self.age += 1;
            return;
        }
        let m3 = 3 * touched.len();
        let mut pcc = DMatrix::zeros(m3, m3);
        for j in 0..m3 {
            self.response.forces.fill(Vector3::zeros());
            self.response.forces[touched[j / 3]][j % 3] = 1.0;
            self.response.respond(system, ws, x, touched);
            for (r, &c) in touched.iter().enumerate() {
                for e in 0..3 {
                    pcc[(3 * r + e, j)] = self.response.out[3 * c + e];
                }
            }
        }
        self.pcc = pcc;
        self.cached = touched.to_vec();
        self.age = 1;
        self.refreshes += 1;
    }

    /// F̃ of the active nodes at their velocities `u` (3m).
    fn reduced<S: ContactSystem>(
        &self,
        system: &S,
        ws: &S::Workspace,
        x: &[f64],
        u: &DVector<f64>,
    ) -> DVector<f64> {
        let mut f = DVector::zeros(u.len());
        for (i, &(k, c)) in self.active.iter().enumerate() {
            let fi = self.node_force(system, ws, x, i, k, c, &u.fixed_rows::<3>(3 * i).into());
            f.fixed_rows_mut::<3>(3 * i).copy_from(&fi);
        }
        f
    }

    /// F̃ of active node `i` (contact index `k`, class-1 node `c`) at velocity `v`.
    #[allow(clippy::too_many_arguments)]
    fn node_force<S: ContactSystem>(
        &self,
        system: &S,
        ws: &S::Workspace,
        x: &[f64],
        i: usize,
        k: usize,
        c: usize,
        v: &Vector3<f64>,
    ) -> Vector3<f64> {
        system.contact_force(ws, k, &vec3(x, c), v) - self.rest[i]
    }

    /// Solves u = b + a P̃_CC F̃(u) (module docs): Newton's method from `start` (and from b,
    /// whichever has the smaller residual); if that stalls, by continuation in a (Newton at
    /// a/4, a/2, 3a/4, a, each from the last), which follows the root that grows out of the
    /// explicit predictor where Stribeck weakening gives the equation several. Returns the
    /// solution with the smaller residual and whether it met [`NEWTON_ACCEPT`].
    fn solve<S: ContactSystem>(
        &mut self,
        system: &S,
        ws: &S::Workspace,
        x: &[f64],
        b: &DVector<f64>,
        a: f64,
        start: DVector<f64>,
    ) -> (DVector<f64>, bool) {
        let accept = NEWTON_ACCEPT * (1.0 + b.amax());
        let (u, r) = self.newton(system, ws, x, b, a, start);
        if r <= accept {
            return (u, true);
        }
        let mut v = b.clone();
        let mut rv = f64::INFINITY;
        for s in [0.25, 0.5, 0.75, 1.0] {
            (v, rv) = self.newton(system, ws, x, b, a * s, v);
        }
        if rv < r {
            (v, rv <= accept)
        } else {
            (u, false)
        }
    }

    /// Newton's method on u = b + a P̃_CC F̃(u) from `start` (or b, if its residual is
    /// smaller), with a backtracking line search; returns u and its largest residual.
    fn newton<S: ContactSystem>(
        &mut self,
        system: &S,
        ws: &S::Workspace,
        x: &[f64],
        b: &DVector<f64>,
        a: f64,
        start: DVector<f64>,
    ) -> (DVector<f64>, f64) {
        let m3 = b.len();
        let scale = 1.0 + b.amax();
        let residual = |s: &Self, u: &DVector<f64>| {
            let f = s.reduced(system, ws, x, u);
            (u - b - &s.pcc * &f * a, f)
        };
        let mut u = start;
        let (mut r, mut f) = residual(self, &u);
        // the explicit predictor is the other natural start
        if u != *b {
            let (rb, fb) = residual(self, b);
            if rb.norm() < r.norm() {
                (u, r, f) = (b.clone(), rb, fb);
            }
        }
        let mut kv = DMatrix::zeros(m3, m3);
        for _ in 0..NEWTON_ITERATIONS {
            if r.amax() <= NEWTON_TOLERANCE * scale {
                break;
            }
            self.newton_iterations += 1;
            // per-node Jacobians by forward differences: the Stribeck weakening and the
            // cap's dependence on f_n are in F̃ but not in the analytic contact Jacobian
            let eps = 1e-8 * (1.0 + u.amax());
            for (i, &(k, c)) in self.active.iter().enumerate() {
                let ui: Vector3<f64> = u.fixed_rows::<3>(3 * i).into();
                let f0: Vector3<f64> = f.fixed_rows::<3>(3 * i).into();
                let mut block = Matrix3::zeros();
                for d in 0..3 {
                    let mut up = ui;
                    up[d] += eps;
                    let fd = self.node_force(system, ws, x, i, k, c, &up);
                    block.set_column(d, &((fd - f0) / eps));
                }
                kv.fixed_view_mut::<3, 3>(3 * i, 3 * i).copy_from(&block);
            }
            let jac = DMatrix::identity(m3, m3) - &self.pcc * &kv * a;
            let Some(du) = jac.lu().solve(&r) else {
                break;
            };
            let norm = r.norm();
            let mut step = 1.0;
            loop {
                let trial = &u - &du * step;
                let (rt, ft) = residual(self, &trial);
                if rt.norm() < norm || step < 1.0 / 64.0 {
                    (u, r, f) = (trial, rt, ft);
                    break;
                }
                step *= 0.5;
            }
        }
        let rmax = r.amax();
        (u, rmax)
    }

    /// One ARK step on a penalty or stick ground (module docs).
    fn ark_step<S: ContactSystem>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<(), CoreError> {
        let n = y.len();
        let n3 = n / 2;
        let m = system.contact_points();
        let normal = system.ground_normal();
        let mut work = system.contact_work(ws).unwrap_or_default();
        self.y0.copy_from_slice(y);
        let mut ke = std::mem::take(&mut self.ke);
        let mut power = [(0.0, 0.0); 4];
        self.impulse.fill(Vector3::zeros());
        let result = (|| {
            for i in 0..4 {
                self.tmp.copy_from_slice(&self.y0);
                for j in 0..i {
                    let (ae, ai) = (h * AE[i][j], h * AI[i][j]);
                    for (o, k) in self.tmp.iter_mut().zip(&ke[j]) {
                        *o += ae * k;
                    }
                    for (o, k) in self.tmp[n3..].iter_mut().zip(&self.ki[j]) {
                        *o += ai * k;
                    }
                }
                self.ki[i].fill(0.0);
                let x = self.tmp[..n3].to_vec();
                self.active.clear();
                self.rest.clear();
                for k in 0..m {
                    let c = system.contact_node(k);
                    let xc = vec3(&x, c);
                    if system.ground_height(&xc) < 0.0 {
                        self.active.push((k, c));
                        self.rest
                            .push(system.contact_force(ws, k, &xc, &Vector3::zeros()));
                    } else {
                        self.last[k] = None;
                    }
                }
                if !self.active.is_empty() {
                    system.prepare_response(ws, &x)?;
                    let touched: Vec<usize> = self.active.iter().map(|a| a.1).collect();
                    let m3 = 3 * touched.len();
                    let b = DVector::from_fn(m3, |r, _| self.tmp[n3 + 3 * touched[r / 3] + r % 3]);
                    let u = if i == 0 {
                        b.clone()
                    } else {
                        self.refresh(system, ws, &x, &touched);
                        let start = DVector::from_fn(m3, |r, _| {
                            self.last[self.active[r / 3].0].map_or(b[r], |v| v[r % 3])
                        });
                        self.contact_stages += 1;
                        let (u, ok) = self.solve(system, ws, &x, &b, h * GAMMA, start);
                        if !ok {
                            self.unconverged += 1;
                        }
                        u
                    };
                    let f = self.reduced(system, ws, &x, &u);
                    self.response.forces.fill(Vector3::zeros());
                    let hb = h * B[i];
                    for (q, &(k, c)) in self.active.iter().enumerate() {
                        let fq: Vector3<f64> = f.fixed_rows::<3>(3 * q).into();
                        self.response.forces[c] = fq;
                        self.last[k] = Some(u.fixed_rows::<3>(3 * q).into());
                        self.impulse[k] += fq * hb;
                    }
                    self.response.respond(system, ws, &x, &touched);
                    self.ki[i].copy_from_slice(&self.response.out);
                    let a = h * AI[i][i];
                    for (o, k) in self.tmp[n3..].iter_mut().zip(&self.ki[i]) {
                        *o += a * k;
                    }
                }
                power[i] = system.rhs_explicit(t + C[i] * h, &self.tmp, &mut ke[i], ws, &[])?;
            }
            for (i, bi) in B.iter().enumerate() {
                let hb = h * bi;
                for q in 0..n {
                    y[q] += hb * ke[i][q];
                }
                for q in 0..n3 {
                    y[n3 + q] += hb * self.ki[i][q];
                }
                work.0 += hb * power[i].0;
                work.1 += hb * power[i].1;
            }
            // the implicit forces' work: each node's impulse times its mean velocity over
            // the step (exact for an impulse on a free mass, whatever the damping time)
            for k in 0..m {
                let c = system.contact_node(k);
                let j = self.impulse[k];
                if j != Vector3::zeros() {
                    let mean = (vec3(&self.y0[n3..], c) + vec3(&y[n3..], c)) * 0.5;
                    let along = j.dot(&normal) * mean.dot(&normal);
                    work.0 += along;
                    work.1 += j.dot(&mean) - along;
                }
            }
            Ok::<(), CoreError>(())
        })();
        self.ke = ke;
        result?;
        system.set_contact_work(ws, work);
        Ok(())
    }
}

impl<S: ContactSystem> Integrator<S> for ImexArk {
    fn boxed_clone(&self) -> Option<Box<dyn Integrator<S>>> {
        Some(Box::new(self.clone()))
    }

    fn kind(&self) -> IntegratorKind {
        IntegratorKind::ImexArk
    }

    /// Advances `y` from `t` to `t + h` in place (module docs).
    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        if !system.splits_contact() {
            return self.rk4.step(system, ws, t, y, h);
        }
        self.ark_step(system, ws, t, y, h)?;
        Ok(StepOutcome::fixed(h))
    }

    fn implicit_solves(&self) -> (u64, u64) {
        (self.contact_stages, self.unconverged)
    }
}
