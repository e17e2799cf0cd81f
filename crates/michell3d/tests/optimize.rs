//! Michell optima (Skelton's setting, fixed ρ = r_q/r₀) against closed forms, brute force and
//! the continuum limit.

use michell3d::optimize::{
    beta_for, continuum_normalized, joint_count, optimize, planar_yield_optimum, OptimizeRequest,
};
use michell3d::{analyse, AnalysisRequest, Geometry, MichellParams, MichellTruss};

/// Normalised yield mass of the planar truss at (q, φ) with β from ρ, through the force
/// propagation and sizing (not the closed form).
fn propagated_yield_mass(q: usize, rho: f64, phi: f64) -> f64 {
    let a = rho.powf(1.0 / q as f64);
    let p = MichellParams::planar(q, 1.0, beta_for(a, phi), phi);
    assert!(
        (p.radius(q) - rho).abs() < 1e-12,
        "the truss reaches r_q = ρ r₀"
    );
    analyse(&AnalysisRequest::new(p))
        .unwrap()
        .normalized_yield_mass
}

#[test]
fn the_planar_closed_form_optimum_is_the_minimum_of_the_propagated_mass() {
    for (q, rho) in [(1, 0.5), (3, 0.25), (6, 0.1)] {
        let (beta, phi, f) = planar_yield_optimum(q, rho);
        let at_opt = propagated_yield_mass(q, rho, phi);
        assert!((at_opt - f).abs() < 1e-9 * f, "q = {q}: {at_opt} vs {f}");
        // a dense scan of φ never goes below the closed-form optimum
        let best_scan = (1..2000)
            .map(|i| i as f64 * std::f64::consts::PI / 2000.0)
            .map(|p| propagated_yield_mass(q, rho, p))
            .fold(f64::INFINITY, f64::min);
        assert!(
            best_scan >= f * (1.0 - 1e-12),
            "q = {q}: scan {best_scan} < {f}"
        );
        assert!(
            best_scan <= f * (1.0 + 1e-4),
            "q = {q}: scan {best_scan} ≫ {f}"
        );
        let a = rho.powf(1.0 / q as f64);
        assert!((beta.tan() - a).abs() < 1e-14);
        assert!((phi.cos() - 2.0 * a / (1.0 + a * a)).abs() < 1e-14);
    }
}

#[test]
fn the_planar_optimum_tends_to_michells_continuum() {
    let rho: f64 = 0.2;
    let l = (1.0 / rho).ln();
    let mut previous = f64::INFINITY;
    for q in [1usize, 2, 5, 10, 50, 200, 1000] {
        let (_, _, f) = planar_yield_optimum(q, rho);
        assert!(f < previous, "decreasing in q");
        previous = f;
        // 2q sinh(L/q) = 2L (1 + L²/(6q²) + …)
        let gap = f / continuum_normalized(rho) - 1.0;
        let leading = l * l / (6.0 * (q * q) as f64);
        if q >= 10 {
            assert!(
                (gap / leading - 1.0).abs() < 0.01,
                "q = {q}: {gap} vs {leading}"
            );
        }
    }
    assert!((previous / (2.0 * l) - 1.0).abs() < 1e-6);
}

#[test]
fn the_optimal_complexity_with_a_joint_mass_equals_brute_force() {
    for joint_mass in [1e-4, 1e-3, 5e-3] {
        let req = OptimizeRequest {
            joint_mass,
            max_complexity: 200,
            ..OptimizeRequest::new(Geometry::Planar, 0.05)
        };
        let o = optimize(&req).unwrap();
        // steel yield mass per unit normalised mass: the q = 1 analysis gives the factor
        let one = optimize(&OptimizeRequest {
            complexity: Some(1),
            ..req.clone()
        })
        .unwrap();
        let per_unit = one.member_mass_kg / one.normalized_yield_mass;
        let total = |q: usize| {
            per_unit * planar_yield_optimum(q, 0.05).2
                + joint_mass * joint_count(Geometry::Planar, q) as f64
        };
        let brute = (1..=200)
            .min_by(|&a, &b| total(a).total_cmp(&total(b)))
            .unwrap();
        assert_eq!(o.complexity, brute, "joint mass {joint_mass}");
        assert!((o.mass_kg - total(brute)).abs() < 1e-9 * o.mass_kg);
        assert_eq!(o.joints, joint_count(Geometry::Planar, brute));
    }
}

#[test]
fn joint_counts_equal_the_built_trusses() {
    for q in 1..=5 {
        let planar = MichellTruss::new(MichellParams::planar(q, 1.0, 0.5, 0.4)).unwrap();
        assert_eq!(planar.nodes().len(), joint_count(Geometry::Planar, q));
        let cyl = Geometry::Cylindrical { delta: 0.2 };
        let t = MichellTruss::new(MichellParams::cylindrical(q, 1.0, 0.5, 0.4, 0.2)).unwrap();
        assert_eq!(t.nodes().len(), joint_count(cyl, q));
    }
}

#[test]
fn a_three_d_optimum_is_a_local_minimum_and_its_penalty_is_against_the_planar_optimum() {
    let geometry = Geometry::Cylindrical { delta: 0.25 };
    let req = OptimizeRequest {
        complexity: Some(2),
        ..OptimizeRequest::new(geometry, 0.3)
    };
    let o = optimize(&req).unwrap();
    let a = 0.3f64.powf(0.5);
    let mass = |phi: f64| {
        let p = MichellParams::cylindrical(2, 1.0, beta_for(a, phi), phi, 0.25);
        analyse(&AnalysisRequest::new(p))
            .unwrap()
            .mass_kg
            .yield_buckling
    };
    assert!((mass(o.phi) - o.member_mass_kg).abs() < 1e-12);
    for d in [1e-3, 1e-2, 1e-1] {
        assert!(
            mass(o.phi + d) >= o.member_mass_kg * (1.0 - 1e-9),
            "φ + {d}"
        );
        assert!(
            mass(o.phi - d) >= o.member_mass_kg * (1.0 - 1e-9),
            "φ − {d}"
        );
    }
    let planar = o.planar_mass_kg.unwrap();
    assert!((o.mass_penalty.unwrap() - o.mass_kg / planar).abs() < 1e-15);
    // the planar optimum with the same sizing is no heavier than the planar truss at the
    // yield-optimal φ
    let (_, phi_y, _) = planar_yield_optimum(2, 0.3);
    let planar_at = |phi: f64| {
        let p = MichellParams::planar(2, 1.0, beta_for(a, phi), phi);
        analyse(&AnalysisRequest::new(p))
            .unwrap()
            .mass_kg
            .yield_buckling
    };
    assert!(planar <= planar_at(phi_y) * (1.0 + 1e-12));
}

#[test]
fn bad_requests_name_the_parameter() {
    let err = optimize(&OptimizeRequest::new(Geometry::Planar, 1.5)).unwrap_err();
    assert!(err.to_string().contains("radius_ratio"), "{err}");
    let err = optimize(&OptimizeRequest::new(Geometry::Planar, 0.5)).unwrap_err();
    assert!(err.to_string().contains("joint_mass"), "{err}");
}
