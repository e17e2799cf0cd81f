//! Forward sensitivities of a trajectory (issue 47, item 4): the derivatives of the state
//! y(t) = (x, v) of the rigid-bar dynamics with respect to string rest lengths, stiffnesses
//! and dampings, bar masses and the initial state, integrated alongside the state.
//!
//! With ẏ = f(y; p) the model's right-hand side ([`Model::rhs`]: the class-1 bar dynamics,
//! the strings, gravity, loads, the constraint forces and, where the scene has one, the
//! penalty ground), the sensitivity S_j = ∂y/∂p_j of one parameter solves the variational
//! equation
//!
//! > Ṡ_j = (∂f/∂y) S_j + ∂f/∂p_j,   S_j(0) = ∂y₀/∂p_j,
//!
//! and the state and every S_j are advanced together by the classical Runge–Kutta method on
//! one fixed step (the augmented system (y, S_1 … S_k)). Runge–Kutta discretisation and
//! differentiation commute: S_j after each step is the derivative of the discrete RK4
//! trajectory itself, not of the exact flow, so it agrees with a central difference of two
//! whole runs (the check of `tests/sensitivity.rs`) to the precision of its ingredients, not
//! to the step's truncation error. The ingredients: (∂f/∂y) S_j by a central difference of
//! f along S_j, and ∂f/∂p_j by a central difference of f between two models built with p_j
//! moved (both with the step η = ε^{1/3} relative to the scale of y or p_j: an error of order
//! ε^{2/3} ≈ 4·10⁻¹¹ relative). The string force k (1 − s₀/‖s‖) + c sᵀṡ/‖s‖² is linear in k
//! and c, so their central differences are exact but for round-off. Cost per stage: one
//! evaluation of f, two per parameter for (∂f/∂y) S_j and two more per model parameter.
//!
//! Non-smooth events: a string going slack or taut and a node touching or leaving the penalty
//! ground put a kink in f (its derivative jumps, f stays continuous); the trajectory stays
//! differentiable in the parameters, and an RK4 step across one is differentiated as taken
//! (checked through a landing on the ground to 2·10⁻⁷). A force that itself jumps is another
//! matter: the penalty ground's normal damping c adds c times the impact speed the instant a
//! node touches, and the trajectory's derivative then jumps by a term (the saltation of the
//! event time) that the variational equation does not carry — give the ground no normal
//! damping where derivatives through a landing matter. The events met are reported
//! ([`TrajectorySensitivity::events`]: the step in which a string's strain or a contact node's
//! penetration changed sign), so that a caller can see which derivatives cross one.
//!
//! The steps are not projected on the bar lengths (a projection would need its own
//! derivative): each run reports its [`TrajectorySensitivity::bar_length_drift`], the largest
//! bar-length error relative to the shortest bar, and a [`Warning::Drift`] past the limit
//! `simulate` keeps (10⁻⁶), beside the numbers it concerns.
//!
//! Parameters: [`DynamicsParameter`]. The initial state moves a whole bar (both ends, its
//! length kept) in position or velocity; a bar sharing a node with another bar or a support
//! (a class-k joint) is refused by name, since moving it alone would break the joint.

use crate::forces::Ground;
use crate::model::Model;
use crate::system::vec3;
use nalgebra::Vector3;
use tensegrity_core::error::DynamicsError;
use tensegrity_core::warning::{DriftInvariant, Warning};
use tensegrity_core::{CoreError, Structure};

/// A parameter of the dynamics (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DynamicsParameter {
    /// The rest length s₀ of string j (m).
    RestLength(usize),
    /// The stiffness k of string j (N/m).
    Stiffness(usize),
    /// The damping c of string j (N s/m).
    Damping(usize),
    /// The mass of bar k (kg).
    BarMass(usize),
    /// The initial position of bar k along `axis` (both ends moved together; m).
    InitialPosition {
        /// The bar.
        bar: usize,
        /// 0, 1, 2 for x, y, z.
        axis: usize,
    },
    /// The initial velocity of bar k along `axis` (both ends; m/s).
    InitialVelocity {
        /// The bar.
        bar: usize,
        /// 0, 1, 2 for x, y, z.
        axis: usize,
    },
}

impl std::fmt::Display for DynamicsParameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::RestLength(j) => write!(f, "string {j} rest length"),
            Self::Stiffness(j) => write!(f, "string {j} stiffness"),
            Self::Damping(j) => write!(f, "string {j} damping"),
            Self::BarMass(k) => write!(f, "bar {k} mass"),
            Self::InitialPosition { bar, axis } => write!(
                f,
                "bar {bar} initial position {}",
                "xyz".as_bytes()[*axis.min(&2)] as char
            ),
            Self::InitialVelocity { bar, axis } => write!(
                f,
                "bar {bar} initial velocity {}",
                "xyz".as_bytes()[*axis.min(&2)] as char
            ),
        }
    }
}

/// A kink of the right-hand side met in a step: a string going slack or taut, a contact
/// node touching or leaving the ground.
#[derive(Debug, Clone, PartialEq)]
pub struct SensitivityEvent {
    /// The start of the step it was met in (s).
    pub time: f64,
    /// What changed (`string 3 slack`, `node 5 touches the ground`, …).
    pub what: String,
}

/// A trajectory and its sensitivities at the sample times.
#[derive(Debug, Clone, PartialEq)]
pub struct TrajectorySensitivity {
    /// The sample times (s), the start first.
    pub times: Vec<f64>,
    /// The file nodes' positions at each sample (m).
    pub nodes: Vec<Vec<Vector3<f64>>>,
    /// ∂x_i/∂p_j of every file node at each sample: `[sample][parameter][node]`.
    pub node_sensitivities: Vec<Vec<Vec<Vector3<f64>>>>,
    /// The model's whole state y at each sample (x then v of the class-1 node copies).
    pub states: Vec<Vec<f64>>,
    /// ∂y/∂p_j at each sample: `[sample][parameter]`.
    pub state_sensitivities: Vec<Vec<Vec<f64>>>,
    /// The kinks met (module docs).
    pub events: Vec<SensitivityEvent>,
    /// Right-hand side evaluations made.
    pub rhs_evaluations: usize,
    /// The largest bar-length error over the run, max_k |‖b_k‖ − l_k| relative to the
    /// shortest bar (module docs: the steps are not projected).
    pub bar_length_drift: f64,
    /// A [`Warning::Drift`] when `bar_length_drift` passed the limit `simulate` keeps
    /// ([`crate::drift::DriftLimits`]' `bar_length`, 10⁻⁶): the trajectory (and its
    /// derivatives) is then that of a model whose bars have stretched.
    pub warnings: Vec<Warning>,
}

/// The step η of a central difference, relative to `scale` (module docs).
fn eta(scale: f64) -> f64 {
    f64::EPSILON.cbrt() * scale.max(1.0)
}

fn refused(item: String, reason: impl Into<String>) -> CoreError {
    DynamicsError::Unsupported {
        item,
        reason: reason.into(),
    }
    .into()
}

/// The two models of a model parameter moved by ±h (the minus one by 0 near zero), their
/// workspaces and the half-distance h of the difference.
struct MovedModels {
    plus: Model,
    minus: Model,
    ws: (crate::model::Workspace, crate::model::Workspace),
    h: f64,
}

/// One parameter of a run: a pair of moved models (a model parameter) or an initial state
/// direction.
enum Prepared {
    Model(Box<MovedModels>),
    Initial,
}

/// `structure` with the model parameter `p` set to `value` (an initial-state parameter
/// leaves it as it is), validated again.
pub fn with_parameter(
    structure: &Structure,
    p: DynamicsParameter,
    value: f64,
) -> Result<Structure, CoreError> {
    let mut strings = structure.strings().to_vec();
    let mut bars = structure.bars().to_vec();
    let out_of_range = || refused(p.to_string(), "past the last member");
    match p {
        DynamicsParameter::RestLength(j) => {
            strings.get_mut(j).ok_or_else(out_of_range)?.rest_length = Some(value)
        }
        DynamicsParameter::Stiffness(j) => {
            strings.get_mut(j).ok_or_else(out_of_range)?.stiffness = Some(value)
        }
        DynamicsParameter::Damping(j) => {
            strings.get_mut(j).ok_or_else(out_of_range)?.damping = value
        }
        DynamicsParameter::BarMass(k) => {
            bars.get_mut(k).ok_or_else(out_of_range)?.mass = Some(value)
        }
        _ => return Ok(structure.clone()),
    }
    structure.with_members(bars, strings)
}

/// `structure` with the model parameter `p` moved by `h` from its value `value`.
fn moved(
    structure: &Structure,
    p: DynamicsParameter,
    value: f64,
    h: f64,
) -> Result<Structure, CoreError> {
    with_parameter(structure, p, value + h)
}

/// The trajectory of `structure` (on `ground`, if any) from its initial state to `t_end` by
/// fixed RK4 steps of `dt`, sampled every `every` steps (and at the end), with the
/// sensitivities of every sample to each of `parameters` (module docs). A parameter naming a
/// string or bar past the last, a string without a stiffness, a bar without a mass, an axis
/// past z or an initial-state move of a jointed or supported bar is refused by name.
pub fn forward_sensitivities(
    structure: &Structure,
    ground: Option<Ground>,
    parameters: &[DynamicsParameter],
    dt: f64,
    t_end: f64,
    every: usize,
) -> Result<TrajectorySensitivity, CoreError> {
    if !(dt > 0.0 && dt.is_finite() && t_end > 0.0 && t_end.is_finite()) {
        return Err(refused(
            "dt, t_end".into(),
            format!("a step {dt} and an end time {t_end} must be finite and positive"),
        ));
    }
    let model = Model::new(structure, ground.clone())?;
    let mut ws = model.workspace()?;
    let y0 = model.initial_state(structure)?;
    let n = y0.len();
    let (ns, nb) = (structure.n_strings(), structure.n_bars());
    // the copies of each node: a bar whose ends are shared (a joint) or supported is jointed
    let mut uses = vec![0usize; structure.n_nodes()];
    for b in structure.bars() {
        uses[b.nodes[0]] += 1;
        uses[b.nodes[1]] += 1;
    }
    let fixed = structure.fixed_dofs();
    let mut prepared = Vec::with_capacity(parameters.len());
    let mut s0: Vec<Vec<f64>> = Vec::with_capacity(parameters.len());
    for &p in parameters {
        let name = p.to_string();
        let check_string = |j: usize| -> Result<(), CoreError> {
            if j >= ns {
                return Err(refused(
                    name.clone(),
                    format!("string {j} is past the last ({ns} strings)"),
                ));
            }
            Ok(())
        };
        let check_bar = |k: usize| -> Result<(), CoreError> {
            if k >= nb {
                return Err(refused(
                    name.clone(),
                    format!("bar {k} is past the last ({nb} bars)"),
                ));
            }
            Ok(())
        };
        let mut start = vec![0.0; n];
        let scale = match p {
            DynamicsParameter::RestLength(j) => {
                check_string(j)?;
                let s = &structure.strings()[j];
                let [a, c] = s.nodes;
                Some(
                    s.rest_length
                        .unwrap_or((structure.nodes()[c] - structure.nodes()[a]).norm()),
                )
            }
            DynamicsParameter::Stiffness(j) => {
                check_string(j)?;
                match structure.strings()[j].stiffness {
                    Some(k) => Some(k),
                    None => return Err(refused(name, "the string has no stiffness to move")),
                }
            }
            DynamicsParameter::Damping(j) => {
                check_string(j)?;
                Some(structure.strings()[j].damping)
            }
            DynamicsParameter::BarMass(k) => {
                check_bar(k)?;
                match structure.bars()[k].mass {
                    Some(m) => Some(m),
                    None => return Err(refused(name, "the bar has no mass to move")),
                }
            }
            DynamicsParameter::InitialPosition { bar, axis }
            | DynamicsParameter::InitialVelocity { bar, axis } => {
                check_bar(bar)?;
                if axis > 2 {
                    return Err(refused(name, format!("axis {axis} is past z (0, 1, 2)")));
                }
                let ends = structure.bars()[bar].nodes;
                if ends
                    .iter()
                    .any(|&i| uses[i] > 1 || fixed[i].iter().any(|&f| f))
                {
                    return Err(refused(
                        name,
                        "the bar is joined to another or supported: moving it alone would break the joint",
                    ));
                }
                let half = if matches!(p, DynamicsParameter::InitialPosition { .. }) {
                    0
                } else {
                    3 * model.n_class1_nodes()
                };
                for copy in [2 * bar, 2 * bar + 1] {
                    start[half + 3 * copy + axis] = 1.0;
                }
                None
            }
        };
        match scale {
            Some(value) => {
                let h = eta(value.abs());
                // a value within h of zero (an undamped string) is differenced forwards: the
                // string force is linear in its damping and stiffness, so exactly
                let back = if value - h < 0.0 { 0.0 } else { h };
                let plus = Model::new(&moved(structure, p, value, h)?, ground.clone())?;
                let minus = Model::new(&moved(structure, p, value, -back)?, ground.clone())?;
                let ws = (plus.workspace()?, minus.workspace()?);
                prepared.push(Prepared::Model(Box::new(MovedModels {
                    plus,
                    minus,
                    ws,
                    h: 0.5 * (h + back),
                })));
            }
            None => prepared.push(Prepared::Initial),
        }
        s0.push(start);
    }
    let k = parameters.len();
    let steps = (t_end / dt).ceil() as usize;
    let every = every.max(1);
    let mut y = y0;
    let mut s = s0;
    let mut out = TrajectorySensitivity {
        times: Vec::new(),
        nodes: Vec::new(),
        node_sensitivities: Vec::new(),
        states: Vec::new(),
        state_sensitivities: Vec::new(),
        events: Vec::new(),
        rhs_evaluations: 0,
        bar_length_drift: 0.0,
        warnings: Vec::new(),
    };
    let bar_lengths = |y: &[f64]| -> Vec<f64> {
        (0..nb)
            .map(|b| (vec3(y, 2 * b + 1) - vec3(y, 2 * b)).norm())
            .collect()
    };
    let lengths0 = bar_lengths(&y);
    let shortest = lengths0.iter().copied().fold(f64::INFINITY, f64::min);
    let mut evals = 0usize;
    let sample = |out: &mut TrajectorySensitivity, t: f64, y: &[f64], s: &[Vec<f64>]| {
        out.times.push(t);
        out.nodes.push(model.nodes_of(y));
        // a file node's derivative is its representative copy's (anchors do not move)
        let zero: Vec<f64> = vec![0.0; y.len()];
        out.node_sensitivities.push(
            s.iter()
                .map(|sj| {
                    // an anchor reads back its own position from any state: subtract it
                    let anchors = model.nodes_of(&zero);
                    let d = model.nodes_of(sj);
                    d.iter().zip(&anchors).map(|(d, a)| d - a).collect()
                })
                .collect(),
        );
        out.states.push(y.to_vec());
        out.state_sensitivities.push(s.to_vec());
    };
    sample(&mut out, 0.0, &y, &s);
    let mut t = 0.0;
    // f and the augmented right-hand side at (t, y, S)
    let mut f_at = |t: f64,
                    y: &[f64],
                    s: &[Vec<f64>],
                    dy: &mut [f64],
                    ds: &mut [Vec<f64>],
                    prepared: &mut [Prepared]|
     -> Result<(), CoreError> {
        model.rhs(t, y, dy, &mut ws)?;
        evals += 1;
        let ymax = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
        let mut yp = vec![0.0; n];
        for j in 0..k {
            let smax = s[j].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for v in ds[j].iter_mut() {
                *v = 0.0;
            }
            if smax > 0.0 {
                let h = eta(ymax) / smax;
                for i in 0..n {
                    yp[i] = y[i] + h * s[j][i];
                }
                model.rhs(t, &yp, &mut fp, &mut ws)?;
                for i in 0..n {
                    yp[i] = y[i] - h * s[j][i];
                }
                model.rhs(t, &yp, &mut fm, &mut ws)?;
                evals += 2;
                for i in 0..n {
                    ds[j][i] = (fp[i] - fm[i]) / (2.0 * h);
                }
            }
            if let Prepared::Model(m) = &mut prepared[j] {
                let MovedModels {
                    plus,
                    minus,
                    ws: (wp, wm),
                    h,
                } = m.as_mut();
                plus.rhs(t, y, &mut fp, wp)?;
                minus.rhs(t, y, &mut fm, wm)?;
                evals += 2;
                for i in 0..n {
                    ds[j][i] += (fp[i] - fm[i]) / (2.0 * *h);
                }
            }
        }
        Ok(())
    };
    let mut kinks = Kinks::new(structure, &model, ground.as_ref(), &y);
    let (mut k1, mut k2, mut k3, mut k4) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let zeros = || vec![vec![0.0; n]; k];
    let (mut l1, mut l2, mut l3, mut l4) = (zeros(), zeros(), zeros(), zeros());
    let mut yt = vec![0.0; n];
    let mut st = zeros();
    for step in 1..=steps {
        let h = dt.min(t_end - t);
        f_at(t, &y, &s, &mut k1, &mut l1, &mut prepared)?;
        let stage = |c: f64, kk: &[f64], ll: &[Vec<f64>], yt: &mut [f64], st: &mut [Vec<f64>]| {
            for i in 0..n {
                yt[i] = y[i] + c * kk[i];
            }
            for j in 0..k {
                for i in 0..n {
                    st[j][i] = s[j][i] + c * ll[j][i];
                }
            }
        };
        stage(0.5 * h, &k1, &l1, &mut yt, &mut st);
        f_at(t + 0.5 * h, &yt, &st, &mut k2, &mut l2, &mut prepared)?;
        stage(0.5 * h, &k2, &l2, &mut yt, &mut st);
        f_at(t + 0.5 * h, &yt, &st, &mut k3, &mut l3, &mut prepared)?;
        stage(h, &k3, &l3, &mut yt, &mut st);
        f_at(t + h, &yt, &st, &mut k4, &mut l4, &mut prepared)?;
        for i in 0..n {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        for j in 0..k {
            for i in 0..n {
                s[j][i] += h / 6.0 * (l1[j][i] + 2.0 * l2[j][i] + 2.0 * l3[j][i] + l4[j][i]);
            }
        }
        if let Some(i) = y.iter().position(|v| !v.is_finite()) {
            return Err(refused(
                format!("state {i}"),
                format!("not finite at t = {t} s"),
            ));
        }
        kinks.step(t, &model, &y, &mut out.events);
        let error = bar_lengths(&y)
            .iter()
            .zip(&lengths0)
            .fold(0.0f64, |e, (l, l0)| e.max((l - l0).abs()));
        out.bar_length_drift = out.bar_length_drift.max(error / shortest);
        t += h;
        if step % every == 0 || step == steps {
            sample(&mut out, t, &y, &s);
        }
    }
    out.rhs_evaluations = evals;
    let limit = crate::drift::DriftLimits::default().bar_length;
    if out.bar_length_drift > limit {
        out.warnings.push(Warning::Drift {
            invariant: DriftInvariant::BarLength,
            value: out.bar_length_drift,
            limit,
            remedy: "use a smaller `dt`: the sensitivities integrate RK4 without projecting on the bar lengths".into(),
        });
    }
    Ok(out)
}

/// The signs of the strings' strains and the contact nodes' clearances, to report the kinks
/// a step crossed.
struct Kinks {
    strings: Vec<([usize; 2], f64)>,
    contact: Option<(Ground, Vec<usize>)>,
    taut: Vec<bool>,
    touching: Vec<bool>,
}

impl Kinks {
    fn new(structure: &Structure, model: &Model, ground: Option<&Ground>, y: &[f64]) -> Self {
        let strings = structure
            .strings()
            .iter()
            .map(|s| {
                let [a, b] = s.nodes;
                let l = (structure.nodes()[b] - structure.nodes()[a]).norm();
                (s.nodes, s.rest_length.unwrap_or(l))
            })
            .collect();
        let contact = ground.map(|g| {
            let nodes = g
                .nodes
                .clone()
                .unwrap_or_else(|| (0..structure.n_nodes()).collect());
            (g.clone(), nodes)
        });
        let mut k = Self {
            strings,
            contact,
            taut: Vec::new(),
            touching: Vec::new(),
        };
        let (taut, touching) = k.state(model, y);
        k.taut = taut;
        k.touching = touching;
        k
    }

    fn state(&self, model: &Model, y: &[f64]) -> (Vec<bool>, Vec<bool>) {
        let x = model.nodes_of(y);
        let taut = self
            .strings
            .iter()
            .map(|&([a, b], s0)| (x[b] - x[a]).norm() > s0)
            .collect();
        let touching = match &self.contact {
            Some((g, nodes)) => nodes
                .iter()
                .map(|&i| (x[i] - g.point).dot(&g.normal) < 0.0)
                .collect(),
            None => Vec::new(),
        };
        (taut, touching)
    }

    fn step(&mut self, t: f64, model: &Model, y: &[f64], events: &mut Vec<SensitivityEvent>) {
        let (taut, touching) = self.state(model, y);
        for (j, (&now, &was)) in taut.iter().zip(&self.taut).enumerate() {
            if now != was {
                let what = format!("string {j} {}", if now { "taut" } else { "slack" });
                events.push(SensitivityEvent { time: t, what });
            }
        }
        if let Some((_, nodes)) = &self.contact {
            for ((&now, &was), &i) in touching.iter().zip(&self.touching).zip(nodes) {
                if now != was {
                    let what = format!(
                        "node {i} {} the ground",
                        if now { "touches" } else { "leaves" }
                    );
                    events.push(SensitivityEvent { time: t, what });
                }
            }
        }
        self.taut = taut;
        self.touching = touching;
    }
}
