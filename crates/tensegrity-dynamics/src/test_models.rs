//! The test models of the dynamics: every structure of the core's `test_models` (re-exported)
//! and the grounds of its contact scenes ([`dropped_prism_ground`]).

pub use tensegrity_core::test_models::*;

use crate::{Ground, GroundModel};
use nalgebra::Vector3;

/// The penalty ground z = 0 of the dropped-prism scenes: stiffness `k` (N/m), normal damping
/// `damping` (N·s/m), μ_s = 0.6, μ_k = 0.5 and a soft regularisation (0.1 m/s, Stribeck
/// 0.2 m/s) so that the feet creep out of the tangential prestress and the prism really comes
/// to rest.
pub fn dropped_prism_ground(k: f64, damping: f64) -> Ground {
    Ground::new(
        Vector3::zeros(),
        Vector3::z(),
        GroundModel::Penalty {
            stiffness: k,
            damping,
            mu_static: 0.6,
            mu_kinetic: 0.5,
            regularization_velocity: 0.1,
            stribeck_velocity: 0.2,
        },
    )
}

/// A system identification problem with its answer (issue 47, item 5): a structure whose
/// parameters are to be recovered from a noisy measurement of its motion.
#[derive(Debug, Clone)]
pub struct IdentificationCase {
    /// The structure with the true values (for reference).
    pub truth: tensegrity_core::Structure,
    /// The structure with the start values: the identification's starting point.
    pub start: tensegrity_core::Structure,
    /// The parameters to identify.
    pub parameters: Vec<crate::sensitivity::DynamicsParameter>,
    /// Their true values.
    pub true_values: Vec<f64>,
    /// The observed nodes.
    pub observed: Vec<usize>,
    /// Their measured positions at each sample (sample 0 the start).
    pub measured: Vec<Vec<Vector3<f64>>>,
    /// The sampling of the measurement.
    pub settings: crate::identify::IdentifySettings,
    /// The noise's standard deviation (m).
    pub sigma: f64,
}

/// Gaussian noise of standard deviation `sigma` from a fixed linear congruential sequence
/// (Box–Muller): the same numbers on every machine.
pub fn gaussian_noise(sigma: f64, count: usize) -> Vec<f64> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let (u, v) = (uniform(), uniform());
            sigma * (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
        })
        .collect()
}

/// The six-bar icosahedron ([`six_bar`]: 1 kg bars, prestress 50 N/m) whose 24 strings each
/// have their own stiffness, 1000 N/m ± 20 %, and damping, 2 N s/m ± 30 % (a deterministic
/// spread), its bars set moving at 0.5 m/s each in its own direction; every node measured
/// every 2 ms over 0.4 s (RK4, dt = 1 ms) with Gaussian noise of `sigma` (m) per coordinate.
/// The start: every stiffness 1000 N/m and damping 2 N s/m.
pub fn six_bar_identification(sigma: f64) -> tensegrity_core::Result<IdentificationCase> {
    use crate::sensitivity::{forward_sensitivities, with_parameter, DynamicsParameter};
    let spread = |i: usize| (0.7 + 1.37 * i as f64).sin();
    let moving = |s: &tensegrity_core::Structure| {
        let mut v = vec![[0.0; 3]; s.n_nodes()];
        for (k, b) in s.bars().iter().enumerate() {
            let u = [spread(3 * k), spread(3 * k + 1), spread(3 * k + 2)].map(|x| 0.5 * x);
            v[b.nodes[0]] = u;
            v[b.nodes[1]] = u;
        }
        s.to_builder().velocities(v).build()
    };
    let nominal = six_bar(1.0, 1000.0, 50.0, 2.0)?;
    let mut truth = nominal.clone();
    let (mut parameters, mut true_values) = (Vec::new(), Vec::new());
    for j in 0..nominal.n_strings() {
        let k = 1000.0 * (1.0 + 0.2 * spread(j));
        let c = 2.0 * (1.0 + 0.3 * spread(j + 31));
        truth = with_parameter(&truth, DynamicsParameter::Stiffness(j), k)?;
        truth = with_parameter(&truth, DynamicsParameter::Damping(j), c)?;
        parameters.extend([
            DynamicsParameter::Stiffness(j),
            DynamicsParameter::Damping(j),
        ]);
        true_values.extend([k, c]);
    }
    let (truth, start) = (moving(&truth)?, moving(&nominal)?);
    let settings = crate::identify::IdentifySettings {
        dt: 1e-3,
        every: 2,
        ..Default::default()
    };
    let run = forward_sensitivities(&truth, None, &[], settings.dt, 0.4, settings.every)?;
    let n = truth.n_nodes();
    let e = gaussian_noise(sigma, run.nodes.len() * 3 * n);
    let measured = (run.nodes.iter().enumerate())
        .map(|(s, nodes)| {
            (nodes.iter().enumerate())
                .map(|(i, x)| {
                    let at = 3 * (n * s + i);
                    x + Vector3::new(e[at], e[at + 1], e[at + 2])
                })
                .collect()
        })
        .collect();
    Ok(IdentificationCase {
        truth,
        start,
        parameters,
        true_values,
        observed: (0..n).collect(),
        measured,
        settings,
        sigma,
    })
}
