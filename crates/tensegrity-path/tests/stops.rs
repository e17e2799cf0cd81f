//! A path that cannot go on keeps its points and says why (`Stop::StepTooSmall`, naming the
//! load factor), never an error that loses them, never NaN; and strings that slacken into a
//! mechanism do not stop it.

use crate::common;
use nalgebra::Vector3;
use tensegrity_path::model::Drivers;

use common::assert_finite;
use tensegrity_path::point::{Event, Stop};
use tensegrity_path::{follow, ElasticMember, ElasticModel, MemberKind, PathSettings, Support};

/// The two-bar truss of examples/von_mises.toml (supports at x = ±1, the apex at y = 0.5,
/// EA = 10⁷ Pa × π (0.01 m)², 100 N down on the apex; the apex moves along y), beside a
/// string between two anchors 1 m apart whose rest length is driven to 10 + 20 λ m: slack
/// for λ > −0.45, it carries nothing to the truss, but its rest length reaches zero at
/// λ = −1/2. The truss snaps through: λ rises to its fold at 1.2059, falls through zero (the
/// bars flat) towards the second fold at −1.2059 — and no load factor below −1/2 is
/// admissible, so the path cannot reach its target 2 and stops on the way down, just above
/// −1/2.
fn truss_with_a_driven_string() -> ElasticModel {
    let ea = 1e7 * std::f64::consts::PI * 1e-4;
    let bar = |nodes| ElasticMember {
        nodes,
        kind: MemberKind::Bar,
        ea,
        rest_length: 1.25f64.sqrt(),
    };
    ElasticModel {
        nodes: vec![
            Vector3::new(-1.0, 0.0, 0.0),
            Vector3::new(0.0, 0.5, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 0.0, 5.0),
            Vector3::new(0.0, 0.0, 6.0),
        ],
        members: vec![
            bar([0, 1]),
            bar([1, 2]),
            ElasticMember {
                nodes: [3, 4],
                kind: MemberKind::String,
                ea: 1e3,
                rest_length: 10.0,
            },
        ],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support::along(1, vec![Vector3::x(), Vector3::z()]),
            Support::pinned(2),
            Support::pinned(3),
            Support::pinned(4),
        ],
        load: vec![
            Vector3::zeros(),
            Vector3::new(0.0, -100.0, 0.0),
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::zeros(),
        ],
        drivers: Drivers {
            rest_length_changes: vec![0.0, 0.0, 20.0],
            displacements: vec![],
            dead_load: vec![],
            ..Default::default()
        },
    }
}

#[test]
fn a_path_that_cannot_go_on_keeps_its_points_and_names_the_load_factor() {
    let path = follow(
        &truss_with_a_driven_string(),
        &PathSettings {
            target: 2.0,
            ..PathSettings::default()
        },
    )
    .unwrap();
    let Stop::StepTooSmall { message } = &path.stop else {
        panic!("{:?}", path.stop)
    };
    assert!(
        message.contains("load factor") && message.contains("member 2"),
        "{message}"
    );
    // the points up to there: past the first fold, the bars flat at λ = 0 on the way down
    let folds: Vec<f64> = path
        .events
        .iter()
        .filter_map(|e| match e {
            Event::LimitPoint { lambda, .. } => Some(*lambda),
            _ => None,
        })
        .collect();
    assert_eq!(folds.len(), 1, "{:?}", path.events);
    assert!((folds[0] - 1.2059).abs() < 1e-3, "{}", folds[0]);
    for p in &path.points {
        assert_finite(p);
    }
    let last = path.points.last().unwrap();
    assert!(last.nodes[1][1] < 0.0, "{:?}", last.nodes[1]);
    assert!(
        last.lambda > -0.5 && last.lambda < -0.5 + 1e-6,
        "{}",
        last.lambda
    );
}

/// Two prestressed strings in series along z: a support at z = 0, node 1 at z = 1 (free along
/// z only), a support at z = 2; rest lengths 0.9 m (tension EA/9 each), driven to
/// 0.9 + 0.2 λ (string 0, below) and 0.9 + 0.1 λ (string 1, above). Node 1 balances the two
/// tensions, so they are equal all the way and vanish together where both strings are at
/// their rest lengths, L₀,₀ + L₀,₁ = 2: λ* = 2/3. Past it node 1 is free between the two
/// strings' reach (a continuum of unloaded equilibria, the tangent singular with both slack).
fn strings() -> ElasticModel {
    let string = |nodes| ElasticMember {
        nodes,
        kind: MemberKind::String,
        ea: 900.0,
        rest_length: 0.9,
    };
    ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::z(), Vector3::new(0.0, 0.0, 2.0)],
        members: vec![string([0, 1]), string([1, 2])],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support::along(1, vec![Vector3::x(), Vector3::y()]),
            Support::pinned(2),
        ],
        load: vec![Vector3::zeros(); 3],
        drivers: Drivers {
            rest_length_changes: vec![0.2, 0.1],
            displacements: vec![],
            dead_load: vec![],
            ..Default::default()
        },
    }
}

#[test]
fn strings_that_slacken_together_into_a_mechanism_leave_the_path_on_an_edge() {
    let lambda_star = 2.0 / 3.0;
    let path = follow(&strings(), &PathSettings::default()).unwrap();
    assert_eq!(path.stop, Stop::ReachedTarget);
    // both slacken at λ*, exactly; one takes the node on at zero force (an edge of the
    // continuum: the node where that string is at its rest length)
    let Some(Event::Slackened {
        members, lambda, ..
    }) = path.events.first()
    else {
        panic!("{:?}", path.events)
    };
    assert_eq!(members, &vec![0, 1]);
    assert!((lambda - lambda_star).abs() < 1e-12, "{lambda}");
    for p in &path.points {
        assert_finite(p);
        let (l0a, l0b) = (0.9 + 0.2 * p.lambda, 0.9 + 0.1 * p.lambda);
        let z = p.nodes[1][2];
        if p.lambda < lambda_star {
            // EA (z − a)/a = EA (2 − z − b)/b → z = 2a/(a + b), one tension
            let expected = 2.0 * l0a / (l0a + l0b);
            assert!((z - expected).abs() < 1e-9, "λ {}", p.lambda);
            let t = 900.0 * (z - l0a) / l0a;
            assert!((p.tensions[0] - t).abs() < 1e-7 && (p.tensions[1] - t).abs() < 1e-7);
            assert!(p.slack.is_empty());
        } else {
            assert!(
                (z - l0a).abs() < 1e-9 || (2.0 - z - l0b).abs() < 1e-9,
                "λ {}: {z}",
                p.lambda
            );
            assert!(
                p.tensions.iter().all(|t| t.abs() < 1e-9),
                "{:?}",
                p.tensions
            );
        }
    }
}

/// A path given a work limit stops there with `Stop::WorkLimit`, its points kept and each an
/// equilibrium on the two-bar truss's path (λ growing past both folds on the inverted truss
/// toward a target it cannot reach in the time); a limit that is not positive is refused.
#[test]
fn a_path_out_of_time_keeps_its_points() {
    let mut truss = truss_with_a_driven_string();
    truss.members.truncate(2);
    truss.drivers = Drivers::default();
    let limited = PathSettings {
        target: 1e6,
        max_steps: usize::MAX,
        max_seconds: Some(0.02),
        ..PathSettings::default()
    };
    let path = follow(&truss, &limited).unwrap();
    assert_eq!(path.stop, Stop::WorkLimit { seconds: 0.02 });
    assert!(path.points.len() > 10, "{}", path.points.len());
    for p in &path.points {
        assert_finite(p);
        // Newton's tolerance is relative to the load, 100 |λ| N
        let load = 100.0 * p.lambda.abs().max(1.0);
        assert!(p.residual < 1e-8 * load, "step {}: {}", p.step, p.residual);
    }
    let last = path.points.last().unwrap().lambda;
    assert!(last > 1.2 && last < 1e6, "{last}");
    for bad in [0.0, -1.0, f64::NAN] {
        let e = follow(
            &truss,
            &PathSettings {
                max_seconds: Some(bad),
                ..PathSettings::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("max_seconds"), "{e}");
    }
}
