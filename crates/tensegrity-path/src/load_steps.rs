//! Load control: λ = 1/K, 2/K, …, 1, Newton at each from the last equilibrium (crate docs).
//! It cannot follow a path past a limit point: Newton then fails (the error names the
//! arc-length path) or lands on another branch — a jump, reported as [`Event::Jump`] when the
//! step moved the structure more than [`JUMP_RATIO`] times the tangent's prediction.

use crate::arclength::point_of;
use crate::dofs::Dofs;
use crate::error::{PathError, Result};
use crate::model::ElasticModel;
use crate::newton;
use crate::point::{Event, PathReport, Stop};

/// How many times the tangent's predicted displacement increment a load step may move the
/// structure before it counts as a jump ([`Event::Jump`]).
pub const JUMP_RATIO: f64 = 3.0;

/// The equilibria at λ = k/`steps`, k = 0 … `steps` (times `target`), as a path report
/// without events but the slack changes.
///
/// ```
/// use nalgebra::Vector3;
/// use tensegrity_path::{load_steps, ElasticMember, ElasticModel, MemberKind, Support};
/// let bar = ElasticMember { nodes: [0, 1], kind: MemberKind::Bar, ea: 1e4, rest_length: 1.0 };
/// let m = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x()], members: vec![bar],
///     clusters: Vec::new(),
///     supports: vec![Support::pinned(0), Support::along(1, vec![Vector3::y(), Vector3::z()])],
///     load: vec![Vector3::zeros(), Vector3::new(100.0, 0.0, 0.0)], drivers: Default::default() };
/// let path = load_steps(&m, 4, 1.0).unwrap();
/// assert_eq!(path.points.len(), 5);
/// assert!((path.points[2].tensions[0] - 50.0).abs() < 1e-9);
/// ```
pub fn load_steps(model: &ElasticModel, steps: usize, target: f64) -> Result<PathReport> {
    if steps == 0 {
        return Err(PathError::InvalidSetting {
            name: "load_steps",
            value: 0.0,
            reason: "must be at least 1".into(),
        });
    }
    let mut owned = model.clone().validated()?;
    newton::check_rest_lengths(&owned, target)?;
    let dofs = Dofs::of(&owned)?;
    let mut x = owned.nodes.clone();
    let mut report = PathReport {
        points: Vec::new(),
        events: Vec::new(),
        stop: Stop::ReachedTarget,
    };
    for k in 0..=steps {
        let lambda = target * k as f64 / steps as f64;
        let lambda0 = report.points.last().map_or(0.0, |p| p.lambda);
        let eq = newton::solve(&owned, &dofs, &x, lambda0, lambda).map_err(|e| match e {
            PathError::NotConverged {
                lambda,
                residual,
                tolerance,
                iterations,
                ..
            } => PathError::NotConverged {
                lambda,
                residual,
                tolerance,
                iterations,
                hint: "; a limit point may lie before this load: follow the path by its arc length"
                    .into(),
            },
            e => e,
        })?;
        let eq = if owned.has_friction() {
            settle_friction(&mut owned, &dofs, eq)?
        } else {
            eq
        };
        let model = &owned;
        if let Some(prev) = report.points.last() {
            // the tangent's prediction of this step against what Newton found
            let states = crate::forces::member_states(model, &x, prev.lambda);
            let k_t = crate::factor::Factored::of(model, &dofs, &states);
            let dp = newton::load_rate(model, &dofs, &states) * (lambda - prev.lambda);
            // the free part of the step: less the held nodes' driven motion
            let driven = dofs.drive(&x, lambda - prev.lambda);
            let moved: f64 =
                eq.x.iter()
                    .zip(&driven)
                    .map(|(a, b)| (a - b).norm_squared())
                    .sum::<f64>()
                    .sqrt();
            if let Some(v) = k_t.and_then(|mut k| k.solve(&dp)) {
                let predicted = v.norm();
                if moved > JUMP_RATIO * predicted {
                    report.events.push(Event::Jump {
                        from_lambda: prev.lambda,
                        to_lambda: lambda,
                        ratio: moved / predicted.max(f64::MIN_POSITIVE),
                    });
                }
            }
        }
        x = eq.x.clone();
        report.points.push(point_of(model, &dofs, k, &eq, None));
    }
    Ok(report)
}

/// Fixed-point iterations of a load step with pulley friction before it is refused.
pub const MAX_FRICTION_ITERATIONS: usize = 500;

/// Pulley friction at one load step (crate docs, [`crate::clusters`]): from the equilibrium
/// `eq` at the step's start rest lengths, the clusters' material slides to the capstan law
/// at its geometry ([`crate::clusters::slide`], always from the step's start), Newton finds
/// the equilibrium of the new rest lengths, and so on until no rest length moves more than
/// 10⁻¹⁴ of the longest cluster: then equilibrium and the capstan law hold together (a
/// slipping pulley's tension ratio at e^{μθ} to about 10⁻¹² relative). The model keeps the
/// rest lengths and the pulleys' states.
fn settle_friction(
    model: &mut ElasticModel,
    dofs: &Dofs,
    mut eq: newton::Equilibrium,
) -> Result<newton::Equilibrium> {
    let start = crate::clusters::friction_rest_lengths(model);
    let scale = model
        .clusters
        .iter()
        .map(|c| c.rest_length)
        .fold(0.0, f64::max);
    for _ in 0..MAX_FRICTION_ITERATIONS {
        let crate::clusters::Slid { rest, pulleys, .. } =
            crate::clusters::slide(model, &eq.states, &start)?;
        let mut change = 0.0_f64;
        for ((cluster, rest), pulleys) in model.clusters.iter_mut().zip(rest).zip(pulleys) {
            if let Some(f) = &mut cluster.friction {
                for (old, new) in f.rest_lengths.iter().zip(&rest) {
                    change = change.max((old - new).abs());
                }
                f.rest_lengths = rest;
                f.pulleys = pulleys;
            }
        }
        eq = newton::solve(model, dofs, &eq.x, eq.lambda, eq.lambda)?;
        if change <= 1e-14 * scale {
            return Ok(eq);
        }
    }
    Err(PathError::model(
        "pulley friction",
        format!(
            "the clusters' sliding did not settle in {MAX_FRICTION_ITERATIONS} iterations at load factor {:e}: more load steps",
            eq.lambda
        ),
    ))
}
