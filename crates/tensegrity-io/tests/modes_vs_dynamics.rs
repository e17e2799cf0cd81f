//! Two independent methods: the lowest elastic mode of the prestressed Snelson prism from the
//! linear modal analysis (tangent stiffness, consistent rigid-bar mass) against the period of
//! small free oscillations along that mode in the nonlinear rigid-bar dynamics.

use nalgebra::Vector3;
use std::path::Path;
use tensegrity_dynamics::{IntegratorKind, Quantities, Simulation, SimulationSettings};
use tensegrity_io::scene::Scene;
use tensegrity_statics::stiffness::{self, MassModel};

#[test]
fn modal_frequency_matches_the_period_of_small_oscillations() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/prism.toml");
    let s = Scene::from_path(&path).unwrap().structure;
    let (q, residual) = stiffness::equilibrium_force_densities(&s).unwrap();
    assert!(
        residual < 1e-5,
        "the scene's rest lengths realise a self-stress"
    );
    let modes = stiffness::modal_analysis_with(&s, &q, MassModel::Consistent).unwrap();
    // six rigid-body modes, then the prestress-stiffened mechanism
    assert!(modes.eigenvalues[..6]
        .iter()
        .all(|w| w.abs() < 1e-6 * modes.eigenvalues[6]));
    let f = modes.frequencies_hz[6];
    let phi = modes.shapes.column(6);

    // start at equilibrium with a small velocity along the mode, bar-length rates removed
    let eps = 1e-4;
    let mut v: Vec<Vector3<f64>> = (0..s.n_nodes())
        .map(|i| Vector3::new(phi[3 * i], phi[3 * i + 1], phi[3 * i + 2]) * eps)
        .collect();
    for b in s.bars() {
        let [i, j] = b.nodes;
        let e = (s.nodes()[j] - s.nodes()[i]).normalize();
        let stretch = (v[j] - v[i]).dot(&e);
        v[i] += 0.5 * stretch * e;
        v[j] -= 0.5 * stretch * e;
    }
    let s = s
        .to_builder()
        .velocities(v.iter().map(|x| [x.x, x.y, x.z]))
        .build()
        .unwrap();
    let period = 1.0 / f;
    let settings = SimulationSettings {
        t_end: 3.0 * period,
        integrator: IntegratorKind::Rk45,
        rtol: 1e-11,
        atol: 1e-14,
        output_interval: Some(period / 200.0),
        quantities: Quantities::nodes(),
        ..Default::default()
    };
    let run = Simulation::new(&s, settings).unwrap().run().unwrap();
    // modal coordinate η(t) = φ · (x(t) − x₀) (φ is M-orthonormal; the projection is enough
    // to time the zero crossings)
    let x0 = s.nodes();
    let eta: Vec<(f64, f64)> = run
        .samples
        .iter()
        .map(|smp| {
            let x = smp.nodes.as_ref().unwrap();
            let d: f64 = (0..x.len())
                .map(|i| {
                    let dx = x[i] - x0[i];
                    dx.x * phi[3 * i] + dx.y * phi[3 * i + 1] + dx.z * phi[3 * i + 2]
                })
                .sum();
            (smp.t, d)
        })
        .collect();
    // downward zero crossings, by linear interpolation
    let crossings: Vec<f64> = eta
        .windows(2)
        .filter(|w| w[0].1 > 0.0 && w[1].1 <= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * w[0].1 / (w[0].1 - w[1].1))
        .collect();
    assert!(crossings.len() >= 2, "{crossings:?}");
    let measured = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    assert!(
        ((measured - period) / period).abs() < 1e-5,
        "period {measured} s from the dynamics vs {period} s from the modes"
    );
}
