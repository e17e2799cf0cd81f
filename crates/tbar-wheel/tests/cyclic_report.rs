//! The T-bar wheel through the cyclic path against the dense path (issue 20, item 5): for
//! N ≤ 64 treads, both rims (fixed and the free rim body), wheels and extended wheels,
//! complexities 1 and 2, the report's rank, self-stress dimension, mechanisms and internal
//! mechanisms are equal, and its margin, minimum prestress and mass agree to 1e-9.
//!
//! Why 1e-9: both paths solve the same LPs — the dense one over the whole self-stress space,
//! the cyclic one over its fully symmetric part, which holds an optimum because the LPs are
//! invariant under the rotation (their gains are constant on member orbits) — with the same
//! interior-point method to a gap of 1e-10, and both recompute the margin and the minimum
//! prestress exactly from the returned state. Observed differences are ≤ 1e-13 (relative).
//! The same geometry gives the same critical member, tread and active set.
//!
//! And: an uncertified cyclic rank decision falls back to the dense SVD (or says so), and a
//! wheel with coincident nodes, whose descriptor does not validate, takes the dense path with
//! a warning.

use michell3d::MichellParams;
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::statics::backend_with;
use tbar_wheel::symmetry::wheel_symmetry;
use tbar_wheel::{
    tbar_report, tbar_report_dense, BarBase, Layout, RimMode, TbarGeometry, TbarParams, TbarReport,
    TbarRequest,
};
use tensegrity_statics::Statics;
use tensegrity_statics::{Factorization, StaticsSettings};

fn close(a: Option<f64>, b: Option<f64>, what: &str) {
    match (a, b) {
        (Some(x), Some(y)) => assert!((x - y).abs() <= 1e-9 * y.abs(), "{what}: {x} vs {y}"),
        (x, y) => assert_eq!(x, y, "{what}"),
    }
}

/// The cyclic report of `p` (which must go through the blocks) against the dense one.
fn compare(p: TbarParams, what: &str) -> TbarReport {
    let mut req = TbarRequest::new(p);
    req.prestress = Some(10.0);
    req.directions = 60;
    let (c, d) = (tbar_report(&req).unwrap(), tbar_report_dense(&req).unwrap());
    assert_eq!(c.statics_method, Factorization::Cyclic, "{what}");
    assert_eq!(d.statics_method, Factorization::Svd, "{what}");
    assert_eq!(
        (
            c.rank,
            c.self_stress_dim,
            c.mechanisms,
            c.internal_mechanisms
        ),
        (
            d.rank,
            d.self_stress_dim,
            d.mechanisms,
            d.internal_mechanisms
        ),
        "{what}"
    );
    assert_eq!(c.prestressable, d.prestressable, "{what}");
    assert!(
        (c.prestress_margin - d.prestress_margin).abs() < 1e-9,
        "{what}: margin {} vs {}",
        c.prestress_margin,
        d.prestress_margin
    );
    close(c.min_prestress, d.min_prestress, what);
    close(c.mass_kg, d.mass_kg, what);
    close(
        c.mass.as_ref().map(|m| m.yield_mass_kg),
        d.mass.as_ref().map(|m| m.yield_mass_kg),
        what,
    );
    assert_eq!(c.active_members, d.active_members, "{what}");
    let member = |r: &TbarReport| r.critical_member.as_ref().map(|m| (m.member, m.tread));
    assert_eq!(member(&c), member(&d), "{what}");
    assert_eq!(c.slack_fraction, d.slack_fraction, "{what}");
    assert_eq!(c.min_strings_carrying, d.min_strings_carrying, "{what}");
    assert_eq!(c.warnings, d.warnings, "{what}");
    // both rank decisions have a clear gap; the cyclic one names its narrowest block
    assert_eq!(
        (&c.statics_warning, &d.statics_warning),
        (&None, &None),
        "{what}"
    );
    assert!(
        c.spectral_gap.is_clear() && d.spectral_gap.is_clear(),
        "{what}"
    );
    assert!(
        c.spectral_gap.block.is_some() && d.spectral_gap.block.is_none(),
        "{what}"
    );
    c
}

fn params(q: usize, n: usize, layout: Layout, rim: RimMode) -> TbarParams {
    let m = MichellParams::cylindrical(q, 1.0, FRAC_PI_6, PI / n as f64, 0.25);
    TbarParams::tread(m).with_layout(layout).with_rim(rim)
}

#[test]
fn fixed_rim_wheels_up_to_64_treads_match_the_dense_path() {
    let mut prestressable = 0;
    for n in [3, 4, 5, 8, 16, 31, 64] {
        let r = compare(
            params(1, n, Layout::Wheel, RimMode::Fixed),
            &format!("q = 1 wheel of {n}"),
        );
        assert_eq!(r.self_stress_dim, 2 * n);
        if r.min_prestress.is_some() {
            prestressable += 1;
        }
    }
    assert_eq!(prestressable, 7, "every q = 1 wheel carries the envelope");
    for n in [3, 8] {
        let ext = Layout::Extended { offset: 0.7 };
        compare(params(1, n, ext, RimMode::Fixed), &format!("extended {n}"));
        compare(
            params(2, n, Layout::Wheel, RimMode::Fixed),
            &format!("q = 2, {n}"),
        );
    }
    let sph = MichellParams::spherical(1, 1.0, FRAC_PI_6, PI / 6.0, 0.3);
    let chord = TbarParams::tread(sph)
        .with_layout(Layout::Wheel)
        .with_bar_base(BarBase::Chord);
    compare(chord, "spherical chord-based wheel of 6");
}

#[test]
fn rim_body_wheels_up_to_64_treads_match_the_dense_path() {
    for n in [3, 8, 64] {
        let r = compare(
            params(1, n, Layout::Wheel, RimMode::Body),
            &format!("rim body, wheel of {n}"),
        );
        assert_eq!((r.mechanisms, r.internal_mechanisms), (6, 0), "free body");
        assert!(r.prestressable);
    }
    compare(
        params(1, 4, Layout::Extended { offset: 0.5 }, RimMode::Body),
        "rim body, extended 4",
    );
    compare(
        params(2, 5, Layout::Wheel, RimMode::Body),
        "rim body, q = 2 wheel of 5",
    );
}

#[test]
fn an_uncertified_cyclic_rank_falls_back_to_the_dense_svd() {
    let g = TbarGeometry::new(params(1, 8, Layout::Wheel, RimMode::Body)).unwrap();
    let s = g.structure().unwrap();
    let sym = wheel_symmetry(&g, &s).unwrap();
    let dense = Statics::new(&s).unwrap();
    let sv = dense.singular_values();
    let smallest = sv[..dense.rank()].last().copied().unwrap();
    // the rank tolerance 3× the smallest non-zero singular value: inside the uncertain band
    let settings = StaticsSettings::default()
        .rank_tolerance(3.0 * smallest / sv[0])
        .unwrap();
    let b = backend_with(&s, Some(&sym), settings).unwrap();
    assert_eq!(b.kind(), Factorization::Svd, "falls back to the SVD");
    let b = backend_with(&s, Some(&sym), StaticsSettings::default()).unwrap();
    assert_eq!(b.kind(), Factorization::Cyclic);
    assert!(b.certification().is_certified());
}

#[test]
fn the_cyclic_load_response_is_the_dense_one_rotated() {
    use tbar_wheel::envelope::LoadResponse;
    let g = TbarGeometry::new(params(2, 6, Layout::Wheel, RimMode::Fixed)).unwrap();
    let s = g.structure().unwrap();
    let sym = wheel_symmetry(&g, &s).unwrap();
    let cyclic = backend_with(&s, Some(&sym), StaticsSettings::default()).unwrap();
    let dense = Statics::new(&s).unwrap();
    let rc = LoadResponse::new(cyclic.as_ref(), &g.tips, 1e6, "wheel").unwrap();
    let rd = LoadResponse::new(&dense, &g.tips, 1e6, "wheel").unwrap();
    assert_eq!(rc.g.len(), 1, "one tip computed per tip orbit");
    let scale = rd.g[0].iter().map(|v| v.norm()).fold(0.0, f64::max);
    for t in 0..g.tips.len() {
        let (a, b) = (rc.tip_response(t), rd.tip_response(t));
        let err = a
            .iter()
            .zip(b.iter())
            .map(|(x, y): (&Vector3<f64>, &Vector3<f64>)| (x - y).norm())
            .fold(0.0, f64::max);
        assert!(err < 1e-12 * scale, "tip {t}: {err:e}");
    }
    for (x, y) in rc.worst_gains().iter().zip(rd.worst_gains()) {
        assert!((x.0 - y.0).abs() < 1e-12 * scale);
    }
}

#[test]
fn a_wheel_without_a_valid_descriptor_takes_the_dense_path_and_says_so() {
    // q = 2, 12 treads, copies 0.5 apart: nodes of the two copies coincide, so the rotation
    // cannot tell them apart
    let p = params(2, 12, Layout::Extended { offset: 0.5 }, RimMode::Fixed);
    let g = TbarGeometry::new(p).unwrap();
    let coincident = (0..g.nodes.len())
        .any(|i| (0..i).any(|j| (g.nodes[i] - g.nodes[j]).norm() < 1e-9 && (i < 72) != (j < 72)));
    assert!(coincident, "the two copies share positions");
    let r = tbar_report(&TbarRequest::new(p)).unwrap();
    assert_eq!(r.statics_method, Factorization::Svd);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.kind() == "no_cyclic_symmetry"
                && w.to_string().contains("no cyclic symmetry")),
        "{:?}",
        r.warnings
    );
}
