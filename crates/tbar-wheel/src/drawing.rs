//! Line drawings of Figs. 5.1–5.3 as polylines (pure geometry: the io crate's figure module
//! plots them).
//!
//! A set of members is drawn as few polylines as possible without false segments: a
//! depth-first walk over the members' graph goes along every member and back, so each
//! connected component is one polyline. Views: the side view (ι̂₂ horizontal, ι̂₃ vertical;
//! the wheel's plane, Figs. 5.1–5.2) and the top view (ι̂₂ horizontal, ι̂₁ vertical; the two
//! wheels of Fig. 5.3 side by side).

use crate::geometry::TbarGeometry;
use nalgebra::Vector3;

/// A projection plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// (y, z): the plane of the wheel.
    Side,
    /// (y, x): from above, the axle direction vertical.
    Top,
}

impl View {
    fn project(&self, p: &Vector3<f64>) -> (f64, f64) {
        match self {
            View::Side => (p.y, p.z),
            View::Top => (p.y, p.x),
        }
    }
}

/// One polyline with a legend label (empty for the second and later pieces of a kind).
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    /// Legend text.
    pub label: String,
    /// Projected points (m).
    pub points: Vec<(f64, f64)>,
}

/// Node sequences that trace every edge (there and back), one per connected component.
pub fn walks(n_nodes: usize, edges: &[[usize; 2]]) -> Vec<Vec<usize>> {
    let mut adj = vec![Vec::new(); n_nodes];
    for (e, &[a, b]) in edges.iter().enumerate() {
        adj[a].push((b, e));
        adj[b].push((a, e));
    }
    let mut used = vec![false; edges.len()];
    let mut out = Vec::new();
    for start in 0..n_nodes {
        if adj[start].iter().all(|&(_, e)| used[e]) {
            continue;
        }
        let mut path = vec![start];
        // stack of (node, next adjacency slot)
        let mut stack = vec![(start, 0usize)];
        while let Some(&mut (node, ref mut slot)) = stack.last_mut() {
            if let Some(&(next, e)) = adj[node][*slot..].iter().find(|&&(_, e)| !used[e]) {
                *slot = adj[node].iter().position(|&(_, f)| f == e).unwrap_or(0) + 1;
                used[e] = true;
                path.push(next);
                stack.push((next, 0));
            } else {
                stack.pop();
                if let Some(&(parent, _)) = stack.last() {
                    path.push(parent);
                }
            }
        }
        out.push(path);
    }
    out
}

/// The polylines of a view: strings, the rim body's bars (if any), then the bars with the rim
/// polygon through the bar bases. In the side view only the first wheel's strings are drawn
/// (the copy projects onto them).
pub fn polylines(g: &TbarGeometry, view: View) -> Vec<Polyline> {
    let copies = g.params.copies();
    let per_wheel = g.tips.len() / copies.max(1);
    let shown = if view == View::Side {
        per_wheel
    } else {
        g.tips.len()
    };
    let mut out = Vec::new();
    let strings: Vec<[usize; 2]> = if view == View::Side && copies > 1 {
        let first_copy = g.nodes.len() / copies;
        g.strings
            .iter()
            .copied()
            .filter(|s| s[0] < first_copy && s[1] < first_copy)
            .collect()
    } else {
        g.strings.clone()
    };
    for (i, w) in walks(g.nodes.len(), &strings).into_iter().enumerate() {
        out.push(Polyline {
            label: if i == 0 {
                "strings".into()
            } else {
                String::new()
            },
            points: w.iter().map(|&n| view.project(&g.nodes[n])).collect(),
        });
    }
    let mut bars = Vec::new();
    for w in 0..copies {
        let range = w * per_wheel..((w + 1) * per_wheel).min(shown);
        let mut pts = Vec::new();
        for k in range.clone() {
            let [base, tip] = g.bars[k];
            pts.extend([base, tip, base].map(|n| view.project(&g.nodes[n])));
        }
        if range.len() > 1 {
            let [base, _] = g.bars[range.start];
            pts.push(view.project(&g.nodes[base]));
        }
        if !pts.is_empty() {
            bars.push(pts);
        }
    }
    if let Some(rim) = &g.rim {
        for (i, w) in walks(g.nodes.len(), &rim.bars).into_iter().enumerate() {
            out.push(Polyline {
                label: if i == 0 {
                    "rim body".into()
                } else {
                    String::new()
                },
                points: w.iter().map(|&n| view.project(&g.nodes[n])).collect(),
            });
        }
    }
    for (i, pts) in bars.into_iter().enumerate() {
        out.push(Polyline {
            label: if i == 0 {
                "bars and rim".into()
            } else {
                String::new()
            },
            points: pts,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_walk_traces_every_edge_twice_and_nothing_else() {
        let edges = [[0, 1], [1, 2], [1, 3], [3, 0], [4, 5]];
        let w = walks(6, &edges);
        assert_eq!(w.len(), 2);
        let mut seen = std::collections::HashMap::new();
        for path in &w {
            for p in path.windows(2) {
                let key = (p[0].min(p[1]), p[0].max(p[1]));
                assert!(edges
                    .iter()
                    .any(|e| (e[0].min(e[1]), e[0].max(e[1])) == key));
                *seen.entry(key).or_insert(0) += 1;
            }
        }
        assert_eq!(seen.len(), 5);
        assert!(seen.values().all(|&c| c == 2));
    }
}
