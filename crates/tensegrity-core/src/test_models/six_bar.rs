//! The six-bar tensegrity icosahedron (the expanded octahedron): three pairs of parallel bars
//! of length 2 along x, y and z, the bars of a pair 1 apart, 24 strings along the edges of the
//! icosahedron their 12 ends span that no bar takes. In its self-equilibrium every string
//! carries force density q and every bar −(3/2) q: at the end (½, 0, 1) of a z-bar the four
//! strings pull along Σ (x_j − x_i) = (0, 0, −3) and the bar pushes along (0, 0, 2) (its
//! other end at (½, 0, −1)), so q_bar · 2 + q · (−3) … balance for q_bar = −(3/2) q.

use crate::{Bar, Result, StringMember, Structure};

/// The 12 nodes: z-bars at x = ±½ (nodes 0–3), x-bars at y = ±½ (4–7), y-bars at z = ±½
/// (8–11), each pair's bars listed as (−end, +end).
pub fn six_bar_nodes() -> Vec<[f64; 3]> {
    let mut nodes = Vec::with_capacity(12);
    for s in [0.5, -0.5] {
        nodes.push([s, 0.0, -1.0]);
        nodes.push([s, 0.0, 1.0]);
    }
    for s in [0.5, -0.5] {
        nodes.push([-1.0, s, 0.0]);
        nodes.push([1.0, s, 0.0]);
    }
    for s in [0.5, -0.5] {
        nodes.push([0.0, -1.0, s]);
        nodes.push([0.0, 1.0, s]);
    }
    nodes
}

/// The six-bar icosahedron in its self-equilibrium (module docs): bars of mass `bar_mass`
/// (kg), strings of stiffness `stiffness` (N/m) and damping `damping` (N·s/m) whose rest
/// lengths l (1 − q/k) realise the string force density `prestress` q (N/m), so that it is at
/// rest in equilibrium. Strings are the pairs of nodes at the icosahedron's edge length √(3/2)
/// (bars and the far pairs excluded), in index order.
pub fn six_bar(bar_mass: f64, stiffness: f64, prestress: f64, damping: f64) -> Result<Structure> {
    let nodes = six_bar_nodes();
    let dist = |a: usize, b: usize| {
        let (x, y) = (nodes[a], nodes[b]);
        ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
    };
    let edge = 1.5f64.sqrt();
    let mut b = Structure::builder().nodes(nodes.clone());
    for k in 0..6 {
        b = b.bar(Bar::new(2 * k, 2 * k + 1).mass(bar_mass));
    }
    for i in 0..12 {
        for j in i + 1..12 {
            let l = dist(i, j);
            if (l - edge).abs() < 1e-12 {
                b = b.string(
                    StringMember::new(i, j)
                        .stiffness(stiffness)
                        .rest_length(l * (1.0 - prestress / stiffness))
                        .damping(damping),
                );
            }
        }
    }
    b.build()
}
