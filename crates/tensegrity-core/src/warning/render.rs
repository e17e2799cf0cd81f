//! The text of every [`Warning`]: the one place warnings become sentences (the CLI, the
//! Python package and the `message` of the JSON all show this).

use super::{DriftInvariant, Warning};
use std::fmt;

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use Warning as W;
        match self {
            W::NotPrestressable => f.write_str(
                "the self-stress is not prestressable: no state with every string in tension and every bar in compression",
            ),
            W::NotPrestressStable => f.write_str(
                "the prestressed form is not stable: a mechanism is not stiffened by the prestress",
            ),
            W::NoPrestressedStructure { reason } => write!(f, "no prestressed structure: {reason}"),
            W::StaticsNotCertified { reason } => f.write_str(reason),
            W::NoLoadEnvelope { reason } => write!(f, "no load envelope: {reason}"),
            W::RimFreeBody => f.write_str(
                "rim body: free-body statics (six rigid-body motions, no supports); the load \
                 envelope, minimum prestress and mass are computed with the rigid rim (rim = fixed)",
            ),
            W::MethodChosen { reason } => f.write_str(reason),
            W::NoCyclicSymmetry { reason } => {
                write!(f, "no cyclic symmetry ({reason}): the statics take the dense SVD")
            }
            W::PrestressBelowMinimum { prestress, minimum, load, slack_fraction } => write!(
                f,
                "the prestress {prestress} N is below the minimum {minimum:.4} N that carries the load envelope (w0 = {load} N from every direction): strings go slack for {:.1} % of the sampled directions, and the mass is sized for a structure that does not carry the envelope (not a valid sizing; raise `prestress` to at least {minimum:.4} N)",
                100.0 * slack_fraction
            ),
            W::SingleLoopTrack => f.write_str(
                "a single loop stands on tips in one plane (track 0): it tips under any \
                 lateral force; the extended wheel (a copy at an offset along the axle) gives \
                 the track",
            ),
            W::SlackInContact { min_tension, capacity, tips, per_tip, suggested_min_tension } => write!(
                f,
                "the prestress (smallest string tension {min_tension:.3} N) keeps every string taut only for tip loads up to {capacity:.3} N, less than the wheel's weight per landing tip m g / {tips} = {per_tip:.3} N: strings may go slack in contact (raise min_tension to about {suggested_min_tension:.3} N)"
            ),
            W::SankBelowGround { depth, tolerance } => write!(
                f,
                "a contact node sank {depth:.4} m below the ground (tolerance {tolerance:.4} m)"
            ),
            W::SankBelowSlope { depth, tolerance, tolerance_fraction } => write!(
                f,
                "a contact node sank {depth:.4} m below the slope, more than the tolerance {tolerance:.4} m ({} % of R_o): the contact is too soft for this wheel",
                100.0 * tolerance_fraction
            ),
            W::GroundPulled { min_normal } => write!(
                f,
                "the ground pulled on the wheel (normal force down to {min_normal:.3} N): a real slope only pushes"
            ),
            W::LiftOff { model, runs } => {
                let runs: Vec<String> = runs
                    .iter()
                    .map(|r| format!("n = {} (min {:.1} N)", r.sides, r.min_normal))
                    .collect();
                write!(
                    f,
                    "the {model}'s net normal force goes negative for {}: the wheel would leave the \
                     slope there, outside the model's assumptions",
                    runs.join(", ")
                )
            }
            W::EnergyBudget { error, tolerance } => write!(
                f,
                "the energy budget misses by {error:.2e} of its largest term (more than {tolerance:.0e}): reduce dt"
            ),
            W::RigidEnergyBudget { error } => write!(
                f,
                "the rigid model's energy budget closes only to {error:.2e} relative: reduce dt"
            ),
            W::ImpactNotConverged { t, sweeps } => write!(
                f,
                "the simultaneous impact at t = {t:.6} s did not converge in {sweeps} sweeps"
            ),
            W::ImpactCreatedEnergy { t, energy } => write!(
                f,
                "the impact at t = {t:.6} s created {energy:.3e} J (Newton restitution with friction \
                 is not energy-consistent there)"
            ),
            W::Drift { invariant, value, limit, remedy } => drift(f, *invariant, *value, *limit, remedy),
            W::StoppedEarly { t, t_end, reason } => write!(
                f,
                "the integration stopped before t_end = {t_end} s ({reason}); every figure covers only [0, {t}] s"
            ),
            W::Interrupted { t, t_end } => write!(
                f,
                "the run was interrupted at t = {t} s of t_end = {t_end} s (its observer asked it to stop); every figure covers only [0, {t}] s"
            ),
            W::RigidStopped { t, reason } => {
                write!(f, "rigid rolling stopped at t = {t:.6} s: {reason}; the samples end there")
            }
            W::NotConverged { quantity, value, refined, relative_change, estimated_error, tolerance, refinement } => {
                not_converged(f, quantity, [*value, *refined], *relative_change, *estimated_error, *tolerance, refinement)
            }
            W::RefinementFailed { refinement } => write!(f, "not converged: {refinement}"),
            W::NonFinite { quantity } => write!(
                f,
                "`{quantity}` is not a finite number: the run left double precision (a gravity, speed or stiffness out of range), and its numbers are no answer"
            ),
            W::InRun { sides, run, warning } => write!(f, "n = {sides}, {run}: {warning}"),
            W::RowFailed { sides, error } => write!(f, "n = {sides}: {error}"),
            W::OptimizerNotConverged { stop, iterations, objective } => write!(
                f,
                "the optimiser did not converge (stopped by {stop} after {iterations} iterations); the best point found, objective {objective:e}, is reported and written"
            ),
            W::OptimizerStalled { projected_gradient, gtol, objective } => write!(
                f,
                "the optimiser stopped on its objective rule (the objective fell by less than ftol in an iteration) with the projected gradient at {projected_gradient:e}, above gtol {gtol:e}: objective {objective:e} is not a verified stationary point, and an ill-conditioned problem can stall well above its optimum (a smaller ftol, or the levenberg_marquardt method for a sum of squares)"
            ),
            W::MembersChangedKind { members } => write!(
                f,
                "members {members:?} changed sign (sign = \"free\"): the designed topology lists them as the other kind (a bar in tension as a string)"
            ),
        }
    }
}

/// An invariant past its limit, with the remedy.
fn drift(
    f: &mut fmt::Formatter<'_>,
    invariant: DriftInvariant,
    value: f64,
    limit: f64,
    remedy: &str,
) -> fmt::Result {
    let what = match invariant {
        DriftInvariant::Energy => "energy of this conservative model drifted",
        DriftInvariant::EnergyGrowth => {
            "energy of this passive (damped or conservative) model grew"
        }
        DriftInvariant::BarLength => "bar lengths drifted",
        DriftInvariant::Constraint => "joint and support constraints (N P = D) drifted",
        DriftInvariant::ImplicitSolve => {
            "implicit contact stages were left unconverged (Newton's residual above its acceptance)"
        }
        DriftInvariant::CreepChatter => {
            "contact nodes chattered on the ground (the change of their tangential velocity reversed from one step to the next: the split IMEX's bias on a creeping contact)"
        }
    };
    let of = match invariant {
        DriftInvariant::ImplicitSolve => "of them",
        DriftInvariant::CreepChatter => "of their steps",
        _ => "",
    };
    if !of.is_empty() {
        // 100 × 0.1 is 10.000000000000002: print the limit to 3 decimals, trimmed
        let limit = format!("{:.3}", 100.0 * limit);
        let limit = limit.trim_end_matches('0').trim_end_matches('.');
        return write!(
            f,
            "{what}: {:.1} % {of}, above the limit {limit} %; the trajectory is not trustworthy: {remedy}",
            100.0 * value,
        );
    }
    write!(
        f,
        "{what}: {value:.3e} relative, above the limit {limit:.1e}; the trajectory is not trustworthy: {remedy}"
    )
}

/// A quantity that moved at the refined resolution.
fn not_converged(
    f: &mut fmt::Formatter<'_>,
    quantity: &str,
    [value, refined]: [Option<f64>; 2],
    relative_change: Option<f64>,
    estimated_error: Option<f64>,
    tolerance: f64,
    refinement: &str,
) -> fmt::Result {
    let show = |x: Option<f64>| x.map_or_else(|| "none".to_string(), |x| format!("{x:.6}"));
    let error = |e: Option<f64>, r: f64| 100.0 * e.unwrap_or(2.0 * r);
    match relative_change {
        Some(r) if value.is_none() => write!(
            f,
            "not converged: `{quantity}` moved by {:.2} % at the companion resolution ({refinement}): its error, extrapolated, is {:.2} % (tolerance {:.2} %)",
            100.0 * r,
            error(estimated_error, r),
            100.0 * tolerance
        ),
        Some(r) => write!(
            f,
            "not converged: `{quantity}` moved by {:.2} % at the companion resolution ({refinement}): {} -> {}; its error, extrapolated, is {:.2} % (tolerance {:.2} %)",
            100.0 * r,
            show(value),
            show(refined),
            error(estimated_error, r),
            100.0 * tolerance
        ),
        None => write!(
            f,
            "not converged: `{quantity}` is {} but {} at the companion resolution ({refinement})",
            show(value),
            show(refined),
        ),
    }
}
