//! The symmetry-adapted statics of cyclic structures against the dense path and closed
//! forms: Snelson prisms (margin 1/√3 for p = 3, ERRATA P.1), a bicycle wheel (axis nodes,
//! an axial bar, supports), random Cₙ-symmetric structures (orbits of n, n/2 and 1 members),
//! and every way a descriptor can fail validation.

use nalgebra::Vector3;
use std::collections::HashSet;
use std::f64::consts::PI;
use tensegrity_core::test_models::{snelson, snelson_twist};
use tensegrity_core::{Bar, CoreError, StaticsError, StringMember, Structure, Support};
use tensegrity_statics::symmetry::{CyclicStatics, CyclicSymmetry, SymmetryError};
use tensegrity_statics::Statics;

/// Symmetric and dense: rank, self-stress, mechanisms, rigid-body and internal mechanisms,
/// the margin to 1e-9; per-representation counts add up. Returns the symmetric margin.
fn compare(s: &Structure, sym: &CyclicSymmetry, what: &str) -> f64 {
    let c = CyclicStatics::new(s, sym).unwrap();
    let d = Statics::new(s).unwrap();
    assert_eq!(c.rank(), d.rank(), "rank, {what}");
    assert_eq!(
        c.self_stress_dim(),
        d.self_stress_dim(),
        "self-stress, {what}"
    );
    assert_eq!(c.mechanisms(), d.mechanisms(), "mechanisms, {what}");
    assert_eq!(c.free_dofs(), d.dofs().len(), "{what}");
    let f = d.flexes().unwrap();
    assert_eq!(c.rigid_body(), f.rigid_body, "rigid-body motions, {what}");
    assert_eq!(
        c.internal_mechanisms(),
        f.internal.ncols(),
        "internal, {what}"
    );
    assert!((c.sigma_max() - d.singular_values()[0]).abs() < 1e-12 * c.sigma_max());
    let reps = c.representations();
    assert_eq!(reps.len(), sym.order());
    assert_eq!(reps.iter().map(|r| r.columns).sum::<usize>(), s.n_members());
    assert_eq!(reps.iter().map(|r| r.rank).sum::<usize>(), c.rank());
    // blocks k and n − k are conjugate: equal counts
    for r in reps {
        let m = reps[(sym.order() - r.k) % sym.order()];
        assert_eq!(
            (r.rank, r.self_stress, r.mechanisms),
            (m.rank, m.self_stress, m.mechanisms)
        );
    }
    let (ps, pd) = (c.prestressability().unwrap(), d.prestressability().unwrap());
    assert!(
        (ps.margin - pd.margin).abs() < 1e-9,
        "margin {} vs {}, {what}",
        ps.margin,
        pd.margin
    );
    assert_eq!(ps.prestressable, pd.prestressable, "{what}");
    // the symmetric basis spans self-stresses
    let a = tensegrity_statics::equilibrium_matrix(s, d.dofs());
    let b = c.symmetric_self_stress_basis();
    if b.ncols() > 0 {
        assert!((&a * &b).amax() < 1e-10 * c.sigma_max(), "A B = 0, {what}");
        let gram = b.transpose() * &b;
        let eye = nalgebra::DMatrix::<f64>::identity(b.ncols(), b.ncols());
        assert!((gram - eye).amax() < 1e-10, "orthonormal, {what}");
    }
    ps.margin
}

#[test]
fn snelson_prisms_match_the_dense_path_and_the_closed_form() {
    for p in 3..=8 {
        let s = snelson(p, snelson_twist(p), 1.0, 1.0, 1.2).build().unwrap();
        let sym = CyclicSymmetry::from_positions(&s, p, Vector3::z(), Vector3::zeros()).unwrap();
        let margin = compare(&s, &sym, &format!("Snelson p = {p}"));
        if p == 3 {
            // q_ring : q_vertical : q_bar = 1 : √3 : −√3 → margin 1/√3 at max|q| = 1
            assert!((margin - 1.0 / 3f64.sqrt()).abs() < 1e-9, "{margin}");
        }
        // one self-stress, fully symmetric
        let c = CyclicStatics::new(&s, &sym).unwrap();
        assert_eq!(c.self_stress_dim(), 1);
        assert_eq!(c.representations()[0].self_stress, 1);
    }
}

/// A bicycle wheel: hub bar along x between (∓h, 0, 0), n rim nodes at radius r joined by
/// rim bars, two spokes (strings) from each rim node to the hub ends, and with `cross` also
/// diameters (strings) between opposite rim nodes (orbits of n/2, n even).
fn bicycle(n: usize, cross: bool) -> tensegrity_core::StructureBuilder {
    let (h, r) = (0.3, 1.0);
    let mut b = Structure::builder();
    for k in 0..n {
        let a = 2.0 * PI * k as f64 / n as f64;
        b = b.node([0.0, r * a.cos(), r * a.sin()]);
    }
    b = b.node([-h, 0.0, 0.0]).node([h, 0.0, 0.0]);
    b = b.bar(Bar::new(n, n + 1));
    for k in 0..n {
        b = b.bar(Bar::new(k, (k + 1) % n));
    }
    for k in 0..n {
        b = b
            .string(StringMember::new(k, n))
            .string(StringMember::new(k, n + 1));
    }
    if cross {
        for k in 0..n / 2 {
            b = b.string(StringMember::new(k, k + n / 2));
        }
    }
    b
}

#[test]
fn bicycle_wheels_with_axis_nodes_diameters_and_supports() {
    for n in [3, 4, 6, 9, 12] {
        let s = bicycle(n, false).build().unwrap();
        let sym = CyclicSymmetry::from_positions(&s, n, Vector3::x(), Vector3::zeros()).unwrap();
        let m = compare(&s, &sym, &format!("wheel n = {n}"));
        assert!(m > 1e-3, "the bicycle wheel is prestressable: {m}");
        if n % 2 == 0 {
            let s = bicycle(n, true).build().unwrap();
            let sym =
                CyclicSymmetry::from_positions(&s, n, Vector3::x(), Vector3::zeros()).unwrap();
            assert!(sym.member_orbits().iter().any(|o| o.size == n / 2));
            compare(&s, &sym, &format!("wheel n = {n} with diameters"));
        }
        // rim pinned; hub ends held in y and z only (free along the axis)
        let mut b = bicycle(n, false);
        for k in 0..n {
            b = b.support(Support::pinned(k));
        }
        b = b
            .support(Support::directions(n, [false, true, true]))
            .support(Support::directions(n + 1, [false, true, true]));
        let s = b.build().unwrap();
        let sym = CyclicSymmetry::from_positions(&s, n, Vector3::x(), Vector3::zeros()).unwrap();
        compare(&s, &sym, &format!("supported wheel n = {n}"));
        // hub ends held along the axis only: one end free transversally
        let s = bicycle(n, false)
            .support(Support::directions(n, [true, false, false]))
            .build()
            .unwrap();
        let sym = CyclicSymmetry::from_positions(&s, n, Vector3::x(), Vector3::zeros()).unwrap();
        compare(&s, &sym, &format!("axially held wheel n = {n}"));
    }
}

/// A small deterministic generator (64-bit LCG) in [0, 1).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, m: usize) -> usize {
        (self.next() * m as f64) as usize % m
    }
}

/// A random Cₙ-symmetric structure about the axis (1, 1, 1)/√3 through (0.5, −0.2, 0.1):
/// a motif of `m` off-axis nodes rotated n times, two axis nodes, member families joining
/// motif node i of copy k to motif node j of copy k + shift (all k), spokes to the axis nodes
/// and the axial member.
fn random_cyclic(
    n: usize,
    m: usize,
    families: usize,
    seed: u64,
) -> (Structure, Vector3<f64>, Vector3<f64>) {
    let mut rng = Lcg(seed);
    let axis = Vector3::new(1.0, 1.0, 1.0).normalize();
    let centre = Vector3::new(0.5, -0.2, 0.1);
    let motif: Vec<Vector3<f64>> = (0..m)
        .map(|_| Vector3::new(rng.next() - 0.5, rng.next() + 0.5, rng.next() - 0.5) * 2.0)
        .collect();
    let mut b = Structure::builder().allow_isolated_nodes(true);
    for k in 0..n {
        let rot = nalgebra::Rotation3::from_axis_angle(
            &nalgebra::Unit::new_normalize(axis),
            2.0 * PI * k as f64 / n as f64,
        );
        for x in &motif {
            let y = rot * x + centre;
            b = b.node([y.x, y.y, y.z]);
        }
    }
    let (a0, a1) = (n * m, n * m + 1);
    for t in [-0.7, 0.9] {
        let y = centre + axis * t;
        b = b.node([y.x, y.y, y.z]);
    }
    let mut seen = HashSet::new();
    let mut add = |b: tensegrity_core::StructureBuilder, i: usize, j: usize, bar: bool| {
        if i == j || !seen.insert((i.min(j), i.max(j))) {
            return b;
        }
        if bar {
            b.bar(Bar::new(i, j))
        } else {
            b.string(StringMember::new(i, j))
        }
    };
    b = add(b, a0, a1, true);
    for f in 0..families {
        let (i, j) = (rng.below(m), rng.below(m));
        let shift = if f == 0 { n / 2 } else { rng.below(n) };
        let bar = rng.next() < 0.3;
        for k in 0..n {
            b = add(b, k * m + i, ((k + shift) % n) * m + j, bar);
        }
    }
    for j in 0..m {
        let end = if rng.next() < 0.5 { a0 } else { a1 };
        for k in 0..n {
            b = add(b, k * m + j, end, false);
        }
    }
    (b.build().unwrap(), axis, centre)
}

#[test]
fn random_cyclic_structures_match_the_dense_path() {
    let mut seed = 1;
    let mut orbit_sizes = HashSet::new();
    let (mut stress_off_zero, mut internal_off_zero) = (false, false);
    for n in [3, 4, 5, 6, 8] {
        for (m, families) in [(2, 3), (3, 6), (4, 9)] {
            seed += 1;
            let (s, axis, centre) = random_cyclic(n, m, families, seed);
            let sym = CyclicSymmetry::from_positions(&s, n, axis, centre).unwrap();
            compare(&s, &sym, &format!("random n = {n}, motif {m}, seed {seed}"));
            let c = CyclicStatics::new(&s, &sym).unwrap();
            let sizes: HashSet<usize> = sym.member_orbits().iter().map(|o| o.size).collect();
            orbit_sizes.extend(sizes);
            for r in c.representations() {
                stress_off_zero |= r.k != 0 && r.self_stress > 0;
                internal_off_zero |= r.k != 0 && r.internal_mechanisms > 0;
            }
        }
    }
    // the sample exercises every kind of orbit and non-trivial representations
    assert!(
        [1, 2, 3, 4, 5, 8].iter().all(|d| orbit_sizes.contains(d)),
        "{orbit_sizes:?}"
    );
    assert!(stress_off_zero && internal_off_zero);
}

fn symmetry_error(e: CoreError) -> SymmetryError {
    match e {
        CoreError::Statics(StaticsError::Symmetry(s)) => *s,
        other => panic!("expected a symmetry error, got {other}"),
    }
}

#[test]
fn invalid_descriptors_name_what_fails() {
    let n = 5;
    let s = bicycle(n, false).build().unwrap();
    let nodes: Vec<usize> = (0..n).map(|k| (k + 1) % n).chain([n, n + 1]).collect();
    let members: Vec<usize> = [0]
        .into_iter()
        .chain((0..n).map(|k| 1 + (k + 1) % n))
        .chain((0..2 * n).map(|e| n + 1 + (2 * (e / 2 + 1) + e % 2) % (2 * n)))
        .collect();
    let ok = CyclicSymmetry::new(
        &s,
        n,
        Vector3::x(),
        Vector3::zeros(),
        nodes.clone(),
        members.clone(),
    );
    assert!(ok.is_ok(), "{:?}", ok.err());
    let new = |n: usize, axis: Vector3<f64>, nodes: Vec<usize>, members: Vec<usize>| {
        symmetry_error(
            CyclicSymmetry::new(&s, n, axis, Vector3::zeros(), nodes, members).unwrap_err(),
        )
    };
    // the rotation by 2π/5 about −x carries rim node 0 to rim node 4, not 1
    let e = new(n, -Vector3::x(), nodes.clone(), members.clone());
    assert!(
        matches!(
            e,
            SymmetryError::NodeNotMapped {
                node: 0,
                image: 1,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("node 0"), "{e}");
    // a wrong order
    let e = new(4, Vector3::x(), nodes.clone(), members.clone());
    assert!(matches!(e, SymmetryError::NodeNotMapped { .. }), "{e}");
    assert!(matches!(
        new(2, Vector3::x(), nodes.clone(), members.clone()),
        SymmetryError::TooFewSides { n: 2 }
    ));
    // not a permutation: two nodes onto one
    let mut dup = nodes.clone();
    dup[1] = dup[0];
    let e = new(n, Vector3::x(), dup, members.clone());
    assert!(
        matches!(
            e,
            SymmetryError::NotAPermutation {
                which: "node",
                item: 1,
                image: 1,
                ..
            }
        ),
        "{e}"
    );
    // wrong length
    let e = new(n, Vector3::x(), nodes[..3].to_vec(), members.clone());
    assert!(
        matches!(
            e,
            SymmetryError::PermutationLength {
                which: "node",
                expected: 7,
                found: 3
            }
        ),
        "{e}"
    );
    // a member mapped to the wrong member: rim bar 1 (member 1) onto rim bar 3
    let mut wrong = members.clone();
    wrong.swap(1, 3);
    let e = new(n, Vector3::x(), nodes.clone(), wrong);
    assert!(matches!(e, SymmetryError::MemberNotMapped { .. }), "{e}");
    assert!(e.to_string().contains("bar 1"), "{e}");
    // a zero axis
    let e = new(n, Vector3::zeros(), nodes.clone(), members.clone());
    assert!(
        matches!(e, SymmetryError::BadAxis { what: "axis", .. }),
        "{e}"
    );
    // an asymmetric support
    let s2 = bicycle(n, false)
        .support(Support::pinned(0))
        .build()
        .unwrap();
    let e = symmetry_error(
        CyclicSymmetry::new(
            &s2,
            n,
            Vector3::x(),
            Vector3::zeros(),
            nodes.clone(),
            members,
        )
        .unwrap_err(),
    );
    assert!(
        matches!(
            e,
            SymmetryError::SupportNotSymmetric {
                node: 0,
                image: 1,
                ..
            }
        ),
        "{e}"
    );
    // from positions: a structure that is not symmetric
    let mut moved = bicycle(n, false).build().unwrap().nodes().to_vec();
    moved[2].y += 0.1;
    let s3 = s.with_nodes(moved).unwrap();
    let e = symmetry_error(
        CyclicSymmetry::from_positions(&s3, n, Vector3::x(), Vector3::zeros()).unwrap_err(),
    );
    assert!(
        matches!(e, SymmetryError::NoImageNode { node: 1, .. }),
        "{e}"
    );
}
