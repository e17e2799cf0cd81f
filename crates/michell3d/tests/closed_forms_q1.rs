//! Complexity-1 closed forms: eq. 4.15–4.20 (cylindrical), 4.25–4.31 (spherical), the sign
//! conditions 4.21–4.23 (4.23 as corrected by ERRATA 4.13), the member lengths of ERRATA
//! 4.26–4.27 and the buckling criterion of eq. 4.65 (ERRATA 4.28). The formulas are typed in
//! here independently of the crate.
use crate::common;

use common::Rng;
use michell3d::sizing::q1_bar_buckling_governs;
use michell3d::*;
use std::f64::consts::PI;
use tensegrity_core::Material;

struct Case {
    r0: f64,
    beta: f64,
    phi: f64,
    w0: f64,
    az: f64,
    gamma: f64,
}

fn random_case(rng: &mut Rng) -> Case {
    let beta = rng.uniform(0.15, 1.4);
    Case {
        r0: rng.uniform(0.3, 3.0),
        beta,
        phi: rng.uniform(0.1, (PI - beta).min(1.2) - 0.05),
        w0: rng.uniform(1.0, 5000.0),
        az: rng.uniform(0.0, 2.0 * PI),
        gamma: rng.uniform(0.0, PI),
    }
}

fn ac(beta: f64, phi: f64) -> (f64, f64) {
    let s = (beta + phi).sin();
    (beta.sin() / s, phi.sin() / s)
}

/// Eq. 4.15–4.17, members (1010, 1001, 0100).
fn cylindrical_q1(k: &Case, delta: f64) -> [f64; 3] {
    let (a, c) = ac(k.beta, k.phi);
    let (b, r0, w0) = (k.beta, k.r0, k.w0);
    let (sp, cp, sg, cg) = (k.az.sin(), k.az.cos(), k.gamma.sin(), k.gamma.cos());
    let pre = w0 / (2.0 * r0 * delta * a * c * (2.0 * b).sin());
    let t = (sp * sg * b.sin() - cg * b.cos()) * a * delta;
    let u = c * cp * sg * (2.0 * b).sin();
    [
        pre * (t - u),
        pre * (t + u),
        w0 / (r0 * c * (2.0 * b).sin()) * (sp * sg * b.sin() + cg * b.cos()),
    ]
}

/// Eq. 4.25–4.28.
fn spherical_q1(k: &Case, eps: f64) -> [f64; 3] {
    let (a, _) = ac(k.beta, k.phi);
    let (r0, w0, phi) = (k.r0, k.w0, k.phi);
    let (sp, cp, sg, cg) = (k.az.sin(), k.az.cos(), k.gamma.sin(), k.gamma.cos());
    let sigma = cp * sg / (a * r0 * phi.cos() * eps.tan());
    let rho = sp * sg / (r0 * (1.0 - a * phi.cos()));
    let e = cg / (a * r0 * phi.sin());
    [
        w0 / 4.0 * (rho - 2.0 * sigma - e),
        w0 / 4.0 * (rho + 2.0 * sigma - e),
        w0 / 2.0 * (rho + e),
    ]
}

fn solve(p: MichellParams, k: &Case, method: Method) -> Vec<f64> {
    let t = MichellTruss::new(p).unwrap();
    // Member order: parent 0, children UL = 1010, UR = 1001, D = 0100.
    assert_eq!(t.label(t.members()[0].child), vec![1, 0, 1, 0]);
    assert_eq!(t.label(t.members()[1].child), vec![1, 0, 0, 1]);
    assert_eq!(t.label(t.members()[2].child), vec![0, 1, 0, 0]);
    let w = tip_load(k.w0, k.az, k.gamma).unwrap();
    propagate(&t, &NodalLoads::tip(w), method)
        .unwrap()
        .force_density
}

fn assert_close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= tol * scale,
            "{what}: got {got:?}, want {want:?}"
        );
    }
}

#[test]
fn cylindrical_q1_matches_eq_4_15_to_4_17() {
    let mut rng = Rng::new(1);
    for _ in 0..200 {
        let k = random_case(&mut rng);
        let delta = rng.uniform(0.05, 1.0)
            * if rng.uniform(0.0, 1.0) < 0.3 {
                -1.0
            } else {
                1.0
            };
        let p = MichellParams::cylindrical(1, k.r0, k.beta, k.phi, delta);
        let want = cylindrical_q1(&k, delta);
        assert_close(&solve(p, &k, Method::Recursive), &want, 1e-12, "recursive");
        assert_close(&solve(p, &k, Method::Global), &want, 1e-12, "global");
    }
}

#[test]
fn spherical_q1_matches_eq_4_25_to_4_28() {
    let mut rng = Rng::new(2);
    for _ in 0..200 {
        let k = random_case(&mut rng);
        let eps = rng.uniform(0.05, 1.5)
            * if rng.uniform(0.0, 1.0) < 0.3 {
                -1.0
            } else {
                1.0
            };
        let p = MichellParams::spherical(1, k.r0, k.beta, k.phi, eps);
        let want = spherical_q1(&k, eps);
        assert_close(&solve(p, &k, Method::Recursive), &want, 1e-12, "recursive");
        assert_close(&solve(p, &k, Method::Global), &want, 1e-12, "global");
    }
}

/// Eq. 4.18–4.20 and 4.29–4.31: φ_w = 0, γ = π gives w₀/(4 r₀ c sin β) (twice) and
/// −w₀/(2 r₀ c sin β), in both parameterisations.
#[test]
fn q1_bending_special_case() {
    let (r0, beta, phi, w0) = (1.3, 0.6, 0.35, 750.0);
    let (_, c) = ac(beta, phi);
    let lam = w0 / (4.0 * r0 * c * beta.sin());
    let want = [lam, lam, -2.0 * lam];
    let k = Case {
        r0,
        beta,
        phi,
        w0,
        az: 0.0,
        gamma: PI,
    };
    for p in [
        MichellParams::cylindrical(1, r0, beta, phi, 0.37),
        MichellParams::spherical(1, r0, beta, phi, 0.2),
    ] {
        assert_close(
            &solve(p, &k, Method::Recursive),
            &want,
            1e-12,
            "special case",
        );
    }
}

/// Eq. 4.21, 4.22 and corrected 4.23 predict the sign of every q = 1 member on a 40×20 grid.
#[test]
fn q1_sign_conditions_match_sign_map() {
    let (beta, phi, delta, r0) = (0.5, 0.4, 0.3, 1.0);
    let (a, c) = ac(beta, phi);
    let t = MichellTruss::new(MichellParams::cylindrical(1, r0, beta, phi, delta)).unwrap();
    let az = AngleGrid::new(0.0, 2.0 * PI, 40);
    let po = AngleGrid::new(0.013, PI - 0.013, 20);
    let maps = sign_maps(&t, &[0, 1, 2], 10.0, az, po, Method::Recursive).unwrap();
    let mut checked = 0;
    for ip in 0..po.n {
        for ia in 0..az.n {
            let (p, g) = (az.at(ia), po.at(ip));
            let lhs = (p.sin() * g.sin() * beta.sin() - g.cos() * beta.cos()) * a * delta;
            let rhs = c * p.cos() * g.sin() * (2.0 * beta).sin();
            let predicted = [
                lhs > rhs,
                lhs > -rhs,
                p.sin() * g.sin() * beta.sin() > -g.cos() * beta.cos(),
            ];
            for m in 0..3 {
                let s = maps[m].sign(ip, ia);
                if s != 0 {
                    assert_eq!(s > 0, predicted[m], "member {m} at φ={p}, γ={g}");
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 2300);
    // Regions are not trivial: each member is in tension on part of the sphere only.
    for m in &maps {
        let f = m.tension_fraction();
        assert!(f > 0.1 && f < 0.9, "tension fraction {f}");
    }
}

/// ERRATA 4.26/4.27: ‖m₁₀₁₀‖ = r₀√(a²δ²+c²) (0.507442 at β = π/6, φ = π/8, δ = 0.25) and
/// ‖m₀₁₀₀‖ = r₀c.
#[test]
fn q1_member_lengths() {
    let (beta, phi, delta) = (PI / 6.0, PI / 8.0, 0.25);
    let t = MichellTruss::new(MichellParams::cylindrical(1, 1.0, beta, phi, delta)).unwrap();
    let (a, c) = ac(beta, phi);
    assert!((t.members()[0].length - 0.507442).abs() < 1e-6);
    assert!((t.members()[0].length - (a * a * delta * delta + c * c).sqrt()).abs() < 1e-14);
    assert!((t.members()[1].length - t.members()[0].length).abs() < 1e-14);
    assert!((t.members()[2].length - c).abs() < 1e-14);
}

/// Corrected eq. 4.65: the q = 1 bar buckles iff r₀² c² sin β > π w₀ E / (8 σ²); the sizing
/// agrees on both sides of the threshold, and the bar's radius is eq. 4.63/4.64.
#[test]
fn q1_bar_failure_mode_matches_eq_4_65() {
    let steel = Material::new(7862.0, 210e9, 690e6);
    let (beta, phi) = (PI / 6.0, PI / 8.0);
    let (_, c) = ac(beta, phi);
    // Threshold load w* = 8 σ² r₀² c² sin β / (π E).
    let w_star = 8.0 * 690e6f64.powi(2) * c * c * beta.sin() / (PI * 210e9);
    for (w0, buckles) in [(0.5 * w_star, true), (2.0 * w_star, false)] {
        let p = MichellParams::cylindrical(1, 1.0, beta, phi, 0.25);
        assert_eq!(q1_bar_buckling_governs(&p, w0, &steel), buckles);
        let t = MichellTruss::new(p).unwrap();
        let s = propagate_recursive(&t, &NodalLoads::tip(tip_load(w0, 0.0, PI).unwrap())).unwrap();
        let sizing = size_members(&t.lengths(), &s.forces(&t), &steel, &steel);
        assert_eq!(sizing.members[2].kind, MemberKind::Bar);
        assert_eq!(sizing.members[0].kind, MemberKind::String);
        assert_eq!(sizing.buckling_governed == vec![2], buckles);
        // Eq. 4.62–4.64 with the corrected lengths.
        let b = c; // r0 = 1
        let r_y = (w0 * b / (2.0 * PI * 690e6 * c * beta.sin())).sqrt();
        let r_b = (2.0 * w0 * b.powi(3) / (PI.powi(3) * 210e9 * c * beta.sin())).powf(0.25);
        let r = sizing.members[2].size.unwrap().radius;
        assert!((r - r_y.max(r_b)).abs() < 1e-12 * r);
        let s_len = t.members()[0].length;
        let r_s = (w0 * s_len / (4.0 * PI * 690e6 * c * beta.sin())).sqrt();
        assert!((sizing.members[0].size.unwrap().radius - r_s).abs() < 1e-12 * r_s);
    }
}
