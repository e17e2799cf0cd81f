//! A form-finding topology: nodes (optionally with positions, an initial guess), bars and
//! strings (node pairs, optional force density, group, target length and weight per length),
//! named groups of members sharing a force density, fixed nodes with their coordinates, and
//! point loads on nodes.
//!
//! Loads (point loads and members' self-weight) are taken by the force density method only,
//! and only with fixed nodes to carry them: the fixed nodes' reactions balance them. A
//! free-standing topology with loads is refused naming `loads` (or the first weighted member):
//! loads whose sum is not zero cannot be in equilibrium without supports, and self-balanced
//! loads would leave the form undetermined up to the affine null space of D.

use crate::error::{FormFindError, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One member of a topology (a bar or a string).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Member {
    /// Its two node indices (start, end).
    pub nodes: [usize; 2],
    /// Force density q (N/m, tension-positive: negative for a bar), if given here.
    pub force_density: Option<f64>,
    /// The group whose force density (and length) it takes.
    pub group: Option<String>,
    /// Target (rest) length in m, for dynamic relaxation.
    pub length: Option<f64>,
    /// Axial stiffness EA in N, for dynamic relaxation and synthesis (default: the settings').
    pub stiffness: Option<f64>,
    /// Weight per unit length (N/m, acting along −z), for the force density method's
    /// self-weight: half of w · L at each end node, L the found length.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weight: Option<f64>,
}

impl Member {
    /// A member between two nodes, nothing else given.
    pub fn new(start: usize, end: usize) -> Self {
        Member {
            nodes: [start, end],
            force_density: None,
            group: None,
            length: None,
            stiffness: None,
            weight: None,
        }
    }

    /// With a force density (N/m, tension-positive).
    pub fn force_density(mut self, q: f64) -> Self {
        self.force_density = Some(q);
        self
    }

    /// In a group.
    pub fn group(mut self, name: &str) -> Self {
        self.group = Some(name.to_string());
        self
    }

    /// With a rest length (m), for dynamic relaxation.
    ///
    /// ```
    /// let m = formfind::Member::new(0, 1).length(0.8);
    /// assert_eq!(m.length, Some(0.8));
    /// ```
    pub fn length(mut self, length: f64) -> Self {
        self.length = Some(length);
        self
    }

    /// With an axial stiffness EA (N), for dynamic relaxation and the synthesis.
    ///
    /// ```
    /// let m = formfind::Member::new(0, 1).stiffness(100.0);
    /// assert_eq!(m.stiffness, Some(100.0));
    /// ```
    pub fn stiffness(mut self, ea: f64) -> Self {
        self.stiffness = Some(ea);
        self
    }
}

/// A named group of members sharing a force density (and optionally a target length).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Group {
    /// Force density of every member of the group (N/m, tension-positive).
    pub force_density: Option<f64>,
    /// Target (rest) length of every member of the group (m).
    pub length: Option<f64>,
    /// Weight per unit length of every member of the group (N/m, along −z).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weight: Option<f64>,
}

/// A node held at given coordinates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FixedNode {
    /// The node index.
    pub node: usize,
    /// Its coordinates (m).
    pub position: [f64; 3],
}

/// A point load on a node (the force density method's external force p_i).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodeLoad {
    /// The node index.
    pub node: usize,
    /// The force (N).
    pub force: [f64; 3],
}

/// A clustered string of a topology: one continuous string through `nodes` (in order, at
/// least three) over frictionless pulleys or sliding joints, with one prescribed tension
/// `force` along every segment (the `cluster` module docs: how the methods find its form).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct ClusterString {
    /// The nodes it passes through, in order (at least three: two segments).
    pub nodes: Vec<usize>,
    /// Its prescribed tension t (N), the same in every segment.
    pub force: Option<f64>,
    /// Axial stiffness EA of the string (N), as a member's `stiffness`, for the rest-length
    /// synthesis (default: the synthesis' stiffness, or E · `area` of its `material`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Material name (one of the core's materials): carried into the written scene, and with
    /// `area` its stiffness EA = E A.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Cross-section area A (m²), with `material`: EA = E A.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area: Option<f64>,
}

impl ClusterString {
    /// A cluster through `nodes` with tension `force` (N), nothing else given.
    pub fn new<I: IntoIterator<Item = usize>>(nodes: I, force: f64) -> Self {
        ClusterString {
            nodes: nodes.into_iter().collect(),
            force: Some(force),
            ..ClusterString::default()
        }
    }

    /// The segments, as node pairs in order.
    pub fn segments(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        self.nodes.windows(2).map(|w| [w[0], w[1]])
    }

    /// Its axial stiffness EA (N): its own `stiffness`, else E · `area` of its `material`,
    /// else `default`.
    pub fn axial_stiffness(&self, default: f64) -> f64 {
        if let Some(ea) = self.stiffness {
            return ea;
        }
        let table = tensegrity_core::MaterialTable::builtin();
        match (&self.material, self.area) {
            (Some(m), Some(a)) => table.get(m).map_or(default, |m| m.youngs_modulus * a),
            _ => default,
        }
    }
}

/// A connectivity to find the form of. Members are numbered bars first, then strings, in
/// the order given; the segments of the clusters follow them where the methods need one
/// force density per two-node element (bars, strings, then every cluster's segments in
/// order: [`Topology::force_pairs`]).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Topology {
    /// Number of nodes.
    pub n_nodes: usize,
    /// Initial or reference positions, one per node, if known.
    pub nodes: Option<Vec<[f64; 3]>>,
    /// The bars (compression members).
    pub bars: Vec<Member>,
    /// The strings (tension members).
    pub strings: Vec<Member>,
    /// Named groups.
    pub groups: BTreeMap<String, Group>,
    /// Fixed nodes.
    pub fixed: Vec<FixedNode>,
    /// Point loads (several on one node add up); they need fixed nodes (module docs).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<NodeLoad>,
    /// Clustered strings with a prescribed tension (the `cluster` module docs).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub clusters: Vec<ClusterString>,
}

impl Topology {
    /// Bars then strings.
    pub fn members(&self) -> impl Iterator<Item = &Member> {
        self.bars.iter().chain(self.strings.iter())
    }

    /// The name of member k (`bars[i]` or `strings[j]`), as errors name it; past the
    /// members, the cluster whose segment k is in the order of [`Topology::force_pairs`]
    /// (`clusters[c]`).
    pub fn member_name(&self, k: usize) -> String {
        if k < self.bars.len() {
            format!("bars[{k}]")
        } else if k < self.n_members() {
            format!("strings[{}]", k - self.bars.len())
        } else {
            let mut s = k - self.n_members();
            for (c, cl) in self.clusters.iter().enumerate() {
                let n = cl.nodes.len().saturating_sub(1);
                if s < n {
                    return format!("clusters[{c}]");
                }
                s -= n;
            }
            format!("element {k}")
        }
    }

    /// The node pairs of the two-node elements the methods take one force density each:
    /// the members (bars then strings), then every cluster's segments in order.
    pub fn force_pairs(&self) -> Vec<[usize; 2]> {
        let mut p = self.member_nodes();
        for c in &self.clusters {
            p.extend(c.segments());
        }
        p
    }

    /// The number of cluster segments (over all clusters).
    pub fn n_segments(&self) -> usize {
        let n = |c: &ClusterString| c.nodes.len().saturating_sub(1);
        self.clusters.iter().map(n).sum()
    }

    /// The tension (N) of every cluster segment, in the order of [`Topology::force_pairs`]
    /// (0 where a cluster gives no `force`).
    pub fn segment_tensions(&self) -> Vec<f64> {
        let mut t = Vec::with_capacity(self.n_segments());
        for c in &self.clusters {
            let f = c.force.unwrap_or(0.0);
            t.extend(std::iter::repeat_n(f, c.nodes.len().saturating_sub(1)));
        }
        t
    }

    /// Checks indices, groups, fixed nodes and numbers; every failure names the item. The
    /// node count is checked against what the members and fixed nodes can reach (every node
    /// is on a member or fixed, so at most 2 · members + fixed) before anything per node is
    /// allocated.
    pub fn validate(&self) -> Result<()> {
        let bad = |item: String, reason: String| FormFindError::InvalidTopology { item, reason };
        if let Some(nodes) = &self.nodes {
            if nodes.len() != self.n_nodes {
                return Err(bad(
                    "nodes".into(),
                    format!("{} positions for {} nodes", nodes.len(), self.n_nodes),
                ));
            }
            for (i, p) in nodes.iter().enumerate() {
                if p.iter().any(|x| !x.is_finite()) {
                    return Err(bad(
                        format!("nodes[{i}]"),
                        "coordinates must be finite".into(),
                    ));
                }
            }
        }
        for (k, m) in self.members().enumerate() {
            let name = self.member_name(k);
            for &i in &m.nodes {
                if i >= self.n_nodes {
                    return Err(bad(
                        name.clone(),
                        format!(
                            "node {i} out of range (the topology has {} nodes)",
                            self.n_nodes
                        ),
                    ));
                }
            }
            if m.nodes[0] == m.nodes[1] {
                return Err(bad(name, format!("both ends on node {}", m.nodes[0])));
            }
            if let Some(q) = m.force_density {
                if !q.is_finite() {
                    return Err(bad(
                        format!("{name}.force_density"),
                        "must be finite".into(),
                    ));
                }
            }
            for (what, v) in [("length", m.length), ("stiffness", m.stiffness)] {
                if let Some(v) = v {
                    if !(v.is_finite() && v > 0.0) {
                        return Err(bad(
                            format!("{name}.{what}"),
                            format!("{v} must be finite and positive"),
                        ));
                    }
                }
            }
            if let Some(w) = m.weight {
                if !(w.is_finite() && w >= 0.0) {
                    return Err(bad(
                        format!("{name}.weight"),
                        format!("{w} must be finite and not negative (N/m)"),
                    ));
                }
            }
            if let Some(g) = &m.group {
                if !self.groups.contains_key(g) {
                    return Err(bad(
                        format!("{name}.group"),
                        format!("no group named \"{g}\""),
                    ));
                }
            }
        }
        if self.n_members() == 0 && self.clusters.is_empty() {
            return Err(bad("bars".into(), "the topology has no members".into()));
        }
        let (members, fixed) = (self.n_members(), self.fixed.len());
        let reach = self.reach();
        if self.n_nodes > reach {
            let reason = too_many_nodes(self.n_nodes, members, fixed);
            let reason = if self.clusters.is_empty() {
                reason
            } else {
                format!(
                    "{reason} (plus {} cluster node(s))",
                    reach - 2 * members - fixed
                )
            };
            return Err(bad("n_nodes".into(), reason));
        }
        self.validate_clusters()?;
        let mut seen = std::collections::HashMap::new();
        let mut touched = vec![false; self.n_nodes];
        for (k, m) in self.members().enumerate() {
            let key = (m.nodes[0].min(m.nodes[1]), m.nodes[0].max(m.nodes[1]));
            if let Some(other) = seen.insert(key, k) {
                return Err(bad(
                    self.member_name(k),
                    format!(
                        "joins nodes {} and {}, as {} does",
                        key.0,
                        key.1,
                        self.member_name(other)
                    ),
                ));
            }
            touched[key.0] = true;
            touched[key.1] = true;
        }
        for f in &self.fixed {
            if let Some(t) = touched.get_mut(f.node) {
                *t = true; // a held node may stand alone (an anchor of nothing)
            }
        }
        let mut segments: std::collections::HashMap<(usize, usize), usize> = Default::default();
        for (c, cl) in self.clusters.iter().enumerate() {
            for [a, b] in cl.segments() {
                let key = (a.min(b), a.max(b));
                let other = match (seen.get(&key), segments.get(&key)) {
                    (Some(&k), _) => Some(self.member_name(k)),
                    (None, Some(&d)) if d == c => Some("another of its segments".to_string()),
                    (None, Some(&d)) => Some(format!("a segment of clusters[{d}]")),
                    (None, None) => None,
                };
                if let Some(other) = other {
                    return Err(bad(
                        format!("clusters[{c}]"),
                        format!(
                            "its segment joins nodes {} and {}, as {other} does",
                            key.0, key.1
                        ),
                    ));
                }
                segments.insert(key, c);
                touched[a] = true;
                touched[b] = true;
            }
        }
        if let Some(i) = touched.iter().position(|t| !t) {
            return Err(bad(
                format!("node {i}"),
                "no member ends at it (and it is not fixed)".into(),
            ));
        }
        for (name, g) in &self.groups {
            if let Some(q) = g.force_density {
                if !q.is_finite() {
                    return Err(bad(
                        format!("groups.{name}.force_density"),
                        format!("{q} must be finite"),
                    ));
                }
            }
            if let Some(l) = g.length {
                if !(l.is_finite() && l > 0.0) {
                    return Err(bad(
                        format!("groups.{name}.length"),
                        format!("{l} must be finite and positive"),
                    ));
                }
            }
            if let Some(w) = g.weight {
                if !(w.is_finite() && w >= 0.0) {
                    return Err(bad(
                        format!("groups.{name}.weight"),
                        format!("{w} must be finite and not negative (N/m)"),
                    ));
                }
            }
        }
        let mut fixed_seen = std::collections::HashMap::new();
        for (i, f) in self.fixed.iter().enumerate() {
            if f.node < self.n_nodes {
                if let Some(j) = fixed_seen.insert(f.node, i) {
                    return Err(bad(
                        format!("fixed[{i}]"),
                        format!("node {} is already fixed by fixed[{j}]", f.node),
                    ));
                }
            }
        }
        for (i, f) in self.fixed.iter().enumerate() {
            if f.node >= self.n_nodes {
                return Err(bad(
                    format!("fixed[{i}]"),
                    format!("node {} out of range", f.node),
                ));
            }
            if f.position.iter().any(|x| !x.is_finite()) {
                return Err(bad(format!("fixed[{i}].position"), "must be finite".into()));
            }
        }
        self.validate_loads()
    }

    /// What the members, fixed nodes and clusters reach: 2 · members + fixed + the nodes the
    /// clusters list (every node is on one of them).
    fn reach(&self) -> usize {
        let cluster_nodes = self.clusters.iter().map(|c| c.nodes.len());
        let listed = cluster_nodes.fold(0usize, usize::saturating_add);
        let members = self.n_members().saturating_mul(2);
        members
            .saturating_add(self.fixed.len())
            .saturating_add(listed)
    }

    /// Each cluster: at least three nodes, in range, no zero segment (two equal nodes in a
    /// row), a positive finite tension `force`, a positive finite `stiffness` or `area`, a known
    /// `material`, `area` only with a `material` and not with a `stiffness`.
    fn validate_clusters(&self) -> Result<()> {
        let bad = |item: String, reason: String| FormFindError::InvalidTopology { item, reason };
        for (c, cl) in self.clusters.iter().enumerate() {
            let name = format!("clusters[{c}]");
            if cl.nodes.len() < 3 {
                return Err(bad(
                    name,
                    format!(
                        "passes through {} node(s): a cluster runs through at least three (two \
                         segments); give a two-node string as [[strings]]",
                        cl.nodes.len()
                    ),
                ));
            }
            if let Some(&i) = cl.nodes.iter().find(|&&i| i >= self.n_nodes) {
                return Err(bad(
                    name,
                    format!(
                        "node {i} out of range (the topology has {} nodes)",
                        self.n_nodes
                    ),
                ));
            }
            if let Some((s, [a, _])) = cl.segments().enumerate().find(|(_, [a, b])| a == b) {
                return Err(bad(
                    name,
                    format!("segment {s} has both ends on node {a} (zero length)"),
                ));
            }
            match cl.force {
                None => {
                    return Err(bad(
                        format!("{name}.force"),
                        "no tension given: a cluster's one tension t (N) is prescribed, the \
                         form is found for it"
                            .into(),
                    ))
                }
                Some(t) if !(t.is_finite() && t > 0.0) => {
                    return Err(bad(
                        format!("{name}.force"),
                        format!("{t} must be finite and positive (a string's tension, N)"),
                    ))
                }
                _ => {}
            }
            for (what, v) in [("stiffness", cl.stiffness), ("area", cl.area)] {
                if let Some(v) = v.filter(|v| !(v.is_finite() && *v > 0.0)) {
                    return Err(bad(
                        format!("{name}.{what}"),
                        format!("{v} must be finite and positive"),
                    ));
                }
            }
            let table = tensegrity_core::MaterialTable::builtin();
            if let Some(m) = cl.material.as_deref().filter(|m| table.get(m).is_none()) {
                return Err(bad(
                    format!("{name}.material"),
                    format!(
                        "unknown material \"{m}\" (known: {})",
                        table.names().join(", ")
                    ),
                ));
            }
            if cl.area.is_some() && (cl.material.is_none() || cl.stiffness.is_some()) {
                return Err(bad(
                    format!("{name}.area"),
                    "an area gives the stiffness E A with a `material`, and only without a \
                     `stiffness`: give a material and no stiffness, or no area"
                        .into(),
                ));
            }
        }
        Ok(())
    }

    /// Loads on existing nodes, finite, and only with fixed nodes to carry them (module docs).
    fn validate_loads(&self) -> Result<()> {
        let bad = |item: String, reason: String| FormFindError::InvalidTopology { item, reason };
        for (i, l) in self.loads.iter().enumerate() {
            if l.node >= self.n_nodes {
                return Err(bad(
                    format!("loads[{i}]"),
                    format!(
                        "node {} out of range (the topology has {} nodes)",
                        l.node, self.n_nodes
                    ),
                ));
            }
            if l.force.iter().any(|x| !x.is_finite()) {
                return Err(bad(
                    format!("loads[{i}].force"),
                    format!("{:?} must be finite", l.force),
                ));
            }
        }
        if !self.fixed.is_empty() {
            return Ok(());
        }
        let weighted = self
            .given_weights()
            .iter()
            .position(|w| w.is_some_and(|w| w > 0.0));
        if !self.loads.is_empty() {
            let mut sum = [0.0; 3];
            for l in &self.loads {
                for (s, f) in sum.iter_mut().zip(l.force) {
                    *s += f;
                }
            }
            let balance = if sum.iter().any(|&s| s != 0.0) {
                format!(
                    "they sum to {sum:?} N, which nothing balances without supports (the \
                     equilibrium of the whole needs Σ p = 0)"
                )
            } else {
                "even self-balanced loads leave a free-standing form undetermined (any \
                 affine image of the null space of D may be added)"
                    .to_string()
            };
            return Err(bad(
                "loads".into(),
                format!(
                    "{} load(s) on a free-standing topology (no [[fixed]] nodes): {balance}; \
                     hold the nodes that carry them (`fixed`, the supports)",
                    self.loads.len()
                ),
            ));
        }
        if let Some(k) = weighted {
            return Err(bad(
                format!("{}.weight", self.member_name(k)),
                "self-weight on a free-standing topology (no [[fixed]] nodes): nothing \
                 balances it; hold the nodes that carry it (`fixed`, the supports)"
                    .into(),
            ));
        }
        Ok(())
    }
}

/// Why `n_nodes` nodes are too many for `members` members and `fixed` fixed nodes.
pub fn too_many_nodes(n_nodes: usize, members: usize, fixed: usize) -> String {
    format!(
        "{n_nodes} nodes, but every node must be on a member or fixed, and {members} \
         member(s) and {fixed} fixed node(s) reach at most {}",
        members.saturating_mul(2).saturating_add(fixed)
    )
}

/// Whether force density `q` has the sign of its member's kind (bar < 0 < string).
pub(crate) fn member_kind_ok(is_bar: bool, q: f64) -> bool {
    if is_bar {
        q < 0.0
    } else {
        q > 0.0
    }
}

impl Topology {
    /// Number of members (bars then strings).
    pub fn n_members(&self) -> usize {
        self.bars.len() + self.strings.len()
    }

    /// The node pair of every member, bars then strings.
    pub fn member_nodes(&self) -> Vec<[usize; 2]> {
        self.members().map(|m| m.nodes).collect()
    }

    /// Whether member k (bars then strings) is a bar.
    pub fn is_bar(&self, k: usize) -> bool {
        k < self.bars.len()
    }

    /// The force density of every member, bars then strings: the member's own value, else
    /// its group's. `None` where neither gives one.
    pub fn given_force_densities(&self) -> Vec<Option<f64>> {
        self.members()
            .map(|m| {
                m.force_density.or_else(|| {
                    m.group
                        .as_ref()
                        .and_then(|g| self.groups.get(g))
                        .and_then(|g| g.force_density)
                })
            })
            .collect()
    }

    /// The force densities of the force density method: every member's (or its group's),
    /// bars negative and strings positive; the first member without one, or with the wrong
    /// sign, is named.
    pub fn force_densities(&self) -> Result<Vec<f64>> {
        self.given_force_densities()
            .into_iter()
            .enumerate()
            .map(|(k, q)| {
                let name = self.member_name(k);
                let q = q.ok_or_else(|| FormFindError::InvalidTopology {
                    item: format!("{name}.force_density"),
                    reason: "no force density on the member or its group (give one, or use \
                             the adaptive method, which finds them)"
                        .into(),
                })?;
                if !member_kind_ok(self.is_bar(k), q) {
                    let sign = if self.is_bar(k) {
                        "negative (a bar is compressed; q is tension-positive)"
                    } else {
                        "positive (a string is in tension)"
                    };
                    return Err(FormFindError::InvalidTopology {
                        item: format!("{name}.force_density"),
                        reason: format!("{q} must be {sign}"),
                    });
                }
                Ok(q)
            })
            .collect()
    }

    /// The weight per unit length of every member (N/m): its own, else its group's.
    pub fn given_weights(&self) -> Vec<Option<f64>> {
        self.members()
            .map(|m| {
                m.weight.or_else(|| {
                    m.group
                        .as_ref()
                        .and_then(|g| self.groups.get(g))
                        .and_then(|g| g.weight)
                })
            })
            .collect()
    }

    /// Whether the topology carries loads: a point load, or a member with a weight.
    pub fn is_loaded(&self) -> bool {
        !self.loads.is_empty() || self.given_weights().iter().any(Option::is_some)
    }

    /// The target (rest) length of every member: its own, else its group's.
    pub fn given_lengths(&self) -> Vec<Option<f64>> {
        self.members()
            .map(|m| {
                m.length.or_else(|| {
                    m.group
                        .as_ref()
                        .and_then(|g| self.groups.get(g))
                        .and_then(|g| g.length)
                })
            })
            .collect()
    }

    /// The initial nodes as vectors, if given.
    pub fn initial_nodes(&self) -> Option<Vec<nalgebra::Vector3<f64>>> {
        self.nodes
            .as_ref()
            .map(|ns| ns.iter().map(|p| nalgebra::Vector3::from(*p)).collect())
    }

    /// The same topology with `lengths` (bars then strings) as every member's target length
    /// and `stiffness` (bars then strings, EA in N) as its axial stiffness, and no force
    /// densities (dynamic relaxation refuses them): the input of dynamic relaxation that
    /// reproduces a synthesized form ([`crate::rest_lengths`]).
    pub fn with_lengths(&self, lengths: &[f64], stiffness: &[f64]) -> Topology {
        let mut t = self.clone();
        for g in t.groups.values_mut() {
            g.force_density = None;
        }
        for (k, m) in t.bars.iter_mut().chain(t.strings.iter_mut()).enumerate() {
            m.force_density = None;
            if let Some(&l) = lengths.get(k) {
                m.length = Some(l);
            }
            if let Some(&e) = stiffness.get(k) {
                m.stiffness = Some(e);
            }
        }
        t
    }
}
