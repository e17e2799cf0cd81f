//! The load path against the linear stiffness of the statics (two independent codes): a
//! prestressed string net under a small load moves as K⁻¹ P, K the tangent stiffness that
//! `tensegrity_statics::stiffness::tangent_stiffness` assembles from the force densities and
//! axial stiffnesses (material + geometric) at the net's prestressed equilibrium, to 10⁻⁸
//! relative.

use nalgebra::{DVector, Vector3};
use tensegrity_core::{StringMember, Structure, Support};
use tensegrity_path::{load_steps, ElasticModel};
use tensegrity_statics::{stiffness, DofMap};

/// A 4 × 4 grid of nodes, its 12 border nodes pinned on the saddle z = (x² − y²)/8, the four
/// inner ones free; strings along the grid lines between them (k = 100 N/m, rest length 0.9
/// of the length), a load `p` on every inner node, the nodes at `x` (or the grid).
fn net(x: Option<&[[f64; 3]]>, p: Vector3<f64>) -> Structure {
    let index = |i: usize, j: usize| 4 * i + j;
    let border = |i: usize, j: usize| i == 0 || i == 3 || j == 0 || j == 3;
    let grid: Vec<[f64; 3]> = (0..16)
        .map(|k| {
            let (i, j) = (k / 4, k % 4);
            let (a, b) = (i as f64 - 1.5, j as f64 - 1.5);
            [
                a,
                b,
                if border(i, j) {
                    (a * a - b * b) / 8.0
                } else {
                    0.0
                },
            ]
        })
        .collect();
    let nodes = x.map_or(grid.clone(), |x| x.to_vec());
    // the corners are on no string
    let mut b = Structure::builder().allow_isolated_nodes(true);
    for n in &nodes {
        b = b.node(*n);
    }
    for i in 0..4 {
        for j in 0..4 {
            let here = index(i, j);
            for (ni, nj) in [(i + 1, j), (i, j + 1)] {
                if ni < 4 && nj < 4 && !(border(i, j) && border(ni, nj)) {
                    // rest lengths from the grid, whatever the nodes
                    let l = (Vector3::from(grid[index(ni, nj)]) - Vector3::from(grid[here])).norm();
                    b = b.string(
                        StringMember::new(here, index(ni, nj))
                            .stiffness(100.0)
                            .rest_length(0.9 * l),
                    );
                }
            }
            if border(i, j) {
                b = b.support(Support::pinned(here));
            } else {
                b = b.load(here, [p.x, p.y, p.z]);
            }
        }
    }
    b.build().unwrap()
}

#[test]
fn a_small_load_moves_the_prestressed_net_as_the_statics_linear_stiffness() {
    let p = Vector3::new(0.3, -0.2, -1.0);
    let model = ElasticModel::from_structure(&net(None, p)).unwrap();
    // the prestressed equilibrium (λ = 0) and two small loads
    let lambda = 1e-5;
    let path = load_steps(&model, 1, lambda).unwrap();
    let (rest, loaded) = (&path.points[0], &path.points[1]);
    // the statics' tangent at the prestressed equilibrium: q = t/L, axial stiffness k
    let at_rest = net(Some(&rest.nodes), p);
    let dofs = DofMap::of(&at_rest);
    let lengths = at_rest.member_lengths();
    let q = DVector::from_iterator(
        rest.tensions.len(),
        rest.tensions.iter().zip(&lengths).map(|(t, l)| t / l),
    );
    let axial = stiffness::axial_stiffness(&at_rest).unwrap();
    let k = stiffness::tangent_stiffness(&at_rest, &dofs, &q, &axial);
    let load = DVector::from_iterator(dofs.len(), dofs.free.iter().map(|&(_, a)| p[a]));
    let u_linear = k.lu().solve(&load).unwrap();
    let u_path = DVector::from_iterator(
        dofs.len(),
        dofs.free
            .iter()
            .map(|&(n, a)| (loaded.nodes[n][a] - rest.nodes[n][a]) / lambda),
    );
    let error = (&u_path - &u_linear).amax() / u_linear.amax();
    assert!(error < 1e-8, "{error:.3e}: {u_path} against {u_linear}");
    // and the prestress is real: every string taut, the inner nodes moved to equilibrium
    assert!(
        rest.tensions.iter().all(|&t| t > 1.0),
        "{:?}",
        rest.tensions
    );
}
