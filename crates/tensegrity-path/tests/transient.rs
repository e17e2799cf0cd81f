//! The elastic dynamics (`tensegrity_path::transient`) against closed forms: a mass on an
//! axial spring (undamped and damped oscillators), the axial frequencies of a free bar under
//! the lumped and consistent mass matrices, a string that goes slack in flight, and the
//! errors of a model that cannot run.

use nalgebra::Vector3;
use tensegrity_dynamics::{IntegratorKind, Sample, SimulationSettings};
use tensegrity_path::transient::{ElasticDynamics, RK4_STABILITY};
use tensegrity_path::{ElasticMember, ElasticModel, MassDistribution, Masses, MemberKind, Support};

/// Node 0 pinned, node 1 (mass `m`) on the member along x, held in y and z; the member's
/// rest length 1 m, its end started at 1 + `stretch`.
fn oscillator(kind: MemberKind, ea: f64, m: f64, c: f64, stretch: f64) -> ElasticDynamics {
    let model = ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::new(1.0 + stretch, 0.0, 0.0)],
        members: vec![ElasticMember {
            nodes: [0, 1],
            kind,
            ea,
            rest_length: 1.0,
        }],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support::along(1, vec![Vector3::y(), Vector3::z()]),
        ],
        load: vec![Vector3::zeros(); 2],
        drivers: Default::default(),
    };
    let masses = Masses {
        members: vec![0.0],
        nodes: vec![0.0, m],
        distribution: MassDistribution::Lumped,
    };
    let damping = if c > 0.0 { vec![c] } else { vec![] };
    ElasticDynamics::new(model, masses, damping, None, &[]).unwrap()
}

fn run(d: &ElasticDynamics, kind: IntegratorKind, dt: f64, t_end: f64) -> Vec<Vector3<f64>> {
    let settings = SimulationSettings {
        t_end,
        integrator: kind,
        dt,
        ..Default::default()
    };
    d.run(&settings, &mut Vec::<Sample>::new())
        .unwrap()
        .final_nodes
}

/// x(t) = 1 + δ cos ω t, ω = √(EA/(L₀ m)); with a dashpot c, ζ = c/(2 m ω):
/// x − 1 = δ e^{−ζωt} (cos ω_d t + ζ/√(1−ζ²) sin ω_d t), ω_d = ω √(1 − ζ²).
#[test]
fn a_mass_on_a_spring_oscillates_at_the_closed_form_frequency() {
    let (ea, m, delta, t): (f64, f64, f64, f64) = (400.0, 1.0, 0.01, 1.3);
    let omega = (ea / m).sqrt();
    let d = oscillator(MemberKind::Bar, ea, m, 0.0, delta);
    assert!((d.highest_frequency() - omega).abs() < 1e-12 * omega);
    let exact = 1.0 + delta * (omega * t).cos();
    let x = run(&d, IntegratorKind::Rk4, 1e-4, t)[1].x;
    // RK4's phase error (ωh)⁵/120 per step: 6e-13 at ωh = 2e-3
    assert!((x - exact).abs() < 1e-11, "{x} against {exact}");
    // Newmark (the trapezoidal rule): the phase lags by (ωh)²/12 per radian
    let x = run(&d, IntegratorKind::Newmark, 1e-3, t)[1].x;
    let lag = (omega * 1e-3).powi(2) / 12.0 * omega * t;
    let expected = 1.0 + delta * (omega * t * (1.0 - (omega * 1e-3).powi(2) / 12.0)).cos();
    assert!(
        (x - expected).abs() < 1e-7 * delta.max(lag),
        "{x} against {expected}"
    );
    // damped
    let c = 4.0;
    let zeta = c / (2.0 * m * omega);
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let d = oscillator(MemberKind::Bar, ea, m, c, delta);
    let exact = 1.0
        + delta
            * (-zeta * omega * t).exp()
            * ((wd * t).cos() + zeta / (1.0 - zeta * zeta).sqrt() * (wd * t).sin());
    let x = run(&d, IntegratorKind::Rk4, 1e-4, t)[1].x;
    assert!((x - exact).abs() < 1e-11, "damped: {x} against {exact}");
}

/// A point mass on an elastic support (no member): ω = √(k/m), along the spring's skew
/// direction only.
#[test]
fn a_mass_on_an_elastic_support_oscillates_at_the_closed_form() {
    let (k, m, t): (f64, f64, f64) = (900.0, 4.0, 0.7);
    let d = Vector3::new(1.0, 1.0, 0.0).normalize();
    let model = ElasticModel {
        nodes: vec![Vector3::zeros()],
        members: vec![],
        // held rigidly across the spring's direction, on the spring along it
        clusters: Vec::new(),
        supports: vec![
            Support::along(
                0,
                vec![Vector3::new(1.0, -1.0, 0.0).normalize(), Vector3::z()],
            ),
            Support::along(0, vec![d]).elastic(k),
        ],
        load: vec![Vector3::zeros()],
        drivers: Default::default(),
    };
    let masses = Masses {
        members: vec![],
        nodes: vec![m],
        distribution: MassDistribution::Lumped,
    };
    let v0 = [d * 0.3];
    let dynamics = ElasticDynamics::new(model, masses, vec![], None, &v0).unwrap();
    let omega = (k / m).sqrt();
    assert!((dynamics.highest_frequency() - omega).abs() < 1e-12 * omega);
    let x = run(&dynamics, IntegratorKind::Rk4, 1e-4, t)[0];
    // u(t) = (v₀/ω) sin ω t along d
    let exact = 0.3 / omega * (omega * t).sin();
    assert!(
        (x.dot(&d) - exact).abs() < 1e-11,
        "{} against {exact}",
        x.dot(&d)
    );
    assert!(x.dot(&Vector3::new(1.0, -1.0, 0.0)).abs() < 1e-15 && x.z == 0.0);
}

/// A free bar's axial frequency: √(12 EA/(m L)) with the consistent mass matrix, √(4 EA/(m L))
/// lumped (one element's eigenvalues).
#[test]
fn a_free_bars_axial_frequency_is_the_closed_forms() {
    let (ea, m) = (1e6, 2.0);
    for (distribution, factor) in [
        (MassDistribution::Consistent, 12.0),
        (MassDistribution::Lumped, 4.0),
    ] {
        let model = ElasticModel {
            nodes: vec![Vector3::zeros(), Vector3::x()],
            members: vec![ElasticMember {
                nodes: [0, 1],
                kind: MemberKind::Bar,
                ea,
                rest_length: 1.0,
            }],
            clusters: Vec::new(),
            supports: vec![],
            load: vec![Vector3::zeros(); 2],
            drivers: Default::default(),
        };
        let masses = Masses {
            members: vec![m],
            nodes: vec![0.0; 2],
            distribution,
        };
        let d = ElasticDynamics::new(model, masses, vec![], None, &[]).unwrap();
        let omega = (factor * ea / m).sqrt();
        let w = d.highest_frequency();
        assert!(
            (w - omega).abs() < 1e-9 * omega,
            "{distribution:?}: {w} against {omega}"
        );
        // both distributions carry the same momentum and kinetic energy for a uniform motion
        let v = vec![Vector3::new(1.0, 2.0, 0.0); 2];
        let t = d.masses().kinetic_energy(d.model(), &v);
        assert!((t - 0.5 * m * 5.0).abs() < 1e-12);
    }
}

/// A mass thrown toward the anchor of a string: the string goes slack at once and the mass
/// flies at constant speed until the string is taut again; the energy is kept through the
/// kinks of the force.
#[test]
fn a_slack_string_carries_nothing_in_flight() {
    let d = oscillator(MemberKind::String, 100.0, 1.0, 0.0, -0.2);
    // started slack at rest: nothing moves
    let x = run(&d, IntegratorKind::Rk4, 1e-3, 1.0)[1].x;
    assert_eq!(x, 0.8);
    // started stretched: it swings through the slack range at the speed it left it with
    let d = oscillator(MemberKind::String, 100.0, 1.0, 0.0, 0.05);
    let settings = SimulationSettings {
        t_end: 2.0,
        integrator: IntegratorKind::Rk45,
        dt: 1e-2,
        rtol: 1e-10,
        atol: 1e-12,
        ..Default::default()
    };
    let r = d.run(&settings, &mut Vec::<Sample>::new()).unwrap();
    // ½ k δ² = ½ m v²: the speed in flight is δ √(k/m) = 0.5 m/s, and the energy is kept
    assert!(r.energy_drift < 1e-7, "{}", r.energy_drift);
    let e = d.energy(&r.final_state);
    assert!(
        (e.total() - 0.5 * 100.0 * 0.05 * 0.05).abs() < 1e-8,
        "{e:?}"
    );
}

#[test]
fn models_that_cannot_run_are_refused_naming_the_item() {
    // a free node with no mass
    let model = ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::x()],
        members: vec![ElasticMember {
            nodes: [0, 1],
            kind: MemberKind::String,
            ea: 100.0,
            rest_length: 1.0,
        }],
        clusters: Vec::new(),
        supports: vec![Support::pinned(0)],
        load: vec![Vector3::zeros(); 2],
        drivers: Default::default(),
    };
    let masses = |nodes: Vec<f64>| Masses {
        members: vec![0.0],
        nodes,
        distribution: MassDistribution::Lumped,
    };
    let e =
        ElasticDynamics::new(model.clone(), masses(vec![0.0, 0.0]), vec![], None, &[]).unwrap_err();
    assert!(e.to_string().starts_with("node 1: it moves"), "{e}");
    let e = ElasticDynamics::new(model.clone(), masses(vec![0.0, -1.0]), vec![], None, &[])
        .unwrap_err();
    assert!(e.to_string().starts_with("node 1: point mass -1"), "{e}");
    // a velocity along a support
    let v = vec![Vector3::x(), Vector3::zeros()];
    let e =
        ElasticDynamics::new(model.clone(), masses(vec![0.0, 1.0]), vec![], None, &v).unwrap_err();
    assert!(
        e.to_string().starts_with("node 0: its initial velocity"),
        "{e}"
    );
    // RK4 above its limit, an integrator of rigid bars
    let d = ElasticDynamics::new(model, masses(vec![0.0, 1.0]), vec![], None, &[]).unwrap();
    let limit = RK4_STABILITY / d.highest_frequency();
    for (kind, dt, says) in [
        (
            IntegratorKind::Rk4,
            1.5 * limit,
            "exceeds its stability limit",
        ),
        (
            IntegratorKind::Rattle,
            1e-3,
            "integrated by rk4, rk45 or newmark",
        ),
    ] {
        let settings = SimulationSettings {
            t_end: 1.0,
            integrator: kind,
            dt,
            ..Default::default()
        };
        let e = d.run(&settings, &mut Vec::<Sample>::new()).unwrap_err();
        assert!(e.to_string().contains(says), "{e}");
    }
}
