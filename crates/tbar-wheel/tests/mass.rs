//! Mass for the envelope against the Michell truss, and the q ≥ 2 finding.

use michell3d::MichellParams;
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::mass::mass_sweep;
use tbar_wheel::{tbar_report, TbarParams, TbarRequest};
use tensegrity_core::MaterialTable;

#[test]
fn q1_yield_mass_is_the_envelope_force_times_length() {
    let p = TbarParams::tread(MichellParams::cylindrical(
        1,
        0.5,
        FRAC_PI_6,
        PI / 8.0,
        0.25,
    ));
    let mut req = TbarRequest::new(p);
    req.load = 2000.0;
    let r = tbar_report(&req).unwrap();
    let steel = *MaterialTable::builtin().get("steel").unwrap();
    let coords: Vec<nalgebra::Vector3<f64>> = r
        .node_coordinates
        .iter()
        .map(|c| nalgebra::Vector3::from(*c))
        .collect();
    let len = |[a, b]: [usize; 2]| (coords[a] - coords[b]).norm();
    // q = 1: the four strings are symmetric and all bind at the optimum, so each string's
    // largest tension is 2 × its prestress; the bar's largest compression is P + w0‖g_bar‖
    let f = r.prestress_force.as_ref().unwrap();
    let strings: f64 = r
        .string_nodes
        .iter()
        .enumerate()
        .map(|(k, e)| 2.0 * f[1 + k] * len(*e))
        .sum();
    assert_eq!(r.active_members, [1, 2, 3, 4]);
    let m = r.mass.unwrap();
    let rho_sigma = steel.density / steel.yield_strength;
    let bar_yield = m.yield_mass_kg - rho_sigma * strings;
    assert!(bar_yield > rho_sigma * r.min_prestress.unwrap() * len(r.bar_nodes[0]));
    assert!(m.michell_mass_kg > 0.0 && m.mass_kg >= m.yield_mass_kg);
}

#[test]
fn sweep_over_q_and_delta() {
    let p = TbarParams::tread(MichellParams::cylindrical(
        1,
        1.0,
        FRAC_PI_6,
        PI / 8.0,
        0.25,
    ));
    let rows = mass_sweep(&p, &[1, 2], &[0.25, 0.5], 1000.0, 1e6, "steel");
    assert_eq!(rows.len(), 4);
    for r in &rows[..2] {
        assert!(r.mass.as_ref().unwrap().mass_ratio > 0.0, "{r:?}");
    }
    // finding: with every lattice member a string, no q ≥ 2 tread is prestressable (the
    // level-1 nodes cannot be balanced by tension alone), so it has no envelope
    for r in &rows[2..] {
        assert!(r.mass.is_none());
        assert!(
            r.note.as_ref().unwrap().contains("not prestressable"),
            "{r:?}"
        );
    }
}
