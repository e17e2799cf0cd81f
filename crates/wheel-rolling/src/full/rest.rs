//! The full wheel's start at rest: its deformed shape under gravity on the slope
//! ([`FullStart::Rest`], the default), so that the elastic wheel begins where the rigid one
//! does — at rest, in the same pose — instead of sagging out of its unloaded shape.
//!
//! **Why.** Released from its unloaded prestressed shape, the elastic wheel sags into the
//! penalty ground and its strings stretch; that transient (tens of microseconds of sag at
//! 10⁶ N/m) throws it into the pivot with a spin the rigid wheel reaches only tens of
//! milliseconds later, and the pivot out of its near-balanced start (an inverted pendulum)
//! amplifies that head start: n = 8 on 30° with strings and ground at 10⁶ N/m, 6 % more axle
//! travel at 0.9 of the first impact than the rigid wheel.
//!
//! **What the start is.** With x the class-1 node positions, a(x) the accelerations of the
//! full model at rest (strings, gravity g₀(0, sin φ, −cos φ), bar constraints, and the ground
//! as springs: normal k δ and a tangential spring k_t per touching node anchored where the
//! node first touched, no cap), the start x* solves
//!
//! * **the wheel rests** (the gravity moment about the downhill pair tips it uphill, φ < π/n
//!   for a polygon wheel): a(x*) = 0 with groups 0 and 1 on the ground — its static
//!   equilibrium;
//! * **the wheel pivots** (the moment tips it downhill): a(x*) = α e(x*), where
//!   e_i = e_x × (x_i − p) is the rigid rotation about the axle direction through the
//!   downhill pair's mean position p and α = Σ e·a / Σ e·e: the wheel at rest whose every
//!   node accelerates as a rigid body pivoting about the downhill pair — the rigid model's
//!   state at t = 0⁺, with the ground's reaction on the downhill pair only (the uphill pair,
//!   left out of the ground here, carries nothing, as in the rigid model). The shape is
//!   then turned rigidly about that axis until the lowest uphill node just touches the
//!   slope (height 0, no force), and the wheel starts from there. The turn is the
//!   penetration and sag over the pair spacing (about 10⁻⁴ rad at 10⁶ N/m).
//!
//! So in both cases the run begins with no deformation transient: what the wheel does next
//! is what the loads do, not its release.
//!
//! **How** (dynamic relaxation with kinetic damping): the pseudo-motion ẍ = a(x, ẋ) − α e
//! (α = 0 when the wheel rests; α = eᵀM a / eᵀM e with M the bars' consistent mass, so the
//! pseudo-velocity is also kept M-orthogonal to e) is integrated with RK4 at the run's step
//! (the dynamics crate's [`Rk4`] over the pseudo-dynamics as a [`System`]),
//! projected onto the bar lengths and joints after every step, the anchors moved as in the
//! run; whenever the pseudo-kinetic energy Σ ‖ẋ‖² falls (a peak has passed), every velocity
//! is set to zero. It stops when the residual max ‖a − α e‖ at rest is below [`RESIDUAL`] g₀
//! and the largest speed below [`SPEED`] g₀ dt (converged). A wheel on one pair can have a
//! soft mode that the loads drive with almost no restoring force (the default toroid's
//! strings, 2·10⁴ N/m: the relaxation drifts sideways and stalls near 10⁻² g₀): when the
//! least residual has not halved for [`STALL`] steps, or after [`MAX_STEPS`], the relaxation
//! keeps its least-residual state if that residual is below [`ACCEPT`] g₀, and otherwise the
//! wheel starts unloaded ([`Settled::converged`] false). A relaxation that fails (a step too
//! large for the stiffness) also leaves the wheel unloaded: the run then says why.
//!
//! **When** ([`FullStart::Auto`], the default): at rest when the wheel is stiff, m g/(k R_o)
//! below [`defaults::RIGID_THRESHOLD`] (k the softest string): where the rigid model applies
//! and the two models are compared (docs/notes/ROLLING.md, "Cross-validation"). A flexible wheel
//! (the default strings: 7·10⁻³) starts unloaded as before: its relaxation does not converge
//! (the soft mode above) and would cost thousands of steps. The thesis contact has no spring
//! to rest on: it always starts unloaded, as does [`FullStart::Unloaded`].
//!
//! Measured (`toroid` test `rolling_pivot`, strings and ground 10⁶ N/m, μ = 1.2, e = 0, stick
//! contact, RK4 at 5·10⁻⁵ s; the full model against the rigid one): n = 8 on 30°, first
//! impact −0.07 % and axle travel at 0.9 t₁ +0.19 % (unloaded start: −2.0 % and +6.3 %); the
//! relaxation takes about 2 000 steps there (a tenth of the run to the first impact).

use super::scene::WheelScene;
use crate::contact::ContactModel;
use crate::defaults;
use crate::error::Result;
use nalgebra::Vector3;
use tensegrity_core::{CoreError, Structure};
use tensegrity_dynamics::{
    ConstraintSet, Ground, GroundModel, Integrator, Model, NodeRef, Rk4, System, Workspace,
};

/// Relative residual acceleration (of g₀) at which the relaxation stops.
pub const RESIDUAL: f64 = 1e-3;

/// Largest pseudo-speed (of g₀ dt) at which the relaxation stops.
pub const SPEED: f64 = 1e-2;

/// Largest number of relaxation steps.
pub const MAX_STEPS: usize = 20_000;

/// Steps without halving the best residual after which the relaxation gives up (a mode
/// the loads drive without a restoring force: no rest state near the start).
pub const STALL: usize = 4096;

/// A relaxation that stalls keeps its least-residual state when that residual is below
/// this fraction of g₀.
pub const ACCEPT: f64 = 0.01;

/// The residual is evaluated every this many steps.
const CHECK_EVERY: usize = 16;

/// How the full wheel starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FullStart {
    /// [`FullStart::Rest`] for a stiff wheel (m g / (k R_o) below
    /// [`defaults::RIGID_THRESHOLD`], k the softest string: where the rigid model applies and
    /// the two are compared), else [`FullStart::Unloaded`] (module docs).
    #[default]
    Auto,
    /// At rest in its deformed shape under gravity on the slope (module docs): the rigid
    /// model's start.
    Rest,
    /// In the scene's unloaded prestressed shape, released at t = 0 (the model before the
    /// start at rest; it sags into the ground at the release).
    Unloaded,
}

impl FullStart {
    /// Whether the wheel of `scene` (under gravity `gravity`) starts at rest.
    pub fn at_rest(self, scene: &WheelScene, gravity: f64) -> bool {
        match self {
            Self::Rest => true,
            Self::Unloaded => false,
            Self::Auto => {
                let k = scene
                    .structure
                    .strings()
                    .iter()
                    .filter_map(|s| s.stiffness)
                    .fold(f64::INFINITY, f64::min);
                scene.mass * gravity / (k * scene.outer_radius) < defaults::RIGID_THRESHOLD
            }
        }
    }
}

/// What the relaxation did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settled {
    /// Whether the wheel pivots from its start (else it rests).
    pub pivots: bool,
    /// Whether the relaxation converged; when it did not, the wheel starts unloaded
    /// (module docs).
    pub converged: bool,
    /// Relaxation steps taken.
    pub steps: usize,
    /// Final residual max ‖a − α e‖ (m/s²).
    pub residual: f64,
    /// Rotation about the downhill pair applied to bring the uphill pair onto the slope
    /// (rad, negative rolling downhill).
    pub turn: f64,
}

/// The scene's structure (under the run's gravity) moved to its start at rest on the slope
/// z = `plane_z` (module docs), with what the relaxation did; `None` for the thesis contact.
pub(super) fn settle(
    structure: &Structure,
    scene: &WheelScene,
    contact: &ContactModel,
    dt: f64,
) -> Result<Option<(Structure, Settled)>> {
    let k = contact.stiffness();
    if matches!(contact, ContactModel::Thesis { .. }) || k.is_nan() || k <= 0.0 {
        return Ok(None);
    }
    let kt = match *contact {
        ContactModel::Stick {
            tangential_stiffness,
            ..
        } => tangential_stiffness,
        _ => defaults::TANGENTIAL_STIFFNESS_RATIO * k,
    };
    let g0 = structure.gravity().map_or(0.0, |g| g.norm());
    let mut model = Model::new(structure, None)?;
    let class1 = |i: usize| match model.node_map()[i] {
        NodeRef::Free(c) => Some(c),
        NodeRef::Anchor(_) => None,
    };
    let uphill: Vec<usize> = scene.contact_groups[0]
        .iter()
        .filter_map(|&i| class1(i))
        .collect();
    let downhill: Vec<usize> = scene.contact_groups[1]
        .iter()
        .filter_map(|&i| class1(i))
        .collect();
    let plane = Vector3::new(0.0, 0.0, scene.plane_z());
    let springs = GroundModel::Stick {
        stiffness: k,
        damping: 0.0,
        mu_static: f64::MAX,
        mu_kinetic: f64::MAX,
        tangential_stiffness: kt,
        tangential_damping: 0.0,
    };
    let mut ground = Ground::new(plane, Vector3::z(), springs);
    let mut y = model.initial_state(structure)?;
    let mut relax = Relax {
        pivot: Some(downhill.clone()),
        masses: bar_masses(structure),
        dy: vec![0.0; y.len()],
        n3: y.len() / 2,
    };
    // does the wheel tip downhill about the downhill pair? (the gravity moment's sign)
    ground.nodes = Some(scene.contact_groups[1].clone());
    model.set_ground(ground.clone())?;
    let mut ws = model.workspace()?;
    let alpha = relax.alpha(&model, &y, &mut ws)?;
    // e is a positive spin about x; rolling downhill is a negative one
    let pivots = alpha < 0.0;
    if !pivots {
        ground.nodes = Some(scene.contact_groups[..2].concat());
        model.set_ground(ground)?;
        ws = model.workspace()?;
        relax.pivot = None;
    }
    let mut constraints = ConstraintSet::new(&model)?;
    let mut rk = Rk4::new(y.len());
    let (mut ke_prev, mut steps, mut residual) = (0.0, 0, f64::INFINITY);
    let (mut best, mut best_at, mut converged) = (f64::INFINITY, 0, false);
    let (mut least, mut at_least) = (f64::INFINITY, y.clone());
    while steps < MAX_STEPS && steps - best_at < STALL {
        let pseudo = PseudoDynamics {
            model: &model,
            relax: &relax,
        };
        rk.step(&pseudo, &mut ws, 0.0, &mut y, dt)?;
        constraints.project(&model, &mut y, 1e-12 * scene.outer_radius, 0.0)?;
        model.update_contact_anchors(&y, &mut ws);
        let (x, v) = y.split_at_mut(relax.n3);
        relax.remove(x, v);
        steps += 1;
        // kinetic damping: a peak of the pseudo-kinetic energy has passed
        let ke: f64 = v.iter().map(|c| c * c).sum();
        if ke < ke_prev {
            v.iter_mut().for_each(|c| *c = 0.0);
            ke_prev = 0.0;
        } else {
            ke_prev = ke;
        }
        if steps % CHECK_EVERY == 0 {
            let speed = v.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
            residual = relax.residual(&model, &y, &mut ws)?;
            if !residual.is_finite() {
                break;
            }
            if residual <= RESIDUAL * g0 && speed <= SPEED * g0 * dt {
                converged = true;
                break;
            }
            if residual < least {
                (least, at_least) = (residual, y.clone());
            }
            if residual < 0.5 * best {
                (best, best_at) = (residual, steps);
            }
        }
    }
    if !converged && least <= ACCEPT * g0 {
        (converged, residual, y) = (true, least, at_least);
    }
    let n3 = relax.n3;
    y[n3..].iter_mut().for_each(|c| *c = 0.0);
    let turn = if pivots && converged {
        touch(&mut y[..n3], &uphill, &downhill, scene.plane_z())
    } else {
        0.0
    };
    let settled = Settled {
        pivots,
        converged,
        steps,
        residual,
        turn,
    };
    if !converged {
        return Ok(Some((structure.clone(), settled)));
    }
    let nodes = model.nodes_of(&y);
    Ok(Some((structure.with_nodes(nodes)?, settled)))
}

/// The pseudo-dynamics of the relaxation: the model's accelerations less the rigid pivot's.
struct Relax {
    /// The class-1 nodes of the downhill pair when the wheel pivots.
    pivot: Option<Vec<usize>>,
    /// Mass of every bar (its ends are class-1 nodes 2k, 2k + 1).
    masses: Vec<f64>,
    dy: Vec<f64>,
    n3: usize,
}

impl Relax {
    /// The pivot's centre p (mean of the downhill nodes) in `x`.
    fn centre(nodes: &[usize], x: &[f64]) -> Vector3<f64> {
        nodes.iter().map(|&c| node(x, c)).sum::<Vector3<f64>>() / nodes.len() as f64
    }

    /// (eᵀ M u / eᵀ M e, p) for the field `u` at positions `x` (M the bars' consistent mass
    /// m/6 [[2, 1], [1, 2]]).
    fn component(&self, nodes: &[usize], x: &[f64], u: &[f64]) -> (f64, Vector3<f64>) {
        let p = Self::centre(nodes, x);
        let (mut eu, mut ee) = (0.0, 0.0);
        for (k, &m) in self.masses.iter().enumerate() {
            let (a, b) = (2 * k, 2 * k + 1);
            let (ea, eb) = (spin(&node(x, a), &p), spin(&node(x, b), &p));
            let (ma, mb) = ((2.0 * ea + eb) * (m / 6.0), (ea + 2.0 * eb) * (m / 6.0));
            eu += ma.dot(&node(u, a)) + mb.dot(&node(u, b));
            ee += ma.dot(&ea) + mb.dot(&eb);
        }
        (eu / ee, p)
    }

    /// Removes the pivot's component (M-weighted) from the field `u` at positions `x`.
    fn remove(&self, x: &[f64], u: &mut [f64]) {
        let Some(nodes) = &self.pivot else {
            return;
        };
        let (alpha, p) = self.component(nodes, x, u);
        for c in 0..x.len() / 3 {
            let e = spin(&node(x, c), &p);
            for d in 0..3 {
                u[3 * c + d] -= alpha * e[d];
            }
        }
    }

    /// The pivot's α at rest in `y` (the wheel at `y`'s positions, no velocity).
    fn alpha(&mut self, model: &Model, y: &[f64], ws: &mut Workspace) -> Result<f64> {
        let mut rest = y.to_vec();
        rest[self.n3..].iter_mut().for_each(|c| *c = 0.0);
        model.rhs(0.0, &rest, &mut self.dy, ws)?;
        let nodes = self.pivot.as_deref().unwrap_or(&[]);
        let (x, dv) = (&rest[..self.n3], &self.dy[self.n3..]);
        Ok(self.component(nodes, x, dv).0)
    }

    /// The pseudo-accelerations at `y` into `out`.
    fn rhs(
        &self,
        model: &Model,
        y: &[f64],
        out: &mut [f64],
        ws: &mut Workspace,
    ) -> std::result::Result<(), CoreError> {
        model.rhs(0.0, y, out, ws)?;
        let (x, dv) = (&y[..self.n3], &mut out[self.n3..]);
        self.remove(x, dv);
        Ok(())
    }

    /// max ‖a − α e‖ at rest at `y`'s positions.
    fn residual(&mut self, model: &Model, y: &[f64], ws: &mut Workspace) -> Result<f64> {
        let mut rest = y.to_vec();
        rest[self.n3..].iter_mut().for_each(|c| *c = 0.0);
        let mut out = std::mem::take(&mut self.dy);
        self.rhs(model, &rest, &mut out, ws)?;
        let r = out[self.n3..]
            .chunks_exact(3)
            .map(|a| Vector3::new(a[0], a[1], a[2]).norm())
            .fold(0.0, f64::max);
        self.dy = out;
        Ok(r)
    }
}

/// The pseudo-dynamics ẍ = a(x, ẋ) − α e of the relaxation (module docs) as the system its
/// RK4 steps: the model's right-hand side at t = 0 with the pivot's component removed.
struct PseudoDynamics<'a> {
    model: &'a Model,
    relax: &'a Relax,
}

impl System for PseudoDynamics<'_> {
    type Workspace = Workspace;

    fn state_len(&self) -> usize {
        self.model.state_len()
    }

    /// The pseudo-accelerations ([`Relax::rhs`]); the relaxation is autonomous (`t` unused).
    fn rhs(
        &self,
        _t: f64,
        y: &[f64],
        dy: &mut [f64],
        ws: &mut Workspace,
    ) -> std::result::Result<(), CoreError> {
        self.relax.rhs(self.model, y, dy, ws)
    }
}

/// The mass of every bar: given, or ρ π r² l from its material and radius (as the model
/// takes it).
fn bar_masses(structure: &Structure) -> Vec<f64> {
    (0..structure.n_bars())
        .map(|k| structure.bar_mass(k).unwrap_or(1.0))
        .collect()
}

fn node(x: &[f64], c: usize) -> Vector3<f64> {
    Vector3::new(x[3 * c], x[3 * c + 1], x[3 * c + 2])
}

/// The rigid rotation field e_x × (x − p) at `x`.
fn spin(x: &Vector3<f64>, p: &Vector3<f64>) -> Vector3<f64> {
    let r = x - p;
    Vector3::new(0.0, -r.z, r.y)
}

/// Turns the positions `x` rigidly about the axle direction through the downhill pair's
/// centre until the lowest uphill node is at height 0 above the slope z = `plane_z`; returns
/// the angle (rad).
fn touch(x: &mut [f64], uphill: &[usize], downhill: &[usize], plane_z: f64) -> f64 {
    let p = Relax::centre(downhill, x);
    let height = |x: &[f64], theta: f64| {
        let (s, c) = theta.sin_cos();
        uphill
            .iter()
            .map(|&i| {
                let r = node(x, i) - p;
                (p.z + r.y * s + r.z * c - plane_z, r.y * c - r.z * s)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .unwrap_or((0.0, 1.0))
    };
    let mut theta = 0.0;
    for _ in 0..8 {
        let (h, slope) = height(x, theta);
        if slope == 0.0 {
            break;
        }
        theta -= h / slope;
    }
    let (s, c) = theta.sin_cos();
    for i in 0..x.len() / 3 {
        let r = node(x, i) - p;
        x[3 * i + 1] = p.y + r.y * c - r.z * s;
        x[3 * i + 2] = p.z + r.y * s + r.z * c;
    }
    theta
}
