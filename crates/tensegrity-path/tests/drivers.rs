//! What the load factor drives beside the load (TsgFEM's forced motions and rest lengths):
//! two bars in series along z between a support at z = 0, node 1 at z = 1 (free along z) and
//! a support at z = 2.
//!
//! - Bar A's rest length driven to 1 + λ δ: equal tensions EA_a (u − λδ)/(1 + λδ) = −EA_b u
//!   give node 1's rise u = EA_a λ δ / (EA_a + EA_b (1 + λ δ)) (exact, nonlinear in λ).
//! - The top support driven up by λ d: EA_a u = EA_b (λ d − u), u = EA_b λ d/(EA_a + EA_b),
//!   the top support's reaction +EA_a u along z (the tension of both bars).

use nalgebra::Vector3;
use tensegrity_path::model::Drivers;
use tensegrity_path::{
    follow, load_steps, ElasticMember, ElasticModel, MemberKind, PathSettings, Support,
};

const EA_A: f64 = 1000.0;
const EA_B: f64 = 3000.0;

fn series(drivers: Drivers) -> ElasticModel {
    let bar = |nodes| ElasticMember {
        nodes,
        kind: MemberKind::Bar,
        ea: 0.0,
        rest_length: 1.0,
    };
    let (mut a, mut b) = (bar([0, 1]), bar([1, 2]));
    a.ea = EA_A;
    b.ea = EA_B;
    ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::z(), Vector3::new(0.0, 0.0, 2.0)],
        members: vec![a, b],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support {
                node: 1,
                directions: vec![Vector3::x(), Vector3::y()],
                stiffness: None,
            },
            Support::pinned(2),
        ],
        load: vec![Vector3::zeros(); 3],
        drivers,
    }
}

#[test]
fn a_driven_rest_length_moves_the_node_as_the_closed_form() {
    let delta = 0.2;
    let model = series(Drivers {
        rest_length_changes: vec![delta, 0.0],
        displacements: vec![],
        dead_load: vec![],
        ..Default::default()
    });
    let path = follow(&model, &PathSettings::default()).unwrap();
    assert!(path.points.len() > 3);
    for p in &path.points {
        let l = p.lambda;
        let u = EA_A * l * delta / (EA_A + EA_B * (1.0 + l * delta));
        assert!(
            (p.displacements[1][2] - u).abs() < 1e-12,
            "λ {l}: {} against {u}",
            p.displacements[1][2]
        );
        assert!(
            (p.tensions[0] - p.tensions[1]).abs() < 1e-9,
            "{:?}",
            p.tensions
        );
    }
    assert_eq!(path.points.last().unwrap().lambda, 1.0);
    // load steps reach the same end
    let steps = load_steps(&model, 4, 1.0).unwrap();
    let (a, b) = (steps.points.last().unwrap(), path.points.last().unwrap());
    assert!((a.displacements[1][2] - b.displacements[1][2]).abs() < 1e-12);
}

#[test]
fn a_driven_support_moves_the_node_and_its_reaction_is_the_tension() {
    let d = 0.1;
    let mut motion = vec![Vector3::zeros(); 3];
    motion[2] = Vector3::new(0.0, 0.0, d);
    let path = follow(
        &series(Drivers {
            rest_length_changes: vec![],
            displacements: motion,
            dead_load: vec![],
            ..Default::default()
        }),
        &PathSettings::default(),
    )
    .unwrap();
    for p in &path.points {
        let u = EA_B * p.lambda * d / (EA_A + EA_B);
        assert!(
            (p.displacements[1][2] - u).abs() < 1e-12,
            "λ {}: {}",
            p.lambda,
            p.displacements[1][2]
        );
        assert!((p.displacements[2][2] - p.lambda * d).abs() < 1e-15);
        let top = p
            .reactions
            .iter()
            .find(|r| r.node == 2 && r.direction[2] == 1.0)
            .unwrap();
        // bar B is stretched (u < λ d): it pulls the top support down, which pushes back up
        assert!(
            (top.force - EA_A * u).abs() < 1e-9,
            "{} against {}",
            top.force,
            EA_A * u
        );
    }
}

#[test]
fn a_displacement_on_a_free_direction_and_a_vanishing_rest_length_are_refused() {
    let mut motion = vec![Vector3::zeros(); 3];
    motion[1] = Vector3::new(0.0, 0.0, 0.1); // node 1 is free along z
    let err = follow(
        &series(Drivers {
            rest_length_changes: vec![],
            displacements: motion,
            dead_load: vec![],
            ..Default::default()
        }),
        &PathSettings::default(),
    )
    .unwrap_err();
    assert!(
        err.to_string().starts_with("displacement of node 1: "),
        "{err}"
    );
    let err = follow(
        &series(Drivers {
            rest_length_changes: vec![-2.0, 0.0],
            displacements: vec![],
            dead_load: vec![],
            ..Default::default()
        }),
        &PathSettings::default(),
    )
    .unwrap_err();
    assert!(
        err.to_string().contains("member 0") && err.to_string().contains("not positive"),
        "{err}"
    );
}
