//! The assembled truss: numbered nodes and parent → child members.
//!
//! Member j runs from a parent node to one of its children; its vector is
//! m = n_parent − n_child (eq. 4.33) and its length ‖m‖. Members are numbered by parent, then by
//! child slot (3-D: UL, UR, D; planar: U, D), so member j of a 3-D truss has parent j / 3.
//! Non-support nodes (levels 0..q−1) are numbered before the supports (level q).

use crate::error::Result;
use crate::nodes::{self, NodeTuple};
use crate::params::MichellParams;
use nalgebra::Vector3;
use serde::Serialize;
use tensegrity_core::{Bar, Structure, StructureBuilder, Support};

/// Which child of its parent a member reaches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// 3-D: to (U+1, D, L+1, R).
    UpLeft,
    /// 3-D: to (U+1, D, L, R+1).
    UpRight,
    /// Planar: to n_(i+1)k (Skelton's "U spiral").
    Up,
    /// To (U, D+1, L, R), or planar n_i(k+1) ("D spiral").
    Down,
}

impl Branch {
    /// True for the members that raise U (UL, UR, planar U).
    pub fn is_up(&self) -> bool {
        !matches!(self, Branch::Down)
    }
}

/// A node of the truss.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// Its tuple.
    pub tuple: NodeTuple,
    /// Its position (m).
    pub position: Vector3<f64>,
}

/// A member from a parent node to a child node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Member {
    /// Parent node index (lower level).
    pub parent: usize,
    /// Child node index (level + 1).
    pub child: usize,
    /// Which child.
    pub branch: Branch,
    /// m = n_parent − n_child (m).
    pub vector: Vector3<f64>,
    /// ‖m‖ (m).
    pub length: f64,
}

/// A planar or 3-D discrete Michell truss of complexity q.
#[derive(Debug, Clone)]
pub struct MichellTruss {
    params: MichellParams,
    nodes: Vec<Node>,
    members: Vec<Member>,
    n_free: usize,
}

impl MichellTruss {
    /// Builds the truss after validating `params`.
    ///
    /// ```
    /// use michell3d::{MichellParams, MichellTruss};
    /// let p = MichellParams::cylindrical(3, 1.0, std::f64::consts::FRAC_PI_6, 0.3, 0.25);
    /// let t = MichellTruss::new(p).unwrap();
    /// assert_eq!((t.nodes().len(), t.members().len()), (20, 30));
    /// ```
    pub fn new(params: MichellParams) -> Result<Self> {
        params.validate()?;
        let q = params.complexity;
        let planar = params.geometry.is_planar();
        let nodes: Vec<Node> = nodes::tuples(q, planar)
            .into_iter()
            .map(|tuple| Node {
                tuple,
                position: nodes::position(&params, &tuple),
            })
            .collect();
        let n_free = if planar {
            nodes::node_count_planar(q - 1)
        } else {
            nodes::node_count_3d(q - 1)
        };
        let mut members = Vec::with_capacity(if planar {
            nodes::member_count_planar(q)
        } else {
            nodes::member_count_3d(q)
        });
        for (parent, node) in nodes[..n_free].iter().enumerate() {
            let mut push = |child_tuple: NodeTuple, branch: Branch, child: usize| {
                let vector = node.position - nodes[child].position;
                debug_assert_eq!(nodes[child].tuple, child_tuple);
                members.push(Member {
                    parent,
                    child,
                    branch,
                    vector,
                    length: vector.norm(),
                });
            };
            if planar {
                let [up, down] = node.tuple.planar_children();
                push(up, Branch::Up, nodes::index_planar(&up));
                push(down, Branch::Down, nodes::index_planar(&down));
            } else {
                let [ul, ur, dn] = node.tuple.children();
                push(ul, Branch::UpLeft, nodes::index_3d(&ul));
                push(ur, Branch::UpRight, nodes::index_3d(&ur));
                push(dn, Branch::Down, nodes::index_3d(&dn));
            }
        }
        Ok(Self {
            params,
            nodes,
            members,
            n_free,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &MichellParams {
        &self.params
    }

    /// True for Skelton's planar truss.
    pub fn is_planar(&self) -> bool {
        self.params.geometry.is_planar()
    }

    /// Members per non-support node: 2 (planar) or 3.
    pub fn children_per_node(&self) -> usize {
        if self.is_planar() {
            2
        } else {
            3
        }
    }

    /// All nodes, levels 0..=q.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// All members, numbered by parent then child slot.
    pub fn members(&self) -> &[Member] {
        &self.members
    }

    /// Member lengths (m).
    pub fn lengths(&self) -> Vec<f64> {
        self.members.iter().map(|m| m.length).collect()
    }

    /// The truss as a core [`Structure`]: every member a bar (parent → child), the level-q
    /// nodes pinned; members numbered as [`MichellTruss::members`].
    pub fn structure(&self) -> Result<Structure> {
        Ok(self.structure_builder().build()?)
    }

    /// The builder of [`MichellTruss::structure`], for callers that add members (extra
    /// strings) before it validates.
    pub fn structure_builder(&self) -> StructureBuilder {
        let mut b = Structure::builder().nodes(self.nodes.iter().map(|n| n.position.into()));
        for m in &self.members {
            b = b.bar(Bar::new(m.parent, m.child));
        }
        for s in self.n_free..self.nodes.len() {
            b = b.support(Support::pinned(s));
        }
        b
    }

    /// Number of non-support nodes (levels 0..q−1); they come first in the numbering.
    pub fn n_free(&self) -> usize {
        self.n_free
    }

    /// Whether node `i` is a support (level q).
    pub fn is_support(&self, i: usize) -> bool {
        i >= self.n_free
    }

    /// Index of a tuple, if it belongs to the truss.
    pub fn find(&self, t: &NodeTuple) -> Option<usize> {
        let planar = self.is_planar();
        if t.level() > self.params.complexity || (!planar && t.l + t.r != t.u) {
            return None;
        }
        let i = if planar {
            nodes::index_planar(t)
        } else {
            nodes::index_3d(t)
        };
        (self.nodes.get(i)?.tuple == *t).then_some(i)
    }

    /// Report label of node `i`: `[U, D, L, R]`, or `[i, k]` for a planar truss.
    pub fn label(&self, i: usize) -> Vec<usize> {
        self.nodes[i].tuple.label(self.is_planar())
    }

    /// The member from `parent` to `child` tuples, if any.
    pub fn find_member(&self, parent: &NodeTuple, child: &NodeTuple) -> Option<usize> {
        let p = self.find(parent)?;
        let c = self.find(child)?;
        let k = self.children_per_node();
        (k * p..k * p + k).find(|&j| j < self.members.len() && self.members[j].child == c)
    }
}
