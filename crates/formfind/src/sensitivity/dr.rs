//! Exact derivatives of dynamic relaxation's fixed point with held nodes, with respect to the
//! members' rest lengths s0 and axial stiffnesses EA.
//!
//! Member k = (a, b) of length L and unit vector e (from a to b) carries (the `dr` module)
//!
//! > T = EA (L − s0) / s0   (a string: max(T, 0), slack below its rest length),
//!
//! and the out-of-balance force of a free node is R_a = Σ_k T_k e_k over its members (e_k
//! pointing away from it). The found form solves R(X, θ) = 0 on the free nodes, so
//!
//! > K_t ∂X_f/∂θ = ∂R/∂θ,   K_t = −∂R/∂X = Σ_k [(∂T/∂L) e eᵀ + (T/L)(I − e eᵀ)] on the
//! > members' free ends (±, the tangent stiffness),
//!
//! with ∂T/∂L = EA/s0 (zero for a slack string). The parameters enter through T alone:
//! ∂T/∂s0 = −EA L / s0² and ∂T/∂EA = (L − s0) / s0, so ∂R/∂θ is T's derivative times e_k
//! at a and −e_k at b. **Forward** ([`DrSensitivity::forward`]): one sparse LU solve of one
//! column per parameter, the nodes and the tensions (∂T = (∂T/∂L) e · (∂x_b − ∂x_a) + ∂T/∂θ).
//! **Adjoint** ([`DrSensitivity::adjoint`]): K_t λ = ∂f/∂X_f (K_t is symmetric), then
//! df/dθ = λ · ∂R/∂θ, one solve whatever the number of parameters.
//!
//! The form is dynamic relaxation's, converged to its tolerance (relative residual 10⁻¹² on
//! the defaults), so the derivatives hold to about that. A string exactly at its rest length
//! is where T has a kink: its derivative is taken on the slack side. Refused by name: no held
//! nodes (K_t then has the rigid-body motions in its null space), clustered strings, loads
//! (the form finder refuses them for dynamic relaxation), and a singular K_t (a mechanism the
//! held nodes and tensions do not stiffen).

use crate::error::{FormFindError, Result};
use crate::method::{Method, Settings};
use crate::topology::Topology;
use nalgebra::{Matrix3, Vector3};
use tensegrity_linalg::{CscMatrix, SparseLu};

/// A parameter of dynamic relaxation's form (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrParameter {
    /// The rest length s0 of member k (bars then strings).
    RestLength(usize),
    /// The axial stiffness EA of member k.
    Stiffness(usize),
}

/// The derivatives of a form's nodes and tensions with respect to one parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct DrDerivative {
    /// ∂x_i of every node (zero at held nodes).
    pub nodes: Vec<Vector3<f64>>,
    /// ∂T_k of every member's tension (N).
    pub tensions: Vec<f64>,
}

/// The gradient of a scalar objective of the nodes ([`DrSensitivity::adjoint`]).
#[derive(Debug, Clone, PartialEq)]
pub struct DrGradient {
    /// df/ds0_k, one per member.
    pub rest_lengths: Vec<f64>,
    /// df/dEA_k, one per member.
    pub stiffnesses: Vec<f64>,
}

/// Dynamic relaxation's form with held nodes, its tangent stiffness factored (module docs).
pub struct DrSensitivity {
    pairs: Vec<[usize; 2]>,
    rest: Vec<f64>,
    ea: Vec<f64>,
    nodes: Vec<Vector3<f64>>,
    tension: Vec<f64>,
    length: Vec<f64>,
    /// Whether member k's tension follows its length (a bar, or a taut string).
    active: Vec<bool>,
    /// Each node's index among the free ones.
    free_index: Vec<Option<usize>>,
    n_free: usize,
    lu: SparseLu,
}

impl DrSensitivity {
    /// Finds the form of `topology` by dynamic relaxation under `settings` (its method is
    /// taken as `dr`: rest lengths on every member, initial nodes, held nodes) and factors
    /// its tangent stiffness. Refused by name: no held nodes, clusters, loads, a singular
    /// tangent stiffness (module docs), and whatever dynamic relaxation refuses.
    ///
    /// ```
    /// use formfind::sensitivity::{DrParameter, DrSensitivity};
    /// use formfind::{FixedNode, Member, Settings, Topology};
    /// // a node between two anchors 2 m apart, on two strings of rest length 0.8 m and
    /// // stiffness 100 N: it sits in the middle, each string at T = 100 (1 − 0.8)/0.8 = 25 N
    /// let t = Topology {
    ///     n_nodes: 3,
    ///     nodes: Some(vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.1, 0.0, 0.0]]),
    ///     strings: vec![
    ///         Member::new(0, 2).length(0.8).stiffness(100.0),
    ///         Member::new(2, 1).length(0.8).stiffness(100.0),
    ///     ],
    ///     fixed: vec![
    ///         FixedNode { node: 0, position: [-1.0, 0.0, 0.0] },
    ///         FixedNode { node: 1, position: [1.0, 0.0, 0.0] },
    ///     ],
    ///     ..Topology::default()
    /// };
    /// let mut s = DrSensitivity::find(&t, &Settings::default()).unwrap();
    /// assert!(s.nodes()[2].norm() < 1e-10);
    /// // the two tensions stay equal, L₀/s0 = L₁/s0′ with L₀ + L₁ = 2, so x = −1 + 2 s0/(s0 + s0′)
    /// // and lengthening the first string moves the node by ∂x/∂s0 = 2 s0′/(s0 + s0′)² = 0.625
    /// let d = s.forward(DrParameter::RestLength(0)).unwrap();
    /// assert!((d.nodes[2].x - 0.625).abs() < 1e-9, "{}", d.nodes[2]);
    /// ```
    pub fn find(topology: &Topology, settings: &Settings) -> Result<Self> {
        if topology.fixed.is_empty() {
            return super::refused(
                "fixed",
                "the derivatives of a relaxed form need held nodes: without them its tangent stiffness is singular (rigid-body motions)",
            );
        }
        if !topology.clusters.is_empty() {
            return super::refused(
                "clusters",
                "the derivatives of a relaxed form with clustered strings are not available yet",
            );
        }
        if !topology.loads.is_empty() {
            return super::refused(
                "loads",
                "dynamic relaxation takes no loads: the derivatives of a loaded form are the force density method's (FdmSensitivity)",
            );
        }
        let dr = Settings {
            method: Method::Dr,
            ..settings.clone()
        };
        let (nodes, _, _, _) = crate::dr::run(topology, &dr)?;
        let rest: Vec<f64> = topology
            .given_lengths()
            .into_iter()
            .map(|l| l.unwrap_or(f64::NAN))
            .collect();
        let ea: Vec<f64> = topology
            .members()
            .map(|m| m.stiffness.unwrap_or(settings.stiffness))
            .collect();
        let pairs = topology.member_nodes();
        let nb = topology.bars.len();
        let mut free_index = vec![None; topology.n_nodes];
        let mut held = vec![false; topology.n_nodes];
        for f in &topology.fixed {
            held[f.node] = true;
        }
        let mut n_free = 0;
        for (i, slot) in free_index.iter_mut().enumerate() {
            if !held[i] {
                *slot = Some(n_free);
                n_free += 1;
            }
        }
        let (mut tension, mut length, mut active) = (Vec::new(), Vec::new(), Vec::new());
        for (k, &[a, b]) in pairs.iter().enumerate() {
            let l = (nodes[b] - nodes[a]).norm();
            let t = ea[k] * (l - rest[k]) / rest[k];
            let taut = k < nb || t > 0.0;
            tension.push(if taut { t } else { 0.0 });
            length.push(l);
            active.push(taut);
        }
        // K_t on the free coordinates (3 per free node)
        let mut triplets = Vec::new();
        for (k, &[a, b]) in pairs.iter().enumerate() {
            let e = (nodes[b] - nodes[a]) / length[k];
            let eet = e * e.transpose();
            let axial = if active[k] { ea[k] / rest[k] } else { 0.0 };
            let block = eet * axial + (Matrix3::identity() - eet) * (tension[k] / length[k]);
            for (p, sp) in [(a, 1.0), (b, -1.0)] {
                for (c, sc) in [(a, 1.0), (b, -1.0)] {
                    let (Some(fp), Some(fc)) = (free_index[p], free_index[c]) else {
                        continue;
                    };
                    for r in 0..3 {
                        for s in 0..3 {
                            triplets.push((3 * fp + r, 3 * fc + s, sp * sc * block[(r, s)]));
                        }
                    }
                }
            }
        }
        let k_t = CscMatrix::from_triplets(3 * n_free, 3 * n_free, &triplets)?;
        let lu = SparseLu::new(&k_t).map_err(|e| FormFindError::SingularSystem {
            hint: format!(
                "the tangent stiffness of the relaxed form is singular ({e}): a mechanism the held nodes and the tensions do not stiffen"
            ),
        })?;
        let mut s = Self {
            pairs,
            rest,
            ea,
            nodes,
            tension,
            length,
            active,
            free_index,
            n_free,
            lu,
        };
        s.check_regular(&k_t)?;
        Ok(s)
    }

    /// A numerically singular K_t factors without complaint: solve K_t y = K_t z for a
    /// fixed z and require y = z (as the force density method's D_ff).
    fn check_regular(&mut self, k_t: &CscMatrix) -> Result<()> {
        let z: Vec<f64> = (0..3 * self.n_free)
            .map(|i| (0.7 + 1.3 * i as f64).sin())
            .collect();
        let mut y = k_t.mul_vec(&z);
        self.lu.solve_in_place(&mut y);
        let off = y
            .iter()
            .zip(&z)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        if off.is_nan() || off > 1e-6 {
            return Err(FormFindError::SingularSystem {
                hint: format!(
                    "the tangent stiffness of the relaxed form is singular (a test solve is off by {off:.1e}): a mechanism the held nodes and the tensions do not stiffen"
                ),
            });
        }
        Ok(())
    }

    /// The found nodes.
    pub fn nodes(&self) -> &[Vector3<f64>] {
        &self.nodes
    }

    /// The members' tensions T_k (N).
    pub fn tensions(&self) -> &[f64] {
        &self.tension
    }

    /// ∂T_k/∂θ at fixed nodes for `parameter` (module docs), and its member.
    fn direct(&self, parameter: DrParameter) -> (usize, f64) {
        match parameter {
            DrParameter::RestLength(k) => {
                let d = if self.active[k] {
                    -self.ea[k] * self.length[k] / (self.rest[k] * self.rest[k])
                } else {
                    0.0
                };
                (k, d)
            }
            DrParameter::Stiffness(k) => {
                let d = if self.active[k] {
                    (self.length[k] - self.rest[k]) / self.rest[k]
                } else {
                    0.0
                };
                (k, d)
            }
        }
    }

    /// The unit vector of member k, from its start to its end.
    fn unit(&self, k: usize) -> Vector3<f64> {
        let [a, b] = self.pairs[k];
        (self.nodes[b] - self.nodes[a]) / self.length[k]
    }

    /// The derivatives of the nodes and tensions with respect to `parameter` (module docs):
    /// one solve. A member out of range is the error, naming it.
    pub fn forward(&mut self, parameter: DrParameter) -> Result<DrDerivative> {
        let m = self.pairs.len();
        let k = match parameter {
            DrParameter::RestLength(k) | DrParameter::Stiffness(k) => k,
        };
        if k >= m {
            return Err(FormFindError::InvalidTopology {
                item: "member".into(),
                reason: format!("index {k} is out of range ({m} members)"),
            });
        }
        let (k, dt) = self.direct(parameter);
        let e = self.unit(k);
        let [a, b] = self.pairs[k];
        let mut rhs = vec![0.0; 3 * self.n_free];
        for (node, sign) in [(a, 1.0), (b, -1.0)] {
            if let Some(f) = self.free_index[node] {
                for r in 0..3 {
                    rhs[3 * f + r] += sign * dt * e[r];
                }
            }
        }
        self.lu.solve_in_place(&mut rhs);
        let nodes: Vec<Vector3<f64>> = self
            .free_index
            .iter()
            .map(|f| {
                f.map_or(Vector3::zeros(), |f| {
                    Vector3::from_column_slice(&rhs[3 * f..3 * f + 3])
                })
            })
            .collect();
        let tensions = (0..m)
            .map(|j| {
                let [a, b] = self.pairs[j];
                let axial = if self.active[j] {
                    self.ea[j] / self.rest[j]
                } else {
                    0.0
                };
                let own = if j == k { dt } else { 0.0 };
                axial * self.unit(j).dot(&(nodes[b] - nodes[a])) + own
            })
            .collect();
        Ok(DrDerivative { nodes, tensions })
    }

    /// The gradient of a scalar objective f of the nodes, given ∂f/∂x_i of every node
    /// (`dnodes`; a held node's is ignored): one solve (module docs). A list of the wrong
    /// length is the error.
    pub fn adjoint(&mut self, dnodes: &[Vector3<f64>]) -> Result<DrGradient> {
        if dnodes.len() != self.nodes.len() {
            return Err(FormFindError::InvalidTopology {
                item: "dnodes".into(),
                reason: format!(
                    "{} node derivatives for {} nodes",
                    dnodes.len(),
                    self.nodes.len()
                ),
            });
        }
        let mut lambda = vec![0.0; 3 * self.n_free];
        for (i, f) in self.free_index.iter().enumerate() {
            if let Some(f) = f {
                for r in 0..3 {
                    lambda[3 * f + r] = dnodes[i][r];
                }
            }
        }
        self.lu.solve_in_place(&mut lambda);
        let at = |i: usize| {
            self.free_index[i].map_or(Vector3::zeros(), |f| {
                Vector3::from_column_slice(&lambda[3 * f..3 * f + 3])
            })
        };
        let m = self.pairs.len();
        let (mut rest_lengths, mut stiffnesses) = (Vec::with_capacity(m), Vec::with_capacity(m));
        for k in 0..m {
            let [a, b] = self.pairs[k];
            // λ · ∂R/∂θ = ∂T/∂θ (λ_a − λ_b) · e
            let arm = (at(a) - at(b)).dot(&self.unit(k));
            rest_lengths.push(self.direct(DrParameter::RestLength(k)).1 * arm);
            stiffnesses.push(self.direct(DrParameter::Stiffness(k)).1 * arm);
        }
        Ok(DrGradient {
            rest_lengths,
            stiffnesses,
        })
    }
}
