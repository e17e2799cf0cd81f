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
use crate::defaults;
use crate::error::{Result, ToroidError};
use crate::rolling::{summarise, RollingResult, RollingSample};
use nalgebra::Vector3;
use tensegrity_core::dynamics::{
    Ground, GroundModel, IntegratorKind, Quantities, Simulation, SimulationResult,
    SimulationSettings,
};
use tensegrity_core::Structure;

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

/// Relative tolerance of the adaptive integrators (rk45, sdirk) in a rolling run: positions
/// to about 1 µm on a metre-sized wheel.
pub const ADAPTIVE_RTOL: f64 = 1e-6;
/// Absolute tolerance of the adaptive integrators in a rolling run.
pub const ADAPTIVE_ATOL: f64 = 1e-8;

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

impl ContactModel {
    /// The thesis contact with the default damping [`defaults::GROUND_DAMPING`].
    pub const THESIS: ContactModel = ContactModel::Thesis {
        damping: defaults::GROUND_DAMPING,
    };

    /// The penalty ground with the defaults of [`crate::defaults`]: stiffness 10⁵ N/m,
    /// damping 200 N·s/m, μ_s = 0.8 and μ_k = 0.75 μ_s = 0.6.
    pub const PENALTY: ContactModel = ContactModel::Penalty {
        stiffness: defaults::GROUND_STIFFNESS,
        damping: defaults::GROUND_DAMPING,
        mu_static: defaults::STATIC_FRICTION,
        mu_kinetic: defaults::KINETIC_FRICTION_RATIO * defaults::STATIC_FRICTION,
    };
}

impl Default for FullRolling {
    /// 50° slope, penalty ground ([`ContactModel::PENALTY`]), strings 2·10⁴ N/m with a 20 N
    /// minimum prestress, RK4 at 0.1 ms, 1 ms output (the values of [`crate::defaults`]).
    fn default() -> Self {
        Self {
            incline: defaults::INCLINE_DEG.to_radians(),
            gravity: defaults::GRAVITY,
            contact: ContactModel::PENALTY,
            string_stiffness: defaults::STRING_STIFFNESS,
            min_string_tension: defaults::ROLL_MIN_TENSION,
            integrator: IntegratorKind::Rk4,
            dt: defaults::ROLL_DT,
            output_dt: defaults::ROLL_OUTPUT_DT,
        }
    }
}

impl FullRolling {
    /// Rolls `toroid` for `t_end` seconds from rest on its prism-0 contact pair.
    pub fn run(&self, toroid: &Toroid, t_end: f64) -> Result<RollingResult> {
        self.validate(t_end)?;
        let (structure, ground) = self.model(toroid)?;
        let d = SimulationSettings::default();
        let settings = SimulationSettings {
            t_end,
            integrator: self.integrator,
            dt: self.dt,
            rtol: if self.integrator.is_adaptive() {
                ADAPTIVE_RTOL
            } else {
                d.rtol
            },
            atol: if self.integrator.is_adaptive() {
                ADAPTIVE_ATOL
            } else {
                d.atol
            },
            output_interval: Some(self.output_dt),
            quantities: Quantities {
                nodes: true,
                velocities: true,
                contact_forces: true,
                energy: true,
                member_forces: false,
            },
            ..d
        };
        let mut sim = Simulation::new(&structure, settings)?;
        sim.model.set_ground(ground)?;
        let result = sim.run()?;

        let (samples, impacts) = wheel_samples(toroid, &result);
        if samples.is_empty() {
            return Err(ToroidError::NoSamples {
                output_dt: self.output_dt,
            });
        }
        // the first sample's pair counts as the starting contact, not an impact
        Ok(summarise(
            samples,
            impacts.saturating_sub(1),
            self.output_dt,
        ))
    }

    fn validate(&self, t_end: f64) -> Result<()> {
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
        Ok(())
    }

    /// The prestressed structure under the tilted gravity, and the ground under prism 0.
    fn model(&self, toroid: &Toroid) -> Result<(Structure, Ground)> {
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
        Ok((structure, ground))
    }
}

/// The wheel's samples of a simulation (hub, spin, summed contact force, slip) and the number
/// of contact-pair touch-downs (the first sample's pair included).
fn wheel_samples(toroid: &Toroid, result: &SimulationResult) -> (Vec<RollingSample>, usize) {
    let n = toroid.params.sides;
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
        let (hub, v_hub) = (hub_of(x), hub_of(v));
        let omega = rim
            .iter()
            .map(|&i| {
                let r = x[i] - hub;
                let w = v[i] - v_hub;
                (r.y * w.z - r.z * w.y) / (r.y * r.y + r.z * r.z)
            })
            .sum::<f64>()
            / n as f64;
        let c = contact_of(smp.contact_forces.iter().flatten(), x, v, n);
        impacts += c
            .touching
            .iter()
            .zip(&in_contact)
            .filter(|(now, before)| **now && !**before)
            .count();
        in_contact = c.touching;
        samples.push(RollingSample {
            t: smp.t,
            s: hub.y,
            h: hub.z + toroid.params.outer_radius,
            pivot: c.pivot,
            // the wheel rolls towards +y, i.e. with a negative x spin
            omega: -omega,
            normal: c.force.z,
            tangential: c.force.y,
            energy: smp.energy.map_or(f64::NAN, |(_, total)| total),
            slip: c.slip,
        });
    }
    (samples, impacts)
}

/// The contact of one sample.
struct Contact {
    /// Summed contact force (N).
    force: Vector3<f64>,
    /// Slope coordinate y of the most loaded contact node (NaN without contact).
    pivot: f64,
    /// Which prisms touch the ground.
    touching: Vec<bool>,
    /// Mean in-plane speed of the loaded contact nodes (m/s).
    slip: f64,
}

fn contact_of<'a>(
    forces: impl Iterator<Item = &'a (usize, Vector3<f64>)>,
    x: &[Vector3<f64>],
    v: &[Vector3<f64>],
    n: usize,
) -> Contact {
    let mut force = Vector3::zeros();
    let mut pivot = f64::NAN;
    let mut strongest = 0.0;
    let mut touching = vec![false; n];
    let (mut slip_sum, mut slip_count) = (0.0, 0usize);
    for (node, f) in forces {
        force += f;
        if f.z > 0.0 {
            // sliding speed in the slope plane (z is the slope normal)
            slip_sum += v[*node].xy().norm();
            slip_count += 1;
            touching[node / 5] = true;
        }
        if f.z > strongest {
            strongest = f.z;
            pivot = x[*node].y;
        }
    }
    let slip = if slip_count > 0 {
        slip_sum / slip_count as f64
    } else {
        0.0
    };
    Contact {
        force,
        pivot,
        touching,
        slip,
    }
}

/// Which model a rolling run uses; serialises as `"rigid"` or `"full"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
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
