//! Rolling down an incline: the full tensegrity model.
//!
//! The prestressed toroid (bars rigid with mass = bar density × length, strings linear elastic
//! with the rest lengths that realise a prestress design) is integrated with the core's
//! rigid-bar dynamics N̈M + NK = W + ΩPᵀ (class-2 rim joints as constrained class-1 copies).
//! In the wheel frame the incline is the plane z = −R_o under the starting contact pair, and
//! gravity is tilted by the slope angle φ: g = g₀ (0, sin φ, −cos φ), so the wheel rolls
//! towards +y about the x axis. Only the outer tread nodes (n1, n2 of every prism) can touch
//! the ground, through either the thesis contact model (weight-based normal reaction plus
//! velocity damping, §3.2.2) or a penalty spring–damper with regularised Coulomb friction.
//!
//! Recorded per sample: the axle (hub: the midpoint of the axle bar with spokes, else the
//! centroid of the rim joints) along the slope s = y and above it h = z + R_o, the spin
//! ω = mean over rim joints of ((r − hub) × (v − v_hub))ₓ / ‖r − hub‖², the summed contact
//! force (normal = z, tangential = y components) and the slip, the mean in-plane speed of the
//! contact nodes that carry load.

use crate::analysis::{prestress_design, prestressed_structure};
use crate::builder::Toroid;
use crate::error::{Result, ToroidError};
use crate::rolling::{summarise, RollingResult, RollingSample};
use nalgebra::Vector3;
use tensegrity_core::dynamics::{
    Ground, GroundModel, IntegratorKind, Quantities, Simulation, SimulationSettings,
};

/// The ground contact of the full model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactModel {
    /// Thesis §3.2.2: damping c (N·s/m) drives contact-node velocities to zero.
    Thesis {
        /// Damping of the contact-node velocities (N·s/m).
        damping: f64,
    },
    /// Penalty normal spring–damper with regularised Coulomb friction.
    Penalty {
        /// Normal stiffness (N/m).
        stiffness: f64,
        /// Normal damping (N·s/m).
        damping: f64,
        /// Static friction coefficient.
        mu_static: f64,
        /// Kinetic friction coefficient.
        mu_kinetic: f64,
    },
}

/// Settings of a full-model rolling run.
#[derive(Debug, Clone, PartialEq)]
pub struct FullRolling {
    /// Slope angle φ (rad).
    pub incline: f64,
    /// Gravity g₀ (m/s²).
    pub gravity: f64,
    /// Ground contact.
    pub contact: ContactModel,
    /// String stiffness (N/m).
    pub string_stiffness: f64,
    /// Smallest string tension of the prestress design (N).
    pub min_string_tension: f64,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Step of the fixed-step integrators, largest step of RK45 (s).
    pub dt: f64,
    /// Output interval (s).
    pub output_dt: f64,
}

impl Default for FullRolling {
    /// 50° slope, penalty ground (10⁵ N/m, 200 N·s/m, μ 0.8/0.6), strings 2·10⁴ N/m with
    /// a 20 N minimum prestress, RK4 at 0.1 ms, 1 ms output.
    fn default() -> Self {
        Self {
            incline: 50f64.to_radians(),
            gravity: 9.81,
            contact: ContactModel::Penalty {
                stiffness: 1e5,
                damping: 200.0,
                mu_static: 0.8,
                mu_kinetic: 0.6,
            },
            string_stiffness: 2e4,
            min_string_tension: 20.0,
            integrator: IntegratorKind::Rk4,
            dt: 1e-4,
            output_dt: 1e-3,
        }
    }
}

impl FullRolling {
    /// Rolls `toroid` for `t_end` seconds from rest on its prism-0 contact pair.
    pub fn run(&self, toroid: &Toroid, t_end: f64) -> Result<RollingResult> {
        for (name, v) in [
            ("gravity", self.gravity),
            ("dt", self.dt),
            ("output_dt", self.output_dt),
            ("t_end", t_end),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ToroidError::InvalidParameter {
                    name,
                    value: v,
                    reason: "must be positive".into(),
                });
            }
        }
        if !(self.incline.is_finite() && self.incline.abs() < std::f64::consts::FRAC_PI_2) {
            return Err(ToroidError::InvalidParameter {
                name: "incline",
                value: self.incline,
                reason: "must lie in (−π/2, π/2)".into(),
            });
        }
        let design = prestress_design(toroid, self.min_string_tension)?;
        let (sin, cos) = self.incline.sin_cos();
        let structure = prestressed_structure(toroid, &design, self.string_stiffness)?
            .to_builder()
            .gravity([0.0, self.gravity * sin, -self.gravity * cos])
            .build()?;
        let r_o = toroid.params.outer_radius;
        let n = toroid.params.sides;
        let model = match self.contact {
            ContactModel::Thesis { damping } => GroundModel::Thesis {
                damping,
                tolerance: 1e-6 * r_o,
            },
            ContactModel::Penalty {
                stiffness,
                damping,
                mu_static,
                mu_kinetic,
            } => GroundModel::Penalty {
                stiffness,
                damping,
                mu_static,
                mu_kinetic,
                regularization_velocity: 1e-3,
                stribeck_velocity: 1e-2,
            },
        };
        let mut ground = Ground::new(Vector3::new(0.0, 0.0, -r_o), Vector3::z(), model);
        ground.nodes = Some((0..n).flat_map(|k| [5 * k, 5 * k + 1]).collect());
        let settings = SimulationSettings {
            t_end,
            integrator: self.integrator,
            dt: self.dt,
            output_interval: Some(self.output_dt),
            quantities: Quantities {
                nodes: true,
                velocities: true,
                contact_forces: true,
                energy: true,
                member_forces: false,
            },
            ..Default::default()
        };
        let mut sim = Simulation::new(&structure, settings).map_err(dynamics_error)?;
        sim.model.set_ground(ground).map_err(dynamics_error)?;
        let result = sim.run().map_err(dynamics_error)?;

        let rim: Vec<usize> = (0..n).map(|k| 5 * k + 2).collect();
        let hub_of = |x: &[Vector3<f64>]| match toroid.axle {
            Some([a, b]) => 0.5 * (x[a] + x[b]),
            None => rim.iter().map(|&i| x[i]).sum::<Vector3<f64>>() / n as f64,
        };
        let mut samples = Vec::with_capacity(result.samples.len());
        let mut in_contact = vec![false; n];
        let mut impacts = 0;
        for smp in &result.samples {
            let (Some(x), Some(v)) = (&smp.nodes, &smp.velocities) else {
                continue;
            };
            let hub = hub_of(x);
            let v_hub = hub_of(v);
            let omega = rim
                .iter()
                .map(|&i| {
                    let r = x[i] - hub;
                    let w = v[i] - v_hub;
                    (r.y * w.z - r.z * w.y) / (r.y * r.y + r.z * r.z)
                })
                .sum::<f64>()
                / n as f64;
            let mut force = Vector3::zeros();
            let mut pivot = f64::NAN;
            let mut strongest = 0.0;
            let mut touching = vec![false; n];
            let (mut slip_sum, mut slip_count) = (0.0, 0usize);
            for (node, f) in smp.contact_forces.iter().flatten() {
                force += f;
                if f.z > 0.0 {
                    // sliding speed in the slope plane (z is the slope normal)
                    slip_sum += v[*node].xy().norm();
                    slip_count += 1;
                }
                if f.z > 0.0 {
                    touching[node / 5] = true;
                }
                if f.z > strongest {
                    strongest = f.z;
                    pivot = x[*node].y;
                }
            }
            impacts += touching
                .iter()
                .zip(&in_contact)
                .filter(|(now, before)| **now && !**before)
                .count();
            in_contact = touching;
            samples.push(RollingSample {
                t: smp.t,
                s: hub.y,
                h: hub.z + r_o,
                pivot,
                // the wheel rolls towards +y, i.e. with a negative x spin
                omega: -omega,
                normal: force.z,
                tangential: force.y,
                energy: smp.energy.map_or(f64::NAN, |(_, total)| total),
                slip: if slip_count > 0 {
                    slip_sum / slip_count as f64
                } else {
                    0.0
                },
            });
        }
        if samples.is_empty() {
            return Err(ToroidError::InvalidParameter {
                name: "output_dt",
                value: self.output_dt,
                reason: "no sample was recorded".into(),
            });
        }
        // the first sample's pair counts as the starting contact, not an impact
        Ok(summarise(
            samples,
            impacts.saturating_sub(1),
            self.output_dt,
        ))
    }
}

fn dynamics_error(e: tensegrity_core::CoreError) -> ToroidError {
    ToroidError::Dynamics(e.to_string())
}

/// Which model a rolling run uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fidelity {
    /// The reduced rigid polygon ([`crate::rolling::RigidRolling`]).
    Rigid,
    /// The full tensegrity dynamics ([`FullRolling`]).
    Full,
}

/// The strain ε = m g / (k R_o) that one string of stiffness k would take carrying the whole
/// wheel weight over the wheel radius: a cheap measure of how much the wheel deforms.
pub fn deformation_measure(
    mass: f64,
    gravity: f64,
    string_stiffness: f64,
    outer_radius: f64,
) -> f64 {
    mass * gravity / (string_stiffness * outer_radius)
}

/// Below this [`deformation_measure`] the `auto` fidelity picks the rigid model.
pub const RIGID_THRESHOLD: f64 = 1e-3;

/// The fidelity `auto` picks: rigid when [`deformation_measure`] < [`RIGID_THRESHOLD`].
///
/// ```
/// use toroid::rolling_full::{auto_fidelity, Fidelity};
/// assert_eq!(auto_fidelity(14.4, 9.81, 2e4, 1.0), Fidelity::Full);
/// assert_eq!(auto_fidelity(14.4, 9.81, 2e6, 1.0), Fidelity::Rigid);
/// ```
pub fn auto_fidelity(
    mass: f64,
    gravity: f64,
    string_stiffness: f64,
    outer_radius: f64,
) -> Fidelity {
    if deformation_measure(mass, gravity, string_stiffness, outer_radius) < RIGID_THRESHOLD {
        Fidelity::Rigid
    } else {
        Fidelity::Full
    }
}
