//! The T-bar wheel built for the full rolling model (`tbar_wheel::rolling_full`): the built
//! shape is an equilibrium of the prestress with the rim-body bar forces determined (an
//! isostatic rim), the free body keeps exactly its six rigid motions, the starting pose
//! stands on the side of treads 0 and 1, and the prestress level is the envelope's.

use michell3d::MichellParams;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::rolling_full::{full_wheel, FullWheel, FullWheelRequest, PrestressLevel};
use tbar_wheel::{tbar_report, Layout, TbarError, TbarParams, TbarRequest};
use tensegrity_statics::Statics;

fn params(n: usize, layout: Layout) -> TbarParams {
    let m = MichellParams::cylindrical(1, 1.0, FRAC_PI_6, PI / n as f64, 0.25);
    TbarParams::tread(m).with_layout(layout)
}

fn wheel(n: usize, layout: Layout) -> FullWheel {
    full_wheel(&params(n, layout), &FullWheelRequest::default()).unwrap()
}

#[test]
fn the_built_shape_is_an_equilibrium_with_determined_bar_forces() {
    for (n, layout) in [(6, Layout::Wheel), (4, Layout::Extended { offset: 0.5 })] {
        let w = wheel(n, layout);
        let s = &w.structure;
        let st = Statics::new(s).unwrap();
        let a = st.matrix();
        let (nb, ns) = (s.n_bars(), s.n_strings());
        let lengths = s.member_lengths();
        // string force densities from the rest lengths: t = k (L − L₀), q = t / L
        let q_s = DVector::from_iterator(
            ns,
            s.strings().iter().enumerate().map(|(i, m)| {
                let l = lengths[nb + i];
                m.stiffness.unwrap() * (l - m.rest_length.unwrap()) / l
            }),
        );
        let a_b = a.columns(0, nb).into_owned();
        let rhs = -(a.columns(nb, ns) * &q_s);
        let svd = a_b.clone().svd(true, true);
        // no bar-only self-stress: the bars' forces are determined
        let smax = svd.singular_values.max();
        assert_eq!(svd.rank(1e-10 * smax), nb, "n = {n}");
        let q_b: DVector<f64> = svd.solve(&rhs, 1e-10 * smax).unwrap();
        let residual = (&a_b * &q_b - &rhs).norm() / rhs.norm();
        assert!(residual < 1e-10, "n = {n}: residual {residual:e}");
        // the treads' bars carry the prescribed compression
        for k in 0..w.geometry.bars.len() {
            let f = q_b[k] * lengths[k];
            let want = -w.prestress.bar_compression;
            assert!(
                (f - want).abs() < 1e-8 * want.abs(),
                "bar {k}: {f} vs {want}"
            );
        }
        // and every string is taut at the built length
        assert!(q_s.iter().all(|&q| q > 0.0));
        let min_t = (0..ns)
            .map(|i| q_s[i] * lengths[nb + i])
            .fold(f64::INFINITY, f64::min);
        assert!((min_t - w.prestress.min_string_tension).abs() < 1e-9 * min_t);
    }
}

#[test]
fn the_isostatic_rim_keeps_only_the_six_rigid_motions() {
    // q = 1: |R| = 3nc rim points, 1 + 6nc + 4nc² rim bars, 3|R| kept: the ring first (the
    // loop keeps all 4n ring bars, the extended n = 4 wheel 55 of its 4nc² = 64), then the
    // spokes the rank still needs, no axle bar
    let cases = [
        (6, Layout::Wheel, 1, (30, 24)),
        (4, Layout::Extended { offset: 0.5 }, 2, (17, 55)),
    ];
    for (n, layout, c, kept) in cases {
        let w = wheel(n, layout);
        let r = 3 * n * c;
        let rim = w.geometry.rim.as_ref().unwrap();
        assert_eq!(rim.bars.len(), 3 * r, "n = {n}");
        assert_eq!(w.redundant_rim_bars, 1 + 6 * n * c + 4 * n * c * c - 3 * r);
        assert_eq!((rim.spokes, rim.ring), kept, "n = {n}");
        let st = Statics::new(&w.structure).unwrap();
        assert_eq!(st.mechanisms(), 6, "n = {n}: a free, internally rigid body");
    }
}

#[test]
fn the_wheel_starts_on_the_side_of_treads_zero_and_one() {
    let n = 6;
    let w = wheel(n, Layout::Extended { offset: 0.5 });
    let x = w.structure.nodes();
    let (s, c) = (PI / n as f64).sin_cos();
    assert_eq!(w.contact_groups.len(), n);
    for k in 0..n {
        assert_eq!(w.contact_groups[k].len(), 2);
        for &i in &w.contact_groups[k] {
            // the tips lie on the circle r₀ about the axle, 2π/n apart from the side 0–1
            let angle = -0.5 * PI - PI / n as f64 + 2.0 * PI * k as f64 / n as f64;
            assert!((x[i].y - angle.cos()).abs() < 1e-12 && (x[i].z - angle.sin()).abs() < 1e-12);
        }
    }
    for (k, sign) in [(0, -1.0), (1, 1.0)] {
        for &i in &w.contact_groups[k] {
            assert!((x[i].y - sign * s).abs() < 1e-12 && (x[i].z + c).abs() < 1e-12);
        }
    }
    for h in w.hubs {
        assert!(x[h].y.abs() < 1e-12 && x[h].z.abs() < 1e-12);
    }
    // mass properties are those of the structure's bars (rim body included)
    let m: f64 = w.structure.bars().iter().map(|b| b.mass.unwrap()).sum();
    assert!((w.mass.mass - m).abs() < 1e-12 * m);
}

#[test]
fn the_prestress_level_is_the_envelopes() {
    let p = params(6, Layout::Wheel);
    // the rim-supported tread's min_prestress per newton of tip load (the report's LP)
    let tread = tbar_report(&TbarRequest::new(p.with_layout(Layout::Tread))).unwrap();
    let per_load = tread.min_prestress.unwrap() / tread.load;
    let default = wheel(6, Layout::Wheel);
    let f = default.prestress;
    assert!((f.bar_compression / f.tip_load_capacity - per_load).abs() < 1e-6 * per_load);
    assert!((f.tip_load_capacity - 2.0 * default.mass.mass * 9.81).abs() < 1e-9);
    assert!(default.warnings(9.81).is_empty());
    let low = full_wheel(
        &p,
        &FullWheelRequest {
            prestress: PrestressLevel::MinTension(1.0),
            ..FullWheelRequest::default()
        },
    )
    .unwrap();
    assert!((low.prestress.min_string_tension - 1.0).abs() < 1e-12);
    let w = low.warnings(9.81);
    assert_eq!(w.len(), 1);
    let text = w[0].to_string();
    assert!(
        text.contains("raise min_tension") && !text.contains("--"),
        "{text}"
    );
    // the fields carry the numbers the text shows: the weight per tip over the capacity
    let tensegrity_core::Warning::SlackInContact {
        capacity,
        per_tip,
        suggested_min_tension,
        ..
    } = w[0]
    else {
        panic!("{:?}", w[0]);
    };
    assert!(per_tip > capacity);
    assert!((suggested_min_tension - per_tip / capacity).abs() < 1e-12);
}

#[test]
fn bad_requests_name_what_is_wrong() {
    let err = |p: &TbarParams, r: &FullWheelRequest| full_wheel(p, r).unwrap_err();
    let d = FullWheelRequest::default();
    let e = err(&params(6, Layout::Tread), &d);
    assert!(
        matches!(&e, TbarError::InvalidParameter(p) if p.name == "layout"),
        "{e}"
    );
    let soft = FullWheelRequest {
        string_stiffness: 1.0,
        ..d
    };
    let e = err(&params(6, Layout::Wheel), &soft);
    assert!(e.to_string().contains("string_stiffness"), "{e}");
    let e = err(
        &params(6, Layout::Wheel),
        &FullWheelRequest {
            rim_density: -1.0,
            ..d
        },
    );
    assert!(e.to_string().contains("rim_density"), "{e}");
    // q = 2 treads are not prestressable (README): no prestress to build
    let m = MichellParams::cylindrical(2, 1.0, FRAC_PI_6, PI / 6.0, 0.25);
    let e = err(&TbarParams::tread(m).with_layout(Layout::Wheel), &d);
    assert!(matches!(e, TbarError::NotPrestressable { .. }), "{e}");
}

#[test]
fn independent_bars_of_a_braced_square_drop_the_second_diagonal() {
    let x: Vec<_> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        .iter()
        .map(|p| nalgebra::Vector3::new(p[0], p[1], 0.0))
        .collect();
    // in the plane z = 0 a braced square has one self-stress; in 3-D the out-of-plane
    // motions do not change that: 6 bars, rank 5
    let bars = [[0, 1], [1, 2], [2, 3], [3, 0], [0, 2], [1, 3]];
    let keep = tbar_wheel::rolling_full::independent_bars(&x, &bars);
    assert_eq!(keep, [0, 1, 2, 3, 4]);
    let rows = DMatrix::from_fn(6, 12, |k, j| {
        let [a, b] = bars[k];
        let d = (x[b] - x[a]).normalize();
        if j / 3 == a {
            -d[j % 3]
        } else if j / 3 == b {
            d[j % 3]
        } else {
            0.0
        }
    });
    assert_eq!(rows.rank(1e-10), 5);
}
