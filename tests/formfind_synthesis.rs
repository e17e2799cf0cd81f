//! Rest-length synthesis and dynamic relaxation: the synthesized structure is in
//! equilibrium at t = 0 (statics and dynamics agree), and dynamic relaxation from the
//! synthesized rest lengths returns to the force density method's geometry.

use formfind::{
    builtin, form_find, rest_lengths, synthesize, FormFound, Method, Settings, Synthesis, Topology,
};
use nalgebra::{Matrix3, Vector3};
use tensegrity_dynamics::{Simulation, SimulationSettings};
use tensegrity_statics::{backend, StaticsSettings};

fn fdm(t: &Topology) -> FormFound {
    form_find(
        t,
        &Settings {
            method: Method::Fdm,
            analyse: true,
            ..Settings::default()
        },
    )
    .unwrap()
}

/// The largest distance between `a` and the best rigid motion (and, with `scale`, uniform
/// scaling) of `b` onto it (Kabsch), relative to the size of `a`.
fn aligned_distance(a: &[Vector3<f64>], b: &[Vector3<f64>], scale: bool) -> f64 {
    let n = a.len() as f64;
    let ca = a.iter().sum::<Vector3<f64>>() / n;
    let cb = b.iter().sum::<Vector3<f64>>() / n;
    let mut h = Matrix3::zeros();
    for (p, q) in a.iter().zip(b) {
        h += (q - cb) * (p - ca).transpose();
    }
    let svd = h.svd(true, true);
    let (u, vt) = (svd.u.unwrap(), svd.v_t.unwrap());
    let mut d = Matrix3::identity();
    if (vt.transpose() * u.transpose()).determinant() < 0.0 {
        d[(2, 2)] = -1.0;
    }
    let r = vt.transpose() * d * u.transpose();
    let s = if scale {
        let num: f64 = a
            .iter()
            .zip(b)
            .map(|(p, q)| (p - ca).dot(&(r * (q - cb))))
            .sum();
        let den: f64 = b.iter().map(|q| (q - cb).norm_squared()).sum();
        num / den
    } else {
        1.0
    };
    let size = a.iter().map(|p| (p - ca).norm()).fold(0.0, f64::max);
    a.iter()
        .zip(b)
        .map(|(p, q)| ((p - ca) - s * r * (q - cb)).norm())
        .fold(0.0, f64::max)
        / size
}

#[test]
fn dynamic_relaxation_returns_to_the_force_density_form() {
    for name in ["prism:3", "prism:6", "octahedron", "tower:4:2", "grid:3"] {
        let t = builtin(name).unwrap();
        let found = fdm(&t);
        let syn = Synthesis {
            prestress: 100.0,
            stiffness: 1e4,
            bar_mass: 1.0,
        };
        let r = rest_lengths(&t, &found, &syn).unwrap();
        let mut dr = t.with_lengths(&r.rest_length, &r.stiffness);
        // Start from the found form, perturbed by up to 5 % of its size.
        let size = found.structure_size();
        let start: Vec<[f64; 3]> = found
            .nodes
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = 0.05 * size;
                let f = |k: usize| w * ((i * 7 + k * 13) as f64 * 0.37).sin();
                [p.x + f(0), p.y + f(1), p.z + f(2)]
            })
            .collect();
        dr.nodes = Some(start);
        let relaxed = form_find(
            &dr,
            &Settings {
                method: Method::Dr,
                tolerance: 1e-13,
                max_iterations: 200_000,
                analyse: true,
                ..Settings::default()
            },
        )
        .unwrap();
        assert_eq!(relaxed.method, Method::Dr);
        let d = aligned_distance(&found.nodes, &relaxed.nodes, false);
        assert!(d < 1e-8, "{name}: DR vs FDM geometry {d:e} (rigid motion)");
        let d = aligned_distance(&found.nodes, &relaxed.nodes, true);
        assert!(
            d < 1e-8,
            "{name}: DR vs FDM geometry {d:e} (rigid motion and scale)"
        );
        // Its force densities are the scaled self-stress.
        for (k, (qd, qf)) in relaxed
            .force_density
            .iter()
            .zip(&found.force_density)
            .enumerate()
        {
            assert!(
                (qd - r.scale * qf).abs() < 1e-6 * r.scale * qf.abs(),
                "{name}: member {k}: {qd} vs {}",
                r.scale * qf
            );
        }
        assert!(
            relaxed.prestressable == Some(true) && relaxed.prestress_stable == Some(true),
            "{name}"
        );
        assert_eq!(relaxed.self_stress_dim, found.self_stress_dim, "{name}");
    }
}

/// Runs 1 s of dynamics without loads or gravity and returns the largest node motion
/// relative to the structure's size.
fn motion_after_one_second(s: &tensegrity_core::Structure, size: f64) -> f64 {
    let settings = SimulationSettings {
        t_end: 1.0,
        dt: 1e-4,
        ..SimulationSettings::default()
    };
    let sim = Simulation::new(s, settings).unwrap();
    let r = sim.run().unwrap();
    r.final_nodes
        .iter()
        .zip(s.nodes())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
        / size
}

#[test]
fn synthesized_structures_start_in_equilibrium() {
    for name in ["prism:3", "prism:8", "octahedron", "tower:3:2"] {
        let t = builtin(name).unwrap();
        let found = fdm(&t);
        let syn = Synthesis::default();
        let s = synthesize(&t, &found, &syn).unwrap();
        // String tensions at t = 0: the scaled force densities, the largest = prestress.
        let r = rest_lengths(&t, &found, &syn).unwrap();
        let nb = t.bars.len();
        let mut max_t = 0.0f64;
        for (j, st) in s.strings().iter().enumerate() {
            let l = (s.nodes()[st.nodes[1]] - s.nodes()[st.nodes[0]]).norm();
            let k = st.stiffness.unwrap();
            let tension = k * (l - st.rest_length.unwrap());
            assert!((tension - r.tension[nb + j]).abs() < 1e-9 * syn.prestress);
            max_t = max_t.max(tension);
        }
        assert!((max_t - syn.prestress).abs() < 1e-9 * syn.prestress);
        // Statics: prestressable, the same self-stress dimension.
        let b = backend(&s, StaticsSettings::default()).unwrap();
        assert_eq!(Some(b.self_stress_dim()), found.self_stress_dim, "{name}");
        assert!(b.prestressability().unwrap().prestressable, "{name}");
        // Dynamics: nothing moves.
        let moved = motion_after_one_second(&s, found.structure_size());
        assert!(moved < 1e-9, "{name}: a node moved {moved:e} of the size");
    }
}

#[test]
fn synthesized_grid_with_fixed_boundary_starts_in_equilibrium() {
    for k in [2, 3] {
        let t = builtin(&format!("grid:{k}")).unwrap();
        let found = fdm(&t);
        let s = synthesize(&t, &found, &Synthesis::default()).unwrap();
        assert_eq!(s.supports().len(), t.fixed.len());
        let b = backend(&s, StaticsSettings::default()).unwrap();
        assert_eq!(Some(b.self_stress_dim()), found.self_stress_dim);
        assert!(b.prestressability().unwrap().prestressable);
        let moved = motion_after_one_second(&s, found.structure_size());
        assert!(moved < 1e-9, "a node moved {moved:e} of the size");
    }
}

#[test]
fn synthesis_refuses_what_it_cannot_realise() {
    let t = builtin("prism:4").unwrap();
    let found = fdm(&t);
    let bad = Synthesis {
        prestress: -1.0,
        ..Synthesis::default()
    };
    let e = synthesize(&t, &found, &bad).unwrap_err().to_string();
    assert!(e.contains("prestress"), "{e}");
    let crushed = Synthesis {
        prestress: 1e6,
        stiffness: 1e3,
        bar_mass: 1.0,
    };
    let e = synthesize(&t, &found, &crushed).unwrap_err().to_string();
    assert!(e.contains("bars["), "{e}");
    let mut slack = found.clone();
    slack.force_density[5] = 0.0;
    let e = synthesize(&t, &slack, &Synthesis::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("strings[1]"), "{e}");
}
