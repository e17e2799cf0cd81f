//! Built-in topologies by name: `prism:N`, `octahedron`, `tower:N:M`, `grid:K`.
//!
//! Each carries initial nodes (its exact form, up to the affine freedom) and groups with
//! force densities that admit the form, so every method applies.
//!
//! - `prism:N` (3 ≤ N ≤ [`MAX_PRISM`]): bottom nodes 0…N−1 on the unit circle at z = 0
//!   (angle 2πi/N), top nodes N…2N−1 at z = 1 (angle 2πi/N + π/2 + π/N). Members: bars
//!   (i, N+i), bottom strings (i, i+1), top strings (N+i, N+i+1), vertical strings
//!   (i, N+(i−1 mod N)), indices mod N. Groups `bars` (q = −1), `bottom` and `top`
//!   (q = 1/(2 sin(π/N))), `vertical` (q = 1).
//! - `octahedron`: the expanded octahedron, six bars of length 2 in three parallel pairs,
//!   half a bar length apart: bar 2a+s (axis a = x, y, z; s = 0 for the + offset, 1 for the
//!   −) runs along axis a from −1 to 1 (nodes 2·bar, 2·bar+1), offset ±½ along axis a+2
//!   (mod 3). The 24 strings are the edges of the 8 triangles, one per octant (σx, σy, σz):
//!   the end σ_a of the bar along a whose offset sign is σ_{a+2}. Groups `bars` (q = −3/2)
//!   and `strings` (q = 1): string/bar = −2/3.
//! - `tower:N:M` (M ≥ 1 stages, N·(M+1) ≤ 1200 nodes): layers l = 0…M of N nodes (node lN+i at angle
//!   2πi/N + l(π/2 + π/N), z = l); stage s is a prism between layers s and s+1 sharing its
//!   rings with the neighbouring stages (class-2 joints at the inner layers). Members: bars
//!   (sN+i, (s+1)N+i) stage by stage, then ring strings (lN+i, lN+i+1) layer by layer, then
//!   vertical strings (sN+i, (s+1)N+(i−1 mod N)) stage by stage. Groups `bars` (−1),
//!   `vertical` (1), `ring_end` (layers 0 and M: 1/(2 sin(π/N))) and `ring_inner`
//!   (1/sin(π/N), the sum of the two stages' rings). Each inner ring is planar, so
//!   neighbouring stages may take affine maps that differ by a fold along it: D has nullity
//!   4 + (M − 1), the form is prestress stable but not super stable, and the self-stress
//!   space has dimension M (one per stage).
//! - `grid:K` (1 ≤ K ≤ [`MAX_GRID`]): a double-layer grid of K × K four-bar prisms. Unit
//!   (u, v) has its bottom square on the lattice corners (u…u+1, v…v+1, z = 0) and its top
//!   square, twisted by 3π/4 and of radius ½, on the midpoints of the cell's edges at
//!   z = ½; neighbouring units share their corner nodes (bottom layer, up to four bars) and
//!   edge-midpoint nodes (top layer, two bars). Nodes: the (K+1)² corners (index
//!   v(K+1)+u) then the midpoints of the x-parallel edges ((K+1)K, at (u+½, v)) then of the
//!   y-parallel edges (K(K+1), at (u, v+½)). Members unit by unit (row-major): 4 bars
//!   (corner i to top node i), then the bottom lattice edges (each once: q = ½ on the
//!   boundary, 1 inside, groups `edge_boundary` / `edge_inner`), then per unit the 4 top
//!   strings (`top`, q = 1) and 4 vertical strings (`vertical`, q = 1). For K ≥ 2 the
//!   boundary is fixed: every corner node on the outline, and every top node on the outline
//!   except those whose bar ends at a fixed corner (no bar is held at both ends) or at a
//!   corner that already has two bars to fixed top nodes (in bar order), so that the
//!   rigid bars of the dynamics meet no redundant constraint. This
//!   removes the free grid's folding freedom along the lattice lines (a free grid's D has
//!   nullity 4 + 2(K − 1): each unit may take its own affine map, continuous across the
//!   lattice planes) and makes D_ff positive definite. `grid:1` is the free-standing
//!   four-bar prism with r_b = 1/√2, r_t = ½.

use crate::error::{FormFindError, Result};
use crate::topology::{FixedNode, Group, Member, Topology};
use std::collections::BTreeMap;
use std::f64::consts::PI;
use tensegrity_core::request::InvalidParameter;

/// The names (and forms) [`builtin`] knows.
pub const BUILTINS: &[&str] = &["prism:N", "octahedron", "tower:N:M", "grid:K"];

/// Largest N of `prism:N` and `tower:N:M`.
pub const MAX_PRISM: usize = 1000;
/// Largest number of stages M of `tower:N:M`.
pub const MAX_STAGES: usize = 1000;
/// Largest K of `grid:K`.
pub const MAX_GRID: usize = 300;

/// A built-in topology by name (see the module documentation of the forms).
///
/// ```
/// let t = formfind::builtin("prism:3").unwrap();
/// assert_eq!((t.n_nodes, t.bars.len(), t.strings.len()), (6, 3, 9));
/// assert!(formfind::builtin("prism:2").is_err());
/// ```
pub fn builtin(name: &str) -> Result<Topology> {
    let parts: Vec<&str> = name.trim().split(':').collect();
    match parts.as_slice() {
        ["prism", n] => Ok(prism(parse(name, "N", n, 3, MAX_PRISM)?)),
        ["octahedron"] => Ok(octahedron()),
        ["tower", n, m] => {
            let n = parse(name, "N", n, 3, MAX_PRISM)?;
            let m = parse(name, "M", m, 1, MAX_STAGES)?;
            if n * (m + 1) > crate::fdm::DENSE_MAX_NODES {
                return Err(FormFindError::InvalidParameter(InvalidParameter::raw(
                    format!("N·(M+1) of built-in \"{name}\""),
                    n * (m + 1),
                    format!(
                        "a tower has N·(M+1) nodes, at most {} (its stacked rings let the \
                         stages fold, which needs the dense null space)",
                        crate::fdm::DENSE_MAX_NODES
                    ),
                )));
            }
            Ok(tower(n, m))
        }
        ["grid", k] => Ok(grid(parse(name, "K", k, 1, MAX_GRID)?)),
        _ => Err(FormFindError::UnknownBuiltin {
            name: name.to_string(),
            known: BUILTINS.join(", "),
        }),
    }
}

/// Parses one integer parameter of a built-in name, in [lo, hi].
fn parse(name: &str, what: &str, text: &str, lo: usize, hi: usize) -> Result<usize> {
    let invalid = |reason: String| {
        FormFindError::InvalidParameter(InvalidParameter::text(
            format!("{what} of built-in \"{name}\""),
            text,
            reason,
        ))
    };
    let v: usize = text
        .trim()
        .parse()
        .map_err(|_| invalid(format!("{what} must be a whole number")))?;
    if v < lo || v > hi {
        return Err(invalid(format!("{what} must lie in {lo}…{hi}")));
    }
    Ok(v)
}

/// The twist of an N-bar prism's top polygon against its bottom one, π/2 + π/N.
pub fn prism_twist(n: usize) -> f64 {
    PI / 2.0 + PI / n as f64
}

fn group(q: f64) -> Group {
    Group {
        force_density: Some(q),
        length: None,
        weight: None,
    }
}

fn groups(list: &[(&str, f64)]) -> BTreeMap<String, Group> {
    list.iter()
        .map(|&(n, q)| (n.to_string(), group(q)))
        .collect()
}

fn prism(n: usize) -> Topology {
    let a = prism_twist(n);
    let mut nodes = Vec::with_capacity(2 * n);
    for i in 0..n {
        let t = 2.0 * PI * i as f64 / n as f64;
        nodes.push([t.cos(), t.sin(), 0.0]);
    }
    for i in 0..n {
        let t = 2.0 * PI * i as f64 / n as f64 + a;
        nodes.push([t.cos(), t.sin(), 1.0]);
    }
    let bars = (0..n)
        .map(|i| Member::new(i, n + i).group("bars"))
        .collect();
    let mut strings: Vec<Member> = (0..n)
        .map(|i| Member::new(i, (i + 1) % n).group("bottom"))
        .collect();
    strings.extend((0..n).map(|i| Member::new(n + i, n + (i + 1) % n).group("top")));
    strings.extend((0..n).map(|i| Member::new(i, n + (i + n - 1) % n).group("vertical")));
    let ring = 1.0 / (2.0 * (PI / n as f64).sin());
    Topology {
        n_nodes: 2 * n,
        nodes: Some(nodes),
        bars,
        strings,
        groups: groups(&[
            ("bars", -1.0),
            ("bottom", ring),
            ("top", ring),
            ("vertical", 1.0),
        ]),
        fixed: Vec::new(),
        loads: Vec::new(),
        clusters: Vec::new(),
    }
}

fn octahedron() -> Topology {
    let node = |axis: usize, offset_negative: bool, end_positive: bool| {
        2 * (2 * axis + offset_negative as usize) + end_positive as usize
    };
    let mut nodes = vec![[0.0; 3]; 12];
    for axis in 0..3 {
        for neg in [false, true] {
            for pos in [false, true] {
                let mut p = [0.0; 3];
                p[axis] = if pos { 1.0 } else { -1.0 };
                p[(axis + 2) % 3] = if neg { -0.5 } else { 0.5 };
                nodes[node(axis, neg, pos)] = p;
            }
        }
    }
    let bars = (0..6)
        .map(|b| Member::new(2 * b, 2 * b + 1).group("bars"))
        .collect();
    let mut strings = Vec::new();
    for oct in 0..8 {
        let s = [oct & 1 != 0, oct & 2 != 0, oct & 4 != 0]; // true = negative side
        let tri: Vec<usize> = (0..3).map(|a| node(a, s[(a + 2) % 3], !s[a])).collect();
        for (x, y) in [(0, 1), (1, 2), (2, 0)] {
            strings.push(Member::new(tri[x], tri[y]).group("strings"));
        }
    }
    Topology {
        n_nodes: 12,
        nodes: Some(nodes),
        bars,
        strings,
        groups: groups(&[("bars", -1.5), ("strings", 1.0)]),
        fixed: Vec::new(),
        loads: Vec::new(),
        clusters: Vec::new(),
    }
}

fn tower(n: usize, m: usize) -> Topology {
    let a = prism_twist(n);
    let mut nodes = Vec::with_capacity(n * (m + 1));
    for l in 0..=m {
        for i in 0..n {
            let t = 2.0 * PI * i as f64 / n as f64 + l as f64 * a;
            nodes.push([t.cos(), t.sin(), l as f64]);
        }
    }
    let mut bars = Vec::with_capacity(n * m);
    for s in 0..m {
        bars.extend((0..n).map(|i| Member::new(s * n + i, (s + 1) * n + i).group("bars")));
    }
    let mut strings = Vec::with_capacity(n * (2 * m + 1));
    for l in 0..=m {
        let g = if l == 0 || l == m {
            "ring_end"
        } else {
            "ring_inner"
        };
        strings.extend((0..n).map(|i| Member::new(l * n + i, l * n + (i + 1) % n).group(g)));
    }
    for s in 0..m {
        strings.extend(
            (0..n).map(|i| Member::new(s * n + i, (s + 1) * n + (i + n - 1) % n).group("vertical")),
        );
    }
    let ring = 1.0 / (2.0 * (PI / n as f64).sin());
    Topology {
        n_nodes: n * (m + 1),
        nodes: Some(nodes),
        bars,
        strings,
        groups: groups(&[
            ("bars", -1.0),
            ("ring_end", ring),
            ("ring_inner", 2.0 * ring),
            ("vertical", 1.0),
        ]),
        fixed: Vec::new(),
        loads: Vec::new(),
        clusters: Vec::new(),
    }
}

fn grid(k: usize) -> Topology {
    let corner = |u: usize, v: usize| v * (k + 1) + u;
    let nc = (k + 1) * (k + 1);
    let xmid = |u: usize, v: usize| nc + v * k + u; // (u+½, v), v in 0..=k
    let ny = nc + (k + 1) * k;
    let ymid = |u: usize, v: usize| ny + v * (k + 1) + u; // (u, v+½), u in 0..=k
    let n_nodes = ny + k * (k + 1);
    let mut nodes = vec![[0.0; 3]; n_nodes];
    for v in 0..=k {
        for u in 0..=k {
            nodes[corner(u, v)] = [u as f64, v as f64, 0.0];
        }
    }
    for v in 0..=k {
        for u in 0..k {
            nodes[xmid(u, v)] = [u as f64 + 0.5, v as f64, 0.5];
        }
    }
    for v in 0..k {
        for u in 0..=k {
            nodes[ymid(u, v)] = [u as f64, v as f64 + 0.5, 0.5];
        }
    }
    let mut bars = Vec::with_capacity(4 * k * k);
    let mut top = Vec::with_capacity(4 * k * k);
    let mut vertical = Vec::with_capacity(4 * k * k);
    for v in 0..k {
        for u in 0..k {
            // Bottom corners at angles π/4 + iπ/2, top nodes at π + iπ/2 (W, S, E, N).
            let b = [
                corner(u + 1, v + 1),
                corner(u, v + 1),
                corner(u, v),
                corner(u + 1, v),
            ];
            let t = [ymid(u, v), xmid(u, v), ymid(u + 1, v), xmid(u, v + 1)];
            for i in 0..4 {
                bars.push(Member::new(b[i], t[i]).group("bars"));
                top.push(Member::new(t[i], t[(i + 1) % 4]).group("top"));
                vertical.push(Member::new(b[i], t[(i + 3) % 4]).group("vertical"));
            }
        }
    }
    let mut strings = Vec::with_capacity(2 * k * (k + 1) + 8 * k * k);
    for v in 0..=k {
        for u in 0..k {
            let g = if v == 0 || v == k {
                "edge_boundary"
            } else {
                "edge_inner"
            };
            strings.push(Member::new(corner(u, v), corner(u + 1, v)).group(g));
        }
    }
    for v in 0..k {
        for u in 0..=k {
            let g = if u == 0 || u == k {
                "edge_boundary"
            } else {
                "edge_inner"
            };
            strings.push(Member::new(corner(u, v), corner(u, v + 1)).group(g));
        }
    }
    strings.extend(top);
    strings.extend(vertical);
    let on_outline = |p: &[f64; 3]| {
        let kk = k as f64;
        p[0] == 0.0 || p[1] == 0.0 || p[0] == kk || p[1] == kk
    };
    // A top node on the outline is fixed unless its bar ends at a fixed corner (no bar held
    // at both ends) or at a corner that already has two bars to fixed top nodes (three would
    // pin that corner, four over-constrain it): the rigid bars of the dynamics then meet no
    // redundant constraint.
    let mut fix = vec![false; n_nodes];
    let mut pinned_bars = vec![0usize; n_nodes];
    for (i, p) in nodes.iter().enumerate().take(nc) {
        fix[i] = on_outline(p);
    }
    for b in &bars {
        let [c, t] = b.nodes;
        if on_outline(&nodes[t]) && !fix[c] && pinned_bars[c] < 2 {
            fix[t] = true;
            pinned_bars[c] += 1;
        }
    }
    let fixed = if k == 1 {
        Vec::new()
    } else {
        (0..n_nodes)
            .filter(|&i| fix[i])
            .map(|node| FixedNode {
                node,
                position: nodes[node],
            })
            .collect()
    };
    Topology {
        n_nodes,
        nodes: Some(nodes),
        bars,
        strings,
        groups: groups(&[
            ("bars", -1.0),
            ("edge_boundary", 0.5),
            ("edge_inner", 1.0),
            ("top", 1.0),
            ("vertical", 1.0),
        ]),
        fixed,
        loads: Vec::new(),
        clusters: Vec::new(),
    }
}
