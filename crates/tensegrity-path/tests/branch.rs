//! A simple (pitchfork) bifurcation and the switch onto its branch: a stiff bar standing on a
//! pinned base, its top held in the x–z plane by two prestressed horizontal strings to anchors
//! at x = ±1 (stiffness k, tension t₀), loaded down by λ P.
//!
//! On the straight path the top's lateral stiffness is 2k + t_bar/L' (the strings' axial
//! stiffness, the compressed bar's geometric one; L' its length, t_bar its force: the share
//! EA/(EA + 2 t₀) of λ P, the strings' geometric stiffness taking the rest as the top sinks),
//! so it bifurcates where λ P EA/(EA + 2 t₀) = 2 k L'. On the buckled branch, the bar (rigid to 10⁻⁶) leaning to x = sin θ, the
//! moment of the forces about the base vanishes: λ P x = Σ_s T_s (x_s-lever) — the closed form
//! `buckled_lambda` below, from the strings' stretch alone.

use nalgebra::Vector3;
use tensegrity_path::point::Event;
use tensegrity_path::stability::Stability;
use tensegrity_path::{follow, ElasticMember, ElasticModel, MemberKind, PathSettings, Support};

const K: f64 = 100.0;
const T0: f64 = 10.0;
const P: f64 = 100.0;
const EA_BAR: f64 = 1e9;

fn column() -> ElasticModel {
    let l0 = 1.0 - T0 / K; // the strings' rest length: tension t0 at length 1
    let string = |anchor| ElasticMember {
        nodes: [1, anchor],
        kind: MemberKind::String,
        ea: K * l0,
        rest_length: l0,
    };
    ElasticModel {
        nodes: vec![
            Vector3::zeros(),
            Vector3::z(),
            Vector3::new(-1.0, 0.0, 1.0),
            Vector3::new(1.0, 0.0, 1.0),
        ],
        members: vec![
            ElasticMember {
                nodes: [0, 1],
                kind: MemberKind::Bar,
                ea: EA_BAR,
                rest_length: 1.0,
            },
            string(2),
            string(3),
        ],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support {
                node: 1,
                directions: vec![Vector3::y()],
                stiffness: None,
            },
            Support::pinned(2),
            Support::pinned(3),
        ],
        load: vec![
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, -P),
            Vector3::zeros(),
            Vector3::zeros(),
        ],
        drivers: Default::default(),
    }
}

/// λ on the buckled branch with the top at (x, 0, z), a rigid bar of length 1: the forces'
/// component across the bar vanishes.
fn buckled_lambda(x: f64, z: f64) -> f64 {
    let l0 = 1.0 - T0 / K;
    let top = Vector3::new(x, 0.0, z);
    let across = Vector3::new(z, 0.0, -x); // normal to the bar in the plane
    let mut f = Vector3::zeros();
    for anchor in [Vector3::new(-1.0, 0.0, 1.0), Vector3::new(1.0, 0.0, 1.0)] {
        let d = anchor - top;
        let t = K * (d.norm() - l0); // EA (L − L0)/L0 with EA = k L0
        f += d / d.norm() * t.max(0.0);
    }
    // f·across − λ P (ẑ·across) = 0, ẑ·across = −x
    -f.dot(&across) / (P * x)
}

#[test]
fn the_path_bifurcates_at_the_closed_form_load_and_follows_the_buckled_branch() {
    let settings = PathSettings {
        target: 2.5,
        switch_branch: true,
        ..PathSettings::default()
    };
    let path = follow(&column(), &settings).unwrap();
    let (lambda_c, switched) = path
        .events
        .iter()
        .find_map(|e| match e {
            Event::Bifurcation {
                lambda,
                switched,
                mode,
                ..
            } => {
                // the mode: the top moving sideways
                assert!(
                    (mode[1][0].abs() - 1.0).abs() < 1e-9 && mode[1][2].abs() < 1e-6,
                    "{mode:?}"
                );
                Some((*lambda, *switched))
            }
            _ => None,
        })
        .expect("a bifurcation");
    assert!(switched);
    // the bar carries the share EA/(EA + 2 t0) of the load (the strings' geometric stiffness
    // t0/1 each takes the rest as the top sinks), so λ_c P EA/(EA + 2 t0) = 2 k L', with
    // L' = 1 − (the bar's force)/EA its shortened length
    let share = EA_BAR / (EA_BAR + 2.0 * T0);
    let mut expected = 2.0 * K / P;
    for _ in 0..5 {
        expected = 2.0 * K * (1.0 - expected * P * share / EA_BAR) / (P * share);
    }
    assert!(
        (lambda_c - expected).abs() < 1e-8 * expected,
        "{lambda_c} against {expected}"
    );
    // after the switch: the top leans, every point on the closed form of the buckled branch
    let after: Vec<_> = path
        .points
        .iter()
        .filter(|p| p.nodes[1][0].abs() > 1e-3)
        .collect();
    assert!(after.len() >= 3, "{} points off the axis", after.len());
    for p in &after {
        let [x, _, z] = p.nodes[1];
        let expected = buckled_lambda(x, z);
        assert!(
            (p.lambda - expected).abs() < 1e-5 * expected,
            "x = {x}: λ {} against {expected}",
            p.lambda
        );
    }
    // the straight path is stable below λ_c; the buckled branch falls (λ below λ_c as it
    // leans) and is unstable: the bifurcation is subcritical once a string slackens
    assert!(path
        .points
        .iter()
        .filter(|p| p.lambda < 0.99 * lambda_c && p.nodes[1][0].abs() < 1e-9)
        .all(|p| p.stability == Stability::Stable));
    // (while the bar still stands: above the strings' level it hangs and is stable again)
    for p in after
        .iter()
        .filter(|p| (0.05..0.9).contains(&p.nodes[1][0]) && p.nodes[1][2] > 0.2)
    {
        assert!(
            p.lambda < lambda_c && p.stability == Stability::Unstable,
            "{} {:?}",
            p.lambda,
            p.stability
        );
    }
    // the string on the side it leans to slackens where its length reaches its rest length
    // 0.9: the top on the unit circle at distance 0.9 from (1, 0, 1) (bisected in x)
    let slack = path.events.iter().find_map(|e| match e {
        Event::Slackened {
            members, lambda, ..
        } => Some((members.clone(), *lambda)),
        _ => None,
    });
    let (members, lambda_slack) = slack.expect("a string slackens");
    assert_eq!(members, vec![2]);
    let gap = |x: f64| (1.0 - x).powi(2) + (1.0 - (1.0 - x * x).sqrt()).powi(2) - 0.81;
    let (mut lo, mut hi) = (0.0, 0.5);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let x = 0.5 * (lo + hi);
    let expected = buckled_lambda(x, (1.0 - x * x).sqrt());
    assert!(
        (lambda_slack - expected).abs() < 1e-5 * expected,
        "{lambda_slack} against {expected}"
    );
}

#[test]
fn without_the_switch_the_straight_path_goes_on_unstable() {
    let path = follow(
        &column(),
        &PathSettings {
            target: 2.5,
            ..PathSettings::default()
        },
    )
    .unwrap();
    let last = path.points.last().unwrap();
    assert!(last.nodes[1][0].abs() < 1e-9);
    assert_eq!(last.stability, Stability::Unstable);
}
