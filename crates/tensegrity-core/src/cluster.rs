//! [`Cluster`]: a clustered string — one continuous string through several nodes, over
//! pulleys or sliding joints at its inner nodes, so one tension acts along all its segments.
//!
//! A cluster through the nodes n₀, n₁, …, n_p has the segments (n₀, n₁), …, (n_{p−1}, n_p)
//! and the length L = Σ_i ‖x_{n_{i+1}} − x_{n_i}‖. Linear elastic, tension-only, like a
//! string: its tension is
//!
//! > t = k (L − L₀) when L > L₀, else 0,
//!
//! k its `stiffness` (N/m, of the whole cluster: EA/L₀) and L₀ its `rest_length` (m), plus
//! c dL/dt with its `damping` c (N·s/m) while taut. Frictionless (the default), the tension
//! is the same in every segment: on segment i it pulls its two nodes toward each other with
//! t e_i, e_i its unit vector. A pulley with friction coefficient μ at inner node n_i (its
//! `friction`, one value per inner node) lets the tensions on its two sides differ up to the
//! capstan law t_out ≤ t_in e^{μθ}, θ the wrap angle (the angle between the two segments'
//! directions at the node).
//!
//! With the segments' force densities q_i = t/l_i the cluster adds to the equilibrium of
//! node j the force Σ_i t e_i over the segments at j: the clustering of the segments
//! (CTSFEM's A Sᵀ, one column per cluster instead of one per segment).

use crate::error::{CoreError, ModelError};
use nalgebra::Vector3;

/// A clustered string through `nodes` (in order; inner nodes are pulleys). Built with
/// [`Cluster::new`] and its setters, added with
/// [`StructureBuilder::cluster`](crate::StructureBuilder::cluster); the builder checks it
/// ([`Cluster::check`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Cluster {
    /// The nodes it passes through, in order (at least three: two segments).
    pub nodes: Vec<usize>,
    /// Axial stiffness k of the whole cluster (N/m; EA/L₀).
    pub stiffness: Option<f64>,
    /// Rest length L₀ of the whole cluster (m).
    pub rest_length: Option<f64>,
    /// Damping coefficient c on the rate of its length (N·s/m; 0: undamped).
    pub damping: f64,
    /// The friction coefficient μ of the pulley at each inner node (`nodes.len() − 2`
    /// values); `None`: frictionless.
    pub friction: Option<Vec<f64>>,
    /// Material name (sizing).
    pub material: Option<String>,
}

impl Cluster {
    /// A frictionless cluster through `nodes`, with no other property.
    ///
    /// ```
    /// use tensegrity_core::Cluster;
    /// let c = Cluster::new([0, 3, 5]).stiffness(1e3).rest_length(2.0);
    /// assert_eq!(c.segments().collect::<Vec<_>>(), vec![[0, 3], [3, 5]]);
    /// assert_eq!((c.stiffness, c.rest_length, c.damping), (Some(1e3), Some(2.0), 0.0));
    /// ```
    pub fn new<I: IntoIterator<Item = usize>>(nodes: I) -> Self {
        Self {
            nodes: nodes.into_iter().collect(),
            stiffness: None,
            rest_length: None,
            damping: 0.0,
            friction: None,
            material: None,
        }
    }

    /// Sets the axial stiffness k of the whole cluster (N/m).
    ///
    /// ```
    /// use tensegrity_core::Cluster;
    /// assert_eq!(Cluster::new([0, 1, 2]).stiffness(50.0).stiffness, Some(50.0));
    /// ```
    pub fn stiffness(mut self, k: f64) -> Self {
        self.stiffness = Some(k);
        self
    }

    /// Sets the rest length L₀ of the whole cluster (m).
    ///
    /// ```
    /// use tensegrity_core::Cluster;
    /// assert_eq!(Cluster::new([0, 1, 2]).rest_length(1.5).rest_length, Some(1.5));
    /// ```
    pub fn rest_length(mut self, l0: f64) -> Self {
        self.rest_length = Some(l0);
        self
    }

    /// Sets the damping coefficient c (N·s/m).
    ///
    /// ```
    /// use tensegrity_core::Cluster;
    /// assert_eq!(Cluster::new([0, 1, 2]).damping(3.0).damping, 3.0);
    /// ```
    pub fn damping(mut self, c: f64) -> Self {
        self.damping = c;
        self
    }

    /// Sets the pulleys' friction coefficients μ, one per inner node.
    ///
    /// ```
    /// use tensegrity_core::Cluster;
    /// let c = Cluster::new([0, 1, 2, 3]).friction([0.1, 0.2]);
    /// assert_eq!(c.friction, Some(vec![0.1, 0.2]));
    /// assert!(!c.is_frictionless());
    /// ```
    pub fn friction<I: IntoIterator<Item = f64>>(mut self, mu: I) -> Self {
        self.friction = Some(mu.into_iter().collect());
        self
    }

    /// Sets the material name (sizing).
    ///
    /// ```
    /// use tensegrity_core::Cluster;
    /// assert_eq!(Cluster::new([0, 1, 2]).material("dyneema").material.as_deref(), Some("dyneema"));
    /// ```
    pub fn material(mut self, name: &str) -> Self {
        self.material = Some(name.to_string());
        self
    }

    /// Whether every pulley is frictionless (no `friction`, or all zero).
    pub fn is_frictionless(&self) -> bool {
        self.friction
            .as_ref()
            .is_none_or(|mu| mu.iter().all(|&m| m == 0.0))
    }

    /// The segments, as node pairs in order.
    pub fn segments(&self) -> impl Iterator<Item = [usize; 2]> + '_ {
        self.nodes.windows(2).map(|w| [w[0], w[1]])
    }

    /// The inner nodes (the pulleys).
    ///
    /// ```
    /// use tensegrity_core::Cluster;
    /// assert_eq!(Cluster::new([4, 1, 2, 0]).inner_nodes(), &[1, 2]);
    /// ```
    pub fn inner_nodes(&self) -> &[usize] {
        &self.nodes[1..self.nodes.len().saturating_sub(1).max(1)]
    }

    /// Its length L = Σ segment lengths at the node positions `x` (m).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_core::Cluster;
    /// let x = [Vector3::zeros(), Vector3::new(3.0, 4.0, 0.0), Vector3::new(3.0, 4.0, 1.0)];
    /// assert_eq!(Cluster::new([0, 1, 2]).length(&x), 6.0);
    /// ```
    pub fn length(&self, x: &[Vector3<f64>]) -> f64 {
        self.segments().map(|[a, b]| (x[b] - x[a]).norm()).sum()
    }

    /// Checks the cluster numbered `k` against `n` nodes at `x`: at least three nodes, each
    /// in range, no segment of zero length (two consecutive nodes equal or coincident), its
    /// stiffness and rest length positive and finite where given, its damping and friction
    /// coefficients non-negative and finite, one friction coefficient per inner node. The
    /// error names `cluster k`.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_core::Cluster;
    /// let x = vec![Vector3::zeros(), Vector3::x(), Vector3::y()];
    /// assert!(Cluster::new([0, 1, 2]).check(0, &x).is_ok());
    /// let e = Cluster::new([0, 1]).check(3, &x).unwrap_err().to_string();
    /// assert_eq!(e, "cluster 3: passes through 2 node(s): a cluster runs through at least three (two segments); give a two-node string as [[strings]]");
    /// let e = Cluster::new([0, 1, 2]).friction([0.1, 0.2]).check(0, &x).unwrap_err().to_string();
    /// assert!(e.contains("2 friction coefficient(s) for 1 inner node(s)"), "{e}");
    /// ```
    pub fn check(&self, k: usize, x: &[Vector3<f64>]) -> Result<(), CoreError> {
        let item = || format!("cluster {k}");
        let invalid = |reason: String| -> CoreError {
            ModelError::InvalidCluster { cluster: k, reason }.into()
        };
        if self.nodes.len() < 3 {
            return Err(invalid(format!(
                "passes through {} node(s): a cluster runs through at least three (two segments); give a two-node string as [[strings]]",
                self.nodes.len()
            )));
        }
        let n = x.len();
        if let Some(&bad) = self.nodes.iter().find(|&&i| i >= n) {
            return Err(ModelError::NodeIndexOutOfRange {
                item: item(),
                node: bad,
                n_nodes: n,
            }
            .into());
        }
        for (s, [a, b]) in self.segments().enumerate() {
            let length = (x[b] - x[a]).norm();
            if a == b || length == 0.0 {
                return Err(invalid(format!(
                    "segment {s} (nodes {a} and {b}) has zero length"
                )));
            }
            if !length.is_finite() {
                return Err(invalid(format!(
                    "segment {s} (nodes {a} and {b}): its length overflows double precision: scale the structure down"
                )));
            }
        }
        for (name, value) in [
            ("stiffness", self.stiffness),
            ("rest_length", self.rest_length),
        ] {
            if let Some(v) = value.filter(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(ModelError::NonPositiveConstant {
                    item: item(),
                    name,
                    value: v,
                }
                .into());
            }
        }
        let mut non_negative = vec![("damping", self.damping)];
        if let Some(mu) = &self.friction {
            let inner = self.nodes.len() - 2;
            if mu.len() != inner {
                return Err(invalid(format!(
                    "{} friction coefficient(s) for {inner} inner node(s): give one per pulley",
                    mu.len()
                )));
            }
            non_negative.extend(mu.iter().map(|&m| ("friction", m)));
        }
        for (name, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(ModelError::NegativeConstant {
                    item: item(),
                    name,
                    value,
                }
                .into());
            }
        }
        Ok(())
    }
}
