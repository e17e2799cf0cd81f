//! Tangent stiffness against finite differences, flex counts, prestress stability and modal
//! frequencies against closed forms.

use crate::common;

use approx::assert_relative_eq;
use common::*;
use nalgebra::{DMatrix, DVector, Vector3};
use std::f64::consts::PI;
use tensegrity_core::{Bar, Material, StringMember, Structure, Support};
use tensegrity_statics::stiffness::{self, rigid_body_motions};
use tensegrity_statics::DofMap;
use tensegrity_statics::Statics;

/// Internal nodal forces (on the free dofs) of elastic members at node positions `x`:
/// strings k(l − s0)⁺, bars E A (l − l0)/l0 with l0 the initial length.
fn internal_forces(s: &Structure, x: &[Vector3<f64>], dofs: &DofMap) -> DVector<f64> {
    let mut f = DVector::zeros(dofs.len());
    let l0 = s.member_lengths();
    for (k, [i, j]) in s.member_nodes().into_iter().enumerate() {
        let m = x[j] - x[i];
        let l = m.norm();
        let tension = match s.member_id(k) {
            tensegrity_core::MemberId::Bar(b) => {
                let bar = &s.bars()[b];
                let e = s.member_material(s.member_id(k)).unwrap().youngs_modulus;
                e * PI * bar.radius.unwrap().powi(2) * (l - l0[k]) / l0[k]
            }
            tensegrity_core::MemberId::String(st) => {
                let st = &s.strings()[st];
                (st.stiffness.unwrap() * (l - st.rest_length.unwrap())).max(0.0)
            }
        };
        let t = m / l * tension;
        // force on node i is +t (pulled towards j), on j is −t; A q = w uses the negative
        for d in 0..3 {
            if let Some(r) = dofs.row[i][d] {
                f[r] -= t[d];
            }
            if let Some(r) = dofs.row[j][d] {
                f[r] += t[d];
            }
        }
    }
    f
}

fn prestressed_prism() -> Structure {
    prestressed_snelson(3, 0.005, false).0
}

#[test]
fn tangent_stiffness_matches_finite_differences_of_internal_forces() {
    let s = prestressed_prism()
        .to_builder()
        .support(Support::pinned(0))
        .build()
        .unwrap();
    let dofs = DofMap::of(&s);
    // in this elastic model the bars sit at their initial length (no elastic force), so the
    // force densities at the reference point are the strings' k(1 − s0/l) and zero for bars
    let mut q = stiffness::string_force_densities(&s).unwrap();
    for k in 0..s.n_bars() {
        q[k] = 0.0;
    }
    let axial = stiffness::axial_stiffness(&s).unwrap();
    let kt = stiffness::tangent_stiffness(&s, &dofs, &q, &axial);
    let x0: Vec<Vector3<f64>> = s.nodes().to_vec();
    let h = 1e-7;
    let mut fd = DMatrix::zeros(dofs.len(), dofs.len());
    for (c, &(node, d)) in dofs.free.iter().enumerate() {
        let mut xp = x0.clone();
        let mut xm = x0.clone();
        xp[node][d] += h;
        xm[node][d] -= h;
        let col = (internal_forces(&s, &xp, &dofs) - internal_forces(&s, &xm, &dofs)) / (2.0 * h);
        fd.set_column(c, &col);
    }
    let scale = kt.amax();
    assert!(
        (&kt - &fd).amax() < 1e-6 * scale,
        "max diff {}",
        (&kt - &fd).amax() / scale
    );
    assert_relative_eq!(kt.clone(), kt.transpose(), epsilon = 1e-9 * scale);
}

#[test]
fn rigid_body_motions_respect_supports() {
    let free = dbar(2.0, 1.0).build().unwrap();
    assert_eq!(
        rigid_body_motions(&free, &DofMap::of(&free))
            .unwrap()
            .ncols(),
        6
    );
    let pinned = dbar(2.0, 1.0).support(Support::pinned(0)).build().unwrap();
    // only rotations about node 0 remain
    assert_eq!(
        rigid_body_motions(&pinned, &DofMap::of(&pinned))
            .unwrap()
            .ncols(),
        3
    );
    let two = dbar(2.0, 1.0)
        .support(Support::pinned(0))
        .support(Support::pinned(3))
        .build()
        .unwrap();
    // rotation about the axis through nodes 0 and 3
    assert_eq!(
        rigid_body_motions(&two, &DofMap::of(&two)).unwrap().ncols(),
        1
    );
    let st = Statics::new(&two).unwrap();
    // 6 free dofs, rank 5 (string 0-3 now spans two supports: zero column) ...
    let flexes = st.flexes().unwrap();
    assert_eq!(flexes.rigid_body, 1);
    assert_eq!(st.mechanisms(), flexes.rigid_body + flexes.internal.ncols());
}

#[test]
fn a_planar_dbar_is_not_prestress_stable_out_of_plane_but_the_prism_is() {
    let s = dbar(2.0, 1.0).build().unwrap();
    let st = Statics::new(&s).unwrap();
    let pre = st.prestressability().unwrap();
    let stab = st.prestress_stability(&pre.stress).unwrap();
    // the out-of-plane flex of the D-bar: bars compressed, its stress energy is not positive
    assert_eq!(stab.internal_mechanisms, 1);
    assert!(!stab.stable);

    let prism = prestressed_prism();
    let st = Statics::new(&prism).unwrap();
    let q = stiffness::string_force_densities(&prism).unwrap();
    let sol_bars = {
        // bar force densities from equilibrium with the string tensions
        let pre = st.prestressability().unwrap();
        let scale = q[prism.n_bars()] / pre.stress[prism.n_bars()];
        pre.stress * scale
    };
    assert_relative_eq!(
        sol_bars.rows(3, 9).into_owned(),
        q.rows(3, 9).into_owned(),
        max_relative = 1e-9
    );
    assert!(st.prestress_stability(&sol_bars).unwrap().stable);
}

#[test]
fn axial_mode_of_a_supported_bar_has_the_closed_form_frequency() {
    let (m, l, r, e) = (2.0, 1.5, 0.01, 70e9);
    let s = Structure::builder()
        .material("m", Material::new(2700.0, e, 1e8))
        .nodes([[0.0, 0.0, 0.0], [0.3, 0.4, l]])
        .bar(Bar::new(0, 1).mass(m).material("m").radius(r))
        .support(Support::pinned(0))
        .build()
        .unwrap();
    let q = DVector::zeros(1);
    let modes = stiffness::modal_analysis(&s, &q).unwrap();
    let len = s.member_lengths()[0];
    let k = e * PI * r * r / len;
    // ω² = k / (m/2) for the free end; the two transverse modes are zero-frequency
    assert_relative_eq!(modes.eigenvalues[2], k / (0.5 * m), max_relative = 1e-10);
    assert!(modes.eigenvalues[0].abs() < 1e-6 * modes.eigenvalues[2]);
    // the mode shape is along the bar
    let shape = modes.shapes.column(2).normalize();
    let axis = s.member_vector(0).normalize();
    assert_relative_eq!(
        shape.dot(&DVector::from_row_slice(axis.as_slice())).abs(),
        1.0,
        epsilon = 1e-10
    );
}

#[test]
fn a_tensioned_string_gives_the_taut_string_transverse_frequency() {
    // mass at the free end of a bar pinned at its base, held sideways by two pretensioned strings
    // in the y direction: transverse (y) stiffness 2k, transverse (x) stiffness 2T/ls
    let (ls, k, t, m) = (1.0, 500.0, 40.0, 3.0);
    let s0 = ls - t / k;
    let s = Structure::builder()
        .material("m", Material::new(2700.0, 70e9, 1e8))
        .nodes([
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 2.0],
            [0.0, -ls, 2.0],
            [0.0, ls, 2.0],
        ])
        .bar(Bar::new(0, 1).mass(2.0 * m).material("m").radius(0.02))
        .string(StringMember::new(1, 2).stiffness(k).rest_length(s0))
        .string(StringMember::new(1, 3).stiffness(k).rest_length(s0))
        .support(Support::pinned(0))
        .support(Support::pinned(2))
        .support(Support::pinned(3))
        .build()
        .unwrap();
    let q = stiffness::string_force_densities(&s).unwrap();
    assert_relative_eq!(q[1] * ls, t, max_relative = 1e-12);
    let modes = stiffness::modal_analysis(&s, &q).unwrap();
    let w = &modes.eigenvalues;
    assert_relative_eq!(w[0], 2.0 * t / ls / m, max_relative = 1e-9);
    assert_relative_eq!(w[1], 2.0 * k / m, max_relative = 1e-9);
    assert_relative_eq!(
        modes.frequencies_hz[1],
        (2.0 * k / m).sqrt() / (2.0 * PI),
        max_relative = 1e-9
    );
}

#[test]
fn modal_analysis_reports_missing_properties() {
    let s = dbar(2.0, 1.0).build().unwrap();
    let err = stiffness::modal_analysis(&s, &DVector::zeros(6))
        .unwrap_err()
        .to_string();
    assert!(err.contains("bar 0") && err.contains("material"), "{err}");
}
