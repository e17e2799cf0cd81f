//! Dynamic tip-over (thesis §3.3.2 checked with the full 3-D dynamics).
//!
//! The prestressed wheel stands on level ground resting on a side of its polygon (the outer
//! tread pairs of prisms 0 and n−1 touching, the hub at height h = R_o cos(π/n)), on a stiff
//! penalty ground with friction high enough that it tips before it slides. After a settling
//! time a lateral force F(t) along +ι̂₁ is ramped at the hub (half on each axle end with spokes,
//! else shared by the rim nodes, whose centroid is the hub), F = F_rate (t − t_settle).
//!
//! **Static threshold** for this pose: the wheel tips about the far tread edge (x = +T/2) when
//! the moment of F about it exceeds that of the weight, F h > m g T/2, i.e.
//!
//! > F_static = (m g / 2) (T / h),  h = R_o cos(π/n)
//!
//! (the thesis's (m g/2)(T/R_o) with the hub height of a wheel standing on a vertex).
//!
//! **Dynamic threshold**: the force at which the near tread edge (x = −T/2) unloads, i.e. its
//! summed normal contact force first reaches zero, located by linear interpolation between
//! output samples. For a quasi-static ramp it equals the static threshold up to the wheel's
//! elastic deformation and the ramp's inertia. The lean angle (the tilt of the wheel's axis,
//! the normal of the rim polygon, out of the horizontal plane, positive towards +ι̂₁ at the top)
//! is recorded at every sample.
//!
//! **Tipped** ([`tip_angle`]): a rigid wheel leaning by α about its far edge under the weight
//! and a lateral force F at the hub (the centre of mass) turns over when the resultant passes
//! outside the edge, h sin(α + ψ) > (T/2) cos(α + ψ) with tan ψ = F/(m g), i.e. beyond
//!
//! > α_c(F) = atan(T / 2h) − atan(F / (m g)),
//!
//! the static tip angle atan(T/2h) at F = 0, and 0 at the static threshold. The wheel has
//! `tipped` when, with its near edge lifted, its lean passes α_c of the force at that sample:
//! from there the load turns it over without any further increase.
//!
//! **Measured** (defaults, RK4 at 0.1 ms with the bar lengths and joints projected after every
//! step): the ramp's threshold is within 1.2 % of the static one for n = 8 … 16 and T = 0.2 …
//! 0.6 m (0.09 % for the reference wheel); a force held at 0.9–0.95 of it leaves the wheel
//! upright, at 1.1 it tips. Without the projection RK4 lets the stiff wheel's bar lengths drift
//! (10⁻⁵ in 0.5 s at rest, 10 % after a fall) and the thresholds came out 3–20 % low: every
//! report carries `valid`, `max_penetration` and the integrator's drift `warnings`.
//!
//! The friction law is regularised (μN tanh(v/v_reg)); its damping-like slope μN/v_reg must
//! stay within RK4's stability at the step (μ N dt / (v_reg m) ≲ 2.8), hence v_reg = 10⁻² m/s.

use crate::analysis::{analyse, prestress_design, prestressed_structure};
use crate::builder::Toroid;
use crate::error::{Result, ToroidError};
use nalgebra::{Rotation3, Vector3};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::CoreError;
use tensegrity_core::Warning;
use tensegrity_derive::{Columns, Params};
use tensegrity_dynamics::{
    Convergence, Ground, GroundModel, IntegratorKind, Quantities, Simulation, SimulationSettings,
};

/// Help texts shared by [`DynamicTipover`] and the request of the rolling tip-over.
pub(crate) mod help {
    /// `string_stiffness`.
    pub const STRING_STIFFNESS: &str = "String stiffness of the wheel: the threshold is the rigid one only for a stiff wheel (a soft one deforms and tips early)";
    /// `dt`, whose default differs between the standing and the rolling wheel.
    pub const DT: &str = "RK4 step; stiffer strings need a smaller one (default 1e-4 s for the standing wheel under a ramp, 2.5e-5 s for the rolling one, whose wobble coarser steps damp away)";
}

/// Settings of a dynamic tip-over run (flat serde form, flattened into
/// [`crate::request::TipoverDynamicRequest`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize, Params)]
#[params(order = "dt, output_dt, settle, ramp_time, ramp_to, hold")]
#[serde(default)]
pub struct DynamicTipover {
    /// Gravity (m/s²).
    #[param(number, unit = "m/s^2", help = "Gravity", positive)]
    pub gravity: f64,
    /// String stiffness of the prestressed wheel (N/m).
    #[param(number, unit = "N/m", help = crate::tipover_dynamic::help::STRING_STIFFNESS, positive)]
    pub string_stiffness: f64,
    /// Smallest string tension of the prestress (N).
    #[param(
        number,
        unit = "N",
        help = "Smallest string tension of the prestress",
        positive
    )]
    pub min_tension: f64,
    /// Axial damping of every string (N·s/m), so that the ramp's ringing dies out.
    #[param(
        number,
        unit = "N s/m",
        help = "Axial damping of every string",
        non_negative
    )]
    pub string_damping: f64,
    /// Penalty ground stiffness (N/m).
    #[param(number, unit = "N/m", help = "Penalty ground stiffness", positive)]
    pub ground_stiffness: f64,
    /// Penalty ground damping (N·s/m).
    #[param(number, unit = "N s/m", help = "Penalty ground damping", non_negative)]
    pub ground_damping: f64,
    /// Static friction coefficient (kinetic = 0.75 of it).
    #[param(
        number,
        help = "Static friction coefficient of the ground (kinetic = 0.75 μ)",
        non_negative
    )]
    pub mu: f64,
    /// Regularisation velocity of the friction law (m/s). Its damping-like slope μN/v_reg
    /// must stay within RK4's stability at `dt` (μ N dt / (v_reg m) ≲ 2.8), else the contact
    /// chatters.
    #[param(
        number,
        unit = "m/s",
        help = "Regularisation velocity of the friction law",
        positive
    )]
    pub friction_regularization: f64,
    /// Time at rest before the ramp starts (s).
    #[param(
        number,
        unit = "s",
        help = "Time at rest before the ramp starts",
        non_negative
    )]
    pub settle: f64,
    /// Duration of the ramp from 0 to `ramp_to` × the static threshold (s).
    #[param(
        number,
        unit = "s",
        help = "Ramp duration, from 0 to ramp_to × the static threshold",
        positive
    )]
    pub ramp_time: f64,
    /// Largest force of the ramp as a multiple of the static threshold.
    #[param(
        number,
        help = "Largest force of the ramp, as a multiple of the static threshold",
        positive
    )]
    pub ramp_to: f64,
    /// Time the force is held at its largest value after the ramp (s).
    #[param(
        number,
        unit = "s",
        help = "Time the largest force is held after the ramp",
        non_negative
    )]
    pub hold: f64,
    /// RK4 step (s).
    #[param(
        number,
        unit = "s",
        help = crate::tipover_dynamic::help::DT,
        positive
    )]
    pub dt: f64,
    /// Output interval (s).
    #[param(number, unit = "s", help = "Output interval of the history", positive)]
    pub output_dt: f64,
}

impl Default for DynamicTipover {
    /// A quasi-static ramp: 0.5 s settling, then 0 → 1.3 F_static over 4 s, stiff strings
    /// (2·10⁶ N/m) and ground (10⁶ N/m), μ_s = 1.
    fn default() -> Self {
        Self {
            gravity: crate::defaults::GRAVITY,
            string_stiffness: 2e6,
            min_tension: 2000.0,
            string_damping: 200.0,
            ground_stiffness: 1e6,
            ground_damping: 2e3,
            mu: 1.0,
            friction_regularization: 1e-2,
            settle: 0.5,
            ramp_time: 4.0,
            ramp_to: 1.3,
            hold: 0.0,
            dt: 1e-4,
            output_dt: 2e-3,
        }
    }
}

/// One recorded sample of a dynamic tip-over run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LeanSample {
    /// Time (s).
    pub t: f64,
    /// Lateral force at the hub (N).
    pub force: f64,
    /// Lean angle of the wheel (rad, positive towards +ι̂₁ at the top).
    pub lean: f64,
    /// Summed normal contact force on the near tread edge, x < 0 (N).
    pub near_normal: f64,
    /// Summed normal contact force on the far tread edge, x > 0 (N).
    pub far_normal: f64,
}

/// The result of [`DynamicTipover::run`]; serialises to the JSON of `tipover --dynamic`.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct DynamicTipoverReport {
    /// Number of sides n.
    pub sides: usize,
    /// Outer tread width T (m).
    #[column(unit = "m")]
    pub outer_tread: f64,
    /// Wheel mass (kg).
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// Hub height of the starting pose, R_o cos(π/n) (m).
    #[column(unit = "m")]
    pub hub_height: f64,
    /// (m g / 2)(T / h) (N).
    #[column(unit = "N")]
    pub static_threshold: f64,
    /// Lateral force at which the near tread edge unloads (N); `None` if it never does.
    #[column(unit = "N")]
    pub dynamic_threshold: Option<f64>,
    /// dynamic / static − 1.
    pub relative_difference: Option<f64>,
    /// Largest lean angle reached (rad).
    #[column(unit = "rad")]
    pub max_lean: f64,
    /// Lean at the end of the run (rad).
    #[column(unit = "rad")]
    pub final_lean: f64,
    /// The static tip angle atan(T / 2h) of the wheel at rest (rad): the lean at which its
    /// weight alone turns it over.
    #[column(unit = "rad")]
    pub static_tip_angle: f64,
    /// Whether the wheel tipped: its near edge lifted and its lean passed the tip angle of
    /// the load at that time, α_c(F) = atan(T/2h) − atan(F/(m g)) (module docs).
    pub tipped: bool,
    /// When it tipped (s).
    #[column(unit = "s")]
    pub tip_time: Option<f64>,
    /// Deepest contact node below the ground (m).
    #[column(unit = "m")]
    pub max_penetration: f64,
    /// No warning: the run stayed inside its model.
    pub valid: bool,
    /// What the run violated (penetration past 1 % of R_o, integrator drift, an unconverged
    /// quantity).
    pub warnings: Vec<Warning>,
    /// The headline quantities re-run at a companion resolution: twice the step and half the
    /// ground stiffness where 2 dt stays inside RK4's stability
    /// ([`DynamicTipover::coarse_refused`]), else half the step and twice the ground
    /// stiffness ([`crate::request::TipoverDynamicRequest`]); null when not checked.
    #[column(nested)]
    pub convergence: Option<Convergence>,
    /// The history (not serialised; `--out` writes it as CSV).
    #[serde(skip)]
    pub samples: Vec<LeanSample>,
}

/// The lean (rad) beyond which a rigid wheel of tread T and hub height h, loaded by a
/// lateral force `lateral` at its centre of mass against a `normal` weight component, turns
/// over about its edge: atan(T / 2h) − atan(lateral / normal) (module docs).
///
/// ```
/// use toroid::tipover_dynamic::tip_angle;
/// // at rest: the static tip angle; at the static threshold F = m g T / 2h: zero
/// assert!((tip_angle(0.4, 1.0, 0.0, 100.0) - 0.2f64.atan()).abs() < 1e-15);
/// assert!(tip_angle(0.4, 1.0, 20.0, 100.0).abs() < 1e-15);
/// ```
pub fn tip_angle(tread: f64, hub_height: f64, lateral: f64, normal: f64) -> f64 {
    (0.5 * tread / hub_height).atan() - lateral.atan2(normal)
}

/// What watches a ramp: (standing model, ground, t, nodes) per recorded sample.
pub type FrameWatch<'a> =
    dyn FnMut(&tensegrity_core::Structure, &Ground, f64, &[Vector3<f64>]) + 'a;

impl DynamicTipover {
    /// Runs the ramp on `toroid` (see the module docs).
    pub fn run(&self, toroid: &Toroid) -> Result<DynamicTipoverReport> {
        self.run_watched(toroid, None)
    }

    /// The time the ramp runs: settling, ramp and hold (s).
    pub fn t_end(&self) -> f64 {
        self.settle + self.ramp_time + self.hold
    }

    /// [`DynamicTipover::run`], handing `watch` the standing model, its ground and the nodes
    /// of every recorded sample (every `output_dt`, file numbering) after the run: what a
    /// front end animates.
    pub fn run_watched(
        &self,
        toroid: &Toroid,
        watch: Option<&mut FrameWatch<'_>>,
    ) -> Result<DynamicTipoverReport> {
        self.validate()?;
        let p = &toroid.params;
        let n = p.sides;
        let mass = analyse(toroid)?.mass_kg;
        let hub_height = p.outer_radius * (PI / n as f64).cos();
        let static_threshold = 0.5 * mass * self.gravity * p.outer_tread / hub_height;
        let (structure, ground) = self.standing_model(toroid, [0.0, 0.0, -self.gravity])?;
        let hubs = hub_nodes(toroid);
        let t_end = self.settle + self.ramp_time + self.hold;
        let mut sim = Simulation::new(&structure, self.settings(t_end))?;
        let floor = ground.clone();
        sim.model.set_ground(ground)?;
        let ramp = *self;
        let rate = self.ramp_to * static_threshold / self.ramp_time;
        let share = hubs.clone();
        sim.model.set_load_schedule(Box::new(move |t, f| {
            let force = ramp.force_at(t, rate);
            for &i in &share {
                f[i] = Vector3::new(force / share.len() as f64, 0.0, 0.0);
            }
        }));
        let result = sim.run().map_err(|e| diverged(e, self.dt))?;
        if let Some(watch) = watch {
            for s in &result.samples {
                if let Some(nodes) = &s.nodes {
                    watch(&structure, &floor, s.t, nodes);
                }
            }
        }
        let samples = lean_history(toroid, &result.samples, |t| self.force_at(t, rate));
        let validity = RunValidity::of(toroid, &result, hub_height);
        let weight = mass * self.gravity;
        Ok(report(
            toroid,
            (mass, weight),
            hub_height,
            static_threshold,
            samples,
            validity,
        ))
    }

    /// The prestressed, damped wheel resting on a side of its polygon on the plane z = −h,
    /// h = R_o cos(π/n), under `gravity`, and its penalty ground (outer tread pairs only).
    pub(crate) fn standing_model(
        &self,
        toroid: &Toroid,
        gravity: [f64; 3],
    ) -> Result<(tensegrity_core::Structure, Ground)> {
        let n = toroid.params.sides;
        let hub_height = toroid.params.outer_radius * (PI / n as f64).cos();
        let design = prestress_design(toroid, self.min_tension)?;
        let spin = Rotation3::from_axis_angle(&Vector3::x_axis(), PI / n as f64);
        let structure = prestressed_structure(toroid, &design, self.string_stiffness)?;
        let nodes: Vec<Vector3<f64>> = structure.nodes().iter().map(|x| spin * x).collect();
        let mut builder = structure.to_builder_without_strings();
        for s in structure.strings() {
            builder = builder.string(s.clone().damping(self.string_damping));
        }
        let structure = builder
            .build()?
            .with_nodes(nodes)?
            .to_builder()
            .gravity(gravity)
            .build()?;
        let mut ground = Ground::new(
            Vector3::new(0.0, 0.0, -hub_height),
            Vector3::z(),
            GroundModel::Penalty {
                stiffness: self.ground_stiffness,
                damping: self.ground_damping,
                mu_static: self.mu,
                mu_kinetic: crate::defaults::KINETIC_FRICTION_RATIO * self.mu,
                regularization_velocity: self.friction_regularization,
                stribeck_velocity: 3.0 * self.friction_regularization,
            },
        );
        ground.nodes = Some((0..n).flat_map(|k| [5 * k, 5 * k + 1]).collect());
        Ok((structure, ground))
    }

    /// F(t): zero while settling, then the ramp, then held.
    fn force_at(&self, t: f64, rate: f64) -> f64 {
        rate * (t - self.settle).clamp(0.0, self.ramp_time)
    }

    fn settings(&self, t_end: f64) -> SimulationSettings {
        SimulationSettings {
            t_end,
            integrator: IntegratorKind::Rk4,
            dt: self.dt,
            output_interval: Some(self.output_dt),
            // RK4 alone lets the stiff wheel's bar lengths drift (10⁻⁵ in 0.5 s at rest): project
            project: true,
            quantities: Quantities {
                nodes: true,
                velocities: false,
                contact_forces: true,
                energy: false,
                member_forces: false,
            },
            ..SimulationSettings::default()
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        use tensegrity_core::validate::{non_negative, positive};
        positive("gravity", self.gravity)?;
        positive("string_stiffness", self.string_stiffness)?;
        positive("min_tension", self.min_tension)?;
        positive("ground_stiffness", self.ground_stiffness)?;
        non_negative("ground_damping", self.ground_damping)?;
        non_negative("string_damping", self.string_damping)?;
        non_negative("mu", self.mu)?;
        positive("friction_regularization", self.friction_regularization)?;
        non_negative("settle", self.settle)?;
        positive("ramp_time", self.ramp_time)?;
        positive("ramp_to", self.ramp_to)?;
        non_negative("hold", self.hold)?;
        positive("dt", self.dt)?;
        positive("output_dt", self.output_dt)?;
        Ok(())
    }
}

/// Where the hub force goes: the axle ends with spokes, else the rim nodes (centroid = hub).
fn hub_nodes(toroid: &Toroid) -> Vec<usize> {
    match toroid.axle {
        Some([a, b]) => vec![a, b],
        None => (0..toroid.params.sides).map(|k| 5 * k + 2).collect(),
    }
}

/// The lean angle of the wheel (the tilt of its axis, the rim polygon's area vector, out of
/// the ground plane z, positive when the top moves towards +ι̂₁) and the hub (rim centroid).
pub(crate) fn lean_and_hub(x: &[Vector3<f64>], rim: &[usize]) -> (f64, Vector3<f64>) {
    let n = rim.len();
    let c = rim.iter().map(|&i| x[i]).sum::<Vector3<f64>>() / n as f64;
    let axis: Vector3<f64> = (0..n)
        .map(|k| (x[rim[k]] - c).cross(&(x[rim[(k + 1) % n]] - c)))
        .sum();
    let axis = if axis.x < 0.0 { -axis } else { axis };
    ((-axis.z).atan2(axis.x), c)
}

/// Lean angle and edge loads of every sample.
pub(crate) fn lean_history(
    toroid: &Toroid,
    samples: &[tensegrity_dynamics::Sample],
    force_at: impl Fn(f64) -> f64,
) -> Vec<LeanSample> {
    let n = toroid.params.sides;
    let rim: Vec<usize> = (0..n).map(|k| 5 * k + 2).collect();
    samples
        .iter()
        .filter_map(|s| {
            let x = s.nodes.as_ref()?;
            let (lean, c) = lean_and_hub(x, &rim);
            let (mut near, mut far) = (0.0, 0.0);
            for (node, f) in s.contact_forces.iter().flatten() {
                if x[*node].x < c.x {
                    near += f.z;
                } else {
                    far += f.z;
                }
            }
            Some(LeanSample {
                t: s.t,
                force: force_at(s.t),
                lean,
                near_normal: near,
                far_normal: far,
            })
        })
        .collect()
}

/// Whether a standing-wheel run stayed inside its model: the contact nodes no deeper below the
/// ground than [`crate::defaults::PENETRATION_TOLERANCE`] R_o, and no drift warning of the
/// core integrator. The penalty ground never pulls, so the normal force needs no check.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct RunValidity {
    /// Deepest contact node below the ground over the samples (m, ≥ 0).
    pub max_penetration: f64,
    /// What the run violated, one sentence each.
    pub warnings: Vec<Warning>,
}

impl RunValidity {
    /// The validity of a run of the wheel standing on the plane z = −`hub_height`.
    pub(crate) fn of(
        toroid: &Toroid,
        result: &tensegrity_dynamics::SimulationResult,
        hub_height: f64,
    ) -> Self {
        let n = toroid.params.sides;
        let max_penetration = result
            .samples
            .iter()
            .filter_map(|s| s.nodes.as_ref())
            .flat_map(|x| (0..n).flat_map(move |k| [x[5 * k].z, x[5 * k + 1].z]))
            .map(|z| -(z + hub_height))
            .fold(0.0, f64::max);
        let mut warnings: Vec<Warning> = result.warnings.iter().map(|&w| w.into()).collect();
        let tolerance = crate::defaults::PENETRATION_TOLERANCE * toroid.params.outer_radius;
        if max_penetration > tolerance {
            warnings.push(Warning::SankBelowGround {
                depth: max_penetration,
                tolerance,
            });
        }
        Self {
            max_penetration,
            warnings,
        }
    }
}

fn report(
    toroid: &Toroid,
    (mass_kg, weight): (f64, f64),
    hub_height: f64,
    static_threshold: f64,
    samples: Vec<LeanSample>,
    validity: RunValidity,
) -> DynamicTipoverReport {
    // the first unloading of the near edge while the force rises
    let dynamic_threshold = samples.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        (a.force > 0.0 && a.near_normal > 0.0 && b.near_normal <= 0.0).then(|| {
            let s = a.near_normal / (a.near_normal - b.near_normal);
            a.force + s * (b.force - a.force)
        })
    });
    let max_lean = samples.iter().map(|s| s.lean).fold(f64::MIN, f64::max);
    let final_lean = samples.last().map_or(0.0, |s| s.lean);
    let tread = toroid.params.outer_tread;
    let tip_time = samples
        .iter()
        .find(|s| s.near_normal <= 0.0 && s.lean > tip_angle(tread, hub_height, s.force, weight))
        .map(|s| s.t);
    DynamicTipoverReport {
        sides: toroid.params.sides,
        outer_tread: toroid.params.outer_tread,
        mass_kg,
        hub_height,
        static_threshold,
        dynamic_threshold,
        relative_difference: dynamic_threshold.map(|d| d / static_threshold - 1.0),
        max_lean,
        final_lean,
        static_tip_angle: tip_angle(tread, hub_height, 0.0, 1.0),
        tipped: tip_time.is_some(),
        tip_time,
        max_penetration: validity.max_penetration,
        valid: validity.warnings.is_empty(),
        warnings: validity.warnings,
        convergence: None,
        samples,
    }
}

/// The refinement of the timed runs' convergence check.
pub const REFINEMENT: &str = "dt/2, ground stiffness x2";

/// The coarsening of the timed runs' convergence check, where it serves
/// ([`DynamicTipover::coarse_refused`]).
pub const COARSENING: &str = "2 dt, ground stiffness / 2 (coarse companion)";

impl DynamicTipover {
    /// The same run at the refined resolution: half the step, twice the ground stiffness.
    pub fn refined(&self) -> Self {
        Self {
            dt: 0.5 * self.dt,
            ground_stiffness: 2.0 * self.ground_stiffness,
            ..*self
        }
    }

    /// The same run at the coarse resolution ([`COARSENING`]): twice the step, half the
    /// ground stiffness (the refined run's change undone), half the work.
    pub fn coarse(&self) -> Self {
        Self {
            dt: 2.0 * self.dt,
            ground_stiffness: 0.5 * self.ground_stiffness,
            ..*self
        }
    }

    /// Why the coarse companion does not serve this run on `toroid`, or `None` when it does:
    /// its step 2 dt must stay within the output interval and the run, and 2 dt·λ within
    /// [`STABILITY_MARGIN`](tensegrity_dynamics::convergence::STABILITY_MARGIN) × RK4's
    /// stability bound, λ the fastest rate of the standing wheel on the coarse ground
    /// ([`tensegrity_dynamics::convergence::explicit_rate`]: RK4 takes the ground's damper
    /// explicitly, 2c/m). On the defaults (10⁶ N/m, 2000 N·s/m) it does not: the damper's rate
    /// puts 2 dt far past the bound, and a run at 2·10⁻⁴ s reads a threshold of 26.6 N
    /// against 30.4 N at 10⁻⁴ s and 30.7 N at 5·10⁻⁵ s (each with its refined ground).
    pub fn coarse_refused(&self, toroid: &Toroid) -> Result<Option<String>> {
        use tensegrity_dynamics::convergence::{explicit_rate, stability_bound, STABILITY_MARGIN};
        let coarse = self.coarse();
        if coarse.dt > self.output_dt {
            return Ok(Some(format!(
                "2 dt exceeds the output interval {} s",
                self.output_dt
            )));
        }
        if coarse.dt > self.t_end() {
            return Ok(Some("2 dt exceeds the run".into()));
        }
        let (structure, ground) = coarse.standing_model(toroid, [0.0, 0.0, -self.gravity])?;
        let model = tensegrity_dynamics::Model::new(&structure, Some(ground))?;
        let rate = explicit_rate(&model, IntegratorKind::Rk4);
        let bound = stability_bound(IntegratorKind::Rk4).unwrap_or(0.0);
        let reach = coarse.dt * rate;
        // (a NaN rate refuses it too)
        if reach.is_nan() || reach > STABILITY_MARGIN * bound {
            return Ok(Some(format!(
                "2 dt times λ, {reach:.3}, exceeds {STABILITY_MARGIN} × rk4's stability bound {bound}"
            )));
        }
        Ok(None)
    }
}

impl DynamicTipoverReport {
    /// The convergence of this report's headline quantities against the `refined` run's:
    /// the dynamic threshold and the tip time within 2 %, the largest and the final lean
    /// within 5 % (on a scale of at least 0.01 rad), and whether it tipped.
    pub fn convergence(&self, refined: &Self) -> Convergence {
        self.convergence_with(refined, Convergence::new(REFINEMENT))
    }

    /// As [`DynamicTipoverReport::convergence`] against a `companion` of either resolution,
    /// into the empty comparison `c` (its label, companion, order and cost): the order is 1
    /// for both (measured: the threshold reads 30.44, 30.71 and 30.73 N at (dt, k) = (1, ½,
    /// ¼)·10⁻⁴ s × (1, 2, 4)·10⁶ N/m, changes that fall fourteenfold, faster than order 1: a
    /// quasi-static ramp has no landing whose duration moves as k^(−½)).
    pub fn convergence_with(&self, refined: &Self, mut c: Convergence) -> Convergence {
        let lean_scale = 0.01;
        c.compare(
            "dynamic_threshold",
            self.dynamic_threshold,
            refined.dynamic_threshold,
            0.02,
            0.0,
        )
        .compare("tip_time", self.tip_time, refined.tip_time, 0.02, 0.0)
        .compare(
            "max_lean",
            Some(self.max_lean),
            Some(refined.max_lean),
            0.05,
            lean_scale,
        )
        .compare(
            "final_lean",
            Some(self.final_lean),
            Some(refined.final_lean),
            0.05,
            lean_scale,
        )
        .compare(
            "tipped",
            Some(f64::from(u8::from(self.tipped))),
            Some(f64::from(u8::from(refined.tipped))),
            0.5,
            1.0,
        );
        c
    }
}

/// `main()`, and with `check` also `refined()` in a second thread beside it.
pub(crate) fn beside<A, B: Send>(
    check: bool,
    main: impl FnOnce() -> A,
    refined: impl FnOnce() -> B + Send,
) -> (A, Option<B>) {
    if !check {
        return (main(), None);
    }
    std::thread::scope(|s| {
        let handle = s.spawn(refined);
        let a = main();
        (a, handle.join().ok())
    })
}

/// The convergence of a refined run that failed (its error named).
pub(crate) fn refined_failed(why: impl std::fmt::Display) -> Convergence {
    let mut c = Convergence::new(format!("{REFINEMENT}: the refined run failed: {why}"));
    c.converged = false;
    c
}

/// Why a coarse companion's report cannot be compared with `main`'s: its run failed, or it
/// carries a warning of a kind the run does not (it left its regime: it sank, it drifted);
/// `None` when it can.
pub(crate) fn coarse_failure(
    main: &DynamicTipoverReport,
    coarse: &Result<DynamicTipoverReport>,
) -> Option<String> {
    let r = match coarse {
        Err(e) => return Some(format!("its run failed: {e}")),
        Ok(r) => r,
    };
    let kinds: Vec<&str> = main.warnings.iter().map(|w| w.kind()).collect();
    let new: Vec<String> = r
        .warnings
        .iter()
        .filter(|w| !kinds.contains(&w.kind()))
        .map(|w| w.to_string())
        .collect();
    (!new.is_empty()).then(|| format!("it carries warnings the run does not: {}", new.join("; ")))
}

/// Lays `convergence` on a result's `warnings` (one per unconverged quantity, or the
/// refined run's failure) and returns it.
pub(crate) fn judge(convergence: Convergence, warnings: &mut Vec<Warning>) -> Option<Convergence> {
    warnings.extend(convergence.warnings());
    Some(convergence)
}

/// A run-away state of the RK4 run as [`ToroidError::TipoverDiverged`], whose remedy is the
/// one this run has (a smaller `dt`; the core's message also names integrators the request
/// does not take). Any other error is the core's.
fn diverged(e: CoreError, dt: f64) -> ToroidError {
    use tensegrity_core::{error::StepHint, DynamicsError as D};
    let (t, what) = match e {
        CoreError::Dynamics(D::Diverged { t, what }) => (t, what.to_string()),
        CoreError::Dynamics(D::BlowUp {
            t,
            member,
            distance,
            limit,
            ..
        }) => {
            let hint = StepHint::Unknown;
            let e = D::BlowUp {
                t,
                member,
                distance,
                limit,
                hint,
            };
            (t, e.to_string())
        }
        CoreError::Dynamics(D::NonFiniteState { t, member, .. }) => {
            let hint = StepHint::Unknown;
            (t, D::NonFiniteState { t, member, hint }.to_string())
        }
        other => return other.into(),
    };
    ToroidError::TipoverDiverged { t, dt, what }
}
