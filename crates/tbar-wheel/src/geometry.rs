//! Geometry of the T-bar tread (Fig. 5.1), wheel (Fig. 5.2) and extended wheel (Fig. 5.3).
//!
//! **Lattice** (§5.1, ERRATA 5.1). Nodes are four-index tuples (U, D, L, R) with the Michell
//! conventions 𝕏 = L − R, ℤ = U − D and level l = U + D. A node's four offspring are
//! (U+1, L+1), (U+1, R+1), (D+1, L+1), (D+1, R+1); identical tuples reached from different
//! parents are one node, so level l holds every tuple with U + D = L + R = l: (l+1)² nodes
//! (1, 4, 9, 16, 25 for l = 0..4). Positions reuse michell3d's parameterisation
//! ([`michell3d::nodes::position`]) with r_l = r₀aˡ of the node's own level:
//!
//! - cylindrical (eq. 4.11): n = r_l [𝕏δ, cos ℤφ, sin ℤφ];
//! - spherical (eq. 4.12):   n = r_l [cos(ℤφ) tan(𝕏ε), cos ℤφ, sin ℤφ].
//!
//! For q = 1 this gives n₁₀₁₀ = r₁[δ, cos φ, sin φ], n₁₀₀₁ = r₁[−δ, cos φ, sin φ],
//! n₀₁₁₀ = r₁[δ, cos φ, −sin φ], n₀₁₀₁ = r₁[−δ, cos φ, −sin φ] (§5.1). Every lattice member
//! (parent → child) is a string; the tip n₀₀₀₀ = [0, r₀, 0] is the principal node.
//!
//! **Bar and rim.** One bar runs radially from its base on the rim to the tip: the base is the
//! rim point [0, r_q, 0] ([`BarBase::Rim`]) or the chord point [0, r_q cos φ, 0]
//! ([`BarBase::Chord`]). Level-q nodes lie on the rim cylinder of radius r_q; the rim is rigid,
//! so every level-q node and every bar base is a pinned support. With the rim base and even q
//! the base is the lattice node (q/2, q/2, q/2, q/2): the two are one node.
//!
//! **Wheel.** Tread k is tread 0 rotated by 2kφ about ι̂₁ (k = 0..π/φ − 1). A node of tread k
//! at ℤ lies at the angle (ℤ + 2k)φ, so tread k's rim nodes at ℤ = +1 are tread k+1's at
//! ℤ = −1: neighbours share rim nodes. Nodes are merged by **position** (distance below
//! [`MERGE_TOL`]·r₀), which covers every coincidence at once: shared rim nodes, the bar base
//! on a lattice node, and (q ≥ 2) the interior nodes that neighbouring treads share; members
//! that then join the same two nodes are one member. For q = 1, φ = π/8: 8 treads × (tip +
//! base) + 16 rim nodes (32 rim points shared in pairs) = 32 nodes, 8 bars and 8 × 4 = 32
//! strings. The **extended wheel** adds a copy of the wheel translated by the offset along
//! ι̂₁; the two copies share nothing (64 nodes, 16 bars, 64 strings for q = 1, φ = π/8).
//!
//! **Rim body.** With [`RimMode::Body`] the supports are replaced by a rim body of bars (two
//! hub nodes `hub_left`, `hub_right` appended last, spokes and a ring; see [`crate::rim`]),
//! attached at the end of [`TbarGeometry::new`].
//!
//! **Labels.** Tread 0 of the first wheel: `tip`, `bar_base`, then its lattice tuples level by
//! level as `UDLR` (e.g. `1010`; `U_D_L_R` when an index exceeds 9), inside a level by D
//! ascending then L descending. Nodes first met in tread k > 0 are prefixed `t{k}.`, and in the
//! copy of the extended wheel `e.t{k}.`; a shared node keeps its first label. Node order:
//! tread by tread in that order, each tread tip, bar base, lattice.

use crate::error::Result;
use crate::params::{BarBase, Layout, RimMode, TbarParams};
use crate::rim::RimBody;
use michell3d::nodes::{position, NodeTuple};
use nalgebra::{Rotation3, Vector3};
use std::collections::{BTreeMap, HashMap, HashSet};
use tensegrity_core::{Bar, StringMember, Structure, Support};

/// Nodes closer than this × r₀ are one node.
pub const MERGE_TOL: f64 = 1e-9;

/// Most nodes a structure may have before merging (copies × treads × (lattice nodes + 2)),
/// checked before anything is built: about 0.5 GB of geometry and statics blocks.
pub const MAX_NODES: usize = 2_000_000;

/// The tuples of lattice level l in label order (D ascending, then L descending): (l+1)².
///
/// ```
/// let lev = tbar_wheel::geometry::lattice_level(1);
/// let labels: Vec<_> = lev.iter().map(tbar_wheel::geometry::tuple_label).collect();
/// assert_eq!(labels, ["1010", "1001", "0110", "0101"]);
/// ```
pub fn lattice_level(level: usize) -> Vec<NodeTuple> {
    let mut out = Vec::with_capacity((level + 1) * (level + 1));
    for d in 0..=level {
        for l in (0..=level).rev() {
            out.push(NodeTuple::new(level - d, d, l, level - l));
        }
    }
    out
}

/// The four offspring (U+1, L+1), (U+1, R+1), (D+1, L+1), (D+1, R+1) of a tuple.
pub fn offspring(t: &NodeTuple) -> [NodeTuple; 4] {
    let NodeTuple { u, d, l, r } = *t;
    [
        NodeTuple::new(u + 1, d, l + 1, r),
        NodeTuple::new(u + 1, d, l, r + 1),
        NodeTuple::new(u, d + 1, l + 1, r),
        NodeTuple::new(u, d + 1, l, r + 1),
    ]
}

/// `UDLR` (e.g. `1010`), or `U_D_L_R` when an index exceeds 9.
pub fn tuple_label(t: &NodeTuple) -> String {
    if t.u.max(t.d).max(t.l).max(t.r) <= 9 {
        format!("{}{}{}{}", t.u, t.d, t.l, t.r)
    } else {
        format!("{}_{}_{}_{}", t.u, t.d, t.l, t.r)
    }
}

/// Lattice nodes of a complexity-q tread: Σ_{l=0}^{q} (l+1)² = (q+1)(q+2)(2q+3)/6.
pub fn lattice_node_count(q: usize) -> usize {
    (q + 1) * (q + 2) * (2 * q + 3) / 6
}

/// One node of a tread before merging.
#[derive(Debug, Clone)]
struct RawNode {
    label: String,
    position: Vector3<f64>,
    support: bool,
}

/// One tread before merging: nodes (tip first, bar base second), strings parent → child and
/// the bar (base, tip) as indices into `nodes`.
#[derive(Debug, Clone)]
struct RawTread {
    nodes: Vec<RawNode>,
    strings: Vec<[usize; 2]>,
    bar: [usize; 2],
}

/// Tread 0, unrotated.
fn raw_tread(params: &TbarParams) -> RawTread {
    let m = &params.michell;
    let q = params.complexity();
    let r_q = params.rim_radius();
    let base = match params.bar_base {
        BarBase::Rim => Vector3::new(0.0, r_q, 0.0),
        BarBase::Chord => Vector3::new(0.0, r_q * m.phi.cos(), 0.0),
    };
    let tip = NodeTuple::new(0, 0, 0, 0);
    let mut nodes = vec![
        RawNode {
            label: "tip".into(),
            position: position(m, &tip),
            support: false,
        },
        RawNode {
            label: "bar_base".into(),
            position: base,
            support: true,
        },
    ];
    let mut index: HashMap<NodeTuple, usize> = HashMap::from([(tip, 0)]);
    for level in 1..=q {
        for t in lattice_level(level) {
            index.insert(t, nodes.len());
            nodes.push(RawNode {
                label: tuple_label(&t),
                position: position(m, &t),
                support: level == q,
            });
        }
    }
    let mut strings = Vec::new();
    for level in 0..q {
        for t in lattice_level(level) {
            for c in offspring(&t) {
                strings.push([index[&t], index[&c]]);
            }
        }
    }
    RawTread {
        nodes,
        strings,
        bar: [1, 0],
    }
}

/// Merges nodes by position on a hash grid.
struct Merger {
    tol: f64,
    cell: f64,
    grid: HashMap<[i64; 3], Vec<usize>>,
    positions: Vec<Vector3<f64>>,
}

impl Merger {
    fn new(r0: f64) -> Self {
        Self {
            tol: MERGE_TOL * r0,
            cell: 1e3 * MERGE_TOL * r0,
            grid: HashMap::new(),
            positions: Vec::new(),
        }
    }

    fn key(&self, p: &Vector3<f64>) -> [i64; 3] {
        [0, 1, 2].map(|d| (p[d] / self.cell).floor() as i64)
    }

    /// The index of the node at `p`, and whether it is new.
    fn insert(&mut self, p: Vector3<f64>) -> (usize, bool) {
        let k = self.key(&p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    // saturating: a position far out (a huge offset) keeps a key
                    let kk = [
                        k[0].saturating_add(dx),
                        k[1].saturating_add(dy),
                        k[2].saturating_add(dz),
                    ];
                    if let Some(list) = self.grid.get(&kk) {
                        if let Some(&i) = list
                            .iter()
                            .find(|&&i| (self.positions[i] - p).norm() <= self.tol)
                        {
                            return (i, false);
                        }
                    }
                }
            }
        }
        let i = self.positions.len();
        self.positions.push(p);
        self.grid.entry(k).or_default().push(i);
        (i, true)
    }
}

/// A built T-bar tread, wheel or extended wheel.
#[derive(Debug, Clone)]
pub struct TbarGeometry {
    /// The parameters it was built from.
    pub params: TbarParams,
    /// Node positions (m).
    pub nodes: Vec<Vector3<f64>>,
    /// Node labels (see the module docs), same order.
    pub labels: Vec<String>,
    /// Whether each node is a rim support (pinned).
    pub supported: Vec<bool>,
    /// The treads' bars as [base, tip] (the rim body's bars are in `rim`).
    pub bars: Vec<[usize; 2]>,
    /// Strings as [parent, child].
    pub strings: Vec<[usize; 2]>,
    /// The tip node of every tread (wheel by wheel, tread by tread).
    pub tips: Vec<usize>,
    /// Lattice nodes per level of one tread, levels 0..=q: (l+1)².
    pub level_sizes: Vec<usize>,
    /// The rim body ([`RimMode::Body`]): hub nodes (appended after the treads' nodes) and
    /// bars; `None` with the rigid rim.
    pub rim: Option<RimBody>,
}

impl TbarGeometry {
    /// Validates `params` and builds the structure's geometry.
    ///
    /// ```
    /// use michell3d::MichellParams;
    /// use tbar_wheel::{Layout, TbarGeometry, TbarParams};
    /// use std::f64::consts::{FRAC_PI_6, PI};
    /// let m = MichellParams::cylindrical(1, 1.0, FRAC_PI_6, PI / 8.0, 0.25);
    /// let g = TbarGeometry::new(TbarParams::tread(m).with_layout(Layout::Wheel)).unwrap();
    /// assert_eq!((g.treads(), g.nodes.len(), g.bars.len(), g.strings.len()), (8, 32, 8, 32));
    /// ```
    pub fn new(params: TbarParams) -> Result<Self> {
        params.validate()?;
        let per_wheel = params.treads_per_wheel()?;
        let raw_nodes = params.copies() * per_wheel * (lattice_node_count(params.complexity()) + 2);
        if raw_nodes > MAX_NODES {
            return Err(crate::error::TbarError::TooLarge {
                what: "nodes before merging (copies × treads × (lattice nodes + 2))",
                size: raw_nodes,
                limit: MAX_NODES,
            });
        }
        let raw = raw_tread(&params);
        let phi = params.michell.phi;
        let offset = match params.layout {
            Layout::Extended { offset } => offset,
            _ => 0.0,
        };
        let mut g = Self {
            params,
            nodes: Vec::new(),
            labels: Vec::new(),
            supported: Vec::new(),
            bars: Vec::new(),
            strings: Vec::new(),
            tips: Vec::new(),
            level_sizes: (0..=params.complexity())
                .map(|l| (l + 1) * (l + 1))
                .collect(),
            rim: None,
        };
        for copy in 0..params.copies() {
            let mut merger = Merger::new(params.michell.r0);
            let first = g.nodes.len();
            let mut seen = std::collections::HashSet::new();
            for k in 0..per_wheel {
                let rot = Rotation3::from_axis_angle(&Vector3::x_axis(), 2.0 * k as f64 * phi);
                let shift = Vector3::new(copy as f64 * offset, 0.0, 0.0);
                let prefix = match (copy, k) {
                    (0, 0) => String::new(),
                    (0, k) => format!("t{k}."),
                    (_, k) => format!("e.t{k}."),
                };
                let map: Vec<usize> = raw
                    .nodes
                    .iter()
                    .map(|n| {
                        let p = rot * n.position + shift;
                        let (i, new) = merger.insert(p);
                        let i = first + i;
                        if new {
                            g.nodes.push(p);
                            g.labels.push(format!("{prefix}{}", n.label));
                            g.supported.push(n.support);
                        } else {
                            g.supported[i] |= n.support;
                        }
                        i
                    })
                    .collect();
                g.tips.push(map[0]);
                g.bars.push([map[raw.bar[0]], map[raw.bar[1]]]);
                for s in &raw.strings {
                    let (a, b) = (map[s[0]], map[s[1]]);
                    if seen.insert((a.min(b), a.max(b))) {
                        g.strings.push([a, b]);
                    }
                }
            }
        }
        if params.rim == RimMode::Body {
            attach_rim(&mut g);
        }
        Ok(g)
    }

    /// Every bar of the structure: the treads' bars, then the rim body's.
    pub fn all_bars(&self) -> Vec<[usize; 2]> {
        let mut out = self.bars.clone();
        if let Some(r) = &self.rim {
            out.extend_from_slice(&r.bars);
        }
        out
    }

    /// Number of treads (both wheels of an extended wheel).
    pub fn treads(&self) -> usize {
        self.tips.len()
    }

    /// The core structure: the treads' bars (base → tip) first, then the rim body's bars (if
    /// any), then strings (parent → child); with the rigid rim every rim node and bar base is
    /// pinned, with the rim body nothing is (a free body).
    pub fn structure(&self) -> Result<Structure> {
        let mut b = Structure::builder().nodes(self.nodes.iter().map(|p| [p.x, p.y, p.z]));
        for [s, e] in self.all_bars() {
            b = b.bar(Bar::new(s, e));
        }
        for &[s, e] in &self.strings {
            b = b.string(StringMember::new(s, e));
        }
        for (i, _) in self.supported.iter().enumerate().filter(|&(_, &s)| s) {
            b = b.support(Support::pinned(i));
        }
        Ok(b.build()?)
    }
}

/// Adds the hub nodes and the rim-body bars to `g`, turning its rim supports into rim points.
fn attach_rim(g: &mut TbarGeometry) {
    let rim_points: Vec<usize> = (0..g.nodes.len()).filter(|&i| g.supported[i]).collect();
    let r_q = g.params.rim_radius();
    let (x_min, x_max) = rim_points
        .iter()
        .fold((f64::INFINITY, -f64::INFINITY), |a, &i| {
            (a.0.min(g.nodes[i].x), a.1.max(g.nodes[i].x))
        });
    let hubs = [g.nodes.len(), g.nodes.len() + 1];
    for (label, x) in [("hub_left", x_min - r_q), ("hub_right", x_max + r_q)] {
        g.nodes.push(Vector3::new(x, 0.0, 0.0));
        g.labels.push(label.to_string());
        g.supported.push(false);
    }
    g.supported.iter_mut().for_each(|s| *s = false);
    let mut bars = vec![hubs];
    for &p in &rim_points {
        bars.extend(hubs.map(|h| [p, h]));
    }
    let spokes = bars.len() - 1;
    let ring = ring_bars(g, &rim_points);
    let n_ring = ring.len();
    bars.extend(ring);
    g.rim = Some(RimBody {
        hubs,
        bars,
        rim_points,
        spokes,
        ring: n_ring,
    });
}

/// Every point of an angle group joined to every point of the next group.
fn ring_bars(g: &TbarGeometry, points: &[usize]) -> Vec<[usize; 2]> {
    let phi = g.params.michell.phi;
    let turns = (2.0 * std::f64::consts::PI / phi).round() as i64;
    let mut groups: BTreeMap<i64, Vec<usize>> = BTreeMap::new();
    for &p in points {
        let n = g.nodes[p];
        let k = (n.z.atan2(n.y) / phi).round() as i64;
        let k = if g.params.layout == Layout::Tread {
            k
        } else {
            k.rem_euclid(turns)
        };
        groups.entry(k).or_default().push(p);
    }
    let list: Vec<&Vec<usize>> = groups.values().collect();
    let closed = g.params.layout != Layout::Tread && list.len() > 2;
    let links = if closed {
        list.len()
    } else {
        list.len().saturating_sub(1)
    };
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for i in 0..links {
        let (a, b) = (list[i], list[(i + 1) % list.len()]);
        for &p in a {
            for &q in b {
                if p != q && seen.insert((p.min(q), p.max(q))) {
                    out.push([p, q]);
                }
            }
        }
    }
    out
}
