//! Strings that go slack under load.
//!
//! A prestressed rod (closed form): a string (stiffness k_s) and a bar (k_b) side by side
//! between a support and node 1 above it, prestressed to t₀ (the string's rest length shorter,
//! the bar's longer than their common length). A downward load F shortens both by
//! u = F/(k_s + k_b) while both act; the string slackens when its tension t₀ − k_s u reaches
//! zero, at F = t₀ (1 + k_b/k_s); beyond it the bar alone resists.

use nalgebra::Vector3;
use tensegrity_path::point::Event;
use tensegrity_path::{follow, ElasticMember, ElasticModel, MemberKind, PathSettings, Support};

const KS: f64 = 1000.0;
const KB: f64 = 4000.0;
const T0: f64 = 20.0;
const F: f64 = 50.0;

/// Support 0 at the origin, node 1 at z = 1 (held across).
fn rod() -> ElasticModel {
    // string: length 1, tension t0 = k_s (1 − L0) → L0 = 1 − t0/k_s; EA = k_s L0
    let ls = 1.0 - T0 / KS;
    // bar: compression −t0 = k_b (1 − L0) → L0 = 1 + t0/k_b
    let lb = 1.0 + T0 / KB;
    ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::new(0.0, 0.0, 1.0)],
        members: vec![
            ElasticMember {
                nodes: [0, 1],
                kind: MemberKind::String,
                ea: KS * ls,
                rest_length: ls,
            },
            ElasticMember {
                nodes: [0, 1],
                kind: MemberKind::Bar,
                ea: KB * lb,
                rest_length: lb,
            },
        ],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support {
                node: 1,
                directions: vec![Vector3::x(), Vector3::y()],
                stiffness: None,
            },
        ],
        load: vec![Vector3::zeros(), Vector3::new(0.0, 0.0, -F)],
        drivers: Default::default(),
    }
}

#[test]
fn the_string_slackens_at_the_closed_form_load_and_the_bar_carries_the_rest() {
    let path = follow(
        &rod(),
        &PathSettings {
            target: 3.0,
            ..PathSettings::default()
        },
    )
    .unwrap();
    let start = &path.points[0];
    assert!(
        (start.tensions[0] - T0).abs() < 1e-9 && (start.tensions[1] + T0).abs() < 1e-9,
        "{:?}",
        start.tensions
    );
    let slackened: Vec<(f64, &Vec<usize>)> = path
        .events
        .iter()
        .filter_map(|e| match e {
            Event::Slackened {
                lambda, members, ..
            } => Some((*lambda, members)),
            _ => None,
        })
        .collect();
    assert_eq!(slackened.len(), 1, "{:?}", path.events);
    let expected = T0 * (1.0 + KB / KS) / F;
    assert!(
        (slackened[0].0 - expected).abs() < 1e-9 * expected,
        "{} against {expected}",
        slackened[0].0
    );
    assert_eq!(slackened[0].1, &vec![0]);
    for p in &path.points {
        let f = p.lambda * F;
        // while taut both resist; once slack the bar alone
        let u = if f < T0 * (1.0 + KB / KS) {
            f / (KS + KB)
        } else {
            T0 / KS + (f - T0 * (1.0 + KB / KS)) / KB
        };
        assert!(
            (p.displacements[1][2] + u).abs() < 1e-10,
            "λ {}: {} against {}",
            p.lambda,
            p.displacements[1][2],
            -u
        );
        assert_eq!(
            p.slack.contains(&0),
            f > T0 * (1.0 + KB / KS) + 1e-9,
            "λ {}",
            p.lambda
        );
    }
    let last = path.points.last().unwrap();
    assert_eq!(last.lambda, 3.0);
    assert_eq!(last.tensions[0], 0.0);
    assert!(
        (last.tensions[1] + 3.0 * F).abs() < 1e-9,
        "the bar carries the whole load"
    );
}

#[test]
fn a_pull_keeps_the_string_taut() {
    // the load reversed (a target below zero): the string stretches, the bar unloads
    let path = follow(
        &rod(),
        &PathSettings {
            target: -1.0,
            ..PathSettings::default()
        },
    )
    .unwrap();
    assert!(
        path.events
            .iter()
            .all(|e| !matches!(e, Event::Slackened { .. })),
        "{:?}",
        path.events
    );
    let last = path.points.last().unwrap();
    assert_eq!(last.lambda, -1.0);
    let u = F / (KS + KB);
    assert!(
        (last.tensions[0] - (T0 + KS * u)).abs() < 1e-9,
        "{:?}",
        last.tensions
    );
    assert!(
        (last.tensions[1] - (-T0 + KB * u)).abs() < 1e-9,
        "{:?}",
        last.tensions
    );
}
