//! Rolling down an incline: the reduced (rigid) model.
//!
//! The wheel is a rigid body of mass m and moment of inertia I₁ about its axle whose contact
//! points are the n outer tread pairs (n1_k, n2_k): a regular n-gon of circumradius R_o in the
//! rolling plane. In incline coordinates (s downhill along the slope, h normal to it, slope
//! angle φ, gravity g) the model, as the thesis describes the rolling, is:
//!
//! - **pivoting** about the downhill contact pair, with θ the angle of the axle from the slope
//!   normal through the pivot (positive downhill): (I₁ + m R_o²) θ̈ = m g R_o sin(θ + φ); the
//!   contact force is F = m a_c − m g (normal part N, tangential part F_t);
//! - **impact** when the next pair touches (θ = π/n): plastic and without slip, conserving
//!   angular momentum about the new contact, ω⁺ = ω⁻ (I₁ + m R_o² cos(2π/n)) / (I₁ + m R_o²).
//!
//! The contact is held bilateral and without slip (as the thesis's damped contact does). The
//! run reports where that assumption fails: the time during which N < 0 (a free wheel would
//! leave the slope), the smallest N, and the friction coefficient max |F_t|/N that rolling
//! without slip needs. Pivot phases are integrated with classical RK4 at a fixed step; impacts
//! are located by bisection of the step to 1e-12 s. The wheel starts at rest on one contact
//! pair, on the edge between it and its uphill neighbour (θ = −π/n); if φ ≤ π/n it stays there.

use crate::error::{Result, ToroidError};
use std::f64::consts::PI;

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
    /// Position of the pivoting contact pair along the slope (m).
    pub pivot: f64,
    /// Angular velocity about the axle (rad/s, positive when rolling downhill).
    pub omega: f64,
    /// Normal contact force (N).
    pub normal: f64,
    /// Tangential contact force (N, positive downhill).
    pub tangential: f64,
    /// Kinetic plus gravitational energy (J), zero at the start.
    pub energy: f64,
    /// Mean sliding speed of the loaded contact nodes along the slope (m/s); 0 in the rigid
    /// model, which rolls without slip.
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
            Err(ToroidError::InvalidParameter {
                name,
                value,
                reason: reason.to_string(),
            })
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
        Ok(())
    }

    fn accel(&self, theta: f64) -> f64 {
        let ia = self.i1 + self.mass * self.outer_radius.powi(2);
        self.mass * self.gravity * self.outer_radius * (theta + self.incline).sin() / ia
    }

    /// RK4 step of (θ, θ̇).
    fn step(&self, theta: f64, rate: f64, dt: f64) -> (f64, f64) {
        let f = |th: f64, w: f64| (w, self.accel(th));
        let k1 = f(theta, rate);
        let k2 = f(theta + 0.5 * dt * k1.0, rate + 0.5 * dt * k1.1);
        let k3 = f(theta + 0.5 * dt * k2.0, rate + 0.5 * dt * k2.1);
        let k4 = f(theta + dt * k3.0, rate + dt * k3.1);
        (
            theta + dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            rate + dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    }

    /// Runs for `t_end` seconds from rest on a contact pair.
    ///
    /// ```
    /// use toroid::rolling::RigidRolling;
    /// let run = RigidRolling {
    ///     sides: 8, outer_radius: 1.0, mass: 10.0, i1: 6.0, incline: 0.1,
    ///     gravity: 9.81, dt: 1e-3, output_dt: 0.01,
    ///     mu_static: 0.8, mu_kinetic: 0.6, restitution: 0.0,
    /// };
    /// // 0.1 rad < π/8: the wheel stays on its edge
    /// let r = run.run(2.0).unwrap();
    /// assert_eq!(r.impacts, 0);
    /// assert_eq!(r.mean_speed, 0.0);
    /// ```
    pub fn run(&self, t_end: f64) -> Result<RollingResult> {
        self.validate(t_end)?;
        let half = PI / self.sides as f64;
        let step_length = 2.0 * self.outer_radius * half.sin();
        let ratio = self.impact_ratio();
        let rolls = self.incline > half;
        let (mut sp, mut theta, mut rate) = (0.0, -half, 0.0);
        let (mut t, mut impacts) = (0.0, 0usize);
        let n_out = (t_end / self.output_dt).floor() as usize;
        let mut samples = Vec::with_capacity(n_out + 2);
        for i in 0..=n_out {
            let t_out = i as f64 * self.output_dt;
            while rolls && t < t_out {
                let dt = self.dt.min(t_out - t);
                let (th, w) = self.step(theta, rate, dt);
                if th < half {
                    (theta, rate, t) = (th, w, t + dt);
                    continue;
                }
                // locate θ = π/n, then the plastic impact onto the next pair
                let (mut lo, mut hi) = (0.0, dt);
                while hi - lo > 1e-12 {
                    let mid = 0.5 * (lo + hi);
                    if self.step(theta, rate, mid).0 < half {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let (_, w) = self.step(theta, rate, hi);
                (sp, theta, rate, t) = (sp + step_length, -half, w * ratio, t + hi);
                impacts += 1;
            }
            samples.push(self.sample(sp, theta, rate, t_out));
        }
        Ok(summarise(samples, impacts, self.output_dt))
    }

    fn sample(&self, sp: f64, theta: f64, rate: f64, t: f64) -> RollingSample {
        let (r, m, g) = (self.outer_radius, self.mass, self.gravity);
        let acc = self.accel(theta);
        let a_s = r * (acc * theta.cos() - rate * rate * theta.sin());
        let a_h = r * (-acc * theta.sin() - rate * rate * theta.cos());
        let (s, h) = (sp + r * theta.sin(), r * theta.cos());
        let half = PI / self.sides as f64;
        let (s0, h0) = (-r * half.sin(), r * half.cos());
        let (sin, cos) = self.incline.sin_cos();
        RollingSample {
            t,
            s,
            h,
            pivot: sp,
            omega: rate,
            normal: m * (a_h + g * cos),
            tangential: m * (a_s - g * sin),
            slip: 0.0,
            energy: 0.5 * (self.i1 + m * r * r) * rate * rate
                + m * g * ((h - h0) * cos - (s - s0) * sin),
        }
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
