//! Inverse form-finding (issue 47, item 2): the force densities whose form best meets a
//! weighted sum of goals, by a bound-constrained quasi-Newton method ([`lbfgsb`]) on the
//! exact gradient ([`crate::sensitivity`], one adjoint solve per evaluation; the equations in
//! the `objective` module).
//!
//! A problem ([`DesignSpec`]) names the force densities that vary ([`ParameterSpec`]: every
//! member's, a group's shared one, listed members; bounds that keep each member's sign), the
//! terms of the objective ([`TermSpec`]: an error over goals, as jax-fdm's losses: squared,
//! mean squared, root mean squared, absolute, prediction) and the goals ([`GoalSpec`]: node
//! positions or the topology's own shape, single coordinates, distances to planes and lines,
//! member lengths, forces, directions and force densities (an L2 regulariser), reactions,
//! their magnitudes and limits, the load path, smoothness). [`design`] starts from the topology's force
//! densities (the form of the force density method with held nodes: free-standing forms,
//! self-weight and clusters are refused by name, as by the derivatives) and returns the
//! designed topology (every member's force density set; the form found from it is the
//! optimum's) with the optimisation history.
//!
//! A single node held by four strings to anchors, aimed at a point it can reach: the designed
//! form reaches it.
//!
//! ```
//! use formfind::design::{design, DesignSpec, GoalSpec, TermSpec};
//! use formfind::{FixedNode, Member, NodeLoad, Topology};
//! let anchors = [[0.0, 0.0, 1.0], [3.0, 0.5, 0.0], [1.0, 2.5, 0.5], [-0.5, 1.0, 2.0]];
//! let t = Topology {
//!     n_nodes: 5,
//!     strings: (0..4).map(|k| Member::new(k, 4).force_density(1.0)).collect(),
//!     fixed: (0..4).map(|k| FixedNode { node: k, position: anchors[k] }).collect(),
//!     loads: vec![NodeLoad { node: 4, force: [0.0, 0.0, -2.0] }],
//!     ..Topology::default()
//! };
//! let goal = GoalSpec::Position { nodes: Some(vec![4]), target: Some([1.0, 1.0, 0.5]), targets: None, weight: 1.0 };
//! let spec = DesignSpec {
//!     terms: vec![TermSpec { goals: vec![goal], ..TermSpec::default() }],
//!     ..DesignSpec::default()
//! };
//! let d = design(&t, &spec).unwrap();
//! assert!(d.converged && d.objective < 1e-9, "{} {:?}", d.objective, d.stop);
//! let x = d.nodes[4];
//! assert!((x[0] - 1.0).abs() < 1e-4 && (x[2] - 0.5).abs() < 1e-4, "{x:?}");
//! ```

pub mod lbfgsb;
pub mod levenberg_marquardt;
mod objective;
mod spec;

pub use spec::{
    DesignSpec, ErrorKind, GoalSpec, OptimizerMethod, OptimizerSpec, ParameterSpec, Selection,
    TermSpec,
};

use crate::error::{FormFindError, Result};
use crate::topology::Topology;
use nalgebra::Vector3;
use objective::{Goal, Problem, Term, Variable};
use serde::Serialize;
use tensegrity_derive::Columns;

/// The smallest magnitude a varied force density may take (N/m): a string's q ≥ this, a
/// bar's q ≤ −this (at zero the member is slack and the form may not exist).
pub const SIGN_FLOOR: f64 = 1e-6;

/// A design variable of the result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignVariable {
    /// The members whose force density it sets (bars then strings).
    pub members: Vec<usize>,
    /// Its value at the start (N/m).
    pub start: f64,
    /// Its designed value (N/m).
    pub value: f64,
    /// Lower bound (N/m; −∞ is none, written as `null` in JSON).
    pub lower: f64,
    /// Upper bound (N/m).
    pub upper: f64,
    /// df/dv at the designed value.
    pub gradient: f64,
}

/// One row of the optimisation history.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignIterate {
    /// The iteration (0: the start).
    pub iteration: usize,
    /// The objective.
    pub objective: f64,
    /// Each term's value, in the order of the terms.
    pub terms: Vec<f64>,
    /// The projected gradient's largest component.
    pub projected_gradient: f64,
    /// The largest change of a variable in this iteration (N/m).
    pub step: f64,
    /// Objective evaluations (each one form and one adjoint solve) so far.
    pub evaluations: usize,
}

/// The result of [`design`].
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct Designed {
    /// The terms' names, in order.
    pub term_names: Vec<String>,
    /// The objective at the start.
    pub initial_objective: f64,
    /// The objective at the designed force densities.
    pub objective: f64,
    /// Each term's value there.
    pub terms: Vec<f64>,
    /// Whether the optimiser converged (the gradient or the objective rule).
    pub converged: bool,
    /// Whether the designed point is stationary by the gradient rule: its projected
    /// gradient within `gtol`. The objective rule (`stop = "objective"`) converges without
    /// it, on an objective that stalled, which on an ill-conditioned problem can lie well
    /// above the optimum (jax-fdm's cable net under L-BFGS-B: 13 % above); the engine's
    /// report then carries an `optimizer_stalled` warning. Levenberg–Marquardt's objective
    /// rule takes a nearly undamped Gauss–Newton step, near a minimum of its sum of squares
    /// (the same net within 2·10⁻⁶ of the optimum, not stationary by gtol = 10⁻⁸): no warning.
    pub stationary: bool,
    /// The projected gradient at the designed point, ‖x − P(x − ∇f)‖∞ (P the projection on
    /// the bounds).
    pub projected_gradient: f64,
    /// Why it stopped: `gradient`, `objective`, `iterations`, `evaluations`, `line_search`
    /// (for `levenberg_marquardt`: no damped step decreased the objective).
    pub stop: &'static str,
    /// The optimiser: `lbfgsb` or `levenberg_marquardt` ([`OptimizerMethod`]).
    pub method: &'static str,
    /// Iterations.
    pub iterations: usize,
    /// Objective evaluations (L-BFGS-B: one form and one adjoint solve each;
    /// Levenberg–Marquardt: one form each, and one adjoint solve per residual for each
    /// Jacobian).
    pub evaluations: usize,
    /// The variables.
    pub variables: Vec<DesignVariable>,
    /// Every member's designed force density (N/m, bars then strings).
    pub force_density: Vec<f64>,
    /// The designed form's nodes (m).
    pub nodes: Vec<[f64; 3]>,
    /// Its member lengths (m).
    pub length: Vec<f64>,
    /// Its member forces q L (N).
    pub force: Vec<f64>,
    /// The reactions at the held nodes, in the topology's `fixed` order (N).
    pub reactions: Vec<[f64; 3]>,
    /// The history, the start first.
    pub history: Vec<DesignIterate>,
    /// The members (bars then strings, as given) whose sign-free force density changed sign:
    /// the designed topology lists them as the other kind (a bar with q > 0 as a string).
    pub changed_kind: Vec<usize>,
    /// The topology with every member's designed force density (its groups' force densities
    /// removed; the found nodes as its `nodes`): the form-finding of it is the designed form.
    #[serde(skip)]
    pub topology: Topology,
}

/// Solves the design problem `spec` on `topology` (module docs). A problem that names a
/// member, node, group or held node the topology lacks, a target count that does not match,
/// bounds that exclude the member's sign or each other, or no goal, is refused naming the
/// item (`design.terms[1].goals[0].members`); the form's own refusals are the derivatives'.
pub fn design(topology: &Topology, spec: &DesignSpec) -> Result<Designed> {
    topology.validate()?;
    let problem = compile(topology, spec)?;
    let settings = spec.optimizer.settings();
    let lower: Vec<f64> = problem.variables.iter().map(|v| v.lower).collect();
    let upper: Vec<f64> = problem.variables.iter().map(|v| v.upper).collect();
    let start: Vec<f64> = problem.variables.iter().map(|v| v.start).collect();
    let mut term_rows: Vec<Vec<f64>> = Vec::new();
    let failed = vec![f64::NAN; problem.terms.len()];
    let minimum = match spec.optimizer.method {
        OptimizerMethod::Lbfgsb => lbfgsb::minimize(
            |v, g| match problem.evaluate(v) {
                Ok(e) => {
                    g.copy_from_slice(&e.gradient);
                    term_rows.push(e.terms);
                    Ok(e.objective)
                }
                Err(e) => {
                    term_rows.push(failed.clone());
                    Err(e)
                }
            },
            &start,
            &lower,
            &upper,
            &settings,
        )?,
        OptimizerMethod::LevenbergMarquardt => {
            if let Err(i) = problem.least_squares() {
                return refused(
                    format!("design.terms[{i}].error"),
                    format!(
                        "levenberg_marquardt minimises a sum of squares: every term's error must be squared or mean_squared, not {}",
                        problem.terms[i].error.name()
                    ),
                );
            }
            levenberg_marquardt::minimize(
                |v, jacobian| match problem.residuals(v, jacobian) {
                    Ok(r) => {
                        term_rows.push(r.terms);
                        Ok((r.values, r.jacobian))
                    }
                    Err(e) => {
                        term_rows.push(failed.clone());
                        Err(e)
                    }
                },
                &start,
                &lower,
                &upper,
                &settings,
            )?
        }
    };
    let at = problem.evaluate(&minimum.x)?;
    let projected_gradient =
        lbfgsb::projected_gradient_norm(&minimum.x, &at.gradient, &lower, &upper);
    let q = problem.force_densities(&minimum.x);
    let history = minimum
        .history
        .iter()
        .map(|it| DesignIterate {
            iteration: it.iteration,
            objective: it.objective,
            terms: term_rows[it.evaluation - 1].clone(),
            projected_gradient: it.projected_gradient,
            step: it.step,
            evaluations: it.evaluations,
        })
        .collect();
    let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
    let nodes: Vec<[f64; 3]> = at.form.nodes().iter().map(arr).collect();
    let mut designed = topology.clone();
    for g in designed.groups.values_mut() {
        g.force_density = None;
    }
    // every member its designed q; one whose sign-free q changed sign is the other kind
    let mut members: Vec<(bool, crate::topology::Member)> = topology
        .members()
        .enumerate()
        .map(|(k, m)| {
            let mut m = m.clone();
            m.force_density = Some(q[k]);
            (q[k] < 0.0 || (q[k] == 0.0 && topology.is_bar(k)), m)
        })
        .collect();
    let changed_kind: Vec<usize> = (0..q.len())
        .filter(|&k| members[k].0 != topology.is_bar(k))
        .collect();
    designed.bars = members
        .iter()
        .filter(|(bar, _)| *bar)
        .map(|(_, m)| m.clone())
        .collect();
    designed.strings = members
        .drain(..)
        .filter(|(bar, _)| !bar)
        .map(|(_, m)| m)
        .collect();
    designed.nodes = Some(nodes.clone());
    Ok(Designed {
        changed_kind,
        term_names: problem.terms.iter().map(|t| t.name.clone()).collect(),
        initial_objective: minimum.history[0].objective,
        objective: at.objective,
        terms: at.terms,
        converged: minimum.stop.converged(),
        stationary: projected_gradient <= settings.gtol,
        projected_gradient,
        stop: minimum.stop.name(),
        method: spec.optimizer.method.name(),
        iterations: minimum.iterations,
        evaluations: minimum.evaluations,
        variables: problem
            .variables
            .iter()
            .zip(&minimum.x)
            .zip(&at.gradient)
            .map(|((var, &value), &gradient)| DesignVariable {
                members: var.members.clone(),
                start: var.start,
                value,
                lower: var.lower,
                upper: var.upper,
                gradient,
            })
            .collect(),
        force_density: q,
        nodes,
        length: at.form.lengths(),
        force: at.form.forces(),
        reactions: at.form.reactions().iter().map(arr).collect(),
        history,
        topology: designed,
    })
}

/// A design problem compiled against its topology: the objective and its exact gradient at
/// any values of the variables, for an optimiser of the caller's (scipy's, through Python) or
/// a check by finite differences.
///
/// ```
/// use formfind::design::{DesignProblem, DesignSpec, GoalSpec, TermSpec};
/// let grid = formfind::builtin("grid:2").unwrap();
/// let goal = GoalSpec::LoadPath { members: None, target: None, weight: 1.0 };
/// let spec = DesignSpec {
///     terms: vec![TermSpec { goals: vec![goal], ..TermSpec::default() }],
///     ..DesignSpec::default()
/// };
/// let p = DesignProblem::new(&grid, &spec).unwrap();
/// let (f, g) = p.objective(&p.start()).unwrap();
/// assert!(f > 0.0 && g.len() == p.start().len());
/// ```
pub struct DesignProblem(Problem);

impl DesignProblem {
    /// Compiles `spec` on `topology` (refusals as [`design`]'s).
    pub fn new(topology: &Topology, spec: &DesignSpec) -> Result<Self> {
        topology.validate()?;
        Ok(Self(compile(topology, spec)?))
    }

    /// The variables' start values (N/m).
    pub fn start(&self) -> Vec<f64> {
        self.0.variables.iter().map(|v| v.start).collect()
    }

    /// The variables' lower bounds (N/m, −∞ for none).
    pub fn lower(&self) -> Vec<f64> {
        self.0.variables.iter().map(|v| v.lower).collect()
    }

    /// The variables' upper bounds (N/m, ∞ for none).
    pub fn upper(&self) -> Vec<f64> {
        self.0.variables.iter().map(|v| v.upper).collect()
    }

    /// The members each variable sets.
    pub fn members(&self) -> Vec<Vec<usize>> {
        self.0.variables.iter().map(|v| v.members.clone()).collect()
    }

    /// The objective and its gradient with respect to the variables at `v` (one form and one
    /// adjoint solve); a wrong count of values is the error.
    pub fn objective(&self, v: &[f64]) -> Result<(f64, Vec<f64>)> {
        let e = self.evaluate(v)?;
        Ok((e.objective, e.gradient))
    }

    /// The objective, its gradient and each term's value at `v` (one evaluation).
    pub fn objective_with_terms(&self, v: &[f64]) -> Result<(f64, Vec<f64>, Vec<f64>)> {
        let e = self.evaluate(v)?;
        Ok((e.objective, e.gradient, e.terms))
    }

    /// The residuals r (f = ‖r‖², one per component of each goal: √(α w / n) (p − t), n the
    /// term's goal count for a mean-squared error, else 1) and their exact Jacobian dr/dv
    /// (residuals × variables; one adjoint solve per residual) at `v`: the model of the
    /// `levenberg_marquardt` optimiser, for scipy's `least_squares` or a check. A problem
    /// with a term whose error is not `squared` or `mean_squared` is refused naming it.
    ///
    /// ```
    /// use formfind::design::{DesignProblem, DesignSpec, ErrorKind, GoalSpec, TermSpec};
    /// let grid = formfind::builtin("grid:2").unwrap();
    /// let goal = GoalSpec::LoadPath { members: None, target: None, weight: 1.0 };
    /// let term = TermSpec { goals: vec![goal], ..TermSpec::default() }; // squared
    /// let spec = DesignSpec { terms: vec![term], ..DesignSpec::default() };
    /// let p = DesignProblem::new(&grid, &spec).unwrap();
    /// let v = p.start();
    /// let (r, j) = p.residuals(&v).unwrap();
    /// let (f, g) = p.objective(&v).unwrap();
    /// // f = ‖r‖² and ∇f = 2 Jᵀ r: two routes to the same numbers
    /// assert!((r.iter().map(|x| x * x).sum::<f64>() - f).abs() < 1e-12 * f);
    /// for (c, gc) in g.iter().enumerate() {
    ///     let jtr: f64 = (0..r.len()).map(|i| j[(i, c)] * r[i]).sum();
    ///     assert!((2.0 * jtr - gc).abs() < 1e-10 * f.max(1.0));
    /// }
    /// ```
    pub fn residuals(&self, v: &[f64]) -> Result<(Vec<f64>, nalgebra::DMatrix<f64>)> {
        self.check_length(v)?;
        if let Err(i) = self.0.least_squares() {
            return refused(
                format!("design.terms[{i}].error"),
                format!(
                    "residuals need a sum of squares: the error is {}, not squared or mean_squared",
                    self.0.terms[i].error.name()
                ),
            );
        }
        let r = self.0.residuals(v, true)?;
        let j = r.jacobian.expect("asked for");
        Ok((r.values, j))
    }

    fn check_length(&self, v: &[f64]) -> Result<()> {
        if v.len() != self.0.variables.len() {
            return refused(
                "design.parameters".into(),
                format!(
                    "{} values for {} variables",
                    v.len(),
                    self.0.variables.len()
                ),
            );
        }
        Ok(())
    }

    fn evaluate(&self, v: &[f64]) -> Result<objective::Evaluation> {
        self.check_length(v)?;
        self.0.evaluate(v)
    }
}

fn refused<T>(item: String, reason: impl Into<String>) -> Result<T> {
    Err(FormFindError::InvalidTopology {
        item,
        reason: reason.into(),
    })
}

/// Members that share one variable, its bounds as given, the item that asked for it and
/// whether its sign is free.
type MemberSet = (Vec<usize>, Option<f64>, Option<f64>, String, bool);

/// The problem of `spec` on `topology`, its indices checked (the items named as in the file).
fn compile(topology: &Topology, spec: &DesignSpec) -> Result<Problem> {
    let m = topology.n_members();
    let n = topology.n_nodes;
    let given = topology.given_force_densities();
    if let Some(k) = given.iter().position(Option::is_none) {
        return refused(
            format!("{}.force_density", topology.member_name(k)),
            "a design starts from the given force densities: give every member one (or its group)",
        );
    }
    let base: Vec<f64> = given.into_iter().flatten().collect();
    let group_members = |name: &str, item: &str| -> Result<Vec<usize>> {
        if !topology.groups.contains_key(name) {
            return refused(item.into(), format!("no group `{name}` in the topology"));
        }
        Ok((0..m)
            .filter(|&k| topology.members().nth(k).and_then(|x| x.group.as_deref()) == Some(name))
            .collect())
    };
    let check_members = |members: &[usize], item: &str| -> Result<()> {
        match members.iter().find(|&&k| k >= m) {
            Some(k) => refused(
                item.into(),
                format!("member {k} is past the last ({m} members)"),
            ),
            None if members.is_empty() => refused(item.into(), "no members"),
            None => Ok(()),
        }
    };
    // the variables, each member in at most one
    let mut sets: Vec<MemberSet> = Vec::new();
    if spec.parameters.is_empty() {
        let mut seen_groups = Vec::new();
        for (k, member) in topology.members().enumerate() {
            match (&member.force_density, &member.group) {
                (None, Some(g)) => {
                    if !seen_groups.contains(g) {
                        seen_groups.push(g.clone());
                        let members = group_members(g, "design.parameters")?;
                        sets.push((members, None, None, format!("groups.{g}"), false));
                    }
                }
                _ => sets.push((vec![k], None, None, topology.member_name(k), false)),
            }
        }
    }
    for (i, p) in spec.parameters.iter().enumerate() {
        let item = format!("design.parameters[{i}]");
        let free = match p.sign.as_deref() {
            None | Some("member") => false,
            Some("free") => true,
            Some(other) => {
                return refused(
                    format!("{item}.sign"),
                    format!("{other:?}: \"member\" (the default: a bar's q < 0, a string's > 0) or \"free\""),
                )
            }
        };
        let chosen = [!p.members.is_empty(), p.group.is_some(), p.select.is_some()];
        if chosen.iter().filter(|&&c| c).count() != 1 {
            return refused(item, "give exactly one of `members`, `group` and `select`");
        }
        for (name, b) in [("lower", p.lower), ("upper", p.upper)] {
            if b.is_some_and(|b| b.is_nan()) {
                return refused(format!("{item}.{name}"), "not a number");
            }
        }
        if let Some(g) = &p.group {
            let members = group_members(g, &format!("{item}.group"))?;
            sets.push((members, p.lower, p.upper, item, free));
        } else if let Some(sel) = p.select {
            for k in (0..m).filter(|&k| match sel {
                Selection::All => true,
                Selection::Bars => topology.is_bar(k),
                Selection::Strings => !topology.is_bar(k),
            }) {
                sets.push((vec![k], p.lower, p.upper, item.clone(), free));
            }
        } else {
            check_members(&p.members, &format!("{item}.members"))?;
            if p.shared {
                sets.push((p.members.clone(), p.lower, p.upper, item, free));
            } else {
                for &k in &p.members {
                    sets.push((vec![k], p.lower, p.upper, item.clone(), free));
                }
            }
        }
    }
    let mut owner = vec![None; m];
    let mut variables = Vec::with_capacity(sets.len());
    for (members, lower, upper, item, free) in sets {
        let bars = members.iter().filter(|&&k| topology.is_bar(k)).count();
        if !free && bars != 0 && bars != members.len() {
            return refused(
                item,
                "one force density for bars and strings: their signs differ",
            );
        }
        for &k in &members {
            if let Some(other) = owner[k].replace(item.clone()) {
                return refused(
                    item,
                    format!("{} is varied by {other} already", topology.member_name(k)),
                );
            }
        }
        let (sign_lower, sign_upper) = if free {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else if bars > 0 {
            (f64::NEG_INFINITY, -SIGN_FLOOR)
        } else {
            (SIGN_FLOOR, f64::INFINITY)
        };
        let lo = lower.map_or(sign_lower, |l| l.max(sign_lower));
        let up = upper.map_or(sign_upper, |u| u.min(sign_upper));
        if lo > up {
            return refused(
                item,
                format!(
                    "the bounds [{lo}, {up}] are empty (a {}'s force density is {})",
                    if bars > 0 { "bar" } else { "string" },
                    if bars > 0 { "negative" } else { "positive" }
                ),
            );
        }
        let start = base[members[0]];
        variables.push(Variable {
            members,
            lower: lo,
            upper: up,
            start,
        });
    }
    if variables.is_empty() {
        return refused("design.parameters".into(), "no force density varies");
    }
    // the terms
    if spec.terms.is_empty() {
        return refused(
            "design.terms".into(),
            "no terms: give at least one [[design.terms]] with goals",
        );
    }
    let held: Vec<usize> = topology.fixed.iter().map(|f| f.node).collect();
    let is_held = |i: usize| held.contains(&i);
    let free: Vec<usize> = (0..n).filter(|&i| !is_held(i)).collect();
    let pairs = topology.member_nodes();
    let mut neighbours = vec![Vec::new(); n];
    for &[a, b] in &pairs {
        neighbours[a].push(b);
        neighbours[b].push(a);
    }
    let mut terms = Vec::with_capacity(spec.terms.len());
    for (t, term) in spec.terms.iter().enumerate() {
        let titem = format!("design.terms[{t}]");
        if !term.weight.is_finite() || term.weight < 0.0 {
            return refused(format!("{titem}.weight"), "must be finite and not negative");
        }
        if term.goals.is_empty() {
            return refused(format!("{titem}.goals"), "no goals");
        }
        let mut goals = Vec::new();
        for (j, goal) in term.goals.iter().enumerate() {
            let item = format!("{titem}.goals[{j}]");
            compile_goal(
                goal,
                &item,
                topology,
                &free,
                &held,
                &neighbours,
                &group_members,
                &check_members,
                &mut goals,
            )?;
        }
        terms.push(Term {
            name: term.name.clone().unwrap_or_else(|| format!("term {t}")),
            error: term.error,
            weight: term.weight,
            goals,
        });
    }
    Ok(Problem {
        topology: topology.clone(),
        base,
        variables,
        terms,
    })
}

/// One goal's elements appended to `goals` (a goal per node or member).
#[allow(clippy::too_many_arguments)]
fn compile_goal(
    goal: &GoalSpec,
    item: &str,
    topology: &Topology,
    free: &[usize],
    held: &[usize],
    neighbours: &[Vec<usize>],
    group_members: &dyn Fn(&str, &str) -> Result<Vec<usize>>,
    check_members: &dyn Fn(&[usize], &str) -> Result<()>,
    goals: &mut Vec<(Goal, f64)>,
) -> Result<()> {
    let n = topology.n_nodes;
    let m = topology.n_members();
    let weight_ok = |w: f64| -> Result<f64> {
        if w.is_finite() && w >= 0.0 {
            Ok(w)
        } else {
            refused(format!("{item}.weight"), "must be finite and not negative")
        }
    };
    let members_of = |members: &Option<Vec<usize>>, group: &Option<String>| -> Result<Vec<usize>> {
        match (members, group) {
            (Some(_), Some(_)) => refused(item.into(), "give `members` or `group`, not both"),
            (Some(ms), None) => {
                check_members(ms, &format!("{item}.members"))?;
                Ok(ms.clone())
            }
            (None, Some(g)) => group_members(g, &format!("{item}.group")),
            (None, None) => Ok((0..m).collect()),
        }
    };
    let nodes_of = |nodes: &Option<Vec<usize>>, default: &[usize]| -> Result<Vec<usize>> {
        let ns = nodes.clone().unwrap_or_else(|| default.to_vec());
        if let Some(i) = ns.iter().find(|&&i| i >= n) {
            return refused(
                format!("{item}.nodes"),
                format!("node {i} is past the last ({n} nodes)"),
            );
        }
        if ns.is_empty() {
            return refused(format!("{item}.nodes"), "no nodes");
        }
        Ok(ns)
    };
    let held_of = |nodes: &Option<Vec<usize>>| -> Result<Vec<usize>> {
        let ns = nodes_of(nodes, held)?;
        ns.iter()
            .map(|i| match held.iter().position(|h| h == i) {
                Some(index) => Ok(index),
                None => refused(
                    format!("{item}.nodes"),
                    format!("node {i} is not held: it has no reaction"),
                ),
            })
            .collect()
    };
    fn targets<T: Copy>(
        item: &str,
        one: Option<T>,
        many: &Option<Vec<T>>,
        count: usize,
    ) -> Result<Option<Vec<T>>> {
        match (one, many) {
            (Some(_), Some(_)) => refused(item.into(), "give `target` or `targets`, not both"),
            (Some(t), None) => Ok(Some(vec![t; count])),
            (None, Some(ts)) if ts.len() != count => refused(
                format!("{item}.targets"),
                format!("{} targets for {count} goals", ts.len()),
            ),
            (None, Some(ts)) => Ok(Some(ts.clone())),
            (None, None) => Ok(None),
        }
    }
    let finite3 = |v: &[f64; 3], what: &str| -> Result<Vector3<f64>> {
        if v.iter().all(|x| x.is_finite()) {
            Ok(Vector3::from(*v))
        } else {
            refused(format!("{item}.{what}"), "not finite")
        }
    };
    // a plane's normal or a line's direction: finite, nonzero, made unit
    let unit = |v: &[f64; 3], what: &str| -> Result<Vector3<f64>> {
        let u = finite3(v, what)?;
        if u.norm() == 0.0 {
            return refused(format!("{item}.{what}"), format!("a {what} of zero length"));
        }
        Ok(u.normalize())
    };
    let finite = |v: f64, what: &str| -> Result<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            refused(format!("{item}.{what}"), "not finite")
        }
    };
    let need = |item_key: &str| -> FormFindError {
        FormFindError::InvalidTopology {
            item: format!("{item}.{item_key}"),
            reason: "this goal needs a target".into(),
        }
    };
    match goal {
        GoalSpec::Position {
            nodes,
            target,
            targets: ts,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let ns = nodes_of(nodes, free)?;
            let t = match targets(item, *target, ts, ns.len())? {
                Some(t) => t,
                None => {
                    let Some(reference) = &topology.nodes else {
                        return refused(
                            format!("{item}.target"),
                            "no target, and the topology gives no `nodes` to match",
                        );
                    };
                    ns.iter().map(|&i| reference[i]).collect()
                }
            };
            for (node, t) in ns.into_iter().zip(t) {
                goals.push((
                    Goal::Position {
                        node,
                        target: finite3(&t, "target")?,
                    },
                    w,
                ));
            }
        }
        GoalSpec::Coordinate {
            nodes,
            axis,
            target,
            targets: ts,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            if *axis > 2 {
                return refused(
                    format!("{item}.axis"),
                    format!("{axis}: 0, 1 or 2 for x, y, z"),
                );
            }
            let ns = nodes_of(nodes, free)?;
            let t = targets(item, *target, ts, ns.len())?.ok_or_else(|| need("target"))?;
            for (node, t) in ns.into_iter().zip(t) {
                let target = finite(t, "target")?;
                goals.push((
                    Goal::Coordinate {
                        node,
                        axis: *axis,
                        target,
                    },
                    w,
                ));
            }
        }
        GoalSpec::Plane {
            nodes,
            point,
            normal,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let (point, normal) = (finite3(point, "point")?, unit(normal, "normal")?);
            for node in nodes_of(nodes, free)? {
                goals.push((
                    Goal::Plane {
                        node,
                        point,
                        normal,
                    },
                    w,
                ));
            }
        }
        GoalSpec::Line {
            nodes,
            point,
            direction,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let (point, direction) = (finite3(point, "point")?, unit(direction, "direction")?);
            for node in nodes_of(nodes, free)? {
                goals.push((
                    Goal::Line {
                        node,
                        point,
                        direction,
                    },
                    w,
                ));
            }
        }
        GoalSpec::ForceDensity {
            members,
            group,
            target,
            targets: ts,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let ks = members_of(members, group)?;
            let t = targets(item, target.or(ts.is_none().then_some(0.0)), ts, ks.len())?
                .ok_or_else(|| need("target"))?;
            for (member, t) in ks.into_iter().zip(t) {
                let target = finite(t, "target")?;
                goals.push((Goal::ForceDensity { member, target }, w));
            }
        }
        GoalSpec::ReactionForce {
            nodes,
            target,
            targets: ts,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let hs = held_of(nodes)?;
            let t = targets(item, *target, ts, hs.len())?.ok_or_else(|| need("target"))?;
            for (index, t) in hs.into_iter().zip(t) {
                let target = finite(t, "target")?;
                goals.push((
                    Goal::ReactionForce {
                        held: index,
                        target,
                    },
                    w,
                ));
            }
        }
        GoalSpec::Length {
            members,
            group,
            target,
            targets: ts,
            weight,
        }
        | GoalSpec::Force {
            members,
            group,
            target,
            targets: ts,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let ks = members_of(members, group)?;
            let t = targets(item, *target, ts, ks.len())?.ok_or_else(|| need("target"))?;
            let is_length = matches!(goal, GoalSpec::Length { .. });
            for (member, t) in ks.into_iter().zip(t) {
                let target = finite(t, "target")?;
                goals.push((
                    if is_length {
                        Goal::Length { member, target }
                    } else {
                        Goal::Force { member, target }
                    },
                    w,
                ));
            }
        }
        GoalSpec::Direction {
            members,
            group,
            target,
            targets: ts,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let ks = members_of(members, group)?;
            let t = targets(item, *target, ts, ks.len())?.ok_or_else(|| need("target"))?;
            for (member, t) in ks.into_iter().zip(t) {
                let v = finite3(&t, "target")?;
                if v.norm() == 0.0 {
                    return refused(format!("{item}.target"), "a direction of zero length");
                }
                goals.push((
                    Goal::Direction {
                        member,
                        target: v.normalize(),
                    },
                    w,
                ));
            }
        }
        GoalSpec::Reaction {
            nodes,
            target,
            targets: ts,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let hs = held_of(nodes)?;
            let t = targets(item, *target, ts, hs.len())?.ok_or_else(|| need("target"))?;
            for (index, t) in hs.into_iter().zip(t) {
                goals.push((
                    Goal::Reaction {
                        held: index,
                        target: finite3(&t, "target")?,
                    },
                    w,
                ));
            }
        }
        GoalSpec::ReactionLimit {
            nodes,
            limit,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let limit = finite(*limit, "limit")?;
            if limit < 0.0 {
                return refused(format!("{item}.limit"), "a reaction limit is not negative");
            }
            for index in held_of(nodes)? {
                goals.push((Goal::ReactionLimit { held: index, limit }, w));
            }
        }
        GoalSpec::LoadPath {
            members,
            target,
            weight,
        } => {
            let w = weight_ok(*weight)?;
            let ks = members_of(members, &None)?;
            let target = finite(target.unwrap_or(0.0), "target")?;
            goals.push((
                Goal::LoadPath {
                    members: ks,
                    target,
                },
                w,
            ));
        }
        GoalSpec::Smoothness { nodes, weight } => {
            let w = weight_ok(*weight)?;
            for node in nodes_of(nodes, free)? {
                let nb = neighbours[node].clone();
                if nb.is_empty() {
                    return refused(
                        format!("{item}.nodes"),
                        format!("node {node} has no neighbours"),
                    );
                }
                goals.push((
                    Goal::Smoothness {
                        node,
                        neighbours: nb,
                    },
                    w,
                ));
            }
        }
    }
    Ok(())
}
