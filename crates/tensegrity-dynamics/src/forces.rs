//! External forces: nodal loads, gravity on bar masses, and ground contact with an inclined
//! plane.
//!
//! Gravity acts as m_b g/2 at each end of every bar (ERRATA 3.8). The ground is the plane
//! through `point` with unit outward `normal`; a node at x has signed height
//! h = (x − point)·normal and penetration δ = −h.
//!
//! * [`GroundModel::Penalty`]: for δ > 0 the normal force is f_n = max(0, k δ − c v_n)
//!   (v_n = v·normal) and the friction is regularised Coulomb with a Stribeck transition from
//!   static to kinetic friction:
//!   f_t = −μ(‖v_t‖) f_n tanh(‖v_t‖/v_reg) v_t/‖v_t‖,
//!   μ(v) = μ_k + (μ_s − μ_k) exp(−(v/v_s)²). Potential energy ½ k δ².
//! * [`GroundModel::Thesis`] (thesis §3.2.2 with ERRATA 3.7): every node within `tolerance`
//!   of the plane (or below it) is a contact node; the contact nodes share equally the normal
//!   reaction equal and opposite to the normal component of the total weight, and a damping
//!   force −c v drives their velocities to zero (the thesis damps the in-plane tangential and
//!   normal components; we damp all three). Not conservative.
//! * [`GroundModel::Stick`]: the penalty normal force with an elastic–plastic tangential
//!   spring per node that holds a stick up to μ_s f_n (module [`super::stick`]).

use nalgebra::Vector3;

/// How the ground reacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GroundModel {
    /// Thesis §3.2.2: weight-based normal reaction plus velocity damping at contact nodes.
    Thesis {
        /// Damping c (N·s/m) of the contact-node velocity.
        damping: f64,
        /// Distance (m) under which a node counts as touching.
        tolerance: f64,
    },
    /// Penalty spring–damper on penetration plus regularised Coulomb friction.
    Penalty {
        /// Normal stiffness k (N/m).
        stiffness: f64,
        /// Normal damping c (N·s/m); the normal force is clipped at zero (no adhesion).
        damping: f64,
        /// Static friction coefficient μ_s.
        mu_static: f64,
        /// Kinetic friction coefficient μ_k.
        mu_kinetic: f64,
        /// Regularisation velocity v_reg (m/s) of the tanh friction law.
        regularization_velocity: f64,
        /// Stribeck velocity v_s (m/s) of the static→kinetic transition.
        stribeck_velocity: f64,
    },
    /// Penalty spring–damper on penetration with friction that sticks: an elastic–plastic
    /// tangential spring per node, anchored on the plane (equations in [`super::stick`]).
    Stick {
        /// Normal stiffness k (N/m).
        stiffness: f64,
        /// Normal damping c (N·s/m); the normal force is clipped at zero (no adhesion).
        damping: f64,
        /// Static friction coefficient μ_s (the cap while the anchor holds).
        mu_static: f64,
        /// Kinetic friction coefficient μ_k (the cap while the anchor slides).
        mu_kinetic: f64,
        /// Tangential spring stiffness k_t (N/m).
        tangential_stiffness: f64,
        /// Tangential damping c_t (N·s/m).
        tangential_damping: f64,
    },
}

/// A ground plane and the nodes that can touch it.
#[derive(Debug, Clone, PartialEq)]
pub struct Ground {
    /// A point on the plane.
    pub point: Vector3<f64>,
    /// Unit outward normal (the side the structure lives on).
    pub normal: Vector3<f64>,
    /// Reaction model.
    pub model: GroundModel,
    /// Nodes (file numbering) that can touch the ground; `None` = every node.
    pub nodes: Option<Vec<usize>>,
}

impl Ground {
    /// A horizontal-or-inclined plane through `point` with normal `normal` (normalised here).
    pub fn new(point: Vector3<f64>, normal: Vector3<f64>, model: GroundModel) -> Self {
        Self {
            point,
            normal: normal.normalize(),
            model,
            nodes: None,
        }
    }

    /// Signed height of `x` above the plane.
    #[inline]
    pub fn height(&self, x: &Vector3<f64>) -> f64 {
        (x - self.point).dot(&self.normal)
    }

    /// Penalty-model force on a node at `x` moving with `v` (zero for the thesis model, whose
    /// reaction needs all contact nodes at once).
    #[inline]
    pub fn penalty_force(&self, x: &Vector3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
        let GroundModel::Penalty {
            stiffness,
            damping,
            mu_static,
            mu_kinetic,
            regularization_velocity,
            stribeck_velocity,
        } = self.model
        else {
            return Vector3::zeros();
        };
        let delta = -self.height(x);
        if delta <= 0.0 {
            return Vector3::zeros();
        }
        let vn = v.dot(&self.normal);
        let fn_ = (stiffness * delta - damping * vn).max(0.0);
        let mut f = self.normal * fn_;
        let vt = v - self.normal * vn;
        let speed = vt.norm();
        if speed > 0.0 && fn_ > 0.0 {
            let x = speed / stribeck_velocity;
            let mu = mu_kinetic + (mu_static - mu_kinetic) * (-x * x).exp();
            let scale = mu * fn_ * (speed / regularization_velocity).tanh() / speed;
            f -= vt * scale;
        }
        f
    }

    /// Potential energy stored in the ground spring at `x` (penalty model only).
    #[inline]
    pub fn potential(&self, x: &Vector3<f64>) -> f64 {
        match self.model {
            GroundModel::Penalty { stiffness, .. } | GroundModel::Stick { stiffness, .. } => {
                let delta = (-self.height(x)).max(0.0);
                0.5 * stiffness * delta * delta
            }
            GroundModel::Thesis { .. } => 0.0,
        }
    }
}
