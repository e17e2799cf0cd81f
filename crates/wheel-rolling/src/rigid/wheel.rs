//! The rigid polygon wheel: geometry of its contact vertices, the full planar state and the
//! dynamics of a single contact (pivot or slip), integrated with classical RK4.
//!
//! Vertex j sits at the axle plus R (−sin ψ_j, −cos ψ_j) in slope coordinates (s downhill,
//! h normal), with ψ_j = α − 2πj/n and α the wheel's rotation (ω = α̇ > 0 rolling downhill).
//! Its gap above the slope is h − R cos ψ_j and its velocity (u − R ω cos ψ_j, v + R ω sin ψ_j).
//!
//! With one contact vertex at angle θ = ψ_k (axle = contact + R (sin θ, cos θ)) and the
//! contact force (F_t, N) on the wheel, the equations of motion are
//! m s̈ = F_t + m g sin φ, m ḧ = N − m g cos φ and I₁ θ̈ = R (N sin θ − F_t cos θ).
//! Pivoting (the contact fixed) they reduce to (I₁ + m R²) θ̈ = m g R sin(θ + φ); slipping with
//! F_t = σ N (σ = −μ_k sign of the slip velocity w) to
//! θ̈ = m R (sin θ − σ cos θ)(g cos φ − R θ̇² cos θ) / (I₁ + m R² sin θ (sin θ − σ cos θ)),
//! N = m (g cos φ − R (θ̈ sin θ + θ̇² cos θ)), ẇ = F_t/m + g sin φ − R (θ̈ cos θ − θ̇² sin θ).

use std::f64::consts::PI;

/// The wheel's constants, in the slope frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Wheel {
    /// Number of contact vertices n.
    pub n: usize,
    /// Circumradius R (m).
    pub r: f64,
    /// Mass m (kg).
    pub m: f64,
    /// Moment of inertia about the axle I₁ (kg m²).
    pub i1: f64,
    /// Downhill gravity component g sin φ (m/s²).
    pub gs: f64,
    /// Normal gravity component g cos φ (m/s²).
    pub gn: f64,
    /// Static friction coefficient.
    pub mu_s: f64,
    /// Kinetic friction coefficient.
    pub mu_k: f64,
    /// Normal coefficient of restitution.
    pub e: f64,
    /// Half the angle between vertices, π/n.
    pub half: f64,
}

/// The planar state of the wheel: axle position and velocity, rotation and spin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Body {
    /// Axle along the slope (m, downhill).
    pub s: f64,
    /// Axle above the slope (m).
    pub h: f64,
    /// Rotation α (rad, positive rolling downhill).
    pub alpha: f64,
    /// ṡ (m/s).
    pub u: f64,
    /// ḣ (m/s).
    pub v: f64,
    /// ω = α̇ (rad/s).
    pub omega: f64,
}

/// State of a single-contact phase: θ, θ̇, contact position s_c, slip velocity w = ṡ_c and the
/// friction work dissipated so far (J).
pub(crate) type ContactState = [f64; 5];

/// Accelerations and contact force of a single-contact phase.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ContactForces {
    /// θ̈ (rad/s²).
    pub theta_dd: f64,
    /// Normal force N (N).
    pub normal: f64,
    /// Tangential force F_t (N, positive downhill).
    pub tangential: f64,
    /// ẇ (m/s²), zero when pivoting.
    pub w_dot: f64,
}

impl Wheel {
    /// ψ_j of vertex j.
    pub fn psi(&self, b: &Body, j: usize) -> f64 {
        b.alpha - 2.0 * PI * j as f64 / self.n as f64
    }

    /// Height of vertex j above the slope (m).
    pub fn gap(&self, b: &Body, j: usize) -> f64 {
        b.h - self.r * self.psi(b, j).cos()
    }

    /// Position of vertex j along the slope (m).
    pub fn vertex_s(&self, b: &Body, j: usize) -> f64 {
        b.s - self.r * self.psi(b, j).sin()
    }

    /// Velocity of vertex j: (tangential, normal) (m/s).
    pub fn vertex_velocity(&self, b: &Body, j: usize) -> (f64, f64) {
        let (sin, cos) = self.psi(b, j).sin_cos();
        (b.u - self.r * b.omega * cos, b.v + self.r * b.omega * sin)
    }

    /// Kinetic energy and gravitational potential m (g cos φ h − g sin φ s) (J).
    pub fn energies(&self, b: &Body) -> (f64, f64) {
        let kinetic = 0.5 * self.m * (b.u * b.u + b.v * b.v) + 0.5 * self.i1 * b.omega * b.omega;
        (kinetic, self.m * (self.gn * b.h - self.gs * b.s))
    }

    /// The denominator I₁ + m R² sin θ (sin θ − σ cos θ) of the slip dynamics (it also sets
    /// the effective mass of a sliding impulse); it must stay positive (no Painlevé paradox).
    pub fn slip_denominator(&self, theta: f64, sigma: f64) -> f64 {
        let (sin, cos) = theta.sin_cos();
        self.i1 + self.m * self.r * self.r * sin * (sin - sigma * cos)
    }

    /// Accelerations and contact force pivoting (`sigma` = None) or slipping with F_t = σ N.
    pub fn forces(&self, theta: f64, omega: f64, sigma: Option<f64>) -> ContactForces {
        let (m, r) = (self.m, self.r);
        let (sin, cos) = theta.sin_cos();
        let w2 = omega * omega;
        let theta_dd = match sigma {
            // m g R sin(θ + φ) / (I₁ + m R²)
            None => m * r * (sin * self.gn + cos * self.gs) / (self.i1 + m * r * r),
            Some(sg) => {
                m * r * (sin - sg * cos) * (self.gn - r * w2 * cos)
                    / self.slip_denominator(theta, sg)
            }
        };
        let a_s = r * (theta_dd * cos - w2 * sin);
        let a_h = -r * (theta_dd * sin + w2 * cos);
        let normal = m * (a_h + self.gn);
        match sigma {
            None => ContactForces {
                theta_dd,
                normal,
                tangential: m * (a_s - self.gs),
                w_dot: 0.0,
            },
            Some(sg) => ContactForces {
                theta_dd,
                normal,
                tangential: sg * normal,
                w_dot: sg * normal / m + self.gs - a_s,
            },
        }
    }

    /// Time derivative of a contact state.
    fn derivative(&self, y: &ContactState, sigma: Option<f64>) -> ContactState {
        let f = self.forces(y[0], y[1], sigma);
        [y[1], f.theta_dd, y[3], f.w_dot, -f.tangential * y[3]]
    }

    /// One classical RK4 step of length `dt`.
    pub fn rk4(&self, y: &ContactState, sigma: Option<f64>, dt: f64) -> ContactState {
        let add = |a: &ContactState, k: &ContactState, c: f64| {
            let mut out = *a;
            out.iter_mut().zip(k).for_each(|(o, k)| *o += c * k);
            out
        };
        let k1 = self.derivative(y, sigma);
        let k2 = self.derivative(&add(y, &k1, 0.5 * dt), sigma);
        let k3 = self.derivative(&add(y, &k2, 0.5 * dt), sigma);
        let k4 = self.derivative(&add(y, &k3, dt), sigma);
        let mut out = *y;
        for i in 0..5 {
            out[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        out
    }

    /// The body of a single-contact state on vertex k.
    pub fn body_of(&self, y: &ContactState, k: usize) -> Body {
        let (sin, cos) = y[0].sin_cos();
        Body {
            s: y[2] + self.r * sin,
            h: self.r * cos,
            alpha: y[0] + 2.0 * PI * k as f64 / self.n as f64,
            u: y[3] + self.r * y[1] * cos,
            v: -self.r * y[1] * sin,
            omega: y[1],
        }
    }

    /// The single-contact state of a body touching on vertex k, with friction work `work`.
    pub fn contact_of(&self, b: &Body, k: usize, work: f64) -> ContactState {
        let theta = self.psi(b, k);
        let (sin, cos) = theta.sin_cos();
        [
            theta,
            b.omega,
            b.s - self.r * sin,
            b.u - self.r * b.omega * cos,
            work,
        ]
    }

    /// Ballistic flight of `tau` seconds: s̈ = g sin φ, ḧ = −g cos φ, ω constant.
    pub fn fly(&self, b: &Body, tau: f64) -> Body {
        Body {
            s: b.s + b.u * tau + 0.5 * self.gs * tau * tau,
            h: b.h + b.v * tau - 0.5 * self.gn * tau * tau,
            alpha: b.alpha + b.omega * tau,
            u: b.u + self.gs * tau,
            v: b.v - self.gn * tau,
            omega: b.omega,
        }
    }

    /// Rate of change of vertex j's gap in flight (m/s).
    pub fn gap_rate(&self, b: &Body, j: usize) -> f64 {
        self.vertex_velocity(b, j).1
    }
}
