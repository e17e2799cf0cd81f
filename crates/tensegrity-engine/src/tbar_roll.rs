//! `tbar roll`: the T-bar wheel (or extended wheel) rolling down an incline beside the toroid
//! of the same outer radius and number of sides, over the number of treads n = π/φ, with the
//! out-of-plane tip-over of the T-bar structure.
//!
//! The T-bar columns come from the tbar-wheel crate ([`TbarRollRequest::tbar_row`]: its
//! wheel description in wheel-rolling's rigid or full model); the toroid column is composed
//! here, since topology crates do not depend on each other: the reference toroid (ERRATA:
//! T = 0.4, t = 0.3, D = 0.1, R_o = 1, R_i = 0.6, R_m = 0.8, spokes + inner rings) scaled by
//! r₀ with n sides and the same bar density ([`toroid_params`]), rolled with the same model —
//! the rigid polygon of its m and I₁ under the T-bar's settings, or `toroid::roll` with the
//! full model ([`toroid_request`]).

use tbar_wheel::roll::{TbarRollReport, TbarRollRequest, Watch};
use tbar_wheel::TbarError;
use tensegrity_core::budget::Estimate;
use tensegrity_core::request::{InvalidParameter, Request};
use toroid::{RollRequest, Stabilize, ToroidParams, ToroidWheel, WheelSpec};
use wheel_rolling::{defaults, Fidelity, FidelityChoice, Polygon, Wheel, WheelRun};

/// Runs `tbar roll` (module docs): one row per number of treads; what fails in a row is named
/// in its `errors`, a request the command refuses is an error, and under `strict` so is a
/// report that is not valid.
///
/// ```
/// use tbar_wheel::TbarRollRequest;
/// use tensegrity_engine::tbar_roll::tbar_roll;
/// let r = tbar_roll(&TbarRollRequest {
///     treads: Some(vec![8]),
///     t_end: Some(0.5),
///     ..Default::default()
/// })
/// .unwrap();
/// let row = &r.rows[0];
/// assert!(row.errors.is_empty(), "{:?}", row.errors);
/// assert!(row.tbar.is_some() && row.toroid.is_some());
/// ```
pub fn tbar_roll(request: &TbarRollRequest) -> Result<TbarRollReport, TbarError> {
    let r = report(request)?;
    strict_check(request, &r)?;
    Ok(r)
}

/// The `strict` rule: under `strict`, a report that is not valid is an error (exit code 1 on
/// the command line).
pub fn strict_check(request: &TbarRollRequest, report: &TbarRollReport) -> Result<(), TbarError> {
    Ok(wheel_rolling::strict_check(
        request.checks.strict,
        &report.warnings,
    )?)
}

/// As [`tbar_roll`], the report returned whatever its validity (a front end writes it, then
/// applies [`strict_check`]).
pub fn report(request: &TbarRollRequest) -> Result<TbarRollReport, TbarError> {
    report_watched(request, None)
}

/// As [`report`], the T-bar run of the first row (the first number of treads) handing its
/// node frames at the watched times to the watch (an animation of
/// [`TbarRollRequest::drawing`]).
pub fn report_watched(
    request: &TbarRollRequest,
    mut watch: Option<Watch>,
) -> Result<TbarRollReport, TbarError> {
    request.validate()?;
    let rim = request.rim()?;
    let rows = request
        .treads()
        .into_iter()
        .map(|n| {
            let mut row = request.tbar_row_watched(n, rim, watch.take());
            match toroid_column(request, n) {
                Ok(s) => row.toroid = Some(s),
                Err(e) => row.errors.push(format!("toroid: {e}")),
            }
            row
        })
        .collect();
    let rows: Vec<tbar_wheel::roll::TbarRollRow> = rows;
    let model = ran(request, &rows);
    Ok(TbarRollReport {
        model,
        fidelity: request.fidelity,
        full_tensegrity_rolling: model == Fidelity::Full,
        structure: request.layout().name(),
        rim,
        contact: (model == Fidelity::Full).then_some(request.contact),
        incline_rad: request.settings.incline,
        t_end: request.t_end(),
        valid: true,
        warnings: Vec::new(),
        rows,
    }
    .judged())
}

/// The model that ran: the one asked for, or with `auto` the full model when any row's T-bar
/// run used it (else rigid).
fn ran(request: &TbarRollRequest, rows: &[tbar_wheel::roll::TbarRollRow]) -> Fidelity {
    match request.fidelity {
        FidelityChoice::Rigid => Fidelity::Rigid,
        FidelityChoice::Full => Fidelity::Full,
        FidelityChoice::Auto => {
            let full = rows
                .iter()
                .filter_map(|r| r.tbar.as_ref())
                .any(|t| t.model == Fidelity::Full);
            if full {
                Fidelity::Full
            } else {
                Fidelity::Rigid
            }
        }
    }
}

/// The reference toroid's parameters scaled to outer radius r₀, with n sides.
pub fn toroid_params(request: &TbarRollRequest, n: usize) -> ToroidParams {
    let r = ToroidParams::REFERENCE;
    let k = request.r0 / r.outer_radius;
    ToroidParams {
        sides: n,
        outer_tread: k * r.outer_tread,
        inner_tread: k * r.inner_tread,
        offset: k * r.offset,
        outer_radius: k * r.outer_radius,
        inner_radius: k * r.inner_radius,
        rim_radius: k * r.rim_radius,
    }
}

/// The toroid column's wheel: the scaled reference toroid with spokes and inner rings.
fn toroid_wheel(request: &TbarRollRequest, n: usize) -> WheelSpec {
    WheelSpec {
        params: toroid_params(request, n),
        stabilize: Stabilize::SPOKES_INNER,
        bar_density: request.bar_density,
        scale_with_n: false,
    }
}

/// The toroid's full-model request in the settings of `request` (n sides). The toroid's
/// model takes μ_k = 0.75 μ_s: a different `mu_kinetic` applies to the T-bar only, and the
/// toroid column is refused.
pub fn toroid_request(
    request: &TbarRollRequest,
    n: usize,
) -> Result<RollRequest, InvalidParameter> {
    let ratio = request.mu_kinetic() / request.mu_static.max(f64::MIN_POSITIVE);
    if request.mu_kinetic.is_some() && (ratio - defaults::KINETIC_FRICTION_RATIO).abs() > 1e-12 {
        return Err(InvalidParameter::new(
            "mu_kinetic",
            request.mu_kinetic(),
            format!(
                "the toroid's full model takes μ_k = {} μ_s; mu_kinetic applies to the T-bar only",
                defaults::KINETIC_FRICTION_RATIO
            ),
        ));
    }
    Ok(RollRequest {
        fidelity: match request.fidelity {
            FidelityChoice::Auto => FidelityChoice::Auto,
            _ => FidelityChoice::Full,
        },
        min_tension: request.min_tension.unwrap_or(defaults::ROLL_MIN_TENSION),
        ..rigid_toroid_request(request, n)
    })
}

/// The toroid column of the row of `n` treads.
fn toroid_column(
    request: &TbarRollRequest,
    n: usize,
) -> Result<WheelRun, Box<dyn std::error::Error>> {
    match request.fidelity {
        FidelityChoice::Rigid => {
            let t = toroid_wheel(request, n).build()?;
            let a = toroid::analyse(&t)?;
            let wheel = ToroidWheel {
                toroid: &t,
                analysis: &a,
                string_stiffness: request.settings.string_stiffness,
                min_tension: defaults::ROLL_MIN_TENSION,
            };
            Ok(request.rigid_run(&wheel.polygon())?)
        }
        FidelityChoice::Full | FidelityChoice::Auto => {
            let r = toroid::roll(&toroid_request(request, n)?)?;
            let polygon = Polygon {
                sides: n,
                outer_radius: request.r0,
                mass: r.mass_kg,
                i1: r.i1,
            };
            Ok(WheelRun {
                model: r.fidelity,
                fidelity_reason: r.fidelity_reason,
                mass_kg: r.mass_kg,
                i1: r.i1,
                impact_ratio: polygon.impact_ratio(),
                summary: r.summary,
            })
        }
    }
}

/// The resource estimate of `tbar roll`, the runs of every row one after the other: for
/// the rigid model the toroid column's statics and rigid run ([`toroid::budget::roll`] of
/// the rigid model) and the T-bar's rigid run of the same size (its steps and samples grow
/// with `t_end`, the statics with the treads); for the full model the T-bar's and the
/// toroid's full runs; each again at half the step with `convergence_check` (the refined
/// companion and its twin: the check's cost where no coarse companion serves; a coarse one
/// costs ⅛ or ¼ run (rigid), ¼ to 1 (full), [`wheel_rolling::convergence`], so the estimate
/// stays an upper bound of the usual case). The T-bar's
/// refined run runs beside its run, on a thread of its own
/// ([`wheel_rolling::roll_checked`]): on two cores or more the pair takes the time of the
/// longer, refined run, not the sum ([`checked_pair`]). Named
/// `treads = [..], t_end = .., dt = ..`. [`estimate_on`] with this machine's cores.
///
/// ```
/// use tbar_wheel::TbarRollRequest;
/// use tensegrity_core::budget::Limits;
/// use tensegrity_engine::tbar_roll::estimate;
/// let r = TbarRollRequest { t_end: Some(1e9), ..Default::default() };
/// let e = estimate(&r).unwrap().unwrap();
/// assert!(Limits::default().check(&e).is_err());
/// assert!(e.parameters.to_string().contains("t_end = 1000000000"));
/// ```
pub fn estimate(request: &TbarRollRequest) -> Result<Option<Estimate>, TbarError> {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    estimate_on(request, cores)
}

/// A full run beside the refined and the twin runs of its convergence check, counted as
/// running at once (three threads; [`wheel_rolling::roll_checked`] runs the companion beside
/// the run and the twin only where needed, after them): memory and output add; the wall
/// time is that of the three on at most two cores, the sum on one
/// ([`wheel_rolling::estimate::parallel`]).
///
/// Measured (release, a shared 2-core machine at load 3.4): `tbar roll --extended 0.5
/// --fidelity full` took 20.5 s of CPU and 28.5 s of wall time (7.1 s of CPU and 10.9 s of
/// wall time without the check), against 64.4 s estimated as the sum and 43.7 s as the pair.
pub fn checked_pair(run: Estimate, refined: Estimate, cores: usize) -> Estimate {
    let what = format!("{}, beside it {} and the twin run", run.what, refined.what);
    let workers = cores.clamp(1, 2);
    // the check's twin (the run again from a start turned by 1e-6 rad) runs on a third thread
    match wheel_rolling::estimate::parallel(&[run.clone(), refined, run.clone()], workers, what) {
        Some(pair) => pair,
        None => run,
    }
}

/// [`estimate`] on a machine of `cores` cores.
pub fn estimate_on(request: &TbarRollRequest, cores: usize) -> Result<Option<Estimate>, TbarError> {
    let rim = request.rim()?;
    let (t_end, dt) = (request.t_end(), request.spec(request.fidelity).full_dt());
    let mut total: Option<Estimate> = None;
    for n in request.treads() {
        let e = match request.fidelity {
            FidelityChoice::Rigid => {
                let toroid = toroid::budget::roll(&rigid_toroid_request(request, n));
                toroid.clone().then(toroid)
            }
            FidelityChoice::Full | FidelityChoice::Auto => {
                let p = request.tbar_params(n, rim);
                let mut e = tbar_wheel::rolling_full::full_roll_estimate(&p, t_end, dt)?;
                if request.checks.convergence_check {
                    let fine = tbar_wheel::rolling_full::full_roll_estimate(&p, t_end, dt / 2.0)?;
                    e = checked_pair(e, fine, cores);
                }
                if let Ok(req) = toroid_request(request, n) {
                    e = e.then(toroid::budget::roll(&req));
                }
                e
            }
        };
        total = Some(match total {
            Some(t) => t.then(e),
            None => e,
        });
    }
    let treads = request.treads();
    let largest = treads.iter().copied().max().unwrap_or_default();
    Ok(total.map(|e| Estimate {
        what: format!(
            "the {} rolling runs of n = {treads:?}",
            match request.fidelity {
                FidelityChoice::Rigid => "rigid",
                FidelityChoice::Full => "full",
                FidelityChoice::Auto => "auto (rigid, then full)",
            }
        ),
        parameters: format!("treads = {largest}, t_end = {t_end}, dt = {dt}")
            .as_str()
            .into(),
        ..e
    }))
}

/// The toroid's rigid-model request of the row of `n` treads (the estimate's, and the base
/// of the full model's [`toroid_request`]).
fn rigid_toroid_request(request: &TbarRollRequest, n: usize) -> RollRequest {
    RollRequest {
        wheel: toroid_wheel(request, n),
        settings: request.settings,
        t_end: request.t_end(),
        fidelity: FidelityChoice::Rigid,
        contact: request.contact,
        mu: request.mu_static,
        min_tension: defaults::ROLL_MIN_TENSION,
        integrator: tensegrity_dynamics::IntegratorKind::Rk4,
        checks: tensegrity_core::request::RunChecks {
            strict: false,
            ..request.checks
        },
        ensemble: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_compare_the_two_wheels_and_report_the_tipover() {
        // moved from the CLI: `tbar roll --beta pi/6 --cylindrical 0.25 --extended 0.4
        // --treads 8,12 --t-end 2`
        let r = tbar_roll(&TbarRollRequest {
            extended: Some(0.4),
            treads: Some(vec![8, 12]),
            t_end: Some(2.0),
            ..TbarRollRequest::default()
        })
        .unwrap();
        assert_eq!(
            (r.model, r.full_tensegrity_rolling),
            (Fidelity::Rigid, false)
        );
        assert_eq!(r.rows.len(), 2);
        for row in &r.rows {
            assert!(row.errors.is_empty(), "{:?}", row.errors);
            let (t, o) = (row.tbar.as_ref().unwrap(), row.toroid.as_ref().unwrap());
            // both roll down 30° > π/n and bump: more treads, smaller oscillation
            assert!(t.summary.impacts > 0 && o.summary.impacts > 0);
            let tip = row.tipover.as_ref().unwrap();
            let mg = row.mass_properties.unwrap().mass * 9.81;
            assert!((tip.critical_lateral_force - 0.5 * mg * 0.4).abs() < 1e-12);
        }
        let osc = |i: usize| {
            r.rows[i]
                .tbar
                .as_ref()
                .unwrap()
                .summary
                .axle_height_oscillation
        };
        assert!(osc(1) < osc(0));
        // the toroid column is `toroid::roll` with the rigid fidelity (the reference wheel,
        // R_o = 1)
        let base = RollRequest::with_sides(8);
        let direct = toroid::roll(&RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 2.0,
            settings: wheel_rolling::RollSettings {
                incline: tbar_wheel::roll::DEFAULT_INCLINE_DEG.to_radians(),
                ground_stiffness: tbar_wheel::roll::DEFAULT_GROUND_STIFFNESS,
                ..base.settings
            },
            ..base
        })
        .unwrap();
        let ours = r.rows[0].toroid.as_ref().unwrap();
        assert_eq!((ours.mass_kg, ours.i1), (direct.mass_kg, direct.i1));
        assert_eq!(ours.summary, direct.summary);
        let j = serde_json::to_value(&r).unwrap();
        assert_eq!((&j["model"], &j["rim"]), (&"rigid".into(), &"fixed".into()));
        for key in [
            "valid",
            "warnings",
            "min_normal_force",
            "airborne_fraction",
            "model",
            "I1",
        ] {
            assert!(j["rows"][0]["tbar"].get(key).is_some(), "{key}");
            assert!(j["rows"][0]["toroid"].get(key).is_some(), "{key}");
        }
    }

    #[test]
    fn a_kinetic_friction_the_toroid_cannot_take_fails_its_column_only() {
        let req = TbarRollRequest {
            mu_kinetic: Some(0.3),
            ..TbarRollRequest::default()
        };
        let e = toroid_request(&req, 8).unwrap_err();
        assert_eq!(e.name, "mu_kinetic");
        assert!(!e.to_string().contains("--"), "{e}");
        // 0.75 μ_s given explicitly is the toroid's own
        let same = TbarRollRequest {
            mu_kinetic: Some(0.75 * 0.8),
            ..TbarRollRequest::default()
        };
        assert!(toroid_request(&same, 8).is_ok());
    }

    #[test]
    fn the_full_estimate_counts_both_wheels_of_every_row() {
        let full = TbarRollRequest {
            fidelity: FidelityChoice::Full,
            treads: Some(vec![6, 8]),
            ..TbarRollRequest::default()
        };
        // on one core the convergence check's refined run (half the step) and its twin (the
        // run again, from a start turned by 1e-6 rad) add their time
        let e = estimate_on(&full, 1).unwrap().unwrap();
        let runs = |n: usize| {
            let p = full.tbar_params(n, tbar_wheel::RimMode::Body);
            let t = tbar_wheel::rolling_full::full_roll_estimate(&p, 1.0, 1e-4).unwrap();
            let fine = tbar_wheel::rolling_full::full_roll_estimate(&p, 1.0, 5e-5).unwrap();
            let toroid = toroid::budget::roll(&toroid_request(&full, n).unwrap());
            (t.work_s, fine.work_s, toroid.work_s)
        };
        let one = |n: usize| {
            let (t, fine, toroid) = runs(n);
            2.0 * t + fine + toroid
        };
        assert!((e.work_s - one(6) - one(8)).abs() < 1e-9 * e.work_s);
        // on two cores they run beside the run: the three share the two cores, at least the
        // refined run's time
        let two = estimate_on(&full, 2).unwrap().unwrap();
        let pair = |n: usize| {
            let (t, fine, toroid) = runs(n);
            assert!(fine > t);
            (0.5 * (2.0 * t + fine)).max(fine) + toroid
        };
        assert!((two.work_s - pair(6) - pair(8)).abs() < 1e-9 * two.work_s);
        // the two are held at once on any number of cores: their memory adds
        assert_eq!(two.memory_bytes, e.memory_bytes);
        let p = full.tbar_params(8, tbar_wheel::RimMode::Body);
        let run = tbar_wheel::rolling_full::full_roll_estimate(&p, 1.0, 1e-4).unwrap();
        let fine = tbar_wheel::rolling_full::full_roll_estimate(&p, 1.0, 5e-5).unwrap();
        assert!(e.memory_bytes >= 2.0 * run.memory_bytes + fine.memory_bytes);
        assert!(!e.parameters.to_string().contains("--"), "{}", e.parameters);
        assert!(estimate(&TbarRollRequest::default()).unwrap().is_some());
    }

    /// `tbar roll --extended 0.5 --fidelity full` (issue 42): refused at the default
    /// `--max-work` when its refined run was counted after its run (64.4 s estimated, 20.5 s
    /// of CPU measured, release), admitted as the pair that runs at once on two cores.
    #[test]
    fn the_default_full_extended_roll_fits_the_default_work_limit() {
        let r = TbarRollRequest {
            fidelity: FidelityChoice::Full,
            extended: Some(0.5),
            ..TbarRollRequest::default()
        };
        let limit = tensegrity_core::budget::DEFAULT_MAX_WORK_S;
        let one = estimate_on(&r, 1).unwrap().unwrap().work_s;
        let two = estimate_on(&r, 2).unwrap().unwrap().work_s;
        // the run, its refined run and its twin (since 2026-12-06), then the toroid's
        assert!(one > limit && (one - 85.9).abs() < 0.5, "{one}");
        assert!(two < limit && (two - 44.5).abs() < 0.5, "{two}");
        // still above what it measured: 20.5 s of CPU, 28.5 s of wall time on a loaded machine
        assert!(two > 28.5);
    }
}
