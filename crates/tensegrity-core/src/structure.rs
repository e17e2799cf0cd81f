//! The structure model: nodes N (3×n), bars, strings, supports, loads and gravity.
//!
//! A [`Structure`] can only be obtained from [`StructureBuilder::build`], which validates every
//! item and reports the first problem as a [`CoreError`] naming it. Members are numbered bars
//! first, then strings, both in insertion order; that order is used by every analysis
//! (force-density vectors, self-stress bases, ...).
//!
//! Building works by indices: members are checked without hash maps or text labels, a
//! member's or node's name (`bar 3`, `node 7`) being formatted only for the error that
//! reports it (the `checks` submodule).

use crate::cluster::Cluster;
use crate::error::{ModelError, Result};
use crate::material::{Material, MaterialTable};
pub use crate::member_id::MemberId;
use nalgebra::{Matrix3xX, Vector3};

mod checks;

/// A compressive member, rigid in dynamics, elastic in stiffness analysis when it has a
/// material and a radius.
#[derive(Debug, Clone, PartialEq)]
pub struct Bar {
    /// Start and end node (the member vector is `n[end] − n[start]`).
    pub nodes: [usize; 2],
    /// Mass in kg (dynamics, gravity, modal analysis).
    pub mass: Option<f64>,
    /// Material name (sizing, axial stiffness).
    pub material: Option<String>,
    /// Cross-section radius in m (axial stiffness E·πr²/l).
    pub radius: Option<f64>,
}

impl Bar {
    /// A bar from `start` to `end` with no other property.
    ///
    /// ```
    /// use tensegrity_core::Bar;
    /// let bar = Bar::new(0, 1).mass(1.5).material("steel");
    /// assert_eq!(bar.nodes, [0, 1]);
    /// assert_eq!(bar.mass, Some(1.5));
    /// ```
    pub fn new(start: usize, end: usize) -> Self {
        Self {
            nodes: [start, end],
            mass: None,
            material: None,
            radius: None,
        }
    }

    /// Sets the mass (kg).
    pub fn mass(mut self, mass: f64) -> Self {
        self.mass = Some(mass);
        self
    }

    /// Sets the material name.
    pub fn material(mut self, name: &str) -> Self {
        self.material = Some(name.to_string());
        self
    }

    /// Sets the cross-section radius (m).
    ///
    /// ```
    /// use tensegrity_core::Bar;
    /// assert_eq!(Bar::new(0, 1).radius(0.01).radius, Some(0.01));
    /// ```
    pub fn radius(mut self, radius: f64) -> Self {
        self.radius = Some(radius);
        self
    }
}

/// A tension-only member: linear elastic with a rest length, optionally damped.
#[derive(Debug, Clone, PartialEq)]
pub struct StringMember {
    /// Start and end node.
    pub nodes: [usize; 2],
    /// Axial stiffness k in N/m.
    pub stiffness: Option<f64>,
    /// Rest length s0 in m.
    pub rest_length: Option<f64>,
    /// Damping coefficient c in N·s/m (0 = undamped).
    pub damping: f64,
    /// Material name (sizing).
    pub material: Option<String>,
}

impl StringMember {
    /// A string from `start` to `end` with no other property.
    ///
    /// ```
    /// use tensegrity_core::StringMember;
    /// let s = StringMember::new(0, 2).stiffness(100.0).rest_length(0.9);
    /// assert_eq!(s.stiffness, Some(100.0));
    /// assert_eq!(s.rest_length, Some(0.9));
    /// ```
    pub fn new(start: usize, end: usize) -> Self {
        Self {
            nodes: [start, end],
            stiffness: None,
            rest_length: None,
            damping: 0.0,
            material: None,
        }
    }

    /// Sets the axial stiffness k (N/m).
    pub fn stiffness(mut self, k: f64) -> Self {
        self.stiffness = Some(k);
        self
    }

    /// Sets the rest length s0 (m).
    pub fn rest_length(mut self, s0: f64) -> Self {
        self.rest_length = Some(s0);
        self
    }

    /// Sets the damping coefficient c (N·s/m).
    ///
    /// ```
    /// use tensegrity_core::StringMember;
    /// assert_eq!(StringMember::new(0, 1).damping(2.0).damping, 2.0);
    /// ```
    pub fn damping(mut self, c: f64) -> Self {
        self.damping = c;
        self
    }

    /// Sets the material name.
    ///
    /// ```
    /// use tensegrity_core::StringMember;
    /// assert_eq!(StringMember::new(0, 1).material("steel").material.as_deref(), Some("steel"));
    /// ```
    pub fn material(mut self, name: &str) -> Self {
        self.material = Some(name.to_string());
        self
    }
}

/// A node held in some directions: some (by default all) of x, y, z, and any further
/// directions of any orientation ([`Support::along`]); rigidly, or by a spring of stiffness k
/// along each held direction ([`Support::elastic`]).
///
/// The held directions are the flagged axes (`fixed`, in x, y, z order) followed by the
/// `along` directions; together they must be unit vectors (to [`UNIT_TOLERANCE`]), finite and
/// independent (one to three), which [`StructureBuilder::build`] checks, naming the support.
/// Analyses that read only the axes ([`Structure::fixed_dofs`]: the dynamics) see the `fixed`
/// flags alone; front ends refuse to hand them a support with `along` directions or a
/// stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// The supported node.
    pub node: usize,
    /// Which of x, y, z are held.
    pub fixed: [bool; 3],
    /// Further held directions of any orientation (unit vectors), after the flagged axes.
    pub along: Vec<Vector3<f64>>,
    /// The stiffness k (N/m) of a spring along each held direction (an elastic support);
    /// `None`: held rigidly.
    pub stiffness: Option<f64>,
}

/// How far from 1 the norm of a support's `along` direction may be (absolute): a direction
/// is a unit vector, and a wrong one (a normal not normalised, a typo) is refused rather
/// than silently normalised.
pub const UNIT_TOLERANCE: f64 = 1e-6;

impl Support {
    /// A node fixed in all three directions.
    ///
    /// ```
    /// use tensegrity_core::Support;
    /// assert_eq!(Support::pinned(3).fixed, [true; 3]);
    /// ```
    pub fn pinned(node: usize) -> Self {
        Self::directions(node, [true; 3])
    }

    /// A node fixed only in the directions flagged `true` (x, y, z).
    ///
    /// ```
    /// use tensegrity_core::Support;
    /// let roller = Support::directions(0, [false, false, true]);
    /// assert_eq!(roller.fixed, [false, false, true]);
    /// ```
    pub fn directions(node: usize, fixed: [bool; 3]) -> Self {
        Self {
            node,
            fixed,
            along: Vec::new(),
            stiffness: None,
        }
    }

    /// A node held along directions of any orientation (unit vectors, one to three,
    /// independent), none of x, y, z flagged: a roller on an incline is held along the
    /// incline's normal.
    ///
    /// ```
    /// use tensegrity_core::Support;
    /// // a roller on a 30° incline: held along its normal (−sin 30°, 0, cos 30°)
    /// let (s, c) = 30f64.to_radians().sin_cos();
    /// let roller = Support::along(1, [[-s, 0.0, c]]);
    /// assert_eq!((roller.fixed, roller.along.len()), ([false; 3], 1));
    /// assert_eq!(roller.held_directions()[0].z, c);
    /// ```
    pub fn along<I: IntoIterator<Item = [f64; 3]>>(node: usize, directions: I) -> Self {
        Self {
            along: directions.into_iter().map(Vector3::from).collect(),
            ..Self::directions(node, [false; 3])
        }
    }

    /// The same support held by a spring of stiffness `k` (N/m) along each held direction
    /// instead of rigidly.
    ///
    /// ```
    /// use tensegrity_core::Support;
    /// let spring = Support::directions(2, [false, false, true]).elastic(1e4);
    /// assert_eq!((spring.stiffness, spring.is_elastic()), (Some(1e4), true));
    /// assert!(!Support::pinned(0).is_elastic());
    /// ```
    pub fn elastic(mut self, k: f64) -> Self {
        self.stiffness = Some(k);
        self
    }

    /// Whether the support is a spring ([`Support::elastic`]).
    pub fn is_elastic(&self) -> bool {
        self.stiffness.is_some()
    }

    /// The held directions: the flagged axes (x, y, z order), then the `along` directions.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_core::Support;
    /// let mut s = Support::directions(0, [false, false, true]);
    /// s.along.push(Vector3::new(0.6, 0.8, 0.0));
    /// assert_eq!(s.held_directions(), vec![Vector3::z(), Vector3::new(0.6, 0.8, 0.0)]);
    /// ```
    pub fn held_directions(&self) -> Vec<Vector3<f64>> {
        (0..3)
            .filter(|&d| self.fixed[d])
            .map(|d| Vector3::ith(d, 1.0))
            .chain(self.along.iter().copied())
            .collect()
    }

    /// An orthonormal basis of the span of the held directions (Gram–Schmidt in the order of
    /// [`Support::held_directions`]), or why there is none: a direction that is not finite,
    /// not of unit norm (to [`UNIT_TOLERANCE`]), or dependent on the ones before it (a
    /// residual below 10⁻⁹). The message names the direction, not the support.
    ///
    /// ```
    /// use tensegrity_core::Support;
    /// let basis = Support::along(0, [[0.6, 0.8, 0.0], [0.0, 0.0, 1.0]]).held_basis().unwrap();
    /// assert_eq!(basis.len(), 2);
    /// let e = Support::along(0, [[0.6, 0.8, 0.0], [-0.6, -0.8, 0.0]]).held_basis().unwrap_err();
    /// assert!(e.contains("dependent"), "{e}");
    /// let e = Support::along(0, [[1.0, 1.0, 0.0]]).held_basis().unwrap_err();
    /// assert!(e.contains("norm 1.414"), "{e}");
    /// ```
    pub fn held_basis(&self) -> std::result::Result<Vec<Vector3<f64>>, String> {
        let n_fixed = self.fixed.iter().filter(|&&f| f).count();
        let mut basis: Vec<Vector3<f64>> = Vec::with_capacity(3);
        for (h, d) in self.held_directions().into_iter().enumerate() {
            let name = || match h.checked_sub(n_fixed) {
                Some(a) => format!("along direction {a} {}", show(&d)),
                None => format!("direction {}", show(&d)),
            };
            if !d.iter().all(|v| v.is_finite()) {
                return Err(format!("{} is not finite", name()));
            }
            let norm = d.norm();
            if (norm - 1.0).abs() > UNIT_TOLERANCE {
                let hint = if norm > 0.0 {
                    format!(", e.g. {}", show(&(d / norm)))
                } else {
                    String::new()
                };
                return Err(format!(
                    "{} has norm {norm:.6}, not 1: give a unit vector (to {UNIT_TOLERANCE:e}){hint}",
                    name()
                ));
            }
            let mut v = d / norm;
            for b in &basis {
                v -= b * b.dot(&v);
            }
            if basis.len() == 3 || v.norm() < 1e-9 {
                return Err(format!(
                    "{} is dependent on the held directions before it (a direction repeated, or in the plane of two others): give one to three independent directions",
                    name()
                ));
            }
            basis.push(v.normalize());
        }
        Ok(basis)
    }
}

/// A direction as `[x, y, z]` (shortest round-trip numbers), for messages.
fn show(v: &Vector3<f64>) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

/// An external force applied at a node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Load {
    /// The loaded node.
    pub node: usize,
    /// The force in N.
    pub force: Vector3<f64>,
}

/// A validated tensegrity structure.
#[derive(Debug, Clone, PartialEq)]
pub struct Structure {
    nodes: Vec<Vector3<f64>>,
    velocities: Option<Vec<Vector3<f64>>>,
    bars: Vec<Bar>,
    strings: Vec<StringMember>,
    clusters: Vec<Cluster>,
    supports: Vec<Support>,
    loads: Vec<Load>,
    gravity: Option<Vector3<f64>>,
    materials: MaterialTable,
}

impl Structure {
    /// Starts a builder.
    ///
    /// ```
    /// use tensegrity_core::{Bar, StringMember, Structure, Support};
    /// let s = Structure::builder()
    ///     .node([0.0, 0.0, 0.0])
    ///     .node([1.0, 0.0, 0.0])
    ///     .node([0.0, 1.0, 0.0])
    ///     .bar(Bar::new(0, 1))
    ///     .string(StringMember::new(1, 2))
    ///     .string(StringMember::new(2, 0))
    ///     .support(Support::pinned(0))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.n_members(), 3);
    /// ```
    pub fn builder() -> StructureBuilder {
        StructureBuilder::default()
    }

    /// Node positions, one per node.
    pub fn nodes(&self) -> &[Vector3<f64>] {
        &self.nodes
    }

    /// The node matrix N (3×n, column i = node i).
    #[allow(non_snake_case)]
    pub fn N(&self) -> Matrix3xX<f64> {
        Matrix3xX::from_columns(&self.nodes)
    }

    /// Initial node velocities, if given.
    pub fn velocities(&self) -> Option<&[Vector3<f64>]> {
        self.velocities.as_deref()
    }

    /// The bars.
    pub fn bars(&self) -> &[Bar] {
        &self.bars
    }

    /// The strings.
    pub fn strings(&self) -> &[StringMember] {
        &self.strings
    }

    /// The clustered strings ([`Cluster`]): continuous strings through several nodes.
    pub fn clusters(&self) -> &[Cluster] {
        &self.clusters
    }

    /// Whether the structure has clustered strings: an analysis that does not model them
    /// refuses the structure rather than leave them out ([`Structure::refuse_clusters`]).
    pub fn has_clusters(&self) -> bool {
        !self.clusters.is_empty()
    }

    /// Refuses a structure with clustered strings for an `analysis` that does not model
    /// them, naming the first cluster.
    ///
    /// ```
    /// use tensegrity_core::{Cluster, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0]])
    ///     .cluster(Cluster::new([0, 1, 2]))
    ///     .build()
    ///     .unwrap();
    /// let e = s.refuse_clusters("the rigid-bar dynamics").unwrap_err().to_string();
    /// assert!(e.starts_with("cluster 0: clustered strings are not modelled by the rigid-bar dynamics"), "{e}");
    /// ```
    pub fn refuse_clusters(&self, analysis: &'static str) -> Result<()> {
        match self.clusters.is_empty() {
            true => Ok(()),
            false => Err(ModelError::ClustersNotModelled {
                cluster: 0,
                analysis,
            }
            .into()),
        }
    }

    /// The supports.
    pub fn supports(&self) -> &[Support] {
        &self.supports
    }

    /// The nodal loads.
    pub fn loads(&self) -> &[Load] {
        &self.loads
    }

    /// The gravitational acceleration, if any (m/s²).
    pub fn gravity(&self) -> Option<Vector3<f64>> {
        self.gravity
    }

    /// The material table (built-in plus user materials).
    pub fn materials(&self) -> &MaterialTable {
        &self.materials
    }

    /// Number of nodes n.
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// Number of bars β.
    pub fn n_bars(&self) -> usize {
        self.bars.len()
    }

    /// Number of strings α.
    pub fn n_strings(&self) -> usize {
        self.strings.len()
    }

    /// Number of members β + α.
    pub fn n_members(&self) -> usize {
        self.bars.len() + self.strings.len()
    }

    /// The member in column `k` of the member ordering (bars first, then strings).
    pub fn member_id(&self, k: usize) -> MemberId {
        if k < self.bars.len() {
            MemberId::Bar(k)
        } else {
            MemberId::String(k - self.bars.len())
        }
    }

    /// The column of `id` in the member ordering.
    pub fn member_index(&self, id: MemberId) -> usize {
        match id {
            MemberId::Bar(i) => i,
            MemberId::String(i) => self.bars.len() + i,
        }
    }

    /// End nodes `[start, end]` of every member, bars first.
    pub fn member_nodes(&self) -> Vec<[usize; 2]> {
        self.bars
            .iter()
            .map(|b| b.nodes)
            .chain(self.strings.iter().map(|s| s.nodes))
            .collect()
    }

    /// Member vector `n[end] − n[start]` of member column `k`.
    pub fn member_vector(&self, k: usize) -> Vector3<f64> {
        let [i, j] = self.member_nodes_of(k);
        self.nodes[j] - self.nodes[i]
    }

    /// Length of every member, bars first.
    pub fn member_lengths(&self) -> Vec<f64> {
        (0..self.n_members())
            .map(|k| self.member_vector(k).norm())
            .collect()
    }

    fn member_nodes_of(&self, k: usize) -> [usize; 2] {
        match self.member_id(k) {
            MemberId::Bar(i) => self.bars[i].nodes,
            MemberId::String(i) => self.strings[i].nodes,
        }
    }

    /// The mass of bar `k` (kg): its `mass`, or else ρ π r² l from its material's density, its
    /// radius and its length; `None` when it has neither.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Material, Structure};
    /// let s = Structure::builder()
    ///     .node([0.0, 0.0, 0.0]).node([2.0, 0.0, 0.0])
    ///     .material("m", Material::new(1000.0, 1e9, 1e6))
    ///     .bar(Bar::new(0, 1).material("m").radius(0.1))
    ///     .build().unwrap();
    /// let m = s.bar_mass(0).unwrap();
    /// assert!((m - 1000.0 * std::f64::consts::PI * 0.01 * 2.0).abs() < 1e-12);
    /// ```
    pub fn bar_mass(&self, k: usize) -> Option<f64> {
        let bar = &self.bars[k];
        bar.mass.or_else(|| {
            let material = self.member_material(MemberId::Bar(k))?;
            let r = bar.radius?;
            let [a, b] = bar.nodes;
            Some(
                material.density
                    * std::f64::consts::PI
                    * r
                    * r
                    * (self.nodes[b] - self.nodes[a]).norm(),
            )
        })
    }

    /// The material of member `id`, if it names one.
    pub fn member_material(&self, id: MemberId) -> Option<&Material> {
        let name = match id {
            MemberId::Bar(i) => self.bars[i].material.as_deref(),
            MemberId::String(i) => self.strings[i].material.as_deref(),
        }?;
        self.materials.get(name)
    }

    /// For each node, which of x, y, z its support flags (`fixed`). A support's `along`
    /// directions and its stiffness are not seen here: the statics and the load paths read
    /// the supports themselves ([`Structure::supports`], [`Support::held_basis`]).
    pub fn fixed_dofs(&self) -> Vec<[bool; 3]> {
        let mut fixed = vec![[false; 3]; self.nodes.len()];
        for s in &self.supports {
            for d in 0..3 {
                fixed[s.node][d] |= s.fixed[d];
            }
        }
        fixed
    }

    /// Number of bars meeting at each node.
    pub fn bars_per_node(&self) -> Vec<usize> {
        let mut count = vec![0; self.nodes.len()];
        for b in &self.bars {
            count[b.nodes[0]] += 1;
            count[b.nodes[1]] += 1;
        }
        count
    }

    /// Class-k joints: `(node, k)` for every node shared by k ≥ 2 bars.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .bar(Bar::new(0, 2))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.class_k_nodes(), vec![(0, 2)]);
    /// ```
    pub fn class_k_nodes(&self) -> Vec<(usize, usize)> {
        self.bars_per_node()
            .into_iter()
            .enumerate()
            .filter(|&(_, k)| k >= 2)
            .collect()
    }

    /// The class of the structure: the largest number of bars meeting at a node (at least 1).
    pub fn class(&self) -> usize {
        self.bars_per_node().into_iter().max().unwrap_or(0).max(1)
    }

    /// The total external nodal force matrix W (3×n): loads plus, when gravity is set, half of
    /// each bar's weight at each of its ends.
    #[allow(non_snake_case)]
    pub fn W(&self) -> Matrix3xX<f64> {
        let mut w = Matrix3xX::zeros(self.nodes.len());
        for l in &self.loads {
            let mut col = w.column_mut(l.node);
            col += l.force;
        }
        if let Some(g) = self.gravity {
            for b in &self.bars {
                if let Some(m) = b.mass {
                    for &i in &b.nodes {
                        let mut col = w.column_mut(i);
                        col += 0.5 * m * g;
                    }
                }
            }
        }
        w
    }

    /// Whether any external load acts (nodal loads, or gravity on massive bars).
    pub fn is_loaded(&self) -> bool {
        !self.loads.is_empty()
            || (self.gravity.is_some_and(|g| g.norm() > 0.0)
                && self.bars.iter().any(|b| b.mass.is_some()))
    }

    /// A copy with new node positions (same topology and properties), validated again.
    pub fn with_nodes(&self, nodes: Vec<Vector3<f64>>) -> Result<Structure> {
        let mut b = self.to_builder();
        b.nodes = nodes;
        b.build()
    }

    /// A copy with its members' properties replaced (masses, stiffnesses, rest lengths,
    /// dampings): `bars` and `strings` must be the same members in the same order (each the
    /// same node pair), else the error names the first that is not; validated again.
    ///
    /// ```
    /// use tensegrity_core::{Bar, StringMember, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    ///     .bar(Bar::new(0, 1).mass(1.0))
    ///     .string(StringMember::new(1, 2).stiffness(100.0))
    ///     .build()
    ///     .unwrap();
    /// let mut strings = s.strings().to_vec();
    /// strings[0].damping = 2.0;
    /// let t = s.with_members(s.bars().to_vec(), strings).unwrap();
    /// assert_eq!(t.strings()[0].damping, 2.0);
    /// assert!(s.with_members(vec![], s.strings().to_vec()).is_err());
    /// ```
    pub fn with_members(&self, bars: Vec<Bar>, strings: Vec<StringMember>) -> Result<Structure> {
        let same = |what: &str, k: usize, a: [usize; 2], b: Option<[usize; 2]>| {
            if b == Some(a) {
                Ok(())
            } else {
                Err(crate::request::InvalidParameter::raw(
                    format!("{what} {k}"),
                    format!("{a:?}"),
                    "not the structure's member (the same members, in order, are replaced)",
                ))
            }
        };
        for (what, found, expected) in [
            ("bars", bars.len(), self.bars.len()),
            ("strings", strings.len(), self.strings.len()),
        ] {
            if found != expected {
                let what = what.to_string();
                return Err(ModelError::LengthMismatch {
                    what,
                    expected,
                    found,
                }
                .into());
            }
        }
        for (k, b) in bars.iter().enumerate() {
            same("bar", k, b.nodes, self.bars.get(k).map(|x| x.nodes))?;
        }
        for (k, s) in strings.iter().enumerate() {
            same("string", k, s.nodes, self.strings.get(k).map(|x| x.nodes))?;
        }
        let mut b = self.to_builder();
        b.bars = bars;
        b.strings = strings;
        b.build()
    }

    /// A builder holding everything in this structure except its strings (to re-add them
    /// with new properties, in order).
    pub fn to_builder_without_strings(&self) -> StructureBuilder {
        let mut b = self.to_builder();
        b.strings.clear();
        b
    }

    /// A builder holding everything in this structure, to modify and rebuild.
    pub fn to_builder(&self) -> StructureBuilder {
        StructureBuilder {
            nodes: self.nodes.clone(),
            velocities: self.velocities.clone(),
            bars: self.bars.clone(),
            strings: self.strings.clone(),
            clusters: self.clusters.clone(),
            supports: self.supports.clone(),
            loads: self.loads.clone(),
            gravity: self.gravity,
            materials: self.materials.clone(),
            user_materials: Vec::new(),
            allow_isolated: false,
        }
    }
}

/// By-value builder for [`Structure`]; [`build`](StructureBuilder::build) validates.
#[derive(Debug, Clone, Default)]
pub struct StructureBuilder {
    nodes: Vec<Vector3<f64>>,
    velocities: Option<Vec<Vector3<f64>>>,
    bars: Vec<Bar>,
    strings: Vec<StringMember>,
    clusters: Vec<Cluster>,
    supports: Vec<Support>,
    loads: Vec<Load>,
    gravity: Option<Vector3<f64>>,
    materials: MaterialTable,
    user_materials: Vec<(String, Material)>,
    allow_isolated: bool,
}

impl StructureBuilder {
    /// Appends a node.
    ///
    /// ```
    /// use tensegrity_core::Structure;
    /// let b = Structure::builder().node([0.0, 0.0, 0.0]);
    /// assert!(b.build().is_err()); // no members yet
    /// ```
    pub fn node(mut self, position: [f64; 3]) -> Self {
        self.nodes.push(Vector3::from(position));
        self
    }

    /// Appends several nodes.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.n_nodes(), 2);
    /// ```
    pub fn nodes<I: IntoIterator<Item = [f64; 3]>>(mut self, positions: I) -> Self {
        self.nodes.extend(positions.into_iter().map(Vector3::from));
        self
    }

    /// Sets the initial velocity of every node (one entry per node).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    ///     .velocities([[0.0; 3], [1.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.velocities().unwrap()[1].x, 1.0);
    /// ```
    pub fn velocities<I: IntoIterator<Item = [f64; 3]>>(mut self, velocities: I) -> Self {
        self.velocities = Some(velocities.into_iter().map(Vector3::from).collect());
        self
    }

    /// Appends a bar.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1).mass(1.0))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.n_bars(), 1);
    /// ```
    pub fn bar(mut self, bar: Bar) -> Self {
        self.bars.push(bar);
        self
    }

    /// Appends several bars (in order).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    ///     .bars([Bar::new(0, 1), Bar::new(1, 2)])
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.n_bars(), 2);
    /// ```
    pub fn bars<I: IntoIterator<Item = Bar>>(mut self, bars: I) -> Self {
        self.bars.extend(bars);
        self
    }

    /// Appends several strings (in order).
    ///
    /// ```
    /// use tensegrity_core::{StringMember, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    ///     .strings([StringMember::new(0, 1), StringMember::new(1, 2)])
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.n_strings(), 2);
    /// ```
    pub fn strings<I: IntoIterator<Item = StringMember>>(mut self, strings: I) -> Self {
        self.strings.extend(strings);
        self
    }

    /// Appends a string.
    ///
    /// ```
    /// use tensegrity_core::{StringMember, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .string(StringMember::new(0, 1).stiffness(100.0).rest_length(1.8))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.n_strings(), 1);
    /// ```
    pub fn string(mut self, string: StringMember) -> Self {
        self.strings.push(string);
        self
    }

    /// Appends a clustered string ([`Cluster`]); the build checks it
    /// ([`Cluster::check`]), its segments against the members (a segment duplicating a bar,
    /// a string or another cluster's segment is refused) and its material.
    ///
    /// ```
    /// use tensegrity_core::{Cluster, Structure};
    /// // a string from node 0 over a pulley at node 1 down to node 2
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0]])
    ///     .cluster(Cluster::new([0, 1, 2]).stiffness(1e3).rest_length(2.5))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.clusters().len(), 1);
    /// assert!((s.clusters()[0].length(s.nodes()) - 2.0 * 2f64.sqrt()).abs() < 1e-15);
    /// let twice = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0]])
    ///     .string(tensegrity_core::StringMember::new(2, 1))
    ///     .cluster(Cluster::new([0, 1, 2]))
    ///     .build();
    /// assert_eq!(twice.unwrap_err().to_string(), "cluster 0: segment 1 (nodes 1 and 2) duplicates string 0");
    /// ```
    pub fn cluster(mut self, cluster: Cluster) -> Self {
        self.clusters.push(cluster);
        self
    }

    /// Adds a support (rigid or elastic, along x, y, z or any directions: [`Support`]); the
    /// build checks it, naming it by its index (`support 2: ...`).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure, Support};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .support(Support::pinned(0))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.supports().len(), 1);
    /// ```
    pub fn support(mut self, support: Support) -> Self {
        self.supports.push(support);
        self
    }

    /// Adds a nodal force (N).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .load(1, [-1e4, 0.0, 0.0])
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(s.W()[(0, 1)], -1e4);
    /// ```
    pub fn load(mut self, node: usize, force: [f64; 3]) -> Self {
        self.loads.push(Load {
            node,
            force: Vector3::from(force),
        });
        self
    }

    /// Sets the gravitational acceleration (m/s²).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1).mass(2.0))
    ///     .gravity([0.0, 0.0, -9.81])
    ///     .build()
    ///     .unwrap();
    /// assert!((s.W()[(2, 0)] + 9.81).abs() < 1e-12);
    /// ```
    pub fn gravity(mut self, acceleration: [f64; 3]) -> Self {
        self.gravity = Some(Vector3::from(acceleration));
        self
    }

    /// Adds a user material (shadowing a built-in one of the same name).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Material, Structure};
    /// let s = Structure::builder()
    ///     .material("alu", Material::new(2700.0, 60e9, 110e6))
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1).material("alu"))
    ///     .build()
    ///     .unwrap();
    /// assert!(s.materials().get("alu").is_some());
    /// ```
    pub fn material(mut self, name: &str, material: Material) -> Self {
        self.user_materials.push((name.to_string(), material));
        self
    }

    /// Accepts nodes that no member touches (off by default: an isolated node is usually a
    /// typo, and it makes the equilibrium matrix rank deficient).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// let b = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [5.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1));
    /// assert!(b.clone().build().is_err());
    /// assert!(b.allow_isolated_nodes(true).build().is_ok());
    /// ```
    pub fn allow_isolated_nodes(mut self, allow: bool) -> Self {
        self.allow_isolated = allow;
        self
    }

    /// Validates everything and returns the structure, or the first problem found.
    pub fn build(self) -> Result<Structure> {
        let StructureBuilder {
            nodes,
            velocities,
            bars,
            strings,
            clusters,
            supports,
            loads,
            gravity,
            mut materials,
            user_materials,
            allow_isolated,
        } = self;
        for (name, m) in &user_materials {
            materials.insert(name, *m)?;
        }
        let n = nodes.len();
        for (i, p) in nodes.iter().enumerate() {
            check_finite(|| format!("node {i}"), p)?;
        }
        if let Some(v) = &velocities {
            if v.len() != n {
                return Err(ModelError::LengthMismatch {
                    what: "velocities".into(),
                    expected: n,
                    found: v.len(),
                }
                .into());
            }
            for (i, p) in v.iter().enumerate() {
                check_finite(|| format!("velocity of node {i}"), p)?;
            }
        }
        if bars.is_empty() && strings.is_empty() && clusters.is_empty() {
            return Err(ModelError::NoMembers.into());
        }

        // nodes on a cluster only are not isolated: the clusters are checked after
        checks::check_members(&nodes, &bars, &strings, true)?;
        checks::check_clusters(&nodes, &bars, &strings, &clusters, allow_isolated)?;
        for (k, c) in clusters.iter().enumerate() {
            if let Some(name) = &c.material {
                if materials.get(name).is_none() {
                    materials.lookup(name, &format!("cluster {k}"))?;
                }
            }
        }

        // the item's name is formatted only for an error
        for (i, b) in bars.iter().enumerate() {
            let item = || MemberId::Bar(i).to_string();
            positive(item, "mass", b.mass)?;
            positive(item, "radius", b.radius)?;
            if let Some(name) = &b.material {
                if materials.get(name).is_none() {
                    materials.lookup(name, &item())?;
                }
            }
        }
        for (i, s) in strings.iter().enumerate() {
            let item = || MemberId::String(i).to_string();
            positive(item, "stiffness", s.stiffness)?;
            positive(item, "rest_length", s.rest_length)?;
            if !(s.damping.is_finite() && s.damping >= 0.0) {
                return Err(ModelError::NegativeConstant {
                    item: item(),
                    name: "damping",
                    value: s.damping,
                }
                .into());
            }
            if let Some(name) = &s.material {
                if materials.get(name).is_none() {
                    materials.lookup(name, &item())?;
                }
            }
        }

        let mut supported: Vec<Option<usize>> = vec![None; n];
        for (i, s) in supports.iter().enumerate() {
            if s.node >= n {
                return Err(ModelError::NodeIndexOutOfRange {
                    item: format!("support {i}"),
                    node: s.node,
                    n_nodes: n,
                }
                .into());
            }
            if let Some(other) = supported[s.node] {
                return Err(ModelError::DuplicateSupport {
                    support: i,
                    other,
                    node: s.node,
                }
                .into());
            }
            if !s.fixed.iter().any(|&f| f) && s.along.is_empty() {
                return Err(ModelError::EmptySupport { support: i }.into());
            }
            if let Err(reason) = s.held_basis() {
                return Err(ModelError::InvalidSupport { support: i, reason }.into());
            }
            if let Some(k) = s.stiffness {
                if !(k.is_finite() && k > 0.0) {
                    return Err(ModelError::NonPositiveConstant {
                        item: format!("support {i}"),
                        name: "stiffness",
                        value: k,
                    }
                    .into());
                }
            }
            supported[s.node] = Some(i);
        }
        for (i, l) in loads.iter().enumerate() {
            if l.node >= n {
                return Err(ModelError::NodeIndexOutOfRange {
                    item: format!("load {i}"),
                    node: l.node,
                    n_nodes: n,
                }
                .into());
            }
            check_finite(|| format!("load {i}"), &l.force)?;
        }
        // loads on one node add up: their sum must stay finite too (two loads of 1e308)
        let mut sums = vec![Vector3::zeros(); n];
        for (i, l) in loads.iter().enumerate() {
            sums[l.node] += l.force;
            check_finite(
                || format!("load {i} (the sum of the loads on node {})", l.node),
                &sums[l.node],
            )?;
        }
        if let Some(g) = &gravity {
            check_finite(|| "gravity".to_string(), g)?;
        }

        Ok(Structure {
            nodes,
            velocities,
            bars,
            strings,
            clusters,
            supports,
            loads,
            gravity,
            materials,
        })
    }
}

/// Every component of `v` finite, else an error naming `item()` (formatted only then).
fn check_finite(item: impl Fn() -> String, v: &Vector3<f64>) -> Result<()> {
    match v.iter().position(|value| !value.is_finite()) {
        None => Ok(()),
        Some(d) => Err(ModelError::NonFinite {
            item: item(),
            axis: ['x', 'y', 'z'][d],
            value: v[d],
        }
        .into()),
    }
}

/// A set value must be finite and positive, else an error naming `item()`.
fn positive(item: impl Fn() -> String, name: &'static str, value: Option<f64>) -> Result<()> {
    match value {
        Some(v) if !(v.is_finite() && v > 0.0) => Err(ModelError::NonPositiveConstant {
            item: item(),
            name,
            value: v,
        }
        .into()),
        _ => Ok(()),
    }
}
