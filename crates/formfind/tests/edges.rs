//! The library at its edges (issue 42): a node count no member reaches, the estimate of the
//! method that will run, force densities and stiffnesses at the ends of the double range.

use formfind::{
    builtin, estimate, form_find, rest_lengths, synthesize, FormFindError, Member, Method,
    Settings, Synthesis, Topology, EIGEN_FLOPS,
};
use tensegrity_core::budget::DENSE_FLOP_RATE;

/// A zig-zag chain of `n` nodes: bars between neighbours, strings every other node.
fn chain(n: usize) -> Topology {
    Topology {
        n_nodes: n,
        nodes: Some(
            (0..n)
                .map(|i| [i as f64, 0.5 * (i % 2) as f64, 0.0])
                .collect(),
        ),
        bars: (0..n - 1).map(|i| Member::new(i, i + 1)).collect(),
        strings: (0..n - 2).map(|i| Member::new(i, i + 2)).collect(),
        ..Topology::default()
    }
}

#[test]
fn a_node_count_no_member_reaches_is_refused_before_it_is_allocated() {
    let t = Topology {
        n_nodes: 1_000_000_000_000,
        bars: vec![Member::new(0, 1)],
        ..Topology::default()
    };
    let e = form_find(&t, &Settings::default()).unwrap_err().to_string();
    assert_eq!(
        e,
        "n_nodes: 1000000000000 nodes, but every node must be on a member or fixed, and 1 \
         member(s) and 0 fixed node(s) reach at most 2"
    );
    // usize::MAX members' worth of reach does not overflow the check
    let t = Topology {
        n_nodes: usize::MAX,
        ..t
    };
    assert!(form_find(&t, &Settings::default()).is_err());
}

#[test]
fn the_estimate_is_the_method_that_runs_over_its_iteration_cap() {
    // no force density: the adaptive method, max_iterations eigensolves of 1000 nodes
    let t = chain(1000);
    let e = estimate(&t, &Settings::default());
    assert!(
        e.what.starts_with("the adaptive force density iteration"),
        "{}",
        e.what
    );
    let per_solve = EIGEN_FLOPS * 1e9 / DENSE_FLOP_RATE;
    assert!(
        e.work_s > 10_000.0 * per_solve && e.work_s < 10_100.0 * per_solve,
        "{}",
        e.work_s
    );
    assert!(
        e.parameters.to_string().contains("max_iterations = 10000"),
        "{}",
        e.parameters
    );
    // a tenth of the cap, about a tenth of the work
    let capped = Settings {
        max_iterations: 1000,
        ..Settings::default()
    };
    let ratio = estimate(&t, &capped).work_s / e.work_s;
    assert!((ratio - 0.1).abs() < 0.01, "{ratio}");
    // every force density given: one direct solve; `auto` adds the adaptive fallback
    let prism = builtin("prism:12").unwrap();
    let fdm = estimate(&prism, &Settings::default());
    // the form alone unless its statics are asked for (`analyse`), then their estimate too
    assert_eq!(fdm.what, "the force density method (dense null space)");
    let analysed = Settings {
        analyse: true,
        ..Settings::default()
    };
    let with_statics = estimate(&prism, &analysed);
    assert!(
        with_statics
            .what
            .starts_with("the force density method (dense null space), then"),
        "{}",
        with_statics.what
    );
    assert!(with_statics.work_s > fdm.work_s);
    assert!(!fdm.parameters.to_string().contains("max_iterations"));
    let auto = Settings {
        method: Method::Auto,
        ..Settings::default()
    };
    let fallback = estimate(&prism, &auto);
    assert!(
        fallback
            .what
            .contains("then the adaptive force density iteration"),
        "{}",
        fallback.what
    );
    // 10 000 more eigensolves of the 24 nodes (and the g × g Gram factor, g = 4 groups)
    let extra =
        (fallback.work_s - fdm.work_s) / (1e4 * EIGEN_FLOPS * 24f64.powi(3) / DENSE_FLOP_RATE);
    assert!((extra - 1.0).abs() < 1e-3, "{extra}");
}

/// The 3-bar prism with its force densities times `scale` on every member.
fn scaled_prism(scale: f64) -> Topology {
    let mut t = builtin("prism:3").unwrap();
    let q = t.given_force_densities();
    for g in t.groups.values_mut() {
        g.force_density = None;
    }
    for (m, q) in t.bars.iter_mut().chain(t.strings.iter_mut()).zip(q) {
        m.force_density = q.map(|q| q * scale);
    }
    t
}

#[test]
fn force_densities_near_the_largest_double_find_the_same_form() {
    let (one, huge) = (scaled_prism(1.0), scaled_prism(1e300));
    let settings = Settings {
        analyse: true,
        ..Settings::default()
    };
    let (a, b) = (
        form_find(&one, &settings).unwrap(),
        form_find(&huge, &settings).unwrap(),
    );
    assert!(
        b.residual.is_finite() && b.residual < 1e-12,
        "{}",
        b.residual
    );
    assert!(b.prestressable == Some(true) && b.prestress_stable == Some(true));
    for (p, r) in a.nodes.iter().zip(&b.nodes) {
        assert!((p - r).norm() < 1e-12, "{p} vs {r}");
    }
    assert_eq!(b.force_density[0], -1e300);
    // the same forces at the prestress level
    let syn = Synthesis::default();
    let (ra, rb) = (
        rest_lengths(&one, &a, &syn).unwrap(),
        rest_lengths(&huge, &b, &syn).unwrap(),
    );
    for (x, y) in ra.tension.iter().zip(&rb.tension) {
        assert!((x - y).abs() < 1e-9 * x.abs(), "{x} vs {y}");
    }
    assert!((rb.scale * 1e300 / ra.scale - 1.0).abs() < 1e-12);
    // the adaptive method from them too
    let adaptive = Settings {
        method: Method::Adaptive,
        ..Settings::default()
    };
    let c = form_find(&huge, &adaptive).unwrap();
    assert!(c.residual < 1e-12 && c.force_density.iter().all(|q| q.is_finite()));
}

#[test]
fn a_stiffness_beyond_double_precision_is_refused_naming_it_and_the_string() {
    let t = builtin("prism:3").unwrap();
    let found = form_find(&t, &Settings::default()).unwrap();
    let stiff = Synthesis {
        stiffness: 1e308,
        ..Synthesis::default()
    };
    let e = synthesize(&t, &found, &stiff).unwrap_err();
    assert!(matches!(e, FormFindError::InvalidParameter(_)), "{e}");
    let e = e.to_string();
    // the first string: the bottom ring carries 1/√3 of the vertical's force density
    assert!(
        e.starts_with("stiffness = 1e308: strings[0] would stretch by T/EA = "),
        "{e}"
    );
    assert!(e.contains("lower the stiffness (at most"), "{e}");
    // a prestress that overflows the tensions
    let loud = Synthesis {
        prestress: f64::MAX,
        ..Synthesis::default()
    };
    let e = synthesize(&t, &found, &loud).unwrap_err().to_string();
    assert!(
        e.starts_with("prestress = ") && e.contains("tension overflows"),
        "{e}"
    );
    // the largest admitted stiffness is admitted
    let r = rest_lengths(&t, &found, &Synthesis::default()).unwrap();
    let t_min = r.tension[3..].iter().fold(f64::INFINITY, |a, &x| a.min(x));
    let edge = Synthesis {
        stiffness: 0.99 * t_min / formfind::MIN_STRAIN,
        ..Synthesis::default()
    };
    let s = synthesize(&t, &found, &edge).unwrap();
    assert_eq!(s.n_strings(), 9);
}
