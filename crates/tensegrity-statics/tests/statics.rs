//! Statics against closed forms and published values: D-bar connectivity (thesis eq. 2.8–2.10),
//! Snelson prisms (ERRATA P.1), load solves, prestressability margins.

use crate::common;

use approx::assert_relative_eq;
use common::*;
use nalgebra::{DMatrix, DVector, Matrix3xX};
use std::f64::consts::PI;
use tensegrity_core::{Bar, Connectivity, StringMember, Structure, Support};
use tensegrity_statics::Statics;
use tensegrity_statics::{equilibrium_matrix_full, DofMap};

#[test]
fn dbar_connectivity_matches_thesis_eq_2_8_to_2_10() {
    let (l, h) = (3.0, 0.8);
    let s = dbar(l, h).build().unwrap();
    let c = Connectivity::of(&s);
    let cb = DMatrix::from_row_slice(
        4,
        4,
        &[
            -1., 1., 0., 0., -1., 0., 1., 0., 0., -1., 0., 1., 0., 0., -1., 1.,
        ],
    );
    let cs = DMatrix::from_row_slice(2, 4, &[-1., 0., 0., 1., 0., -1., 1., 0.]);
    assert_eq!(c.C_b(), cb);
    assert_eq!(c.C_s(), cs);
    // eq. 2.10
    let b_expected = Matrix3xX::from_column_slice(&[
        l / 2.0,
        h / 2.0,
        0.0,
        l / 2.0,
        -h / 2.0,
        0.0,
        l / 2.0,
        -h / 2.0,
        0.0,
        l / 2.0,
        h / 2.0,
        0.0,
    ]);
    let s_expected = Matrix3xX::from_column_slice(&[l, 0.0, 0.0, 0.0, -h, 0.0]);
    let n = s.N();
    assert_relative_eq!(c.B(&n), b_expected, epsilon = 1e-15);
    assert_relative_eq!(c.S(&n), s_expected, epsilon = 1e-15);
    // sparse products agree with the dense ones
    assert_relative_eq!(c.B(&n), &n * c.C_b().transpose(), epsilon = 1e-15);
    // ERRATA 2.2: R = N C_rᵀ is the bar centres; bar 2 (n1 → n3) has centre (3L/4, h/4)
    let r = c.R(&n);
    assert_relative_eq!(r[(0, 2)], 0.75 * l, epsilon = 1e-15);
    assert_relative_eq!(r[(1, 2)], 0.25 * h, epsilon = 1e-15);
    assert_relative_eq!(c.R(&n), &n * c.C_r().transpose(), epsilon = 1e-15);
    // the D-bar's two inner nodes are class-2 joints, the ends too
    assert_eq!(s.class_k_nodes(), vec![(0, 2), (1, 2), (2, 2), (3, 2)]);
}

#[test]
fn dbar_has_a_single_self_stress_bars_compressed_strings_tensioned() {
    for (l, h) in [(2.0, 1.0), (3.0, 0.8), (1.0, 2.5)] {
        let s = dbar(l, h).build().unwrap();
        let st = Statics::new(&s).unwrap();
        assert_eq!(st.rank(), 5);
        assert_eq!(st.self_stress_dim(), 1);
        // 12 dofs − rank 5 = 7: six rigid-body motions and one out-of-plane flex
        assert_eq!(st.mechanisms(), 7);
        assert_eq!(st.flexes().unwrap().internal.ncols(), 1);
        // equilibrium of node 0 and node 1 gives q = (−1, −1, −1, −1, 1, 1)/√6 for any L, h
        let q = st.self_stress_basis();
        let expected = DVector::from_row_slice(&[-1., -1., -1., -1., 1., 1.]) / 6f64.sqrt();
        assert_relative_eq!(q.column(0).into_owned(), expected, epsilon = 1e-12);
        let p = st.prestressability().unwrap();
        assert!(p.prestressable);
        assert_relative_eq!(p.margin, 1.0, epsilon = 1e-9);
    }
}

/// ERRATA P.1: q_v = −q_bar, q_bottom = q_v r_t / (2 r_b sin(π/p)), q_top = q_v r_b / (2 r_t sin(π/p)).
#[test]
fn snelson_prisms_are_prestressable_exactly_at_the_published_twist() {
    for p in 3..=6 {
        for (rb, rt, h) in [(1.0, 1.0, 1.0), (1.0, 0.6, 2.0)] {
            let twist = PI / 2.0 - PI / p as f64;
            let s = snelson(p, twist, rb, rt, h).build().unwrap();
            let st = Statics::new(&s).unwrap();
            assert_eq!(st.self_stress_dim(), 1, "p = {p}");
            assert_eq!(st.rank(), 4 * p - 1);
            let q = st.self_stress_basis().column(0).into_owned();
            let qv = q[3 * p];
            let sin = (PI / p as f64).sin();
            for i in 0..p {
                assert_relative_eq!(q[i], -qv, max_relative = 1e-10);
                assert_relative_eq!(q[p + i], qv * rt / (2.0 * rb * sin), max_relative = 1e-10);
                assert_relative_eq!(
                    q[2 * p + i],
                    qv * rb / (2.0 * rt * sin),
                    max_relative = 1e-10
                );
                assert_relative_eq!(q[3 * p + i], qv, max_relative = 1e-10);
            }
            let pre = st.prestressability().unwrap();
            assert!(pre.prestressable, "p = {p}");
            // with one state the margin is its smallest signed entry over its largest entry
            let signed_min = (0..4 * p)
                .map(|k| if k < p { -q[k] } else { q[k] })
                .fold(f64::INFINITY, f64::min);
            assert_relative_eq!(pre.margin, signed_min / q.amax(), epsilon = 1e-9);
            // 6p dofs − (4p − 1) rank − 6 rigid-body motions = 2p − 5 internal mechanisms,
            // all stiffened by the prestress
            let stab = st.prestress_stability(&pre.stress).unwrap();
            assert_eq!(stab.internal_mechanisms, 2 * p - 5);
            assert!(stab.stable);
            assert!(stab.eigenvalues[0] > 1e-3);

            for off in [-1.0f64, 1.0] {
                let s = snelson(p, twist + off.to_radians(), rb, rt, h)
                    .build()
                    .unwrap();
                let st = Statics::new(&s).unwrap();
                let sv = st.singular_values();
                assert!(
                    sv[sv.len() - 1] > 1e-4 * sv[0],
                    "p = {p}: σ_min/σ_max = {}",
                    sv[sv.len() - 1] / sv[0]
                );
                assert_eq!(st.self_stress_dim(), 0);
                assert!(!st.prestressability().unwrap().prestressable);
            }
        }
    }
}

#[test]
fn equal_radius_triangular_prism_has_the_published_ratios() {
    // ERRATA P.1, n = 3: q_bottom = q_top = 1, q_vertical = √3, q_bar = −√3
    let s = snelson(3, PI / 6.0, 1.0, 1.0, 1.0).build().unwrap();
    let st = Statics::new(&s).unwrap();
    let q = st.self_stress_basis().column(0).into_owned();
    let q = &q / q[3];
    let r3 = 3f64.sqrt();
    let expected = [-r3, -r3, -r3, 1., 1., 1., 1., 1., 1., r3, r3, r3];
    assert_relative_eq!(q, DVector::from_row_slice(&expected), epsilon = 1e-12);
    assert_relative_eq!(
        st.prestressability().unwrap().margin,
        1.0 / r3,
        epsilon = 1e-9
    );
}

#[test]
fn prestress_lp_agrees_with_a_brute_force_scan_on_a_two_dimensional_stress_space() {
    // two stacked prisms sharing the middle triangle: dim 2 self-stress space
    let mut b = Structure::builder();
    let tw = PI / 6.0;
    for (z, a0) in [(0.0, 0.0), (1.0, tw), (2.0, 2.0 * tw)] {
        for i in 0..3 {
            let a = 2.0 * PI * i as f64 / 3.0 + a0;
            b = b.node([a.cos(), a.sin(), z]);
        }
    }
    for stage in 0..2 {
        for i in 0..3 {
            b = b.bar(Bar::new(3 * stage + i, 3 * stage + 3 + (i + 1) % 3));
        }
    }
    for ring in 0..3 {
        for i in 0..3 {
            b = b.string(StringMember::new(3 * ring + i, 3 * ring + (i + 1) % 3));
        }
    }
    for stage in 0..2 {
        for i in 0..3 {
            b = b.string(StringMember::new(3 * stage + i, 3 * stage + 3 + i));
        }
    }
    let s = b.build().unwrap();
    let st = Statics::new(&s).unwrap();
    assert_eq!(st.self_stress_dim(), 2);
    let v = st.self_stress_basis();
    let nb = s.n_bars();
    let margin_of = |theta: f64| {
        let q = &v * DVector::from_row_slice(&[theta.cos(), theta.sin()]);
        (0..q.len())
            .map(|k| if k < nb { -q[k] } else { q[k] })
            .fold(f64::INFINITY, f64::min)
            / q.amax()
    };
    // coarse scan, then golden-section refinement around the best angle
    let n = 3600;
    let best = (0..n)
        .map(|i| 2.0 * PI * i as f64 / n as f64)
        .max_by(|a, b| margin_of(*a).total_cmp(&margin_of(*b)))
        .unwrap();
    let (mut lo, mut hi) = (best - 2.0 * PI / n as f64, best + 2.0 * PI / n as f64);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if margin_of(a) < margin_of(b) {
            lo = a;
        } else {
            hi = b;
        }
    }
    let brute = margin_of(0.5 * (lo + hi));
    let lp = st.prestressability().unwrap();
    assert!(lp.prestressable);
    assert_relative_eq!(lp.margin, brute, epsilon = 1e-7);
}

#[test]
fn no_self_stress_means_zero_margin() {
    let s = loaded_dbar(2.0, 1e4);
    let st = Statics::new(&s).unwrap();
    assert_eq!(st.self_stress_dim(), 0);
    let p = st.prestressability().unwrap();
    assert_eq!((p.margin, p.prestressable), (0.0, false));
}

#[test]
fn loaded_dbar_forces_and_reactions_match_hand_calculation() {
    let load = 1e4;
    let s = loaded_dbar(2.0, load);
    let st = Statics::new(&s).unwrap();
    let sol = st.solve_loads();
    // each 45° bar carries load/(2 cos 45°) in compression, the string pulls with the load
    let bar_force = -load / 2f64.sqrt();
    for k in 0..4 {
        assert_relative_eq!(sol.member_force[k], bar_force, max_relative = 1e-12);
        assert_relative_eq!(
            sol.force_density[k],
            bar_force / 2f64.sqrt(),
            max_relative = 1e-12
        );
    }
    assert_relative_eq!(sol.member_force[4], load, max_relative = 1e-12);
    assert!(sol.residual < 1e-9 * load);
    assert_eq!(sol.reactions.len(), 1);
    let (node, r) = sol.reactions[0];
    assert_eq!(node, 0);
    assert_relative_eq!(r.x, load, max_relative = 1e-12);
    assert!(r.y.abs() < 1e-9 && r.z.abs() < 1e-9);
}

#[test]
fn min_norm_load_solve_agrees_with_an_independent_pseudo_inverse() {
    // a loaded prism on three pinned bottom nodes: rows removed, self-stresses present
    let s = snelson(4, PI / 4.0, 1.0, 0.7, 1.3)
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .support(Support::directions(2, [false, false, true]))
        .load(5, [10.0, -20.0, -100.0])
        .load(6, [0.0, 5.0, -80.0])
        .build()
        .unwrap();
    let st = Statics::new(&s).unwrap();
    let sol = st.solve_loads();
    // independent: nalgebra's own SVD pseudo-inverse on the matrix built from the full one
    let dofs = DofMap::of(&s);
    let a_full = equilibrium_matrix_full(&s);
    let rows: Vec<usize> = dofs.free.iter().map(|&(i, d)| 3 * i + d).collect();
    let a = a_full.select_rows(rows.iter());
    let w = dofs.gather(&s.W());
    let pinv = a.clone().pseudo_inverse(1e-10).unwrap();
    let q_ref = pinv * &w;
    assert_relative_eq!(
        sol.force_density,
        q_ref,
        max_relative = 1e-9,
        epsilon = 1e-9
    );
    // reactions balance the applied loads: Σ reactions + Σ loads = 0 (translation equilibrium)
    let total_load: nalgebra::Vector3<f64> = s.loads().iter().map(|l| l.force).sum();
    let total_reaction: nalgebra::Vector3<f64> = sol.reactions.iter().map(|(_, r)| *r).sum();
    let residual_force: nalgebra::Vector3<f64> = {
        // free-dof imbalance, if any, also counts
        let imbalance = &a * &sol.force_density - &w;
        let mut v = nalgebra::Vector3::zeros();
        for (r, &(_, d)) in dofs.free.iter().enumerate() {
            v[d] += imbalance[r];
        }
        v
    };
    assert_relative_eq!(
        total_reaction + total_load + residual_force,
        nalgebra::Vector3::zeros(),
        epsilon = 1e-9
    );
}

#[test]
fn gravity_loads_half_the_bar_weight_on_each_end() {
    // a vertical bar on a pinned base, held by nothing else: reaction = weight
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [0.0, 0.0, 2.0]])
        .bar(Bar::new(0, 1).mass(3.0))
        .support(Support::pinned(0))
        .gravity([0.0, 0.0, -9.81])
        .build()
        .unwrap();
    let sol = Statics::new(&s).unwrap().solve_loads();
    // the top node carries half the weight down the bar: compression 1.5 g
    assert_relative_eq!(sol.member_force[0], -1.5 * 9.81, max_relative = 1e-12);
    assert_relative_eq!(sol.reactions[0].1.z, 3.0 * 9.81, max_relative = 1e-12);
}

#[test]
fn rank_tolerance_setting_is_used() {
    // 0.01° off the twist: σ_min is small but nonzero; a loose tolerance calls it a self-stress
    let s = snelson(3, PI / 6.0 + 0.01f64.to_radians(), 1.0, 1.0, 1.0)
        .build()
        .unwrap();
    let strict = Statics::new(&s).unwrap();
    assert_eq!(strict.self_stress_dim(), 0);
    let settings = tensegrity_statics::StaticsSettings::default()
        .rank_tolerance(1e-3)
        .unwrap();
    let loose = Statics::with_settings(&s, settings).unwrap();
    assert_eq!(loose.self_stress_dim(), 1);
}
