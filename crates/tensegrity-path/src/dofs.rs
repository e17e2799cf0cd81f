//! The free directions of the nodes: each node's displacement is Σ_b q_b e_b over an
//! orthonormal basis e_b of the complement of its support's directions, so the unknowns are
//! the reduced coordinates q (a node held along d moves in the plane normal to d, one held
//! along two directions along their common normal, a pinned node not at all).

use crate::error::{PathError, Result};
use crate::model::ElasticModel;
use nalgebra::{Matrix3, Vector3};

/// The reduced coordinates: one (node, unit direction) per free coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Dofs {
    /// Each free coordinate's node and direction.
    pub free: Vec<(usize, Vector3<f64>)>,
    /// Each held direction: node and unit direction (the reactions' directions).
    pub held: Vec<(usize, Vector3<f64>)>,
    /// The index in `free` of each node's first free coordinate, and their count.
    pub of_node: Vec<(usize, usize)>,
    /// Each node's motion per unit load factor (its driven displacement along its held
    /// directions; zero for free nodes).
    pub held_motion: Vec<Vector3<f64>>,
}

impl Dofs {
    /// The free and held directions of `model` (its supports validated); dependent support
    /// directions of one node are an error naming the node.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_path::{dofs::Dofs, ElasticModel, Support};
    /// let m = ElasticModel {
    ///     nodes: vec![Vector3::zeros(); 2],
    ///     members: vec![],
    ///     supports: vec![Support { node: 1, directions: vec![Vector3::new(1.0, 1.0, 0.0).normalize()] }],
    ///     load: vec![Vector3::zeros(); 2],
    ///     drivers: Default::default(),
    /// };
    /// let d = Dofs::of(&m).unwrap();
    /// assert_eq!((d.free.len(), d.held.len()), (5, 1));
    /// // node 1 moves normal to (1, 1, 0)/√2
    /// let (first, count) = d.of_node[1];
    /// assert_eq!(count, 2);
    /// for (_, e) in &d.free[first..first + count] {
    ///     assert!(e.dot(&Vector3::new(1.0, 1.0, 0.0)).abs() < 1e-15);
    /// }
    /// ```
    pub fn of(model: &ElasticModel) -> Result<Self> {
        let n = model.nodes.len();
        let mut held_at: Vec<Vec<Vector3<f64>>> = vec![Vec::new(); n];
        for s in &model.supports {
            held_at[s.node].extend(s.directions.iter().copied());
        }
        let (mut free, mut held, mut of_node) = (Vec::new(), Vec::new(), Vec::with_capacity(n));
        let mut held_motion = Vec::with_capacity(n);
        for (i, dirs) in held_at.iter().enumerate() {
            // orthonormalise the held directions (Gram–Schmidt), refusing dependent ones
            let mut basis: Vec<Vector3<f64>> = Vec::new();
            for d in dirs {
                let mut v = *d;
                for b in &basis {
                    v -= b * b.dot(&v);
                }
                if v.norm() < 1e-9 {
                    return Err(PathError::model(
                        format!("support of node {i}"),
                        "its directions are dependent (a direction repeated or in the plane of two others): give independent ones",
                    ));
                }
                basis.push(v.normalize());
            }
            held.extend(basis.iter().map(|b| (i, *b)));
            let d = model
                .drivers
                .displacements
                .get(i)
                .copied()
                .unwrap_or_else(Vector3::zeros);
            let along: Vector3<f64> = basis.iter().map(|b| b * b.dot(&d)).sum();
            if (d - along).norm() > 1e-12 * d.norm().max(f64::MIN_POSITIVE) {
                return Err(PathError::model(
                    format!("displacement of node {i}"),
                    "a driven displacement moves a node along its held directions only: support the node along it (its free directions follow from equilibrium)",
                ));
            }
            held_motion.push(along);
            // the complement: eigenvectors of I − Σ b bᵀ with eigenvalue 1
            let projector = Matrix3::identity()
                - basis
                    .iter()
                    .map(|b| b * b.transpose())
                    .sum::<Matrix3<f64>>();
            let eig = projector.symmetric_eigen();
            let start = free.len();
            for a in 0..3 {
                if eig.eigenvalues[a] > 0.5 {
                    free.push((i, eig.eigenvectors.column(a).into_owned()));
                }
            }
            of_node.push((start, free.len() - start));
        }
        Ok(Self {
            free,
            held,
            of_node,
            held_motion,
        })
    }

    /// The number of free coordinates.
    pub fn len(&self) -> usize {
        self.free.len()
    }

    /// Whether no coordinate is free.
    pub fn is_empty(&self) -> bool {
        self.free.is_empty()
    }

    /// The reduced vector of per-node forces: each free direction's component.
    pub fn reduce(&self, f: &[Vector3<f64>]) -> nalgebra::DVector<f64> {
        nalgebra::DVector::from_iterator(self.len(), self.free.iter().map(|(i, e)| e.dot(&f[*i])))
    }

    /// `x` with the held nodes moved by their motion over a change `d_lambda` of the load
    /// factor.
    pub fn drive(&self, x: &[Vector3<f64>], d_lambda: f64) -> Vec<Vector3<f64>> {
        x.iter()
            .zip(&self.held_motion)
            .map(|(x, d)| x + d * d_lambda)
            .collect()
    }

    /// The nodal displacements of the reduced coordinates `q`.
    pub fn expand(&self, q: &nalgebra::DVector<f64>, n_nodes: usize) -> Vec<Vector3<f64>> {
        let mut u = vec![Vector3::zeros(); n_nodes];
        for (b, (i, e)) in self.free.iter().enumerate() {
            u[*i] += e * q[b];
        }
        u
    }
}
