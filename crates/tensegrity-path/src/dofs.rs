//! The free directions of the nodes: each node's displacement is Σ_b q_b e_b over an
//! orthonormal basis e_b of the complement of its support's directions, so the unknowns are
//! the reduced coordinates q (a node held along d moves in the plane normal to d, one held
//! along two directions along their common normal, a pinned node not at all). The
//! directions of an elastic support stay free: its springs ([`Spring`]) act on them.

use crate::error::{PathError, Result};
use crate::model::ElasticModel;
use nalgebra::{Matrix3, Vector3};

/// A spring of an elastic support (crate docs): it adds k d (d·(u − λ a)) to the node's
/// resisting force and k d dᵀ to the tangent, u the node's displacement from the reference
/// state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// The node.
    pub node: usize,
    /// Its unit direction d.
    pub direction: Vector3<f64>,
    /// Its stiffness k (N/m).
    pub stiffness: f64,
    /// The motion a of its anchor per unit load factor (m; the node's driven displacement
    /// beyond its rigidly held directions, zero without one).
    pub anchor: Vector3<f64>,
}

impl Spring {
    /// The spring's force on its node along its direction, −k d·(u − λ a) (N), at node
    /// displacement `u` and load factor `lambda`.
    pub fn force(&self, u: &Vector3<f64>, lambda: f64) -> f64 {
        -self.stiffness * self.direction.dot(&(u - self.anchor * lambda))
    }
}

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
    /// The springs of the elastic supports, one per direction (their nodes' directions stay
    /// free coordinates).
    pub springs: Vec<Spring>,
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
    ///     clusters: Vec::new(),
    ///     supports: vec![Support::along(1, vec![Vector3::new(1.0, 1.0, 0.0).normalize()])],
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
        let mut springs_at: Vec<Vec<(Vector3<f64>, f64)>> = vec![Vec::new(); n];
        for s in &model.supports {
            match s.stiffness {
                None => held_at[s.node].extend(s.directions.iter().copied()),
                Some(k) => springs_at[s.node].extend(s.directions.iter().map(|d| (*d, k))),
            }
        }
        let (mut free, mut held, mut of_node) = (Vec::new(), Vec::new(), Vec::with_capacity(n));
        let mut held_motion = Vec::with_capacity(n);
        let mut springs = Vec::new();
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
            // what is left moves the anchor of the node's springs, along their directions
            let anchor = d - along;
            let mut spring_span: Vec<Vector3<f64>> = basis.clone();
            for (s, _) in &springs_at[i] {
                let mut v = *s;
                for b in &spring_span {
                    v -= b * b.dot(&v);
                }
                if v.norm() > 1e-9 {
                    spring_span.push(v.normalize());
                }
            }
            let spanned: Vector3<f64> = spring_span.iter().map(|b| b * b.dot(&d)).sum();
            if (d - spanned).norm() > 1e-12 * d.norm().max(f64::MIN_POSITIVE) {
                return Err(PathError::model(
                    format!("displacement of node {i}"),
                    "a driven displacement moves a node along its held directions only (or the anchor of its springs along theirs): support the node along it (its free directions follow from equilibrium)",
                ));
            }
            springs.extend(springs_at[i].iter().map(|&(direction, stiffness)| Spring {
                node: i,
                direction,
                stiffness,
                anchor,
            }));
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
            springs,
        })
    }

    /// The springs' resisting forces at every node, Σ k d (d·(u − λ a)) (N; crate docs), at
    /// node positions `x` and load factor `lambda` (u = x − `reference`).
    pub fn spring_forces(
        &self,
        reference: &[Vector3<f64>],
        x: &[Vector3<f64>],
        lambda: f64,
    ) -> Vec<Vector3<f64>> {
        let mut r = vec![Vector3::zeros(); x.len()];
        for s in &self.springs {
            let u = x[s.node] - reference[s.node];
            r[s.node] -= s.direction * s.force(&u, lambda);
        }
        r
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
