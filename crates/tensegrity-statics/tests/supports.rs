//! Supports along any unit direction and elastic supports in the statics.
//!
//! - A structure held along skew directions against the same structure rotated so that those
//!   directions are coordinate axes (held by x, y, z flags, the path every other test
//!   covers): two independent runs whose counts, self-stresses, load-solve forces, reactions
//!   (rotated), prestress tests and natural frequencies agree to 10⁻¹², on the dense SVD, the
//!   sparse QR and the nested dissection.
//! - A node on an inclined roller: the reaction normal to the incline, P / cos θ, and the bar
//!   force, −P tan θ, the closed forms.
//! - An elastic support: the equilibrium analyses count it as a support; the modes carry its
//!   springs, ω² = 2k/m and 2(k + EA/L)/m on a bar's free end.

use nalgebra::{DVector, Matrix3, Vector3};
use std::f64::consts::PI;
use tensegrity_core::test_models::{snelson, snelson_twist};
use tensegrity_core::{Bar, Material, Structure, StructureBuilder, Support};
use tensegrity_statics::report::{statics_report, StaticsReport, StaticsRequest};
use tensegrity_statics::stiffness;
use tensegrity_statics::{
    reaction_components, DofMap, NestedStatics, SparseStatics, Statics, StaticsBackend,
    StaticsMethod, StaticsSettings,
};

/// d_a = (1, 2, 2)/3, d_b = (2, 1, −2)/3, d_c = d_a × d_b... rows (d_b, d_c, d_a): the
/// rotation R with R d_b = x, R d_c = y, R d_a = z.
fn frame() -> (Vector3<f64>, Vector3<f64>, Matrix3<f64>) {
    let d_a = Vector3::new(1.0, 2.0, 2.0) / 3.0;
    let d_b = Vector3::new(2.0, 1.0, -2.0) / 3.0;
    let d_c = d_a.cross(&d_b);
    let r = Matrix3::from_rows(&[d_b.transpose(), d_c.transpose(), d_a.transpose()]);
    assert!((r * r.transpose() - Matrix3::identity()).amax() < 1e-15 && r.determinant() > 0.0);
    (d_a, d_b, r)
}

/// A square pyramid of bars (base edges, both base diagonals, four legs: one self-stress in
/// the base), node 0 pinned, node 1 held along d_a and (d_a + d_b)/√2 (the d_a–d_b plane,
/// two directions that are not orthogonal), node 2 along d_a; loads on the apex and node 3.
/// `rotated`: the same structure turned by R, node 1 held along x and z, node 2 along z.
fn pyramid(rotated: bool) -> Structure {
    let (d_a, d_b, r) = frame();
    let turn = |p: [f64; 3]| -> [f64; 3] {
        let v = Vector3::from(p);
        let v = if rotated { r * v } else { v };
        [v.x, v.y, v.z]
    };
    let alu = Material::new(2700.0, 70e9, 200e6);
    let bar = |i, j| Bar::new(i, j).material("alu").radius(0.01).mass(1.0);
    let mut b = Structure::builder()
        .material("alu", alu)
        .nodes(
            [
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
                [1.0, 1.0, 1.5],
            ]
            .map(turn),
        )
        .bars([(0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3)].map(|(i, j)| bar(i, j)))
        .bars([(0, 4), (1, 4), (2, 4), (3, 4)].map(|(i, j)| bar(i, j)))
        .support(Support::pinned(0))
        .load(4, turn([300.0, -200.0, -1000.0]))
        .load(3, turn([100.0, 50.0, 0.0]));
    b = if rotated {
        b.support(Support::directions(1, [true, false, true]))
            .support(Support::directions(2, [false, false, true]))
    } else {
        let mixed = (d_a + d_b) / 2f64.sqrt();
        b.support(Support::along(1, [d_a.into(), mixed.into()]))
            .support(Support::along(2, [d_a.into()]))
    };
    b.build().unwrap()
}

fn report(s: &Structure, method: StaticsMethod) -> StaticsReport {
    let request = StaticsRequest {
        settings: StaticsSettings::default().method(method),
        modes: Some(15),
        ..StaticsRequest::default()
    };
    statics_report(s, &request).unwrap()
}

/// The largest difference of two lists relative to the largest magnitude of the second.
fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn a_skew_support_gives_what_the_rotated_structure_gives_on_the_axes() {
    let (d_a, d_b, r) = frame();
    let (skew, axes) = (pyramid(false), pyramid(true));
    // the skew node's frame: no x, y, z rows for nodes 1 and 2
    let dofs = DofMap::of(&skew);
    assert!(!dofs.is_axis_aligned() && DofMap::of(&axes).is_axis_aligned());
    assert_eq!((dofs.len(), DofMap::of(&axes).len()), (9, 9));
    for method in [StaticsMethod::Dense, StaticsMethod::Sparse] {
        let (a, b) = (report(&skew, method), report(&axes, method));
        assert_eq!(
            (
                a.rank,
                a.self_stress_dim,
                a.mechanisms,
                a.internal_mechanisms
            ),
            (9, 1, 0, 0)
        );
        assert_eq!(
            (
                a.rank,
                a.self_stress_dim,
                a.mechanisms,
                a.internal_mechanisms
            ),
            (
                b.rank,
                b.self_stress_dim,
                b.mechanisms,
                b.internal_mechanisms
            )
        );
        assert_eq!(a.load_carried, Some(true));
        assert!(
            rel(&a.self_stress[0], &b.self_stress[0]) < 1e-12,
            "{method:?}"
        );
        let (fa, fb) = (a.member_force.unwrap(), b.member_force.unwrap());
        let e = rel(&fa, &fb);
        assert!(e < 1e-12, "{method:?}: member forces differ by {e:e}");
        // the reactions, turned: R r_skew = r_axes, each in the span of its held directions
        let (ra, rb) = (a.reactions.unwrap(), b.reactions.unwrap());
        let turned: Vec<f64> = ra
            .iter()
            .flat_map(|x| {
                (r * Vector3::from(x.force))
                    .iter()
                    .copied()
                    .collect::<Vec<_>>()
            })
            .collect();
        let axes_r: Vec<f64> = rb.iter().flat_map(|x| x.force).collect();
        let e = rel(&turned, &axes_r);
        assert!(e < 1e-12, "{method:?}: reactions differ by {e:e}");
        // along the given directions: r = a₁ d_a + a₂ (d_a + d_b)/√2 = r_z d_a + r_x d_b
        let [rx, _, rz] = rb[1].force;
        let along = &ra[1].along;
        assert!((along[0] - (rz - rx)).abs() < 1e-12 * 1e3, "{along:?}");
        assert!(
            (along[1] - 2f64.sqrt() * rx).abs() < 1e-12 * 1e3,
            "{along:?}"
        );
        assert!((ra[2].along[0] - rb[2].force[2]).abs() < 1e-12 * 1e3);
        assert!(rb[1].along.is_empty());
        // the natural frequencies (the tangent on the nodes' frames) are the turned ones
        let (wa, wb) = (
            a.natural_frequencies_hz.unwrap(),
            b.natural_frequencies_hz.unwrap(),
        );
        assert_eq!(wa.len(), 9);
        let e = rel(&wa, &wb);
        assert!(e < 1e-10, "{method:?}: frequencies differ by {e:e}");
    }
    // the held reaction of node 2 lies along d_a; of node 1 in the d_a–d_b plane
    let sol = Statics::new(&skew).unwrap().solve_loads();
    let normal = d_a.cross(&d_b);
    assert!(sol.reactions[1].1.dot(&normal).abs() < 1e-12 * 1e3);
    assert!(sol.reactions[2].1.cross(&d_a).norm() < 1e-12 * 1e3);
}

/// A Snelson prism standing on node 0 (pinned), node 1 (held along d_a and d_b) and node 2
/// (held along d_a), or turned by R and held along the axes.
fn prism(rotated: bool) -> Structure {
    let (d_a, d_b, r) = frame();
    let bare = snelson(3, snelson_twist(3), 1.0, 1.0, 1.2).build().unwrap();
    let nodes: Vec<Vector3<f64>> = if rotated {
        bare.nodes().iter().map(|p| r * p).collect()
    } else {
        bare.nodes().to_vec()
    };
    let mut b: StructureBuilder = bare.with_nodes(nodes).unwrap().to_builder();
    b = b.support(Support::pinned(0));
    b = if rotated {
        b.support(Support::directions(1, [true, false, true]))
            .support(Support::directions(2, [false, false, true]))
    } else {
        b.support(Support::along(1, [d_a.into(), d_b.into()]))
            .support(Support::along(2, [d_a.into()]))
    };
    b.build().unwrap()
}

#[test]
fn the_prestress_tests_see_the_skew_supports_as_the_turned_axes() {
    let (skew, axes) = (prism(false), prism(true));
    let (sa, sb) = (Statics::new(&skew).unwrap(), Statics::new(&axes).unwrap());
    // one self-stress, one internal mechanism (the supports take the six rigid motions)
    assert_eq!((sa.self_stress_dim(), sa.mechanisms()), (1, 1));
    assert_eq!((sb.self_stress_dim(), sb.mechanisms()), (1, 1));
    assert_eq!(sa.flexes().unwrap().rigid_body, 0);
    let q = sb.self_stress_basis().column(0).into_owned();
    assert!((sa.self_stress_basis().column(0) - &q).amax() < 1e-12);
    let (pa, pb) = (
        sa.prestress_stability(&q).unwrap(),
        sb.prestress_stability(&q).unwrap(),
    );
    assert!(pa.stable && pb.stable);
    assert!(
        rel(&pa.eigenvalues, &pb.eigenvalues) < 1e-12,
        "{pa:?} {pb:?}"
    );
    // the sparse QR: its dense test (Ω on the frames) and its sparse Cholesky test
    let settings = StaticsSettings::default();
    let (xa, xb) = (
        SparseStatics::with_settings(&skew, settings).unwrap(),
        SparseStatics::with_settings(&axes, settings).unwrap(),
    );
    let (pa, pb) = (
        xa.prestress_stability(&q).unwrap(),
        xb.prestress_stability(&q).unwrap(),
    );
    assert!(
        rel(&pa.eigenvalues, &pb.eigenvalues) < 1e-10,
        "{pa:?} {pb:?}"
    );
    assert_eq!(
        (
            xa.stable_by_cholesky(&q).unwrap(),
            xb.stable_by_cholesky(&q).unwrap()
        ),
        (Some(true), Some(true))
    );
    // the flex test alone agrees (the penalised stress matrix certified these first)
    assert_eq!(
        (
            xa.stable_by_flexes(&q).unwrap(),
            xb.stable_by_flexes(&q).unwrap()
        ),
        (Some(true), Some(true))
    );
    // a stress that softens the mechanism is unstable on both
    assert_eq!(
        (
            xa.stable_by_cholesky(&-&q).unwrap(),
            xb.stable_by_cholesky(&-&q).unwrap()
        ),
        (Some(false), Some(false))
    );
    // the nested dissection of A: its penalised stress matrix on the frames
    let (na, nb) = (
        NestedStatics::members_with_settings(&skew, settings).unwrap(),
        NestedStatics::members_with_settings(&axes, settings).unwrap(),
    );
    assert_eq!((na.self_stress_dim(), na.mechanisms()), (1, 1));
    assert!(na.prestress_stability(&q).unwrap().stable);
    assert!(nb.prestress_stability(&q).unwrap().stable);
}

/// A horizontal bar from a pinned node to node 1 on a roller on an incline at θ (held along
/// its normal n = (−sin θ, 0, cos θ) and along y), a load P down at node 1.
fn inclined_roller(theta: f64, p: f64) -> Structure {
    let (s, c) = theta.sin_cos();
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1))
        .support(Support::pinned(0))
        .support(Support::along(1, [[-s, 0.0, c], [0.0, 1.0, 0.0]]))
        .load(1, [0.0, 0.0, -p])
        .build()
        .unwrap()
}

#[test]
fn an_inclined_roller_reacts_normal_to_the_incline_with_the_closed_form() {
    // node 1: bar force −T x̂ (tension T), reaction R n, load −P ẑ: along z, R cos θ = P;
    // along x, T = −R sin θ, so R = P / cos θ and T = −P tan θ
    let (theta, p) = (PI / 6.0, 1000.0);
    let r = statics_report(&inclined_roller(theta, p), &StaticsRequest::default()).unwrap();
    assert_eq!((r.rank, r.self_stress_dim, r.mechanisms), (1, 0, 0));
    let force = r.member_force.unwrap()[0];
    assert!((force + p * theta.tan()).abs() < 1e-12 * p, "{force}");
    let reaction = &r.reactions.unwrap()[1];
    let normal = p / theta.cos();
    // along the normal and along y (no force out of the plane)
    assert!(
        (reaction.along[0] - normal).abs() < 1e-12 * p,
        "{reaction:?}"
    );
    assert!(reaction.along[1].abs() < 1e-12 * p, "{reaction:?}");
    let expected = [-p * theta.tan(), 0.0, p];
    assert!(rel(&reaction.force, &expected) < 1e-12, "{reaction:?}");
    // one free axis, along the incline (cos θ, 0, sin θ)
    let dofs = DofMap::of(&inclined_roller(theta, p));
    assert_eq!(dofs.len(), 1);
    let t = dofs.direction(0);
    assert!(t.cross(&Vector3::new(theta.cos(), 0.0, theta.sin())).norm() < 1e-15);
    // the components of any reaction along the given directions rebuild it
    let s = Support::along(1, [[0.6, 0.0, 0.8], [0.0, 1.0, 0.0]]);
    let a = reaction_components(&s, &Vector3::new(3.0, -2.0, 4.0));
    assert!(
        (a[0] - 5.0).abs() < 1e-15 && (a[1] + 2.0).abs() < 1e-15,
        "{a:?}"
    );
}

/// A bar of mass m along x from a pinned node to node 1, held by springs of stiffness k in
/// x, y and z (or rigidly pinned, `k = None`).
fn bar_on_springs(k: Option<f64>) -> Structure {
    let mut support = Support::pinned(1);
    support.stiffness = k;
    Structure::builder()
        .material("steel", Material::new(7850.0, 200e9, 250e6))
        .nodes([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("steel").radius(0.002).mass(3.0))
        .support(Support::pinned(0))
        .support(support)
        .load(1, [0.0, 0.0, -10.0])
        .build()
        .unwrap()
}

#[test]
fn an_elastic_support_is_a_support_to_equilibrium_and_a_spring_to_the_modes() {
    let k = 4.0e5;
    let (elastic, rigid) = (bar_on_springs(Some(k)), bar_on_springs(None));
    let request = StaticsRequest {
        modes: Some(3),
        ..StaticsRequest::default()
    };
    let (e, r) = (
        statics_report(&elastic, &request).unwrap(),
        statics_report(&rigid, &request).unwrap(),
    );
    // the equilibrium analyses: the same counts, forces and reactions (the spring's force)
    assert_eq!(
        (e.rank, e.self_stress_dim, e.mechanisms),
        (r.rank, r.self_stress_dim, r.mechanisms)
    );
    assert_eq!((e.rank, e.self_stress_dim, e.mechanisms), (0, 1, 0));
    assert_eq!(e.reactions, r.reactions);
    assert_eq!(e.reactions.as_ref().unwrap()[1].force, [0.0, 0.0, 10.0]);
    // the modes: the free end of mass m/2 on k I + (EA/L) x xᵀ: ω² = 2k/m (y, z) and
    // 2(k + EA/L)/m (x); the rigid pins leave no free coordinate
    assert!(r.natural_frequencies_hz.is_none_or(|f| f.is_empty()));
    let f = e.natural_frequencies_hz.unwrap();
    let ea_l = 200e9 * PI * 0.002 * 0.002 / 1.5;
    let hz = |w2: f64| w2.sqrt() / (2.0 * PI);
    let expected = [
        hz(2.0 * k / 3.0),
        hz(2.0 * k / 3.0),
        hz(2.0 * (k + ea_l) / 3.0),
    ];
    assert!(rel(&f, &expected) < 1e-12, "{f:?} against {expected:?}");
    // the tangent of the stiffness map: the spring on the node's three free coordinates
    let dofs = DofMap::stiffness_of(&elastic);
    let kt = stiffness::tangent_stiffness(&elastic, &dofs, &DVector::zeros(1), &[ea_l]);
    assert_eq!(kt.nrows(), 3);
    assert!((kt[(0, 0)] - (k + ea_l)).abs() < 1e-12 * ea_l && kt[(1, 1)] == k);
}

#[test]
fn a_skew_elastic_support_adds_k_d_dt_on_its_direction() {
    // node 1 of the inclined roller on a spring along the incline's normal n: in the
    // stiffness map node 1 is free (3 coordinates) and K gains k n nᵀ there
    let (s, c) = (PI / 6.0).sin_cos();
    let k = 2.5e3;
    let structure = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1))
        .support(Support::pinned(0))
        .support(Support::along(1, [[-s, 0.0, c]]).elastic(k))
        .build()
        .unwrap();
    assert_eq!(DofMap::of(&structure).len(), 2);
    let dofs = DofMap::stiffness_of(&structure);
    assert_eq!(dofs.len(), 3);
    let kt = stiffness::tangent_stiffness(&structure, &dofs, &DVector::zeros(1), &[0.0]);
    let n = Vector3::new(-s, 0.0, c);
    let expected = n * n.transpose() * k;
    for i in 0..3 {
        for j in 0..3 {
            assert!((kt[(i, j)] - expected[(i, j)]).abs() < 1e-12 * k);
        }
    }
}
