//! TOML topology files of form-finding: a connectivity (bars, strings, optional node
//! positions as the initial guess, groups sharing a force density, fixed nodes, point loads
//! and members' weights for the force density method) read into a [`formfind::Topology`],
//! and written back ([`to_toml`]).
//!
//! ```toml
//! n_nodes = 6                    # optional: given by `nodes`, else the largest index + 1
//! nodes = [[1.0, 0.0, 0.0], …]   # optional: initial or reference positions (m), one per node
//! [groups.vertical]
//! force_density = 1.0            # N/m, tension-positive (optional)
//! length = 1.2                   # m, target length (optional)
//! weight = 0.5                   # N/m, weight per length along −z (optional; fdm only)
//! [[bars]]
//! nodes = [0, 3]                 # exactly two node indices (0-based)
//! force_density = -1.0           # N/m (a bar's is negative), optional
//! group = "bars"                 # optional: takes the group's force density and length
//! length = 1.5                   # m, optional target (rest) length
//! stiffness = 1e5                # N, optional axial stiffness EA
//! weight = 0.5                   # N/m, optional weight per length along −z (fdm only)
//! [[strings]]
//! nodes = [0, 1]                 # same keys as a bar; a string's force density is positive
//! [[fixed]]
//! node = 0
//! position = [0.0, 0.0, 0.0]     # m
//! [[loads]]                      # point loads (fdm only, with fixed nodes); one node may
//! node = 4                       # carry several, they add up
//! force = [0.0, 0.0, -1.0]       # N
//! [[clusters]]                   # one string through several nodes over frictionless
//! nodes = [0, 4, 1]              # pulleys, in order (at least three nodes)
//! force = 10.0                   # N: its one tension, the same on every segment
//! stiffness = 1e5                # N, optional axial stiffness EA (rest-length synthesis)
//! material = "steel"             # optional (the written scene's); with `area` (m²) EA = E A
//! [design]                       # optional: an inverse form-finding problem, read by
//!                                # `tensegrity design` (the `design` module); ignored here
//! ```
//!
//! A cluster gives its tension `force`, never a force density (one q along segments of
//! different lengths would give different tensions, which a frictionless string cannot
//! carry: `force_density` is refused with that reason), and no `friction` (form-finding is
//! frictionless: refused by name).
//!
//! Members are numbered bars first, then strings, in file order (the order of the force
//! densities a form-finding reports). The reader is strict: a node count beyond what the
//! members and fixed nodes can reach (2 · members + fixed: refused before anything per node
//! is allocated, so `n_nodes = 1000000000000` is an error, not an abort), unknown keys, a member without
//! exactly two indices, an index past the last node, a member joining a node to itself, two
//! members on the same pair of nodes, an unknown or unused group, a force density of the
//! wrong sign (a bar's q < 0, a string's q > 0, tension-positive) or given both by a member
//! and its group, a node on no member, a node fixed twice, a load on a node past the last, a
//! negative weight, loads or weights without fixed nodes and any non-finite number are
//! refused; every error names the file, the line and the item (`bars[3]`, `strings[0].group`,
//! `groups.top`, `fixed[1]`, `loads[0].force`).
//!
//! ```
//! use tensegrity_io::topology::{from_str_named, to_toml};
//! let text = "[[bars]]\nnodes = [0, 2]\n[[bars]]\nnodes = [1, 3]\n\
//!             [[strings]]\nnodes = [0, 1]\n[[strings]]\nnodes = [1, 2]\n\
//!             [[strings]]\nnodes = [2, 3]\n[[strings]]\nnodes = [3, 0]\n";
//! let t = from_str_named(text, "x-module.toml")?;
//! assert_eq!((t.n_nodes, t.bars.len(), t.strings.len()), (4, 2, 4));
//! assert_eq!(from_str_named(&to_toml(&t), "again")?, t);
//! let bad = text.replace("nodes = [3, 0]", "nodes = [3, 0, 1]");
//! let e = from_str_named(&bad, "x-module.toml").unwrap_err().to_string();
//! assert!(e.contains("x-module.toml") && e.contains("line 11") && e.contains("strings[3]"), "{e}");
//! # Ok::<(), tensegrity_io::IoError>(())
//! ```

use crate::error::{IoError, Result};
use crate::scene::line_column;
use formfind::{ClusterString, FixedNode, FormFindError, Group, Member, NodeLoad, Topology};
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use toml::Spanned;

/// The raw contents of a topology file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TopologyFile {
    /// Number of nodes (optional: from `nodes`, else the largest index + 1).
    pub n_nodes: Option<Spanned<usize>>,
    /// Initial or reference positions (m), one per node.
    pub nodes: Option<Spanned<Vec<Spanned<[f64; 3]>>>>,
    /// Bars.
    #[serde(default)]
    pub bars: Vec<Spanned<MemberSpec>>,
    /// Strings.
    #[serde(default)]
    pub strings: Vec<Spanned<MemberSpec>>,
    /// Groups by name.
    #[serde(default)]
    pub groups: BTreeMap<String, Spanned<GroupSpec>>,
    /// Fixed nodes.
    #[serde(default)]
    pub fixed: Vec<Spanned<FixedSpec>>,
    /// Point loads.
    #[serde(default)]
    pub loads: Vec<Spanned<LoadSpec>>,
    /// Clustered strings.
    #[serde(default)]
    pub clusters: Vec<Spanned<ClusterSpec>>,
    /// A design problem on the topology (read by [`crate::design`]; form-finding starts from
    /// the force densities given and ignores it).
    #[serde(default)]
    pub design: Option<serde::de::IgnoredAny>,
}

/// A `[[clusters]]` entry: one string through several nodes with one prescribed tension.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClusterSpec {
    /// The nodes it passes through, in order (at least three).
    pub nodes: Vec<usize>,
    /// Its prescribed tension t (N), the same on every segment.
    pub force: Option<f64>,
    /// Refused with the reason (one force density along the segments is not one tension).
    pub force_density: Option<f64>,
    /// Axial stiffness EA (N), as a member's.
    pub stiffness: Option<f64>,
    /// Material name (a built-in material).
    pub material: Option<String>,
    /// Cross-section area (m²), with `material`: EA = E A.
    pub area: Option<f64>,
    /// Refused with the reason (form-finding is frictionless).
    pub friction: Option<Vec<f64>>,
}

/// A `[[bars]]` or `[[strings]]` entry.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemberSpec {
    /// Start and end node (exactly two).
    pub nodes: Vec<usize>,
    /// Force density (N/m, tension-positive).
    pub force_density: Option<f64>,
    /// Group name.
    pub group: Option<String>,
    /// Target length (m).
    pub length: Option<f64>,
    /// Axial stiffness EA (N).
    pub stiffness: Option<f64>,
    /// Weight per length (N/m, along −z).
    pub weight: Option<f64>,
}

/// A `[groups.NAME]` table.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSpec {
    /// Force density of every member of the group (N/m, tension-positive).
    pub force_density: Option<f64>,
    /// Target length of every member of the group (m).
    pub length: Option<f64>,
    /// Weight per length of every member of the group (N/m, along −z).
    pub weight: Option<f64>,
}

/// A `[[fixed]]` entry.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixedSpec {
    /// The node.
    pub node: usize,
    /// Its coordinates (m).
    pub position: [f64; 3],
}

/// A `[[loads]]` entry.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// The loaded node.
    pub node: usize,
    /// The force (N).
    pub force: [f64; 3],
}

/// Reads a topology file (at most [`crate::read::MAX_SCENE_BYTES`]); errors name the file,
/// the line and the item.
pub fn from_path(path: &Path) -> Result<Topology> {
    let text = crate::read::read_text(path, crate::read::MAX_SCENE_BYTES, "a topology file")?;
    from_str_named(&text, &path.display().to_string())
}

/// Parses and checks topology text; `name` labels the errors (module docs).
pub fn from_str_named(text: &str, name: &str) -> Result<Topology> {
    let file: TopologyFile = parse(text, name)?;
    file.topology()
        .map_err(|(at, source)| IoError::InvalidTopology {
            file: name.to_string(),
            line: at.map(|start| line_column(text, start).0),
            source: Box::new(source),
        })
}

/// The TOML `text` (named `name`) deserialised, a parse error naming the file, the line and
/// the column (the design files' reader shares it).
pub(crate) fn parse<T: serde::de::DeserializeOwned>(text: &str, name: &str) -> Result<T> {
    toml::from_str(text).map_err(|e| {
        let (line, column) = line_column(text, e.span().map_or(0, |s| s.start));
        IoError::Parse {
            file: name.to_string(),
            line,
            column,
            message: e.message().trim_end().to_string(),
        }
    })
}

/// A failed check: the byte offset of the item (where known) and the error naming it.
type Failed = (Option<usize>, FormFindError);

fn bad(at: Option<usize>, item: impl Into<String>, reason: impl Into<String>) -> Failed {
    let (item, reason) = (item.into(), reason.into());
    (at, FormFindError::InvalidTopology { item, reason })
}

fn finite(at: usize, item: String, x: Option<f64>, positive: bool) -> Result<(), Failed> {
    match x {
        Some(v) if !v.is_finite() => Err(bad(Some(at), item, format!("{v} must be finite"))),
        Some(v) if positive && v <= 0.0 => {
            Err(bad(Some(at), item, format!("{v} must be positive")))
        }
        _ => Ok(()),
    }
}

impl TopologyFile {
    /// The members with their names (`bars[i]`, `strings[j]`) and whether each is a bar.
    fn members(&self) -> impl Iterator<Item = (String, bool, &Spanned<MemberSpec>)> {
        let bars = self.bars.iter().enumerate();
        let strings = self.strings.iter().enumerate();
        bars.map(|(i, m)| (format!("bars[{i}]"), true, m))
            .chain(strings.map(|(i, m)| (format!("strings[{i}]"), false, m)))
    }

    /// The checked topology, or the offset of the offending item and its error.
    pub fn topology(&self) -> Result<Topology, Failed> {
        self.check_groups()?;
        let n_nodes = self.node_count()?;
        let mut members = (Vec::new(), Vec::new());
        let mut pairs: HashMap<[usize; 2], String> = HashMap::new();
        let mut used = vec![false; n_nodes];
        for (name, is_bar, spanned) in self.members() {
            let member = self.member(&name, is_bar, spanned, n_nodes)?;
            let [a, b] = member.nodes;
            (used[a], used[b]) = (true, true);
            if let Some(first) = pairs.insert([a.min(b), a.max(b)], name.clone()) {
                let reason =
                    format!("joins nodes {a} and {b}, as {first} does (a member listed twice)");
                return Err(bad(Some(spanned.span().start), name, reason));
            }
            if is_bar {
                &mut members.0
            } else {
                &mut members.1
            }
            .push(member);
        }
        if let Some(unused) = self.groups.iter().find(|(g, _)| {
            !self
                .members()
                .any(|(_, _, m)| m.get_ref().group.as_deref() == Some(g.as_str()))
        }) {
            let reason = "no member is in this group";
            return Err(bad(
                Some(unused.1.span().start),
                format!("groups.{}", unused.0),
                reason,
            ));
        }
        let clusters = self.clusters(n_nodes)?;
        for c in &clusters {
            for &i in &c.nodes {
                used[i] = true;
            }
        }
        if let Some(node) = used.iter().position(|u| !u) {
            return Err(self.unused_node(node, n_nodes));
        }
        let fixed = self.fixed_nodes(n_nodes)?;
        let nodes = self
            .nodes
            .as_ref()
            .map(|v| v.get_ref().iter().map(|p| *p.get_ref()).collect());
        let groups = self.groups.iter().map(|(name, g)| {
            let g = g.get_ref();
            let group = Group {
                force_density: g.force_density,
                length: g.length,
                weight: g.weight,
            };
            (name.clone(), group)
        });
        let topology = Topology {
            n_nodes,
            nodes,
            bars: members.0,
            strings: members.1,
            groups: groups.collect(),
            fixed,
            loads: self.loads(n_nodes)?,
            clusters,
        };
        topology.validate().map_err(|e| (self.offset_of(&e), e))?;
        Ok(topology)
    }

    /// Finite force densities and positive lengths in every group.
    fn check_groups(&self) -> Result<(), Failed> {
        for (name, g) in &self.groups {
            let (at, spec) = (g.span().start, g.get_ref());
            finite(
                at,
                format!("groups.{name}.force_density"),
                spec.force_density,
                false,
            )?;
            finite(at, format!("groups.{name}.length"), spec.length, true)?;
            finite(at, format!("groups.{name}.weight"), spec.weight, false)?;
        }
        Ok(())
    }

    /// The number of nodes: `n_nodes`, the positions given, or the largest index + 1; at
    /// most what the members and fixed nodes reach (every node is on a member or fixed),
    /// checked before anything per node is allocated.
    fn node_count(&self) -> Result<usize, Failed> {
        let n = self.given_node_count()?;
        let (members, fixed) = (self.bars.len() + self.strings.len(), self.fixed.len());
        let listed = (self.clusters.iter().map(|c| c.get_ref().nodes.len()))
            .fold(0usize, usize::saturating_add);
        let reach = members.saturating_mul(2).saturating_add(fixed);
        if n > reach.saturating_add(listed) {
            let (at, item) = match (&self.n_nodes, &self.nodes) {
                (Some(given), _) => (Some(given.span().start), "n_nodes".to_string()),
                (None, Some(nodes)) => (Some(nodes.span().start), "nodes".to_string()),
                (None, None) => self.largest_index_cluster(n - 1),
            };
            let mut reason = formfind::too_many_nodes(n, members, fixed);
            if listed > 0 {
                reason.push_str(&format!(" (plus the {listed} node(s) the clusters list)"));
            }
            if item.starts_with("clusters") {
                reason = format!(
                    "node {} makes the topology {n} nodes (the largest index + 1): {reason}; \
                     fix the index or give `n_nodes`",
                    n - 1
                );
            }
            return Err(bad(at, item, reason));
        }
        Ok(n)
    }

    /// Where the inferred node count comes from when a cluster lists the largest index
    /// `node` (its line and name), else `nodes` without a line.
    fn largest_index_cluster(&self, node: usize) -> (Option<usize>, String) {
        let cluster =
            (self.clusters.iter().enumerate()).find(|(_, c)| c.get_ref().nodes.contains(&node));
        match cluster {
            Some((c, spanned)) => (Some(spanned.span().start), format!("clusters[{c}]")),
            None => (None, "nodes".to_string()),
        }
    }

    /// The number of nodes as given: `n_nodes`, the positions, or the largest index + 1.
    fn given_node_count(&self) -> Result<usize, Failed> {
        let largest = self
            .members()
            .flat_map(|(_, _, m)| m.get_ref().nodes.iter().copied())
            .chain(self.fixed.iter().map(|f| f.get_ref().node))
            .chain(
                self.clusters
                    .iter()
                    .flat_map(|c| c.get_ref().nodes.iter().copied()),
            )
            .max();
        let given = self
            .nodes
            .as_ref()
            .map(|n| (n.get_ref().len(), n.span().start));
        match (&self.n_nodes, given) {
            (Some(n), Some((len, at))) if *n.get_ref() != len => Err(bad(
                Some(at),
                "nodes",
                format!("{len} positions for n_nodes = {}", n.get_ref()),
            )),
            (Some(n), _) => Ok(*n.get_ref()),
            (None, Some((len, _))) => Ok(len),
            (None, None) => match largest {
                Some(i) => Ok(i.saturating_add(1)),
                None => Err(bad(None, "bars", "the topology has no member")),
            },
        }
    }

    /// One member, checked: two indices in range, finite numbers, a known group, the sign of
    /// its force density.
    fn member(
        &self,
        name: &str,
        is_bar: bool,
        spanned: &Spanned<MemberSpec>,
        n_nodes: usize,
    ) -> Result<Member, Failed> {
        let (at, m) = (spanned.span().start, spanned.get_ref());
        let nodes: [usize; 2] = m.nodes.as_slice().try_into().map_err(|_| {
            let reason = format!(
                "`nodes` must hold exactly two node indices, got {} ({:?})",
                m.nodes.len(),
                m.nodes
            );
            bad(Some(at), name, reason)
        })?;
        if let Some(&i) = nodes.iter().find(|&&i| i >= n_nodes) {
            let reason = format!("node {i} out of range (the topology has {n_nodes} nodes)");
            return Err(bad(Some(at), name, reason));
        }
        if nodes[0] == nodes[1] {
            return Err(bad(
                Some(at),
                name,
                format!("both ends on node {}", nodes[0]),
            ));
        }
        finite(at, format!("{name}.force_density"), m.force_density, false)?;
        finite(at, format!("{name}.length"), m.length, true)?;
        finite(at, format!("{name}.stiffness"), m.stiffness, true)?;
        finite(at, format!("{name}.weight"), m.weight, false)?;
        let group_q = match &m.group {
            Some(g) => match self.groups.get(g) {
                Some(spec) => spec.get_ref().force_density,
                None => {
                    let reason = format!("no group named \"{g}\" (no [groups.{g}] table)");
                    return Err(bad(Some(at), format!("{name}.group"), reason));
                }
            },
            None => None,
        };
        if let (Some(q), Some(g)) = (m.force_density.and(group_q), &m.group) {
            let reason =
                format!("{q}: the group \"{g}\" gives the force density already; give it once");
            return Err(bad(Some(at), format!("{name}.force_density"), reason));
        }
        if let Some(q) = m.force_density.or(group_q) {
            let (kind, sign) = if is_bar {
                ("bar", "negative")
            } else {
                ("string", "positive")
            };
            if (is_bar && q >= 0.0) || (!is_bar && q <= 0.0) {
                let from = m.group.as_ref().filter(|_| m.force_density.is_none());
                let item = from.map_or(format!("{name}.force_density"), |g| {
                    format!("groups.{g}.force_density")
                });
                let reason = format!(
                    "{q}: a {kind}'s force density (tension-positive) must be {sign} ({name})"
                );
                let at = from.map_or(at, |g| self.groups[g].span().start);
                return Err(bad(Some(at), item, reason));
            }
        }
        Ok(Member {
            nodes,
            force_density: m.force_density,
            group: m.group.clone(),
            length: m.length,
            stiffness: m.stiffness,
            weight: m.weight,
        })
    }

    /// The clusters, checked: at least three nodes in range, a finite positive `force`, no
    /// force density and no friction (each refused with the reason), finite positive
    /// `stiffness` and `area` (the rest: [`Topology::validate`]).
    fn clusters(&self, n_nodes: usize) -> Result<Vec<ClusterString>, Failed> {
        let mut out = Vec::with_capacity(self.clusters.len());
        for (c, spanned) in self.clusters.iter().enumerate() {
            let (at, spec) = (spanned.span().start, spanned.get_ref());
            let name = format!("clusters[{c}]");
            if spec.nodes.len() < 3 {
                let reason = format!(
                    "`nodes` passes through {} node(s) ({:?}): a cluster runs through at least \
                     three (two segments); give a two-node string as [[strings]]",
                    spec.nodes.len(),
                    spec.nodes
                );
                return Err(bad(Some(at), name, reason));
            }
            if let Some(&i) = spec.nodes.iter().find(|&&i| i >= n_nodes) {
                let reason = format!("node {i} out of range (the topology has {n_nodes} nodes)");
                return Err(bad(Some(at), name, reason));
            }
            if let Some(s) = spec.nodes.windows(2).position(|w| w[0] == w[1]) {
                let a = spec.nodes[s];
                let reason = format!("segment {s} has both ends on node {a} (zero length)");
                return Err(bad(Some(at), name, reason));
            }
            if let Some(q) = spec.force_density {
                let reason = format!(
                    "{q}: a cluster takes its one tension `force` (N), not a force density: one \
                     q along segments of different lengths l_i would give different tensions \
                     q l_i, which a string over frictionless pulleys cannot carry (the segments' \
                     force densities t/l_i are found with the form)"
                );
                return Err(bad(Some(at), format!("{name}.force_density"), reason));
            }
            if spec.friction.is_some() {
                let reason = "form-finding takes clusters frictionless (one tension along the \
                              whole cluster): remove `friction` (a scene's cluster may have it)";
                return Err(bad(Some(at), format!("{name}.friction"), reason));
            }
            finite(at, format!("{name}.force"), spec.force, true)?;
            finite(at, format!("{name}.stiffness"), spec.stiffness, true)?;
            finite(at, format!("{name}.area"), spec.area, true)?;
            out.push(ClusterString {
                nodes: spec.nodes.clone(),
                force: spec.force,
                stiffness: spec.stiffness,
                material: spec.material.clone(),
                area: spec.area,
            });
        }
        Ok(out)
    }

    /// The fixed nodes, checked: in range, finite, each node once.
    fn fixed_nodes(&self, n_nodes: usize) -> Result<Vec<FixedNode>, Failed> {
        let mut seen: HashMap<usize, usize> = HashMap::new();
        let mut fixed = Vec::with_capacity(self.fixed.len());
        for (i, f) in self.fixed.iter().enumerate() {
            let (at, spec) = (Some(f.span().start), f.get_ref());
            let item = format!("fixed[{i}]");
            if spec.node >= n_nodes {
                let reason = format!(
                    "node {} out of range (the topology has {n_nodes} nodes)",
                    spec.node
                );
                return Err(bad(at, item, reason));
            }
            if spec.position.iter().any(|x| !x.is_finite()) {
                let reason = format!("{:?} must be finite", spec.position);
                return Err(bad(at, format!("{item}.position"), reason));
            }
            if let Some(first) = seen.insert(spec.node, i) {
                let reason = format!("node {} is fixed already by fixed[{first}]", spec.node);
                return Err(bad(at, item, reason));
            }
            fixed.push(FixedNode {
                node: spec.node,
                position: spec.position,
            });
        }
        Ok(fixed)
    }

    /// The point loads, checked: in range, finite.
    fn loads(&self, n_nodes: usize) -> Result<Vec<NodeLoad>, Failed> {
        let mut loads = Vec::with_capacity(self.loads.len());
        for (i, l) in self.loads.iter().enumerate() {
            let (at, spec) = (Some(l.span().start), l.get_ref());
            if spec.node >= n_nodes {
                let reason = format!(
                    "node {} out of range (the topology has {n_nodes} nodes)",
                    spec.node
                );
                return Err(bad(at, format!("loads[{i}]"), reason));
            }
            if spec.force.iter().any(|x| !x.is_finite()) {
                let reason = format!("{:?} must be finite", spec.force);
                return Err(bad(at, format!("loads[{i}].force"), reason));
            }
            loads.push(NodeLoad {
                node: spec.node,
                force: spec.force,
            });
        }
        // loads on one node add up: their sum must stay finite too (two loads of 1e308)
        let mut sums = std::collections::BTreeMap::<usize, [f64; 3]>::new();
        for (i, l) in loads.iter().enumerate() {
            let sum = sums.entry(l.node).or_default();
            for (s, f) in sum.iter_mut().zip(l.force) {
                *s += f;
            }
            if sum.iter().any(|x| !x.is_finite()) {
                let reason = format!(
                    "the loads on node {} add up past the largest double (an overflow): give their sum as one finite load",
                    l.node
                );
                let at = Some(self.loads[i].span().start);
                return Err(bad(at, format!("loads[{i}].force"), reason));
            }
        }
        Ok(loads)
    }

    /// The error of a node on no member: where the count of nodes was inferred, the member
    /// with the largest index (a typo there leaves the nodes below it unused), else the node.
    fn unused_node(&self, node: usize, n_nodes: usize) -> Failed {
        let inferred = self.n_nodes.is_none() && self.nodes.is_none();
        let last = self
            .members()
            .find(|(_, _, m)| m.get_ref().nodes.contains(&(n_nodes - 1)));
        match last {
            Some((name, _, m)) if inferred => {
                let reason = format!(
                    "node {} makes the topology {n_nodes} nodes (the largest index + 1), and node {node} is on no member; fix the index or give `n_nodes`",
                    n_nodes - 1
                );
                bad(Some(m.span().start), name, reason)
            }
            _ => bad(
                self.node_span(node),
                format!("nodes[{node}]"),
                "the node is on no member",
            ),
        }
    }

    /// The offset of node `i`'s position, if positions are given.
    fn node_span(&self, i: usize) -> Option<usize> {
        Some(self.nodes.as_ref()?.get_ref().get(i)?.span().start)
    }

    /// The offset of the item an error of [`Topology::validate`] names (`nodes[3]`,
    /// `bars[2].length`, `fixed[0]`, …).
    fn offset_of(&self, e: &FormFindError) -> Option<usize> {
        let FormFindError::InvalidTopology { item, .. } = e else {
            return None;
        };
        let head = item.split('.').next()?;
        if head == "loads" {
            return Some(self.loads.first()?.span().start);
        }
        let (kind, index) = head.split_once('[')?;
        let index: usize = index.strip_suffix(']')?.parse().ok()?;
        match kind {
            "bars" => Some(self.bars.get(index)?.span().start),
            "strings" => Some(self.strings.get(index)?.span().start),
            "fixed" => Some(self.fixed.get(index)?.span().start),
            "loads" => Some(self.loads.get(index)?.span().start),
            "clusters" => Some(self.clusters.get(index)?.span().start),
            "nodes" => self.node_span(index),
            _ => None,
        }
    }
}

/// Writes a topology as TOML that [`from_str_named`] reads back exactly (shortest
/// round-trip number formatting).
pub fn to_toml(t: &Topology) -> String {
    use std::fmt::Write;
    let mut out = format!("n_nodes = {}\n", t.n_nodes);
    let v3 = |p: &[f64; 3]| format!("[{:?}, {:?}, {:?}]", p[0], p[1], p[2]);
    if let Some(nodes) = &t.nodes {
        out.push_str("nodes = [\n");
        for p in nodes {
            let _ = writeln!(out, "  {},", v3(p));
        }
        out.push_str("]\n");
    }
    for (name, g) in &t.groups {
        let _ = writeln!(out, "\n[groups.{}]", toml_key(name));
        if let Some(q) = g.force_density {
            let _ = writeln!(out, "force_density = {q:?}");
        }
        if let Some(l) = g.length {
            let _ = writeln!(out, "length = {l:?}");
        }
        if let Some(w) = g.weight {
            let _ = writeln!(out, "weight = {w:?}");
        }
    }
    for (table, members) in [("bars", &t.bars), ("strings", &t.strings)] {
        for m in members {
            let _ = write!(
                out,
                "\n[[{table}]]\nnodes = [{}, {}]\n",
                m.nodes[0], m.nodes[1]
            );
            if let Some(q) = m.force_density {
                let _ = writeln!(out, "force_density = {q:?}");
            }
            if let Some(g) = &m.group {
                let _ = writeln!(out, "group = {}", toml_string(g));
            }
            if let Some(l) = m.length {
                let _ = writeln!(out, "length = {l:?}");
            }
            if let Some(k) = m.stiffness {
                let _ = writeln!(out, "stiffness = {k:?}");
            }
            if let Some(w) = m.weight {
                let _ = writeln!(out, "weight = {w:?}");
            }
        }
    }
    for f in &t.fixed {
        let _ = write!(
            out,
            "\n[[fixed]]\nnode = {}\nposition = {}\n",
            f.node,
            v3(&f.position)
        );
    }
    for l in &t.loads {
        let _ = write!(
            out,
            "\n[[loads]]\nnode = {}\nforce = {}\n",
            l.node,
            v3(&l.force)
        );
    }
    for c in &t.clusters {
        let nodes: Vec<String> = c.nodes.iter().map(usize::to_string).collect();
        let _ = write!(out, "\n[[clusters]]\nnodes = [{}]\n", nodes.join(", "));
        for (key, v) in [
            ("force", c.force),
            ("stiffness", c.stiffness),
            ("area", c.area),
        ] {
            if let Some(v) = v {
                let _ = writeln!(out, "{key} = {v:?}");
            }
        }
        if let Some(m) = &c.material {
            let _ = writeln!(out, "material = {}", toml_string(m));
        }
    }
    out
}

/// A TOML string literal (quotes and backslashes escaped).
fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// A table key: bare when it can be, else quoted.
fn toml_key(s: &str) -> String {
    let bare = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        s.to_string()
    } else {
        toml_string(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PRISM: &str = r#"
nodes = [[1.0, 0.0, 0.0], [-0.5, 0.866, 0.0], [-0.5, -0.866, 0.0],
         [1.0, 0.0, 1.0], [-0.5, 0.866, 1.0], [-0.5, -0.866, 1.0]]
[groups.vertical]
force_density = 1.0
[groups.bars]
length = 1.5
[[bars]]
nodes = [0, 3]
group = "bars"
[[bars]]
nodes = [1, 4]
group = "bars"
[[bars]]
nodes = [2, 5]
group = "bars"
stiffness = 2e5
[[strings]]
nodes = [0, 1]
force_density = 0.577
[[strings]]
nodes = [1, 2]
[[strings]]
nodes = [2, 0]
[[strings]]
nodes = [3, 4]
[[strings]]
nodes = [4, 5]
[[strings]]
nodes = [5, 3]
[[strings]]
nodes = [0, 5]
group = "vertical"
[[strings]]
nodes = [1, 3]
group = "vertical"
[[strings]]
nodes = [2, 4]
group = "vertical"
length = 1.2
[[fixed]]
node = 0
position = [1.0, 0.0, 0.0]
"#;

    fn err(text: &str) -> String {
        from_str_named(text, "t.toml").unwrap_err().to_string()
    }

    #[test]
    fn a_prism_reads_in_file_order_and_round_trips() {
        let t = from_str_named(PRISM, "prism.toml").unwrap();
        assert_eq!((t.n_nodes, t.bars.len(), t.strings.len()), (6, 3, 9));
        assert_eq!(t.bars[2].stiffness, Some(2e5));
        assert_eq!(t.strings[0].force_density, Some(0.577));
        assert_eq!(t.strings[8].length, Some(1.2));
        assert_eq!(t.groups["vertical"].force_density, Some(1.0));
        assert_eq!(t.groups["bars"].length, Some(1.5));
        assert_eq!(
            t.fixed,
            vec![FixedNode {
                node: 0,
                position: [1.0, 0.0, 0.0]
            }]
        );
        let names: Vec<String> = (0..12).map(|k| t.member_name(k)).collect();
        assert_eq!(
            (names[0].as_str(), names[3].as_str()),
            ("bars[0]", "strings[0]")
        );
        let text = to_toml(&t);
        assert_eq!(from_str_named(&text, "again").unwrap(), t);
        // odd numbers and group names survive too
        let mut odd = t.clone();
        odd.nodes.as_mut().unwrap()[4] = [1.0 / 3.0, -1e-300, 6.02e23];
        let g = odd.groups.remove("vertical").unwrap();
        odd.groups.insert("vertical \"v\" strings".into(), g);
        for s in &mut odd.strings[6..] {
            s.group = Some("vertical \"v\" strings".into());
        }
        assert_eq!(from_str_named(&to_toml(&odd), "odd").unwrap(), odd);
    }

    #[test]
    fn loads_and_weights_read_round_trip_and_bad_ones_are_named_by_line() {
        let net = "[groups.cable]\nforce_density = 1.0\nweight = 0.25\n\
                   [[strings]]\nnodes = [0, 2]\ngroup = \"cable\"\n\
                   [[strings]]\nnodes = [1, 2]\nforce_density = 2.0\nweight = 0.5\n\
                   [[fixed]]\nnode = 0\nposition = [0.0, 0.0, 0.0]\n\
                   [[fixed]]\nnode = 1\nposition = [2.0, 0.0, 0.0]\n\
                   [[loads]]\nnode = 2\nforce = [0.0, 0.0, -1.5]\n\
                   [[loads]]\nnode = 2\nforce = [0.1, 0.0, 0.0]\n";
        let t = from_str_named(net, "net.toml").unwrap();
        assert_eq!(t.groups["cable"].weight, Some(0.25));
        assert_eq!(t.strings[1].weight, Some(0.5));
        assert_eq!(t.loads.len(), 2);
        assert_eq!(t.loads[0].force, [0.0, 0.0, -1.5]);
        assert_eq!(from_str_named(&to_toml(&t), "again").unwrap(), t);
        let cases: &[(&str, &str, &[&str])] = &[
            (
                "node = 2\nforce = [0.0, 0.0, -1.5]",
                "node = 7\nforce = [0.0, 0.0, -1.5]",
                &["line 17", "loads[0]", "node 7 out of range"],
            ),
            (
                "[0.0, 0.0, -1.5]",
                "[0.0, inf, -1.5]",
                &["line 17", "loads[0].force", "finite"],
            ),
            (
                "weight = 0.5",
                "weight = -0.5",
                &["line 7", "strings[1].weight", "not negative"],
            ),
            (
                "weight = 0.25",
                "weight = nan",
                &["line 1", "groups.cable.weight", "finite"],
            ),
            (
                "force = [0.1, 0.0, 0.0]",
                "force = [0.1, 0.0, 0.0]\nmoment = [0.0, 0.0, 0.0]",
                &["unknown field `moment`"],
            ),
        ];
        for (from, to, wants) in cases {
            assert!(net.contains(from), "{from}");
            let e = err(&net.replacen(from, to, 1));
            for w in *wants {
                assert!(e.contains(w), "{from} → {to}: {e}");
            }
        }
        let twice = net
            .replace("[0.0, 0.0, -1.5]", "[0.0, 0.0, 1e308]")
            .replace("[0.1, 0.0, 0.0]", "[0.1, 0.0, 1e308]");
        let e = err(&twice);
        assert!(
            e.contains("line 20")
                && e.contains("loads[1].force: the loads on node 2 add up past the largest double"),
            "{e}"
        );
        // without fixed nodes the loads are refused by the line of the first
        let free = net
            .replace("[[fixed]]\nnode = 0\nposition = [0.0, 0.0, 0.0]\n", "")
            .replace("[[fixed]]\nnode = 1\nposition = [2.0, 0.0, 0.0]\n", "");
        let e = err(&free);
        assert!(
            e.starts_with("t.toml (line 11): loads: 2 load(s) on a free-standing topology"),
            "{e}"
        );
    }

    #[test]
    fn clusters_read_round_trip_and_bad_ones_are_named_by_line() {
        let line = "[[fixed]]\nnode = 0\nposition = [0.0, 0.0, 0.0]\n\
                    [[fixed]]\nnode = 2\nposition = [4.0, 0.0, 1.0]\n\
                    [[loads]]\nnode = 1\nforce = [0.0, 0.0, -10.0]\n\
                    [[clusters]]\nnodes = [0, 1, 2]\nforce = 10.0\nmaterial = \"steel\"\narea = 1e-6\n";
        let t = from_str_named(line, "line.toml").unwrap();
        assert_eq!((t.n_nodes, t.n_members(), t.clusters.len()), (3, 0, 1));
        let c = &t.clusters[0];
        assert_eq!(
            (c.nodes.clone(), c.force, c.area),
            (vec![0, 1, 2], Some(10.0), Some(1e-6))
        );
        assert_eq!(c.axial_stiffness(1.0), 206e9 * 1e-6);
        assert_eq!(from_str_named(&to_toml(&t), "again").unwrap(), t);
        let cases: &[(&str, &str, &[&str])] = &[
            (
                "force = 10.0",
                "force = 10.0\nforce_density = 1.0",
                &[
                    "line 10",
                    "clusters[0].force_density",
                    "not a force density",
                ],
            ),
            (
                "force = 10.0",
                "force = 10.0\nfriction = [0.2]",
                &["line 10", "clusters[0].friction", "frictionless"],
            ),
            (
                "force = 10.0",
                "force = nan",
                &["line 10", "clusters[0].force", "finite"],
            ),
            (
                "force = 10.0\n",
                "",
                &["line 10", "clusters[0].force: no tension given"],
            ),
            (
                "material = \"steel\"",
                "material = \"wood\"",
                &[
                    "line 10",
                    "clusters[0].material",
                    "unknown material \"wood\"",
                ],
            ),
            (
                "material = \"steel\"",
                "stiffness = 1e4",
                &["line 10", "clusters[0].area", "with a `material`"],
            ),
            (
                "area = 1e-6",
                "area = -1.0",
                &["line 10", "clusters[0].area", "positive"],
            ),
            (
                "nodes = [0, 1, 2]",
                "nodes = [0, 1]",
                &["line 10", "at least three"],
            ),
            (
                "nodes = [0, 1, 2]",
                "nodes = [0, 1, 2, 1, 0]",
                &[
                    "line 10",
                    "clusters[0]: its segment joins nodes 1 and 2, as another",
                ],
            ),
            (
                "area = 1e-6",
                "area = 1e-6\nlength = 1.0",
                &["unknown field `length`"],
            ),
        ];
        for (from, to, wants) in cases {
            assert!(line.contains(from), "{from}");
            let e = err(&line.replacen(from, to, 1));
            for w in *wants {
                assert!(e.contains(w), "{from} → {to}: {e}");
            }
        }
        // a cluster's segment on a member's nodes, named with the member
        let on_member = line.replace("[[clusters]]", "[[strings]]\nnodes = [1, 2]\n[[clusters]]");
        let e = err(&on_member);
        assert!(
            e.contains("line 12")
                && e.contains("clusters[0]: its segment joins nodes 1 and 2, as strings[0] does"),
            "{e}"
        );
    }

    #[test]
    fn the_node_count_is_given_or_inferred() {
        let body =
            "[[bars]]\nnodes = [0, 2]\n[[strings]]\nnodes = [0, 1]\n[[strings]]\nnodes = [1, 2]\n";
        assert_eq!(from_str_named(body, "t").unwrap().n_nodes, 3);
        let e = err(&format!("n_nodes = 4\n{body}"));
        assert!(e.contains("nodes[3]") && e.contains("on no member"), "{e}");
        let e = err(&format!("n_nodes = 2\n{body}"));
        assert!(
            e.contains("line 2") && e.contains("bars[0]") && e.contains("node 2 out of range"),
            "{e}"
        );
        let e = err(&format!("n_nodes = 3\nnodes = [[0.0, 0.0, 0.0]]\n{body}"));
        assert!(
            e.contains("line 2") && e.contains("1 positions for n_nodes = 3"),
            "{e}"
        );
        let e = err("");
        assert!(e.contains("no member"), "{e}");
        // a count no member reaches is refused by the line of `n_nodes`, before a vector
        // per node is allocated (10¹² nodes aborted on allocation)
        let e = err(&format!("\nn_nodes = 1000000000000\n{body}"));
        assert_eq!(
            e,
            "t.toml (line 2): n_nodes: 1000000000000 nodes, but every node must be on a member \
             or fixed, and 3 member(s) and 0 fixed node(s) reach at most 6"
        );
        let e = err(&format!("n_nodes = {}\n{body}", i64::MAX));
        assert!(e.contains("line 1") && e.contains("reach at most 6"), "{e}");
    }

    #[test]
    fn every_bad_item_is_named_with_its_line() {
        let cases: &[(&str, &str, &[&str])] = &[
            (
                "nodes = [0, 3]\ngroup",
                "nodes = [0, 3, 4]\ngroup",
                &["line 8", "bars[0]", "exactly two"],
            ),
            (
                "nodes = [2, 0]\n",
                "nodes = [1, 0]\n",
                &["line 23", "strings[2]", "as strings[0] does"],
            ),
            (
                "nodes = [2, 0]\n",
                "nodes = [3, 0]\n",
                &["line 23", "strings[2]", "as bars[0] does"],
            ),
            (
                "nodes = [5, 3]\n",
                "nodes = [5, 5]\n",
                &["line 29", "strings[5]", "both ends on node 5"],
            ),
            (
                "group = \"vertical\"\nlength",
                "group = \"verticals\"\nlength",
                &["line 37", "strings[8].group", "verticals"],
            ),
            (
                "force_density = 0.577",
                "force_density = nan",
                &["line 18", "strings[0].force_density", "finite"],
            ),
            (
                "force_density = 0.577",
                "force_density = -0.5",
                &["line 18", "strings[0].force_density", "positive"],
            ),
            (
                "force_density = 1.0",
                "force_density = -1.0",
                &["line 4", "groups.vertical.force_density", "strings[6]"],
            ),
            (
                "length = 1.5",
                "length = -1.5",
                &["line 6", "groups.bars.length", "positive"],
            ),
            (
                "length = 1.2",
                "length = inf",
                &["line 37", "strings[8].length", "finite"],
            ),
            (
                "stiffness = 2e5",
                "stiffness = 0.0",
                &["line 14", "bars[2].stiffness", "positive"],
            ),
            (
                "[[fixed]]\nnode = 0",
                "[[fixed]]\nnode = 9",
                &["line 41", "fixed[0]", "node 9 out of range"],
            ),
            (
                "position = [1.0, 0.0, 0.0]",
                "position = [1.0, nan, 0.0]",
                &["line 41", "fixed[0].position"],
            ),
            (
                "position = [1.0, 0.0, 0.0]",
                "position = [1.0, 0.0, 0.0]\n[[fixed]]\nnode = 0\nposition = [0.0, 0.0, 0.0]",
                &["line 44", "fixed[1]", "fixed already by fixed[0]"],
            ),
            (
                "[-0.5, 0.866, 1.0]",
                "[-0.5, inf, 1.0]",
                &["line 3", "nodes[4]", "finite"],
            ),
            (
                "stiffness = 2e5",
                "stiffness = 2e5\nmass = 1.0",
                &["line 18", "unknown field `mass`"],
            ),
            (
                "[[fixed]]",
                "[[fixes]]",
                &["line 41", "unknown field `fixes`"],
            ),
            (
                "nodes = [0, 1]\nforce",
                "nodes = [0, -1]\nforce",
                &["line 19", "expected usize"],
            ),
        ];
        for (from, to, wants) in cases {
            assert!(PRISM.contains(from), "{from}");
            let e = err(&PRISM.replacen(from, to, 1));
            assert!(e.starts_with("t.toml"), "{e}");
            for w in *wants {
                assert!(e.contains(w), "{from} → {to}: {e}");
            }
        }
        // a group no member is in, a force density given twice, a bar in tension
        let e = err(&PRISM.replace("[groups.bars]", "[groups.spare]\n[groups.bars]"));
        assert!(e.contains("groups.spare") && e.contains("no member"), "{e}");
        let e = err(&PRISM.replacen(
            "nodes = [2, 4]\ngroup = \"vertical\"",
            "nodes = [2, 4]\ngroup = \"vertical\"\nforce_density = 1.0",
            1,
        ));
        assert!(
            e.contains("strings[8].force_density") && e.contains("give it once"),
            "{e}"
        );
        let e = err(&PRISM.replacen(
            "nodes = [1, 4]\ngroup = \"bars\"",
            "nodes = [1, 4]\nforce_density = 2.0",
            1,
        ));
        assert!(
            e.contains("line 11") && e.contains("bars[1].force_density") && e.contains("negative"),
            "{e}"
        );
    }
}
