//! Exact derivatives of the force density method's form with held nodes.
//!
//! With force densities q (one per member, bars then strings), point loads P and held node
//! positions X_x, the free coordinates solve (the `fdm` module docs)
//!
//! > D_ff X_f = P_f − D_fx X_x,   D = Cᵀ diag(q) C.
//!
//! Differentiating the equilibrium R(X_f, θ) = D_ff X_f + D_fx X_x − P_f = 0 of the free
//! nodes with respect to a parameter θ gives D_ff ∂X_f/∂θ = −∂R/∂θ, one solve with the
//! factors of D_ff the form was found with:
//!
//! - a force density q_k of member k = (a, b), whose term in D X at node a is q_k (x_a − x_b):
//!   ∂R_a/∂q_k = x_a − x_b and ∂R_b/∂q_k = x_b − x_a (at free ends only);
//! - a load p_i on a free node: ∂R_i/∂p_i = −I (a load on a held node goes to its reaction);
//! - a held node's position x_h: ∂R_f/∂x_h = −q_k I for every member k joining h to a free f.
//!
//! **Forward** ([`FdmSensitivity::forward`]): every −∂R/∂θ above is of rank one, b vᵀ with b
//! a column over the free nodes (±1 at the member's free ends, 1 at the loaded node, q_k at
//! the held node's free neighbours) and v a direction (x_a − x_b, or the load's or the
//! coordinate's axis), so ∂X_f = y vᵀ with D_ff y = b: one solve of one column per
//! parameter. It gives the derivative of every node, member length L_k = |x_b − x_a|, force
//! F_k = q_k L_k and reaction r_h = (D X)_h − p_h at the held nodes:
//!
//! > ∂L_k = e_k · (∂x_b − ∂x_a),   ∂F_k = ∂q_k L_k + q_k ∂L_k,
//! > ∂r_h = Σ_k [∂q_k (x_h − x_o) + q_k (∂x_h − ∂x_o)] − ∂p_h,
//!
//! e_k the unit vector along member k and o the other end of each member k at h.
//!
//! **Adjoint** ([`FdmSensitivity::adjoint`]): for a scalar f(X, q) given by its partial
//! derivatives ∂f/∂X (a [`Cotangent`], with ∂f/∂q where f depends on q directly, e.g. through
//! the forces q L), one solve D_ff Λ = ∂f/∂X_f (D_ff is symmetric) gives the whole gradient,
//! whatever the number of parameters:
//!
//! > df/dq_k = ∂f/∂q_k − (λ_a − λ_b) · (x_a − x_b),   df/dp_i = λ_i,
//! > df/dx_h = ∂f/∂x_h + Σ_k q_k λ_f,
//!
//! with λ = 0 at held nodes, f the free end of each member k at h. [`Cotangent::lengths`] and
//! [`Cotangent::forces`] turn derivatives with respect to the member lengths and forces into
//! a cotangent by the chain rule above.
//!
//! Both modes reuse the sparse factors of D_ff (Cholesky where D_ff is positive definite, else
//! LU). The form is the unscaled solve of the loads and force densities as given (the form
//! finder divides both by max|q| for a solve near overflow; the same X). Not covered here:
//! free-standing topologies (their form is a normalised null space, not a solve), self-weight
//! (loads that depend on X), clustered strings (force densities that depend on the form) and
//! dynamic relaxation's fixed point: each is refused by name ([`FdmSensitivity::new`]).

use crate::error::{FormFindError, Result};
use crate::fdm::{held_positions, point_loads, FixedSystem};
use crate::topology::Topology;
use nalgebra::Vector3;

/// A parameter of the force density method's form (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parameter {
    /// The force density of member k (bars then strings).
    ForceDensity(usize),
    /// One component (`axis` 0, 1, 2 for x, y, z) of the point load on `node`.
    Load {
        /// The loaded node.
        node: usize,
        /// The load's component.
        axis: usize,
    },
    /// One component of the position of the `index`-th held node ([`Topology::fixed`]).
    Fixed {
        /// Its index in [`Topology::fixed`].
        index: usize,
        /// The coordinate.
        axis: usize,
    },
}

/// The derivative of a found form with respect to one parameter ([`FdmSensitivity::forward`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FormDerivative {
    /// ∂x_i of every node (a held node's is zero but for its own position's parameter).
    pub nodes: Vec<Vector3<f64>>,
    /// ∂L_k of every member's length.
    pub lengths: Vec<f64>,
    /// ∂F_k of every member's force q_k L_k (N).
    pub forces: Vec<f64>,
    /// ∂r_h of the reaction at each held node, in [`Topology::fixed`]'s order.
    pub reactions: Vec<Vector3<f64>>,
}

/// The partial derivatives of a scalar objective f(X, q): with respect to every node's
/// position and, where f depends on them directly, to the force densities (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Cotangent {
    /// ∂f/∂x_i, one per node (a held node's enters df/dx_h).
    pub nodes: Vec<Vector3<f64>>,
    /// ∂f/∂q_k at fixed X, one per member.
    pub force_densities: Vec<f64>,
}

/// The gradient of a scalar objective of the form ([`FdmSensitivity::adjoint`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FormGradient {
    /// df/dq_k, one per member (bars then strings).
    pub force_densities: Vec<f64>,
    /// df/dp_i, one per node (zero at held nodes: their loads go to the reactions).
    pub loads: Vec<Vector3<f64>>,
    /// df/dx_h, one per held node in [`Topology::fixed`]'s order.
    pub fixed: Vec<Vector3<f64>>,
}

/// −∂R/∂θ of one parameter as a column b over the free nodes times a direction v, and the
/// parameter's own moves (`FdmSensitivity::column`).
struct Column {
    b: Vec<f64>,
    v: Vector3<f64>,
    /// The member whose force density moves (∂q_k = 1).
    member: Option<usize>,
    /// The load component that moves (∂p = 1 at that node and axis).
    load: Option<(usize, usize)>,
    held_move: Option<(usize, Vector3<f64>)>,
}

/// The form of the force density method with held nodes, factored for its derivatives
/// (module docs).
///
/// A node held by four strings to held anchors x_k sits at x = (Σ q_k x_k + p) / Σ q_k, so
/// ∂x/∂q_k = (x_k − x) / Σ q and ∂x/∂p = I / Σ q:
///
/// ```
/// use formfind::sensitivity::{Cotangent, FdmSensitivity, Parameter};
/// use formfind::{FixedNode, Member, NodeLoad, Topology};
/// let anchors = [[0.0, 0.0, 1.0], [3.0, 0.5, 0.0], [1.0, 2.5, 0.5], [-0.5, 1.0, 2.0]];
/// let t = Topology {
///     n_nodes: 5,
///     strings: (0..4).map(|k| Member::new(k, 4)).collect(),
///     fixed: (0..4).map(|k| FixedNode { node: k, position: anchors[k] }).collect(),
///     loads: vec![NodeLoad { node: 4, force: [0.0, 0.0, -2.0] }],
///     ..Topology::default()
/// };
/// let q = [1.0, 2.0, 3.0, 4.0];
/// let mut s = FdmSensitivity::new(&t, &q).unwrap();
/// let x = s.nodes()[4];
/// let d = s.forward(Parameter::ForceDensity(1)).unwrap();
/// let expected = (nalgebra::Vector3::from(anchors[1]) - x) / 10.0;
/// assert!((d.nodes[4] - expected).norm() < 1e-14);
/// // the adjoint of f = z_4: df/dp_z = 1 / Σ q, df/dq_k = (z_k − z) / Σ q
/// let mut df = Cotangent::zeros(5, 4);
/// df.nodes[4].z = 1.0;
/// let g = s.adjoint(&df).unwrap();
/// assert!((g.loads[4].z - 0.1).abs() < 1e-15);
/// assert!((g.force_densities[3] - (anchors[3][2] - x.z) / 10.0).abs() < 1e-14);
/// ```
pub struct FdmSensitivity {
    /// Node pairs of the members, bars then strings.
    pairs: Vec<[usize; 2]>,
    /// Force densities.
    q: Vec<f64>,
    /// The found nodes.
    nodes: Vec<Vector3<f64>>,
    /// Each node's index among the free ones, `None` where held.
    free_index: Vec<Option<usize>>,
    /// The held nodes, in [`Topology::fixed`]'s order.
    held: Vec<usize>,
    /// The point load on every node.
    loads: Vec<Vector3<f64>>,
    /// D_ff, factored.
    system: FixedSystem,
}

impl Cotangent {
    /// The zero cotangent of a form of `n_nodes` nodes and `n_members` members.
    pub fn zeros(n_nodes: usize, n_members: usize) -> Self {
        Self {
            nodes: vec![Vector3::zeros(); n_nodes],
            force_densities: vec![0.0; n_members],
        }
    }

    /// Refuses a cotangent or a list of per-member derivatives `given` (named `what`) that
    /// does not fit the form `s`.
    fn fits(&self, s: &FdmSensitivity, what: &str, given: usize) -> Result<()> {
        let (n, m) = (s.nodes.len(), s.pairs.len());
        if self.nodes.len() != n || self.force_densities.len() != m || given != m {
            return super::refused(
                what,
                format!(
                    "a cotangent of {} nodes and {} members with {given} derivatives, for a form of {n} nodes and {m} members",
                    self.nodes.len(),
                    self.force_densities.len()
                ),
            );
        }
        Ok(())
    }

    /// Adds the cotangent of g(L) with ∂g/∂L_k = `dg_dl[k]` at the form `s` (module docs):
    /// ∂L_k/∂x_b = e_k = −∂L_k/∂x_a. A list or cotangent of the wrong size is the error.
    pub fn lengths(mut self, s: &FdmSensitivity, dg_dl: &[f64]) -> Result<Self> {
        self.fits(s, "lengths", dg_dl.len())?;
        for (k, &[a, b]) in s.pairs.iter().enumerate() {
            let e = s.unit(k);
            self.nodes[b] += dg_dl[k] * e;
            self.nodes[a] -= dg_dl[k] * e;
        }
        Ok(self)
    }

    /// Adds the cotangent of g(F) with ∂g/∂F_k = `dg_df[k]` for the member forces F_k = q_k L_k
    /// at the form `s`: ∂F_k/∂q_k = L_k and ∂F_k/∂x = q_k ∂L_k/∂x. A list or cotangent of the
    /// wrong size is the error.
    pub fn forces(mut self, s: &FdmSensitivity, dg_df: &[f64]) -> Result<Self> {
        self.fits(s, "forces", dg_df.len())?;
        let lengths = s.lengths();
        let scaled: Vec<f64> = dg_df.iter().zip(&s.q).map(|(g, q)| g * q).collect();
        for (k, g) in dg_df.iter().enumerate() {
            self.force_densities[k] += g * lengths[k];
        }
        self.lengths(s, &scaled)
    }
}

impl FdmSensitivity {
    /// Finds the form of `topology` with held nodes under force densities `q` (bars then
    /// strings) and its point loads, and factors D_ff for its derivatives. Refused by name:
    /// a topology without held nodes, with member weights, or with clustered strings (module
    /// docs); a wrong count of force densities; a singular D_ff.
    pub fn new(topology: &Topology, q: &[f64]) -> Result<Self> {
        if topology.fixed.is_empty() {
            return super::refused(
                "fixed",
                "the derivatives of a form need held nodes: a free-standing form is a normalised null space of D, not a solve",
            );
        }
        if !topology.clusters.is_empty() {
            return super::refused(
                "clusters",
                "the derivatives of a form with clustered strings are not available yet: their force densities depend on the form",
            );
        }
        if crate::fdm::member_weights(topology)
            .iter()
            .any(|&w| w != 0.0)
        {
            return super::refused(
                "weight",
                "the derivatives of a form under self-weight are not available yet: its loads depend on the form",
            );
        }
        if q.len() != topology.n_members() {
            return super::refused(
                "force_density",
                format!(
                    "{} force densities for {} members",
                    q.len(),
                    topology.n_members()
                ),
            );
        }
        if let Some(k) = q.iter().position(|x| !x.is_finite()) {
            return super::refused(
                "force_density",
                format!("member {k}'s force density is not finite"),
            );
        }
        let mut system = FixedSystem::new(topology, q, &held_positions(topology))?;
        let loads = point_loads(topology);
        let nodes = system.solve(&loads)?;
        let mut free_index = vec![None; topology.n_nodes];
        for (k, &i) in system.free().iter().enumerate() {
            free_index[i] = Some(k);
        }
        Ok(Self {
            pairs: topology.member_nodes(),
            q: q.to_vec(),
            nodes,
            free_index,
            held: topology.fixed.iter().map(|f| f.node).collect(),
            loads,
            system,
        })
    }

    /// [`FdmSensitivity::new`] with the force densities `topology` gives (each member's own,
    /// else its group's); a member with neither is the error, naming it.
    ///
    /// ```
    /// use formfind::sensitivity::FdmSensitivity;
    /// let grid = formfind::builtin("grid:2").unwrap();
    /// let s = FdmSensitivity::given(&grid).unwrap();
    /// assert_eq!(s.nodes().len(), grid.n_nodes);
    /// let prism = formfind::builtin("prism:3").unwrap(); // free-standing: refused
    /// assert!(FdmSensitivity::given(&prism).is_err());
    /// ```
    pub fn given(topology: &Topology) -> Result<Self> {
        let given = topology.given_force_densities();
        if let Some(k) = given.iter().position(Option::is_none) {
            return Err(FormFindError::InvalidTopology {
                item: format!("member {k}"),
                reason: "no force density (its own or its group's): the derivatives are those of the force density method".into(),
            });
        }
        let q: Vec<f64> = given.into_iter().flatten().collect();
        Self::new(topology, &q)
    }

    /// The force densities the form was found with (bars then strings).
    pub fn force_densities(&self) -> &[f64] {
        &self.q
    }

    /// The held nodes, in [`Topology::fixed`]'s order.
    pub fn held(&self) -> &[usize] {
        &self.held
    }

    /// The found nodes.
    pub fn nodes(&self) -> &[Vector3<f64>] {
        &self.nodes
    }

    /// The member lengths L_k.
    pub fn lengths(&self) -> Vec<f64> {
        self.pairs
            .iter()
            .map(|&[a, b]| (self.nodes[b] - self.nodes[a]).norm())
            .collect()
    }

    /// The member forces F_k = q_k L_k (tension positive).
    pub fn forces(&self) -> Vec<f64> {
        self.lengths()
            .iter()
            .zip(&self.q)
            .map(|(l, q)| l * q)
            .collect()
    }

    /// The reactions r_h = (D X)_h − p_h at the held nodes, in [`Topology::fixed`]'s order:
    /// the force each support exerts on its node, as [`crate::FormFound::reactions`].
    pub fn reactions(&self) -> Vec<Vector3<f64>> {
        let none = vec![Vector3::zeros(); self.nodes.len()];
        let zero = vec![0.0; self.q.len()];
        let sums = self.member_sums(&none, &self.q, &zero);
        sums.iter()
            .zip(&self.held)
            .map(|(r, &h)| r - self.loads[h])
            .collect()
    }

    /// Σ_k [dq_k (x_h − x_o) + q_k (dx_h − dx_o)] over the members k at each held node h (o
    /// the other end), in [`Topology::fixed`]'s order: (D X)_h for dq = q and q = 0, its
    /// derivative along (dx, dq) for q the force densities (module docs).
    fn member_sums(&self, dx: &[Vector3<f64>], dq: &[f64], q: &[f64]) -> Vec<Vector3<f64>> {
        let mut r = vec![Vector3::zeros(); self.nodes.len()];
        for (k, &[a, b]) in self.pairs.iter().enumerate() {
            let t = dq[k] * (self.nodes[a] - self.nodes[b]) + q[k] * (dx[a] - dx[b]);
            r[a] += t;
            r[b] -= t;
        }
        self.held.iter().map(|&h| r[h]).collect()
    }

    /// The unit vector along member k, from its start to its end (zero for a member of zero
    /// length).
    fn unit(&self, k: usize) -> Vector3<f64> {
        let [a, b] = self.pairs[k];
        let d = self.nodes[b] - self.nodes[a];
        let l = d.norm();
        if l > 0.0 {
            d / l
        } else {
            Vector3::zeros()
        }
    }

    /// Solves D_ff Y = B for the three columns of `b` (one row per free node), in place.
    fn solve(&mut self, b: &mut [Vector3<f64>]) {
        for axis in 0..3 {
            let mut column: Vec<f64> = b.iter().map(|v| v[axis]).collect();
            self.system.solve_free_in_place(&mut column);
            for (v, c) in b.iter_mut().zip(&column) {
                v[axis] = *c;
            }
        }
    }

    /// The derivative of the form with respect to `parameter` (module docs, forward): one
    /// solve with the factors of D_ff. An index out of range is the error, naming it.
    pub fn forward(&mut self, parameter: Parameter) -> Result<FormDerivative> {
        let n = self.nodes.len();
        let m = self.pairs.len();
        let Column {
            mut b,
            v,
            member,
            load,
            held_move,
        } = self.column(parameter)?;
        let mut dq = vec![0.0; m];
        if let Some(k) = member {
            dq[k] = 1.0;
        }
        let mut dp = vec![Vector3::zeros(); n];
        if let Some((node, axis)) = load {
            dp[node][axis] = 1.0;
        }
        self.system.solve_free_in_place(&mut b);
        let mut nodes = vec![Vector3::zeros(); n];
        for (i, d) in nodes.iter_mut().enumerate() {
            if let Some(f) = self.free_index[i] {
                *d = b[f] * v;
            }
        }
        if let Some((h, unit)) = held_move {
            nodes[h] = unit;
        }
        let lengths: Vec<f64> = (0..m)
            .map(|k| {
                let [a, b] = self.pairs[k];
                self.unit(k).dot(&(nodes[b] - nodes[a]))
            })
            .collect();
        let base = self.lengths();
        let forces = (0..m)
            .map(|k| dq[k] * base[k] + self.q[k] * lengths[k])
            .collect();
        let mut reactions = self.member_sums(&nodes, &dq, &self.q);
        for (r, &h) in reactions.iter_mut().zip(&self.held) {
            *r -= dp[h];
        }
        Ok(FormDerivative {
            nodes,
            lengths,
            forces,
            reactions,
        })
    }

    /// The node and member counts, checked against a cotangent's (the wrong size is the
    /// error, naming it).
    fn check(&self, df: &Cotangent) -> Result<(usize, usize)> {
        let n = self.nodes.len();
        let m = self.pairs.len();
        if df.nodes.len() != n || df.force_densities.len() != m {
            return Err(FormFindError::InvalidTopology {
                item: "cotangent".into(),
                reason: format!(
                    "{} node and {} member derivatives for {n} nodes and {m} members",
                    df.nodes.len(),
                    df.force_densities.len()
                ),
            });
        }
        Ok((n, m))
    }

    /// −∂R/∂θ of one parameter on the free rows, b vᵀ (module docs, forward), with the
    /// parameter's own moves: ∂q, ∂p and a held node's ∂x. An index out of range is the
    /// error, naming it.
    fn column(&self, parameter: Parameter) -> Result<Column> {
        let n = self.nodes.len();
        let m = self.pairs.len();
        let nf = self.system.free().len();
        let out_of_range = |item: &str, i: usize, count: usize| {
            Err(FormFindError::InvalidTopology {
                item: item.into(),
                reason: format!("index {i} is out of range ({count} of them)"),
            })
        };
        // −∂R/∂θ on the free rows is b vᵀ, one column b times a direction v (module docs):
        // one solve of D_ff y = b gives ∂X_f = y vᵀ
        let mut b = vec![0.0; nf];
        let mut v = Vector3::zeros();
        let (mut member, mut load) = (None, None);
        let mut held_move = None;
        match parameter {
            Parameter::ForceDensity(k) => {
                if k >= m {
                    return out_of_range("force_density", k, m);
                }
                member = Some(k);
                let [start, end] = self.pairs[k];
                v = self.nodes[start] - self.nodes[end];
                if let Some(f) = self.free_index[start] {
                    b[f] -= 1.0;
                }
                if let Some(f) = self.free_index[end] {
                    b[f] += 1.0;
                }
            }
            Parameter::Load { node, axis } => {
                if node >= n {
                    return out_of_range("load", node, n);
                }
                if axis > 2 {
                    return out_of_range("axis", axis, 3);
                }
                load = Some((node, axis));
                v[axis] = 1.0;
                if let Some(f) = self.free_index[node] {
                    b[f] = 1.0;
                }
            }
            Parameter::Fixed { index, axis } => {
                if index >= self.held.len() {
                    return out_of_range("fixed", index, self.held.len());
                }
                if axis > 2 {
                    return out_of_range("axis", axis, 3);
                }
                let h = self.held[index];
                v[axis] = 1.0;
                held_move = Some((h, v));
                for (k, &[start, end]) in self.pairs.iter().enumerate() {
                    for (at, other) in [(start, end), (end, start)] {
                        if at == h {
                            if let Some(f) = self.free_index[other] {
                                b[f] += self.q[k];
                            }
                        }
                    }
                }
            }
        }
        Ok(Column {
            b,
            v,
            member,
            load,
            held_move,
        })
    }

    /// The derivatives of one scalar objective f(X, q) (its partial derivatives `df`, as
    /// [`FdmSensitivity::adjoint`] takes them) with respect to each of `parameters`, in
    /// forward mode: one solve per parameter and no other work per node or member than the
    /// product with ∂f/∂X (df/dθ = Σ_f (∂f/∂x_f · v) y_f + ∂f/∂θ, ∂X_f = y vᵀ). The adjoint
    /// gives the same for every parameter at once; this is the cheaper for a few of them.
    ///
    /// ```
    /// use formfind::sensitivity::{Cotangent, FdmSensitivity, Parameter};
    /// let grid = formfind::builtin("grid:2").unwrap();
    /// let mut s = FdmSensitivity::given(&grid).unwrap();
    /// let mut df = Cotangent::zeros(grid.n_nodes, grid.n_members());
    /// df.nodes[4].z = 1.0;
    /// let params = [Parameter::ForceDensity(0), Parameter::ForceDensity(5)];
    /// let forward = s.forward_gradient(&df, &params).unwrap();
    /// let adjoint = s.adjoint(&df).unwrap();
    /// assert!((forward[1] - adjoint.force_densities[5]).abs() < 1e-14);
    /// ```
    pub fn forward_gradient(
        &mut self,
        df: &Cotangent,
        parameters: &[Parameter],
    ) -> Result<Vec<f64>> {
        self.check(df)?;
        let free: Vec<Vector3<f64>> = self.system.free().iter().map(|&i| df.nodes[i]).collect();
        let mut out = Vec::with_capacity(parameters.len());
        for &parameter in parameters {
            let mut column = self.column(parameter)?;
            self.system.solve_free_in_place(&mut column.b);
            let mut d: f64 = free
                .iter()
                .zip(&column.b)
                .map(|(c, y)| y * c.dot(&column.v))
                .sum();
            if let Parameter::ForceDensity(k) = parameter {
                d += df.force_densities[k];
            }
            if let Some((h, unit)) = column.held_move {
                d += df.nodes[h].dot(&unit);
            }
            out.push(d);
        }
        Ok(out)
    }

    /// The gradient of a scalar objective f(X, q) given by its partial derivatives `df`
    /// (module docs, adjoint): one solve with the factors of D_ff, whatever the number of
    /// parameters. A cotangent of the wrong size is the error.
    pub fn adjoint(&mut self, df: &Cotangent) -> Result<FormGradient> {
        let (n, m) = self.check(df)?;
        let free = self.system.free().to_vec();
        let mut lambda: Vec<Vector3<f64>> = free.iter().map(|&i| df.nodes[i]).collect();
        self.solve(&mut lambda);
        let at = |i: usize| self.free_index[i].map_or(Vector3::zeros(), |f| lambda[f]);
        let force_densities = (0..m)
            .map(|k| {
                let [a, b] = self.pairs[k];
                df.force_densities[k] - (at(a) - at(b)).dot(&(self.nodes[a] - self.nodes[b]))
            })
            .collect();
        let loads = (0..n).map(at).collect();
        let mut fixed: Vec<Vector3<f64>> = self.held.iter().map(|&h| df.nodes[h]).collect();
        for (index, &h) in self.held.iter().enumerate() {
            for (k, &[a, b]) in self.pairs.iter().enumerate() {
                for (end, other) in [(a, b), (b, a)] {
                    if end == h {
                        fixed[index] += self.q[k] * at(other);
                    }
                }
            }
        }
        Ok(FormGradient {
            force_densities,
            loads,
            fixed,
        })
    }
}
