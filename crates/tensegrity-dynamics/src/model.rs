//! The class-1 model with coincidence constraints, and its right-hand side.
//!
//! Every bar k owns two class-1 nodes, 2k (start) and 2k+1 (end). A node of the structure file
//! shared by several bars becomes one copy per bar; the first copy (lowest bar index) is its
//! representative and carries its strings, loads and ground contact; the copies are tied in a
//! chain by coincidence constraints n_{copy j−1} − n_{copy j} = 0 (a chain keeps the Ω system
//! of a many-bar joint banded, where ties to the representative would make it dense). A
//! supported node adds n_rep·e_d = d for every fixed direction d. Together these are the
//! columns of N P = D (with D constant). Nodes on no bar must be fixed in all three
//! directions: they become anchors (fixed points for strings).
//!
//! Per bar (thesis eq. 2.1–2.2 with J = m/12, ERRATA 2.3/2.5), with end forces f₁, f₂:
//!
//! J b̈ = ½(f₂ − f₁) − (1/(2l²)) b bᵀ(f₂ − f₁) − (J/l²) b ‖ḃ‖²,   m r̈ = f₁ + f₂,
//!
//! n̈₁ = r̈ − ½b̈, n̈₂ = r̈ + ½b̈, with the *current* length l. This is N̈M + NK = F with
//! λ̂ = −Ĵ l̂⁻²⌊ḂᵀḂ⌋ − ½ l̂⁻²⌊BᵀFC_bᵀ⌋, evaluated bar by bar in O(β). The forces are
//! F = W − S γ̂ C_s + ΩPᵀ (ERRATA 2.8). Ω solves the closed form
//!
//! [(PᵀM⁻¹P)⊗I₃ − ¼ Σ_k (J_k l_k²)⁻¹ (h_k h_kᵀ)⊗(b_k b_kᵀ)] vec Ω = vec(D̈ − N̈₀P),
//!
//! which is sparse (two constraints interact only through a shared bar); its pattern is
//! factored symbolically once (module `omega`) and refactored numerically per evaluation.
//! Small jointed structures (at most 8 constrained bars) skip Ω: the same KKT system is solved
//! in joint space, N P = D eliminated by its 0/1 null-space basis and one multiplier per bar
//! solved for instead (module `omega::joint_space`; the Ω path remains its fallback and
//! gives [`Model::member_forces`] the joint forces).
//! Because N P = D is linear, every Runge–Kutta method keeps it to round-off when the initial
//! velocities satisfy Ṅ P = 0.

use super::cluster_forces::{ClusterData, ClusterEnd};
use super::forces::{Ground, GroundModel};
use super::omega::joint_space::{JointScratch, JointSpace};
use super::omega::{axis_of, ConstraintMatrix, Row, RowEntry};
use super::strings::StringLaw;
use super::system::System;
pub(crate) use super::system::{set3, vec3};
use nalgebra::Vector3;
use tensegrity_core::error::{CoreError, DynamicsError, ModelError, StepHint};
use tensegrity_core::structure::{MemberId, Structure};

/// Time-varying rest lengths: called with t and the slice of rest lengths (one per string,
/// then one per cluster, pre-filled with the static values) to overwrite.
pub type RestLengthFn = Box<dyn Fn(f64, &mut [f64]) + Send + Sync>;
/// Time-varying loads: called with t and a zeroed slice (one force per file node) to fill;
/// these forces are added to the static loads.
pub type LoadFn = Box<dyn Fn(f64, &mut [Vector3<f64>]) + Send + Sync>;

/// One rest length driven over one control period [t0, t1] of a [`Stepper`](crate::Stepper):
/// r(t) = r0 (1 − w) + r1 w with w = (t − t0)/(t1 − t0), held at r0 before and r1 after (the
/// interpolation of a scene's actuation tables, so that a stepped run and a table reproduce
/// each other bit for bit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Drive {
    /// The rest-length slot (strings, then clusters).
    pub slot: usize,
    pub t0: f64,
    pub t1: f64,
    pub r0: f64,
    pub r1: f64,
}

impl Drive {
    /// The rest length at `t`.
    #[inline]
    pub(crate) fn at(&self, t: f64) -> f64 {
        if t <= self.t0 {
            self.r0
        } else if t >= self.t1 {
            self.r1
        } else {
            let w = (t - self.t0) / (self.t1 - self.t0);
            self.r0 * (1.0 - w) + self.r1 * w
        }
    }
}

/// Where a file node lives in the class-1 model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeRef {
    /// Class-1 node index (the representative copy).
    Free(usize),
    /// A fixed string anchor at this position.
    Anchor(Vector3<f64>),
}

#[derive(Debug, Clone, Copy)]
pub(crate) struct BarData {
    pub mass: f64,
    pub inv_mass: f64,
    /// 12 / m (J⁻¹ for a unit length), computed once.
    pub inv_j: f64,
    pub length0: f64,
}

#[derive(Debug, Clone, Copy)]
pub(crate) struct StringData {
    pub ends: [NodeRef; 2],
    pub law: StringLaw,
}

/// A linear scalar constraint row of N P = D: Σ grad·x = target.
#[derive(Debug, Clone)]
pub(crate) struct LinearRow {
    pub row: Row,
    pub target: f64,
}

/// A constraint row of N P = D whose gradients are all ±e_d: Σ_e s_e x[at_e] = target.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AxisRow {
    pub at: [usize; 2],
    pub s: [f64; 2],
    pub len: usize,
}

impl AxisRow {
    /// −Σ_e s_e a[at_e], summed in the entries' order from 0 (exactly the row's terms of
    /// `constraint_rhs`'s entry loop).
    #[inline]
    pub(crate) fn neg_dot(&self, a: &[f64]) -> f64 {
        let mut acc = 0.0;
        for (&at, &s) in self.at.iter().zip(&self.s).take(self.len) {
            acc -= s * a[at];
        }
        acc
    }
}

/// The class-1 dynamic model of a [`Structure`].
pub struct Model {
    pub(crate) n_nodes: usize,
    pub(crate) n1: usize,
    pub(crate) bars: Vec<BarData>,
    pub(crate) inv_mass: Vec<f64>,
    pub(crate) node_map: Vec<NodeRef>,
    pub(crate) strings: Vec<StringData>,
    /// The clustered strings (module `cluster_forces`).
    pub(crate) clusters: Vec<ClusterData>,
    pub(crate) w_const: Vec<Vector3<f64>>,
    pub(crate) linear_rows: Vec<LinearRow>,
    pub(crate) ground: Option<Ground>,
    pub(crate) contact: Vec<(usize, usize)>,
    pub(crate) total_weight: Vector3<f64>,
    pub(crate) rest_fn: Option<RestLengthFn>,
    pub(crate) load_fn: Option<LoadFn>,
    /// Rest lengths set step by step by a [`Stepper`](crate::Stepper) (after `rest_fn`).
    pub(crate) drives: Vec<Drive>,
    pub(crate) constrained_bars: Vec<usize>,
    /// The entries of N P = D as (row, class-1 node, axis d, sign s) when every gradient is
    /// s·e_d (always, for the rows built here): the Ω right-hand side and the constraint forces
    /// then take one multiply per entry instead of a 3-vector product.
    pub(crate) axis_entries: Option<Vec<(usize, usize, usize, f64)>>,
    /// The same entries row by row: for row r, up to two (position 3·node + d in a state
    /// half, sign s) with the count (the Ω right-hand side and the ‖N P − D‖ monitor as one
    /// pass over the rows).
    pub(crate) axis_rows: Option<Vec<AxisRow>>,
    pub(crate) x0: Vec<f64>,
    /// The joint-space form of the constrained bars (module `omega::joint_space`), when
    /// they are few: the right-hand side then solves for the bar multipliers instead of Ω.
    pub(crate) joint_space: Option<JointSpace>,
    /// The bars on no constraint row (their accelerations are the class-1 closed form).
    pub(crate) free_bars: Vec<usize>,
    /// The class-1 nodes of every string's ends, when no string ends at an anchor.
    pub(crate) string_nodes: Option<Vec<[usize; 2]>>,
}

impl std::fmt::Debug for Model {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Model")
            .field("nodes", &self.n_nodes)
            .field("class1_nodes", &self.n1)
            .field("bars", &self.bars.len())
            .field("strings", &self.strings.len())
            .field("constraint_rows", &self.linear_rows.len())
            .field("ground", &self.ground)
            .finish()
    }
}

/// Preallocated buffers for right-hand-side evaluations (one per integrator).
pub struct Workspace {
    pub(crate) f: Vec<Vector3<f64>>,
    pub(crate) rest: Vec<f64>,
    pub(crate) gamma: Vec<f64>,
    pub(crate) extra: Vec<Vector3<f64>>,
    pub(crate) contact_f: Vec<Vector3<f64>>,
    pub(crate) omega: Option<ConstraintMatrix>,
    /// The Ω right-hand side and multipliers (also the multipliers of the contact split's
    /// constraint solves, module `contact_split`).
    pub(crate) omega_rhs: Vec<f64>,
    pub(crate) bhat: Vec<Vector3<f64>>,
    /// The force-independent terms of every bar's accelerations, from the first pass of the
    /// last right-hand side (reused by its second pass after the Ω solve).
    pub(crate) bar_terms: Vec<BarTerms>,
    pub(crate) rhs_evals: u64,
    /// Friction anchors of the contact nodes ([`GroundModel::Stick`], module `stick`).
    pub(crate) anchors: Vec<Option<super::anchor::Anchor>>,
    /// Scratch of the joint-space form.
    pub(crate) joint: Box<JointScratch>,
    /// The contact's non-conservative work (normal damping, tangential friction; J, from the
    /// start) as integrated by an integrator that applies the contact in its own substeps
    /// ([`super::imex`]); `None` for integrators that evaluate it in the right-hand side.
    pub(crate) contact_work: Option<(f64, f64)>,
}

/// The terms of a bar's accelerations that do not depend on the forces: b = x_b − x_a,
/// l² = ‖b‖², and the centripetal term b ‖ḃ‖² / l².
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct BarTerms {
    pub b: Vector3<f64>,
    pub l2: f64,
    pub centripetal: Vector3<f64>,
}

impl BarTerms {
    /// The terms of the bar from `xa` to `xb` with end velocities `va`, `vb`.
    #[inline]
    pub(crate) fn of(xa: &[f64], xb: &[f64], va: &[f64], vb: &[f64]) -> Self {
        let b = Vector3::new(xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]);
        let bd = Vector3::new(vb[0] - va[0], vb[1] - va[1], vb[2] - va[2]);
        let l2 = b.norm_squared();
        Self {
            b,
            l2,
            centripetal: b * (bd.norm_squared() / l2),
        }
    }

    /// The accelerations of the two ends under end forces `fa`, `fb`, with ḃ = v_b − v_a and
    /// J⁻¹ = 12/m: b̈ = (½f_d − b (½ bᵀf_d / l²)) J⁻¹ − b ‖ḃ‖²/l² (f_d = f_b − f_a),
    /// r̈ = (f_a + f_b)/m, n̈_a = r̈ − ½b̈, n̈_b = r̈ + ½b̈ (module docs).
    #[inline]
    pub(crate) fn accel(
        &self,
        bar: &BarData,
        fa: &Vector3<f64>,
        fb: &Vector3<f64>,
        out: &mut [f64],
    ) {
        let b = &self.b;
        let fd = fb - fa;
        let bdd = (0.5 * fd - b * (0.5 * b.dot(&fd) / self.l2)) * bar.inv_j - self.centripetal;
        let rdd = (fa + fb) / bar.mass;
        let (aa, ab) = (rdd - 0.5 * bdd, rdd + 0.5 * bdd);
        out[..3].copy_from_slice(aa.as_slice());
        out[3..6].copy_from_slice(ab.as_slice());
    }
}

impl std::fmt::Debug for Workspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Workspace")
            .field("rhs_evals", &self.rhs_evals)
            .finish()
    }
}

impl Workspace {
    /// Number of right-hand-side evaluations made with this workspace.
    pub fn rhs_evals(&self) -> u64 {
        self.rhs_evals
    }
}

/// Node i of `y` with one range check (as [`vec3`]).
#[inline]
fn node_of(y: &[f64], i: usize) -> Vector3<f64> {
    let p = &y[3 * i..3 * i + 3];
    Vector3::new(p[0], p[1], p[2])
}

/// The model as the system the integrators advance: y = (x, v) of the class-1 nodes,
/// f = [`Model::rhs`].
impl System for Model {
    type Workspace = Workspace;

    fn state_len(&self) -> usize {
        Model::state_len(self)
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64], ws: &mut Workspace) -> Result<(), CoreError> {
        Model::rhs(self, t, y, dy, ws)
    }
}

impl Model {
    /// Builds the class-1 model of `structure`: every bar needs a mass (given, or ρπr²l from
    /// its material and radius), every string a stiffness (a missing rest length means the
    /// initial length, i.e. no prestress).
    pub fn new(structure: &Structure, ground: Option<Ground>) -> Result<Self, CoreError> {
        let n_nodes = structure.n_nodes();
        let nb = structure.n_bars();
        if nb == 0 {
            return Err(DynamicsError::NoBars.into());
        }
        let n1 = 2 * nb;
        let nodes = structure.nodes();
        let mut bars = Vec::with_capacity(nb);
        let mut copies: Vec<Vec<usize>> = vec![Vec::new(); n_nodes];
        let mut x0 = vec![0.0; 3 * n1];
        for (k, bar) in structure.bars().iter().enumerate() {
            let [a, b] = bar.nodes;
            // The mass, or else ρ π r² l from the bar's material and radius.
            let mass = structure
                .bar_mass(k)
                .filter(|m| m.is_finite() && *m > 0.0)
                .ok_or(ModelError::MissingProperty {
                    member: MemberId::Bar(k),
                    analysis: "dynamics",
                    property: "mass",
                })?;
            copies[a].push(2 * k);
            copies[b].push(2 * k + 1);
            set3(&mut x0, 2 * k, &nodes[a]);
            set3(&mut x0, 2 * k + 1, &nodes[b]);
            bars.push(BarData {
                mass,
                inv_mass: 1.0 / mass,
                inv_j: 12.0 / mass,
                length0: (nodes[b] - nodes[a]).norm(),
            });
        }
        let fixed = structure.fixed_dofs();
        let mut node_map = Vec::with_capacity(n_nodes);
        let mut linear_rows = Vec::new();
        for i in 0..n_nodes {
            if copies[i].is_empty() {
                if fixed[i] == [true; 3] {
                    node_map.push(NodeRef::Anchor(nodes[i]));
                    continue;
                }
                // Nodes that no member touches at all are harmless: ignore them as anchors.
                let touched = structure.strings().iter().any(|s| s.nodes.contains(&i))
                    || structure.clusters().iter().any(|c| c.nodes.contains(&i));
                if touched {
                    return Err(DynamicsError::FreeNodeWithoutBar { node: i }.into());
                }
                node_map.push(NodeRef::Anchor(nodes[i]));
                continue;
            }
            let rep = copies[i][0];
            node_map.push(NodeRef::Free(rep));
            // a chain of ties (copy j to copy j − 1), not a star on the representative: two
            // ties interact only through a shared copy, so a hub of k bars gives a banded
            // block of Ω instead of a dense k × k one
            for pair in copies[i].windows(2) {
                let (prev, c) = (pair[0], pair[1]);
                for d in 0..3 {
                    let mut e = Vector3::zeros();
                    e[d] = 1.0;
                    linear_rows.push(LinearRow {
                        row: Row {
                            entries: [
                                Some(RowEntry {
                                    node: prev,
                                    grad: e,
                                }),
                                Some(RowEntry { node: c, grad: -e }),
                            ],
                        },
                        target: 0.0,
                    });
                }
            }
            for d in 0..3 {
                if fixed[i][d] {
                    let mut e = Vector3::zeros();
                    e[d] = 1.0;
                    linear_rows.push(LinearRow {
                        row: Row {
                            entries: [Some(RowEntry { node: rep, grad: e }), None],
                        },
                        target: nodes[i][d],
                    });
                }
            }
        }
        let mut strings = Vec::with_capacity(structure.n_strings());
        for (k, s) in structure.strings().iter().enumerate() {
            let stiffness = s.stiffness.ok_or(ModelError::MissingProperty {
                member: MemberId::String(k),
                analysis: "dynamics",
                property: "stiffness",
            })?;
            let [a, b] = s.nodes;
            let rest_length = s.rest_length.unwrap_or((nodes[b] - nodes[a]).norm());
            strings.push(StringData {
                ends: [node_map[a], node_map[b]],
                law: StringLaw {
                    stiffness,
                    rest_length,
                    damping: s.damping,
                },
            });
        }
        let clusters = clusters_of(structure, &node_map)?;
        let mut w_const = vec![Vector3::zeros(); n1];
        for l in structure.loads() {
            if let NodeRef::Free(i) = node_map[l.node] {
                w_const[i] += l.force;
            }
        }
        let mut total_weight = Vector3::zeros();
        if let Some(g) = structure.gravity() {
            for (k, b) in bars.iter().enumerate() {
                w_const[2 * k] += 0.5 * b.mass * g;
                w_const[2 * k + 1] += 0.5 * b.mass * g;
                total_weight += b.mass * g;
            }
        }
        let mut constrained_bars: Vec<usize> = linear_rows
            .iter()
            .flat_map(|r| r.row.entries.iter().flatten().map(|e| e.node / 2))
            .collect();
        constrained_bars.sort_unstable();
        constrained_bars.dedup();
        let inv_mass = bars.iter().map(|b| b.inv_mass).collect();
        let axis_entries: Option<Vec<(usize, usize, usize, f64)>> = linear_rows
            .iter()
            .enumerate()
            .flat_map(|(r, row)| {
                row.row
                    .entries
                    .iter()
                    .flatten()
                    .map(move |e| axis_of(&e.grad).map(|(d, s)| (r, e.node, d, s)))
            })
            .collect();
        let axis_rows = axis_entries.as_ref().map(|entries| {
            let mut rows = vec![
                AxisRow {
                    at: [0; 2],
                    s: [0.0; 2],
                    len: 0,
                };
                linear_rows.len()
            ];
            for &(r, node, d, sign) in entries {
                let row = &mut rows[r];
                row.at[row.len] = 3 * node + d;
                row.s[row.len] = sign;
                row.len += 1;
            }
            rows
        });
        let node_of: Vec<usize> = structure.bars().iter().flat_map(|b| b.nodes).collect();
        let masses: Vec<f64> = bars.iter().map(|b| b.mass).collect();
        let joint_space = JointSpace::new(&constrained_bars, &masses, &node_of, &copies, &fixed);
        let free_bars = (0..nb)
            .filter(|k| constrained_bars.binary_search(k).is_err())
            .collect();
        let string_nodes = strings
            .iter()
            .map(|s| match s.ends {
                [NodeRef::Free(i), NodeRef::Free(j)] => Some([i, j]),
                _ => None,
            })
            .collect();
        let mut model = Self {
            n_nodes,
            n1,
            bars,
            inv_mass,
            node_map,
            strings,
            clusters,
            w_const,
            linear_rows,
            ground: None,
            contact: Vec::new(),
            total_weight,
            rest_fn: None,
            load_fn: None,
            drives: Vec::new(),
            constrained_bars,
            axis_entries,
            axis_rows,
            x0,
            joint_space,
            free_bars,
            string_nodes,
        };
        if let Some(g) = ground {
            model.set_ground(g)?;
        }
        Ok(model)
    }

    /// Sets (or replaces) the ground plane.
    pub fn set_ground(&mut self, ground: Ground) -> Result<(), CoreError> {
        let candidates: Vec<usize> = match &ground.nodes {
            Some(list) => list.clone(),
            None => (0..self.n_nodes).collect(),
        };
        let mut contact = Vec::new();
        for (k, &i) in candidates.iter().enumerate() {
            if i >= self.n_nodes {
                return Err(DynamicsError::GroundNodeOutOfRange {
                    index: k,
                    node: i,
                    n_nodes: self.n_nodes,
                }
                .into());
            }
            if let NodeRef::Free(c) = self.node_map[i] {
                contact.push((i, c));
            }
        }
        if !(ground.normal.iter().all(|v| v.is_finite()) && ground.normal.norm() > 0.0) {
            return Err(DynamicsError::InvalidGroundNormal {
                x: ground.normal.x,
                y: ground.normal.y,
                z: ground.normal.z,
            }
            .into());
        }
        self.contact = contact;
        self.ground = Some(ground);
        Ok(())
    }

    /// Makes the string and cluster rest lengths follow `f` in time (actuation; [`RestLengthFn`]).
    pub fn set_rest_length_schedule(&mut self, f: RestLengthFn) {
        self.rest_fn = Some(f);
    }

    /// The rest lengths at `t` (one per string, then one per cluster): the static ones,
    /// overwritten by the rest-length schedule and then by a stepper's drives.
    pub fn rest_lengths_at(&self, t: f64) -> Vec<f64> {
        let mut rest: Vec<f64> = self
            .strings
            .iter()
            .map(|s| s.law.rest_length)
            .chain(self.clusters.iter().map(|c| c.rest_length))
            .collect();
        if let Some(f) = &self.rest_fn {
            f(t, &mut rest);
        }
        for d in &self.drives {
            rest[d.slot] = d.at(t);
        }
        rest
    }

    /// Adds the time-varying nodal loads of `f` (actuation).
    pub fn set_load_schedule(&mut self, f: LoadFn) {
        self.load_fn = Some(f);
    }

    /// Number of class-1 nodes (two per bar).
    pub fn n_class1_nodes(&self) -> usize {
        self.n1
    }

    /// Length of the state vector: positions then velocities of the class-1 nodes.
    pub fn state_len(&self) -> usize {
        6 * self.n1
    }

    /// Number of scalar constraint rows of N P = D.
    pub fn n_constraint_rows(&self) -> usize {
        self.linear_rows.len()
    }

    /// Where each file node lives in the class-1 model.
    pub fn node_map(&self) -> &[NodeRef] {
        &self.node_map
    }

    /// The ground, if any.
    pub fn ground(&self) -> Option<&Ground> {
        self.ground.as_ref()
    }

    /// The initial state from the structure's nodes and (optional) velocities. Fails when a
    /// fixed direction has a velocity or a bar would change length.
    pub fn initial_state(&self, structure: &Structure) -> Result<Vec<f64>, CoreError> {
        let mut y = vec![0.0; self.state_len()];
        y[..3 * self.n1].copy_from_slice(&self.x0);
        if let Some(vel) = structure.velocities() {
            let (_, v) = y.split_at_mut(3 * self.n1);
            for (k, bar) in structure.bars().iter().enumerate() {
                set3(v, 2 * k, &vel[bar.nodes[0]]);
                set3(v, 2 * k + 1, &vel[bar.nodes[1]]);
            }
            let fixed = structure.fixed_dofs();
            let vmax = vel.iter().map(|v| v.norm()).fold(0.0, f64::max);
            for (i, f) in fixed.iter().enumerate() {
                for d in 0..3 {
                    if f[d] && vel[i][d] != 0.0 {
                        return Err(DynamicsError::InconsistentVelocity {
                            item: format!("node {i}"),
                            reason: "velocity along a fixed direction",
                            residual: vel[i][d].abs(),
                        }
                        .into());
                    }
                }
            }
            for (k, bar) in structure.bars().iter().enumerate() {
                let [a, b] = bar.nodes;
                let bv = structure.nodes()[b] - structure.nodes()[a];
                let rate = bv.dot(&(vel[b] - vel[a])) / bv.norm();
                if rate.abs() > 1e-9 * vmax.max(1.0) {
                    return Err(DynamicsError::InconsistentVelocity {
                        item: MemberId::Bar(k).to_string(),
                        reason: "the bar would change length (bᵀḃ ≠ 0)",
                        residual: rate.abs(),
                    }
                    .into());
                }
            }
        }
        Ok(y)
    }

    /// A fresh workspace (allocates the buffers and the symbolic Ω factorisation).
    pub fn workspace(&self) -> Result<Workspace, CoreError> {
        let omega = if self.linear_rows.is_empty() {
            None
        } else {
            Some(ConstraintMatrix::new(
                self.linear_rows.iter().map(|r| r.row.clone()).collect(),
                true,
            )?)
        };
        let rest = self
            .strings
            .iter()
            .map(|s| s.law.rest_length)
            .chain(self.clusters.iter().map(|c| c.rest_length))
            .collect();
        Ok(Workspace {
            f: vec![Vector3::zeros(); self.n1],
            rest,
            gamma: vec![0.0; self.strings.len()],
            extra: vec![Vector3::zeros(); self.n_nodes],
            contact_f: vec![Vector3::zeros(); self.contact.len()],
            omega_rhs: vec![0.0; self.linear_rows.len()],
            omega,
            bhat: vec![Vector3::zeros(); self.bars.len()],
            bar_terms: vec![BarTerms::default(); self.bars.len()],
            rhs_evals: 0,
            anchors: vec![None; self.contact.len()],
            joint: Box::default(),
            contact_work: None,
        })
    }

    /// The position of a string end (a class-1 node of `x`, or the anchor).
    #[inline]
    fn end_position(&self, r: NodeRef, x: &[f64]) -> Vector3<f64> {
        match r {
            NodeRef::Free(i) => node_of(x, i),
            NodeRef::Anchor(p) => p,
        }
    }

    /// The velocity of a string end (a class-1 node of `v`; an anchor does not move).
    #[inline]
    fn end_rate(&self, r: NodeRef, v: &[f64]) -> Vector3<f64> {
        match r {
            NodeRef::Free(i) => node_of(v, i),
            NodeRef::Anchor(_) => Vector3::zeros(),
        }
    }

    #[inline]
    fn end_state(&self, r: NodeRef, x: &[f64], v: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
        match r {
            NodeRef::Free(i) => (vec3(x, i), vec3(v, i)),
            NodeRef::Anchor(p) => (p, Vector3::zeros()),
        }
    }

    /// Fills `ws.f` with all non-constraint forces on the class-1 nodes at (t, x, v): static
    /// loads and gravity, actuated loads, strings (ws.gamma), ground (ws.contact_f).
    pub(crate) fn applied_forces(&self, t: f64, x: &[f64], v: &[f64], ws: &mut Workspace) {
        ws.f.copy_from_slice(&self.w_const);
        if let Some(load_fn) = &self.load_fn {
            ws.extra.iter_mut().for_each(|e| *e = Vector3::zeros());
            load_fn(t, &mut ws.extra);
            for (i, e) in ws.extra.iter().enumerate() {
                if let NodeRef::Free(c) = self.node_map[i] {
                    ws.f[c] += e;
                }
            }
        }
        if let Some(rest_fn) = &self.rest_fn {
            for (r, s) in ws.rest.iter_mut().zip(&self.strings) {
                *r = s.law.rest_length;
            }
            let clusters = ws.rest.iter_mut().skip(self.strings.len());
            for (r, c) in clusters.zip(&self.clusters) {
                *r = c.rest_length;
            }
            rest_fn(t, &mut ws.rest);
        }
        for d in &self.drives {
            ws.rest[d.slot] = d.at(t);
        }
        if let Some(ends) = &self.string_nodes {
            // every string between class-1 nodes: the same law without the anchor cases
            let strings = ends.iter().zip(&self.strings).zip(&ws.rest);
            for (((&[i, j], s), &rest), gamma_k) in strings.zip(ws.gamma.iter_mut()) {
                let sv = node_of(x, j) - node_of(x, i);
                let rate = if s.law.damping != 0.0 {
                    node_of(v, j) - node_of(v, i)
                } else {
                    Vector3::zeros()
                };
                let gamma = s.law.force_density(&sv, &rate, rest);
                *gamma_k = gamma;
                if gamma != 0.0 {
                    let t = sv * gamma;
                    ws.f[i] += t;
                    ws.f[j] -= t;
                }
            }
        }
        let general = if self.string_nodes.is_some() {
            &[][..]
        } else {
            &self.strings[..]
        };
        for ((s, &rest), gamma_k) in general.iter().zip(&ws.rest).zip(ws.gamma.iter_mut()) {
            let sv = self.end_position(s.ends[1], x) - self.end_position(s.ends[0], x);
            // the rate only enters a damped string's law
            let rate = if s.law.damping != 0.0 {
                self.end_rate(s.ends[1], v) - self.end_rate(s.ends[0], v)
            } else {
                Vector3::zeros()
            };
            let gamma = s.law.force_density(&sv, &rate, rest);
            *gamma_k = gamma;
            if gamma != 0.0 {
                let t = sv * gamma;
                if let NodeRef::Free(i) = s.ends[0] {
                    ws.f[i] += t;
                }
                if let NodeRef::Free(j) = s.ends[1] {
                    ws.f[j] -= t;
                }
            }
        }
        let cluster_rest = &ws.rest[self.strings.len()..];
        for (c, &rest) in self.clusters.iter().zip(cluster_rest) {
            c.add_forces(x, v, rest, &mut ws.f);
        }
        if let Some(g) = &self.ground {
            match g.model {
                GroundModel::Penalty { .. } => {
                    for (k, &(_, c)) in self.contact.iter().enumerate() {
                        let f = g.penalty_force(&vec3(x, c), &vec3(v, c));
                        ws.contact_f[k] = f;
                        ws.f[c] += f;
                    }
                }
                GroundModel::Stick { .. } => {
                    for (k, &(_, c)) in self.contact.iter().enumerate() {
                        let f = g.stick_force(&vec3(x, c), &vec3(v, c), ws.anchors[k].as_ref());
                        ws.contact_f[k] = f;
                        ws.f[c] += f;
                    }
                }
                GroundModel::Thesis { damping, tolerance } => {
                    let count = self
                        .contact
                        .iter()
                        .filter(|&&(_, c)| g.height(&vec3(x, c)) <= tolerance)
                        .count();
                    let wn = (-self.total_weight.dot(&g.normal)).max(0.0);
                    let share = if count > 0 { wn / count as f64 } else { 0.0 };
                    for (k, &(_, c)) in self.contact.iter().enumerate() {
                        let f = if g.height(&vec3(x, c)) <= tolerance {
                            g.normal * share - vec3(v, c) * damping
                        } else {
                            Vector3::zeros()
                        };
                        ws.contact_f[k] = f;
                        ws.f[c] += f;
                    }
                }
            }
        }
    }

    /// The right-hand side of the first-order system y' = (v, a): `y` and `dy` hold the
    /// positions then velocities of the class-1 nodes. Allocation-free.
    pub fn rhs(
        &self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        ws: &mut Workspace,
    ) -> Result<(), CoreError> {
        self.rhs_with(t, y, dy, ws, true)
    }

    /// [`Model::rhs`]; with `joint_space` false the constrained bars always go through Ω
    /// (leaving the constraint forces Gᵀω in `ws.f`, as [`Model::member_forces`] needs).
    pub(crate) fn rhs_with(
        &self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        ws: &mut Workspace,
        joint_space: bool,
    ) -> Result<(), CoreError> {
        ws.rhs_evals += 1;
        let n3 = 3 * self.n1;
        let (x, v) = y.split_at(n3);
        let (dx, dv) = dy.split_at_mut(n3);
        dx.copy_from_slice(v);
        self.applied_forces(t, x, v, ws);
        if let Some(i) = ws.f.iter().position(|f| !f.iter().all(|c| c.is_finite())) {
            return Err(DynamicsError::NonFiniteState {
                t,
                member: MemberId::Bar(i / 2),
                hint: StepHint::Unknown,
            }
            .into());
        }
        if let (true, Some(js)) = (joint_space, &self.joint_space) {
            for &k in &self.free_bars {
                let (xk, vk) = (&x[6 * k..6 * k + 6], &v[6 * k..6 * k + 6]);
                let terms = BarTerms::of(&xk[..3], &xk[3..], &vk[..3], &vk[3..]);
                terms.accel(
                    &self.bars[k],
                    &ws.f[2 * k],
                    &ws.f[2 * k + 1],
                    &mut dv[6 * k..6 * k + 6],
                );
            }
            if js.accelerations(x, v, &ws.f, dv, &mut ws.joint) {
                return Ok(());
            }
        }
        self.first_pass(x, v, &ws.f, dv, &mut ws.bar_terms);
        if let Some(om) = ws.omega.as_mut() {
            for (bh, bt) in ws.bhat.iter_mut().zip(&ws.bar_terms) {
                *bh = bt.b * (1.0 / bt.b.norm());
            }
            if let Err(e) = om.assemble_and_factor(&ws.bhat, &self.inv_mass) {
                // A NaN/∞ in the state or the forces shows up as a failed factorisation:
                // report it as such, naming the bar.
                let bad = (0..self.n1).find(|&i| {
                    !(vec3(x, i).iter().all(|c| c.is_finite())
                        && vec3(v, i).iter().all(|c| c.is_finite())
                        && ws.f[i].iter().all(|c| c.is_finite()))
                });
                return Err(match bad {
                    Some(i) => CoreError::Dynamics(DynamicsError::NonFiniteState {
                        t,
                        member: MemberId::Bar(i / 2),
                        hint: StepHint::Unknown,
                    }),
                    None => e,
                });
            }
            self.constraint_rhs(dv, &mut ws.omega_rhs);
            om.solve_in_place(&mut ws.omega_rhs);
            self.add_constraint_forces(&ws.omega_rhs, &mut ws.f);
            for &k in &self.constrained_bars {
                ws.bar_terms[k].accel(
                    &self.bars[k],
                    &ws.f[2 * k],
                    &ws.f[2 * k + 1],
                    &mut dv[6 * k..6 * k + 6],
                );
            }
        }
        Ok(())
    }

    /// The unconstrained accelerations of every bar into `dv` ([`BarTerms::accel`]), keeping
    /// each bar's force-independent terms in `terms` for the second pass.
    fn first_pass(
        &self,
        x: &[f64],
        v: &[f64],
        f: &[Vector3<f64>],
        dv: &mut [f64],
        terms: &mut [BarTerms],
    ) {
        for ((((bar, t), xk), vk), (fk, out)) in self
            .bars
            .iter()
            .zip(terms.iter_mut())
            .zip(x.chunks_exact(6))
            .zip(v.chunks_exact(6))
            .zip(f.chunks_exact(2).zip(dv.chunks_exact_mut(6)))
        {
            *t = BarTerms::of(&xk[..3], &xk[3..], &vk[..3], &vk[3..]);
            t.accel(bar, &fk[0], &fk[1], out);
        }
    }

    /// The Ω right-hand side −G a of the unconstrained accelerations `dv`.
    pub(crate) fn constraint_rhs(&self, dv: &[f64], out: &mut [f64]) {
        if let Some(rows) = &self.axis_rows {
            for (o, row) in out.iter_mut().zip(rows) {
                *o = row.neg_dot(dv);
            }
            return;
        }
        for (r, row) in out.iter_mut().zip(&self.linear_rows) {
            *r = -row
                .row
                .entries
                .iter()
                .flatten()
                .map(|e| e.grad.dot(&vec3(dv, e.node)))
                .sum::<f64>();
        }
    }

    /// Adds the constraint forces Gᵀ ω to `f`.
    pub(crate) fn add_constraint_forces(&self, omega: &[f64], f: &mut [Vector3<f64>]) {
        if let Some(axis) = &self.axis_entries {
            for &(r, node, d, s) in axis {
                f[node][d] += s * omega[r];
            }
            return;
        }
        for (w, row) in omega.iter().zip(&self.linear_rows) {
            for e in row.row.entries.iter().flatten() {
                f[e.node] += e.grad * *w;
            }
        }
    }

    /// Positions of the file nodes (representative copies, anchors) from a state.
    pub fn nodes_of(&self, y: &[f64]) -> Vec<Vector3<f64>> {
        self.node_map
            .iter()
            .map(|r| match *r {
                NodeRef::Free(i) => vec3(y, i),
                NodeRef::Anchor(p) => p,
            })
            .collect()
    }

    /// Velocities of the file nodes from a state.
    pub fn velocities_of(&self, y: &[f64]) -> Vec<Vector3<f64>> {
        let v = &y[3 * self.n1..];
        self.node_map
            .iter()
            .map(|r| match *r {
                NodeRef::Free(i) => vec3(v, i),
                NodeRef::Anchor(_) => Vector3::zeros(),
            })
            .collect()
    }

    /// Axial member forces (N, tension positive, bars then strings, then one per cluster) at
    /// (t, y): bars −λ_k l_k with λ from the closed form including Ω, strings γ‖s‖, clusters
    /// their tension t (module `cluster_forces`).
    pub fn member_forces(
        &self,
        t: f64,
        y: &[f64],
        ws: &mut Workspace,
    ) -> Result<Vec<f64>, CoreError> {
        let mut dy = vec![0.0; y.len()];
        self.rhs_with(t, y, &mut dy, ws, false)?;
        let n3 = 3 * self.n1;
        let (x, v) = y.split_at(n3);
        let mut out = Vec::with_capacity(self.bars.len() + self.strings.len());
        for (k, bar) in self.bars.iter().enumerate() {
            let b = vec3(x, 2 * k + 1) - vec3(x, 2 * k);
            let bd = vec3(v, 2 * k + 1) - vec3(v, 2 * k);
            let l2 = b.norm_squared();
            let fd = ws.f[2 * k + 1] - ws.f[2 * k];
            let lambda = -(bar.mass / 12.0) * bd.norm_squared() / l2 - 0.5 * b.dot(&fd) / l2;
            out.push(-lambda * l2.sqrt());
        }
        for (k, s) in self.strings.iter().enumerate() {
            let (xa, _) = self.end_state(s.ends[0], x, v);
            let (xb, _) = self.end_state(s.ends[1], x, v);
            out.push(ws.gamma[k] * (xb - xa).norm());
        }
        let rest = &ws.rest[self.strings.len()..];
        let clusters = self.clusters.iter().zip(rest);
        out.extend(clusters.map(|(c, &r)| c.tension_at_rest_length(x, v, r)));
        Ok(out)
    }

    /// Ground contact forces on the contact nodes at (t, y): `(file node, force)` pairs.
    pub fn contact_forces(
        &self,
        t: f64,
        y: &[f64],
        ws: &mut Workspace,
    ) -> Vec<(usize, Vector3<f64>)> {
        let n3 = 3 * self.n1;
        let (x, v) = y.split_at(n3);
        self.applied_forces(t, x, v, ws);
        self.contact
            .iter()
            .zip(&ws.contact_f)
            .map(|(&(i, _), f)| (i, *f))
            .collect()
    }
}

/// The clustered strings of `structure` (module `cluster_forces`): each node a bar's
/// representative class-1 node or a fixed point (a free node on no bar is refused, naming
/// it); a cluster with pulley friction or without a stiffness is refused, naming it; a
/// missing rest length is its length in the structure.
fn clusters_of(structure: &Structure, node_map: &[NodeRef]) -> Result<Vec<ClusterData>, CoreError> {
    let fixed = structure.fixed_dofs();
    let mut out = Vec::with_capacity(structure.clusters().len());
    for (k, c) in structure.clusters().iter().enumerate() {
        let invalid = |reason: &str| -> CoreError {
            ModelError::InvalidCluster {
                cluster: k,
                reason: reason.to_string(),
            }
            .into()
        };
        if !c.is_frictionless() {
            return Err(invalid("pulley friction (the capstan law) is modelled by the elastic dynamics, not the rigid-bar one: run the scene with `[simulation] bars = \"elastic\"` (or give the cluster no `friction`)"));
        }
        let stiffness = c.stiffness.ok_or_else(|| {
            invalid("the dynamics needs its stiffness (N/m, of the whole cluster)")
        })?;
        let mut ends = Vec::with_capacity(c.nodes.len());
        for &i in &c.nodes {
            ends.push(match node_map[i] {
                NodeRef::Free(r) => ClusterEnd::Free(r),
                NodeRef::Anchor(p) if fixed[i] == [true; 3] => ClusterEnd::Fixed(p),
                NodeRef::Anchor(_) => {
                    return Err(DynamicsError::FreeNodeWithoutBar { node: i }.into())
                }
            });
        }
        out.push(ClusterData {
            ends,
            stiffness,
            rest_length: c.rest_length.unwrap_or_else(|| c.length(structure.nodes())),
            damping: c.damping,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::structure::Bar;

    #[test]
    fn the_copies_of_a_many_bar_joint_are_tied_in_a_chain() {
        // a hub (node 0) with five spokes: 3·4 coincidence rows, each copy of the hub in at
        // most two of them per axis (a chain: a banded block of Ω), not the representative in
        // all four (a star: a dense one)
        let tips = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.2],
            [0.0, -1.0, 0.0],
        ];
        let mut b = Structure::builder()
            .nodes([[0.0, 0.0, 0.0]])
            .nodes(tips)
            .nodes([[0.3, 0.3, 1.0]]);
        for k in 1..=5 {
            b = b.bar(Bar::new(0, k).mass(1.0));
        }
        let model = Model::new(&b.build().unwrap(), None).unwrap();
        assert_eq!(model.linear_rows.len(), 12);
        let hub_copies: Vec<usize> = (0..5).map(|k| 2 * k).collect();
        for &c in &hub_copies {
            let rows = model
                .linear_rows
                .iter()
                .filter(|r| r.row.entries.iter().flatten().any(|e| e.node == c))
                .count();
            assert!(rows <= 6, "copy {c} is in {rows} rows");
        }
        // and the chain still makes every copy coincide: the rows' graph is connected
        let mut reached = vec![hub_copies[0]];
        while let Some(next) = model.linear_rows.iter().find_map(|r| {
            let nodes: Vec<usize> = r.row.entries.iter().flatten().map(|e| e.node).collect();
            match nodes[..] {
                [a, b] if reached.contains(&a) && !reached.contains(&b) => Some(b),
                [a, b] if reached.contains(&b) && !reached.contains(&a) => Some(a),
                _ => None,
            }
        }) {
            reached.push(next);
        }
        reached.sort_unstable();
        assert_eq!(reached, hub_copies);
    }
}
