//! The model's side of the contact split ([`ContactSystem`] for [`Model`]): the explicit
//! right-hand side f_E without the ground's velocity-dependent forces, and the constrained
//! response P_C of forces on the contact nodes, which [`Imex`](super::Imex) and
//! [`ImexArk`](super::ImexArk) build their implicit contact parts from.
//!
//! # Equations
//!
//! With y = (x, v) and the ground's force F_c(x, v) on each contact node:
//!
//! * **f_E** ([`ContactSystem::rhs_explicit`]) = (v, a(x, v; F_c(x, 0) + F*)): the rigid-bar
//!   dynamics N̈M + NK = W + ΩPᵀ of [`Model::rhs`] with the ground's position-only force
//!   F_c(x, 0) (the normal spring k δ, the stick law's anchor spring) and a held force F* per
//!   contact node in place of F_c(x, v). Its non-conservative contact power is
//!   Σ (F* + F_c,t(x, 0))·v_c, split into the parts along the normal and tangential to it
//!   (F_c,t the tangential part; the normal spring is the energy budget's ground spring).
//! * **P_C F** ([`ContactSystem::respond`]): the accelerations of every class-1 node under
//!   forces F on the touched contact nodes at positions x and zero velocities: per bar
//!   b̈ = (½f_d − b (½ bᵀf_d / l²)) J⁻¹, r̈ = (f_a + f_b)/m (no centripetal term), and with
//!   joints the multipliers ω of G M⁻¹ Gᵀ ω = −G a (Ω factored at x), whose forces Gᵀω are
//!   added before the constrained bars' accelerations are taken again. It is linear in F.
//!
//! Ω depends on the positions only through the bar directions b̂; a factorisation is reused
//! while every b̂ is within [`OMEGA_REUSE`] of the one it was taken at
//! ([`ContactSystem::prepare_response`]). Without a penalty or stick ground (no split) f_E is
//! [`Model::rhs`].

use super::forces::GroundModel;
use super::model::{BarTerms, Model, Workspace};
use super::omega::ConstraintMatrix;
use super::system::{vec3, ContactSystem};
use nalgebra::{Matrix3, Vector3};
use tensegrity_core::error::{CoreError, DynamicsError, StepHint};
use tensegrity_core::structure::MemberId;

/// Largest change of a bar direction's component at which a factored Ω is kept
/// ([`ContactSystem::prepare_response`]). On the hopping n = 24 wheel at 5·10⁻⁴ s the
/// projection moves the directions by 10⁻¹⁵ … 10⁻⁸ (the response's relative error, far below
/// the step's), a step by 10⁻⁶ and more.
pub const OMEGA_REUSE: f64 = 1e-8;

impl ContactSystem for Model {
    /// Penalty and stick grounds.
    fn splits_contact(&self) -> bool {
        self.ground.as_ref().is_some_and(|g| {
            matches!(
                g.model,
                GroundModel::Penalty { .. } | GroundModel::Stick { .. }
            )
        })
    }

    fn contact_points(&self) -> usize {
        if self.ground.is_some() {
            self.contact.len()
        } else {
            0
        }
    }

    fn contact_node(&self, k: usize) -> usize {
        self.contact[k].1
    }

    fn ground_normal(&self) -> Vector3<f64> {
        self.ground
            .as_ref()
            .map_or_else(Vector3::zeros, |g| g.normal)
    }

    fn ground_height(&self, p: &Vector3<f64>) -> f64 {
        self.ground.as_ref().map_or(f64::INFINITY, |g| g.height(p))
    }

    /// The thesis ground's tolerance, else the plane itself.
    fn touch_height(&self) -> f64 {
        match self.ground.as_ref().map(|g| g.model) {
            Some(GroundModel::Thesis { tolerance, .. }) => tolerance,
            _ => 0.0,
        }
    }

    /// The stick law's force ([`Ground::stick_force`](super::Ground::stick_force); the
    /// penalty force on a penalty ground).
    fn contact_force(
        &self,
        ws: &Workspace,
        k: usize,
        p: &Vector3<f64>,
        u: &Vector3<f64>,
    ) -> Vector3<f64> {
        self.ground.as_ref().map_or_else(Vector3::zeros, |g| {
            g.stick_force(p, u, ws.anchors[k].as_ref())
        })
    }

    fn contact_damping(
        &self,
        ws: &Workspace,
        k: usize,
        p: &Vector3<f64>,
        u: &Vector3<f64>,
    ) -> Matrix3<f64> {
        self.ground
            .as_ref()
            .and_then(|g| g.contact_jacobian(p, u, ws.anchors[k].as_ref()))
            .map_or_else(Matrix3::zeros, |(_, kv)| kv)
    }

    fn rhs_explicit(
        &self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        ws: &mut Workspace,
        held: &[Vector3<f64>],
    ) -> Result<(f64, f64), CoreError> {
        rhs_smooth(self, t, y, dy, ws, held)
    }

    fn prepare_response(&self, ws: &mut Workspace, x: &[f64]) -> Result<(), CoreError> {
        factor_omega_unless_current(self, x, ws)
    }

    fn respond(
        &self,
        ws: &mut Workspace,
        x: &[f64],
        forces: &mut [Vector3<f64>],
        touched: &[usize],
        out: &mut [f64],
    ) {
        out.fill(0.0);
        let zero = [0.0; 3];
        let bar = |k: usize, f: &[Vector3<f64>], out: &mut [f64]| {
            let xk = &x[6 * k..6 * k + 6];
            let t = BarTerms::of(&xk[..3], &xk[3..], &zero, &zero);
            t.accel(
                &self.bars[k],
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
        let Workspace {
            omega, omega_rhs, ..
        } = ws;
        constrain(self, omega, omega_rhs, forces, out);
        for &c in touched {
            bar(c / 2, forces, out);
        }
        for &k in &self.constrained_bars {
            bar(k, forces, out);
        }
    }

    fn kinetic_energy(&self, y: &[f64]) -> f64 {
        Model::kinetic_energy(self, y)
    }

    fn contact_work(&self, ws: &Workspace) -> Option<(f64, f64)> {
        ws.contact_work
    }

    fn set_contact_work(&self, ws: &mut Workspace, work: (f64, f64)) {
        ws.contact_work = Some(work);
    }
}

/// f_A: [`Model::rhs`] without the ground's forces (when they are split off), plus the held
/// force `frozen` (per contact node). Returns the power (normal, tangential) of A's
/// non-conservative contact forces: the held force and the tangential part of the
/// position-only force F_c(x, 0) (the stick law's anchor spring; zero for the penalty law),
/// whose normal part k δ is the ground spring of the energy budget.
fn rhs_smooth(
    model: &Model,
    t: f64,
    y: &[f64],
    dy: &mut [f64],
    ws: &mut Workspace,
    frozen: &[Vector3<f64>],
) -> Result<(f64, f64), CoreError> {
    if !model.splits_contact() {
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
        let Workspace {
            omega,
            omega_rhs,
            f,
            ..
        } = ws;
        constrain(model, omega, omega_rhs, f, dv);
        bar_accelerations(model, x, v, &ws.f, dv, Some(&model.constrained_bars));
    }
    Ok((normal_power, tangential_power))
}

/// Refactors Ω at positions `x` unless it is factored at bar directions within
/// [`OMEGA_REUSE`] of those of `x`. Ω depends on the positions only through the bar directions
/// b̂, and two evaluations of a step share them: the contact substep that opens a step sits
/// where the one that closed the previous step was (moved only by the driver's projection onto
/// the bar constraints), and A's first stage where the opening substep was (B moves no node).
fn factor_omega_unless_current(
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

/// Adds to `f` the joint forces Gᵀω that make the accelerations `dv` (of the forces `f`) keep
/// N P = D (Ω factored), with the multipliers ω solved in `multipliers`.
fn constrain(
    model: &Model,
    omega: &mut Option<ConstraintMatrix>,
    multipliers: &mut [f64],
    f: &mut [Vector3<f64>],
    dv: &[f64],
) {
    let Some(om) = omega.as_mut() else {
        return;
    };
    model.constraint_rhs(dv, multipliers);
    om.solve_in_place(multipliers);
    model.add_constraint_forces(multipliers, f);
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
