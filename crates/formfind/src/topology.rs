//! A form-finding topology: nodes (optionally with positions, an initial guess), bars and
//! strings (node pairs, optional force density, group and target length), named groups of
//! members sharing a force density, and fixed nodes with their coordinates.

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
}

/// A named group of members sharing a force density (and optionally a target length).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Group {
    /// Force density of every member of the group (N/m, tension-positive).
    pub force_density: Option<f64>,
    /// Target (rest) length of every member of the group (m).
    pub length: Option<f64>,
}

/// A node held at given coordinates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FixedNode {
    /// The node index.
    pub node: usize,
    /// Its coordinates (m).
    pub position: [f64; 3],
}

/// A connectivity to find the form of. Members are numbered bars first, then strings, in
/// the order given.
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
}

impl Topology {
    /// Bars then strings.
    pub fn members(&self) -> impl Iterator<Item = &Member> {
        self.bars.iter().chain(self.strings.iter())
    }

    /// The name of member k (`bars[i]` or `strings[j]`), as errors name it.
    pub fn member_name(&self, k: usize) -> String {
        if k < self.bars.len() {
            format!("bars[{k}]")
        } else {
            format!("strings[{}]", k - self.bars.len())
        }
    }

    /// Checks indices, groups, fixed nodes and numbers; every failure names the item.
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
            if let Some(g) = &m.group {
                if !self.groups.contains_key(g) {
                    return Err(bad(
                        format!("{name}.group"),
                        format!("no group named \"{g}\""),
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
        Ok(())
    }
}
