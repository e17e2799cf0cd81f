//! The reduced rigid model: a polygon rolling down an incline with unilateral contact.
//!
//! The wheel is a rigid body of mass m and moment of inertia I₁ about its axle whose contact
//! points are the n outer tread pairs: the vertices of a regular n-gon of circumradius R_o in
//! the rolling plane. In slope coordinates (s downhill along the slope, h normal to it, slope
//! angle φ, gravity g) the ground only pushes (N ≥ 0) and its friction is Coulomb's (μ_s
//! static, μ_k kinetic). The model is hybrid; its phases are
//!
//! - **pivot** about the contact vertex, θ the angle of the axle from the slope normal through
//!   it (positive downhill): (I₁ + m R_o²) θ̈ = m g R_o sin(θ + φ), while N ≥ 0 and
//!   |F_t| ≤ μ_s N, with the contact force F = m a_axle − m g split into N (normal) and F_t
//!   (tangential);
//! - **slip** of the contact vertex with kinetic friction F_t = σ N, σ = −μ_k sign(w) for the
//!   slip velocity w: I₁ θ̈ = R_o (N sin θ − F_t cos θ), m ḧ = N − m g cos φ,
//!   m s̈ = F_t + m g sin φ with the vertex on the slope (h = R_o cos θ); solved for θ̈, N and ẇ
//!   in closed form (see the `wheel` submodule);
//! - **flight**: s̈ = g sin φ, ḧ = −g cos φ, ω constant, solved exactly;
//! - **side**: two vertices on the slope, ω = 0, at rest while tan φ ≤ μ_s (and φ ≤ π/n),
//!   else sliding as a block with s̈ = g (sin φ ∓ μ_k cos φ) as long as the moment balance
//!   keeps both normal forces ≥ 0 (μ_k ≤ tan(π/n)); otherwise it pivots or slips about one
//!   vertex. The start state (θ = −π/n, at rest on the side of the downhill and the uphill
//!   pair) begins here: it pivots (or slips) about the downhill vertex at once when φ > π/n;
//! - **impacts** when a vertex reaches the slope: Newton restitution e on the vertex's normal
//!   velocity and Coulomb friction on the impulse (sticking impulse when |P_t| ≤ μ_s P_n, else
//!   a sliding one with μ_k, see the `impact` submodule); any other touching vertex that still
//!   approaches the slope then gets plastic impulses in turn until none does. With e = 0 and
//!   sticking this is the classic plastic impact conserving the angular momentum about the new
//!   contact, ω⁺/ω⁻ = (I₁ + m R_o² cos(2π/n)) / (I₁ + m R_o²) ([`RigidRolling::impact_ratio`]).
//!
//! After an impact or a smooth event the next phase is chosen consistently: a touching vertex
//! whose normal velocity is positive leaves; with one vertex left at zero normal velocity the
//! wheel pivots if the pivot's N ≥ 0 and |F_t| ≤ μ_s N, slips against the needed friction if
//! only N ≥ 0, and flies if the contact would have to pull; with two (a side) it pivots or slips
//! about the vertex whose motion lifts the other, else slides or rests on the side.
//!
//! **Events** are located to round-off: lift-off (N = 0), touchdown of any vertex, stick → slip
//! (|F_t| = μ_s N), slip → stick (w = 0) and a neighbour touching while in contact
//! (θ = ±π/n), by bisection on the step length of the step that crossed them (the flight's
//! exact solution for touchdowns, with a grazing minimum of a gap bracketed through its rate).
//! Smooth contact phases use classical RK4 with the step `dt`, the friction work ∫ −F_t w dt
//! integrated alongside. An impact whose approach speed is below 10⁻⁶ √(g R_o) is taken as
//! plastic (this ends Zeno bouncing when e > 0; the energy it drops is counted as impact loss).
//! Where Newton restitution with friction would create energy (e near 1 with a strongly
//! coupled impulse), the impact uses the largest e' ≤ e whose impulse dissipates.
//!
//! **Energy budget**: E(t) − E(0) = −(normal impulse losses) − (friction impulse losses) −
//! (friction work in slip and side slides), with E the kinetic plus gravitational energy and an
//! impulse's work P · (c⁻ + c⁺)/2 at its vertex. `validity.energy_balance_error` is the largest
//! residual over the samples divided by the largest term (kinetic energy, potential energy
//! change, accumulated losses); it is about 10⁻¹² with the default 0.1 ms step.
//!
//! The result's validity: `min_normal_force` (the smallest N met at any step or event, ≥ 0 by
//! construction), the airborne and slip fractions of the run, `max_penetration` (the deepest
//! vertex below the slope over the samples beyond the contact tolerance 10⁻¹⁰ R_o, so 0), the
//! energy error, and warnings when the run had to stop (event cap, chattering without time
//! advancing), an impact's sequential impulses did not converge, an impact created energy, or
//! the energy budget did not close to 10⁻⁶. Parameters for which sliding friction has no
//! solution (I₁ + m R_o² sin θ (sin θ ± μ_k cos θ) ≤ 0 for some |θ| ≤ π/n: Painlevé) are
//! rejected with an error naming `mu_kinetic`.
//!
//! The polygon is any wheel's ([`Polygon`]: n, R_o, m, I₁); node frames of a rigid run place
//! the wheel's nodes by its pose (see [`crate::frames`]).

mod hybrid;
mod impact;
mod wheel;

use crate::defaults;
use crate::error::{Result, RollingError};
use crate::frame::WheelFrame;
use crate::frames::RigidFrames;
use crate::observer::{interrupted_warning, Flow, Observer};
pub use crate::polygon::Polygon;
use crate::sample::{summarise, RollingResult, RollingSample};
use crate::settings::RunSpec;
use crate::validity::RollValidity;
use hybrid::{Hybrid, Mode};
use nalgebra::Vector3;
use std::f64::consts::PI;
use tensegrity_core::Warning;
use wheel::Wheel;

/// Settings of a rigid rolling run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidRolling {
    /// Number of contact pairs n.
    pub sides: usize,
    /// Outer radius R_o (m).
    pub outer_radius: f64,
    /// Wheel mass m (kg).
    pub mass: f64,
    /// Moment of inertia about the axle I₁ (kg m²).
    pub i1: f64,
    /// Slope angle φ (rad), 0 ≤ φ < π/2.
    pub incline: f64,
    /// Gravity g (m/s²).
    pub gravity: f64,
    /// Integration step (s).
    pub dt: f64,
    /// Output interval (s).
    pub output_dt: f64,
    /// Static friction coefficient μ_s of the slope.
    pub mu_static: f64,
    /// Kinetic friction coefficient μ_k of the slope.
    pub mu_kinetic: f64,
    /// Normal coefficient of restitution e of an impact (0 = plastic).
    pub restitution: f64,
}

/// A rigid run: the result and the node frames asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidRun {
    /// Samples, summary, impacts and validity.
    pub result: RollingResult,
    /// The wheel's nodes at the requested times (the nearest sample), in time order.
    pub frames: Vec<WheelFrame>,
}

impl RigidRolling {
    /// The rigid model of `polygon` on the slope of `spec` (its incline, gravity, step,
    /// output interval, friction and restitution).
    ///
    /// ```
    /// use wheel_rolling::{Polygon, RigidRolling, RunSpec};
    /// let p = Polygon { sides: 8, outer_radius: 1.0, mass: 14.4, i1: 9.3 };
    /// let model = RigidRolling::new(&p, &RunSpec::default());
    /// assert_eq!((model.sides, model.i1, model.mu_static), (8, 9.3, 0.8));
    /// assert!((model.mu_kinetic - 0.6).abs() < 1e-15);
    /// ```
    pub fn new(polygon: &Polygon, spec: &RunSpec) -> Self {
        Self {
            sides: polygon.sides,
            outer_radius: polygon.outer_radius,
            mass: polygon.mass,
            i1: polygon.i1,
            incline: spec.settings.incline,
            gravity: spec.settings.gravity,
            dt: spec.rigid_dt(),
            output_dt: spec.output_dt,
            mu_static: spec.mu_static,
            mu_kinetic: spec.mu_kinetic,
            restitution: spec.settings.restitution,
        }
    }

    /// The polygon of this model.
    pub fn polygon(&self) -> Polygon {
        Polygon {
            sides: self.sides,
            outer_radius: self.outer_radius,
            mass: self.mass,
            i1: self.i1,
        }
    }

    /// ω⁺/ω⁻ at a pair-to-pair impact: (I₁ + m R_o² cos(2π/n)) / (I₁ + m R_o²).
    pub fn impact_ratio(&self) -> f64 {
        self.polygon().impact_ratio()
    }

    fn validate(&self, t_end: f64) -> Result<()> {
        let bad = |name, value: f64, reason: &str| Err(RollingError::invalid(name, value, reason));
        if self.sides < 3 {
            return bad("sides", self.sides as f64, "at least 3");
        }
        for (name, v) in [
            ("outer_radius", self.outer_radius),
            ("mass", self.mass),
            ("i1", self.i1),
            ("gravity", self.gravity),
            ("dt", self.dt),
            ("output_dt", self.output_dt),
            ("t_end", t_end),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return bad(name, v, "must be positive");
            }
        }
        if !(self.incline.is_finite() && self.incline >= 0.0 && self.incline < PI / 2.0) {
            return bad("incline", self.incline, "must lie in [0, π/2)");
        }
        if !(self.mu_static.is_finite() && self.mu_static >= 0.0) {
            return bad("mu_static", self.mu_static, "must be finite and ≥ 0");
        }
        if !(self.mu_kinetic >= 0.0 && self.mu_kinetic <= self.mu_static) {
            return bad("mu_kinetic", self.mu_kinetic, "must lie in [0, mu_static]");
        }
        if !(0.0..=1.0).contains(&self.restitution) {
            return bad("restitution", self.restitution, "must lie in [0, 1]");
        }
        self.check_painleve()
    }

    /// The slip dynamics and sliding impulses need I₁ + m R² sin θ (sin θ − σ cos θ) > 0 for
    /// |θ| ≤ π/n and |σ| = μ_k; otherwise Coulomb friction has no solution (Painlevé).
    fn check_painleve(&self) -> Result<()> {
        let w = self.wheel();
        let worst = (0..=400)
            .map(|i| -w.half + 2.0 * w.half * i as f64 / 400.0)
            .flat_map(|th| {
                [
                    w.slip_denominator(th, w.mu_k),
                    w.slip_denominator(th, -w.mu_k),
                ]
            })
            .fold(f64::INFINITY, f64::min);
        if worst <= 1e-3 * self.i1 {
            return Err(RollingError::invalid(
                "mu_kinetic",
                self.mu_kinetic,
                format!(
                    "with I1 = {} and n = {} sliding friction has no solution (Painlevé \
                     paradox): lower mu_kinetic",
                    self.i1, self.sides
                ),
            ));
        }
        Ok(())
    }

    fn wheel(&self) -> Wheel {
        let (sin, cos) = self.incline.sin_cos();
        Wheel {
            n: self.sides,
            r: self.outer_radius,
            m: self.mass,
            i1: self.i1,
            gs: self.gravity * sin,
            gn: self.gravity * cos,
            mu_s: self.mu_static,
            mu_k: self.mu_kinetic,
            e: self.restitution,
            half: PI / self.sides as f64,
        }
    }

    /// Runs for `t_end` seconds from rest on a side (the downhill and the uphill contact pair
    /// touching, θ = −π/n).
    ///
    /// ```
    /// use wheel_rolling::RigidRolling;
    /// let run = RigidRolling {
    ///     sides: 8, outer_radius: 1.0, mass: 10.0, i1: 6.0, incline: 0.1,
    ///     gravity: 9.81, dt: 1e-3, output_dt: 0.01,
    ///     mu_static: 0.8, mu_kinetic: 0.6, restitution: 0.0,
    /// };
    /// // 0.1 rad < π/8 and tan 0.1 < 0.8: the wheel stays on its side
    /// let r = run.run(2.0).unwrap();
    /// assert_eq!(r.impacts, 0);
    /// assert_eq!(r.mean_speed, 0.0);
    /// assert!(r.validity.valid());
    /// ```
    pub fn run(&self, t_end: f64) -> Result<RollingResult> {
        Ok(self.run_observed(t_end, &[], &[], None)?.result)
    }

    /// As [`RigidRolling::run`], placing the wheel's nodes (`start_pose`: in the starting
    /// pose, hub at the origin, axle along x, see [`crate::frames`]) at `frame_times`, and
    /// handing every sample and frame to `observer` as it is made. An observer that stops the
    /// run ends it after the sample it stopped on: the result holds exactly the samples the
    /// observer received, `stopped_at` and an interruption warning.
    pub fn run_observed(
        &self,
        t_end: f64,
        start_pose: &[Vector3<f64>],
        frame_times: &[f64],
        mut observer: Option<&mut dyn Observer>,
    ) -> Result<RigidRun> {
        self.validate(t_end)?;
        let mut sim = Hybrid::start(self.wheel());
        let mut budget = Budget::default();
        let mut placer = RigidFrames::new(start_pose, frame_times);
        let n_out = (t_end / self.output_dt).floor() as usize;
        let mut samples = Vec::with_capacity(n_out + 2);
        let mut stopped = false;
        let mut frames = Vec::new();
        let keep_frames = observer.as_deref().is_none_or(|o| o.keeps_frames());
        for i in 0..=n_out {
            let t_out = i as f64 * self.output_dt;
            if i > 0 && !sim.advance_to(t_out, self.dt) {
                break;
            }
            let sample = self.sample(&sim, t_out, &mut budget);
            samples.push(sample);
            let new_frames = placer.push(&sample);
            if let Some(obs) = observer.as_deref_mut() {
                let mut flow = obs.sample(&sample);
                for f in &new_frames {
                    if obs.frame(f) == Flow::Stop {
                        flow = Flow::Stop;
                    }
                }
                stopped = flow == Flow::Stop || !obs.keep_going();
            }
            if keep_frames {
                frames.extend(new_frames);
            }
            if stopped {
                break;
            }
        }
        let last_frames = placer.finish(!stopped);
        if let Some(obs) = observer {
            for f in &last_frames {
                obs.frame(f);
            }
        }
        if keep_frames {
            frames.extend(last_frames);
        }
        let run_time = samples.last().map_or(0.0, |s| s.t);
        let mut r = summarise(samples, sim.impacts.len(), self.output_dt);
        r.validity = self.validity(&sim, &budget, run_time);
        if stopped {
            r.validity.stopped_at = Some(run_time);
            r.validity
                .warnings
                .push(interrupted_warning(run_time, t_end));
        }
        r.impact_log = sim.impacts;
        Ok(RigidRun { result: r, frames })
    }

    fn validity(&self, sim: &Hybrid, budget: &Budget, run_time: f64) -> RollValidity {
        let fraction = |x: f64| if run_time > 0.0 { x / run_time } else { 0.0 };
        let energy_balance_error = if budget.largest_term > 0.0 {
            budget.largest_residual / budget.largest_term
        } else {
            0.0
        };
        let mut warnings = sim.warnings.clone();
        if energy_balance_error > defaults::RIGID_ENERGY_BALANCE_TOLERANCE {
            warnings.push(Warning::RigidEnergyBudget {
                error: energy_balance_error,
            });
        }
        RollValidity {
            min_normal_force: sim.min_normal,
            airborne_fraction: fraction(sim.flight_time),
            slip_fraction: fraction(sim.slip_time),
            max_penetration: budget.max_penetration,
            energy_balance_error,
            warnings,
            stopped_at: None,
            convergence: None,
        }
    }

    fn sample(&self, sim: &Hybrid, t: f64, budget: &mut Budget) -> RollingSample {
        let w = &sim.w;
        let b = sim.body();
        let weight = (w.m * w.gn, w.m * w.gs);
        let (pivot, normal, tangential, slip) = match sim.mode {
            Mode::Contact { y, sigma, .. } => {
                let f = w.forces(y[0], y[1], sigma);
                (y[2], f.normal, f.tangential, y[3].abs())
            }
            Mode::Flight { last, .. } => (last, 0.0, 0.0, 0.0),
            Mode::Side { k, accel, .. } => (
                w.vertex_s(&b, k),
                weight.0,
                w.m * accel - weight.1,
                b.u.abs(),
            ),
            Mode::Rest { k, .. } => (w.vertex_s(&b, k), weight.0, -weight.1, 0.0),
        };
        let (kinetic, potential) = w.energies(&b);
        let energy = kinetic + potential - budget.start(potential);
        let losses = sim.impact_loss + sim.impulse_friction_loss + sim.work();
        budget.record(kinetic, energy - kinetic, losses, energy + losses);
        // a vertex within the contact tolerance of the slope touches it: round-off, not depth
        let deepest = (0..w.n).map(|j| -w.gap(&b, j)).fold(0.0, f64::max);
        if deepest > hybrid::GAP_TOL * w.r {
            budget.max_penetration = budget.max_penetration.max(deepest);
        }
        RollingSample {
            t,
            s: b.s,
            h: b.h,
            pivot,
            omega: b.omega,
            normal,
            tangential,
            energy,
            slip,
        }
    }
}

/// Running figures of the energy budget and the penetration over the samples.
#[derive(Debug, Default)]
struct Budget {
    initial: Option<f64>,
    largest_term: f64,
    largest_residual: f64,
    max_penetration: f64,
}

impl Budget {
    /// The initial potential energy (taken from the first call).
    fn start(&mut self, potential: f64) -> f64 {
        *self.initial.get_or_insert(potential)
    }

    fn record(&mut self, kinetic: f64, potential_change: f64, losses: f64, residual: f64) {
        let term = kinetic.max(potential_change.abs()).max(losses.abs());
        self.largest_term = self.largest_term.max(term);
        self.largest_residual = self.largest_residual.max(residual.abs());
    }
}
