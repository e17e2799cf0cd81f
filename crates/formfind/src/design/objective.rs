//! The objective of a design problem and its exact gradient.
//!
//! With the force densities q(v) of the design variables v (each variable sets the q of its
//! members; the other members keep theirs), the form X(q) of the force density method with
//! held nodes and the goals' predictions p_j(X, q), each term is
//!
//! > T = α A(Σ_j e_j),  e_j = w_j ‖p_j − t_j‖² (squared), w_j ‖p_j − t_j‖₁ (absolute) or
//! > w_j Σ p_j (prediction),
//!
//! A the identity, the mean S / n or the root mean √(S / n) over the term's n goals, and the
//! objective f = Σ T. Its gradient is one adjoint solve ([`crate::sensitivity`]): the chain
//! rule gives ∂f/∂p_j = α A′(S) ∂e_j/∂p_j, and each prediction's partial derivatives with
//! respect to X and q make the cotangent:
//!
//! - a position x_i: ∂/∂x_i = I (a coordinate: the unit vector of its axis; the distance to
//!   a plane (x − p) · n̂: n̂; the offset from a line (I − ûûᵀ)(x − p): I − ûûᵀ);
//! - a force density q_k: ∂/∂q_k = 1 at fixed X;
//! - a length L_k and a force q_k L_k: [`Cotangent::lengths`], [`Cotangent::forces`];
//! - a direction u = d / L, d = x_b − x_a: ∂u/∂d = (I − u uᵀ) / L;
//! - a reaction r_h = Σ_k q_k (x_h − x_o) − p_h: ∂/∂x_h = Σ q_k I, ∂/∂x_o = −q_k I,
//!   ∂/∂q_k = x_h − x_o; its magnitude ‖r‖ and its limit excess max(0, ‖r‖ − r_max) through
//!   r / ‖r‖;
//! - the load path Σ |q_k| L_k²: ∂/∂L_k = 2 |q_k| L_k, ∂/∂q_k = sign(q_k) L_k²;
//! - smoothness x_i − (1/d_i) Σ_j x_j over the d_i neighbours j: I at i, −I / d_i at each j.
//!
//! df/dv is then the sum of df/dq_k over the members of each variable.
//!
//! **Residuals.** When every term is a squared or mean-squared error, f = ‖r‖² with one
//! residual per component of each goal, r = √(α w / n) (p − t) (n the term's goal count for a
//! mean, else 1), and row i of the Jacobian dr/dv is the gradient above with the cotangent of
//! r_i alone, ∂r_i/∂p = √(α w / n) e_c: one adjoint solve per residual, the factorisation of
//! the form reused ([`Problem::residuals`], the model of `super::levenberg_marquardt`).

use super::spec::ErrorKind;
use crate::error::Result;
use crate::sensitivity::{Cotangent, FdmSensitivity};
use crate::topology::Topology;
use nalgebra::{DMatrix, Vector3};

/// One design variable: the members whose force density it sets, and its bounds.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Variable {
    pub members: Vec<usize>,
    pub lower: f64,
    pub upper: f64,
    pub start: f64,
}

/// One goal on one node or member (a term holds n of them).
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Goal {
    Position {
        node: usize,
        target: Vector3<f64>,
    },
    Coordinate {
        node: usize,
        axis: usize,
        target: f64,
    },
    Plane {
        node: usize,
        point: Vector3<f64>,
        normal: Vector3<f64>,
    },
    Line {
        node: usize,
        point: Vector3<f64>,
        direction: Vector3<f64>,
    },
    ForceDensity {
        member: usize,
        target: f64,
    },
    Length {
        member: usize,
        target: f64,
    },
    Force {
        member: usize,
        target: f64,
    },
    Direction {
        member: usize,
        target: Vector3<f64>,
    },
    Reaction {
        held: usize,
        target: Vector3<f64>,
    },
    ReactionForce {
        held: usize,
        target: f64,
    },
    ReactionLimit {
        held: usize,
        limit: f64,
    },
    LoadPath {
        members: Vec<usize>,
        target: f64,
    },
    Smoothness {
        node: usize,
        neighbours: Vec<usize>,
    },
}

/// A compiled term: its error over its weighted goals.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Term {
    pub name: String,
    pub error: ErrorKind,
    pub weight: f64,
    pub goals: Vec<(Goal, f64)>,
}

/// A design problem compiled against its topology (`super::compile`).
#[derive(Debug, Clone)]
pub(super) struct Problem {
    pub topology: Topology,
    /// Every member's force density at the start (the varied ones are overwritten).
    pub base: Vec<f64>,
    pub variables: Vec<Variable>,
    pub terms: Vec<Term>,
}

/// The objective at one point: its value, each term's, and the form found there.
pub(super) struct Evaluation {
    pub objective: f64,
    pub terms: Vec<f64>,
    pub gradient: Vec<f64>,
    pub form: FdmSensitivity,
}

/// The residuals of a sum-of-squares problem ([`Problem::residuals`]).
pub(super) struct Residuals {
    /// r, f = ‖r‖².
    pub values: Vec<f64>,
    /// dr/dv (residuals × variables), when asked.
    pub jacobian: Option<DMatrix<f64>>,
    /// Each term's value.
    pub terms: Vec<f64>,
}

/// The form at one point and what the goals read from it.
struct State {
    q: Vec<f64>,
    form: FdmSensitivity,
    nodes: Vec<Vector3<f64>>,
    pairs: Vec<[usize; 2]>,
    lengths: Vec<f64>,
    reactions: Vec<Vector3<f64>>,
    held: Vec<usize>,
}

/// A prediction: 1 or 3 numbers.
#[derive(Clone, Copy)]
struct Prediction {
    value: Vector3<f64>,
    dim: usize,
}

impl Prediction {
    fn scalar(v: f64) -> Self {
        Self {
            value: Vector3::new(v, 0.0, 0.0),
            dim: 1,
        }
    }
    fn vector(v: Vector3<f64>) -> Self {
        Self { value: v, dim: 3 }
    }
}

impl Problem {
    /// Every member's force density for the variables `v`.
    pub fn force_densities(&self, v: &[f64]) -> Vec<f64> {
        let mut q = self.base.clone();
        for (var, &value) in self.variables.iter().zip(v) {
            for &k in &var.members {
                q[k] = value;
            }
        }
        q
    }

    /// The form at `v` and what the goals read from it.
    fn state(&self, v: &[f64]) -> Result<State> {
        let q = self.force_densities(v);
        let form = FdmSensitivity::new(&self.topology, &q)?;
        Ok(State {
            nodes: form.nodes().to_vec(),
            pairs: self.topology.member_nodes(),
            lengths: form.lengths(),
            reactions: form.reactions(),
            held: form.held().to_vec(),
            form,
            q,
        })
    }

    /// One goal's prediction at `st` and its target (3 numbers; a scalar in the first).
    fn predict(&self, st: &State, goal: &Goal) -> (Prediction, Vector3<f64>) {
        match goal {
            Goal::Position { node, target } => (Prediction::vector(st.nodes[*node]), *target),
            Goal::Plane {
                node,
                point,
                normal,
            } => (
                Prediction::scalar((st.nodes[*node] - point).dot(normal)),
                Vector3::zeros(),
            ),
            Goal::Line {
                node,
                point,
                direction,
            } => {
                let d = st.nodes[*node] - point;
                (
                    Prediction::vector(d - direction * direction.dot(&d)),
                    Vector3::zeros(),
                )
            }
            Goal::ForceDensity { member, target } => (
                Prediction::scalar(st.q[*member]),
                Vector3::new(*target, 0.0, 0.0),
            ),
            Goal::Coordinate { node, axis, target } => (
                Prediction::scalar(st.nodes[*node][*axis]),
                Vector3::new(*target, 0.0, 0.0),
            ),
            Goal::Length { member, target } => (
                Prediction::scalar(st.lengths[*member]),
                Vector3::new(*target, 0.0, 0.0),
            ),
            Goal::Force { member, target } => (
                Prediction::scalar(st.q[*member] * st.lengths[*member]),
                Vector3::new(*target, 0.0, 0.0),
            ),
            Goal::Direction { member, target } => {
                let [a, b] = st.pairs[*member];
                let d = st.nodes[b] - st.nodes[a];
                let l = d.norm();
                let u = if l > 0.0 { d / l } else { Vector3::zeros() };
                (Prediction::vector(u), *target)
            }
            Goal::Reaction { held, target } => (Prediction::vector(st.reactions[*held]), *target),
            Goal::ReactionForce { held, target } => (
                Prediction::scalar(st.reactions[*held].norm()),
                Vector3::new(*target, 0.0, 0.0),
            ),
            Goal::ReactionLimit { held, limit } => (
                Prediction::scalar((st.reactions[*held].norm() - limit).max(0.0)),
                Vector3::zeros(),
            ),
            Goal::LoadPath { members, target } => (
                Prediction::scalar(
                    members
                        .iter()
                        .map(|&k| st.q[k].abs() * st.lengths[k] * st.lengths[k])
                        .sum(),
                ),
                Vector3::new(*target, 0.0, 0.0),
            ),
            Goal::Smoothness { node, neighbours } => {
                let mean = neighbours
                    .iter()
                    .fold(Vector3::zeros(), |s, &j| s + st.nodes[j])
                    / neighbours.len() as f64;
                (Prediction::vector(st.nodes[*node] - mean), Vector3::zeros())
            }
        }
    }

    /// The form at `v`, the objective, its terms and its gradient with respect to `v`
    /// (module docs).
    pub fn evaluate(&self, v: &[f64]) -> Result<Evaluation> {
        let mut st = self.state(v)?;
        let m = st.q.len();
        let mut cot = Cotangent::zeros(st.nodes.len(), m);
        let mut dl = vec![0.0; m];
        let mut dforce = vec![0.0; m];
        let mut values = Vec::with_capacity(self.terms.len());
        for term in &self.terms {
            let predicted: Vec<_> = term
                .goals
                .iter()
                .map(|(g, _)| self.predict(&st, g))
                .collect();
            let sum: f64 = predicted
                .iter()
                .zip(&term.goals)
                .map(|((p, t), (_, w))| element_error(term.error, p, t, *w))
                .sum();
            let n = term.goals.len() as f64;
            let (value, dvalue) = aggregate(term.error, sum, n);
            values.push(term.weight * value);
            let scale = term.weight * dvalue;
            if scale == 0.0 {
                continue;
            }
            for ((p, t), (goal, w)) in predicted.iter().zip(&term.goals) {
                let g = scale * element_slope(term.error, p, t, *w);
                self.pull_back(goal, g, &st)
                    .apply(&mut cot, &mut dl, &mut dforce);
            }
        }
        let cot = cot.lengths(&st.form, &dl)?.forces(&st.form, &dforce)?;
        let grad = st.form.adjoint(&cot)?;
        Ok(Evaluation {
            objective: values.iter().sum(),
            terms: values,
            gradient: self.by_variable(&grad.force_densities),
            form: st.form,
        })
    }

    /// df/dv from df/dq: each variable's members summed.
    fn by_variable(&self, dq: &[f64]) -> Vec<f64> {
        self.variables
            .iter()
            .map(|var| var.members.iter().map(|&k| dq[k]).sum())
            .collect()
    }

    /// Whether every term is a sum of squares (squared or mean-squared errors), so that
    /// f = ‖r‖² ([`Self::residuals`]); the first term that is not, otherwise.
    pub fn least_squares(&self) -> std::result::Result<(), usize> {
        match self
            .terms
            .iter()
            .position(|t| !matches!(t.error, ErrorKind::Squared | ErrorKind::MeanSquared))
        {
            Some(i) => Err(i),
            None => Ok(()),
        }
    }

    /// The residuals r at `v` of a problem whose terms are all squared or mean-squared
    /// errors, f = ‖r‖² (module docs), each term's value, and, when `jacobian`, J = dr/dv
    /// (one adjoint solve per residual, the factorisation reused).
    pub fn residuals(&self, v: &[f64], jacobian: bool) -> Result<Residuals> {
        let mut st = self.state(v)?;
        let m = st.q.len();
        let mut values = Vec::new();
        let mut seeds = Vec::new();
        let mut terms = Vec::with_capacity(self.terms.len());
        for term in &self.terms {
            let n = if term.error == ErrorKind::MeanSquared {
                term.goals.len() as f64
            } else {
                1.0
            };
            let mut sum = 0.0;
            for (goal, w) in &term.goals {
                let (p, t) = self.predict(&st, goal);
                let scale = (term.weight * w / n).sqrt();
                for c in 0..p.dim {
                    let r = scale * (p.value[c] - t[c]);
                    values.push(r);
                    sum += r * r;
                    let mut g = Vector3::zeros();
                    g[c] = scale;
                    seeds.push((goal, g));
                }
            }
            terms.push(sum);
        }
        let jacobian = if jacobian {
            let mut j = DMatrix::zeros(values.len(), self.variables.len());
            for (row, (goal, g)) in seeds.into_iter().enumerate() {
                let mut cot = Cotangent::zeros(st.nodes.len(), m);
                let (mut dl, mut dforce) = (vec![0.0; m], vec![0.0; m]);
                self.pull_back(goal, g, &st)
                    .apply(&mut cot, &mut dl, &mut dforce);
                let cot = cot.lengths(&st.form, &dl)?.forces(&st.form, &dforce)?;
                let grad = st.form.adjoint(&cot)?;
                for (col, d) in self
                    .by_variable(&grad.force_densities)
                    .into_iter()
                    .enumerate()
                {
                    j[(row, col)] = d;
                }
            }
            Some(j)
        } else {
            None
        };
        Ok(Residuals {
            values,
            jacobian,
            terms,
        })
    }

    /// The partial derivatives of f through one goal's prediction, given ∂f/∂p = `g`.
    fn pull_back(&self, goal: &Goal, g: Vector3<f64>, st: &State) -> Pullback {
        let (nodes, q, lengths) = (&st.nodes, &st.q, &st.lengths);
        let (reactions, held, pairs) = (&st.reactions, &st.held, &st.pairs);
        let mut out = Pullback::default();
        let reaction = |out: &mut Pullback, index: usize, g: Vector3<f64>| {
            let h = held[index];
            for (k, &[a, b]) in pairs.iter().enumerate() {
                for (end, other) in [(a, b), (b, a)] {
                    if end == h {
                        out.nodes.push((h, q[k] * g));
                        out.nodes.push((other, -q[k] * g));
                        out.q.push((k, g.dot(&(nodes[h] - nodes[other]))));
                    }
                }
            }
        };
        match goal {
            Goal::Position { node, .. } => out.nodes.push((*node, g)),
            Goal::Plane { node, normal, .. } => out.nodes.push((*node, g.x * normal)),
            Goal::Line {
                node, direction, ..
            } => out.nodes.push((*node, g - direction * direction.dot(&g))),
            Goal::ForceDensity { member, .. } => out.q.push((*member, g.x)),
            Goal::Coordinate { node, axis, .. } => {
                let mut v = Vector3::zeros();
                v[*axis] = g.x;
                out.nodes.push((*node, v));
            }
            Goal::Length { member, .. } => out.lengths.push((*member, g.x)),
            Goal::Force { member, .. } => out.forces.push((*member, g.x)),
            Goal::Direction { member, .. } => {
                let [a, b] = pairs[*member];
                let d = nodes[b] - nodes[a];
                let l = d.norm();
                if l > 0.0 {
                    let u = d / l;
                    let gd = (g - u * u.dot(&g)) / l;
                    out.nodes.push((b, gd));
                    out.nodes.push((a, -gd));
                }
            }
            Goal::Reaction { held, .. } => reaction(&mut out, *held, g),
            Goal::ReactionForce { held, .. } => {
                let r = reactions[*held];
                let norm = r.norm();
                if norm > 0.0 {
                    reaction(&mut out, *held, g.x * r / norm);
                }
            }
            Goal::ReactionLimit { held, limit } => {
                let r = reactions[*held];
                let norm = r.norm();
                if norm > *limit && norm > 0.0 {
                    reaction(&mut out, *held, g.x * r / norm);
                }
            }
            Goal::LoadPath { members, .. } => {
                for &k in members {
                    out.lengths.push((k, g.x * 2.0 * q[k].abs() * lengths[k]));
                    out.q
                        .push((k, g.x * q[k].signum() * lengths[k] * lengths[k]));
                }
            }
            Goal::Smoothness { node, neighbours } => {
                out.nodes.push((*node, g));
                let share = g / neighbours.len() as f64;
                for &j in neighbours {
                    out.nodes.push((j, -share));
                }
            }
        }
        out
    }
}

/// Partial derivatives of f from one goal: on nodes, lengths, forces and q directly.
#[derive(Default)]
struct Pullback {
    nodes: Vec<(usize, Vector3<f64>)>,
    lengths: Vec<(usize, f64)>,
    forces: Vec<(usize, f64)>,
    q: Vec<(usize, f64)>,
}

impl Pullback {
    fn apply(self, cot: &mut Cotangent, dl: &mut [f64], dforce: &mut [f64]) {
        for (i, g) in self.nodes {
            cot.nodes[i] += g;
        }
        for (k, g) in self.lengths {
            dl[k] += g;
        }
        for (k, g) in self.forces {
            dforce[k] += g;
        }
        for (k, g) in self.q {
            cot.force_densities[k] += g;
        }
    }
}

/// e_j of one goal (module docs).
fn element_error(error: ErrorKind, p: &Prediction, t: &Vector3<f64>, w: f64) -> f64 {
    let r = (0..p.dim).map(|c| p.value[c] - t[c]);
    match error {
        ErrorKind::Squared | ErrorKind::MeanSquared | ErrorKind::RootMeanSquared => {
            w * r.map(|x| x * x).sum::<f64>()
        }
        ErrorKind::Absolute | ErrorKind::MeanAbsolute => w * r.map(f64::abs).sum::<f64>(),
        ErrorKind::Prediction | ErrorKind::MeanPrediction => {
            w * (0..p.dim).map(|c| p.value[c]).sum::<f64>()
        }
    }
}

/// ∂e_j/∂p_j.
fn element_slope(error: ErrorKind, p: &Prediction, t: &Vector3<f64>, w: f64) -> Vector3<f64> {
    let mut g = Vector3::zeros();
    for c in 0..p.dim {
        let r = p.value[c] - t[c];
        g[c] = match error {
            ErrorKind::Squared | ErrorKind::MeanSquared | ErrorKind::RootMeanSquared => 2.0 * w * r,
            ErrorKind::Absolute | ErrorKind::MeanAbsolute => {
                if r == 0.0 {
                    0.0
                } else {
                    w * r.signum()
                }
            }
            ErrorKind::Prediction | ErrorKind::MeanPrediction => w,
        };
    }
    g
}

/// A(S) and A′(S) over n goals.
fn aggregate(error: ErrorKind, sum: f64, n: f64) -> (f64, f64) {
    match error {
        ErrorKind::Squared | ErrorKind::Absolute | ErrorKind::Prediction => (sum, 1.0),
        ErrorKind::MeanSquared | ErrorKind::MeanAbsolute | ErrorKind::MeanPrediction => {
            (sum / n, 1.0 / n)
        }
        ErrorKind::RootMeanSquared => {
            let rms = (sum / n).max(0.0).sqrt();
            // at an exact fit the root has no derivative: the fit is the minimum, slope 0
            let slope = if rms > 0.0 { 0.5 / (n * rms) } else { 0.0 };
            (rms, slope)
        }
    }
}
