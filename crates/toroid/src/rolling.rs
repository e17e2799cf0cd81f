//! Rolling down an incline: the reduced rigid model with unilateral contact.
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

mod hybrid;
mod impact;
mod wheel;

use crate::error::{Result, ToroidError};
use crate::validity::RollValidity;
use hybrid::{Hybrid, Mode};
use std::f64::consts::PI;
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

/// One recorded sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingSample {
    /// Time (s).
    pub t: f64,
    /// Axle position along the slope (m, downhill positive).
    pub s: f64,
    /// Axle height above the slope (m).
    pub h: f64,
    /// Position of the contact pair along the slope (m); in flight, the last contact's.
    pub pivot: f64,
    /// Angular velocity about the axle (rad/s, positive when rolling downhill).
    pub omega: f64,
    /// Normal contact force (N), 0 in flight.
    pub normal: f64,
    /// Tangential contact force (N, positive downhill).
    pub tangential: f64,
    /// Kinetic plus gravitational energy (J), zero at the start.
    pub energy: f64,
    /// Mean sliding speed of the loaded contact nodes along the slope (m/s); in the rigid model
    /// the contact vertex's sliding speed |w| (0 when pivoting, resting or flying).
    pub slip: f64,
}

/// The result of a rolling run.
#[derive(Debug, Clone, PartialEq)]
pub struct RollingResult {
    /// Samples at the output interval.
    pub samples: Vec<RollingSample>,
    /// Number of contact-pair impacts.
    pub impacts: usize,
    /// RMS deviation of the axle height about its mean, after the first second (m).
    pub axle_height_oscillation: f64,
    /// Mean downhill speed of the axle after the first second (m/s).
    pub mean_speed: f64,
    /// Largest contact force magnitude (N).
    pub max_reaction: f64,
    /// Smallest normal force (N); negative means the real wheel would lift off.
    pub min_normal: f64,
    /// Sampled time with N < 0 (s).
    pub lift_off_time: f64,
    /// Largest |F_t|/N with N > 0: the friction coefficient rolling without slip needs.
    pub required_friction: f64,
    /// Mean over the samples with contact of the contact nodes' sliding speed (m/s).
    pub mean_slip_speed: f64,
    /// Downhill speed of the axle at the end of the run (m/s).
    pub final_speed: f64,
    /// Every impact of a new contact pair, in time order.
    pub impact_log: Vec<crate::validity::ImpactRecord>,
    /// Admissibility of the run.
    pub validity: crate::validity::RollValidity,
}

impl RigidRolling {
    /// The rigid model of a built toroid (its mass, I₁, sides and outer radius) on a slope,
    /// with g = 9.81 m/s², a 0.1 ms step and 1 ms output.
    ///
    /// ```
    /// use toroid::{analyse, build, rolling::RigidRolling, ToroidParams};
    /// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
    /// let a = analyse(&t).unwrap();
    /// let model = RigidRolling::of(&t, &a, 50f64.to_radians());
    /// assert_eq!((model.sides, model.i1), (8, a.i1));
    /// ```
    pub fn of(toroid: &crate::Toroid, analysis: &crate::ToroidAnalysis, incline: f64) -> Self {
        Self {
            sides: toroid.params.sides,
            outer_radius: toroid.params.outer_radius,
            mass: analysis.mass_kg,
            i1: analysis.i1,
            incline,
            gravity: crate::defaults::GRAVITY,
            dt: crate::defaults::ROLL_DT,
            output_dt: crate::defaults::ROLL_OUTPUT_DT,
            mu_static: crate::defaults::STATIC_FRICTION,
            mu_kinetic: crate::defaults::KINETIC_FRICTION_RATIO * crate::defaults::STATIC_FRICTION,
            restitution: crate::defaults::RESTITUTION,
        }
    }

    /// ω⁺/ω⁻ at a pair-to-pair impact: (I₁ + m R_o² cos(2π/n)) / (I₁ + m R_o²).
    pub fn impact_ratio(&self) -> f64 {
        let mr2 = self.mass * self.outer_radius.powi(2);
        (self.i1 + mr2 * (2.0 * PI / self.sides as f64).cos()) / (self.i1 + mr2)
    }

    fn validate(&self, t_end: f64) -> Result<()> {
        let bad = |name, value: f64, reason: &str| {
            Err(ToroidError::InvalidParameter(
                tensegrity_core::request::InvalidParameter::new(name, value, reason),
            ))
        };
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
            return Err(ToroidError::InvalidParameter(
                tensegrity_core::request::InvalidParameter::new(
                    "mu_kinetic",
                    self.mu_kinetic,
                    format!(
                        "with I1 = {} and n = {} sliding friction has no solution (Painlevé \
                     paradox): lower mu_kinetic",
                        self.i1, self.sides
                    ),
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
    /// use toroid::rolling::RigidRolling;
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
        self.validate(t_end)?;
        let mut sim = Hybrid::start(self.wheel());
        let mut budget = Budget::default();
        let n_out = (t_end / self.output_dt).floor() as usize;
        let mut samples = Vec::with_capacity(n_out + 2);
        samples.push(self.sample(&sim, 0.0, &mut budget));
        for i in 1..=n_out {
            let t_out = i as f64 * self.output_dt;
            if !sim.advance_to(t_out, self.dt) {
                break;
            }
            samples.push(self.sample(&sim, t_out, &mut budget));
        }
        let run_time = samples.last().map_or(0.0, |s| s.t);
        let mut r = summarise(samples, sim.impacts.len(), self.output_dt);
        r.validity = self.validity(&sim, &budget, run_time);
        r.impact_log = sim.impacts;
        Ok(r)
    }

    fn validity(&self, sim: &Hybrid, budget: &Budget, run_time: f64) -> RollValidity {
        let fraction = |x: f64| if run_time > 0.0 { x / run_time } else { 0.0 };
        let energy_balance_error = if budget.largest_term > 0.0 {
            budget.largest_residual / budget.largest_term
        } else {
            0.0
        };
        let mut warnings = sim.warnings.clone();
        if energy_balance_error > 1e-6 {
            warnings.push(format!(
                "the rigid model's energy budget closes only to {energy_balance_error:.2e} \
                 relative: reduce dt"
            ));
        }
        RollValidity {
            min_normal_force: sim.min_normal,
            airborne_fraction: fraction(sim.flight_time),
            slip_fraction: fraction(sim.slip_time),
            max_penetration: budget.max_penetration,
            energy_balance_error,
            warnings,
            stopped_at: None,
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

/// Summary figures of a sampled rolling history (shared by the rigid and the full model).
pub(crate) fn summarise(
    samples: Vec<RollingSample>,
    impacts: usize,
    output_dt: f64,
) -> RollingResult {
    let t_end = samples.last().map_or(0.0, |s| s.t);
    let skip = if t_end > 1.0 { 1.0 } else { 0.0 };
    let tail: Vec<&RollingSample> = samples.iter().filter(|s| s.t >= skip - 1e-12).collect();
    let mean_h = tail.iter().map(|s| s.h).sum::<f64>() / tail.len() as f64;
    let rms = (tail.iter().map(|s| (s.h - mean_h).powi(2)).sum::<f64>() / tail.len() as f64).sqrt();
    let (first, last) = (tail[0], tail[tail.len() - 1]);
    let mean_speed = if last.t > first.t {
        (last.s - first.s) / (last.t - first.t)
    } else {
        0.0
    };
    let with_contact: Vec<f64> = samples
        .iter()
        .filter(|s| s.normal > 0.0)
        .map(|s| s.slip)
        .collect();
    let mean_slip_speed = if with_contact.is_empty() {
        0.0
    } else {
        with_contact.iter().sum::<f64>() / with_contact.len() as f64
    };
    let final_speed = match samples.len() {
        0 | 1 => 0.0,
        n => (samples[n - 1].s - samples[n - 2].s) / (samples[n - 1].t - samples[n - 2].t),
    };
    RollingResult {
        final_speed,
        impact_log: Vec::new(),
        validity: crate::validity::RollValidity::default(),
        mean_slip_speed,
        impacts,
        axle_height_oscillation: rms,
        mean_speed,
        max_reaction: samples
            .iter()
            .map(|s| s.normal.hypot(s.tangential))
            .fold(0.0, f64::max),
        min_normal: samples
            .iter()
            .map(|s| s.normal)
            .fold(f64::INFINITY, f64::min),
        lift_off_time: samples.iter().filter(|s| s.normal < 0.0).count() as f64 * output_dt,
        required_friction: samples
            .iter()
            .filter(|s| s.normal > 0.0)
            .map(|s| s.tangential.abs() / s.normal)
            .fold(0.0, f64::max),
        samples,
    }
}
