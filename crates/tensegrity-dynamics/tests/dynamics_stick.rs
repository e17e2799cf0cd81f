//! Friction that sticks ([`GroundModel::Stick`]) and the IMEX integrator: a bar on a slope
//! below atan μ_s rests at the closed-form spring stretch with zero creep (the regularised law
//! creeps), above it slides with the kinetic-friction acceleration g(sin φ − μ_k cos φ); IMEX
//! agrees with RK4 at a small step on a bar dropped onto the stick ground, and the contact work
//! it reports closes its energy budget where the trapezoidal rule over the samples does not.

use nalgebra::Vector3;
use tensegrity_core::{Bar, Structure};
use tensegrity_dynamics::{Ground, GroundModel, IntegratorKind, Simulation, SimulationSettings};

const G: f64 = 9.81;
const MASS: f64 = 2.0;
const K: f64 = 1e5;
const MU_S: f64 = 0.5;
const MU_K: f64 = 0.4;

/// A 1 m bar of 2 kg lying across a slope of angle `phi` (the plane z = 0 with gravity tilted
/// towards +y), its ends `lift` above the plane.
fn bar_on_slope(phi: f64, lift: f64) -> Structure {
    Structure::builder()
        .nodes([[-0.5, 0.0, lift], [0.5, 0.0, lift]])
        .bar(Bar::new(0, 1).mass(MASS))
        .gravity([0.0, G * phi.sin(), -G * phi.cos()])
        .build()
        .unwrap()
}

fn stick() -> GroundModel {
    GroundModel::Stick {
        stiffness: K,
        damping: 400.0,
        mu_static: MU_S,
        mu_kinetic: MU_K,
        tangential_stiffness: K,
        tangential_damping: 400.0,
    }
}

/// The penalty ground with regularised Coulomb friction (v_reg = 1 mm/s) and normal damping
/// `damping` (N·s/m).
fn penalty(damping: f64) -> GroundModel {
    GroundModel::Penalty {
        stiffness: K,
        damping,
        mu_static: MU_S,
        mu_kinetic: MU_K,
        regularization_velocity: 1e-3,
        stribeck_velocity: 1e-2,
    }
}

fn run(
    s: &Structure,
    ground: GroundModel,
    integrator: IntegratorKind,
    dt: f64,
    t_end: f64,
) -> Vec<Vector3<f64>> {
    let settings = SimulationSettings {
        t_end,
        dt,
        integrator,
        project: true,
        ..Default::default()
    };
    let mut sim = Simulation::new(s, settings).unwrap();
    sim.model
        .set_ground(Ground::new(Vector3::zeros(), Vector3::z(), ground))
        .unwrap();
    sim.run().unwrap().final_nodes
}

/// Static penetration of each end: half the weight's normal part over k.
fn static_lift(phi: f64) -> f64 {
    -MASS * G * phi.cos() / (2.0 * K)
}

#[test]
fn a_bar_on_a_slope_below_atan_mu_rests_at_the_spring_stretch_without_creep() {
    let phi = 20f64.to_radians(); // tan φ = 0.36 < μ_s = 0.5
    let s = bar_on_slope(phi, static_lift(phi));
    let at1 = run(&s, stick(), IntegratorKind::Rk4, 1e-4, 1.0);
    let at2 = run(&s, stick(), IntegratorKind::Rk4, 1e-4, 2.0);
    // closed form: each end's spring carries half of m g sin φ, so it rests at the stretch
    // m g sin φ / (2 k_t) downhill of where it touched
    let stretch = MASS * G * phi.sin() / (2.0 * K);
    for (a, b) in at1.iter().zip(&at2) {
        assert!(
            (b.y - stretch).abs() < 0.02 * stretch,
            "{} vs {stretch}",
            b.y
        );
        // no creep: not a nanometre more in the second second
        assert!((b.y - a.y).abs() < 1e-9, "creep {:e} m", b.y - a.y);
    }
    // the regularised Coulomb law cannot hold it: it creeps at v_reg artanh(tan φ / μ_s)
    let penalty = penalty(400.0);
    let p1 = run(&s, penalty, IntegratorKind::Rk4, 1e-4, 1.0);
    let p2 = run(&s, penalty, IntegratorKind::Rk4, 1e-4, 2.0);
    let creep = p2[0].y - p1[0].y;
    let expected = 1e-3 * (phi.tan() / MU_S).atanh();
    assert!(
        (creep - expected).abs() < 0.05 * expected,
        "{creep} vs {expected}"
    );
}

#[test]
fn a_bar_on_a_slope_above_atan_mu_slides_with_kinetic_friction() {
    let phi = 35f64.to_radians(); // tan φ = 0.70 > μ_s = 0.5
    let s = bar_on_slope(phi, static_lift(phi));
    let (t1, t2) = (0.5, 1.0);
    let y1 = run(&s, stick(), IntegratorKind::Rk4, 1e-4, t1)[0].y;
    let y2 = run(&s, stick(), IntegratorKind::Rk4, 1e-4, t2)[0].y;
    let y3 = run(&s, stick(), IntegratorKind::Rk4, 1e-4, 1.5)[0].y;
    // constant acceleration a: second difference of equally spaced positions = a Δt²
    let a = (y3 - 2.0 * y2 + y1) / (0.5 * 0.5);
    let closed = G * (phi.sin() - MU_K * phi.cos());
    assert!((a - closed).abs() < 1e-3 * closed, "{a} vs {closed}");
}

/// A tilted bar falling 5 cm onto a 20° slope: impact, stick, rocking, rest.
fn tilted_bar_above_a_slope() -> Structure {
    let phi = 20f64.to_radians();
    Structure::builder()
        .nodes([[-0.5, -0.1, 0.05], [0.5, 0.1, 0.25]])
        .bar(Bar::new(0, 1).mass(MASS))
        .gravity([0.0, G * phi.sin(), -G * phi.cos()])
        .build()
        .unwrap()
}

#[test]
fn imex_agrees_with_rk4_at_a_small_step_on_a_bar_dropped_on_the_stick_ground() {
    let s = tilted_bar_above_a_slope();
    let reference = run(&s, stick(), IntegratorKind::Rk4, 1e-5, 0.6);
    let error = |dt: f64| {
        let imex = run(&s, stick(), IntegratorKind::Imex, dt, 0.6);
        imex.iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max)
    };
    let (fine, coarse) = (error(1e-4), error(5e-4));
    eprintln!("imex error {fine:e} (dt 1e-4), {coarse:e} (dt 5e-4)");
    assert!(fine < 1e-3 && coarse < 5e-3, "{fine:e} {coarse:e}");
    assert!(fine < coarse);
    assert_eq!(
        "imex".parse::<IntegratorKind>().unwrap(),
        IntegratorKind::Imex
    );
    assert_eq!(IntegratorKind::Imex.to_string(), "imex");
}

/// The energy budget E(t) − E(0) = W_nc(t) of IMEX runs, with W_nc the contact work the
/// integrator reports (`Sample::contact_work`: the exact kinetic-energy change of its
/// implicit contact substeps), and the same budget with W_nc from the trapezoidal rule over
/// the samples' contact forces and velocities (what a sink computes for an explicit method).
/// Returns (reported, trapezoid) residuals relative to m g L.
fn imex_budget(ground: GroundModel, dt: f64) -> (f64, f64) {
    imex_budget_with(IntegratorKind::Imex, ground, dt)
}

/// [`imex_budget`] under `integrator`.
fn imex_budget_with(integrator: IntegratorKind, ground: GroundModel, dt: f64) -> (f64, f64) {
    let s = tilted_bar_above_a_slope();
    let settings = SimulationSettings {
        t_end: 0.6,
        dt,
        integrator,
        project: true,
        output_interval: Some(dt),
        quantities: tensegrity_dynamics::Quantities {
            nodes: true,
            velocities: true,
            energy: true,
            contact_forces: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let mut sim = Simulation::new(&s, settings).unwrap();
    sim.model
        .set_ground(Ground::new(Vector3::zeros(), Vector3::z(), ground))
        .unwrap();
    let samples = sim.run().unwrap().samples;
    let e0 = samples[0].energy.unwrap().1;
    let power = |smp: &tensegrity_dynamics::Sample| -> f64 {
        let (x, v) = (
            smp.nodes.as_ref().unwrap(),
            smp.velocities.as_ref().unwrap(),
        );
        smp.contact_forces
            .iter()
            .flatten()
            .map(|&(i, f)| f.dot(&v[i]) - K * (-x[i].z).max(0.0) * v[i].z)
            .sum()
    };
    let (mut trapezoid, mut worst_reported, mut worst_trapezoid) = (0.0, 0.0_f64, 0.0_f64);
    for pair in samples.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        trapezoid += 0.5 * (b.t - a.t) * (power(a) + power(b));
        let change = b.energy.unwrap().1 - e0;
        let (wn, wt) = b
            .contact_work
            .expect("the integrator reports its contact work");
        worst_reported = worst_reported.max((change - wn - wt).abs());
        worst_trapezoid = worst_trapezoid.max((change - trapezoid).abs());
    }
    let scale = MASS * G * 1.0;
    (worst_reported / scale, worst_trapezoid / scale)
}

#[test]
fn imex_reports_the_contact_work_that_closes_its_energy_budget() {
    let penalty = penalty(2000.0);
    for (name, ground) in [("penalty", penalty), ("stick", stick())] {
        let (coarse, trapezoid) = imex_budget(ground, 5e-4);
        let (fine, _) = imex_budget(ground, 2.5e-4);
        eprintln!("{name}: reported {coarse:e} (5e-4), {fine:e} (2.5e-4); trapezoid {trapezoid:e}");
        // measured: penalty 1.8e-4, 2.9e-5, trapezoid 2.7e-2; stick 1.4e-4, 6.4e-6, 4.8e-3
        assert!(coarse < 1e-3, "{name}: {coarse:e}");
        assert!(fine < coarse / 2.0, "{name}: {fine:e} against {coarse:e}");
        assert!(trapezoid > 10.0 * coarse, "{name}: {trapezoid:e}");
    }
}

/// The regularised Coulomb law's creep on a slope below atan μ_s is a motion slaved to the
/// friction (velocity v_reg artanh(tan φ / μ_s), where friction balances gravity), and its
/// viscous slope μ f_n / v_reg is stiff: at 5·10⁻⁴ s on a 0.5 kg bar end, c h / m ≈ 4.6. IMEX
/// follows it because A holds the step's starting friction (a splitting with A free of it
/// overshoots the slaved motion by c h / 2m in every step).
#[test]
fn imex_follows_the_slaved_creep_of_the_regularised_friction() {
    let phi = 20f64.to_radians();
    let s = bar_on_slope(phi, static_lift(phi));
    let penalty = penalty(400.0);
    let expected = 1e-3 * (phi.tan() / MU_S).atanh();
    for dt in [2.5e-4, 5e-4] {
        let p1 = run(&s, penalty, IntegratorKind::Imex, dt, 1.0);
        let p2 = run(&s, penalty, IntegratorKind::Imex, dt, 2.0);
        let creep = p2[0].y - p1[0].y;
        eprintln!("dt {dt:e}: creep {creep:e} against {expected:e}");
        assert!(
            (creep - expected).abs() < 0.02 * expected,
            "dt {dt:e}: {creep} vs {expected}"
        );
    }
}

/// The deepest an end of a level bar, dropped 5 cm onto a flat penalty ground with normal
/// damping `damping`, sinks into it within 0.3 s.
fn deepest_penetration(integrator: IntegratorKind, dt: f64, damping: f64) -> f64 {
    let s = bar_on_slope(0.0, 0.05);
    let settings = SimulationSettings {
        t_end: 0.3,
        dt,
        integrator,
        project: true,
        output_interval: Some(dt),
        quantities: tensegrity_dynamics::Quantities {
            nodes: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let mut sim = Simulation::new(&s, settings).unwrap();
    sim.model
        .set_ground(Ground::new(
            Vector3::zeros(),
            Vector3::z(),
            penalty(damping),
        ))
        .unwrap();
    let samples = sim.run().unwrap().samples;
    samples
        .iter()
        .flat_map(|smp| smp.nodes.as_ref().unwrap().iter().map(|p| -p.z))
        .fold(0.0, f64::max)
}

/// A node that lands inside a step still moves at its impact speed at the next step's start.
/// Holding its damping force −c v through A there (module docs of `dynamics::imex`, "The held
/// force at a landing") gives it an impulse of about c h v against its momentum m v (c h / m =
/// 2 at 5·10⁻⁴ s on this overdamped ground, ζ = c / 2√(k m) ≈ 6) and stops it early. IMEX
/// holds no force for a node that has just landed, and B damps the landing implicitly. The
/// landing stays first order in h (the node's damping time m/c = 2.5·10⁻⁴ s is not resolved).
/// Measured deepest penetration against RK4's 2.42·10⁻⁴ m: 2.34, 1.87, 1.44·10⁻⁴ m at
/// h = 10⁻⁴, 2.5·10⁻⁴, 5·10⁻⁴ s; holding the force at the landing, 2.31, 1.58, 0.98·10⁻⁴ m.
#[test]
fn imex_damps_a_landing_on_an_overdamped_ground_without_a_held_impulse() {
    let damping = 4000.0;
    let reference = deepest_penetration(IntegratorKind::Rk4, 1e-5, damping);
    eprintln!("RK4 1e-5: deepest penetration {reference:e} m");
    // the end stops where the damper has taken its momentum: δ ≈ m v / c = 1 · 0.99 / 4000
    assert!((reference - 2.5e-4).abs() < 0.1 * 2.5e-4, "{reference:e}");
    let mut previous = 0.0;
    for (dt, tolerance) in [(1e-4, 0.05), (2.5e-4, 0.3), (5e-4, 0.5)] {
        let imex = deepest_penetration(IntegratorKind::Imex, dt, damping);
        let error = (imex - reference).abs() / reference;
        eprintln!("IMEX {dt:e}: deepest penetration {imex:e} m, relative error {error:.3}");
        assert!(
            error < tolerance,
            "dt {dt:e}: {imex:e} m against RK4's {reference:e} m"
        );
        assert!(error > previous, "the error grows with the step");
        previous = error;
    }
}

/// The slaved creep at steps up to 8× the split IMEX's default: IMEX-ARK's implicit stages
/// see the explicit forces, so the creep is each stage's solution at any step; the split's
/// held force chatters at 4·10⁻³ s (measured: ARK within 2.9·10⁻³ of the closed form at
/// 5·10⁻⁴ … 4·10⁻³ s, the split 8.6× too fast at 4·10⁻³ s). The 2.9·10⁻³ is the model's
/// own (its Stribeck weakening at the creep speed), the same for both at small steps.
#[test]
fn imex_ark_follows_the_slaved_creep_at_steps_where_the_split_chatters() {
    let phi = 20f64.to_radians();
    let s = bar_on_slope(phi, static_lift(phi));
    let penalty = penalty(400.0);
    let expected = 1e-3 * (phi.tan() / MU_S).atanh();
    let creep = |integrator, dt| {
        let p1 = run(&s, penalty, integrator, dt, 1.0);
        let p2 = run(&s, penalty, integrator, dt, 2.0);
        p2[0].y - p1[0].y
    };
    for dt in [5e-4, 2e-3, 4e-3] {
        let c = creep(IntegratorKind::ImexArk, dt);
        eprintln!("imex-ark dt {dt:e}: creep {c:e} against {expected:e}");
        assert!(
            (c - expected).abs() < 5e-3 * expected,
            "dt {dt:e}: {c} vs {expected}"
        );
    }
    let split = creep(IntegratorKind::Imex, 4e-3);
    assert!(
        (split - expected).abs() > expected,
        "split at 4e-3 s: {split}"
    );
}

/// IMEX-ARK counts the implicit forces' work as each node's impulse over the step times its
/// mean velocity: the budget it reports closes where the samples' trapezoid does not
/// (measured: penalty ground damped at 2000 N s/m 3.1·10⁻⁴ at 5·10⁻⁴ s, 1.2·10⁻⁴ at
/// 2.5·10⁻⁴ s, trapezoid 1.0·10⁻¹; stick 1.2·10⁻³, 2.7·10⁻⁴, 3.0·10⁻²). The quadrature of
/// the stages' powers F̃·u with the weights b, tried first, missed it by 1.8·10⁻² and
/// 2.8·10⁻² on the damped ground: the damper's power is not resolved within a step.
#[test]
fn imex_ark_reports_the_contact_work_that_closes_its_energy_budget() {
    for (name, ground) in [("penalty", penalty(2000.0)), ("stick", stick())] {
        let (coarse, trapezoid) = imex_budget_with(IntegratorKind::ImexArk, ground, 5e-4);
        let (fine, _) = imex_budget_with(IntegratorKind::ImexArk, ground, 2.5e-4);
        eprintln!("{name}: reported {coarse:e} (5e-4), {fine:e} (2.5e-4); trapezoid {trapezoid:e}");
        assert!(coarse < 5e-3, "{name}: {coarse:e}");
        assert!(fine < coarse / 2.0, "{name}: {fine:e} against {coarse:e}");
        assert!(trapezoid > 5.0 * coarse, "{name}: {trapezoid:e}");
    }
}

#[test]
fn imex_ark_is_named_imex_ark() {
    assert_eq!(IntegratorKind::ImexArk.to_string(), "imex-ark");
    for name in ["imex-ark", "IMEX-ARK", "ark"] {
        assert_eq!(name.parse::<IntegratorKind>(), Ok(IntegratorKind::ImexArk));
    }
    assert!(!IntegratorKind::ImexArk.is_adaptive());
    let json = serde_json::to_string(&IntegratorKind::ImexArk).unwrap();
    assert_eq!(json, "\"imex-ark\"");
    // the front ends' choices are the names that parse and print back
    for name in IntegratorKind::NAMES {
        let kind: IntegratorKind = name.parse().unwrap();
        assert_eq!(kind.to_string(), *name);
        assert_eq!(serde_json::to_string(&kind).unwrap(), format!("\"{name}\""));
    }
}
