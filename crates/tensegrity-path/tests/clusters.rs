//! Clustered strings in the elastic model (`tensegrity_path::clusters`) against closed
//! forms: the Atwood machine (uniform acceleration, energy conserved, with RK4, RK45 and
//! Newmark), a mass hanging over a pulley on a load path (tension = prestress + load,
//! displacement = load/k), the tangent against finite differences of the forces, a slack
//! cluster, a damped one's energy balance, and the refusals.

use nalgebra::{DVector, Vector3};
use tensegrity_core::{Cluster, Structure};
use tensegrity_dynamics::{IntegratorKind, Sample, SimulationSettings};
use tensegrity_path::dofs::Dofs;
use tensegrity_path::forces::{member_states, resisting_forces};
use tensegrity_path::model::Drivers;
use tensegrity_path::tangent::tangent_stiffness;
use tensegrity_path::transient::ElasticDynamics;
use tensegrity_path::{
    follow, ElasticCluster, ElasticModel, MassDistribution, Masses, PathSettings, Support,
};

const G: f64 = 9.81;

/// The Atwood machine: the pulley (node 0) pinned at the origin, m₁ (node 1) 1 m and m₂
/// (node 2) 1.5 m below it, the cluster 1 → 0 → 2 stretched to the Atwood tension
/// T = 2 m₁ m₂ g/(m₁ + m₂).
fn atwood(m1: f64, m2: f64, k: f64, c: f64, v: &[Vector3<f64>]) -> (ElasticDynamics, f64) {
    let tension = 2.0 * m1 * m2 * G / (m1 + m2);
    let model = ElasticModel {
        nodes: vec![
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, -1.0),
            Vector3::new(0.0, 0.0, -1.5),
        ],
        members: vec![],
        clusters: vec![ElasticCluster {
            nodes: vec![1, 0, 2],
            stiffness: k,
            rest_length: 2.5 - tension / k,
            damping: c,
            friction: None,
        }],
        supports: vec![Support::pinned(0)],
        load: vec![Vector3::zeros(); 3],
        drivers: Default::default(),
    };
    let masses = Masses {
        members: vec![],
        nodes: vec![0.0, m1, m2],
        distribution: MassDistribution::Lumped,
    };
    let gravity = Some(Vector3::new(0.0, 0.0, -G));
    let d = ElasticDynamics::new(model, masses, vec![], gravity, v).unwrap();
    (d, tension)
}

fn settings(kind: IntegratorKind, dt: f64, t_end: f64) -> SimulationSettings {
    SimulationSettings {
        t_end,
        integrator: kind,
        dt,
        ..Default::default()
    }
}

/// m₁ falls and m₂ rises at a = (m₁ − m₂) g/(m₁ + m₂): the cluster's length stays, so its
/// tension stays T and the motion is exactly quadratic (RK4 integrates it to round-off).
#[test]
fn the_atwood_machine_accelerates_uniformly() {
    let (m1, m2) = (3.0, 1.0);
    let a = (m1 - m2) * G / (m1 + m2);
    let (d, tension) = atwood(m1, m2, 1e4, 0.0, &[]);
    // the reported tension is the cluster's, after the (no) members
    let forces = d.member_forces(&d.initial_state());
    assert_eq!(forces.len(), 1);
    assert!((forces[0] - tension).abs() < 1e-12 * tension, "{forces:?}");
    let t = 0.5;
    let fall = 0.5 * a * t * t;
    for (kind, dt, tol) in [
        (IntegratorKind::Rk4, 1e-3, 1e-9),
        (IntegratorKind::Rk45, 1e-3, 1e-9),
        // the trapezoidal rule is exact on constant accelerations too
        (IntegratorKind::Newmark, 1e-2, 1e-9),
    ] {
        let r = d
            .run(&settings(kind, dt, t), &mut Vec::<Sample>::new())
            .unwrap();
        let x = &r.final_nodes;
        let (z1, z2) = (x[1].z + 1.0, x[2].z + 1.5);
        assert!(
            (z1 + fall).abs() < tol * fall,
            "{kind}: m1 moved {z1}, expected {}",
            -fall
        );
        assert!(
            (z2 - fall).abs() < tol * fall,
            "{kind}: m2 moved {z2}, expected {fall}"
        );
        assert!(x[1].xy().norm() == 0.0 && x[2].xy().norm() == 0.0);
        assert!(r.energy_drift < 1e-9, "{kind}: drift {}", r.energy_drift);
        let f = d.member_forces(&r.final_state);
        assert!((f[0] - tension).abs() < 1e-8 * tension, "{kind}: {f:?}");
    }
}

/// Energy ½ m v² + ½ k (L − L₀)² − m g z is conserved when the cluster oscillates (started
/// off the Atwood tension, the masses bounce on it) and the state's parts add up.
#[test]
fn an_oscillating_atwood_machine_conserves_energy() {
    // m₂ pushed down: the cluster stretches beyond T and the masses bounce on it
    let push = [
        Vector3::zeros(),
        Vector3::zeros(),
        Vector3::new(0.0, 0.0, -0.3),
    ];
    let (d, tension) = atwood(2.0, 1.0, 400.0, 0.0, &push);
    let e = d.energy(&d.initial_state());
    let stretch = tension / 400.0;
    assert!((e.strain - 0.5 * 400.0 * stretch * stretch).abs() < 1e-12);
    assert!((e.kinetic - 0.5 * 1.0 * 0.09).abs() < 1e-15);
    let r = d
        .run(
            &settings(IntegratorKind::Rk4, 1e-4, 0.4),
            &mut Vec::<Sample>::new(),
        )
        .unwrap();
    assert!(r.energy_drift < 1e-10, "drift {}", r.energy_drift);
}

/// With a dashpot on the cluster the energy lost equals the dashpot's work (the run's
/// balance), and the tension includes c L̇.
#[test]
fn a_damped_cluster_dissipates_what_its_dashpot_takes() {
    // m₁ and m₂ both pushed down: L grows at 0.5 m/s
    let down = Vector3::new(0.0, 0.0, -0.25);
    let (d, tension) = atwood(2.0, 1.0, 400.0, 5.0, &[Vector3::zeros(), down, down]);
    let y = d.initial_state();
    let plain = tension;
    assert!((d.member_forces(&y)[0] - (plain + 5.0 * 0.5)).abs() < 1e-12);
    assert!((d.dissipation(&y) - 5.0 * 0.25).abs() < 1e-12);
    let r = d
        .run(
            &settings(IntegratorKind::Rk4, 1e-4, 0.5),
            &mut Vec::<Sample>::new(),
        )
        .unwrap();
    assert!(r.energy_drift < 1e-7, "drift {}", r.energy_drift);
}

/// A cluster shorter than its rest length carries nothing: the masses fall freely.
#[test]
fn a_slack_cluster_lets_the_masses_fall() {
    let mut model = atwood(2.0, 1.0, 1e3, 0.0, &[]).0.model().clone();
    model.clusters[0].rest_length = 3.0;
    let masses = Masses {
        members: vec![],
        nodes: vec![0.0, 2.0, 1.0],
        distribution: MassDistribution::Lumped,
    };
    let d =
        ElasticDynamics::new(model, masses, vec![], Some(Vector3::new(0.0, 0.0, -G)), &[]).unwrap();
    assert_eq!(d.member_forces(&d.initial_state()), vec![0.0]);
    let t = 0.1; // both fall 0.049 m: L = 2.5 − 0.049 + 0.049 stays below 3
    let r = d
        .run(
            &settings(IntegratorKind::Rk4, 1e-3, t),
            &mut Vec::<Sample>::new(),
        )
        .unwrap();
    let fall = 0.5 * G * t * t;
    assert!((r.final_nodes[1].z + 1.0 + fall).abs() < 1e-12);
    assert!((r.final_nodes[2].z + 1.5 + fall).abs() < 1e-12);
}

/// An anchor (node 0) and a pulley (node 1) pinned, the cluster 0 → 1 → 2 with node 2 hanging
/// 1 m below the pulley: a weight `t0` on it (the dead load, from λ = 0) stretches the
/// cluster to t0 in the reference state; the load P (down) comes on top.
fn hanging(k: f64, t0: f64, p: f64) -> ElasticModel {
    ElasticModel {
        nodes: vec![
            Vector3::new(-1.0, 0.0, 0.0),
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, -1.0),
        ],
        members: vec![],
        clusters: vec![ElasticCluster {
            nodes: vec![0, 1, 2],
            stiffness: k,
            rest_length: 2.0 - t0 / k,
            damping: 0.0,
            friction: None,
        }],
        supports: vec![Support::pinned(0), Support::pinned(1)],
        load: vec![
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::new(0.0, 0.0, -p),
        ],
        drivers: Drivers {
            dead_load: vec![
                Vector3::zeros(),
                Vector3::zeros(),
                Vector3::new(0.0, 0.0, -t0),
            ],
            ..Drivers::default()
        },
    }
}

/// The pulley turns the load: the tension is the weight plus the load all along the cluster
/// (the anchor's reaction), and the mass sinks by load/k.
#[test]
fn a_load_hanging_over_a_pulley_stretches_the_cluster_by_load_over_k() {
    let (k, t0, p) = (1e4, 100.0, 50.0);
    let model = hanging(k, t0, p);
    let path = follow(&model, &PathSettings::default()).unwrap();
    let last = path.points.last().unwrap();
    assert!((last.lambda - 1.0).abs() < 1e-12, "{}", last.lambda);
    for point in &path.points {
        let load = point.lambda * p;
        assert_eq!(point.tensions.len(), 1);
        let t = point.tensions[0];
        assert!(
            (t - (t0 + load)).abs() < 1e-10 * (t0 + p),
            "{t} at λ {}",
            point.lambda
        );
        let u = point.displacements[2];
        assert!((u[2] + load / k).abs() < 1e-10 * p / k, "{u:?}");
        assert!(u[0].abs() < 1e-12 && u[1].abs() < 1e-12);
        // the anchor holds the tension along the horizontal segment
        let anchor_x = point
            .reactions
            .iter()
            .find(|r| r.node == 0 && r.direction[0].abs() > 0.9)
            .unwrap();
        let along = anchor_x.force * anchor_x.direction[0];
        assert!((along + t).abs() < 1e-9 * t, "{along} against {t}");
    }
    assert!(last.slack.is_empty());
}

/// Lifted by more than its weight, the hanging node's cluster goes slack on the load path
/// (a soft spring holds the node then), and the slack list names the cluster after the
/// members.
#[test]
fn a_cluster_lifted_past_its_weight_goes_slack() {
    let (k, t0) = (1e4, 1.0);
    // an upward load of 2 N against 1 N of prestress, the node held laterally
    let mut model = hanging(k, t0, -2.0);
    model
        .supports
        .push(Support::along(2, vec![Vector3::x(), Vector3::y()]));
    // a soft spring holds the node once the cluster is slack
    model
        .supports
        .push(Support::along(2, vec![Vector3::z()]).elastic(10.0));
    let path = follow(&model, &PathSettings::default()).unwrap();
    let last = path.points.last().unwrap();
    assert_eq!(last.slack, vec![0]);
    assert_eq!(last.tensions, vec![0.0]);
    let slackened = path.events.iter().find_map(|e| match e {
        tensegrity_path::Event::Slackened {
            members, lambda, ..
        } => Some((members.clone(), *lambda)),
        _ => None,
    });
    let (members, lambda) = slackened.expect("a slack event");
    assert_eq!(members, vec![0]);
    // the cluster and the spring share the lift: (k + k_s) u = 2λ, and t = t0 − k u = 0 at
    // λ = t0 (k + k_s)/(2 k)
    let expected = t0 * (k + 10.0) / (2.0 * k);
    assert!(
        (lambda - expected).abs() < 1e-6 * expected,
        "{lambda} against {expected}"
    );
}

/// The tangent (k g gᵀ + Σ (t/l_i)(I − e_i e_iᵀ)) is the derivative of the resisting forces:
/// central differences on a 4-node cluster in a general position, to 10⁻⁷.
#[test]
fn the_cluster_tangent_is_the_derivative_of_its_forces() {
    let model = general_cluster(None);
    let nodes = model.nodes.clone();
    let dofs = Dofs::of(&model).unwrap();
    let (worst, scale, _) = against_differences(&model, &dofs);
    assert!(worst < 1e-7 * scale, "{worst} against {scale}");
    let k = tangent_stiffness(&model, &dofs, &member_states(&model, &nodes, 0.0));
    // the material part couples the first and last segments (through the pulleys)
    let (a, _) = dofs.of_node[1];
    let (b, _) = dofs.of_node[3];
    assert!(k[(a, b)].abs() > 1.0 || k[(a + 1, b)].abs() > 1.0 || k[(a + 2, b)].abs() > 1.0);
}

/// With pulley friction each segment is a string at its own rest length (the pulleys stuck
/// within an increment): (EA/s_i) e eᵀ + (t_i/l_i)(I − e eᵀ) per segment, no coupling
/// between segments; central differences to 10⁻⁷, and the strain energy's gradient is the
/// resisting force.
#[test]
fn a_frictional_cluster_s_tangent_is_the_derivative_of_its_forces() {
    let model = general_cluster(Some(tensegrity_path::model::ClusterFriction::spread(
        vec![0.3, 0.1],
        3.0,
        &[1.2, 0.9, 0.9],
    )));
    let nodes = model.nodes.clone();
    let dofs = Dofs::of(&model).unwrap();
    let states = member_states(&model, &nodes, 0.0);
    // three different tensions: the segments carry their own
    assert!((states[0].tension - states[1].tension).abs() > 1.0);
    let (worst, scale, worst_force) = against_differences(&model, &dofs);
    assert!(worst < 1e-7 * scale, "{worst} against {scale}");
    let r0 = dofs.reduce(&resisting_forces(&model, &states)).amax();
    assert!(worst_force < 1e-7 * r0, "{worst_force} against {r0}");
}

/// A cluster through four nodes in a general position (k = 250 N/m, L₀ = 3 m, node 0
/// pinned), with `friction`.
fn general_cluster(friction: Option<tensegrity_path::model::ClusterFriction>) -> ElasticModel {
    ElasticModel {
        nodes: vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.2, 0.3),
            Vector3::new(1.7, 1.1, -0.4),
            Vector3::new(0.4, 1.9, 0.8),
        ],
        members: vec![],
        clusters: vec![ElasticCluster {
            nodes: vec![0, 1, 2, 3],
            stiffness: 250.0,
            rest_length: 3.0,
            damping: 0.0,
            friction,
        }],
        supports: vec![Support::pinned(0)],
        load: vec![Vector3::zeros(); 4],
        drivers: Default::default(),
    }
}

/// The tangent at the model's nodes against central differences (step 10⁻⁶) of the
/// resisting forces, and the resisting forces against those of the strain energy: the
/// largest column error, the tangent's largest entry and the largest force error.
fn against_differences(model: &ElasticModel, dofs: &Dofs) -> (f64, f64, f64) {
    let nodes = &model.nodes;
    let k = tangent_stiffness(model, dofs, &member_states(model, nodes, 0.0));
    let at = |q: &DVector<f64>| {
        let u = dofs.expand(q, nodes.len());
        let x: Vec<Vector3<f64>> = nodes.iter().zip(&u).map(|(a, b)| a + b).collect();
        let st = member_states(model, &x, 0.0);
        (
            dofs.reduce(&resisting_forces(model, &st)),
            tensegrity_path::clusters::strain_energy(model, &st),
        )
    };
    let h = 1e-6;
    let (mut worst, mut worst_force): (f64, f64) = (0.0, 0.0);
    let r0 = at(&DVector::zeros(dofs.len())).0;
    for c in 0..dofs.len() {
        let mut q = DVector::zeros(dofs.len());
        q[c] = h;
        let plus = at(&q);
        q[c] = -h;
        let minus = at(&q);
        worst = worst.max(((&plus.0 - &minus.0) / (2.0 * h) - k.column(c)).amax());
        worst_force = worst_force.max(((plus.1 - minus.1) / (2.0 * h) - r0[c]).abs());
    }
    (worst, k.amax(), worst_force)
}

/// From a scene's structure: the cluster's stiffness and rest length (default: its length),
/// its damping and friction; a missing stiffness refused naming the cluster.
#[test]
fn a_structure_s_clusters_enter_the_model() {
    let build = |c: Cluster| {
        Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0]])
            .cluster(c)
            .build()
            .unwrap()
    };
    let s = build(Cluster::new([0, 1, 2]).stiffness(50.0).damping(2.0));
    let m = ElasticModel::from_structure(&s).unwrap();
    assert_eq!(m.clusters.len(), 1);
    assert_eq!(
        (m.clusters[0].stiffness, m.clusters[0].damping),
        (50.0, 2.0)
    );
    assert!((m.clusters[0].rest_length - 2.0 * 2f64.sqrt()).abs() < 1e-15);
    // friction: the material spread in proportion to the segments (√2 each), stuck
    let s = build(Cluster::new([0, 1, 2]).stiffness(50.0).friction([0.2]));
    let m = ElasticModel::from_structure(&s).unwrap();
    let f = m.clusters[0].friction.as_ref().unwrap();
    assert_eq!(f.mu, vec![0.2]);
    assert!(f
        .rest_lengths
        .iter()
        .all(|r| (r - 2f64.sqrt()).abs() < 1e-15));
    assert_eq!(f.pulleys, vec![tensegrity_core::capstan::Pulley::Stick]);
    let s = build(Cluster::new([0, 1, 2]));
    let e = ElasticModel::from_structure(&s).unwrap_err().to_string();
    assert!(e.contains("cluster 0") && e.contains("stiffness"), "{e}");
    // a model's own check names the cluster too
    let mut bad = hanging(1e3, 1.0, 1.0);
    bad.clusters[0].nodes = vec![0, 1, 7];
    let e = bad.validated().unwrap_err().to_string();
    assert!(e.contains("cluster 0") && e.contains("node 7"), "{e}");
}

/// The prism of examples/prism.toml with its bottom ring one clustered string (a loop
/// 0 → 1 → 2 → 0 over pulleys, the three ring strings in series), its top triangle turned
/// by 0.05 rad so that it oscillates: the same scene as `tensegrity-dynamics`'s
/// `tests/dynamics_clusters.rs`.
fn clustered_prism() -> Structure {
    use tensegrity_core::{Bar, StringMember};
    const RING: f64 = 1.7147302994931883;
    const VERTICAL: f64 = 1.1065290455901822;
    let nodes = [
        [1.0, 0.0, 0.0],
        [-0.4999999999999998, 0.8660254037844387, 0.0],
        [-0.5000000000000004, -0.8660254037844384, 0.0],
        [0.8660254037844386, 0.5, 1.0],
        [-0.8660254037844385, 0.5000000000000003, 1.0],
        [-1.8369701987210297e-16, -1.0, 1.0],
    ];
    let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 0.05);
    let nodes = nodes.map(|p| {
        let p = Vector3::from(p);
        let q = if p.z > 0.5 { turn * p } else { p };
        [q.x, q.y, q.z]
    });
    let string = |a, b, l| StringMember::new(a, b).stiffness(1000.0).rest_length(l);
    Structure::builder()
        .nodes(nodes)
        .bar(Bar::new(0, 4).mass(1.0))
        .bar(Bar::new(1, 5).mass(1.0))
        .bar(Bar::new(2, 3).mass(1.0))
        .strings([
            string(3, 4, RING),
            string(4, 5, RING),
            string(5, 3, RING),
            string(0, 3, VERTICAL),
            string(1, 4, VERTICAL),
            string(2, 5, VERTICAL),
        ])
        .cluster(
            Cluster::new([0, 1, 2, 0])
                .stiffness(1000.0 / 3.0)
                .rest_length(3.0 * RING),
        )
        .build()
        .unwrap()
}

/// Two independent codes agree: the rigid-bar dynamics (class-1 nodes, the Ω closed form,
/// the cluster a force element) and the elastic node model with all three bars rigid (length
/// constraints, consistent bar masses, the cluster in its forces) give the same motion of
/// the clustered prism to 10⁻⁸ m after 1 s, and the same cluster tension.
#[test]
fn the_rigid_bar_dynamics_and_the_node_model_with_rigid_bars_agree_on_a_clustered_prism() {
    let s = clustered_prism();
    let set = settings(IntegratorKind::Rk4, 2.5e-4, 1.0);
    let rigid = tensegrity_dynamics::Simulation::new(&s, set.clone())
        .unwrap()
        .run()
        .unwrap();
    let model = ElasticModel::from_structure_mixed(&s, &[true; 3]).unwrap();
    assert_eq!(model.clusters.len(), 1);
    let masses = Masses {
        members: [1.0, 1.0, 1.0].into_iter().chain([0.0; 6]).collect(),
        nodes: vec![0.0; 6],
        distribution: MassDistribution::Lumped,
    };
    let d = ElasticDynamics::new(model, masses, vec![], None, &[])
        .unwrap()
        .with_rigid_bars(&[0, 1, 2])
        .unwrap();
    let elastic = d.run(&set, &mut Vec::<Sample>::new()).unwrap();
    let gap = rigid
        .final_nodes
        .iter()
        .zip(&elastic.final_nodes)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    let moved = elastic
        .final_nodes
        .iter()
        .zip(s.nodes())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "the prism stays ({moved:e} m)");
    eprintln!("moved {moved:e} m, gap {gap:e} m");
    assert!(gap < 1e-8, "the two models differ by {gap:e} m");
    assert!(
        elastic.energy_drift < 1e-8,
        "drift {:e}",
        elastic.energy_drift
    );
    // the cluster's tension, last in both
    let t_elastic = *d.member_forces(&elastic.final_state).last().unwrap();
    let l: f64 = [0, 1, 2, 0]
        .windows(2)
        .map(|w| (rigid.final_nodes[w[1]] - rigid.final_nodes[w[0]]).norm())
        .sum();
    let t_rigid = 1000.0 / 3.0 * (l - 3.0 * 1.7147302994931883);
    assert!(
        (t_elastic - t_rigid).abs() < 1e-5 * t_rigid,
        "{t_elastic} vs {t_rigid}"
    );
}
