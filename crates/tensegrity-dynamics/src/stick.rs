//! Friction that sticks: the penalty ground with an elastic–plastic tangential spring per
//! contact node ([`GroundModel::Stick`]).
//!
//! The regularised Coulomb law of [`GroundModel::Penalty`] is a stiff viscous law below
//! v_reg: under a tangential load it creeps at v = v_reg artanh(F_t / μ f_n) and never holds a
//! stick. Here every contact node that touches the plane gets an **anchor** a on the plane (the
//! point where it stuck); between the node's foot point p = x − h(x) n (h the signed height,
//! n the unit normal) and the anchor sits a tangential spring–damper capped by Coulomb's law.
//! For penetration δ = −h(x) > 0, with v_n = v·n and v_t = v − v_n n:
//!
//! * normal force f_n = max(0, k δ − c v_n) (the penalty law, never pulling);
//! * trial tangential force F* = −k_t (p − a) − c_t v_t;
//! * tangential force F_t = F* if ‖F*‖ ≤ μ f_n, else μ f_n F*/‖F*‖ (the cap), with μ = μ_s while
//!   the anchor holds and μ = μ_k while it slides;
//! * the force on the node F = f_n n + F_t; without penetration, or with f_n = 0, F = 0.
//!
//! **Anchor update** (after every accepted step, [`Model::update_contact_anchors`], called by
//! the simulation driver; the anchors are constant inside a step, the force is continuous in
//! the state): a node off the plane (δ ≤ 0) loses its anchor; a node that touches without an
//! anchor gets one at its foot point (an unstretched spring); otherwise, with u = p − a, the
//! anchor holds while k_t ‖u‖ ≤ μ f_n (μ = μ_s if it held at the last step, μ_k if it slid),
//! else it slides: a ← p − (μ_k f_n / k_t) u/‖u‖ (the spring then carries the kinetic
//! friction μ_k f_n) and the node counts as sliding until a step ends with the spring inside
//! its cap.
//!
//! So a node under a tangential load below μ_s f_n does not move along the plane beyond the
//! spring's elastic stretch ‖F_t‖/k_t (no creep): a block on a slope of angle φ < atan μ_s rests
//! at the stretch m g sin φ / k_t, exactly. The spring stores ½ k_t ‖u‖² (not part of the
//! model's potential energy: its work is friction work).
//!
//! [`Ground::contact_jacobian`] gives ∂F/∂x and ∂F/∂v for the linearly implicit integrator
//! ([`super::imex`]): −k n nᵀ − k_t T and −c n nᵀ − c_t T (T = I − n nᵀ) in stick; in slip the
//! normal part and the dependence of the cap on f_n along the sliding direction.

pub use super::anchor::Anchor;
use super::forces::{Ground, GroundModel};
use super::model::{vec3, Model, Workspace};
use nalgebra::{Matrix3, Vector3};

/// The parameters of [`GroundModel::Stick`]: (k, c, μ_s, μ_k, k_t, c_t).
type StickLaw = (f64, f64, f64, f64, f64, f64);

fn stick_law(model: &GroundModel) -> Option<StickLaw> {
    match *model {
        GroundModel::Stick {
            stiffness,
            damping,
            mu_static,
            mu_kinetic,
            tangential_stiffness,
            tangential_damping,
        } => Some((
            stiffness,
            damping,
            mu_static,
            mu_kinetic,
            tangential_stiffness,
            tangential_damping,
        )),
        _ => None,
    }
}

impl Ground {
    /// Foot point of `x` on the plane.
    #[inline]
    fn foot(&self, x: &Vector3<f64>) -> Vector3<f64> {
        x - self.normal * self.height(x)
    }

    /// Force of the stick law on a node at `x` moving with `v`, attached to `anchor` (module
    /// docs); the penalty force for the other ground models.
    pub fn stick_force(
        &self,
        x: &Vector3<f64>,
        v: &Vector3<f64>,
        anchor: Option<&Anchor>,
    ) -> Vector3<f64> {
        let Some((k, c, mu_s, mu_k, kt, ct)) = stick_law(&self.model) else {
            return self.penalty_force(x, v);
        };
        let delta = -self.height(x);
        if delta <= 0.0 {
            return Vector3::zeros();
        }
        let n = self.normal;
        let vn = v.dot(&n);
        let fn_ = (k * delta - c * vn).max(0.0);
        if fn_ == 0.0 {
            return Vector3::zeros();
        }
        let vt = v - n * vn;
        let stretch = anchor.map_or_else(Vector3::zeros, |a| self.foot(x) - a.point);
        let trial = -stretch * kt - vt * ct;
        let mu = if anchor.is_some_and(|a| a.sliding) {
            mu_k
        } else {
            mu_s
        };
        let cap = mu * fn_;
        let size = trial.norm();
        let ft = if size > cap {
            trial * (cap / size)
        } else {
            trial
        };
        n * fn_ + ft
    }

    /// The anchor of a node at `x` moving with `v` after an accepted step, from its anchor
    /// before (module docs); `None` off the plane and for the other ground models.
    pub fn stick_anchor(
        &self,
        x: &Vector3<f64>,
        v: &Vector3<f64>,
        anchor: Option<Anchor>,
    ) -> Option<Anchor> {
        let (k, c, mu_s, mu_k, kt, _) = stick_law(&self.model)?;
        let delta = -self.height(x);
        if delta <= 0.0 {
            return None;
        }
        let p = self.foot(x);
        let Some(a) = anchor else {
            return Some(Anchor {
                point: p,
                sliding: false,
            });
        };
        let fn_ = (k * delta - c * v.dot(&self.normal)).max(0.0);
        let u = p - a.point;
        let size = u.norm();
        let mu = if a.sliding { mu_k } else { mu_s };
        if kt > 0.0 && kt * size <= mu * fn_ {
            return Some(Anchor {
                point: a.point,
                sliding: false,
            });
        }
        let trail = if kt > 0.0 && size > 0.0 {
            (mu_k * fn_ / kt).min(size) / size
        } else {
            0.0
        };
        Some(Anchor {
            point: p - u * trail,
            sliding: true,
        })
    }

    /// The contact force's Jacobians (∂F/∂x, ∂F/∂v) of a node at `x` moving with `v` (module
    /// docs; for the penalty law the slopes of its regularised friction);
    /// `None` when the node carries no force (off the plane, or the thesis model).
    pub fn contact_jacobian(
        &self,
        x: &Vector3<f64>,
        v: &Vector3<f64>,
        anchor: Option<&Anchor>,
    ) -> Option<(Matrix3<f64>, Matrix3<f64>)> {
        let delta = -self.height(x);
        if delta <= 0.0 {
            return None;
        }
        let n = self.normal;
        let nn = n * n.transpose();
        let t = Matrix3::identity() - nn;
        let vn = v.dot(&n);
        let (k, c, tangential) = match self.model {
            GroundModel::Thesis { .. } => return None,
            GroundModel::Penalty {
                stiffness,
                damping,
                mu_static,
                regularization_velocity,
                ..
            } => {
                // F_t = −μ f_n tanh(s/v_reg) ŝ: slope μ f_n sech²(s/v_reg)/v_reg along ŝ,
                // μ f_n tanh(s/v_reg)/s across it (μ's Stribeck variation left out)
                let fn_ = (stiffness * delta - damping * vn).max(0.0);
                let vt = v - n * vn;
                let s = vt.norm();
                let r = s / regularization_velocity;
                let along = mu_static * fn_ / (regularization_velocity * r.cosh().powi(2));
                let tv = if s > 0.0 {
                    let e = vt / s;
                    let across = mu_static * fn_ * r.tanh() / s;
                    let ee = e * e.transpose();
                    (t - ee) * -across - ee * along
                } else {
                    t * -(mu_static * fn_ / regularization_velocity)
                };
                (stiffness, damping, (Matrix3::zeros(), tv))
            }
            GroundModel::Stick { .. } => {
                let (k, c, mu_s, mu_k, kt, ct) = stick_law(&self.model)?;
                let fn_ = (k * delta - c * vn).max(0.0);
                let stretch = anchor.map_or_else(Vector3::zeros, |a| self.foot(x) - a.point);
                let trial = -stretch * kt - (v - n * vn) * ct;
                let mu = if anchor.is_some_and(|a| a.sliding) {
                    mu_k
                } else {
                    mu_s
                };
                let size = trial.norm();
                let tangential = if size <= mu * fn_ {
                    (t * -kt, t * -ct)
                } else {
                    // slip: F_t = μ f_n ŝ, its size follows f_n
                    let s = trial * (mu / size);
                    (s * n.transpose() * -k, s * n.transpose() * -c)
                };
                (k, c, tangential)
            }
        };
        if (k * delta - c * vn) <= 0.0 {
            return None;
        }
        Some((nn * -k + tangential.0, nn * -c + tangential.1))
    }
}

impl Model {
    /// Moves the friction anchors of `ws` to the accepted state `y` (module docs); returns
    /// whether the ground has anchors at all ([`GroundModel::Stick`]).
    pub fn update_contact_anchors(&self, y: &[f64], ws: &mut Workspace) -> bool {
        let Some(g) = &self.ground else {
            return false;
        };
        if stick_law(&g.model).is_none() {
            return false;
        }
        let (x, v) = y.split_at(3 * self.n1);
        for (k, &(_, c)) in self.contact.iter().enumerate() {
            ws.anchors[k] = g.stick_anchor(&vec3(x, c), &vec3(v, c), ws.anchors[k]);
        }
        true
    }

    /// The friction anchors of the contact nodes (one per node of [`Ground::nodes`] that is
    /// on a bar, in that order).
    pub fn contact_anchors<'w>(&self, ws: &'w Workspace) -> &'w [Option<Anchor>] {
        &ws.anchors
    }
}
