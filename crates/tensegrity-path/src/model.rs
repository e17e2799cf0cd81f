//! The elastic model of a load path (crate docs): nodes, members with an axial stiffness EA
//! and a rest length L₀, supports along any directions, and the reference load P.

use crate::error::{PathError, Result};
use nalgebra::Vector3;
use serde::Serialize;
use std::ops::Range;
use tensegrity_core::Structure;

/// The largest ratio of two stiffnesses of one model (members' EA/L₀, elastic supports' k)
/// that is accepted. Newton's residual floor is 64 ε k_max ‖x‖ ([`crate::newton::tolerance`]):
/// at 10¹⁰ it is 1.4·10⁻⁴ of the softest item's force at a strain of one (its k_min ‖x‖),
/// beyond it the softest item's response is round-off. Steel bars beside rubber strings are
/// about 10⁶.
pub const MAX_STIFFNESS_RATIO: f64 = 1e10;

/// Whether a member carries compression.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MemberKind {
    /// Tension and compression.
    Bar,
    /// Tension only: slack (no force, no stiffness) while shorter than its rest length.
    String,
}

/// A member: its nodes, kind, axial stiffness EA (N) and rest length L₀ (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ElasticMember {
    /// Start and end node.
    pub nodes: [usize; 2],
    /// Bar or string.
    pub kind: MemberKind,
    /// Axial stiffness EA (N): the tension is EA (L − L₀)/L₀.
    pub ea: f64,
    /// Rest length L₀ (m).
    pub rest_length: f64,
}

/// A node held along some directions (each a unit vector; one to three, independent):
/// rigidly, or by a spring of stiffness k along each of them (an elastic support, `stiffness`).
///
/// A rigid support removes its directions from the node's free coordinates ([`crate::dofs`]);
/// an elastic one leaves them free and adds, per direction d, the force k d (d·(u − λ a))
/// to the resisting forces (u the node's displacement from the reference state, a its
/// support's driven `displacement` per unit λ: the spring's anchor moves) and k d dᵀ to the
/// tangent; its reaction is the spring's force, −k d·(u − λ a) along d.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// The held node.
    pub node: usize,
    /// The directions along which it cannot move (or along which its springs act).
    pub directions: Vec<Vector3<f64>>,
    /// The stiffness k (N/m) of a spring along each direction; `None`: held rigidly.
    pub stiffness: Option<f64>,
}

impl Support {
    /// A node held in all three directions.
    pub fn pinned(node: usize) -> Self {
        Self::along(node, vec![Vector3::x(), Vector3::y(), Vector3::z()])
    }

    /// A node held rigidly along `directions`.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_path::Support;
    /// let roller = Support::along(1, vec![Vector3::z()]);
    /// assert_eq!((roller.directions.len(), roller.stiffness), (1, None));
    /// ```
    pub fn along(node: usize, directions: Vec<Vector3<f64>>) -> Self {
        Self {
            node,
            directions,
            stiffness: None,
        }
    }

    /// The same support held by a spring of stiffness `k` (N/m) along each direction.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_path::Support;
    /// let spring = Support::along(1, vec![Vector3::x()]).elastic(1e4);
    /// assert_eq!(spring.stiffness, Some(1e4));
    /// ```
    pub fn elastic(mut self, k: f64) -> Self {
        self.stiffness = Some(k);
        self
    }
}

/// What else the load factor λ drives besides the load λ P (TsgFEM's forced motions and rest
/// lengths): each member's rest length L₀ + λ ΔL₀ and each supported node's position moved by
/// λ d along its held directions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Drivers {
    /// ΔL₀ of every member at λ = 1 (m; empty: none).
    pub rest_length_changes: Vec<f64>,
    /// ΔL₀ of every cluster's whole rest length at λ = 1 (m; empty: none): one actuator
    /// reeling all its segments (not a cluster with pulley friction).
    pub cluster_rest_length_changes: Vec<f64>,
    /// The motion d of every node at λ = 1 (m; empty: none); only supported nodes may move,
    /// along their held directions (of an elastic support: its springs' anchor moves).
    pub displacements: Vec<Vector3<f64>>,
    /// A load D on every node that does not grow with λ (N; empty: none): the self-weight,
    /// present from λ = 0 (the path starts from the structure standing under it).
    pub dead_load: Vec<Vector3<f64>>,
}

impl Drivers {
    /// Whether λ drives anything but the load.
    pub fn is_empty(&self) -> bool {
        self.rest_length_changes.iter().all(|&d| d == 0.0)
            && self.cluster_rest_length_changes.iter().all(|&d| d == 0.0)
            && self.displacements.iter().all(|d| d.norm() == 0.0)
            && self.dead_load.iter().all(|d| d.norm() == 0.0)
    }
}

/// A clustered string of the elastic model ([`crate::clusters`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ElasticCluster {
    /// The nodes it passes through, in order (at least three).
    pub nodes: Vec<usize>,
    /// Stiffness k of the whole cluster (N/m; EA = k L₀).
    pub stiffness: f64,
    /// Rest length L₀ of the whole cluster (m).
    pub rest_length: f64,
    /// Damping c on the rate of its length (N·s/m; read by the dynamics only).
    pub damping: f64,
    /// Pulley friction (the capstan law, [`crate::clusters`]); `None`: frictionless
    /// pulleys, one tension along the cluster.
    pub friction: Option<ClusterFriction>,
}

/// The pulley friction of a cluster and its material's distribution over its segments
/// ([`crate::clusters`], `tensegrity_core::capstan`).
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterFriction {
    /// The friction coefficient μ of the pulley at each inner node.
    pub mu: Vec<f64>,
    /// Each segment's rest length s_i (m; Σ s_i = L₀): the state that sliding changes.
    pub rest_lengths: Vec<f64>,
    /// Each pulley's state after the last increment (all stuck at the start).
    pub pulleys: Vec<tensegrity_core::capstan::Pulley>,
}

impl ClusterFriction {
    /// Friction `mu` on a cluster of rest length `rest_length` whose segments have the
    /// lengths `lengths`: its material spread in proportion to them (one strain along the
    /// cluster: the frictionless state).
    ///
    /// ```
    /// use tensegrity_path::model::ClusterFriction;
    /// let f = ClusterFriction::spread(vec![0.2], 1.5, &[1.0, 2.0]);
    /// assert_eq!(f.rest_lengths, vec![0.5, 1.0]);
    /// ```
    pub fn spread(mu: Vec<f64>, rest_length: f64, lengths: &[f64]) -> Self {
        let total: f64 = lengths.iter().sum();
        Self {
            pulleys: vec![tensegrity_core::capstan::Pulley::Stick; mu.len()],
            mu,
            rest_lengths: lengths.iter().map(|l| rest_length * l / total).collect(),
        }
    }
}

impl ElasticCluster {
    /// Its segments, as node pairs in order.
    pub fn segments(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        self.nodes.windows(2).map(|w| [w[0], w[1]])
    }

    /// The number of its segments.
    pub fn n_segments(&self) -> usize {
        self.nodes.len().saturating_sub(1)
    }

    /// Its tension at length `length` (taut only; no damping): k (L − L₀), or 0 when slack.
    ///
    /// ```
    /// use tensegrity_path::model::ElasticCluster;
    /// let c = ElasticCluster { nodes: vec![0, 1, 2], stiffness: 100.0, rest_length: 2.0, damping: 0.0, friction: None };
    /// assert_eq!((c.tension(2.5), c.tension(1.5)), (50.0, 0.0));
    /// ```
    pub fn tension(&self, length: f64) -> f64 {
        (self.stiffness * (length - self.rest_length)).max(0.0)
    }

    /// Its stiffness at the rest length `rest` (N/m): EA/`rest`, its EA = k L₀ kept (a
    /// driven cluster's material does not change as it is reeled, as a driven string's).
    ///
    /// ```
    /// use tensegrity_path::model::ElasticCluster;
    /// let c = ElasticCluster { nodes: vec![0, 1, 2], stiffness: 100.0, rest_length: 2.0, damping: 0.0, friction: None };
    /// assert_eq!((c.stiffness_at(2.0), c.stiffness_at(1.0)), (100.0, 200.0));
    /// ```
    pub fn stiffness_at(&self, rest: f64) -> f64 {
        self.stiffness * self.rest_length / rest
    }
}

impl ElasticModel {
    /// The state indices of cluster `c`'s segments (after the members' and the earlier
    /// clusters' segments: module docs).
    pub fn cluster_states(&self, c: usize) -> Range<usize> {
        let start = self.members.len()
            + self.clusters[..c]
                .iter()
                .map(ElasticCluster::n_segments)
                .sum::<usize>();
        start..start + self.clusters[c].n_segments()
    }

    /// The two nodes of every state entry: the members', then the clusters' segments.
    pub fn state_nodes(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        let segments = self.clusters.iter().flat_map(|c| c.segments());
        self.members.iter().map(|m| m.nodes).chain(segments)
    }

    /// What a state index reports as: the member itself, or `members.len() + c` for a
    /// segment of cluster c (`None` for a cluster's segment after its first: one entry per
    /// cluster).
    pub fn reported_index(&self, k: usize) -> Option<usize> {
        let nm = self.members.len();
        if k < nm {
            return Some(k);
        }
        (0..self.clusters.len())
            .find(|&c| self.cluster_states(c).contains(&k))
            .filter(|&c| self.cluster_states(c).start == k)
            .map(|c| nm + c)
    }

    /// One value per member, then one per cluster (its first segment's), of per-state
    /// `values` (e.g. the tensions): the order of every report ([`crate::clusters`]).
    pub fn reported<T: Copy>(&self, values: &[T]) -> Vec<T> {
        let nm = self.members.len();
        let mut out: Vec<T> = values[..nm.min(values.len())].to_vec();
        for c in 0..self.clusters.len() {
            if let Some(v) = values.get(self.cluster_states(c).start) {
                out.push(*v);
            }
        }
        out
    }

    /// Whether a cluster has pulley friction.
    pub fn has_friction(&self) -> bool {
        self.clusters.iter().any(|c| c.friction.is_some())
    }

    /// One tension per member, then per cluster the largest of its segments' (they are one
    /// tension on frictionless pulleys), from the states' `tensions`.
    pub fn reported_tensions(&self, tensions: &[f64]) -> Vec<f64> {
        let mut out = self.reported(tensions);
        for c in 0..self.clusters.len() {
            let range = self.cluster_states(c);
            if let (Some(t), Some(seg)) = (out.get_mut(self.members.len() + c), tensions.get(range))
            {
                *t = seg.iter().fold(*t, |a, &b| a.max(b));
            }
        }
        out
    }

    /// Whether the state entry `k` carries tension only (a string or a cluster's segment).
    pub fn is_tension_only(&self, k: usize) -> bool {
        self.members
            .get(k)
            .is_none_or(|m| m.kind == MemberKind::String)
    }
}

/// The model (crate docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ElasticModel {
    /// Node positions of the reference state (m).
    pub nodes: Vec<Vector3<f64>>,
    /// The members.
    pub members: Vec<ElasticMember>,
    /// The clustered strings ([`crate::clusters`]; their states and reported tensions come
    /// after the members').
    pub clusters: Vec<ElasticCluster>,
    /// The supports.
    pub supports: Vec<Support>,
    /// The reference load P, one force per node (N); the load is λ P.
    pub load: Vec<Vector3<f64>>,
    /// Rest lengths and support motions driven by λ beside the load.
    pub drivers: Drivers,
}

impl ElasticModel {
    /// The dead load on node `i` (zero without one).
    pub fn dead_load(&self, i: usize) -> Vector3<f64> {
        self.drivers
            .dead_load
            .get(i)
            .copied()
            .unwrap_or_else(Vector3::zeros)
    }

    /// The rest length of member `k` at load factor `lambda`, L₀ + λ ΔL₀.
    pub fn rest_length(&self, k: usize, lambda: f64) -> f64 {
        let change = self
            .drivers
            .rest_length_changes
            .get(k)
            .copied()
            .unwrap_or(0.0);
        self.members[k].rest_length + lambda * change
    }

    /// Cluster `c`'s whole rest length at load factor `lambda`: L₀ + λ ΔL₀ with its
    /// driven change ([`Drivers::cluster_rest_length_changes`]).
    pub fn cluster_rest_length(&self, c: usize, lambda: f64) -> f64 {
        let change = self
            .drivers
            .cluster_rest_length_changes
            .get(c)
            .copied()
            .unwrap_or(0.0);
        self.clusters[c].rest_length + lambda * change
    }

    /// Checks every item: node indices in range, finite positive EA and L₀, finite loads
    /// and nodes, support directions finite and non-zero (normalised here) and independent,
    /// a support's stiffness finite and positive; an error names the support by its index
    /// and node (`support 2 (node 5)`).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_path::{ElasticMember, ElasticModel, MemberKind, Support};
    /// let bar = ElasticMember { nodes: [0, 1], kind: MemberKind::Bar, ea: 1e4, rest_length: 1.0 };
    /// let m = ElasticModel {
    ///     nodes: vec![Vector3::zeros(), Vector3::x()],
    ///     members: vec![bar],
    ///     clusters: Vec::new(),
    ///     supports: vec![Support::pinned(0)],
    ///     load: vec![Vector3::zeros(), Vector3::x()],
    ///     drivers: Default::default(),
    /// };
    /// assert!(m.clone().validated().is_ok());
    /// let mut bad = m;
    /// bad.members[0].nodes = [0, 5];
    /// assert_eq!(bad.validated().unwrap_err().to_string(),
    ///     "member 0 (bar): node 5 does not exist (2 nodes)");
    /// ```
    pub fn validated(mut self) -> Result<Self> {
        let n = self.nodes.len();
        for (i, x) in self.nodes.iter().enumerate() {
            if !x.iter().all(|v| v.is_finite()) {
                return Err(PathError::model(
                    format!("node {i}"),
                    "its coordinates must be finite",
                ));
            }
        }
        if self.load.len() != n {
            return Err(PathError::model(
                "load",
                format!("{} forces for {n} nodes", self.load.len()),
            ));
        }
        for (i, p) in self.load.iter().enumerate() {
            if !p.iter().all(|v| v.is_finite()) {
                return Err(PathError::model(
                    format!("load on node {i}"),
                    "must be finite",
                ));
            }
        }
        for (k, m) in self.members.iter().enumerate() {
            let name = format!("member {k} ({})", kind_name(m.kind));
            if let Some(&bad) = m.nodes.iter().find(|&&i| i >= n) {
                return Err(PathError::model(
                    name,
                    format!("node {bad} does not exist ({n} nodes)"),
                ));
            }
            if m.nodes[0] == m.nodes[1] {
                return Err(PathError::model(name, "joins a node to itself"));
            }
            if !(m.ea.is_finite() && m.ea > 0.0) {
                return Err(PathError::model(
                    name,
                    format!(
                        "its axial stiffness EA = {} N must be finite and positive",
                        m.ea
                    ),
                ));
            }
            if !(m.rest_length.is_finite() && m.rest_length > 0.0) {
                return Err(PathError::model(
                    name,
                    format!(
                        "its rest length {} m must be finite and positive",
                        m.rest_length
                    ),
                ));
            }
        }
        self.check_clusters()?;
        let d = &self.drivers;
        if !d.rest_length_changes.is_empty() && d.rest_length_changes.len() != self.members.len() {
            return Err(PathError::model(
                "rest_length_changes",
                format!(
                    "{} changes for {} members",
                    d.rest_length_changes.len(),
                    self.members.len()
                ),
            ));
        }
        let changes = &d.cluster_rest_length_changes;
        if !changes.is_empty() && changes.len() != self.clusters.len() {
            return Err(PathError::model(
                "cluster_rest_length_changes",
                format!(
                    "{} changes for {} clusters",
                    changes.len(),
                    self.clusters.len()
                ),
            ));
        }
        for (c, change) in changes.iter().enumerate() {
            if !change.is_finite() {
                return Err(PathError::model(
                    format!("cluster {c}"),
                    "its rest length change must be finite",
                ));
            }
            if *change != 0.0 && self.clusters[c].friction.is_some() {
                return Err(PathError::model(
                    format!("cluster {c}"),
                    "a cluster with pulley friction takes no rest_length_change (where its actuator takes in the material is not modelled)",
                ));
            }
        }
        if !d.dead_load.is_empty() && d.dead_load.len() != n {
            return Err(PathError::model(
                "dead_load",
                format!("{} forces for {n} nodes", d.dead_load.len()),
            ));
        }
        if let Some(i) = d
            .dead_load
            .iter()
            .position(|v| !v.iter().all(|c| c.is_finite()))
        {
            return Err(PathError::model(
                format!("dead load on node {i}"),
                "must be finite",
            ));
        }
        if !d.displacements.is_empty() && d.displacements.len() != n {
            return Err(PathError::model(
                "displacements",
                format!("{} motions for {n} nodes", d.displacements.len()),
            ));
        }
        for (k, c) in d.rest_length_changes.iter().enumerate() {
            if !c.is_finite() {
                return Err(PathError::model(
                    format!("member {k}"),
                    "its rest length change must be finite",
                ));
            }
        }
        for (i, v) in d.displacements.iter().enumerate() {
            if !v.iter().all(|c| c.is_finite()) {
                return Err(PathError::model(
                    format!("displacement of node {i}"),
                    "must be finite",
                ));
            }
        }
        for (k, s) in self.supports.iter_mut().enumerate() {
            let item = format!("support {k} (node {})", s.node);
            if s.node >= n {
                return Err(PathError::model(
                    item,
                    format!("node {} does not exist ({n} nodes)", s.node),
                ));
            }
            if s.directions.is_empty() || s.directions.len() > 3 {
                return Err(PathError::model(
                    item,
                    format!("{} directions: give one to three", s.directions.len()),
                ));
            }
            let mut basis: Vec<Vector3<f64>> = Vec::with_capacity(3);
            for d in &mut s.directions {
                let norm = d.norm();
                if !(norm.is_finite() && norm > 0.0) {
                    return Err(PathError::model(
                        item,
                        "a direction must be finite and non-zero",
                    ));
                }
                *d /= norm;
                let mut v = *d;
                for b in &basis {
                    v -= b * b.dot(&v);
                }
                if v.norm() < 1e-9 {
                    return Err(PathError::model(
                        item,
                        "its directions are dependent (a direction repeated or in the plane of two others): give independent ones",
                    ));
                }
                basis.push(v.normalize());
            }
            if let Some(k) = s.stiffness {
                if !(k.is_finite() && k > 0.0) {
                    return Err(PathError::model(
                        item,
                        format!("its stiffness k = {k} N/m must be finite and positive"),
                    ));
                }
            }
        }
        self.check_stiffness_ratio()?;
        Ok(self)
    }

    /// Checks the clusters: at least three nodes, each in range, no segment joining a node
    /// to itself, k and L₀ finite and positive, c finite and ≥ 0; an error names `cluster c`.
    fn check_clusters(&self) -> Result<()> {
        let n = self.nodes.len();
        for (c, cl) in self.clusters.iter().enumerate() {
            let name = format!("cluster {c}");
            if cl.nodes.len() < 3 {
                return Err(PathError::model(
                    name,
                    format!(
                        "passes through {} node(s): a cluster runs through at least three",
                        cl.nodes.len()
                    ),
                ));
            }
            if let Some(&bad) = cl.nodes.iter().find(|&&i| i >= n) {
                return Err(PathError::model(
                    name,
                    format!("node {bad} does not exist ({n} nodes)"),
                ));
            }
            if let Some([a, _]) = cl.segments().find(|[a, b]| a == b) {
                return Err(PathError::model(
                    name,
                    format!("a segment joins node {a} to itself"),
                ));
            }
            for (what, v, unit) in [
                ("stiffness k", cl.stiffness, "N/m"),
                ("rest length", cl.rest_length, "m"),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(PathError::model(
                        name,
                        format!("its {what} {v} {unit} must be finite and positive"),
                    ));
                }
            }
            if !(cl.damping.is_finite() && cl.damping >= 0.0) {
                return Err(PathError::model(
                    name,
                    format!("its damping {} N s/m must be finite and ≥ 0", cl.damping),
                ));
            }
        }
        Ok(())
    }

    /// Refuses stiffnesses (members' EA/L₀, elastic supports' k) whose ratio exceeds
    /// [`MAX_STIFFNESS_RATIO`], naming the stiffest and the softest item: the tangent's
    /// eigenvalues and Newton's corrections carry about 16 digits relative to the stiffest,
    /// so the softest would be round-off (and near the largest double the tangent overflows).
    fn check_stiffness_ratio(&self) -> Result<()> {
        let members = self.members.iter().enumerate().map(|(k, m)| {
            (
                format!("member {k} ({}): EA/L0", kind_name(m.kind)),
                m.ea / m.rest_length,
            )
        });
        let supports = self.supports.iter().enumerate().filter_map(|(k, s)| {
            s.stiffness
                .map(|v| (format!("support {k} (node {}): stiffness", s.node), v))
        });
        let clusters = self
            .clusters
            .iter()
            .enumerate()
            .map(|(c, cl)| (format!("cluster {c}: stiffness"), cl.stiffness));
        let all: Vec<(String, f64)> = members.chain(supports).chain(clusters).collect();
        let by = |a: &&(String, f64), b: &&(String, f64)| a.1.total_cmp(&b.1);
        let (Some(stiff), Some(soft)) = (all.iter().max_by(by), all.iter().min_by(by)) else {
            return Ok(());
        };
        if stiff.1.is_finite() && stiff.1 <= MAX_STIFFNESS_RATIO * soft.1 {
            return Ok(());
        }
        Err(PathError::model(
            stiff.0.clone(),
            format!(
                "{:e} N/m is {:.1e} times {} = {:e} N/m, beyond the ratio {MAX_STIFFNESS_RATIO:e} that double precision resolves: hold a direction rigidly instead of on a stiff spring, or check the units",
                stiff.1,
                stiff.1 / soft.1,
                soft.0,
                soft.1
            ),
        ))
    }

    /// The model of a scene's structure: bars elastic with EA = E · π r² (their material's
    /// Young's modulus and their `radius`) and rest length their length in the scene;
    /// strings with their `stiffness` k (N/m) and `rest_length` (default: their length in the
    /// scene, no prestress), EA = k L₀; the supports along their held directions (the
    /// flagged axes and the `along` ones), rigid or elastic (their `stiffness`); the scene's
    /// loads as P; with `[gravity]`, the weight of every bar with a `mass` (half at each end,
    /// as the statics counts it) as the dead load, present from λ = 0. A bar without a radius
    /// and a string without a stiffness are errors naming the item.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Material, Structure, StringMember, Support};
    /// let s = Structure::builder()
    ///     .node([0.0, 0.0, 0.0]).node([2.0, 0.0, 0.0])
    ///     .material("alu", Material::new(2700.0, 70e9, 100e6))
    ///     .bar(Bar::new(0, 1).material("alu").radius(0.01))
    ///     .support(Support::pinned(0))
    ///     .build().unwrap();
    /// let m = tensegrity_path::ElasticModel::from_structure(&s).unwrap();
    /// let ea = 70e9 * std::f64::consts::PI * 1e-4;
    /// assert!((m.members[0].ea - ea).abs() < 1e-6 * ea);
    /// assert_eq!(m.members[0].rest_length, 2.0);
    /// ```
    pub fn from_structure(s: &Structure) -> Result<Self> {
        Self::from_structure_mixed(s, &[])
    }

    /// [`ElasticModel::from_structure`] with the bars k where `rigid[k]` (missing entries:
    /// elastic) rigid, for the dynamics of [`crate::rigid_bars`]: such a bar needs no radius
    /// nor material, its rest length is its length in the scene (the length it keeps) and
    /// its EA a placeholder that nothing reads (the stiffest elastic member's EA/L₀ at its
    /// length, else 1 N, so that it sets no stiffness ratio); a rigid bar of zero length is an error
    /// naming it.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .node([0.0, 0.0, 0.0]).node([2.0, 0.0, 0.0])
    ///     .bar(Bar::new(0, 1).mass(1.0))
    ///     .build().unwrap();
    /// let m = tensegrity_path::ElasticModel::from_structure_mixed(&s, &[true]).unwrap();
    /// assert_eq!(m.members[0].rest_length, 2.0);
    /// // elastic, it would need its axial stiffness
    /// assert!(tensegrity_path::ElasticModel::from_structure(&s).is_err());
    /// ```
    pub fn from_structure_mixed(s: &Structure, rigid: &[bool]) -> Result<Self> {
        let x = s.nodes();
        let length = |[i, j]: [usize; 2]| (x[j] - x[i]).norm();
        let mut members = Vec::with_capacity(s.n_members());
        for (k, b) in s.bars().iter().enumerate() {
            if rigid.get(k).copied().unwrap_or(false) {
                let l = length(b.nodes);
                if !(l.is_finite() && l > 0.0) {
                    return Err(PathError::model(
                        format!("bar {k}"),
                        format!("a rigid bar of length {l} m: its two nodes must be apart (a rigid bar keeps its length in the scene)"),
                    ));
                }
                members.push(ElasticMember {
                    nodes: b.nodes,
                    kind: MemberKind::Bar,
                    ea: 1.0,
                    rest_length: l,
                });
                continue;
            }
            let Some(radius) = b.radius else {
                return Err(PathError::model(
                    format!("bar {k}"),
                    "an elastic bar needs a radius (its area π r²) and a material with a Young's modulus in the scene",
                ));
            };
            let Some(name) = b.material.as_deref() else {
                return Err(PathError::model(
                    format!("bar {k}"),
                    "an elastic bar needs a material (its Young's modulus) beside its radius in the scene",
                ));
            };
            let material = s.materials().get(name).ok_or_else(|| {
                PathError::model(format!("bar {k}"), format!("unknown material `{name}`"))
            })?;
            members.push(ElasticMember {
                nodes: b.nodes,
                kind: MemberKind::Bar,
                ea: material.youngs_modulus * std::f64::consts::PI * radius * radius,
                rest_length: length(b.nodes),
            });
        }
        for (k, st) in s.strings().iter().enumerate() {
            let Some(stiffness) = st.stiffness else {
                return Err(PathError::model(
                    format!("string {k}"),
                    "an elastic string needs a stiffness (N/m) in the scene",
                ));
            };
            let rest_length = st.rest_length.unwrap_or_else(|| length(st.nodes));
            members.push(ElasticMember {
                nodes: st.nodes,
                kind: MemberKind::String,
                ea: stiffness * rest_length,
                rest_length,
            });
        }
        // a rigid bar's EA is read by nothing but the check of the stiffness ratio and the
        // round-off floors: the stiffest elastic member's EA/L₀ at its length keeps both as
        // the elastic members set them (a placeholder of 1 N beside steel columns of
        // EA/L₀ = 10¹¹ N/m would be refused as a ratio beyond double precision)
        let is_rigid = |k: usize| k < s.n_bars() && rigid.get(k).copied().unwrap_or(false);
        let stiffest = (members.iter().enumerate())
            .filter(|(k, _)| !is_rigid(*k))
            .map(|(_, m)| m.ea / m.rest_length)
            .fold(0.0, f64::max);
        for (k, m) in members.iter_mut().enumerate() {
            if is_rigid(k) && stiffest > 0.0 {
                m.ea = stiffest * m.rest_length;
            }
        }
        let clusters = elastic_clusters(s)?;
        let supports = s
            .supports()
            .iter()
            .map(|sp| Support {
                node: sp.node,
                directions: sp.held_directions(),
                stiffness: sp.stiffness,
            })
            .filter(|sp| !sp.directions.is_empty())
            .collect();
        let mut load = vec![Vector3::zeros(); x.len()];
        for l in s.loads() {
            load[l.node] += l.force;
        }
        // the self-weight, as the statics counts it (half of each bar's mass at each end)
        let w = s.W();
        let dead_load: Vec<Vector3<f64>> = (0..x.len())
            .map(|i| Vector3::from(w.column(i)) - load[i])
            .collect();
        let dead_load = if dead_load.iter().all(|d| d.norm() == 0.0) {
            Vec::new()
        } else {
            dead_load
        };
        Self {
            nodes: x.to_vec(),
            members,
            clusters,
            supports,
            load,
            drivers: Drivers {
                dead_load,
                ..Drivers::default()
            },
        }
        .validated()
    }
}

/// The clusters of a scene's structure ([`crate::clusters`]): their `stiffness` k, their
/// `rest_length` (default: their length in the scene, no prestress), `damping` and pulley
/// `friction` (its material spread over the segments as in the scene: one strain along it);
/// a cluster without a stiffness is an error naming it.
fn elastic_clusters(s: &Structure) -> Result<Vec<ElasticCluster>> {
    let mut out = Vec::with_capacity(s.clusters().len());
    for (c, cl) in s.clusters().iter().enumerate() {
        let Some(stiffness) = cl.stiffness else {
            return Err(PathError::model(
                format!("cluster {c}"),
                "an elastic cluster needs a stiffness (N/m, of the whole cluster) in the scene",
            ));
        };
        let rest_length = cl.rest_length.unwrap_or_else(|| cl.length(s.nodes()));
        let friction = match &cl.friction {
            Some(mu) if !cl.is_frictionless() => {
                let lengths: Vec<f64> = cl
                    .segments()
                    .map(|[a, b]| (s.nodes()[b] - s.nodes()[a]).norm())
                    .collect();
                Some(ClusterFriction::spread(mu.clone(), rest_length, &lengths))
            }
            _ => None,
        };
        out.push(ElasticCluster {
            nodes: cl.nodes.clone(),
            stiffness,
            rest_length,
            damping: cl.damping,
            friction,
        });
    }
    Ok(out)
}

/// The diagonal of the bounding box of `nodes` (m): a structure's size, the scale of its
/// displacements.
///
/// ```
/// use nalgebra::Vector3;
/// assert_eq!(tensegrity_path::model::extent(&[Vector3::zeros(), Vector3::new(3.0, 4.0, 0.0)]), 5.0);
/// ```
pub fn extent(nodes: &[Vector3<f64>]) -> f64 {
    let Some(first) = nodes.first() else {
        return 0.0;
    };
    let (lo, hi) = nodes
        .iter()
        .fold((*first, *first), |(lo, hi), x| (lo.inf(x), hi.sup(x)));
    (hi - lo).norm()
}

/// `bar` or `string`.
pub(crate) fn kind_name(kind: MemberKind) -> &'static str {
    match kind {
        MemberKind::Bar => "bar",
        MemberKind::String => "string",
    }
}
