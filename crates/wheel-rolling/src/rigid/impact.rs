//! The impact law at a contact vertex: Newton restitution on the normal velocity and Coulomb
//! friction on the impulse.
//!
//! An impulse P = (P_t, P_n) at vertex j (angle ψ) changes the body by Δu = P_t/m,
//! Δv = P_n/m, I₁ Δω = R (P_n sin ψ − P_t cos ψ), so the vertex velocity c = (c_t, c_n) changes
//! by W P with the inverse effective mass
//! W = [[1/m + R² cos²ψ/I₁, −R² sin ψ cos ψ/I₁], [−R² sin ψ cos ψ/I₁, 1/m + R² sin²ψ/I₁]].
//! The sticking impulse solves W P = (−c_t, −(1 + e) c_n); it is taken when P_n ≥ 0 and
//! |P_t| ≤ μ_s P_n. Otherwise the impulse slides: P_t = σ P_n with σ = μ_k sign(P_t of the
//! sticking solution) and P_n = −(1 + e) c_n / (W_nn + σ W_nt), whose denominator is the slip
//! denominator D/(m I₁) of [`super::wheel`]. The work of the impulse is exactly
//! P · (c⁻ + c⁺)/2, split into its normal (restitution) and tangential (friction) parts.
//!
//! Newton restitution with friction can create energy when the tangential and normal
//! responses couple (W_nt ≠ 0, e near 1). [`Wheel::dissipative_impulse`] then lowers the
//! restitution to the largest e' ≤ e whose impulse does not create energy (bisection; e' = 0,
//! the plastic impulse, always dissipates).

use super::wheel::{Body, Wheel};

/// What one impulse did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Impulse {
    /// Normal impulse (N·s).
    pub normal: f64,
    /// Tangential impulse (N·s, positive downhill).
    pub tangential: f64,
    /// Energy dissipated by the normal part, −P_n (c_n⁻ + c_n⁺)/2 (J).
    pub normal_loss: f64,
    /// Energy dissipated by the tangential part, −P_t (c_t⁻ + c_t⁺)/2 (J).
    pub friction_loss: f64,
}

impl Wheel {
    /// Applies the impact law at vertex j with restitution `e` to `b`. Nothing happens when the
    /// vertex is not approaching the slope (c_n ≥ 0).
    pub fn impulse(&self, b: &mut Body, j: usize, e: f64) -> Impulse {
        let (ct, cn) = self.vertex_velocity(b, j);
        if cn >= 0.0 {
            return Impulse::default();
        }
        let (sin, cos) = self.psi(b, j).sin_cos();
        let r2i = self.r * self.r / self.i1;
        let (wtt, wnn, wtn) = (
            1.0 / self.m + r2i * cos * cos,
            1.0 / self.m + r2i * sin * sin,
            -r2i * sin * cos,
        );
        let (rt, rn) = (-ct, -(1.0 + e) * cn);
        let det = wtt * wnn - wtn * wtn;
        let (pt, pn) = ((wnn * rt - wtn * rn) / det, (wtt * rn - wtn * rt) / det);
        let (pt, pn) = if pn >= 0.0 && pt.abs() <= self.mu_s * pn {
            (pt, pn)
        } else {
            let sigma = self.mu_k * pt.signum();
            let pn = rn / (wnn + sigma * wtn);
            (sigma * pn, pn)
        };
        b.u += pt / self.m;
        b.v += pn / self.m;
        b.omega += self.r * (pn * sin - pt * cos) / self.i1;
        let (ct2, cn2) = self.vertex_velocity(b, j);
        Impulse {
            normal: pn,
            tangential: pt,
            normal_loss: -pn * 0.5 * (cn + cn2),
            friction_loss: -pt * 0.5 * (ct + ct2),
        }
    }

    /// [`Wheel::impulse`] with the restitution lowered, if needed, to the largest e' ≤ e whose
    /// impulse dissipates energy; also returns e'.
    pub fn dissipative_impulse(&self, b: &mut Body, j: usize, e: f64) -> (Impulse, f64) {
        // round-off of an energy-conserving impulse (e = 1 without friction) is no gain
        let slack = -1e-12 * self.energies(b).0;
        let trial = |e: f64| {
            let mut after = *b;
            let p = self.impulse(&mut after, j, e);
            (after, p, p.normal_loss + p.friction_loss >= slack)
        };
        let (after, p, ok) = trial(e);
        if ok || e == 0.0 {
            *b = after;
            return (p, e);
        }
        let (lo, _) = super::hybrid::bisect(0.0, e, |x| !trial(x).2);
        let (after, p, _) = trial(lo);
        *b = after;
        (p, lo)
    }
}
