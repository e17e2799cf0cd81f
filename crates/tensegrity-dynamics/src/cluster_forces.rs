//! Clustered strings in the rigid-bar dynamics: a force element, like a string, through the
//! nodes n₀, …, n_p over frictionless pulleys (`tensegrity_core::Cluster`). With the
//! segments' unit vectors e_i (from n_i to n_{i+1}) and the length L = Σ_i l_i,
//!
//! > t = k (L − L₀) + c L̇ while L > L₀ (clipped at zero), else 0,   L̇ = Σ_i e_iᵀ(v_{i+1} − v_i),
//!
//! and on each segment t pulls its two ends toward each other: +t e_i on n_i, −t e_i on
//! n_{i+1} (one tension along all the segments). Its potential ½ k (L − L₀)₊² enters the
//! energy monitor ([`ClusterData::potential`]), so a frictionless, undamped cluster keeps
//! the drift checks honest. Every node of a cluster is a bar node (its representative
//! class-1 copy, which also carries its strings) or a node fixed in all three directions; a
//! free node on no bar has no mass and is refused (`FreeNodeWithoutBar`). Pulley friction is
//! modelled by the elastic dynamics only (`tensegrity_path::clusters`): here such a cluster
//! is refused, naming it and the elastic run. An `[[actuation]]` table naming the
//! cluster drives its rest length L₀(t) (the model's rest-length schedule holds the strings'
//! rest lengths, then the clusters'): one actuator changes all its segments.

use nalgebra::Vector3;

/// Where a cluster's node lives: a class-1 node (its index), or a fixed point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClusterEnd {
    /// A class-1 node.
    Free(usize),
    /// A fixed point.
    Fixed(Vector3<f64>),
}

/// A clustered string of the rigid-bar model (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterData {
    /// Its nodes in order.
    pub ends: Vec<ClusterEnd>,
    /// Stiffness k of the whole cluster (N/m).
    pub stiffness: f64,
    /// Rest length L₀ of the whole cluster (m).
    pub rest_length: f64,
    /// Damping c on L̇ (N·s/m).
    pub damping: f64,
}

impl ClusterData {
    fn position(end: ClusterEnd, x: &[f64]) -> Vector3<f64> {
        match end {
            ClusterEnd::Free(i) => Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]),
            ClusterEnd::Fixed(p) => p,
        }
    }

    /// Its length L at class-1 positions `x` (m).
    pub fn length(&self, x: &[f64]) -> f64 {
        self.ends
            .windows(2)
            .map(|w| (Self::position(w[1], x) - Self::position(w[0], x)).norm())
            .sum()
    }

    /// Its tension t at class-1 positions `x` and velocities `v` (N; module docs).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_dynamics::cluster_forces::{ClusterData, ClusterEnd};
    /// let c = ClusterData {
    ///     ends: vec![ClusterEnd::Free(0), ClusterEnd::Fixed(Vector3::zeros()), ClusterEnd::Free(1)],
    ///     stiffness: 100.0, rest_length: 1.5, damping: 2.0,
    /// };
    /// let x = [0.0, 0.0, -1.0, 0.0, 0.0, -1.0];
    /// // L = 2, both ends moving down at 1 m/s: L̇ = 2
    /// let v = [0.0, 0.0, -1.0, 0.0, 0.0, -1.0];
    /// assert_eq!(c.tension(&x, &v), 100.0 * 0.5 + 2.0 * 2.0);
    /// assert_eq!(c.potential(&x), 0.5 * 100.0 * 0.25);
    /// ```
    pub fn tension(&self, x: &[f64], v: &[f64]) -> f64 {
        self.tension_at_rest_length(x, v, self.rest_length)
    }

    /// [`ClusterData::tension`] with the rest length `rest` (an actuated one at its time).
    pub fn tension_at_rest_length(&self, x: &[f64], v: &[f64], rest: f64) -> f64 {
        let mut length = 0.0;
        let mut rate = 0.0;
        for w in self.ends.windows(2) {
            let d = Self::position(w[1], x) - Self::position(w[0], x);
            let l = d.norm();
            length += l;
            if self.damping != 0.0 {
                rate += d.dot(&(Self::position_rate(w[1], v) - Self::position_rate(w[0], v))) / l;
            }
        }
        if length <= rest {
            return 0.0;
        }
        (self.stiffness * (length - rest) + self.damping * rate).max(0.0)
    }

    fn position_rate(end: ClusterEnd, v: &[f64]) -> Vector3<f64> {
        match end {
            ClusterEnd::Free(i) => Vector3::new(v[3 * i], v[3 * i + 1], v[3 * i + 2]),
            ClusterEnd::Fixed(_) => Vector3::zeros(),
        }
    }

    /// Adds its forces at (x, v) with the rest length `rest` to the class-1 forces `f`;
    /// returns its tension (N).
    pub fn add_forces(&self, x: &[f64], v: &[f64], rest: f64, f: &mut [Vector3<f64>]) -> f64 {
        let t = self.tension_at_rest_length(x, v, rest);
        if t == 0.0 {
            return 0.0;
        }
        for w in self.ends.windows(2) {
            let d = Self::position(w[1], x) - Self::position(w[0], x);
            let pull = d * (t / d.norm());
            if let ClusterEnd::Free(i) = w[0] {
                f[i] += pull;
            }
            if let ClusterEnd::Free(j) = w[1] {
                f[j] -= pull;
            }
        }
        t
    }

    /// Its potential energy ½ k (L − L₀)² while taut (J).
    pub fn potential(&self, x: &[f64]) -> f64 {
        self.potential_at(x, self.rest_length)
    }

    /// Its potential energy ½ k (L − r)² while taut (J) at rest length `r`.
    pub fn potential_at(&self, x: &[f64], r: f64) -> f64 {
        let e = (self.length(x) - r).max(0.0);
        0.5 * self.stiffness * e * e
    }
}
