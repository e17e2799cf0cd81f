//! Properties of the statics that hold for any structure, checked on random ones: the
//! self-stress basis lies in the null space of A, rank + nullity = members, and the load solve
//! is the minimal-norm least-squares solution (normal equations hold, q ⟂ null space).

use nalgebra::DVector;
use proptest::prelude::*;
use tensegrity_core::{Bar, StringMember, Structure, Support};
use tensegrity_statics::Statics;

/// A complete graph on `coords.len()` nodes, members alternating bar / string.
fn complete_graph(coords: &[[f64; 3]], n_supports: usize) -> Option<Structure> {
    let n = coords.len();
    let mut b = Structure::builder().nodes(coords.iter().copied());
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..n {
            b = if k % 3 == 0 {
                b.bar(Bar::new(i, j))
            } else {
                b.string(StringMember::new(i, j))
            };
            k += 1;
        }
    }
    for i in 0..n_supports {
        b = b.support(Support::pinned(i));
    }
    b.load(n - 1, [1.0, -2.0, 0.5]).build().ok()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn statics_invariants(
        coords in prop::collection::vec(prop::array::uniform3(-1.0f64..1.0), 4..8),
        n_supports in 0usize..3,
    ) {
        let Some(s) = complete_graph(&coords, n_supports) else { return Ok(()) };
        let st = Statics::new(&s).unwrap();
        let a = st.matrix();
        let m = s.n_members();
        prop_assert_eq!(st.rank() + st.self_stress_dim(), m);
        prop_assert_eq!(st.rank() + st.mechanisms(), a.nrows());
        let scale = a.amax();
        let v = st.self_stress_basis();
        prop_assert!((a * &v).amax() <= 1e-10 * scale);
        // orthonormal basis
        let gram = v.transpose() * &v;
        prop_assert!((gram - nalgebra::DMatrix::identity(v.ncols(), v.ncols())).amax() < 1e-10);

        let sol = st.solve_loads();
        let w = st.dofs().gather(&s.W());
        let r = a * &sol.force_density - &w;
        // least squares: Aᵀ r = 0; minimal norm: q has no self-stress component
        prop_assert!((a.transpose() * &r).amax() <= 1e-9 * scale * w.amax().max(1.0));
        let along_null: DVector<f64> = v.transpose() * &sol.force_density;
        prop_assert!(along_null.amax() <= 1e-9 * sol.force_density.amax().max(1.0));
        // the margin is a valid bound: the returned stress satisfies it
        let p = st.prestressability().unwrap();
        prop_assert!(p.margin >= 0.0 && p.margin <= 1.0);
        // the dense interior point and Clarabel agree on the margin
        let clarabel = Statics::with_settings(
            &s,
            tensegrity_statics::StaticsSettings::default().lp_solver(tensegrity_statics::LpSolver::Clarabel),
        )
        .unwrap()
        .prestressability()
        .unwrap();
        prop_assert!((clarabel.margin - p.margin).abs() < 1e-7, "{} vs {}", clarabel.margin, p.margin);
        if p.prestressable {
            prop_assert!((a * &p.stress).amax() <= 1e-9 * scale);
            for k in 0..m {
                let signed = if k < s.n_bars() { -p.stress[k] } else { p.stress[k] };
                prop_assert!(signed >= p.margin - 1e-12);
            }
        }
    }
}
