//! Inverse form-finding (issue 47, item 2; `formfind::design`): the objective's exact
//! gradient against central finite differences on the five structures of the sensitivity
//! tests, every goal kind and every error kind; the optimiser's optimum against the
//! Karush–Kuhn–Tucker conditions and, for one variable, against a golden-section search of
//! the objective; a reachable target met exactly; the refusals naming their item. The
//! residuals of sum-of-squares problems: ‖r‖² and 2 Jᵀ r against the objective and its
//! gradient, J against central differences, and Levenberg–Marquardt reaching L-BFGS-B's
//! optimum with bounds active.

use crate::sensitivity::{cable_net, spread, structures};
use formfind::design::lbfgsb::{minimize, LbfgsbSettings};
use formfind::design::{
    design, DesignProblem, DesignSpec, ErrorKind, GoalSpec, OptimizerMethod, OptimizerSpec,
    ParameterSpec, Selection, TermSpec,
};
use formfind::Topology;

/// `t` with every member's own force density `q` (its groups' removed).
fn with_q(mut t: Topology, q: &[f64]) -> Topology {
    for g in t.groups.values_mut() {
        g.force_density = None;
    }
    for (k, m) in t.bars.iter_mut().chain(t.strings.iter_mut()).enumerate() {
        m.force_density = Some(q[k]);
    }
    t
}

fn term(error: ErrorKind, weight: f64, goals: Vec<GoalSpec>) -> TermSpec {
    TermSpec {
        name: None,
        error,
        weight,
        goals,
    }
}

/// Every goal kind on `t` (targets from a deterministic spread), one term per error kind.
fn every_goal(t: &Topology) -> DesignSpec {
    let m = t.n_members();
    let held: Vec<usize> = t.fixed.iter().map(|f| f.node).collect();
    let free: Vec<usize> = (0..t.n_nodes).filter(|i| !held.contains(i)).collect();
    let some = |n: usize, of: usize| (0..n.min(of)).collect::<Vec<usize>>();
    let positions = GoalSpec::Position {
        nodes: Some(free.clone()),
        target: None,
        targets: Some(
            free.iter()
                .map(|&i| [spread(i), spread(i + 5), spread(i + 9)])
                .collect(),
        ),
        weight: 1.3,
    };
    let lengths = GoalSpec::Length {
        members: Some(some(4, m)),
        group: None,
        target: Some(0.7),
        targets: None,
        weight: 1.0,
    };
    let forces = GoalSpec::Force {
        members: Some((0..m).rev().take(3).collect()),
        group: None,
        target: None,
        targets: Some(vec![0.5, -0.2, 1.1]),
        weight: 0.8,
    };
    let directions = GoalSpec::Direction {
        members: Some(some(3, m)),
        group: None,
        target: Some([0.2, 0.3, 1.0]),
        targets: None,
        weight: 1.0,
    };
    let reactions = GoalSpec::Reaction {
        nodes: None,
        target: Some([0.1, -0.1, 0.5]),
        targets: None,
        weight: 1.0,
    };
    let limit = GoalSpec::ReactionLimit {
        nodes: None,
        limit: 0.05,
        weight: 2.0,
    };
    let load_path = GoalSpec::LoadPath {
        members: None,
        target: None,
        weight: 0.1,
    };
    let heights = GoalSpec::Coordinate {
        nodes: Some(free.clone()),
        axis: 2,
        target: Some(0.3),
        targets: None,
        weight: 0.9,
    };
    let magnitudes = GoalSpec::ReactionForce {
        nodes: None,
        target: Some(0.4),
        targets: None,
        weight: 1.1,
    };
    let plane = GoalSpec::Plane {
        nodes: None,
        point: [0.1, 0.2, 0.3],
        normal: [0.3, -0.2, 1.0],
        weight: 0.7,
    };
    let line = GoalSpec::Line {
        nodes: Some(free.iter().take(3).copied().collect()),
        point: [0.0, 0.1, 0.0],
        direction: [1.0, 0.5, 0.2],
        weight: 0.4,
    };
    let regulariser = GoalSpec::ForceDensity {
        members: None,
        group: None,
        target: None,
        targets: None,
        weight: 1e-3,
    };
    let smooth = GoalSpec::Smoothness {
        nodes: None,
        weight: 0.5,
    };
    DesignSpec {
        parameters: vec![],
        terms: vec![
            term(ErrorKind::Squared, 1.0, vec![positions.clone(), smooth]),
            term(
                ErrorKind::MeanSquared,
                0.7,
                vec![lengths.clone(), forces.clone()],
            ),
            term(ErrorKind::RootMeanSquared, 1.1, vec![directions, reactions]),
            term(ErrorKind::Prediction, 1.0, vec![load_path]),
            term(ErrorKind::MeanAbsolute, 0.3, vec![lengths, forces, limit]),
            term(ErrorKind::Absolute, 0.2, vec![positions]),
            term(ErrorKind::Squared, 0.6, vec![heights, magnitudes]),
            term(ErrorKind::MeanSquared, 0.5, vec![plane, line, regulariser]),
        ],
        optimizer: OptimizerSpec::default(),
    }
}

/// The central difference of the objective along variable j, Richardson-extrapolated.
fn central(p: &DesignProblem, v: &[f64], j: usize) -> f64 {
    let h = 1e-4 * v[j].abs().max(1e-3);
    let at = |h: f64| {
        let (mut a, mut b) = (v.to_vec(), v.to_vec());
        a[j] += h;
        b[j] -= h;
        (p.objective(&a).unwrap().0 - p.objective(&b).unwrap().0) / (2.0 * h)
    };
    (4.0 * at(h / 2.0) - at(h)) / 3.0
}

#[test]
fn the_objective_gradient_matches_central_differences_on_five_structures() {
    let mut worst = 0.0f64;
    for (name, t, q) in structures() {
        let t = with_q(t, &q);
        let spec = every_goal(&t);
        let p = DesignProblem::new(&t, &spec).unwrap();
        let v = p.start();
        let (f, g) = p.objective(&v).unwrap();
        assert!(f.is_finite() && f > 0.0, "{name}: {f}");
        let scale = g.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        for j in 0..v.len() {
            let fd = central(&p, &v, j);
            let e = (g[j] - fd).abs() / scale;
            worst = worst.max(e);
            assert!(
                e < 1e-6,
                "{name}: variable {j}: exact {} central {fd} ({e:.1e})",
                g[j]
            );
        }
    }
    eprintln!("worst relative difference of the gradient: {worst:.1e}");
}

#[test]
fn groups_and_shared_members_sum_their_members_derivatives() {
    // the cable net: one shared force density for the first row of strings, each of the
    // others its own; the shared variable's derivative is the central difference of the
    // objective when all its members move together
    let (t, q) = cable_net(3);
    let t = with_q(t, &q);
    let mut spec = every_goal(&t);
    spec.parameters = vec![
        ParameterSpec {
            members: vec![0, 1, 2],
            shared: true,
            ..ParameterSpec::default()
        },
        ParameterSpec {
            members: (3..t.n_members()).collect(),
            lower: Some(0.5),
            ..ParameterSpec::default()
        },
    ];
    let p = DesignProblem::new(&t, &spec).unwrap();
    assert_eq!(p.members()[0], vec![0, 1, 2]);
    assert_eq!(p.start().len(), t.n_members() - 2);
    assert_eq!(p.lower()[1], 0.5);
    let v = p.start();
    let (_, g) = p.objective(&v).unwrap();
    let scale = g.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for j in [0, 1, 5] {
        let fd = central(&p, &v, j);
        assert!((g[j] - fd).abs() / scale < 1e-6, "{j}: {} {fd}", g[j]);
    }
}

/// A cable net asked for equal boundary forces and equal inner lengths (jax-fdm's cable-net
/// example in small), every q ≥ `floor`.
fn net_problem(floor: f64) -> (Topology, DesignSpec) {
    let (t, q) = cable_net(4);
    let t = with_q(t, &q);
    let held: Vec<usize> = t.fixed.iter().map(|f| f.node).collect();
    let pairs = t.member_nodes();
    let (edge, inner): (Vec<usize>, Vec<usize>) =
        (0..t.n_members()).partition(|&k| pairs[k].iter().any(|i| held.contains(i)));
    let spec = DesignSpec {
        parameters: vec![ParameterSpec {
            select: Some(Selection::Strings),
            lower: Some(floor),
            ..ParameterSpec::default()
        }],
        terms: vec![
            term(
                ErrorKind::MeanSquared,
                1.0,
                vec![GoalSpec::Force {
                    members: Some(edge),
                    group: None,
                    target: Some(1.0),
                    targets: None,
                    weight: 1.0,
                }],
            ),
            term(
                ErrorKind::MeanSquared,
                1.0,
                vec![GoalSpec::Length {
                    members: Some(inner),
                    group: None,
                    target: Some(0.3),
                    targets: None,
                    weight: 1.0,
                }],
            ),
        ],
        optimizer: OptimizerSpec {
            ftol: 1e-15,
            gtol: 1e-10,
            ..OptimizerSpec::default()
        },
    };
    (t, spec)
}

#[test]
fn the_optimum_meets_the_kkt_conditions_with_bounds_active() {
    // a floor above some of the unbounded optimum's force densities (1.71 and 2.24 of 1.71
    // to 4.84: that optimum meets every goal exactly, objective 7·10⁻¹⁶), so that they rest
    // on it
    let (t, spec) = net_problem(2.0);
    let d = design(&t, &spec).unwrap();
    assert!(d.converged, "{}", d.stop);
    assert!(d.objective < 0.5 * d.initial_objective);
    // the projected gradient from the variables' own values, bounds and gradients; the point
    // stationary where it is within gtol, which the gradient rule's stop means
    let pg = d.variables.iter().fold(0.0f64, |a, v| {
        a.max((v.value - (v.value - v.gradient).clamp(v.lower, v.upper)).abs())
    });
    assert_eq!(d.projected_gradient, pg);
    assert_eq!(d.stationary, pg <= spec.optimizer.gtol);
    assert!(d.stop != "gradient" || d.stationary);
    // stopped on the objective rule at once (ftol 0.5): converged, not stationary
    let mut early = spec.clone();
    early.optimizer.ftol = 0.5;
    let e = design(&t, &early).unwrap();
    assert_eq!(
        (e.converged, e.stop, e.stationary),
        (true, "objective", false)
    );
    assert!(e.projected_gradient > early.optimizer.gtol);
    let on_bound = d.variables.iter().filter(|v| v.value == v.lower).count();
    assert!(
        on_bound > 0,
        "no bound active: the check would not test one"
    );
    let scale = d
        .variables
        .iter()
        .fold(0.0f64, |a, v| a.max(v.gradient.abs()));
    for v in &d.variables {
        if v.value == v.lower {
            // at the lower bound the objective may only rise inwards
            assert!(v.gradient >= -1e-9, "{v:?}");
        } else {
            assert!(v.gradient.abs() < 1e-6 * scale.max(1.0), "{v:?}");
        }
    }
    // the history is monotone and ends at the result
    for w in d.history.windows(2) {
        assert!(w[1].objective <= w[0].objective);
    }
    assert_eq!(d.history.last().unwrap().objective, d.objective);
    assert_eq!(d.history[0].objective, d.initial_objective);
    // every row's terms are its own point's (the line search may accept an earlier trial
    // than its last)
    for row in &d.history {
        let terms: f64 = row.terms.iter().sum();
        assert!(
            (terms - row.objective).abs() <= 1e-14 * row.objective,
            "{row:?}"
        );
    }
    // the designed topology reproduces the designed form by the plain force density method
    let found = formfind::form_find(&d.topology, &formfind::Settings::default()).unwrap();
    for (a, b) in found.nodes.iter().zip(&d.nodes) {
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() < 1e-12, "{a:?} {b:?}");
        }
    }
}

#[test]
fn one_variable_agrees_with_a_golden_section_search() {
    // the cable net's strings as one group: the objective is a function of one number,
    // minimised independently by a golden-section search on its values alone
    let (t, spec) = net_problem(0.1);
    let mut spec = spec;
    spec.parameters = vec![ParameterSpec {
        members: (0..t.n_members()).collect(),
        shared: true,
        lower: Some(0.1),
        ..ParameterSpec::default()
    }];
    let d = design(&t, &spec).unwrap();
    let p = DesignProblem::new(&t, &spec).unwrap();
    let f = |x: f64| p.objective(&[x]).unwrap().0;
    let (mut a, mut b) = (0.1, 20.0);
    let r = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..200 {
        let (c, e) = (b - r * (b - a), a + r * (b - a));
        if f(c) < f(e) {
            b = e;
        } else {
            a = c;
        }
    }
    let golden = 0.5 * (a + b);
    let v = d.variables[0].value;
    assert!(
        (v - golden).abs() < 1e-6 * golden,
        "L-BFGS-B {v} golden {golden}"
    );
    assert!((d.objective - f(golden)).abs() <= 1e-12 * f(golden));
}

#[test]
fn projected_lbfgs_solves_rosenbrock_and_a_bounded_quadratic() {
    let settings = LbfgsbSettings {
        ftol: 0.0,
        gtol: 1e-10,
        ..LbfgsbSettings::default()
    };
    let inf = [f64::INFINITY; 2];
    let ninf = [f64::NEG_INFINITY; 2];
    let rosen = |x: &[f64], g: &mut [f64]| -> Result<f64, ()> {
        let (a, b) = (1.0 - x[0], x[1] - x[0] * x[0]);
        g[0] = -2.0 * a - 400.0 * x[0] * b;
        g[1] = 200.0 * b;
        Ok(a * a + 100.0 * b * b)
    };
    let m = minimize(rosen, &[-1.2, 1.0], &ninf, &inf, &settings).unwrap();
    assert!(
        (m.x[0] - 1.0).abs() < 1e-9 && (m.x[1] - 1.0).abs() < 1e-9,
        "{:?}",
        m
    );
    // ½ xᵀ A x − bᵀ x on 0 ≤ x ≤ 1 with A = [[4, 1], [1, 3]], b = (−1, 5): the minimum has
    // x₀ = 0 (its gradient 1 · x₁ + 1 > 0 pushes outward) and x₁ = 1 (4 · ... : unconstrained
    // x₁ = 5/3 lies past the upper bound)
    let quad = |x: &[f64], g: &mut [f64]| -> Result<f64, ()> {
        g[0] = 4.0 * x[0] + x[1] + 1.0;
        g[1] = x[0] + 3.0 * x[1] - 5.0;
        Ok(0.5 * (4.0 * x[0] * x[0] + 2.0 * x[0] * x[1] + 3.0 * x[1] * x[1]) + x[0] - 5.0 * x[1])
    };
    let m = minimize(quad, &[0.5, 0.5], &[0.0, 0.0], &[1.0, 1.0], &settings).unwrap();
    assert_eq!(m.x, vec![0.0, 1.0]);
    assert!(m.stop.converged());
}

#[test]
fn bad_problems_are_refused_naming_the_item() {
    let (t, spec) = net_problem(0.1);
    let m = t.n_members();
    let cases: Vec<(DesignSpec, &str)> = vec![
        (
            DesignSpec {
                parameters: vec![ParameterSpec {
                    members: vec![m + 3],
                    ..ParameterSpec::default()
                }],
                ..spec.clone()
            },
            "design.parameters[0].members",
        ),
        (
            DesignSpec {
                parameters: vec![ParameterSpec {
                    group: Some("nope".into()),
                    ..ParameterSpec::default()
                }],
                ..spec.clone()
            },
            "design.parameters[0].group",
        ),
        (
            DesignSpec {
                parameters: vec![ParameterSpec {
                    select: Some(Selection::All),
                    upper: Some(-1.0),
                    ..ParameterSpec::default()
                }],
                ..spec.clone()
            },
            "design.parameters[0]",
        ),
        (
            DesignSpec {
                parameters: vec![
                    ParameterSpec {
                        members: vec![0, 1],
                        ..ParameterSpec::default()
                    },
                    ParameterSpec {
                        members: vec![1],
                        ..ParameterSpec::default()
                    },
                ],
                ..spec.clone()
            },
            "design.parameters[1]",
        ),
        (
            DesignSpec {
                terms: vec![],
                ..spec.clone()
            },
            "design.terms",
        ),
        (
            DesignSpec {
                terms: vec![term(
                    ErrorKind::Squared,
                    1.0,
                    vec![GoalSpec::Length {
                        members: Some(vec![0, 1]),
                        group: None,
                        target: None,
                        targets: Some(vec![1.0]),
                        weight: 1.0,
                    }],
                )],
                ..spec.clone()
            },
            "design.terms[0].goals[0].targets",
        ),
        (
            DesignSpec {
                terms: vec![term(
                    ErrorKind::Squared,
                    1.0,
                    vec![GoalSpec::Reaction {
                        nodes: Some(vec![6]),
                        target: Some([0.0; 3]),
                        targets: None,
                        weight: 1.0,
                    }],
                )],
                ..spec.clone()
            },
            "design.terms[0].goals[0].nodes",
        ),
        (
            DesignSpec {
                terms: vec![term(
                    ErrorKind::Squared,
                    1.0,
                    vec![GoalSpec::Position {
                        nodes: None,
                        target: None,
                        targets: None,
                        weight: 1.0,
                    }],
                )],
                ..spec.clone()
            },
            "design.terms[0].goals[0].target",
        ),
    ];
    for (spec, item) in cases {
        let e = design(&t, &spec).unwrap_err().to_string();
        assert!(
            e.contains(&format!("{item}:")) || e.contains(&format!("{item} ")),
            "{item}: {e}"
        );
    }
}

#[test]
fn attainable_goals_are_met_to_round_off() {
    // equal edge forces 1 N and inner lengths 0.3 m are attainable on the 4 × 4 net: the
    // designed form carries exactly those
    let (t, spec) = net_problem(0.1);
    let d = design(&t, &spec).unwrap();
    assert!(
        d.converged && d.objective < 1e-12,
        "{} {}",
        d.objective,
        d.stop
    );
    let held: Vec<usize> = t.fixed.iter().map(|f| f.node).collect();
    for (k, [a, b]) in t.member_nodes().into_iter().enumerate() {
        if held.contains(&a) || held.contains(&b) {
            assert!((d.force[k] - 1.0).abs() < 1e-6, "{k}: {}", d.force[k]);
        } else {
            assert!((d.length[k] - 0.3).abs() < 1e-6, "{k}: {}", d.length[k]);
        }
    }
}

#[test]
fn a_sign_free_member_may_become_a_bar() {
    // a node between anchors at x = 0 and x = 2, strings of q₁ (to 0) and q₂ = 1 (to 2): it
    // sits at x = 2 q₂ / (q₁ + q₂), so the target x = 3 past the anchors needs q₁ = −1/3, a
    // bar in compression
    let t = Topology {
        n_nodes: 3,
        strings: vec![
            formfind::Member::new(0, 1).force_density(1.0),
            formfind::Member::new(1, 2).force_density(1.0),
        ],
        fixed: vec![
            formfind::FixedNode {
                node: 0,
                position: [0.0, 0.0, 0.0],
            },
            formfind::FixedNode {
                node: 2,
                position: [2.0, 0.0, 0.0],
            },
        ],
        ..Topology::default()
    };
    let goal = GoalSpec::Coordinate {
        nodes: Some(vec![1]),
        axis: 0,
        target: Some(3.0),
        targets: None,
        weight: 1.0,
    };
    let mut spec = DesignSpec {
        parameters: vec![ParameterSpec {
            members: vec![0],
            ..ParameterSpec::default()
        }],
        terms: vec![term(ErrorKind::Squared, 1.0, vec![goal])],
        optimizer: OptimizerSpec {
            ftol: 0.0,
            gtol: 1e-12,
            ..OptimizerSpec::default()
        },
    };
    // with the member's sign kept, x = 2 / (q₁ + 1) < 2 and the goal is out of reach: q₁ at
    // its floor
    let kept = design(&t, &spec).unwrap();
    assert_eq!(kept.force_density[0], formfind::design::SIGN_FLOOR);
    assert!(kept.changed_kind.is_empty());
    spec.parameters[0].sign = Some("free".into());
    let d = design(&t, &spec).unwrap();
    assert!(
        (d.force_density[0] + 1.0 / 3.0).abs() < 1e-9,
        "{:?}",
        d.force_density
    );
    assert!(d.objective < 1e-18);
    assert_eq!(d.changed_kind, vec![0]);
    assert_eq!((d.topology.bars.len(), d.topology.strings.len()), (1, 1));
    let found = formfind::form_find(&d.topology, &formfind::Settings::default()).unwrap();
    assert!((found.nodes[1].x - 3.0).abs() < 1e-9);
    spec.parameters[0].sign = Some("either".into());
    let e = design(&t, &spec).unwrap_err().to_string();
    assert!(e.contains("design.parameters[0].sign"), "{e}");
}

/// `every_goal` with every term's error made a sum of squares (root-mean-squared and
/// mean-absolute become mean-squared, the others squared): every goal kind, as residuals.
fn every_goal_squared(t: &Topology) -> DesignSpec {
    let mut spec = every_goal(t);
    for term in &mut spec.terms {
        term.error = match term.error {
            ErrorKind::MeanSquared | ErrorKind::RootMeanSquared | ErrorKind::MeanAbsolute => {
                ErrorKind::MeanSquared
            }
            _ => ErrorKind::Squared,
        };
    }
    spec
}

#[test]
fn the_residuals_jacobian_matches_the_gradient_and_central_differences() {
    let mut worst = 0.0f64;
    for (name, t, q) in structures() {
        let t = with_q(t, &q);
        let p = DesignProblem::new(&t, &every_goal_squared(&t)).unwrap();
        let v = p.start();
        let (r, j) = p.residuals(&v).unwrap();
        let (f, g) = p.objective(&v).unwrap();
        // f = ‖r‖² and ∇f = 2 Jᵀ r: the residuals against the objective's own adjoint
        let rr: f64 = r.iter().map(|x| x * x).sum();
        assert!((rr - f).abs() <= 1e-12 * f, "{name}: ‖r‖² {rr} f {f}");
        let scale = g.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        for (c, gc) in g.iter().enumerate() {
            let jtr: f64 = (0..r.len()).map(|i| j[(i, c)] * r[i]).sum();
            assert!((2.0 * jtr - gc).abs() <= 1e-10 * scale, "{name}: {c}");
        }
        // each column against central differences of the residuals
        let jmax = j.amax();
        for c in 0..v.len() {
            let h = 1e-4 * v[c].abs().max(1e-3);
            let at = |h: f64| {
                let (mut a, mut b) = (v.clone(), v.clone());
                a[c] += h;
                b[c] -= h;
                let (ra, _) = p.residuals(&a).unwrap();
                let (rb, _) = p.residuals(&b).unwrap();
                ra.iter()
                    .zip(&rb)
                    .map(|(x, y)| (x - y) / (2.0 * h))
                    .collect::<Vec<f64>>()
            };
            let (d1, d2) = (at(h), at(h / 2.0));
            for i in 0..r.len() {
                let fd = (4.0 * d2[i] - d1[i]) / 3.0;
                let e = (j[(i, c)] - fd).abs() / jmax;
                worst = worst.max(e);
                assert!(
                    e < 1e-6,
                    "{name}: dr{i}/dv{c}: exact {} central {fd}",
                    j[(i, c)]
                );
            }
        }
    }
    eprintln!("worst relative difference of the Jacobian: {worst:.1e}");
}

#[test]
fn levenberg_marquardt_reaches_the_lbfgsb_optimum_with_bounds_active() {
    // the KKT problem above: a floor on which some force densities rest
    let (t, mut spec) = net_problem(2.0);
    let quasi_newton = design(&t, &spec).unwrap();
    spec.optimizer.method = OptimizerMethod::LevenbergMarquardt;
    let lm = design(&t, &spec).unwrap();
    assert!(
        lm.converged && lm.method == "levenberg_marquardt",
        "{}",
        lm.stop
    );
    let rel = (lm.objective - quasi_newton.objective).abs() / quasi_newton.objective;
    assert!(rel < 1e-8, "{} {}", lm.objective, quasi_newton.objective);
    for (a, b) in lm.variables.iter().zip(&quasi_newton.variables) {
        assert!((a.value - b.value).abs() < 1e-5 * b.value, "{a:?} {b:?}");
    }
    assert!(lm.variables.iter().any(|v| v.value == v.lower));
    // in far fewer iterations: Gauss–Newton near a small-residual minimum
    assert!(
        lm.iterations * 4 < quasi_newton.iterations,
        "{} {}",
        lm.iterations,
        quasi_newton.iterations
    );
    for w in lm.history.windows(2) {
        assert!(w[1].objective < w[0].objective);
    }
    for row in &lm.history {
        let terms: f64 = row.terms.iter().sum();
        assert!(
            (terms - row.objective).abs() <= 1e-14 * row.objective,
            "{row:?}"
        );
    }
}

#[test]
fn levenberg_marquardt_refuses_a_term_that_is_not_a_sum_of_squares() {
    let (t, q) = cable_net(4);
    let t = with_q(t, &q);
    let mut spec = every_goal(&t);
    spec.optimizer.method = OptimizerMethod::LevenbergMarquardt;
    let e = design(&t, &spec).unwrap_err().to_string();
    assert!(
        e.contains("design.terms[2].error") && e.contains("root_mean_squared"),
        "{e}"
    );
    let p = DesignProblem::new(&t, &spec).unwrap();
    let e = p.residuals(&p.start()).unwrap_err().to_string();
    assert!(e.contains("design.terms[2].error"), "{e}");
}
