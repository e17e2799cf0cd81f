//! The mass of an elastic model for its dynamics ([`crate::transient`]): member masses m_k
//! (uniform along the member) and point masses m_i at nodes, distributed onto the nodes
//!
//! * **lumped**: m_k/2 at each end, M = diag(Σ m_k/2 + m_i) ⊗ I₃;
//! * **consistent** (linear shape functions, the member's exact kinetic energy when its
//!   velocity varies linearly along it): (m_k/6) [[2, 1], [1, 2]] ⊗ I₃ on its two ends,
//!   plus m_i I₃ — TsgFEM's `lumped = 0`.
//!
//! Both carry the same total mass and give a uniform gravity field the same nodal weights
//! (m_k g/2 at each end, m_i g at a node). On the free coordinates q (x = x₀ + Σ q_b e_b,
//! [`Dofs`]) the mass matrix is M_r = Qᵀ M Q, factored once ([`MassSolver`]): a diagonal
//! when lumped (each node's free directions are orthonormal), else dense Cholesky up to
//! [`DENSE_MAX`] free coordinates and sparse Cholesky above.

use crate::dofs::Dofs;
use crate::error::{PathError, Result};
use crate::factor::DENSE_MAX;
use crate::model::ElasticModel;
use nalgebra::{DMatrix, Vector3};
use serde::Serialize;
use tensegrity_linalg::{CscMatrix, SparseCholesky};

/// How a member's mass is distributed onto its nodes (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MassDistribution {
    /// Half at each end: a diagonal mass matrix.
    #[default]
    Lumped,
    /// (m/6) [[2, 1], [1, 2]] per member: the linear shape functions' kinetic energy.
    Consistent,
}

/// The masses of an elastic model's members and nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Masses {
    /// One mass per member of the model (kg; 0: massless).
    pub members: Vec<f64>,
    /// One point mass per node (kg; 0: none).
    pub nodes: Vec<f64>,
    /// Lumped or consistent.
    pub distribution: MassDistribution,
}

impl Masses {
    /// Checks the masses against `model`: one per member and per node, each finite and not
    /// negative, and every node that moves (has a free direction) carries some mass; errors
    /// name the item.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_path::{dofs::Dofs, mass::{MassDistribution, Masses}};
    /// use tensegrity_path::{ElasticMember, ElasticModel, MemberKind, Support};
    /// let bar = ElasticMember { nodes: [0, 1], kind: MemberKind::Bar, ea: 1e4, rest_length: 1.0 };
    /// let m = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x(), Vector3::y()],
    ///     members: vec![bar], clusters: Vec::new(), supports: vec![Support::pinned(0)],
    ///     load: vec![Vector3::zeros(); 3], drivers: Default::default() };
    /// let masses = Masses { members: vec![2.0], nodes: vec![0.0; 3],
    ///     distribution: MassDistribution::Lumped };
    /// let dofs = Dofs::of(&m).unwrap();
    /// // node 2 is free and carries nothing
    /// assert_eq!(masses.checked(&m, &dofs).unwrap_err().to_string(),
    ///     "node 2: it moves (3 free directions) but carries no mass: give it a point mass or a member with a mass");
    /// ```
    pub fn checked(self, model: &ElasticModel, dofs: &Dofs) -> Result<Self> {
        if self.members.len() != model.members.len() || self.nodes.len() != model.nodes.len() {
            return Err(PathError::model(
                "masses",
                format!(
                    "{} member masses and {} node masses for {} members and {} nodes",
                    self.members.len(),
                    self.nodes.len(),
                    model.members.len(),
                    model.nodes.len()
                ),
            ));
        }
        let bad = |m: f64| !(m.is_finite() && m >= 0.0);
        if let Some(k) = self.members.iter().position(|&m| bad(m)) {
            return Err(PathError::model(
                format!("member {k}"),
                format!("mass {}: give a finite mass ≥ 0 (kg)", self.members[k]),
            ));
        }
        if let Some(i) = self.nodes.iter().position(|&m| bad(m)) {
            return Err(PathError::model(
                format!("node {i}"),
                format!("point mass {}: give a finite mass ≥ 0 (kg)", self.nodes[i]),
            ));
        }
        let lumped = self.lumped(model);
        for (i, &(_, count)) in dofs.of_node.iter().enumerate() {
            if count > 0 && lumped[i] <= 0.0 {
                return Err(PathError::model(
                    format!("node {i}"),
                    format!("it moves ({count} free directions) but carries no mass: give it a point mass or a member with a mass"),
                ));
            }
        }
        Ok(self)
    }

    /// Each node's lumped mass: its point mass and half of every member's at it (kg).
    pub fn lumped(&self, model: &ElasticModel) -> Vec<f64> {
        let mut m = self.nodes.clone();
        for (member, &mk) in model.members.iter().zip(&self.members) {
            for i in member.nodes {
                m[i] += 0.5 * mk;
            }
        }
        m
    }

    /// The total mass (kg).
    pub fn total(&self) -> f64 {
        self.members.iter().sum::<f64>() + self.nodes.iter().sum::<f64>()
    }

    /// The weight of every node in the gravity field `g` (m/s²): m_i g + Σ m_k g/2, the same
    /// for both distributions (module docs).
    pub fn weights(&self, model: &ElasticModel, g: Vector3<f64>) -> Vec<Vector3<f64>> {
        self.lumped(model).into_iter().map(|m| g * m).collect()
    }

    /// Whether member k takes the consistent matrix: all members under
    /// [`MassDistribution::Consistent`], none under lumped.
    fn all_consistent(&self) -> Vec<bool> {
        vec![self.distribution == MassDistribution::Consistent; self.members.len()]
    }

    /// The kinetic energy ½ vᵀ M v of the node velocities `v` (J).
    pub fn kinetic_energy(&self, model: &ElasticModel, v: &[Vector3<f64>]) -> f64 {
        match self.distribution {
            MassDistribution::Lumped => self
                .lumped(model)
                .iter()
                .zip(v)
                .map(|(m, v)| 0.5 * m * v.norm_squared())
                .sum(),
            MassDistribution::Consistent => {
                let points: f64 = self
                    .nodes
                    .iter()
                    .zip(v)
                    .map(|(m, v)| 0.5 * m * v.norm_squared())
                    .sum();
                let members: f64 = model
                    .members
                    .iter()
                    .zip(&self.members)
                    .map(|(member, &mk)| {
                        let (a, b) = (v[member.nodes[0]], v[member.nodes[1]]);
                        mk / 6.0 * (a.norm_squared() + a.dot(&b) + b.norm_squared())
                    })
                    .sum();
                points + members
            }
        }
    }

    /// The kinetic energy ½ vᵀ M v (J) with member k's mass consistent where `consistent[k]`
    /// and lumped elsewhere (the rigid bars of [`crate::rigid_bars`] take the consistent
    /// matrix whatever the distribution).
    pub fn kinetic_energy_mixed(
        &self,
        model: &ElasticModel,
        v: &[Vector3<f64>],
        consistent: &[bool],
    ) -> f64 {
        let half = |m: f64, v: &Vector3<f64>| 0.5 * m * v.norm_squared();
        let mut e: f64 = self.nodes.iter().zip(v).map(|(m, v)| half(*m, v)).sum();
        for ((member, &mk), &c) in model.members.iter().zip(&self.members).zip(consistent) {
            let (a, b) = (v[member.nodes[0]], v[member.nodes[1]]);
            e += if c {
                mk / 6.0 * (a.norm_squared() + a.dot(&b) + b.norm_squared())
            } else {
                half(0.5 * mk, &a) + half(0.5 * mk, &b)
            };
        }
        e
    }

    /// The reduced mass matrix M_r = Qᵀ M Q as (row, column, value) triplets on the free
    /// coordinates of `dofs`, both triangles, repeated entries to be summed.
    pub fn triplets(&self, model: &ElasticModel, dofs: &Dofs) -> Vec<(usize, usize, f64)> {
        self.triplets_mixed(model, dofs, &self.all_consistent())
    }

    /// [`Masses::triplets`] with member k's mass consistent where `consistent[k]` and lumped
    /// elsewhere.
    pub fn triplets_mixed(
        &self,
        model: &ElasticModel,
        dofs: &Dofs,
        consistent: &[bool],
    ) -> Vec<(usize, usize, f64)> {
        // the node blocks m I₃ (lumped m_k/2, or the consistent diagonal m_k/3, plus m_i)
        // reduce to m on the node's orthonormal free directions
        let mut diagonal = self.nodes.clone();
        for ((member, &mk), &c) in model.members.iter().zip(&self.members).zip(consistent) {
            for i in member.nodes {
                diagonal[i] += if c { mk / 3.0 } else { 0.5 * mk };
            }
        }
        let mut t = Vec::new();
        for (i, &(first, count)) in dofs.of_node.iter().enumerate() {
            t.extend((first..first + count).map(|b| (b, b, diagonal[i])));
        }
        for ((member, &mk), &c) in model.members.iter().zip(&self.members).zip(consistent) {
            if c {
                let [a, b] = member.nodes;
                let ((a0, ac), (b0, bc)) = (dofs.of_node[a], dofs.of_node[b]);
                for r in a0..a0 + ac {
                    for c in b0..b0 + bc {
                        let v = mk / 6.0 * dofs.free[r].1.dot(&dofs.free[c].1);
                        if v != 0.0 {
                            t.push((r, c, v));
                            t.push((c, r, v));
                        }
                    }
                }
            }
        }
        t
    }
}

/// M_r factored once for the accelerations M_r a = F_r (module docs).
#[derive(Debug)]
pub enum MassSolver {
    /// Lumped: the diagonal's inverse.
    Diagonal(Vec<f64>),
    /// Consistent, small: the Cholesky factor.
    Dense(nalgebra::Cholesky<f64, nalgebra::Dyn>),
    /// Consistent, large: the sparse Cholesky factor (its solve needs its own workspace:
    /// behind a lock, as the right-hand side only borrows the model).
    Sparse(Box<std::sync::Mutex<SparseCholesky>>),
}

impl MassSolver {
    /// Factors the reduced mass matrix of `masses` (checked) on `dofs`.
    pub fn new(masses: &Masses, model: &ElasticModel, dofs: &Dofs) -> Result<Self> {
        let diagonal = masses.distribution == MassDistribution::Lumped;
        Self::from_triplets(dofs.len(), masses.triplets(model, dofs), diagonal)
    }

    /// Factors the n × n reduced mass matrix given as triplets ([`Masses::triplets_mixed`]):
    /// its diagonal alone when `diagonal` (every mass lumped), else Cholesky.
    pub fn from_triplets(
        n: usize,
        triplets: Vec<(usize, usize, f64)>,
        diagonal: bool,
    ) -> Result<Self> {
        let singular = || {
            PathError::model(
                "masses",
                "the mass matrix on the free coordinates is not positive definite",
            )
        };
        if diagonal {
            let mut d = vec![0.0; n];
            for (r, _, v) in triplets {
                d[r] += v;
            }
            return Ok(Self::Diagonal(d.iter().map(|m| 1.0 / m).collect()));
        }
        if n <= DENSE_MAX {
            let mut m = DMatrix::zeros(n, n);
            for (r, c, v) in triplets {
                m[(r, c)] += v;
            }
            return m.cholesky().map(Self::Dense).ok_or_else(singular);
        }
        let lower: Vec<(usize, usize, f64)> =
            triplets.into_iter().filter(|&(r, c, _)| r >= c).collect();
        let lower = CscMatrix::from_triplets(n, n, &lower).map_err(|_| singular())?;
        let mut chol = SparseCholesky::new(lower.pattern()).map_err(|_| singular())?;
        chol.factor(lower.values()).map_err(|_| singular())?;
        Ok(Self::Sparse(Box::new(std::sync::Mutex::new(chol))))
    }

    /// Overwrites `f` (reduced forces) with M_r⁻¹ f.
    pub fn solve_in_place(&self, f: &mut [f64]) {
        match self {
            Self::Diagonal(inv) => f.iter_mut().zip(inv).for_each(|(f, m)| *f *= m),
            Self::Dense(chol) => {
                let mut x = nalgebra::DVectorViewMut::from_slice(f, f.len());
                chol.solve_mut(&mut x);
            }
            Self::Sparse(chol) => chol
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .solve_in_place(f),
        }
    }
}
