//! The system an integrator advances, as traits: the methods of this crate are written
//! against these, not against [`Model`](crate::Model) (which implements all three).
//!
//! # Equations
//!
//! * [`System`]: the first-order ODE y' = f(t, y), y ∈ ℝⁿ, n = [`System::state_len`], with
//!   a workspace of preallocated buffers that every evaluation of f uses (and counts in).
//!   This is all that the explicit Runge–Kutta methods ([`Rk4`](crate::Rk4),
//!   [`Dopri5`](crate::Dopri5)) need.
//! * [`ConstrainedSystem`]: a second-order system of p nodes in ℝ³, y = (x, v) with
//!   x, v ∈ ℝ³ᵖ (n = 6p), and f = (v, a):
//!
//!   M ẍ = F(t, x, ẋ) + G(x)ᵀμ,   g(x) = 0,
//!
//!   M the (block-diagonal, per bar) mass matrix, F the applied forces
//!   ([`ConstrainedSystem::forces`]), g the holonomic constraints with gradient G = ∂g/∂x
//!   and μ their multipliers. The projection back onto the constraints
//!   ([`ConstrainedSystem::project`]) corrects x along M⁻¹Gᵀ until g(x) = 0 and then v
//!   along M⁻¹Gᵀ until G(x) v = 0; RATTLE ([`Rattle`](crate::Rattle)) takes the pieces of
//!   it (factor G M⁻¹ Gᵀ, the position solve, the velocity projection, M⁻¹) one by one, and
//!   SDIRK ([`Sdirk`](crate::Sdirk)) projects its accepted states.
//! * [`ContactSystem`]: the same second-order system with m contact points (nodes on a
//!   ground plane with unit normal n̂ and height h(x) = n̂·(x − x₀)), whose contact force
//!   F_c(x, v) splits into its position-only part F_c(x, 0) and the velocity-dependent rest
//!   F̃ = F_c(x, v) − F_c(x, 0) (the dampers and the regularised friction: the stiff part):
//!
//!   y' = f_E(y) + f_I(y),   f_E = (v, a(x, v; F_c(x, 0) + F*)),   f_I = (0, P_C(x) (F̃ − F*)),
//!
//!   with F* a force held over a step (IMEX: [`Imex`](crate::Imex); zero for ARK:
//!   [`ImexArk`](crate::ImexArk)) and P_C(x) the constrained response: the accelerations of
//!   every node under forces on the contact points alone, at positions x and zero velocities
//!   (linear in the forces; [`ContactSystem::respond`]). f_E is
//!   [`ContactSystem::rhs_explicit`]; the implicit part is built by the method from
//!   [`ContactSystem::contact_force`], its velocity Jacobian ∂F_c/∂v
//!   ([`ContactSystem::contact_damping`]) and P_C.
//!
//! A state's node i is the 3-vector y\[3i..3i+3\]; in y = (x, v) the velocity of
//! node i is node i of v = y\[n/2..\].

use nalgebra::{Matrix3, Vector3};
use tensegrity_core::error::CoreError;

/// The first-order system y' = f(t, y) an integrator advances (module docs).
pub trait System {
    /// Preallocated buffers of the right-hand side (one per integration; it also counts the
    /// evaluations).
    type Workspace;

    /// Length n of the state y.
    fn state_len(&self) -> usize;

    /// dy = f(t, y) (both of length [`state_len`](Self::state_len)), using and counting in
    /// `ws`. Fails on a state the right-hand side cannot evaluate (non-finite forces, a
    /// singular constraint system).
    fn rhs(
        &self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        ws: &mut Self::Workspace,
    ) -> Result<(), CoreError>;
}

/// A constrained second-order system of nodes in ℝ³: M ẍ = F + Gᵀμ, g(x) = 0 (module docs).
/// The state is y = (x, v), each half 3 coordinates per node ([`System::state_len`]/6 nodes).
pub trait ConstrainedSystem: System {
    /// The constraints g with their factored multiplier system G M⁻¹ Gᵀ (one per user: the
    /// factorisation and the iteration's start are kept between calls).
    type Constraints: std::fmt::Debug;

    /// A fresh constraint set; fails when the constraints are redundant (G M⁻¹ Gᵀ singular).
    fn constraints(&self) -> Result<Self::Constraints, CoreError>;

    /// The absolute tolerance of the position constraints that the methods project to.
    fn constraint_tolerance(&self) -> f64;

    /// Projects y onto g(x) = 0 (to `tol`) and then G(x) v = 0, along M⁻¹Gᵀ; returns the
    /// remaining position residual max |g|. `t` only names the time in an error.
    fn project(
        &self,
        constraints: &mut Self::Constraints,
        y: &mut [f64],
        tol: f64,
        t: f64,
    ) -> Result<f64, CoreError>;

    /// Factors G M⁻¹ Gᵀ with G at the positions `x`.
    fn factor_constraints(
        &self,
        constraints: &mut Self::Constraints,
        x: &[f64],
    ) -> Result<(), CoreError>;

    /// Corrects the positions `x` along M⁻¹Gᵀ until max |g(x)| ≤ `tol` by at most
    /// `iterations` quasi-Newton iterations with the current factor.
    fn solve_positions(
        &self,
        constraints: &mut Self::Constraints,
        x: &mut [f64],
        tol: f64,
        t: f64,
        iterations: usize,
    ) -> Result<(), CoreError>;

    /// Projects the velocities `v` onto G v = 0 along M⁻¹Gᵀ (G of the current factor).
    fn project_velocities(&self, constraints: &mut Self::Constraints, v: &mut [f64]);

    /// The applied forces F(t, x, v), one 3-vector per node (without the constraint forces);
    /// counts as one right-hand-side evaluation.
    fn forces<'w>(
        &self,
        t: f64,
        x: &[f64],
        v: &[f64],
        ws: &'w mut Self::Workspace,
    ) -> &'w [Vector3<f64>];

    /// out += scale · M⁻¹ f (f one 3-vector per node).
    fn add_inverse_mass(&self, f: &[Vector3<f64>], scale: f64, out: &mut [f64]);

    /// Whether the applied forces depend on the velocities (damping, contact).
    fn velocity_dependent_forces(&self) -> bool;
}

/// A second-order system of nodes with ground contact split into an explicit and an implicit
/// part (module docs). The state is y = (x, v), each half 3 coordinates per node.
pub trait ContactSystem: System {
    /// Whether the contact law has a velocity-dependent part to treat implicitly (penalty and
    /// stick grounds); without it f_I = 0 and f_E = f.
    fn splits_contact(&self) -> bool;

    /// The number m of contact points (zero without a ground).
    fn contact_points(&self) -> usize;

    /// The node of contact point `k` (< m).
    fn contact_node(&self, k: usize) -> usize;

    /// The ground's unit normal n̂ (zero without a ground).
    fn ground_normal(&self) -> Vector3<f64>;

    /// The height h(p) = n̂·(p − x₀) of a point above the ground plane (negative below it).
    fn ground_height(&self, p: &Vector3<f64>) -> f64;

    /// The height below which a contact point counts as touching.
    fn touch_height(&self) -> f64;

    /// The contact force F_c(p, u) of contact point `k` at position `p` and velocity `u` (its
    /// friction anchor from `ws`).
    fn contact_force(
        &self,
        ws: &Self::Workspace,
        k: usize,
        p: &Vector3<f64>,
        u: &Vector3<f64>,
    ) -> Vector3<f64>;

    /// ∂F_c/∂v of contact point `k` at (p, u) (zero where it carries no force).
    fn contact_damping(
        &self,
        ws: &Self::Workspace,
        k: usize,
        p: &Vector3<f64>,
        u: &Vector3<f64>,
    ) -> Matrix3<f64>;

    /// dy = f_E(t, y) with the held forces `held` (per contact point; missing ones zero) when
    /// the contact splits, else f. Returns the power (normal, tangential) of f_E's
    /// non-conservative contact forces: the held force and the tangential part of
    /// F_c(x, 0).
    fn rhs_explicit(
        &self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        ws: &mut Self::Workspace,
        held: &[Vector3<f64>],
    ) -> Result<(f64, f64), CoreError>;

    /// Prepares [`respond`](Self::respond) at positions `x` (factors the constraint system
    /// unless it is current there).
    fn prepare_response(&self, ws: &mut Self::Workspace, x: &[f64]) -> Result<(), CoreError>;

    /// out = P_C(x) F: the accelerations (one 3-vector per node) of the forces `forces`
    /// (per node, nonzero on the nodes `touched` only) at positions `x` and zero velocities,
    /// the constraint forces that keep g(x) = 0 included (left added to `forces`). Needs
    /// [`prepare_response`](Self::prepare_response) at `x`.
    fn respond(
        &self,
        ws: &mut Self::Workspace,
        x: &[f64],
        forces: &mut [Vector3<f64>],
        touched: &[usize],
        out: &mut [f64],
    );

    /// The kinetic energy ½ vᵀ M v of the state `y`.
    fn kinetic_energy(&self, y: &[f64]) -> f64;

    /// The contact's non-conservative work (normal, tangential) as integrated by a method that
    /// applies the contact itself (`None` where the right-hand side evaluates it).
    fn contact_work(&self, ws: &Self::Workspace) -> Option<(f64, f64)>;

    /// Sets the contact work of [`contact_work`](Self::contact_work).
    fn set_contact_work(&self, ws: &mut Self::Workspace, work: (f64, f64));
}

/// Node `i` of a nodal state half: y\[3i..3i+3\].
#[inline]
pub(crate) fn vec3(y: &[f64], i: usize) -> Vector3<f64> {
    Vector3::new(y[3 * i], y[3 * i + 1], y[3 * i + 2])
}

/// Sets node `i` of a nodal state half.
#[inline]
pub(crate) fn set3(y: &mut [f64], i: usize, v: &Vector3<f64>) {
    y[3 * i] = v.x;
    y[3 * i + 1] = v.y;
    y[3 * i + 2] = v.z;
}
