//! Rigid bars in the node-mass dynamics (`tensegrity_path::rigid_bars`): against the
//! rigid-body dynamics of `tensegrity-dynamics` (an independent code: bars as bodies with
//! their λ closed form) on a spinning, falling prism; a free spinning bar against its
//! conservation laws and the closed form of its tension; a scene with an elastic and a rigid
//! bar against its energy; and the errors of a rigid bar that cannot be.

use nalgebra::Vector3;
use tensegrity_core::{Bar, StringMember, Structure};
use tensegrity_dynamics::{IntegratorKind, Quantities, Sample, Simulation, SimulationSettings};
use tensegrity_path::{ElasticDynamics, ElasticMember, ElasticModel, MassDistribution, Masses};
use tensegrity_path::{MemberKind, Support};

/// The 3-bar prism of examples/prism.toml with its vertical strings 5 % short (out of
/// equilibrium), spinning at ω = (0.3, −0.2, 1.0) rad/s about its centre, under gravity.
fn prism() -> Structure {
    let nodes = [
        [1.0, 0.0, 0.0],
        [-0.4999999999999998, 0.8660254037844387, 0.0],
        [-0.5000000000000004, -0.8660254037844384, 0.0],
        [0.8660254037844386, 0.5, 1.0],
        [-0.8660254037844385, 0.5000000000000003, 1.0],
        [-1.8369701987210297e-16, -1.0, 1.0],
    ];
    let centre = Vector3::new(0.0, 0.0, 0.5);
    let omega = Vector3::new(0.3, -0.2, 1.0);
    let velocities = nodes.map(|x| {
        let v = omega.cross(&(Vector3::from(x) - centre));
        [v.x, v.y, v.z]
    });
    let (ring, vertical) = (1.7147302994931883, 1.1065290455901822 * 0.95);
    let mut b = Structure::builder()
        .nodes(nodes)
        .velocities(velocities)
        .gravity([0.0, 0.0, -9.81]);
    for [i, j] in [[0, 4], [1, 5], [2, 3]] {
        b = b.bar(Bar::new(i, j).mass(1.0));
    }
    for [i, j] in [[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3]] {
        b = b.string(StringMember::new(i, j).stiffness(1000.0).rest_length(ring));
    }
    for [i, j] in [[0, 3], [1, 4], [2, 5]] {
        b = b.string(
            StringMember::new(i, j)
                .stiffness(1000.0)
                .rest_length(vertical),
        );
    }
    b.build().unwrap()
}

/// The node model of `s` with every bar rigid (its mass consistent).
fn node_model(s: &Structure) -> ElasticDynamics {
    let rigid = vec![true; s.n_bars()];
    let model = ElasticModel::from_structure_mixed(s, &rigid).unwrap();
    let masses = Masses {
        members: (0..s.n_bars())
            .map(|k| s.bar_mass(k).unwrap_or(0.0))
            .chain(std::iter::repeat_n(0.0, s.strings().len()))
            .collect(),
        nodes: vec![0.0; s.n_nodes()],
        distribution: MassDistribution::Lumped,
    };
    let v = s.velocities().unwrap_or_default();
    let bars: Vec<usize> = (0..s.n_bars()).collect();
    ElasticDynamics::new(model, masses, vec![], s.gravity(), v)
        .unwrap()
        .with_rigid_bars(&bars)
        .unwrap()
}

fn settings(integrator: IntegratorKind, dt: f64, t_end: f64) -> SimulationSettings {
    SimulationSettings {
        t_end,
        integrator,
        dt,
        ..Default::default()
    }
}

fn largest_distance(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
}

/// Two codes, one motion: the rigid-body dynamics (bars as bodies, λ closed form) and the
/// node model with the bars as length constraints give the same node trajectories. Both
/// converge at RK4's O(h⁴) (each one's error against its own run at h = 62.5 µs falls by 16
/// per halving: 1.6e-5, 9.7e-7, 5.9e-8 m at h = 2, 1, 0.5 ms over 0.6 s), their difference
/// falls faster than their errors (2.1e-8, 1.3e-9, 1.3e-10 m: they share the leading error
/// term) and at h = 62.5 µs they agree to 1e-13 m.
#[test]
fn the_node_model_with_rigid_bars_matches_the_rigid_body_dynamics() {
    let s = prism();
    let node = node_model(&s);
    let t_end = 0.6;
    let rigid_run = |dt: f64| {
        Simulation::new(&s, settings(IntegratorKind::Rk4, dt, t_end))
            .unwrap()
            .run()
            .unwrap()
    };
    let node_run = |dt: f64| {
        node.run(
            &settings(IntegratorKind::Rk4, dt, t_end),
            &mut Vec::<Sample>::new(),
        )
        .unwrap()
    };
    let (rigid_ref, node_ref) = (rigid_run(6.25e-5), node_run(6.25e-5));
    // the prism moved: it fell 1.8 m and turned
    let fall = node_ref.final_nodes[0].z - s.nodes()[0].z;
    assert!(fall < -1.5, "{fall}");
    assert!(
        node_ref.bar_length_drift < 1e-13,
        "{}",
        node_ref.bar_length_drift
    );
    let agreement = largest_distance(&rigid_ref.final_nodes, &node_ref.final_nodes);
    assert!(agreement < 1e-12, "{agreement:e}");
    let (mut differences, mut errors) = (Vec::new(), Vec::new());
    for dt in [2e-3, 1e-3, 5e-4] {
        let (rigid, r) = (rigid_run(dt), node_run(dt));
        assert!(r.bar_length_drift < 1e-13, "{}", r.bar_length_drift);
        differences.push(largest_distance(&rigid.final_nodes, &r.final_nodes));
        errors.push(largest_distance(&r.final_nodes, &node_ref.final_nodes));
    }
    println!("agreement {agreement:e}, differences {differences:?}, errors {errors:?}");
    assert!(differences[2] < 1e-9, "{differences:?}");
    for (d, e) in differences.windows(2).zip(errors.windows(2)) {
        assert!(d[0] / d[1] > 10.0, "{differences:?}");
        assert!((14.0..18.0).contains(&(e[0] / e[1])), "{errors:?}");
    }
}

/// A free bar (m = 2 kg, L = 1.5 m) translating and spinning at ω ⊥ the bar: its kinetic
/// energy ½ m V² + ½ (m L²/12) ω², its angular momentum and its length are constant, its
/// direction turns at ω, and its tension is the consistent ends' centripetal force
/// m ω² L/12 (the end masses m/3 and m/6 coupled: (m/6)(2a − a) with a = ω² L/2). Measured
/// over 2 s (a turn a second): energy and momentum to 1.2e-14 and 1.1e-14 (RK4 at 1 ms),
/// 1.5e-12 and 8e-13 (RK45, tolerance 1e-12), 1.6e-14 and 7.7e-15 (Newmark at 1 ms), the
/// length to 7e-15, 8e-15 and 1.5e-16; the closed form to 3e-12 m (RK4), 1.7e-12 m (RK45),
/// and Newmark to 6e-15 m of the closed form turning at the trapezoidal rule's discrete
/// rate (2/h) atan(ωh/2) (3.4e-6 m of phase lag at ω).
#[test]
fn a_free_spinning_rigid_bar_keeps_its_energy_momentum_and_length() {
    let (m, l) = (2.0, 1.5);
    let omega = Vector3::new(0.0, 0.0, 3.0);
    let velocity = Vector3::new(0.2, -0.1, 0.05);
    let x = vec![Vector3::new(-0.75, 0.0, 0.0), Vector3::new(0.75, 0.0, 0.0)];
    let v: Vec<Vector3<f64>> = x.iter().map(|x| velocity + omega.cross(x)).collect();
    let model = ElasticModel {
        nodes: x,
        members: vec![ElasticMember {
            nodes: [0, 1],
            kind: MemberKind::Bar,
            ea: 1.0,
            rest_length: l,
        }],
        clusters: Vec::new(),
        supports: vec![],
        load: vec![Vector3::zeros(); 2],
        drivers: Default::default(),
    };
    let masses = Masses {
        members: vec![m],
        nodes: vec![0.0; 2],
        distribution: MassDistribution::Lumped,
    };
    let d = ElasticDynamics::new(model, masses, vec![], None, &v)
        .unwrap()
        .with_rigid_bars(&[0])
        .unwrap();
    let y0 = d.initial_state();
    let e0 = d.energy(&y0).total();
    let exact = 0.5 * m * velocity.norm_squared() + 0.5 * (m * l * l / 12.0) * omega.norm_squared();
    assert!((e0 - exact).abs() < 1e-14 * exact, "{e0} against {exact}");
    let tension = d.member_forces(&y0)[0];
    let expected = m * omega.norm_squared() * l / 12.0;
    assert!(
        (tension - expected).abs() < 1e-12 * expected,
        "{tension} against {expected}"
    );
    // angular momentum about the origin under the consistent matrix
    let momentum = |x: &[Vector3<f64>], v: &[Vector3<f64>]| {
        (x[0].cross(&(2.0 * v[0] + v[1])) + x[1].cross(&(v[0] + 2.0 * v[1]))) * (m / 6.0)
    };
    let h0 = momentum(&d.nodes_of(&y0), &d.velocities_of(&y0));
    let t_end = 2.0;
    for (kind, dt, conserved, closed) in [
        (IntegratorKind::Rk4, 1e-3, 1e-10, 1e-9),
        (IntegratorKind::Rk45, 1e-2, 1e-10, 1e-9),
        (IntegratorKind::Newmark, 1e-3, 1e-12, 1e-12),
    ] {
        let mut s = settings(kind, dt, t_end);
        s.rtol = 1e-12;
        s.atol = 1e-14;
        s.output_interval = Some(0.05);
        s.quantities = Quantities {
            nodes: true,
            velocities: true,
            energy: true,
            ..Default::default()
        };
        let mut samples = Vec::<Sample>::new();
        let r = d.run(&s, &mut samples).unwrap();
        let mut worst = (0.0_f64, 0.0_f64, 0.0_f64);
        for smp in &samples {
            let (x, v) = (
                smp.nodes.as_ref().unwrap(),
                smp.velocities.as_ref().unwrap(),
            );
            let (_, e) = smp.energy.unwrap();
            worst.0 = worst.0.max((e - e0).abs() / e0);
            worst.1 = worst.1.max((momentum(x, v) - h0).norm() / h0.norm());
            worst.2 = worst.2.max(((x[1] - x[0]).norm() - l).abs() / l);
        }
        println!(
            "{kind}: energy {:e}, momentum {:e}, length {:e}",
            worst.0, worst.1, worst.2
        );
        assert!(
            worst.0 < conserved && worst.1 < conserved,
            "{kind}: {worst:?}"
        );
        assert!(worst.2 < 1e-12, "{kind}: {worst:?}");
        // the closed form: the centre moves at V, the bar turns at ω (Newmark, the
        // trapezoidal rule: at its discrete rate (2/h) atan(ω h/2))
        let rate = match kind {
            IntegratorKind::Newmark => 2.0 / dt * (omega.z * dt / 2.0).atan(),
            _ => omega.z,
        };
        let angle = rate * t_end;
        let centre = velocity * t_end;
        let half = Vector3::new(angle.cos(), angle.sin(), 0.0) * (0.5 * l);
        let exact = [centre - half, centre + half];
        let error = largest_distance(&r.final_nodes, &exact);
        println!("{kind}: closed form {error:e}");
        assert!(error < closed, "{kind}: {error:e}");
    }
}

/// An elastic bar 0–1 (EA = 2·10⁵ N, 1 kg, started 1 mm long) and a rigid bar 2–3 (1 kg)
/// crossed by four prestressed strings, free in space with no damping: the total energy is
/// kept (stated: Newmark at h = 0.1 ms to 2e-6, RK4 at h = 20 µs to 1e-9; measured 7.8e-7
/// and 1.1e-11), the rigid bar's length to 10⁻¹² relative (measured 4e-16) while the
/// elastic one's oscillates by about its initial stretch (0.9981..1.0010 m).
#[test]
fn a_mixed_scene_keeps_its_energy_and_its_rigid_length() {
    let nodes = vec![
        Vector3::new(-0.5005, 0.0, 0.0),
        Vector3::new(0.5005, 0.0, 0.0),
        Vector3::new(0.1, -0.5, 0.2),
        Vector3::new(-0.05, 0.5, -0.2),
    ];
    // spinning as a whole at ω = (0.5, 1, 2) rad/s (the rigid bar's length kept)
    let omega = Vector3::new(0.5, 1.0, 2.0);
    let v: Vec<Vector3<f64>> = nodes.iter().map(|x| omega.cross(x)).collect();
    let bar = |nodes| ElasticMember {
        nodes,
        kind: MemberKind::Bar,
        ea: 2e5,
        rest_length: 1.0,
    };
    let string = |nodes: [usize; 2]| ElasticMember {
        nodes,
        kind: MemberKind::String,
        ea: 500.0 * 0.6,
        rest_length: 0.6,
    };
    let model = ElasticModel {
        nodes,
        members: vec![
            bar([0, 1]),
            bar([2, 3]),
            string([0, 2]),
            string([2, 1]),
            string([1, 3]),
            string([3, 0]),
        ],
        clusters: Vec::new(),
        supports: vec![],
        load: vec![Vector3::zeros(); 4],
        drivers: Default::default(),
    };
    let masses = Masses {
        members: vec![1.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        nodes: vec![0.0; 4],
        distribution: MassDistribution::Lumped,
    };
    let d = ElasticDynamics::new(model, masses, vec![], None, &v)
        .unwrap()
        .with_rigid_bars(&[1])
        .unwrap();
    let l_rigid = (0.15_f64 * 0.15 + 1.0 + 0.4 * 0.4).sqrt();
    let t_end = 0.05;
    for (kind, dt, limit) in [
        (IntegratorKind::Newmark, 1e-4, 2e-6),
        (IntegratorKind::Rk4, 2e-5, 1e-9),
    ] {
        let mut s = settings(kind, dt, t_end);
        s.output_interval = Some(dt);
        s.quantities = Quantities {
            nodes: true,
            member_forces: true,
            ..Default::default()
        };
        let mut samples = Vec::<Sample>::new();
        let r = d.run(&s, &mut samples).unwrap();
        let (mut rigid, mut lo, mut hi) = (0.0_f64, f64::INFINITY, 0.0_f64);
        for smp in &samples {
            let x = smp.nodes.as_ref().unwrap();
            rigid = rigid.max(((x[3] - x[2]).norm() - l_rigid).abs() / l_rigid);
            let l = (x[1] - x[0]).norm();
            (lo, hi) = (lo.min(l), hi.max(l));
            let f = smp.member_forces.as_ref().unwrap();
            assert!(f.iter().all(|f| f.is_finite()));
        }
        println!(
            "{kind}: energy drift {:e}, rigid length {rigid:e}, elastic length {lo}..{hi}",
            r.energy_drift
        );
        assert!(r.energy_drift < limit, "{kind}: {}", r.energy_drift);
        assert!(rigid < 1e-12, "{kind}: {rigid:e}");
        assert!(
            hi - lo > 1e-3,
            "{kind}: the elastic bar oscillates: {lo}..{hi}"
        );
        // the rigid bar is in compression (the strings pull its ends together)
        let f = samples.last().unwrap().member_forces.as_ref().unwrap();
        assert!(f[1] < 0.0, "{kind}: rigid bar force {}", f[1]);
    }
    // RK4's limit counts the elastic bar alone: its axial mode, ends of m/2 on EA/L,
    // ω = √(4 EA/(m L)) = 894 rad/s (the strings add little)
    let omega = d.highest_frequency();
    let axial = (4.0 * 2e5_f64).sqrt();
    assert!(
        (omega - axial).abs() < 0.02 * axial,
        "{omega} against {axial}"
    );
}

/// A rigid bar of zero length, a string made rigid, a rigid bar stretched by its initial
/// velocities: errors that name the member.
#[test]
fn a_rigid_bar_that_cannot_be_is_an_error_naming_it() {
    // a scene's zero-length bar is refused with the structure, naming it
    let e = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .bar(Bar::new(1, 2).mass(1.0))
        .build()
        .unwrap_err();
    assert!(e.to_string().starts_with("bar 1: has zero length"), "{e}");
    // a model's, by the rigid bars
    let model = ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::x(), Vector3::x()],
        members: vec![ElasticMember {
            nodes: [1, 2],
            kind: MemberKind::Bar,
            ea: 1.0,
            rest_length: 1.0,
        }],
        clusters: Vec::new(),
        supports: vec![Support::pinned(0)],
        load: vec![Vector3::zeros(); 3],
        drivers: Default::default(),
    };
    let masses = Masses {
        members: vec![1.0],
        nodes: vec![0.0; 3],
        distribution: MassDistribution::Lumped,
    };
    let e = ElasticDynamics::new(model, masses, vec![], None, &[])
        .unwrap()
        .with_rigid_bars(&[0])
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "member 0 (bar): a rigid bar of length 0 m: its two nodes must be apart"
    );
    let model = ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::x()],
        members: vec![ElasticMember {
            nodes: [0, 1],
            kind: MemberKind::String,
            ea: 1.0,
            rest_length: 1.0,
        }],
        clusters: Vec::new(),
        supports: vec![Support::pinned(0)],
        load: vec![Vector3::zeros(); 2],
        drivers: Default::default(),
    };
    let masses = Masses {
        members: vec![1.0],
        nodes: vec![0.0; 2],
        distribution: MassDistribution::Lumped,
    };
    let e = ElasticDynamics::new(model.clone(), masses.clone(), vec![], None, &[])
        .unwrap()
        .with_rigid_bars(&[0])
        .unwrap_err();
    assert_eq!(e.to_string(), "member 0 (string): only a bar can be rigid");
    let mut model = model;
    model.members[0].kind = MemberKind::Bar;
    let v = [Vector3::zeros(), Vector3::new(0.1, 0.0, 0.0)];
    let e = ElasticDynamics::new(model, masses, vec![], None, &v)
        .unwrap()
        .with_rigid_bars(&[0])
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("bar 0: a rigid bar whose initial velocities stretch it at 1e-1 m/s"),
        "{e}"
    );
}

/// A rigid bar beside a stiff steel column (EA/L₀ = 1.6·10¹¹ N/m) and a soft string: the
/// rigid bar's unread EA takes the stiffest elastic member's EA/L₀, so it sets no stiffness
/// ratio (a placeholder of 1 N made the model 10¹¹ apart and refused it).
#[test]
fn a_rigid_bar_beside_a_stiff_column_sets_no_stiffness_ratio() {
    use tensegrity_core::Material;
    let s = Structure::builder()
        .material("steel", Material::new(7850.0, 200e9, 250e6))
        .nodes([
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
        ])
        .bar(Bar::new(0, 1).material("steel").radius(0.5).mass(1.0))
        .bar(Bar::new(1, 2).mass(1.0))
        .string(StringMember::new(2, 3).stiffness(100.0))
        .build()
        .unwrap();
    let m = ElasticModel::from_structure_mixed(&s, &[false, true]).unwrap();
    let column = 200e9 * std::f64::consts::PI * 0.25;
    assert!((m.members[0].ea - column).abs() < 1e-6 * column);
    assert!((m.members[1].ea / m.members[1].rest_length - column).abs() < 1e-6 * column);
}
