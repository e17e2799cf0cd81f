//! [`Tableau`]: the Butcher coefficients of the Runge–Kutta methods, one type for the
//! explicit, the embedded, the diagonally implicit and the additive (IMEX) sets, with the
//! named sets the integrators take theirs from: [`RK4`], [`DORMAND_PRINCE`] (5(4)),
//! [`SDIRK3`] (Alexander's SDIRK 3(2)) and [`ARK3`] (ARK3(2)4L\[2\]SA).
//!
//! # Equations
//!
//! An s-stage method (A, b, c) advances y' = f(t, y) from y_n by a step h:
//!
//! Y_i = y_n + h Σ_j a_ij k_j,   k_i = f(t_n + c_i h, Y_i),   y_{n+1} = y_n + h Σ_i b_i k_i.
//!
//! * **Explicit**: A strictly lower triangular, so each Y_i needs only the earlier stages.
//! * **Embedded pair**: weights b̂ of a lower order on the same stages; the local error is
//!   estimated by h Σ_i e_i k_i with the error weights e = b − b̂ ([`Tableau::e`]).
//! * **(E)SDIRK**: A lower triangular with a constant diagonal γ ([`Tableau::gamma`]; an
//!   ESDIRK has a₁₁ = 0): each stage is one implicit equation
//!   Y_i = ψ_i + hγ f(t_n + c_i h, Y_i), ψ_i = y_n + h Σ_{j<i} a_ij k_j. Stiffly accurate when
//!   the last row of A is b (then y_{n+1} = Y_s).
//! * **Additive (ARK)**: for y' = f_E(y) + f_I(y), an explicit A^E ([`Tableau::a`]) for f_E
//!   and an ESDIRK A^I ([`Tableau::a_implicit`]) for f_I with shared b and c:
//!   Y_i = y_n + h Σ_{j<i} a^E_ij f_E(Y_j) + h Σ_{j≤i} a^I_ij f_I(Y_j),
//!   y_{n+1} = y_n + h Σ_i b_i (f_E + f_I)(Y_i).
//! * **Dense output** (Dormand–Prince, Hairer's continuous extension of order 4): with
//!   θ = (t − t_n)/h, Δ = y_{n+1} − y_n and d = h Σ_i d_i k_i ([`Tableau::dense`]),
//!   y(t) ≈ y_n + θ (Δ + (1 − θ)(h k₁ − Δ + θ (Δ − h k₇ − (h k₁ − Δ) + (1 − θ) d))).
//!
//! The order conditions up to order 5 are checked in this file's tests, with the L-stability
//! of the implicit sets; the coefficients are the published ones, and the integrators read
//! them from here without changing the arithmetic of their steps.

/// The Butcher coefficients of one Runge–Kutta method (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tableau<const S: usize> {
    /// The method's name.
    pub name: &'static str,
    /// Classical order of y_{n+1} (of the pair, for an additive method).
    pub order: u32,
    /// Order of the embedded solution b̂, if there is one.
    pub embedded_order: Option<u32>,
    /// Stage matrix A (for an additive pair: the explicit A^E).
    pub a: [[f64; S]; S],
    /// Weights b.
    pub b: [f64; S],
    /// Abscissae c (c = A·1).
    pub c: [f64; S],
    /// Embedded weights b̂.
    pub b_hat: Option<[f64; S]>,
    /// Error weights e = b − b̂ as the step uses them (for Dormand–Prince the published
    /// rationals, not the rounded difference).
    pub e: Option<[f64; S]>,
    /// The implicit stage matrix A^I of an additive pair (sharing b and c).
    pub a_implicit: Option<[[f64; S]; S]>,
    /// The diagonal γ of the (E)SDIRK part.
    pub gamma: Option<f64>,
    /// Dense-output coefficients d (module docs).
    pub dense: Option<[f64; S]>,
}

impl<const S: usize> Tableau<S> {
    /// The number of stages s.
    pub const fn stages(&self) -> usize {
        S
    }

    /// γ, the diagonal of the implicit part (a compile error in a constant for a method
    /// without one).
    pub const fn diagonal(&self) -> f64 {
        match self.gamma {
            Some(g) => g,
            None => panic!("the method has no implicit diagonal"),
        }
    }

    /// The error weights e = b − b̂ (panics for a method without an embedded pair).
    pub const fn error_weights(&self) -> [f64; S] {
        match self.e {
            Some(e) => e,
            None => panic!("the method has no embedded pair"),
        }
    }

    /// The embedded weights b̂ (panics for a method without an embedded pair).
    pub const fn embedded(&self) -> [f64; S] {
        match self.b_hat {
            Some(b) => b,
            None => panic!("the method has no embedded pair"),
        }
    }

    /// The implicit stage matrix A^I (panics for a method that is not additive).
    pub const fn implicit(&self) -> [[f64; S]; S] {
        match self.a_implicit {
            Some(a) => a,
            None => panic!("the method is not an additive pair"),
        }
    }

    /// The dense-output coefficients d (panics for a method without them).
    pub const fn dense_output(&self) -> [f64; S] {
        match self.dense {
            Some(d) => d,
            None => panic!("the method has no dense output"),
        }
    }

    /// Whether A is strictly lower triangular (and there is no implicit part).
    pub fn is_explicit(&self) -> bool {
        self.a_implicit.is_none() && (0..S).all(|i| (i..S).all(|j| self.a[i][j] == 0.0))
    }
}

/// Classic fourth-order Runge–Kutta: c = (0, ½, ½, 1), b = (1, 2, 2, 1)/6.
pub const RK4: Tableau<4> = Tableau {
    name: "RK4",
    order: 4,
    embedded_order: None,
    a: [
        [0.0; 4],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    b: [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    c: [0.0, 0.5, 0.5, 1.0],
    b_hat: None,
    e: None,
    a_implicit: None,
    gamma: None,
    dense: None,
};

/// Dormand–Prince 5(4) (DOPRI5; Dormand & Prince 1980, Hairer, Nørsett & Wanner §II.5):
/// seven stages, first same as last (the last row of A is b, c₇ = 1), with Hairer's
/// continuous extension of order 4.
pub const DORMAND_PRINCE: Tableau<7> = Tableau {
    name: "Dormand–Prince 5(4)",
    order: 5,
    embedded_order: Some(4),
    a: [
        [0.0; 7],
        [0.2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
            0.0,
        ],
        DP_B,
    ],
    b: DP_B,
    c: [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0],
    b_hat: Some([
        5179.0 / 57600.0,
        0.0,
        7571.0 / 16695.0,
        393.0 / 640.0,
        -92097.0 / 339200.0,
        187.0 / 2100.0,
        1.0 / 40.0,
    ]),
    e: Some([
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ]),
    a_implicit: None,
    gamma: None,
    dense: Some([
        -12715105075.0 / 11282082432.0,
        0.0,
        87487479700.0 / 32700410799.0,
        -10690763975.0 / 1880347072.0,
        701980252875.0 / 199316789632.0,
        -1453857185.0 / 822651844.0,
        69997945.0 / 29380423.0,
    ]),
};

/// The fifth-order weights of Dormand–Prince (also the last row of its A).
const DP_B: [f64; 7] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
    0.0,
];

/// γ of Alexander's SDIRK3: the root in (1/6, 1/2) of x³ − 3x² + 3x/2 − 1/6.
pub const SDIRK_GAMMA: f64 = 0.435_866_521_508_459;

/// b₁ = −(6γ² − 16γ + 1)/4 of [`SDIRK3`].
const SDIRK_B1: f64 = -(6.0 * SDIRK_GAMMA * SDIRK_GAMMA - 16.0 * SDIRK_GAMMA + 1.0) / 4.0;
/// b₂ = (6γ² − 20γ + 5)/4 of [`SDIRK3`].
const SDIRK_B2: f64 = (6.0 * SDIRK_GAMMA * SDIRK_GAMMA - 20.0 * SDIRK_GAMMA + 5.0) / 4.0;
/// The embedded weights of [`SDIRK3`]: (γ/(1−γ), (1−2γ)/(1−γ), 0).
const SDIRK_B_HAT: [f64; 3] = [
    SDIRK_GAMMA / (1.0 - SDIRK_GAMMA),
    (1.0 - 2.0 * SDIRK_GAMMA) / (1.0 - SDIRK_GAMMA),
    0.0,
];

/// Alexander's three-stage SDIRK of order 3 (SIAM J. Numer. Anal. 14, 1977), stiffly
/// accurate and L-stable, with an embedded order-2 solution:
///
/// ```text
///  γ  | γ
///  c₂ | (1−γ)/2   γ                    c₂ = (1+γ)/2
///  1  | b₁        b₂      γ            b₁ = −(6γ² − 16γ + 1)/4,  b₂ = (6γ² − 20γ + 5)/4
/// ----+-------------------------
///     | b₁        b₂      γ
///     | γ/(1−γ)   (1−2γ)/(1−γ)  0      (embedded, order 2)
/// ```
pub const SDIRK3: Tableau<3> = Tableau {
    name: "SDIRK 3(2)",
    order: 3,
    embedded_order: Some(2),
    a: [
        [SDIRK_GAMMA, 0.0, 0.0],
        [(1.0 - SDIRK_GAMMA) / 2.0, SDIRK_GAMMA, 0.0],
        [SDIRK_B1, SDIRK_B2, SDIRK_GAMMA],
    ],
    b: [SDIRK_B1, SDIRK_B2, SDIRK_GAMMA],
    c: [SDIRK_GAMMA, (1.0 + SDIRK_GAMMA) / 2.0, 1.0],
    b_hat: Some(SDIRK_B_HAT),
    e: Some([
        SDIRK_B1 - SDIRK_B_HAT[0],
        SDIRK_B2 - SDIRK_B_HAT[1],
        SDIRK_GAMMA - SDIRK_B_HAT[2],
    ]),
    a_implicit: None,
    gamma: Some(SDIRK_GAMMA),
    dense: None,
};

/// γ of ARK3(2)4L\[2\]SA's ESDIRK part.
const ARK_GAMMA: f64 = 0.435_866_521_508_459;

/// The implicit (ESDIRK) tableau a^I of ARK3(2)4L\[2\]SA; its last row is the weights b of
/// both.
const ARK_AI: [[f64; 4]; 4] = [
    [0.0; 4],
    [ARK_GAMMA, ARK_GAMMA, 0.0, 0.0],
    [
        0.257_648_246_066_427_2,
        -0.093_514_767_574_886_25,
        ARK_GAMMA,
        0.0,
    ],
    [
        0.187_641_024_346_723_8,
        -0.595_297_473_576_955,
        0.971_789_927_721_772_1,
        ARK_GAMMA,
    ],
];

/// ARK3(2)4L\[2\]SA of Kennedy & Carpenter (Appl. Numer. Math. 44, 2003): a four-stage
/// explicit tableau a^E ([`Tableau::a`]) paired with an L-stable, stiffly accurate ESDIRK
/// a^I ([`Tableau::a_implicit`], diagonal γ) of order 3, sharing b (the last row of a^I) and
/// c. Its embedded order-2 weights are not used (the method runs at fixed steps here).
pub const ARK3: Tableau<4> = Tableau {
    name: "ARK3(2)4L[2]SA",
    order: 3,
    embedded_order: None,
    a: [
        [0.0; 4],
        [0.871_733_043_016_918, 0.0, 0.0, 0.0],
        [0.527_589_011_976_300_4, 0.072_410_988_023_699_6, 0.0, 0.0],
        [
            0.399_096_007_676_070_1,
            -0.437_557_654_613_519_4,
            1.038_461_646_937_449_3,
            0.0,
        ],
    ],
    b: ARK_AI[3],
    c: [0.0, 0.871_733_043_016_918, 0.6, 1.0],
    b_hat: None,
    e: None,
    a_implicit: Some(ARK_AI),
    gamma: Some(ARK_GAMMA),
    dense: None,
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kind::IntegratorKind;

    /// The largest residual of the order conditions of (A, b, c) up to `order` (≤ 5), i.e.
    /// of every rooted tree with at most `order` nodes.
    fn order_residual<const S: usize>(
        a: &[[f64; S]; S],
        b: &[f64; S],
        c: &[f64; S],
        order: u32,
    ) -> f64 {
        let dot = |u: &[f64; S], v: &[f64; S]| u.iter().zip(v).map(|(x, y)| x * y).sum::<f64>();
        let mul = |u: &[f64; S], v: &[f64; S]| -> [f64; S] { std::array::from_fn(|i| u[i] * v[i]) };
        let am = |v: &[f64; S]| -> [f64; S] { std::array::from_fn(|i| dot(&a[i], v)) };
        let one = [1.0; S];
        let c2 = mul(c, c);
        let c3 = mul(&c2, c);
        let ac = am(c);
        let ac2 = am(&c2);
        let aac = am(&ac);
        let mut conditions: Vec<(f64, f64)> = vec![(dot(b, &one), 1.0)];
        if order >= 2 {
            conditions.push((dot(b, c), 0.5));
        }
        if order >= 3 {
            conditions.push((dot(b, &c2), 1.0 / 3.0));
            conditions.push((dot(b, &ac), 1.0 / 6.0));
        }
        if order >= 4 {
            conditions.push((dot(b, &c3), 0.25));
            conditions.push((dot(b, &mul(c, &ac)), 1.0 / 8.0));
            conditions.push((dot(b, &ac2), 1.0 / 12.0));
            conditions.push((dot(b, &aac), 1.0 / 24.0));
        }
        if order >= 5 {
            conditions.push((dot(b, &mul(&c3, c)), 0.2));
            conditions.push((dot(b, &mul(&c2, &ac)), 0.1));
            conditions.push((dot(b, &mul(c, &ac2)), 1.0 / 15.0));
            conditions.push((dot(b, &mul(c, &aac)), 1.0 / 30.0));
            conditions.push((dot(b, &mul(&ac, &ac)), 0.05));
            conditions.push((dot(b, &am(&c3)), 0.05));
            conditions.push((dot(b, &am(&mul(c, &ac))), 1.0 / 40.0));
            conditions.push((dot(b, &am(&ac2)), 1.0 / 60.0));
            conditions.push((dot(b, &am(&aac)), 1.0 / 120.0));
        }
        conditions
            .iter()
            .map(|(got, want)| (got - want).abs())
            .fold(0.0, f64::max)
    }

    /// c = A·1 for every stage matrix of `t`.
    fn assert_row_sums<const S: usize>(t: &Tableau<S>) {
        for a in std::iter::once(t.a).chain(t.a_implicit) {
            for i in 0..S {
                let row: f64 = a[i].iter().sum();
                assert!(
                    (row - t.c[i]).abs() < 1e-14,
                    "{} row {i}: {row} vs {}",
                    t.name,
                    t.c[i]
                );
            }
        }
    }

    #[test]
    fn every_set_has_its_stated_order_and_not_more() {
        fn check<const S: usize>(t: &Tableau<S>) {
            assert_row_sums(t);
            for a in std::iter::once(t.a).chain(t.a_implicit) {
                let r = order_residual(&a, &t.b, &t.c, t.order);
                assert!(r < 1e-14, "{}: order {} residual {r}", t.name, t.order);
                if t.order < 5 {
                    let r = order_residual(&a, &t.b, &t.c, t.order + 1);
                    assert!(r > 1e-6, "{}: order {} holds too", t.name, t.order + 1);
                }
            }
            if let (Some(b_hat), Some(p)) = (t.b_hat, t.embedded_order) {
                let r = order_residual(&t.a, &b_hat, &t.c, p);
                assert!(r < 1e-14, "{} embedded: residual {r}", t.name);
                let r = order_residual(&t.a, &b_hat, &t.c, p + 1);
                assert!(r > 1e-6, "{} embedded: order {} holds too", t.name, p + 1);
                let e = t.error_weights();
                for i in 0..S {
                    assert!((t.b[i] - b_hat[i] - e[i]).abs() < 1e-15, "{} e{i}", t.name);
                }
            }
        }
        check(&RK4);
        check(&DORMAND_PRINCE);
        check(&SDIRK3);
        check(&ARK3);
        assert!(RK4.is_explicit() && DORMAND_PRINCE.is_explicit());
        assert!(!SDIRK3.is_explicit() && !ARK3.is_explicit());
        // FSAL: the last stage of Dormand–Prince is y_{n+1}
        assert_eq!(DORMAND_PRINCE.a[6], DORMAND_PRINCE.b);
        assert_eq!(DORMAND_PRINCE.c[6], 1.0);
    }

    /// The per-method facts ([`IntegratorKind::facts`]) state the order of the tableau the
    /// method takes its coefficients from.
    #[test]
    fn the_facts_table_states_the_tableaux_orders() {
        assert_eq!(IntegratorKind::Rk4.facts().order, RK4.order);
        assert_eq!(IntegratorKind::Rk4Flight.facts().order, RK4.order);
        assert_eq!(IntegratorKind::Rk45.facts().order, DORMAND_PRINCE.order);
        assert_eq!(IntegratorKind::Sdirk.facts().order, SDIRK3.order);
        assert_eq!(IntegratorKind::ImexArk.facts().order, ARK3.order);
    }

    /// The constants equal the coefficients computed at run time, to the bit (the methods'
    /// results do not depend on where the arithmetic was done).
    #[test]
    fn the_constant_coefficients_are_the_run_time_ones() {
        let g = std::hint::black_box(SDIRK_GAMMA);
        let b1 = -(6.0 * g * g - 16.0 * g + 1.0) / 4.0;
        let b2 = (6.0 * g * g - 20.0 * g + 5.0) / 4.0;
        let b_hat = [g / (1.0 - g), (1.0 - 2.0 * g) / (1.0 - g), 0.0];
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&SDIRK3.b), bits(&[b1, b2, g]));
        assert_eq!(bits(&SDIRK3.c), bits(&[g, (1.0 + g) / 2.0, 1.0]));
        assert_eq!(bits(&SDIRK3.a[1]), bits(&[(1.0 - g) / 2.0, g, 0.0]));
        assert_eq!(bits(&SDIRK3.embedded()), bits(&b_hat));
        let e: Vec<f64> = (0..3).map(|j| SDIRK3.b[j] - b_hat[j]).collect();
        assert_eq!(bits(&SDIRK3.error_weights()), bits(&e));
    }

    /// Alexander's SDIRK: γ solves its cubic, the method is stiffly accurate with a
    /// non-singular A, so R(∞) = 1 − bᵀA⁻¹1 = 0 (L-stable), |R| < 1 on the negative axis, and
    /// the embedded pair differs at third order (a genuine error estimate).
    #[test]
    fn sdirk3_is_l_stable() {
        let t = SDIRK3;
        let g = t.diagonal();
        assert!((g.powi(3) - 3.0 * g * g + 1.5 * g - 1.0 / 6.0).abs() < 1e-15);
        let dot = |u: &[f64; 3], v: &[f64; 3]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
        let c2 = t.c.map(|c| c * c);
        assert!((dot(&t.embedded(), &c2) - 1.0 / 3.0).abs() > 1e-2);
        assert_eq!(t.a[2], t.b);
        // R(z) at z → −∞ through the stability function R(z) = 1 + z bᵀ(I − zA)⁻¹1
        let r = |z: f64| {
            // forward substitution of (I − zA) u = 1 (A lower triangular)
            let mut u = [0.0; 3];
            for i in 0..3 {
                let s: f64 = (0..i).map(|j| t.a[i][j] * u[j]).sum();
                u[i] = (1.0 + z * s) / (1.0 - z * t.a[i][i]);
            }
            1.0 + z * dot(&t.b, &u)
        };
        assert!(r(-1e8).abs() < 1e-6, "R(-1e8) = {}", r(-1e8));
        for z in [-0.1, -1.0, -10.0, -100.0] {
            assert!(r(z).abs() < 1.0, "|R({z})| = {}", r(z).abs());
        }
        // a small step reproduces exp(z) to third order
        let z: f64 = -1e-2;
        assert!((r(z) - z.exp()).abs() < 1e-8);
    }

    /// ARK3(2)4L[2]SA: the ESDIRK part has the diagonal γ and is A-stable on the imaginary
    /// axis and L-stable; b is its last row (stiffly accurate).
    #[test]
    fn the_ark_pair_has_an_l_stable_implicit_part() {
        let ai = ARK3.implicit();
        let b = ARK3.b;
        let gamma = ARK3.diagonal();
        assert_eq!(ai[3], b);
        assert_eq!(ai[0][0], 0.0);
        for i in 1..4 {
            assert_eq!(ai[i][i], gamma);
        }
        // the ESDIRK's stability function R(z) (y' = z y): |R| ≤ 1 on the imaginary axis, and
        // R → 0 as z → −∞ (L-stable)
        let r = |z: nalgebra::Complex<f64>| {
            let mut y = [nalgebra::Complex::new(1.0, 0.0); 4];
            for i in 1..4 {
                let explicit: nalgebra::Complex<f64> = (0..i).map(|j| y[j] * ai[i][j]).sum();
                y[i] = (z * explicit + 1.0) / (-z * gamma + 1.0);
            }
            z * (0..4).map(|i| y[i] * b[i]).sum::<nalgebra::Complex<f64>>() + 1.0
        };
        for w in [0.1, 1.0, 10.0, 1e3, 1e6] {
            let m = r(nalgebra::Complex::new(0.0, w)).norm();
            assert!(m <= 1.0 + 1e-12, "|R({w} i)| = {m}");
        }
        assert!(r(nalgebra::Complex::new(-1e9, 0.0)).norm() < 1e-8);
        assert!((r(nalgebra::Complex::new(-1e-4, 0.0)).re - (-1e-4f64).exp()).abs() < 1e-15);
    }
}
