//! The convergence check of `roll` ([`wheel_rolling::convergence`]): what it reports as
//! converged holds when the run is refined further, what moved is flagged, and the check can
//! be skipped.

use toroid::{roll_observed, FidelityChoice, RollRequest};
use wheel_rolling::{RollSettings, RunChecks};

fn full(t_end: f64) -> RollRequest {
    RollRequest {
        fidelity: FidelityChoice::Full,
        t_end,
        ..RollRequest::default()
    }
}

/// The report's value of a headline quantity by its key.
fn value(json: &serde_json::Value, key: &str) -> Option<f64> {
    key.split('.')
        .try_fold(json, |v, k| v.get(k))
        .and_then(serde_json::Value::as_f64)
}

/// `roll --sides 8 --fidelity full --t-end 3` (IMEX-ARK, the full model's default): every
/// quantity reported converged changes by less than its stated tolerance when the run is
/// repeated at a quarter of the step (the check's rule, the change at 2 dt within τ, bounds
/// the change to any finer run by τ for a first-order or better method); the
/// quantities a start turned by 10⁻⁶ rad moves by more than τ/8 are chaotic, single draws
/// without a warning, each with an interval that holds the quarter step's value; the others,
/// unconverged, make the run invalid. On this run the first
/// impact converges and the hops after it are chaotic, so the run is valid.
#[test]
fn what_is_reported_converged_holds_at_a_quarter_of_the_step() {
    use tensegrity_dynamics::convergence::{Companion, Status};
    let base = full(3.0);
    let r = roll_observed(&base, &[], None).unwrap();
    let c = r.summary.convergence.clone().expect("checked by default");
    // 2 × 2.5e-4 s is past IMEX-ARK's default step (the longest measured to be accurate):
    // a refined companion from the twin's start; the hops moved by more than τ/8, so the twin
    // ran at dt: cost 2 + 1
    println!("{}: {}", c.refinement, c.cost);
    assert_eq!(
        c.refinement,
        "dt/2 (the ground's stiffness is the model's) (refined companion: the full model's 2 dt, 5.000e-4 s, exceeds its default step 2.500e-4 s under imex-ark, the longest measured to be accurate), from a start turned by 1e-6 rad; twin at dt"
    );
    assert_eq!(
        (c.companion, c.order, c.cost),
        (Companion::Refined, 1.0, 3.0)
    );
    assert_eq!(c.quantities.len(), 9);
    // the verdict and the warnings agree; chaotic quantities are not warnings
    let status = |s: Status| c.quantities.iter().filter(|q| q.status == s).count();
    assert_eq!(c.converged, status(Status::NotConverged) == 0);
    let flagged = r
        .summary
        .warnings
        .iter()
        .filter(|w| w.kind() == "not_converged")
        .count();
    assert_eq!(
        status(Status::NotConverged),
        flagged,
        "{:?}",
        r.summary.warnings
    );
    assert!(status(Status::Chaotic) >= 3, "the hops are chaotic: {c:?}");
    for q in c.quantities.iter().filter(|q| q.status == Status::Chaotic) {
        assert!(
            q.twin_change.unwrap() > q.tolerance / 8.0 && !q.converged,
            "{q:?}"
        );
    }
    assert!(r.summary.valid, "{:?}", r.summary.warnings);
    for name in ["first_impact.t", "first_impact.omega_before"] {
        let q = c.quantities.iter().find(|q| q.name == name).unwrap();
        assert_eq!(q.status, Status::Converged, "{q:?}");
    }
    let quarter = roll_observed(
        &RollRequest {
            settings: RollSettings {
                dt: Some(base.spec().full_dt() / 4.0),
                ..base.settings
            },
            checks: RunChecks::NONE,
            ..base
        },
        &[],
        None,
    )
    .unwrap();
    let (a, b) = (
        serde_json::to_value(&r).unwrap(),
        serde_json::to_value(&quarter).unwrap(),
    );
    let mut checked = 0;
    for q in c.quantities.iter().filter(|q| q.converged) {
        let (x, y) = (value(&a, &q.name), value(&b, &q.name));
        assert_eq!(x, q.value, "{}", q.name);
        let (Some(x), Some(y)) = (x, y) else {
            assert_eq!(x.is_some(), y.is_some(), "{}", q.name);
            continue;
        };
        let scale = match q.name.as_str() {
            "impacts" | "airborne_fraction" | "slip_fraction" => 1.0,
            _ => 1e-3,
        };
        let change = (y - x).abs() / x.abs().max(y.abs()).max(scale);
        assert!(
            change < q.tolerance,
            "{}: {x} at dt, {y} at dt/4: {change} ≥ {}",
            q.name,
            q.tolerance
        );
        checked += 1;
    }
    assert!(checked >= 2, "{c:?}");
    // a chaotic quantity's 95 % interval (from the run, the refined run and the twin) holds
    // the quarter step's value, another draw with a smaller bias
    for q in c.quantities.iter().filter(|q| q.status == Status::Chaotic) {
        let [lo, hi] = q.interval.expect("three draws");
        let y = value(&b, &q.name).unwrap();
        assert!(lo <= y && y <= hi, "{}: {y} outside [{lo}, {hi}]", q.name);
    }
}

/// `convergence_check = false` runs once and reports no convergence; the rigid model's
/// events are located to round-off, so its headline quantities hold at 8 dt.
#[test]
fn the_check_can_be_skipped_and_the_rigid_model_converges() {
    let skipped = roll_observed(
        &RollRequest {
            checks: RunChecks::NONE,
            ..full(0.3)
        },
        &[],
        None,
    )
    .unwrap();
    assert!(skipped.summary.convergence.is_none());
    let json = serde_json::to_value(&skipped).unwrap();
    assert!(json["convergence"].is_null());
    let rigid = roll_observed(
        &RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 3.0,
            ..RollRequest::default()
        },
        &[],
        None,
    )
    .unwrap();
    let c = rigid.summary.convergence.expect("checked");
    assert!(
        c.refinement.starts_with("8 dt (coarse companion)"),
        "{}",
        c.refinement
    );
    assert!(c.converged, "{c:?}");
    assert!(rigid.summary.valid, "{:?}", rigid.summary.warnings);
}

/// `strict`: an invalid result is an error naming its warnings (the thesis contact sinks).
#[test]
fn strict_makes_an_invalid_run_an_error() {
    let thesis = RollRequest {
        contact: toroid::ContactKind::Thesis,
        checks: RunChecks {
            strict: true,
            convergence_check: false,
        },
        ..full(1.5)
    };
    let e = toroid::roll(&thesis).unwrap_err();
    assert!(e.to_string().starts_with("strict: "), "{e}");
    assert!(e.to_string().contains("sank"), "{e}");
    // the same run without strict is a report, flagged
    let r = toroid::roll(&RollRequest {
        checks: RunChecks::NONE,
        ..thesis
    })
    .unwrap();
    assert!(!r.summary.valid);
}

/// `ensemble = K`: K perturbed copies, each headline quantity's mean and interval, against
/// one run of the other model; the copies of a rigid pivot from rest agree on the first
/// impact to far better than the models do.
#[test]
fn an_ensemble_reports_every_headline_quantity_against_the_other_model() {
    let r = roll_observed(
        &RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 1.0,
            ensemble: 4,
            checks: RunChecks::NONE,
            ..RollRequest::default()
        },
        &[],
        None,
    )
    .unwrap();
    let e = r.ensemble.expect("K = 4");
    assert_eq!((e.members, e.quantities.len()), (4, 9));
    let first = e
        .quantities
        .iter()
        .find(|q| q.name == "first_impact.t")
        .unwrap();
    let t = r.summary.first_impact.unwrap().t;
    assert!(
        first.low <= t + 1e-9 && t - 1e-9 <= first.high,
        "{first:?} vs {t}"
    );
    assert!(first.high - first.low < 1e-3, "{first:?}");
    // the other model (full) runs once: its first impact is a different number
    let other = first.other_model.expect("the full model ran");
    assert!((other - t).abs() > first.high - first.low);
    assert_eq!(first.spread_exceeds_model_difference, Some(false));
}

/// The split IMEX's creep bias survives halving its own step, so its refined run is IMEX-ARK
/// at half the step: on the n = 24 wheel (50°, 3 s, 2.5e-4 s) the split slips 0.86 of the run
/// and IMEX-ARK 0.65, which the check reports as not converged (the run not valid) instead of
/// a bias confirmed by the same method at half the step.
#[test]
fn a_split_imex_run_is_checked_against_imex_ark() {
    use tensegrity_dynamics::{convergence::Status, IntegratorKind};
    let mut request = full(3.0);
    request.wheel.params.sides = 24;
    request.integrator = IntegratorKind::Imex;
    request.settings.dt = Some(2.5e-4);
    let r = roll_observed(&request, &[], None).unwrap();
    let c = r.summary.convergence.clone().unwrap();
    assert!(c.refinement.contains("imex-ark"), "{}", c.refinement);
    let slip = c
        .quantities
        .iter()
        .find(|q| q.name == "slip_fraction")
        .unwrap();
    assert_eq!(slip.status, Status::NotConverged, "{slip:?}");
    assert!(
        slip.value.unwrap() - slip.refined.unwrap() > 0.1,
        "{slip:?}"
    );
    assert!(!r.summary.valid);
}

/// The coarse companion's error estimate and the refined one's are two estimates of the same
/// error: on 1 s of the full default wheel (IMEX-ARK) at half its default step, 1.25·10⁻⁴ s
/// (where 2 dt is the default, so the coarse companion serves: a full run at its default step
/// keeps the refined one), e = r at 2 dt and e = 2 r at dt/2 (order 1) of the first impact's
/// spin ω⁻ and of the mean speed agree within a factor of 3 (measured 2.8·10⁻³ against
/// 2.0·10⁻³, and 1.1·10⁻³ against 6.6·10⁻⁴), and both are measurable (far above the 10⁻⁶
/// of the twin's start).
#[test]
fn the_coarse_and_the_refined_estimates_of_the_error_agree() {
    use tensegrity_dynamics::convergence::Companion;
    let base = RollRequest {
        checks: RunChecks::NONE,
        ..full(1.0)
    };
    let dt = 0.5 * base.spec().full_dt();
    assert!(wheel_rolling::convergence::coarse_refused(
        &RollRequest {
            settings: RollSettings {
                dt: Some(dt),
                ..base.settings
            },
            ..base
        }
        .spec(),
        wheel_rolling::fidelity::Plan::Full,
        // (the polygon matters to the rigid model only)
        &wheel_rolling::Polygon {
            sides: 8,
            outer_radius: 1.0,
            mass: 12.0,
            i1: 7.5,
        },
    )
    .is_none());
    let at = |step: f64| {
        let r = roll_observed(
            &RollRequest {
                settings: RollSettings {
                    dt: Some(step),
                    ..base.settings
                },
                ..base
            },
            &[],
            None,
        )
        .unwrap();
        let i = r.summary.first_impact.expect("an impact within 1 s");
        [i.omega_before, r.summary.mean_speed]
    };
    let (run, coarse, fine) = (at(dt), at(2.0 * dt), at(0.5 * dt));
    for k in 0..2 {
        let rel = |a: f64, b: f64| (a - b).abs() / a.abs().max(b.abs());
        let (e_coarse, e_fine) = (rel(coarse[k], run[k]), 2.0 * rel(fine[k], run[k]));
        println!("quantity {k}: e at 2 dt {e_coarse:.3e}, at dt/2 {e_fine:.3e}");
        assert!(e_fine > 1e-5 && e_coarse > 1e-5, "{e_coarse} {e_fine}");
        let ratio = e_coarse / e_fine;
        assert!(
            (1.0 / 3.0..3.0).contains(&ratio),
            "{k}: {e_coarse} against {e_fine}"
        );
    }
    // at a quarter of the default step the full model's companion stays at 2 dt: at 4 dt
    // (the default step) the first impact's ω⁻ would be estimated 1.3·10⁻³ against 3.7·10⁻⁵
    // at dt/2 (module docs of `wheel_rolling::convergence`); at an eighth it is 4 dt (half
    // the default step), never 8 dt
    let octagon = wheel_rolling::Polygon {
        sides: 8,
        outer_radius: 1.0,
        mass: 12.0,
        i1: 7.5,
    };
    let quarter = RollRequest {
        settings: RollSettings {
            dt: Some(0.5 * dt),
            ..base.settings
        },
        ..base
    }
    .spec();
    let at = |c| {
        wheel_rolling::convergence::coarse_refused_at(
            &quarter,
            wheel_rolling::fidelity::Plan::Full,
            &octagon,
            c,
        )
    };
    assert!(at(Companion::Coarser)
        .unwrap()
        .contains("exceeds half its default step"));
    assert_eq!(at(Companion::Coarse), None);
    let eighth = RollRequest {
        settings: RollSettings {
            dt: Some(0.25 * dt),
            ..base.settings
        },
        ..base
    }
    .spec();
    let at = |c| {
        wheel_rolling::convergence::coarse_refused_at(
            &eighth,
            wheel_rolling::fidelity::Plan::Full,
            &octagon,
            c,
        )
    };
    assert!(at(Companion::Coarsest).unwrap().contains("at most 4 dt"));
    assert_eq!(at(Companion::Coarser), None);
}

/// The full model's coarse estimate decides only a quantity it puts within half its
/// tolerance (`wheel_rolling::convergence::FULL_COARSE_DECIDES`). On 1 s of the default
/// wheel at a quarter of its default step (6.25·10⁻⁵ s) the final speed moved 1.4 % at 2 dt
/// (within its 2 %), yet it is 2.7 % off a run at a sixteenth of the step: the order-1 rule
/// under-states it 1.9-fold there. That estimate is now checked again at dt/2, and the
/// final speed is not converged. At an eighth of the default step the companion is at 4 dt
/// (a quarter of the run's work), and every quantity it reports converged is within its
/// tolerance of the run at a sixteenth of the default step.
#[test]
fn the_full_models_coarse_estimate_decides_only_within_half_its_tolerance() {
    use tensegrity_dynamics::convergence::{Companion, Status};
    let base = full(1.0);
    let default = base.spec().full_dt();
    let at = |dt: f64, checks: RunChecks| {
        let request = RollRequest {
            settings: RollSettings {
                dt: Some(dt),
                ..base.settings
            },
            checks,
            ..base
        };
        roll_observed(&request, &[], None).unwrap().summary
    };
    let reference = serde_json::to_value(at(default / 16.0, RunChecks::NONE)).unwrap();
    let rel = |a: f64, b: f64, scale: f64| (a - b).abs() / a.abs().max(b.abs()).max(scale);
    let c = at(default / 4.0, RunChecks::default())
        .convergence
        .expect("checked");
    println!("{}: cost {}", c.refinement, c.cost);
    assert_eq!(c.companion, Companion::Refined);
    assert!(
        c.refinement
            .contains("run after the coarse check at 2 dt found final_speed"),
        "{}",
        c.refinement
    );
    let speed = c
        .quantities
        .iter()
        .find(|q| q.name == "final_speed")
        .unwrap();
    let error = rel(
        speed.value.unwrap(),
        value(&reference, "final_speed").unwrap(),
        speed.scale(),
    );
    println!("final speed {speed:?}, {error:.3e} off the reference");
    assert!(error > speed.tolerance, "{error}");
    assert_eq!(speed.status, Status::NotConverged);
    // the coarse check (2 dt, then the twin at 2 dt) and the refined one (dt/2, the twin at dt)
    assert_eq!(c.cost, 4.0);

    let c = at(default / 8.0, RunChecks::default())
        .convergence
        .expect("checked");
    println!("{}: cost {}", c.refinement, c.cost);
    assert_eq!(c.companion, Companion::Coarser);
    assert!(c.cost <= 0.5, "{}", c.cost);
    let mut converged = 0;
    for q in c
        .quantities
        .iter()
        .filter(|q| q.status == Status::Converged)
    {
        let off = rel(
            q.value.unwrap(),
            value(&reference, &q.name).unwrap(),
            q.scale(),
        );
        println!(
            "{}: estimated {:?}, {off:.3e} off",
            q.name, q.estimated_error
        );
        assert!(off <= q.tolerance, "{}: {off}", q.name);
        converged += 1;
    }
    assert!(converged >= 7, "{converged}");
}

/// Where every quantity moves by at most τ/8 against the coarse companion (started from the
/// twin's start), no twin runs: the check costs an eighth of a run (the rigid model's
/// companion is at 8 dt), no quantity has a twin change or an interval (null in the JSON),
/// and all are converged. The rigid n = 8 wheel for 1 s: one pivot and its first impacts,
/// the same at 8 dt and a start turned by 10⁻⁶ rad.
#[test]
fn a_converged_run_costs_an_eighth_of_a_run_and_runs_no_twin() {
    use tensegrity_dynamics::convergence::{Companion, Status};
    let r = roll_observed(
        &RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 1.0,
            ..RollRequest::default()
        },
        &[],
        None,
    )
    .unwrap();
    let c = r.summary.convergence.clone().expect("checked");
    println!("{c:#?}");
    assert_eq!((c.companion, c.cost), (Companion::Coarsest, 0.125), "{c:?}");
    assert!(c.refinement.contains("no twin"), "{}", c.refinement);
    assert!(c.converged && r.summary.valid, "{c:?}");
    for q in &c.quantities {
        assert_eq!(q.status, Status::Converged, "{q:?}");
        assert!(q.twin_change.is_none() && q.interval.is_none(), "{q:?}");
    }
    let json = serde_json::to_value(&c).unwrap();
    let q = &json["quantities"][0];
    assert!(q["twin_change"].is_null() && q["interval"].is_null(), "{q}");
    assert!(q.as_object().unwrap().contains_key("interval"), "{q}");
}

/// The default rigid roll (n = 8, 50°, 10 s) hops chaotically: the coarse companion moves some
/// quantity by more than τ/8, so the companion runs again at 8 dt from the run's own start,
/// the first one being the twin at 8 dt (cost ¼); the hops' impact count, mean axle height and
/// final speed are still classed chaotic (two of them at least: a single twin is one draw),
/// each with its interval, and the run is valid.
#[test]
fn the_twin_runs_and_tells_the_chaotic_hops_of_the_default_rigid_roll() {
    use tensegrity_dynamics::convergence::{Companion, Status};
    let r = roll_observed(
        &RollRequest {
            fidelity: FidelityChoice::Rigid,
            ..RollRequest::default()
        },
        &[],
        None,
    )
    .unwrap();
    let c = r.summary.convergence.clone().expect("checked");
    println!("{c:#?}");
    assert_eq!((c.companion, c.cost), (Companion::Coarsest, 0.25), "{c:?}");
    assert!(c.refinement.contains("twin at 8 dt"), "{}", c.refinement);
    assert!(
        c.quantities.iter().all(|q| q.twin_change.is_some()),
        "{c:?}"
    );
    let chaotic = ["impacts", "mean_axle_height", "final_speed"]
        .iter()
        .filter(|name| {
            let q = c.quantities.iter().find(|q| q.name == **name).unwrap();
            q.status == Status::Chaotic && q.interval.is_some()
        })
        .count();
    assert!(chaotic >= 2, "{c:?}");
    assert!(r.summary.valid, "{:?}", r.summary.warnings);
}

/// Where 2 dt would leave the integrator's stability the companion is refined, and the label
/// says why: RK4 on the penalty ground takes the ground's critical damper explicitly (its
/// rate 2c/m, 3.1·10⁴ 1/s, puts 2 dt = 10⁻⁴ s past the bound), so `roll --fidelity full
/// --integrator rk4 --dt 5e-5` is checked at dt/2 (cost 2 without a twin, 3 with it).
#[test]
fn a_companion_that_would_leave_the_stability_bound_is_refined() {
    use tensegrity_dynamics::{convergence::Companion, IntegratorKind};
    let mut request = full(0.3);
    request.integrator = IntegratorKind::Rk4;
    // half RK4's default step: 2 dt is the default, and the stability bound decides
    request.settings.dt = Some(5e-5);
    let r = roll_observed(&request, &[], None).unwrap();
    let c = r.summary.convergence.clone().expect("checked");
    println!("{} {}", c.refinement, c.cost);
    assert_eq!(c.companion, Companion::Refined);
    assert!(
        c.refinement.starts_with(
            "dt/2 (the ground's stiffness is the model's) (refined companion: 2 dt times λ"
        ),
        "{}",
        c.refinement
    );
    assert!(c
        .refinement
        .contains("exceeds 0.5 × rk4's stability bound 2.6"));
    assert!(c.cost == 2.0 || c.cost == 3.0, "{}", c.cost);
}

/// An observer that watches nothing and whose stop flag is set from the start (a Ctrl-C that
/// arrived while the run went on: the run reads its own interrupt through `keep_going`).
struct StopFlagSet;

/// The set flag of [`StopFlagSet`].
static STOP_SET: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(true);

impl wheel_rolling::Observer for StopFlagSet {
    fn stop_flag(&self) -> Option<&'static std::sync::atomic::AtomicBool> {
        Some(&STOP_SET)
    }
}

/// The companion runs stop once the run's observer's stop flag is set (a Ctrl-C during the
/// check stops it at the companion's next sample instead of after every run it would make):
/// the rigid roll of 3 s is whole, its 8 dt companion and the refined run after it stop at
/// their first sample, and the check is reported failed, with a warning. An ensemble's
/// copies stop too, and the ensemble is left out rather than drawn from copies cut short.
#[test]
fn a_stop_requested_during_the_check_stops_its_companion_runs() {
    let request = RollRequest {
        fidelity: FidelityChoice::Rigid,
        t_end: 3.0,
        ..RollRequest::default()
    };
    let r = roll_observed(&request, &[], Some(&mut StopFlagSet)).unwrap();
    assert_eq!(r.summary.stopped_at, None);
    assert!((r.samples.last().unwrap().t - 3.0).abs() < 1e-9);
    let c = r.summary.convergence.clone().expect("checked by default");
    assert!(!c.converged);
    assert!(
        c.refinement
            .contains("run after the coarse one at 8 dt: it stopped at t = ")
            && c.refinement
                .contains("the companion run failed: it stopped at t = "),
        "{}",
        c.refinement
    );
    assert!(!r.summary.valid);
    let with_ensemble = RollRequest {
        ensemble: 4,
        checks: RunChecks::NONE,
        ..request
    };
    let r = roll_observed(&with_ensemble, &[], Some(&mut StopFlagSet)).unwrap();
    assert_eq!(r.summary.stopped_at, None);
    assert!(r.ensemble.is_none());
    let whole = roll_observed(&with_ensemble, &[], None).unwrap();
    assert_eq!(whole.ensemble.expect("not stopped").members, 4);
}
