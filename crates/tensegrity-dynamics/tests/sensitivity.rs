//! Forward sensitivities of a trajectory (issue 47, item 4; `tensegrity_dynamics::sensitivity`)
//! against central differences of whole runs (Richardson-extrapolated) on two dynamic scenes:
//! the oscillating Snelson prism in free flight (every kind of parameter) and the prism
//! dropped onto the penalty ground (through its contact, whose events are reported); then the
//! system identification of the six-bar icosahedron's 24 string stiffnesses and 24 dampings
//! from a noisy trajectory (issue 47, item 5), each within 1 % and within four of its reported
//! standard errors; the bar-length drift of the unprojected steps, reported and warned past
//! `simulate`'s limit; the refusals.

use nalgebra::Vector3;
use tensegrity_core::warning::Warning;
use tensegrity_core::Structure;
use tensegrity_dynamics::identify::identify;
use tensegrity_dynamics::sensitivity::{forward_sensitivities, with_parameter, DynamicsParameter};
use tensegrity_dynamics::test_models::{
    dropped_prism, dropped_prism_ground, oscillating_prism, six_bar_identification,
};
use tensegrity_dynamics::Ground;

/// A deterministic spread in [−1, 1].
fn spread(i: usize) -> f64 {
    (0.7 + 1.37 * i as f64).sin()
}

/// `structure` with its bars given rigid initial velocities (each bar its own, both ends
/// alike: the bar lengths are kept).
fn with_velocities(structure: &Structure, speed: f64) -> Structure {
    let mut v = vec![Vector3::zeros(); structure.n_nodes()];
    for (k, b) in structure.bars().iter().enumerate() {
        let u = speed * Vector3::new(spread(3 * k), spread(3 * k + 1), spread(3 * k + 2));
        v[b.nodes[0]] = u;
        v[b.nodes[1]] = u;
    }
    structure
        .to_builder()
        .velocities(v.iter().map(|u| [u.x, u.y, u.z]))
        .build()
        .unwrap()
}

/// The final file-node positions of a run of `structure` moved by `h` along `p`.
fn final_nodes(
    structure: &Structure,
    ground: Option<Ground>,
    p: DynamicsParameter,
    h: f64,
    dt: f64,
    t_end: f64,
) -> Vec<Vector3<f64>> {
    let s = match p {
        DynamicsParameter::InitialPosition { bar, axis }
        | DynamicsParameter::InitialVelocity { bar, axis } => {
            let b = structure.bars()[bar].nodes;
            let mut nodes = structure.nodes().to_vec();
            let mut vel =
                structure
                    .velocities()
                    .map(|v| v.to_vec())
                    .unwrap_or(vec![Vector3::zeros(); nodes.len()]);
            for i in b {
                if matches!(p, DynamicsParameter::InitialPosition { .. }) {
                    nodes[i][axis] += h;
                } else {
                    vel[i][axis] += h;
                }
            }
            let s = structure.with_nodes(nodes).unwrap();
            s.to_builder()
                .velocities(vel.iter().map(|u| [u.x, u.y, u.z]))
                .build()
                .unwrap()
        }
        _ => {
            let v = tensegrity_dynamics::identify::parameter_value(structure, p).unwrap();
            with_parameter(structure, p, v + h).unwrap()
        }
    };
    let tr = forward_sensitivities(&s, ground, &[], dt, t_end, usize::MAX).unwrap();
    tr.nodes.last().unwrap().clone()
}

/// The Richardson-extrapolated central difference of the final nodes along `p`.
fn central(
    structure: &Structure,
    ground: Option<Ground>,
    p: DynamicsParameter,
    scale: f64,
    step: f64,
    dt: f64,
    t_end: f64,
) -> Vec<Vector3<f64>> {
    let d = |h: f64| -> Vec<Vector3<f64>> {
        let a = final_nodes(structure, ground.clone(), p, h, dt, t_end);
        let b = final_nodes(structure, ground.clone(), p, -h, dt, t_end);
        a.iter().zip(&b).map(|(a, b)| (a - b) / (2.0 * h)).collect()
    };
    let h = step * scale;
    let (d1, d2) = (d(h), d(h / 2.0));
    d1.iter()
        .zip(&d2)
        .map(|(a, b)| (4.0 * b - a) / 3.0)
        .collect()
}

fn relative(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.amax()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).amax())
        .fold(0.0, f64::max)
        / scale.max(f64::MIN_POSITIVE)
}

/// Every sensitivity of `structure`'s final nodes against central differences.
fn check(
    name: &str,
    structure: &Structure,
    ground: Option<Ground>,
    params: &[(DynamicsParameter, f64)],
    step: f64,
    dt: f64,
    t_end: f64,
) -> Vec<String> {
    let ps: Vec<DynamicsParameter> = params.iter().map(|(p, _)| *p).collect();
    let tr = forward_sensitivities(structure, ground.clone(), &ps, dt, t_end, usize::MAX).unwrap();
    let last = tr.node_sensitivities.last().unwrap();
    for (j, &(p, scale)) in params.iter().enumerate() {
        let fd = central(structure, ground.clone(), p, scale, step, dt, t_end);
        let e = relative(&last[j], &fd);
        println!("{name}: {p}: {e:.1e}");
        assert!(e < 1e-6, "{name}: {p}: {e:.2e}");
    }
    tr.events.iter().map(|e| e.what.clone()).collect()
}

#[test]
fn sensitivities_of_a_free_prism_match_central_differences() {
    let mut prism = oscillating_prism().unwrap();
    // damped strings, and the bars moving: every kind of parameter has an effect
    let mut strings = prism.strings().to_vec();
    for s in strings.iter_mut() {
        s.damping = 0.5;
    }
    prism = prism.with_members(prism.bars().to_vec(), strings).unwrap();
    let prism = with_velocities(&prism, 0.3);
    let params = [
        (DynamicsParameter::RestLength(6), 1.0),
        (DynamicsParameter::RestLength(0), 1.0),
        (DynamicsParameter::Stiffness(3), 1000.0),
        (DynamicsParameter::Damping(7), 1.0),
        (DynamicsParameter::BarMass(1), 1.0),
        (DynamicsParameter::InitialPosition { bar: 2, axis: 0 }, 1.0),
        (DynamicsParameter::InitialVelocity { bar: 0, axis: 2 }, 1.0),
    ];
    let events = check("free prism", &prism, None, &params, 1e-4, 1e-3, 0.5);
    assert!(events.is_empty(), "{events:?}");
}

#[test]
fn sensitivities_through_ground_contact_match_central_differences() {
    // dropped from 2 cm: the feet land at t ≈ 0.064 s and press into the penalty ground. The
    // ground without normal damping: its force k δ is continuous at touchdown (with damping
    // c it would jump by c times the impact speed, and the derivative of the landing with it:
    // the module docs)
    let prism = dropped_prism(0.02, 2.0).unwrap();
    let ground = dropped_prism_ground(1e5, 0.0);
    // the central differences by steps of 10⁻⁷ of each scale (a coarser one straddles the
    // instant a foot's stage crosses the ground); the damping's by 10⁻⁴ N s/m (its effect is
    // small: a finer step would round) and the mass by 10⁻⁶ kg
    let params = [
        (DynamicsParameter::Stiffness(6), 1000.0),
        (DynamicsParameter::Damping(2), 1000.0),
        (DynamicsParameter::BarMass(0), 10.0),
        (DynamicsParameter::RestLength(4), 1.0),
    ];
    let events = check(
        "dropped prism",
        &prism,
        Some(ground),
        &params,
        1e-7,
        2.5e-4,
        0.12,
    );
    assert!(
        events.iter().any(|e| e.contains("touches the ground")),
        "the contact is reported: {events:?}"
    );
}

#[test]
fn the_bar_length_drift_is_reported_and_warned_past_simulates_limit() {
    let prism = with_velocities(&oscillating_prism().unwrap(), 0.3);
    let params = [DynamicsParameter::Stiffness(3)];
    // the largest relative bar-length error of the samples, measured on the file nodes
    let sampled = |tr: &tensegrity_dynamics::sensitivity::TrajectorySensitivity| {
        let lengths = |x: &[Vector3<f64>]| -> Vec<f64> {
            prism
                .bars()
                .iter()
                .map(|b| (x[b.nodes[1]] - x[b.nodes[0]]).norm())
                .collect()
        };
        let l0 = lengths(&tr.nodes[0]);
        let shortest = l0.iter().copied().fold(f64::INFINITY, f64::min);
        tr.nodes
            .iter()
            .map(|x| {
                lengths(x)
                    .iter()
                    .zip(&l0)
                    .fold(0.0f64, |e, (l, l0)| e.max((l - l0).abs()))
            })
            .fold(0.0, f64::max)
            / shortest
    };
    // 1 ms steps: RK4's drift of the lengths stays far below simulate's limit of 1e-6
    let fine = forward_sensitivities(&prism, None, &params, 1e-3, 0.5, 1).unwrap();
    assert!(
        fine.bar_length_drift < 1e-8 && fine.warnings.is_empty(),
        "{}",
        fine.bar_length_drift
    );
    assert!(fine.bar_length_drift >= sampled(&fine));
    // 20 ms steps: the lengths drift past it, and the run says so
    let coarse = forward_sensitivities(&prism, None, &params, 2e-2, 0.5, 1).unwrap();
    assert!(
        coarse.bar_length_drift > 1e-6,
        "{}",
        coarse.bar_length_drift
    );
    assert!(
        coarse.bar_length_drift >= sampled(&coarse)
            && sampled(&coarse) > 0.5 * coarse.bar_length_drift
    );
    match coarse.warnings.as_slice() {
        [w @ Warning::Drift { value, limit, .. }] => {
            assert_eq!((*value, *limit), (coarse.bar_length_drift, 1e-6));
            assert!(w.to_string().contains("smaller `dt`"), "{w}");
        }
        w => panic!("{w:?}"),
    }
}

#[test]
fn string_stiffnesses_and_dampings_of_a_six_bar_are_identified_within_one_percent() {
    // every node every 2 ms over 0.4 s, with 20 µm of noise (test_models::six_bar_identification)
    let case = six_bar_identification(2e-5).unwrap();
    assert_eq!(case.parameters.len(), 48);
    let id = identify(
        &case.start,
        None,
        &case.parameters,
        &case.observed,
        &case.measured,
        &case.settings,
    )
    .unwrap();
    println!(
        "identified in {} iterations, rms {:.2e} → {:.2e} m (converged {})",
        id.iterations, id.rms_start, id.rms, id.converged
    );
    assert!(id.converged);
    // the residual is the noise
    assert!((id.rms / case.sigma - 1.0).abs() < 0.1, "{}", id.rms);
    let mut worst = 0.0f64;
    for (j, p) in case.parameters.iter().enumerate() {
        let (v, t) = (id.values[j], case.true_values[j]);
        let e = (v - t).abs() / t;
        worst = worst.max(e);
        assert!(
            e < 0.01,
            "{p}: identified {v}, true {t} ({:.2} %)",
            100.0 * e
        );
        // the reported standard error accounts for the error (within four of them)
        assert!((v - t).abs() < 4.0 * id.standard_errors[j], "{p}: {v} {t}");
    }
    println!("worst relative error {:.3} %", 100.0 * worst);
}

#[test]
fn bad_parameters_are_refused_naming_them() {
    let prism = oscillating_prism().unwrap();
    let e = forward_sensitivities(
        &prism,
        None,
        &[DynamicsParameter::Stiffness(99)],
        1e-3,
        0.01,
        1,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("string 99") && e.contains("past the last"),
        "{e}"
    );
    let e = forward_sensitivities(
        &prism,
        None,
        &[DynamicsParameter::InitialVelocity { bar: 0, axis: 3 }],
        1e-3,
        0.01,
        1,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("axis 3"), "{e}");
    // a D-bar's bars share nodes: moving one alone would break the joint
    let dbar = tensegrity_dynamics::test_models::dbar(1.0, 0.3, 1.0, 100.0, 0.01).unwrap();
    let e = forward_sensitivities(
        &dbar,
        None,
        &[DynamicsParameter::InitialPosition { bar: 0, axis: 0 }],
        1e-3,
        0.01,
        1,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("joined to another"), "{e}");
}
