//! Extra strings (§4.6, ERRATA 4.30): counts, one self-stress per string (checked against
//! tensegrity-core's SVD), equilibrium of the prestress, and the γ sweep of Fig. 4.20.

use michell3d::*;
use std::f64::consts::{FRAC_PI_6, PI};
use tensegrity_statics::Statics;

#[test]
fn each_extra_string_adds_one_self_stress() {
    for (q, expected) in [(2, 3), (3, 12), (4, 30)] {
        let t = MichellTruss::new(MichellParams::cylindrical(
            q,
            1.0,
            FRAC_PI_6,
            PI / 8.0,
            0.25,
        ))
        .unwrap();
        let s = ExtraStrings::new(&t).unwrap();
        assert_eq!(s.len(), expected, "q = {q}");
        let structure = s.to_structure(&t).unwrap();
        let statics = Statics::new(&structure).unwrap();
        assert_eq!(statics.self_stress_dim(), expected, "q = {q}");
        // Our self-stress states lie in the core's equilibrium null space.
        let a = statics.matrix();
        let nb = t.members().len();
        for j in 0..s.len() {
            let base = s.self_stress(&t, j, Method::Recursive).unwrap();
            let mut x = nalgebra::DVector::zeros(nb + s.len());
            for (i, v) in base.iter().enumerate() {
                x[i] = *v;
            }
            x[nb + j] = 1.0;
            let r = (a * &x).norm();
            assert!(r < 1e-9 * x.norm(), "string {j}: residual {r}");
        }
    }
}

#[test]
fn prestress_is_a_self_stress_and_superposes() {
    let t = MichellTruss::new(MichellParams::spherical(3, 1.0, 0.6, 0.3, 0.1)).unwrap();
    let s = ExtraStrings::new(&t).unwrap();
    let w = tip_load(100.0, 0.4, 2.2).unwrap();
    let loads = NodalLoads::tip(w);
    let plain = propagate_recursive(&t, &loads).unwrap();
    let pre = solve_prestressed(&t, &s, &NodalLoads::new(), 50.0, Method::Recursive).unwrap();
    let both = solve_prestressed(&t, &s, &loads, 50.0, Method::Global).unwrap();
    // Tension 50 N in every extra string.
    for (q, l) in both.extra_force_density.iter().zip(s.lengths()) {
        assert!((q * l - 50.0).abs() < 1e-12);
    }
    // Tip members carry no prestress; total = load + prestress.
    for j in 0..3 {
        assert!(pre.base.force_density[j].abs() < 1e-9);
    }
    for j in 0..t.members().len() {
        let sum = plain.force_density[j] + pre.base.force_density[j];
        assert!((both.base.force_density[j] - sum).abs() < 1e-9 * sum.abs().max(1.0));
    }
    // Some level ≥ 2 member carries prestress.
    assert!(pre.base.force_density[3..].iter().any(|q| q.abs() > 1.0));
}

/// Fig. 4.20 (q = 2): without prestress members beyond the tip change sign as γ sweeps
/// [0, 2π]; with a high prestress every member except the three tip members keeps its sign
/// and the extra strings stay in tension.
#[test]
fn high_prestress_fixes_member_signs() {
    let t = MichellTruss::new(MichellParams::cylindrical(
        2,
        1.0,
        FRAC_PI_6,
        PI / 8.0,
        0.25,
    ))
    .unwrap();
    let s = ExtraStrings::new(&t).unwrap();
    let grid = AngleGrid::new(0.0, 2.0 * PI, 361);
    let low = gamma_sweep(&t, &s, 1000.0, 0.0, grid, 0.0, Method::Recursive).unwrap();
    let high = gamma_sweep(&t, &s, 1000.0, 0.0, grid, 1e6, Method::Recursive).unwrap();
    assert_eq!(high.base_sign_changers(), vec![0, 1, 2]);
    assert!(high.extra_keeps_sign.iter().all(|&k| k));
    let low_changers = low.base_sign_changers();
    assert!(low_changers.len() > 3, "{low_changers:?}");
    assert!(low_changers.iter().any(|&j| j >= 3));
    assert_eq!(high.rows().count(), 361 * (t.members().len() + s.len()));
    // The tip members always change sign (the tip node has no other members).
    for j in 0..3 {
        assert!(!low.base_keeps_sign[j] && !high.base_keeps_sign[j]);
    }
}
