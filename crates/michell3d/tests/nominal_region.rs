//! The nominal region of complexity 1 and the extra-string prestress threshold (§4.6–4.7):
//! the exact cone maximisation against dense sampling, and the claim checked on both sides
//! of the threshold.

use michell3d::nominal_region::{member_data, min_extra_prestress, sign_changes, NominalCone};
use michell3d::{ExtraStrings, Method, MichellParams, MichellTruss};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// Quasi-uniform unit directions (Fibonacci sphere).
fn sphere(n: usize) -> Vec<Vector3<f64>> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let a = golden * i as f64;
            Vector3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect()
}

fn trusses() -> Vec<MichellTruss> {
    [
        MichellParams::cylindrical(2, 1.0, PI / 6.0, PI / 8.0, 0.25),
        MichellParams::cylindrical(3, 1.0, PI / 6.0, PI / 8.0, 0.25),
        MichellParams::spherical(3, 1.0, PI / 6.0, PI / 8.0, PI / 24.0),
    ]
    .into_iter()
    .map(|p| MichellTruss::new(p).unwrap())
    .collect()
}

#[test]
fn the_exact_maximum_over_the_region_bounds_and_matches_sampling() {
    let truss = &trusses()[1];
    let cone = NominalCone::of(truss, Method::Recursive).unwrap();
    let inside: Vec<Vector3<f64>> = sphere(200_000)
        .into_iter()
        .filter(|w| cone.contains(w))
        .collect();
    assert!(
        inside.len() > 100,
        "the region has directions: {}",
        inside.len()
    );
    assert!(
        cone.contains(&Vector3::new(0.0, 0.0, -1.0)),
        "the nominal load is inside"
    );
    for c in sphere(40) {
        let (exact, arg) = cone.max_over(&c);
        assert!(cone.contains(&arg) && (arg.norm() - 1.0).abs() < 1e-12);
        assert!((c.dot(&arg) - exact).abs() < 1e-12);
        let sampled = inside.iter().map(|w| c.dot(w)).fold(f64::MIN, f64::max);
        assert!(sampled <= exact + 1e-12, "{sampled} > {exact}");
        assert!(sampled >= exact - 2e-2, "{sampled} ≪ {exact}");
    }
}

#[test]
fn the_prestress_does_not_reach_the_tip_members() {
    for truss in trusses() {
        let strings = ExtraStrings::new(&truss).unwrap();
        let data = member_data(&truss, &strings, Method::Recursive).unwrap();
        let scale = data.pre.iter().fold(0.0f64, |m, p| m.max(p.abs()));
        assert!(scale > 0.0);
        for p in &data.pre[..3] {
            assert!(p.abs() < 1e-12 * scale, "{p}");
        }
    }
}

/// Whether member j takes both signs over the sampled directions (plus `extra`) at prestress t.
fn changes_sign(
    data: &michell3d::nominal_region::LinearForces,
    dirs: &[Vector3<f64>],
    j: usize,
    t: f64,
    w0: f64,
    tol: f64,
) -> bool {
    let f: Vec<f64> = dirs.iter().map(|w| data.forces(&(w0 * w), t)[j]).collect();
    f.iter().any(|&x| x > tol) && f.iter().any(|&x| x < -tol)
}

#[test]
fn above_the_threshold_no_member_but_the_tip_changes_sign_and_below_it_one_does() {
    let w0 = 1000.0;
    for truss in trusses() {
        let strings = ExtraStrings::new(&truss).unwrap();
        let r = min_extra_prestress(&truss, &strings, w0, Method::Recursive).unwrap();
        assert!(r.unreachable.is_empty(), "{:?}", r.unreachable);
        let t_star = r.min_extra_prestress.unwrap();
        let crit = r.critical_member.unwrap();
        assert!(t_star > 0.0 && crit >= 3, "{t_star} {crit}");
        let cone = NominalCone::of(&truss, Method::Recursive).unwrap();
        let data = member_data(&truss, &strings, Method::Recursive).unwrap();
        let [az, polar] = r.worst_direction.unwrap();
        let worst = Vector3::new(az.cos() * polar.sin(), az.sin() * polar.sin(), polar.cos());
        assert!(cone.contains(&worst));
        let mut dirs: Vec<Vector3<f64>> = sphere(20_000)
            .into_iter()
            .filter(|w| cone.contains(w))
            .collect();
        dirs.extend(cone.rays());
        dirs.push(worst);
        let tol = 1e-9 * w0;
        // 0.1 % above: no member but the tip members changes sign, sampled or exact
        let above = 1.001 * t_star;
        for j in 3..data.pre.len() {
            assert!(
                !changes_sign(&data, &dirs, j, above, w0, tol),
                "member {j} above t*"
            );
        }
        assert!(sign_changes(&truss, &strings, w0, above, Method::Recursive)
            .unwrap()
            .is_empty());
        // 0.1 % below: the critical member does, in the sampled directions too
        let below = 0.999 * t_star;
        assert!(
            changes_sign(&data, &dirs, crit, below, w0, tol),
            "member {crit} below t*"
        );
        let exact = sign_changes(&truss, &strings, w0, below, Method::Recursive).unwrap();
        assert!(exact.contains(&crit), "{exact:?}");
        // the critical member is exactly unloaded at t* in the worst direction
        let f = data.forces(&(w0 * worst), t_star)[crit];
        assert!(f.abs() < 1e-9 * t_star.max(w0), "{f}");
    }
}

#[test]
fn the_threshold_scales_with_the_load() {
    let truss = &trusses()[0];
    let strings = ExtraStrings::new(truss).unwrap();
    let one = min_extra_prestress(truss, &strings, 1.0, Method::Recursive).unwrap();
    let kilo = min_extra_prestress(truss, &strings, 1000.0, Method::Recursive).unwrap();
    let (a, b) = (
        one.min_extra_prestress.unwrap(),
        kilo.min_extra_prestress.unwrap(),
    );
    assert!((b / a - 1000.0).abs() < 1e-9 * 1000.0);
    // recursive and global propagation agree
    let g = min_extra_prestress(truss, &strings, 1000.0, Method::Global).unwrap();
    assert!((g.min_extra_prestress.unwrap() - b).abs() < 1e-8 * b);
}
