//! A double-layer lattice of K × K four-bar prisms (the geometry of formfind's `grid:K`, in
//! its exact form): the 3-D lattice of the sparse statics' scaling (issue 25).

use crate::error::Result;
use crate::structure::{Bar, StringMember, Structure, Support};

/// The double-layer grid of K × K four-bar prisms with its outline held: bottom corners on
/// the lattice (u, v, 0), top nodes on the cell-edge midpoints at z = ½; per unit 4 bars
/// (corner to the opposite edge midpoint), 4 top strings and 4 vertical strings; the
/// lattice edges are strings. Every outline corner is pinned, and every outline top node
/// whose bar ends at a free corner that has fewer than two such pinned bars. Nodes
/// (K+1)² + 2K(K+1), members 14K² + 2K(K+1). K ≥ 2.
pub fn double_layer_grid(k: usize) -> Result<Structure> {
    let corner = |u: usize, v: usize| v * (k + 1) + u;
    let nc = (k + 1) * (k + 1);
    let xmid = |u: usize, v: usize| nc + v * k + u;
    let ny = nc + (k + 1) * k;
    let ymid = |u: usize, v: usize| ny + v * (k + 1) + u;
    let n_nodes = ny + k * (k + 1);
    let mut nodes = vec![[0.0; 3]; n_nodes];
    for v in 0..=k {
        for u in 0..=k {
            nodes[corner(u, v)] = [u as f64, v as f64, 0.0];
            if u < k {
                nodes[xmid(u, v)] = [u as f64 + 0.5, v as f64, 0.5];
            }
            if v < k {
                nodes[ymid(u, v)] = [u as f64, v as f64 + 0.5, 0.5];
            }
        }
    }
    let (mut bars, mut strings) = (Vec::new(), Vec::new());
    for v in 0..k {
        for u in 0..k {
            let b = [
                corner(u + 1, v + 1),
                corner(u, v + 1),
                corner(u, v),
                corner(u + 1, v),
            ];
            let t = [ymid(u, v), xmid(u, v), ymid(u + 1, v), xmid(u, v + 1)];
            for i in 0..4 {
                bars.push([b[i], t[i]]);
                strings.push([t[i], t[(i + 1) % 4]]);
                strings.push([b[i], t[(i + 3) % 4]]);
            }
        }
    }
    for v in 0..=k {
        for u in 0..k {
            strings.push([corner(u, v), corner(u + 1, v)]);
            strings.push([corner(v, u), corner(v, u + 1)]);
        }
    }
    let kk = k as f64;
    let outline = |p: &[f64; 3]| p[0] == 0.0 || p[1] == 0.0 || p[0] == kk || p[1] == kk;
    let mut fix: Vec<bool> = (0..n_nodes).map(|i| i < nc && outline(&nodes[i])).collect();
    let mut pinned_bars = vec![0usize; n_nodes];
    for &[c, t] in &bars {
        if outline(&nodes[t]) && !fix[c] && pinned_bars[c] < 2 {
            fix[t] = true;
            pinned_bars[c] += 1;
        }
    }
    let mut builder = Structure::builder().nodes(nodes);
    for [i, j] in bars {
        builder = builder.bar(Bar::new(i, j));
    }
    for [i, j] in strings {
        builder = builder.string(StringMember::new(i, j));
    }
    for (i, _) in fix.iter().enumerate().filter(|&(_, &f)| f) {
        builder = builder.support(Support::pinned(i));
    }
    builder.build()
}
