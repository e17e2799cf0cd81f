//! The recursive method of joints equals the global sparse solve (ERRATA 4.23) for q ≤ 10, in
//! both parameterisations, the planar truss, random parameters and random load directions; and
//! both satisfy global equilibrium (reactions balance the loads, moments included).
use crate::common;

use common::{rel_diff, Rng};
use michell3d::*;
use nalgebra::Vector3;
use std::f64::consts::PI;

fn random_params(rng: &mut Rng, q: usize, kind: usize) -> MichellParams {
    let beta = rng.uniform(0.3, 1.2);
    let phi = rng.uniform(0.05, 0.35);
    let r0 = rng.uniform(0.5, 2.0);
    match kind {
        0 => MichellParams::planar(q, r0, beta, phi),
        1 => MichellParams::cylindrical(q, r0, beta, phi, rng.uniform(0.05, 0.6)),
        _ => {
            // 0 < |qε| < π/2, and cos(Zφ) ≠ 0 for |Z| ≤ q.
            let eps = rng.uniform(0.1, 1.4) / q as f64;
            MichellParams::spherical(q, r0, beta, phi, eps)
        }
    }
}

fn random_direction(rng: &mut Rng, planar: bool) -> Vector3<f64> {
    let w0 = rng.uniform(1.0, 1e4);
    if planar {
        in_plane_load(w0, rng.uniform(0.0, 2.0 * PI))
    } else {
        tip_load(w0, rng.uniform(0.0, 2.0 * PI), rng.uniform(0.0, PI)).unwrap()
    }
}

fn check_equilibrium(t: &MichellTruss, loads: &NodalLoads, s: &ForceSolution) {
    // Σ forces and Σ moments about the origin of loads + reactions vanish.
    let nodes = t.nodes();
    let mut f = Vector3::zeros();
    let mut m = Vector3::zeros();
    let mut scale = 0.0;
    for &(n, w) in loads.entries() {
        f += w;
        m += nodes[n].position.cross(&w);
        scale += w.norm();
    }
    for (k, r) in s.reactions.iter().enumerate() {
        let n = t.n_free() + k;
        f += r;
        m += nodes[n].position.cross(r);
    }
    assert!(f.norm() < 1e-9 * scale, "force balance {f}");
    assert!(
        m.norm() < 1e-9 * scale * t.params().r0,
        "moment balance {m}"
    );
}

#[test]
fn recursion_equals_global_solve() {
    let mut rng = Rng::new(7);
    let mut worst: f64 = 0.0;
    for q in 1..=10 {
        for kind in 0..3 {
            for _ in 0..3 {
                let p = random_params(&mut rng, q, kind);
                let t = MichellTruss::new(p).unwrap();
                let planar = t.is_planar();
                // A random tip load and random loads on two other free nodes.
                let mut loads = NodalLoads::tip(random_direction(&mut rng, planar));
                for _ in 0..2 {
                    let n = (rng.next_u64() % t.n_free() as u64) as usize;
                    loads = loads.add(n, random_direction(&mut rng, planar));
                }
                let rec = propagate(&t, &loads, Method::Recursive).unwrap();
                let glo = propagate(&t, &loads, Method::Global).unwrap();
                let d = rel_diff(&rec.force_density, &glo.force_density);
                worst = worst.max(d);
                assert!(d < 1e-10, "q = {q}, {p:?}: relative difference {d:e}");
                let r: Vec<f64> = rec
                    .reactions
                    .iter()
                    .flat_map(|v| v.iter().copied())
                    .collect();
                let g: Vec<f64> = glo
                    .reactions
                    .iter()
                    .flat_map(|v| v.iter().copied())
                    .collect();
                assert!(rel_diff(&r, &g) < 1e-10);
                check_equilibrium(&t, &loads, &rec);
            }
        }
    }
    assert!(
        worst > 0.0,
        "two independent solvers should differ by round-off"
    );
}

/// The Fig. 4.18 parameters (φ = π/q) up to q = 10.
#[test]
fn recursion_equals_global_for_fig_4_18_parameters() {
    let w = tip_load(1000.0, 0.3, 2.0).unwrap();
    for q in 2..=10 {
        for p in [
            michell3d::complexity::fig_4_18_params(q, Some(0.25)),
            MichellParams::spherical(q, 1.0, PI / 6.0, PI / (q as f64 + 0.5), 0.1),
        ] {
            let t = MichellTruss::new(p).unwrap();
            let rec = propagate(&t, &NodalLoads::tip(w), Method::Recursive).unwrap();
            let glo = propagate(&t, &NodalLoads::tip(w), Method::Global).unwrap();
            assert!(
                rel_diff(&rec.force_density, &glo.force_density) < 1e-10,
                "q = {q}"
            );
        }
    }
}

/// Exhaustive: q = 2..=35 for the cylindrical truss.
#[test]
fn recursion_equals_global_up_to_q35() {
    let w = tip_load(1000.0, 1.0, 2.0).unwrap();
    for q in 2..=35 {
        let t = MichellTruss::new(michell3d::complexity::fig_4_18_params(q, Some(0.1))).unwrap();
        let rec = propagate(&t, &NodalLoads::tip(w), Method::Recursive).unwrap();
        let glo = propagate(&t, &NodalLoads::tip(w), Method::Global).unwrap();
        assert!(
            rel_diff(&rec.force_density, &glo.force_density) < 1e-8,
            "q = {q}"
        );
    }
}
