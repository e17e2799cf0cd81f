//! Exact derivatives of the tangent stiffness's smallest nonzero eigenvalue and of the
//! natural frequencies (issue 47, item 3; `tensegrity_statics::sensitivity`) with respect to
//! every force density, every axial stiffness, the prestress level and every node's position
//! (at fixed force densities and axial stiffnesses), against extrapolated
//! central differences to 10⁻⁶ relative: Snelson prisms of 3 and 4 bars free-standing and the
//! 3-bar one pinned at its base (both quantities), and the loaded D-bar (the eigenvalue).
//! Repeated eigenvalues are reported with their multiplicity and no derivative; clusters and
//! wrong lengths are refused by name.

use crate::common::*;
use nalgebra::{DVector, Vector3};
use tensegrity_core::test_models::snelson_twist;
use tensegrity_core::Structure;
use tensegrity_statics::sensitivity::{
    natural_frequencies, smallest_stiffness_eigenvalue, EigenDerivative,
};
use tensegrity_statics::stiffness::{self, axial_stiffness};
use tensegrity_statics::DofMap;

/// The p-bar Snelson prism of [`prestressed_snelson`] with bars of 2 mm radius.
fn prism(p: usize, pinned: bool) -> (Structure, DVector<f64>) {
    prestressed_snelson(p, 0.002, pinned)
}

/// The derivative of `f` (of force densities and axial stiffnesses) along `(dq, da)`,
/// Richardson-extrapolated central differences ((4 D(h/2) − D(h)) / 3) at `h`.
fn central(
    f: impl Fn(&DVector<f64>, &[f64]) -> f64,
    q: &DVector<f64>,
    a: &[f64],
    dq: &DVector<f64>,
    da: &[f64],
    h: f64,
) -> f64 {
    let at = |h: f64| {
        let step = |s: f64| {
            let qq = q + dq * (s * h);
            let aa: Vec<f64> = a.iter().zip(da).map(|(x, d)| x + s * h * d).collect();
            f(&qq, &aa)
        };
        (step(1.0) - step(-1.0)) / (2.0 * h)
    };
    (4.0 * at(0.5 * h) - at(h)) / 3.0
}

/// Checks `exact` against central differences of `f` for every q_k (steps of 10⁻⁴ max|q|:
/// a free-standing structure's rigid-body modes leave zero as q leaves its self-stress), every
/// a_k (steps of 10⁻² a_k: a string's effect on a mode the bars dominate is small against the
/// round-off of the eigenvalues) and the prestress level (10⁻³); returns the worst relative
/// error, against the larger of the largest derivative of each kind and |value| / (the
/// parameters' largest size): a mode whose motion is normal to every member (the D-bar's
/// smallest) has axial derivatives of 10⁻³⁵, and the floor judges them against a change of
/// the value by its own size.
fn check(
    name: &str,
    exact: &EigenDerivative,
    f: impl Fn(&DVector<f64>, &[f64]) -> f64,
    q: &DVector<f64>,
    a: &[f64],
) -> f64 {
    let m = q.len();
    assert_eq!(exact.multiplicity, 1, "{name}: {exact:?}");
    let qmax = q.amax();
    let value = exact.value;
    let mut worst = 0.0f64;
    let amax = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    let mut compare = |exact: &[f64], fd: &[f64], what: &str, scale: f64| {
        let floor = value.abs() / scale;
        let size = exact.iter().fold(floor, |s, x| s.max(x.abs()));
        for (k, (e, d)) in exact.iter().zip(fd).enumerate() {
            let r = (e - d).abs() / size;
            assert!(r < 1e-6, "{name} {what} {k}: exact {e} fd {d}");
            worst = worst.max(r);
        }
    };
    let fd_q: Vec<f64> = (0..m)
        .map(|k| {
            let mut dq = DVector::zeros(m);
            dq[k] = qmax;
            central(&f, q, a, &dq, &vec![0.0; m], 1e-4) / qmax
        })
        .collect();
    compare(&exact.force_densities, &fd_q, "q", qmax);
    let fd_a: Vec<f64> = (0..m)
        .map(|k| {
            let mut da = vec![0.0; m];
            da[k] = a[k];
            central(&f, q, a, &DVector::zeros(m), &da, 1e-2) / a[k]
        })
        .collect();
    compare(&exact.axial_stiffnesses, &fd_a, "a", amax);
    let fd_level = central(&f, q, a, q, &vec![0.0; m], 1e-3);
    compare(&[exact.prestress_level.unwrap()], &[fd_level], "level", 1.0);
    worst
}

/// Checks the derivatives by every node's coordinates in `exact` against central differences
/// of `f` (of the structure moved) with steps of 10⁻⁴ of the structure's size, extrapolated;
/// returns the worst error relative to the larger of the largest derivative and |value| /
/// size.
fn check_nodes(
    name: &str,
    exact: &EigenDerivative,
    s: &Structure,
    f: impl Fn(&Structure) -> f64,
) -> f64 {
    let nodes: Vec<Vector3<f64>> = s.nodes().to_vec();
    let size = nodes.iter().fold(0.0f64, |m, x| m.max(x.amax()));
    let floor = exact.value.abs() / size;
    let largest = exact.nodes.iter().fold(floor, |m, x| m.max(x.amax()));
    let fd = node_central_differences(s, 1e-4 * size, f);
    worst_node_error(name, &exact.nodes, &fd, largest)
}

#[test]
fn the_smallest_eigenvalue_derivatives_match_central_differences() {
    let mut cases = vec![];
    // (the 5-bar prism's smallest nonzero eigenvalue is a symmetric pair: not differentiable)
    for (p, pinned) in [(3, false), (4, false), (3, true)] {
        let (s, q) = prism(p, pinned);
        cases.push((format!("prism {p} pinned {pinned}"), s, q));
    }
    let dbar = loaded_dbar(1.0, 10.0);
    let m = dbar.n_members();
    // a compressed bar set and tensioned strings (any q: K is linear in it)
    let q = DVector::from_fn(m, |k, _| {
        if k < dbar.n_bars() {
            -3.0 - 0.1 * k as f64
        } else {
            5.0 + 0.2 * k as f64
        }
    });
    // its bars have no radius: axial stiffnesses given (K is linear in them too)
    let a_dbar: Vec<f64> = (0..m)
        .map(|k| if k < dbar.n_bars() { 1e5 } else { 2e3 })
        .collect();
    let mut cases: Vec<(String, Structure, DVector<f64>, Vec<f64>)> = cases
        .into_iter()
        .map(|(name, s, q)| {
            let a = axial_stiffness(&s).unwrap();
            (name, s, q, a)
        })
        .collect();
    cases.push(("loaded D-bar".to_string(), dbar, q, a_dbar));
    for (name, s, q, a) in cases {
        let exact = smallest_stiffness_eigenvalue(&s, &q, &a).unwrap().unwrap();
        // the same branch: the eigenvalue of the same rank (q off its self-stress moves the
        // free prisms' rigid-body modes off zero, so "the smallest nonzero" would jump)
        let all = |q: &DVector<f64>, a: &[f64]| {
            let dofs = DofMap::stiffness_of(&s);
            let k = stiffness::tangent_stiffness(&s, &dofs, q, a);
            tensegrity_linalg::symmetric_eigen(&k).unwrap().0
        };
        let rank = all(&q, &a).iter().position(|&w| w == exact.value).unwrap();
        let f = |q: &DVector<f64>, a: &[f64]| all(q, a)[rank];
        let worst = check(&name, &exact, f, &q, &a);
        // the node positions, at fixed q and a
        let moved = |m: &Structure| {
            let k = stiffness::tangent_stiffness(m, &DofMap::stiffness_of(m), &q, &a);
            tensegrity_linalg::symmetric_eigen(&k).unwrap().0[rank]
        };
        let nodes = check_nodes(&name, &exact, &s, moved);
        println!(
            "{name}: λ = {:.6e}, worst {worst:.1e}, by the nodes {nodes:.1e}",
            exact.value
        );
    }
}

#[test]
fn the_natural_frequency_derivatives_match_central_differences() {
    for (p, pinned) in [(3, false), (4, false), (3, true)] {
        let (s, q) = prism(p, pinned);
        let a = axial_stiffness(&s).unwrap();
        let modes = natural_frequencies(&s, &q, &a).unwrap();
        let mut checked = 0;
        for (i, mode) in modes.iter().enumerate() {
            // the string-dominated modes (below 100 Hz): the bars' axial modes (~350 Hz) move
            // by 10⁻¹² per N/m of a force density, below the round-off of a difference
            // and away from a near-crossing (within 1 % of a neighbour: the 4-bar prism's
            // 12.407 Hz beside a 12.426 Hz pair), where a finite step bends the branch
            let near = |j: usize| {
                modes.get(j).is_some_and(|n: &EigenDerivative| {
                    (n.value - mode.value).abs() < 1e-2 * mode.value
                })
            };
            if mode.multiplicity != 1
                || mode.prestress_level.is_none()
                || mode.value > 100.0
                || near(i + 1)
                || (i > 0 && near(i - 1))
            {
                continue;
            }
            let f = |q: &DVector<f64>, a: &[f64]| natural_frequencies(&s, q, a).unwrap()[i].value;
            let name = format!("prism {p} pinned {pinned} mode {i}");
            let worst = check(&name, mode, f, &q, &a);
            let moved = |m: &Structure| natural_frequencies(m, &q, &a).unwrap()[i].value;
            let nodes = check_nodes(&name, mode, &s, moved);
            println!(
                "{name}: f = {:.4} Hz, worst {worst:.1e}, by the nodes {nodes:.1e}",
                mode.value
            );
            checked += 1;
        }
        assert!(checked >= 2, "prism {p}: {modes:?}");
    }
}

/// The 4-bar prism is symmetric about its axis: the rigid-body motions are zero and some of
/// its modes pair up; a repeated one has no derivatives, a simple one has them. The 5-bar
/// prism's smallest nonzero stiffness eigenvalue is such a pair.
#[test]
fn repeated_eigenvalues_are_reported_with_their_multiplicity() {
    let (s5, q5) = prism(5, false);
    let a5 = axial_stiffness(&s5).unwrap();
    let pair = smallest_stiffness_eigenvalue(&s5, &q5, &a5)
        .unwrap()
        .unwrap();
    assert_eq!(pair.multiplicity, 2, "{pair:?}");
    assert!(pair.axial_stiffnesses.is_empty() && pair.prestress_level.is_none());
    let (s, q) = prism(4, false);
    let a = axial_stiffness(&s).unwrap();
    let modes = natural_frequencies(&s, &q, &a).unwrap();
    let repeated: Vec<&EigenDerivative> = modes
        .iter()
        .filter(|m| m.multiplicity == 2 && m.value > 0.0)
        .collect();
    assert!(!repeated.is_empty(), "{modes:?}");
    for m in repeated {
        assert!(m.force_densities.is_empty() && m.prestress_level.is_none());
    }
    // the six rigid-body motions of the free-standing prism: frequency 0 (their ω² is
    // round-off), no
    // derivatives
    let zero = modes
        .iter()
        .filter(|m| m.value == 0.0 && m.prestress_level.is_none())
        .count();
    assert_eq!(zero, 6, "{modes:?}");
}

#[test]
fn wrong_inputs_are_refused_by_name() {
    let (s, q) = prism(3, false);
    let a = axial_stiffness(&s).unwrap();
    let short = DVector::from_element(q.len() - 1, 1.0);
    let e = smallest_stiffness_eigenvalue(&s, &short, &a)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("force densities") && e.contains("expected 12"),
        "{e}"
    );
    let e = natural_frequencies(&s, &q, &a[1..])
        .unwrap_err()
        .to_string();
    assert!(e.contains("axial stiffnesses"), "{e}");
    // a massless free node
    let bare = snelson(3, snelson_twist(3), 1.0, 1.0, 1.0).build().unwrap();
    let e = natural_frequencies(&bare, &q, &a).unwrap_err().to_string();
    assert!(e.contains("mass"), "{e}");
}
