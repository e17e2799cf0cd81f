//! The gallery of classic forms in `examples/formfind/` (issue 23), each form-found through
//! the engine's `formfind` request and checked from its outputs alone:
//!
//! - equilibrium recomputed here: Σ_k q_k (n_j − n_i) + p_i = 0 at every free node i (the sum
//!   over the members k = (i, j) at i, i.e. N Cᵀ diag(q) C = 0 at the free nodes, p_i the
//!   node's load in the loaded net `loaded_net.toml`, zero elsewhere), to 10⁻⁹ of
//!   max|q| · the structure's size;
//! - the sign of every member's force density: bars compressed, strings in tension;
//! - the self-stress dimension, against the core's statics of the exported structure (an
//!   independent SVD of its equilibrium matrix) and against the number known for the form;
//! - the symmetry where it is known: the prisms' twist π/2 + π/N and ring ratio, the
//!   octahedron's parallel bars half a bar length apart, the X-module's parallelogram, the
//!   net's mirror symmetry.

use std::f64::consts::PI;
use tensegrity_engine::formfind::{FormfindRequest, Formfound};
use tensegrity_engine::SceneSource;
use tensegrity_statics::{statics_report, StaticsRequest};

type P = [f64; 3];

fn found(file: &str) -> Formfound {
    let request = FormfindRequest {
        topology: Some(SceneSource::Path(
            format!("examples/formfind/{file}").into(),
        )),
        analyse: true,
        ..Default::default()
    };
    request.run().unwrap_or_else(|e| panic!("{file}: {e}"))
}

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: P) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Checks equilibrium, signs and the self-stress dimension (against the core's statics and
/// `self_stress`); returns the nodes.
fn check(file: &str, self_stress: usize) -> (Formfound, Vec<P>) {
    let f = found(file);
    let nodes = balanced(file, &f);
    check_statics(file, &f, self_stress);
    (f, nodes)
}

/// Equilibrium recomputed from the outputs, the force densities' signs and the held nodes;
/// returns the nodes.
fn balanced(file: &str, f: &Formfound) -> Vec<P> {
    let r = &f.report;
    let nodes = r.nodes.clone();
    let members: Vec<[usize; 2]> = f.topology.members().map(|m| m.nodes).collect();
    assert_eq!(r.force_density.len(), members.len(), "{file}");
    let size = nodes
        .iter()
        .flat_map(|a| nodes.iter().map(move |b| norm(sub(*a, *b))))
        .fold(0.0, f64::max);
    let qmax = r.force_density.iter().map(|q| q.abs()).fold(0.0, f64::max);
    assert!(size > 0.0 && qmax > 0.0, "{file}: a collapsed form");
    let mut force = vec![[0.0; 3]; nodes.len()];
    for l in &f.found.loads {
        force[l.node] = l.force;
    }
    for (&[i, j], q) in members.iter().zip(&r.force_density) {
        let s = sub(nodes[j], nodes[i]);
        for a in 0..3 {
            force[i][a] += q * s[a];
            force[j][a] -= q * s[a];
        }
    }
    let fixed: Vec<usize> = f.topology.fixed.iter().map(|x| x.node).collect();
    for (i, g) in force.iter().enumerate().filter(|(i, _)| !fixed.contains(i)) {
        assert!(
            norm(*g) <= 1e-9 * qmax * size,
            "{file}: node {i} off balance by {g:?}"
        );
    }
    let bars = f.topology.bars.len();
    for (k, q) in r.force_density.iter().enumerate() {
        assert!(
            if k < bars { *q < 0.0 } else { *q > 0.0 },
            "{file}: member {k}: q = {q}"
        );
    }
    // the prescribed nodes stay where they are held
    for x in &f.topology.fixed {
        assert!(
            norm(sub(nodes[x.node], x.position)) < 1e-12,
            "{file}: fixed node {}",
            x.node
        );
    }
    nodes
}

/// Checks the self-stress dimension (against the core's statics and `self_stress`).
fn check_statics(file: &str, f: &Formfound, self_stress: usize) {
    let r = &f.report;
    assert_eq!(r.self_stress_dim, Some(self_stress), "{file}");
    assert_eq!(r.prestressable, Some(true), "{file}");
    assert!(r.residual < 1e-9, "{file}: residual {}", r.residual);
    let structure = f.structure.as_ref().expect("a prestressed structure");
    let statics = statics_report(structure, &StaticsRequest::default()).unwrap();
    assert_eq!(
        statics.self_stress_dim, self_stress,
        "{file}: the core's statics"
    );
    assert!(statics.prestressable, "{file}: the core's statics");
}

/// The angle of p about the z axis.
fn azimuth(p: P) -> f64 {
    p[1].atan2(p[0])
}

/// The twist of node n+i against node i about the axis through the rings' centres, and the
/// radii of both rings (an N-bar prism whose rings are horizontal).
fn prism_rings(nodes: &[P], n: usize) -> (Vec<f64>, f64, f64) {
    let centre = |r: std::ops::Range<usize>| {
        let mut c = [0.0; 3];
        for p in &nodes[r.clone()] {
            for a in 0..3 {
                c[a] += p[a] / r.len() as f64;
            }
        }
        c
    };
    let (cb, ct) = (centre(0..n), centre(n..2 * n));
    let twist = (0..n)
        .map(|i| {
            let d = azimuth(sub(nodes[n + i], ct)) - azimuth(sub(nodes[i], cb));
            d.rem_euclid(2.0 * PI)
        })
        .collect();
    (twist, norm(sub(nodes[0], cb)), norm(sub(nodes[n], ct)))
}

/// Rotates the nodes so that the bottom ring (nodes 0..n) lies in a plane z = const.
fn level(nodes: &[P], n: usize) -> Vec<P> {
    let (a, b, c) = (nodes[0], nodes[1], nodes[2]);
    let u = sub(b, a);
    let v = sub(c, a);
    let mut z = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let top = nodes[n];
    if dot(z, sub(top, a)) < 0.0 {
        z = [-z[0], -z[1], -z[2]];
    }
    let z = z.map(|x| x / norm(z));
    let x = u.map(|t| t / norm(u));
    let y = [
        z[1] * x[2] - z[2] * x[1],
        z[2] * x[0] - z[0] * x[2],
        z[0] * x[1] - z[1] * x[0],
    ];
    nodes
        .iter()
        .map(|p| [dot(*p, x), dot(*p, y), dot(*p, z)])
        .collect()
}

/// Every twist is `want`, or every one −`want` (a form found without positions may come out
/// as its mirror image, an equilibrium as well).
fn assert_twist(file: &str, twist: &[f64], want: f64) {
    let sign = if (twist[0] - want).abs() < 0.1 {
        1.0
    } else {
        -1.0
    };
    for t in twist {
        let t = if sign > 0.0 { *t } else { 2.0 * PI - t };
        assert!(
            (t - want).abs() < 1e-10,
            "{file}: twist {t} instead of ±{want}"
        );
    }
}

fn assert_prism(file: &str, n: usize, radius_ratio: f64) {
    let (f, nodes) = check(file, 1);
    let nodes = level(&nodes, n);
    for p in &nodes[..n] {
        assert!(
            (p[2] - nodes[0][2]).abs() < 1e-10,
            "{file}: bottom ring not planar"
        );
    }
    for p in &nodes[n..] {
        assert!(
            (p[2] - nodes[n][2]).abs() < 1e-10,
            "{file}: top ring not planar"
        );
    }
    let (twist, rb, rt) = prism_rings(&nodes, n);
    assert_twist(file, &twist, PI / 2.0 + PI / n as f64);
    assert!(
        (rt / rb - radius_ratio).abs() < 1e-10,
        "{file}: radii {rb}, {rt}"
    );
    assert_eq!(f.report.prestress_stable, Some(true), "{file}");
}

#[test]
fn the_prisms_twist_by_a_right_angle_plus_pi_over_n() {
    assert_prism("prism3.toml", 3, 1.0);
    assert_prism("quadruplex.toml", 4, 1.0);
    assert_prism("prism5.toml", 5, 1.0);
    // rings in the force-density ratio q_b/q_t = (r_t/r_b)²
    assert_prism("prism6_cone.toml", 6, 0.5);
}

#[test]
fn the_simplex_held_at_four_nodes_stands_where_the_free_one_does() {
    // six free coordinates against twelve members: six self-stresses
    let (_, nodes) = check("simplex_fixed.toml", 6);
    // the held nodes fix the affine freedom: the other top nodes are the free form's, the
    // top triangle the bottom one turned by 150 degrees, at height 1
    let (twist, rb, rt) = prism_rings(&nodes, 3);
    assert!(
        (rb - 1.0).abs() < 1e-12 && (rt - 1.0).abs() < 1e-10,
        "{rb} {rt}"
    );
    for t in twist {
        assert!((t - 5.0 * PI / 6.0).abs() < 1e-10, "{t}");
    }
    assert!(
        nodes[3..].iter().all(|p| (p[2] - 1.0).abs() < 1e-10),
        "{nodes:?}"
    );
}

#[test]
fn the_x_module_closes_its_parallelogram() {
    // the three members at the free corner span the plane only (rank 2): four self-stresses
    let (_, nodes) = check("x_module.toml", 4);
    assert!(
        norm(sub(nodes[3], [0.0, 1.0, 0.0])) < 1e-12,
        "{:?}",
        nodes[3]
    );
}

#[test]
fn the_octahedron_has_parallel_bars_half_a_bar_apart() {
    let (f, nodes) = check("octahedron.toml", 1);
    assert_eq!(f.report.prestress_stable, Some(true));
    let bars: Vec<(P, P)> = f
        .topology
        .bars
        .iter()
        .map(|b| (nodes[b.nodes[0]], nodes[b.nodes[1]]))
        .collect();
    let q = &f.report.force_density;
    assert!((q[6] / q[0] + 2.0 / 3.0).abs() < 1e-10, "{q:?}");
    let mut pairs = 0;
    for (i, a) in bars.iter().enumerate() {
        let da = sub(a.1, a.0);
        let length = norm(da);
        for b in &bars[i + 1..] {
            let db = sub(b.1, b.0);
            let cos = dot(da, db).abs() / (length * norm(db));
            if (cos - 1.0).abs() < 1e-10 {
                pairs += 1;
                // the distance between the parallel lines
                let w = sub(b.0, a.0);
                let along = dot(w, da) / length;
                let gap = (dot(w, w) - along * along).sqrt();
                assert!(
                    (gap - length / 2.0).abs() < 1e-10 * length,
                    "{gap} vs {length}"
                );
            } else {
                assert!(cos < 1e-10, "bars neither parallel nor orthogonal: {cos}");
            }
        }
    }
    assert_eq!(pairs, 3);
}

#[test]
fn the_expanded_polyhedra_find_prestressable_spheres() {
    for (file, s) in [("cuboctahedron12.toml", 1), ("icosidodecahedron30.toml", 1)] {
        let (f, nodes) = check(file, s);
        // every bar of a sphere has the same length, and every node the same distance from
        // the centre
        let c = nodes
            .iter()
            .fold([0.0; 3], |c, p| [c[0] + p[0], c[1] + p[1], c[2] + p[2]]);
        let c = c.map(|x| x / nodes.len() as f64);
        let r0 = norm(sub(nodes[0], c));
        for p in &nodes {
            assert!((norm(sub(*p, c)) - r0).abs() < 1e-8 * r0, "{file}");
        }
        let l0 = norm(sub(
            nodes[f.topology.bars[0].nodes[1]],
            nodes[f.topology.bars[0].nodes[0]],
        ));
        for b in &f.topology.bars {
            let l = norm(sub(nodes[b.nodes[1]], nodes[b.nodes[0]]));
            assert!((l - l0).abs() < 1e-8 * l0, "{file}");
        }
    }
}

#[test]
fn the_towers_stand_in_equilibrium() {
    // one self-stress per stage
    let (_, nodes) = check("tower2.toml", 2);
    // three layers of three nodes, each turned by 150 degrees against the one below, all of
    // the same size
    let nodes = level(&nodes, 3);
    for l in 0..2 {
        let (twist, rb, rt) = prism_rings(&nodes[3 * l..3 * l + 6], 3);
        assert_twist("tower2.toml", &twist, 5.0 * PI / 6.0);
        assert!((rt / rb - 1.0).abs() < 1e-10, "{rb} {rt}");
    }
    check("tower3.toml", 3);
}

#[test]
fn the_cable_net_is_mirror_symmetric() {
    let (_, nodes) = check("cable_net.toml", 1);
    // the boundary is symmetric under x → 4 − x (and y → 4 − y): so is the net
    for p in &nodes {
        for mirror in [[4.0 - p[0], p[1], p[2]], [p[0], 4.0 - p[1], p[2]]] {
            let d = nodes
                .iter()
                .map(|q| norm(sub(*q, mirror)))
                .fold(f64::MAX, f64::min);
            assert!(d < 1e-12, "{p:?}: no mirror image ({d:e})");
        }
    }
    // with q_y = 2 q_x the inner nodes sag below the x = const sections of the saddle
    let centre = nodes
        .iter()
        .find(|p| (p[0] - 2.0).abs() < 1e-12 && (p[1] - 2.0).abs() < 1e-12)
        .unwrap();
    assert!(centre[2] < -0.1, "{centre:?}");
}

#[test]
fn dynamic_relaxation_reaches_the_force_density_form() {
    // prism3_dr.toml gives the rest lengths of prism3.toml's form at 100 N: dynamic
    // relaxation must land on that form up to a rigid motion (every distance between two
    // nodes the same, to 1e-8 of the size)
    let dr = found("prism3_dr.toml");
    assert_eq!(dr.report.method.to_string(), "dr");
    let fdm = found("prism3.toml");
    let (a, b) = (&dr.report.nodes, &fdm.report.nodes);
    let size = norm(sub(b[0], b[4]));
    for i in 0..6 {
        for j in 0..6 {
            let (da, db) = (norm(sub(a[i], a[j])), norm(sub(b[i], b[j])));
            assert!((da - db).abs() < 1e-8 * size, "{i}-{j}: {da} vs {db}");
        }
    }
    // and its force densities are the same up to the scale: q / q_vertical
    let (qa, qb) = (&dr.report.force_density, &fdm.report.force_density);
    for k in 0..12 {
        let (ra, rb) = (qa[k] / qa[11], qb[k] / qb[11]);
        assert!((ra - rb).abs() < 1e-8, "member {k}: {ra} vs {rb}");
    }
    // the relaxed form's rank decision follows its residual: the same one self-stress
    assert_eq!(dr.report.self_stress_dim, fdm.report.self_stress_dim);
    assert_eq!(dr.report.self_stress_dim, Some(1));
}

#[test]
fn every_gallery_form_is_in_equilibrium_with_the_right_signs() {
    let mut files: Vec<String> = std::fs::read_dir("examples/formfind")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 12, "{files:?}");
    for file in &files {
        let f = found(file);
        balanced(file, &f);
        // a loaded form carries its loads and needs no self-stress
        let loaded = f.topology.is_loaded();
        assert!(loaded || f.report.prestressable == Some(true), "{file}");
        assert!(f.report.residual < 1e-9, "{file}");
        assert!(f.structure.is_some(), "{file}: no prestressed structure");
    }
}
