//! Clustered strings in the rigid-bar dynamics (`tensegrity_dynamics::cluster_forces`): the
//! Snelson prism with its bottom ring one clustered string (a loop over three pulleys),
//! twisted off its equilibrium, conserves energy, its reported tension is k (L − L₀), a damped cluster
//! dissipates, and the refusals name the node or the cluster. The cross-check against the
//! elastic node model with rigid bars lives in `tensegrity-path`'s `tests/clusters.rs`.

use nalgebra::Vector3;
use tensegrity_core::{Bar, Cluster, StringMember, Structure};
use tensegrity_dynamics::{IntegratorKind, Model, Quantities, Simulation, SimulationSettings};

/// The nodes of examples/prism.toml (unit radii and height, twist 30°).
const NODES: [[f64; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [-0.4999999999999998, 0.8660254037844387, 0.0],
    [-0.5000000000000004, -0.8660254037844384, 0.0],
    [0.8660254037844386, 0.5, 1.0],
    [-0.8660254037844385, 0.5000000000000003, 1.0],
    [-1.8369701987210297e-16, -1.0, 1.0],
];
const RING: f64 = 1.7147302994931883;
const VERTICAL: f64 = 1.1065290455901822;

/// The cluster's stiffness: the three ring strings (1000 N/m each) in series (N/m).
const K: f64 = 1000.0 / 3.0;
/// Its rest length: the three ring strings' (m), which keeps the prism's prestress.
const L0: f64 = 3.0 * RING;

/// The prism of examples/prism.toml with its bottom ring 0 → 1 → 2 → 0 one clustered string
/// (a loop over pulleys at the ring nodes: [`K`], [`L0`], damping `c`), as in
/// examples/clustered_prism.toml, its top triangle turned by `twist` (rad) about the axis:
/// away from equilibrium, the prism oscillates, sliding the cluster over its pulleys.
fn clustered_prism(twist: f64, c: f64) -> Structure {
    let string = |a, b, l| StringMember::new(a, b).stiffness(1000.0).rest_length(l);
    let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), twist);
    let nodes = NODES.map(|p| {
        let p = Vector3::from(p);
        let q = if p.z > 0.5 { turn * p } else { p };
        [q.x, q.y, q.z]
    });
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
                .stiffness(K)
                .rest_length(L0)
                .damping(c),
        )
        .build()
        .unwrap()
}

fn settings(t_end: f64, integrator: IntegratorKind, dt: f64) -> SimulationSettings {
    SimulationSettings {
        t_end,
        integrator,
        dt,
        output_interval: Some(t_end / 10.0),
        quantities: Quantities {
            nodes: true,
            member_forces: true,
            energy: true,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// The cluster's length at `x` (file nodes).
fn length(x: &[Vector3<f64>]) -> f64 {
    [0, 1, 2, 0]
        .windows(2)
        .map(|w| (x[w[1]] - x[w[0]]).norm())
        .sum()
}

/// The twisted prism oscillates with its cluster taut; its energy — the cluster's
/// ½ k (L − L₀)² included — is kept to RK4's truncation error (which falls as h⁴ or
/// faster: a potential that did not match the forces would leave a drift that does not),
/// and to RK45's tolerance; the reported tension is k (L − L₀).
#[test]
fn a_prism_with_a_clustered_string_conserves_energy() {
    let s = clustered_prism(0.05, 0.0);
    let run = |kind, dt| {
        Simulation::new(&s, settings(1.0, kind, dt))
            .unwrap()
            .run()
            .unwrap()
    };
    let (coarse, fine) = (
        run(IntegratorKind::Rk4, 1e-3),
        run(IntegratorKind::Rk4, 2.5e-4),
    );
    assert!(
        fine.energy_drift < 1e-8,
        "rk4: drift {:e}",
        fine.energy_drift
    );
    assert!(
        fine.energy_drift < coarse.energy_drift / 200.0,
        "rk4: drift {:e} at 1e-3 s, {:e} at 2.5e-4 s",
        coarse.energy_drift,
        fine.energy_drift
    );
    let adaptive = run(IntegratorKind::Rk45, 1e-3);
    assert!(
        adaptive.energy_drift < 1e-6,
        "rk45: drift {:e}",
        adaptive.energy_drift
    );
    for r in [&fine, &adaptive] {
        let first = &r.samples[0];
        let last = r.samples.last().unwrap();
        let (x0, x1) = (first.nodes.as_ref().unwrap(), last.nodes.as_ref().unwrap());
        let moved = x0
            .iter()
            .zip(x1)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        assert!(moved > 1e-3, "the prism stays ({moved:e} m)");
        for smp in &r.samples {
            let f = smp.member_forces.as_ref().unwrap();
            // 3 bars, 6 strings, then the cluster: taut throughout
            assert_eq!(f.len(), 10);
            let expected = K * (length(smp.nodes.as_ref().unwrap()) - L0);
            assert!(expected > 10.0, "{expected}");
            assert!(
                (f[9] - expected).abs() < 1e-9 * expected,
                "{} vs {expected}",
                f[9]
            );
        }
    }
}

/// A damped cluster takes energy out: the total energy falls and the model is not counted
/// conservative (no drift warning against it).
#[test]
fn a_damped_cluster_dissipates() {
    let s = clustered_prism(0.05, 20.0);
    assert!(!Model::new(&s, None).unwrap().is_conservative());
    assert!(Model::new(&clustered_prism(0.05, 0.0), None)
        .unwrap()
        .is_conservative());
    let r = Simulation::new(&s, settings(1.0, IntegratorKind::Rk4, 1e-3))
        .unwrap()
        .run()
        .unwrap();
    let energy = |k: usize| r.samples[k].energy.unwrap().1;
    let n = r.samples.len() - 1;
    assert!(
        energy(n) < energy(0) - 1e-3,
        "{} -> {}",
        energy(0),
        energy(n)
    );
}

/// A cluster through a free node on no bar (no mass there) is refused naming the node;
/// pulley friction is refused naming the cluster.
#[test]
fn a_cluster_through_a_massless_node_or_with_friction_is_refused() {
    let base = || {
        Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.0, 1.0]])
            .bar(Bar::new(0, 1).mass(1.0))
    };
    let s = base()
        .cluster(Cluster::new([0, 2, 1]).stiffness(10.0))
        .build()
        .unwrap();
    let e = Model::new(&s, None).unwrap_err().to_string();
    assert!(e.contains("node 2"), "{e}");
    // fixed in all three directions, node 2 is a pulley
    let s = base()
        .cluster(Cluster::new([0, 2, 1]).stiffness(10.0))
        .support(tensegrity_core::Support::pinned(2))
        .build()
        .unwrap();
    assert!(Model::new(&s, None).is_ok());
    let s = base()
        .cluster(Cluster::new([0, 2, 1]).stiffness(10.0).friction([0.3]))
        .support(tensegrity_core::Support::pinned(2))
        .build()
        .unwrap();
    let e = Model::new(&s, None).unwrap_err().to_string();
    assert!(e.contains("cluster 0") && e.contains("friction"), "{e}");
}

/// The rest-length schedule holds the strings' rest lengths, then the clusters': driving
/// slot 6 (after the prism's six strings) shortens the cluster, and its reported tension is
/// k (L − L₀(t)) while the strings keep theirs.
#[test]
fn a_rest_length_schedule_drives_the_cluster_after_the_strings() {
    let s = clustered_prism(0.0, 0.0);
    let mut sim = Simulation::new(&s, settings(0.2, IntegratorKind::Rk4, 1e-3)).unwrap();
    let reeled = L0 - 0.1;
    sim.model
        .set_rest_length_schedule(Box::new(move |_, rest: &mut [f64]| {
            assert_eq!(rest.len(), 7);
            rest[6] = reeled;
        }));
    assert!(!sim.model.is_conservative());
    let r = sim.run().unwrap();
    for smp in &r.samples {
        let f = smp.member_forces.as_ref().unwrap();
        let expected = K * (length(smp.nodes.as_ref().unwrap()) - reeled);
        assert!(
            (f[9] - expected).abs() < 1e-9 * expected,
            "{} vs {expected}",
            f[9]
        );
    }
}
