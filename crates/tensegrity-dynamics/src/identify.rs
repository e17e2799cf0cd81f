//! System identification (issue 47, item 5): the string and bar parameters of a structure
//! whose simulated node trajectory best fits a measured one, by Levenberg–Marquardt on the
//! forward sensitivities ([`crate::sensitivity`]).
//!
//! With r(p) the differences of the simulated and the measured positions of the observed
//! nodes at every sample after the start (RK4 steps of `dt`, a sample every `every` steps:
//! the measurement's times) and J = ∂r/∂p from the sensitivities of the same run, each
//! iteration solves
//!
//! > (JᵀJ + μ diag(JᵀJ)) δ = −Jᵀ r
//!
//! and takes p + δ where it lowers ½‖r‖² (μ divided by 3), else raises μ fourfold and solves
//! again (Marquardt's scaling: each parameter in its own units). It stops when no parameter
//! moves by more than `tolerance` of its value, or at `max_iterations` (not converged, said
//! so). The standard error of each parameter, σ̂ √((JᵀJ)⁻¹)_jj with σ̂² = ‖r‖² / (m − k), is
//! reported beside it (m residuals, k parameters).

use crate::forces::Ground;
use crate::sensitivity::{forward_sensitivities, with_parameter, DynamicsParameter};
use nalgebra::{DMatrix, DVector, Vector3};
use tensegrity_core::error::DynamicsError;
use tensegrity_core::warning::Warning;
use tensegrity_core::{CoreError, Structure};

/// The sampling of the simulated runs and the stopping rules of [`identify`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdentifySettings {
    /// The RK4 step (s).
    pub dt: f64,
    /// Steps between samples (the measurement's sampling: sample k at k · every · dt).
    pub every: usize,
    /// Iterations at most (default 50).
    pub max_iterations: usize,
    /// The largest relative change of a parameter below which it stops (default 10⁻⁹).
    pub tolerance: f64,
}

impl Default for IdentifySettings {
    fn default() -> Self {
        Self {
            dt: 1e-3,
            every: 1,
            max_iterations: 50,
            tolerance: 1e-9,
        }
    }
}

/// The result of [`identify`].
#[derive(Debug, Clone, PartialEq)]
pub struct Identified {
    /// The identified values, one per parameter.
    pub values: Vec<f64>,
    /// Their standard errors (module docs).
    pub standard_errors: Vec<f64>,
    /// The root-mean-square residual at the start and at the end (m).
    pub rms_start: f64,
    /// The root-mean-square residual at the identified values (m).
    pub rms: f64,
    /// Iterations taken.
    pub iterations: usize,
    /// Whether the tolerance was met.
    pub converged: bool,
    /// The structure with the identified values.
    pub structure: Structure,
    /// The bar-length drift of the run at the identified values
    /// ([`TrajectorySensitivity::bar_length_drift`](crate::sensitivity::TrajectorySensitivity::bar_length_drift)).
    pub bar_length_drift: f64,
    /// That run's warnings: a drift past `simulate`'s limit means the fit is that of a model
    /// whose bars stretched (use a smaller `dt`).
    pub warnings: Vec<Warning>,
}

/// The value of `p` in `structure` (a rest length without one: the string's length).
pub fn parameter_value(structure: &Structure, p: DynamicsParameter) -> Option<f64> {
    Some(match p {
        DynamicsParameter::RestLength(j) => {
            let s = structure.strings().get(j)?;
            let [a, b] = s.nodes;
            s.rest_length
                .unwrap_or((structure.nodes()[b] - structure.nodes()[a]).norm())
        }
        DynamicsParameter::Stiffness(j) => structure.strings().get(j)?.stiffness?,
        DynamicsParameter::Damping(j) => structure.strings().get(j)?.damping,
        DynamicsParameter::BarMass(k) => structure.bars().get(k)?.mass?,
        _ => return None,
    })
}

fn refused(item: String, reason: impl Into<String>) -> CoreError {
    DynamicsError::Unsupported {
        item,
        reason: reason.into(),
    }
    .into()
}

/// Identifies `parameters` of `structure` (their values in it are the start) from the
/// `measured` positions of the nodes `observed` (`measured[k][i]` the position of
/// `observed[i]` at sample k, sample 0 the start) on `ground`, if any (module docs). Only
/// model parameters (rest lengths, stiffnesses, dampings, bar masses) are identified; an
/// initial-state parameter, a measurement of the wrong shape or fewer residuals than
/// parameters is refused by name.
pub fn identify(
    structure: &Structure,
    ground: Option<Ground>,
    parameters: &[DynamicsParameter],
    observed: &[usize],
    measured: &[Vec<Vector3<f64>>],
    settings: &IdentifySettings,
) -> Result<Identified, CoreError> {
    let k = parameters.len();
    let mut values = Vec::with_capacity(k);
    for &p in parameters {
        values.push(parameter_value(structure, p).ok_or_else(|| {
            refused(
                p.to_string(),
                "only a model parameter the structure gives (rest length, stiffness, damping, bar mass) is identified",
            )
        })?);
    }
    if measured.len() < 2 {
        return Err(refused(
            "measured".into(),
            "at least the start and one sample",
        ));
    }
    if let Some((s, row)) = measured
        .iter()
        .enumerate()
        .find(|(_, r)| r.len() != observed.len())
    {
        return Err(refused(
            format!("measured[{s}]"),
            format!(
                "{} positions for {} observed nodes",
                row.len(),
                observed.len()
            ),
        ));
    }
    if let Some(&i) = observed.iter().find(|&&i| i >= structure.n_nodes()) {
        return Err(refused(
            "observed".into(),
            format!("node {i} is past the last"),
        ));
    }
    let m = 3 * observed.len() * (measured.len() - 1);
    if m <= k {
        return Err(refused(
            "measured".into(),
            format!("{m} residuals for {k} parameters: too few to identify them"),
        ));
    }
    let samples = measured.len() - 1;
    let t_end = (samples * settings.every) as f64 * settings.dt;
    let at = |values: &[f64]| -> Result<Structure, CoreError> {
        let mut s = structure.clone();
        for (&p, &v) in parameters.iter().zip(values) {
            s = with_parameter(&s, p, v)?;
        }
        Ok(s)
    };
    // residuals (and their Jacobian when asked) of one run
    let run = |values: &[f64], jacobian: bool| -> Result<Run, CoreError> {
        let s = at(values)?;
        let params: &[DynamicsParameter] = if jacobian { parameters } else { &[] };
        let tr = forward_sensitivities(
            &s,
            ground.clone(),
            params,
            settings.dt,
            t_end,
            settings.every,
        )?;
        let mut r = DVector::zeros(m);
        let mut j = jacobian.then(|| DMatrix::zeros(m, k));
        let mut row = 0;
        for sample in 1..=samples {
            for (o, &node) in observed.iter().enumerate() {
                for axis in 0..3 {
                    r[row] = tr.nodes[sample][node][axis] - measured[sample][o][axis];
                    if let Some(j) = j.as_mut() {
                        for c in 0..k {
                            j[(row, c)] = tr.node_sensitivities[sample][c][node][axis];
                        }
                    }
                    row += 1;
                }
            }
        }
        Ok((r, j, (tr.bar_length_drift, tr.warnings)))
    };
    let (mut r, mut jac, _) = run(&values, true)?;
    let rms_start = (r.norm_squared() / m as f64).sqrt();
    let mut mu = 1e-3;
    let mut iterations = 0;
    let mut converged = false;
    while iterations < settings.max_iterations {
        iterations += 1;
        let j = jac.as_ref().expect("a Jacobian with every accepted point");
        let jtj = j.transpose() * j;
        let g = j.transpose() * &r;
        let cost = r.norm_squared();
        let mut accepted = false;
        for _ in 0..30 {
            let mut a = jtj.clone();
            for c in 0..k {
                a[(c, c)] += mu * jtj[(c, c)].max(f64::MIN_POSITIVE);
            }
            let Some(chol) = a.cholesky() else {
                mu *= 4.0;
                continue;
            };
            let delta = chol.solve(&(-&g));
            let trial: Vec<f64> = values
                .iter()
                .zip(delta.iter())
                .map(|(v, d)| v + d)
                .collect();
            let step = values
                .iter()
                .zip(delta.iter())
                .map(|(v, d)| (d / v.abs().max(f64::MIN_POSITIVE)).abs())
                .fold(0.0, f64::max);
            match run(&trial, false) {
                Ok((rt, _, _)) if rt.norm_squared() < cost => {
                    values = trial;
                    mu = (mu / 3.0).max(1e-12);
                    accepted = true;
                    if step <= settings.tolerance {
                        converged = true;
                    }
                    break;
                }
                _ => {
                    if step <= settings.tolerance {
                        // no smaller step can lower the cost: at the minimum to the tolerance
                        converged = true;
                        break;
                    }
                    mu *= 4.0;
                }
            }
        }
        if converged || !accepted {
            break;
        }
        let next = run(&values, true)?;
        r = next.0;
        jac = next.1;
    }
    let (r, jac, (bar_length_drift, warnings)) = run(&values, true)?;
    let dof = (m - k) as f64;
    let sigma2 = r.norm_squared() / dof;
    let j = jac.expect("asked for");
    let standard_errors = match (j.transpose() * &j).try_inverse() {
        Some(inv) => (0..k)
            .map(|c| (sigma2 * inv[(c, c)]).max(0.0).sqrt())
            .collect(),
        None => vec![f64::INFINITY; k],
    };
    Ok(Identified {
        structure: at(&values)?,
        values,
        standard_errors,
        rms_start,
        rms: (r.norm_squared() / m as f64).sqrt(),
        iterations,
        converged,
        bar_length_drift,
        warnings,
    })
}

/// A run's bar-length drift and warnings.
type Checks = (f64, Vec<Warning>);

/// A run's residuals, their Jacobian when asked, and its checks.
type Run = (DVector<f64>, Option<DMatrix<f64>>, Checks);
