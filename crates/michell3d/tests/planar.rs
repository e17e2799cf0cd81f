//! Skelton's planar truss: yield mass closed form (ERRATA 4.3), the published normalised
//! masses (ERRATA 4.4), Michell's continuum limit, and the force regions of Fig. 4.4 (ERRATA 4.2).

use michell3d::planar::{
    force_regions, michell_continuum_normalized, tip_member_force, yield_mass_normalized,
};
use michell3d::*;
use std::f64::consts::{FRAC_PI_4, FRAC_PI_6, PI};

fn solve(p: MichellParams, w: nalgebra::Vector3<f64>) -> (MichellTruss, ForceSolution) {
    let t = MichellTruss::new(p).unwrap();
    let s = propagate_recursive(&t, &NodalLoads::tip(w)).unwrap();
    (t, s)
}

/// Every level carries Σ|t|·l = 2 t₀ c r₀ (t₀ = w₀/(2 sin β)), so the truss yield mass is the
/// closed form q sin φ/(sin β sin(β+φ)) (normalised).
#[test]
fn planar_yield_mass_equals_closed_form() {
    let w0 = 250.0;
    for (q, beta, phi, r0) in [
        (1, 0.5, 0.3, 1.0),
        (3, FRAC_PI_6, PI / 8.0, 2.0),
        (7, 0.9, 0.2, 0.7),
        (12, FRAC_PI_4, 0.1, 1.0),
        (25, 0.4, 0.05, 1.5),
    ] {
        let p = MichellParams::planar(q, r0, beta, phi);
        let (t, s) = solve(p, in_plane_load(w0, 1.5 * PI));
        let m = normalized_yield_mass(&t.lengths(), &s.force_density, w0, r0);
        let closed = yield_mass_normalized(&p);
        assert!(
            (m - closed).abs() < 1e-10 * closed,
            "q = {q}: {m} vs {closed}"
        );
        // Per level: Σ|f|·l = 2 t₀ c r₀.
        let c = p.c();
        let t0 = tip_member_force(w0, beta);
        let f = s.forces(&t);
        for lev in 0..q {
            let sum: f64 = t
                .members()
                .iter()
                .zip(&f)
                .filter(|(m, _)| t.nodes()[m.parent].tuple.level() == lev)
                .map(|(m, f)| f.abs() * m.length)
                .sum();
            assert!((sum - 2.0 * t0 * c * r0).abs() < 1e-10 * sum, "level {lev}");
        }
        // Tip members carry t₀.
        assert!((f[0].abs() - t0).abs() < 1e-10 * t0 && (f[1].abs() - t0).abs() < 1e-10 * t0);
    }
}

/// ERRATA 4.4: with φ = π/q, β = π/6 the normalised yield mass is 4.62 (q = 2), 6.43 (5),
/// 8.32 (10), 10.90 (35), tending to π/sin²β = 4π.
#[test]
fn published_normalised_planar_masses() {
    for (q, published) in [(2, 4.62), (5, 6.43), (10, 8.32), (35, 10.90)] {
        let p = michell3d::complexity::fig_4_18_params(q, None);
        let (t, s) = solve(p, tip_load(1000.0, 0.0, PI).unwrap());
        let m = normalized_yield_mass(&t.lengths(), &s.force_density, 1000.0, 1.0);
        assert!((m - published).abs() < 5e-3, "q = {q}: {m}");
    }
    let p = michell3d::complexity::fig_4_18_params(100_000, None);
    assert!((yield_mass_normalized(&p) - 4.0 * PI).abs() < 1e-3);
}

/// β = π/4: the discrete mass tends to Michell's 2 w r₀ ln(r₀/r_q)/σ as q grows (fixed qφ).
#[test]
fn michell_continuum_limit_for_beta_pi_4() {
    let span = PI / 2.0;
    let mut last_err = f64::INFINITY;
    for q in [2, 8, 32, 128] {
        let p = MichellParams::planar(q, 1.0, FRAC_PI_4, span / q as f64);
        let (t, s) = solve(p, in_plane_load(1.0, 1.5 * PI));
        let m = normalized_yield_mass(&t.lengths(), &s.force_density, 1.0, 1.0);
        let cont = michell_continuum_normalized(&p);
        let err = (m / cont - 1.0).abs();
        assert!(err < last_err, "q = {q}: error {err} did not decrease");
        last_err = err;
    }
    assert!(last_err < 5e-3, "q = 128: relative error {last_err}");
    let p = MichellParams::planar(2000, 1.0, FRAC_PI_4, span / 2000.0);
    let ratio = yield_mass_normalized(&p) / michell_continuum_normalized(&p);
    assert!((ratio - 1.0).abs() < 2e-4, "q = 2000: {ratio}");
    // Both tend to 2·(qφ) for β = π/4.
    assert!((michell_continuum_normalized(&p) - 2.0 * span).abs() < 5e-3);
}

/// Fig. 4.4 (ERRATA 4.2): θ ∈ [π+β, 2π−β] → U spiral in tension, D in compression; θ ∈ [β, π−β]
/// → the reverse; outside, both signs occur in some member family.
#[test]
fn force_regions_of_fig_4_4() {
    for q in [1, 2, 4, 7] {
        let beta = 0.5;
        let p = MichellParams::planar(q, 1.0, beta, 0.25);
        let [(a1, b1), (a2, b2)] = force_regions(beta);
        for (lo, hi, up_tension) in [(a1, b1, true), (a2, b2, false)] {
            for i in 0..=10 {
                let theta = lo + (hi - lo) * (0.001 + 0.998 * i as f64 / 10.0);
                let (t, s) = solve(p, in_plane_load(10.0, theta));
                for (m, q) in t.members().iter().zip(&s.force_density) {
                    assert_eq!((*q > 0.0) == m.branch.is_up(), up_tension, "θ = {theta}");
                }
            }
        }
        // Just outside the first region the tip U member flips sign.
        let (_, s) = solve(p, in_plane_load(10.0, a1 - 0.05));
        assert!(s.force_density[0] < 0.0);
    }
}
