//! Exact derivatives of the force density method's form with held nodes (issue 47, item 1;
//! `formfind::sensitivity`): every forward derivative (nodes, member lengths, forces,
//! reactions) and every adjoint gradient (force densities, loads, held positions) against
//! central finite differences to 10⁻⁶ relative, on five structures — the 3-bar prism and the
//! octahedron held at three nodes, a two-stage tower held at its base, a cable net and the
//! built-in grid under loads — and the two modes against each other. The refusals name
//! their item.

use formfind::sensitivity::{Cotangent, FdmSensitivity, Parameter};
use formfind::{builtin, form_find, FixedNode, Member, NodeLoad, Settings, Topology};
use nalgebra::Vector3;

/// A deterministic spread in [−1, 1] (no random crate: the same numbers everywhere).
pub(crate) fn spread(i: usize) -> f64 {
    (0.7 + 1.37 * i as f64).sin()
}

/// `t` found free-standing, then held at `held` nodes where it was found, with a load on
/// every free node and its force densities moved by up to 10 % and the bars' scaled by
/// `bars` (so that the loads and the force densities both shape it; a self-stress held at
/// three nodes of the prism leaves D_ff nearly singular, its top flung 250 m away, so its
/// bars are halved): the topology and its force densities.
fn held_form(mut t: Topology, held: &[usize], bars: f64) -> (Topology, Vec<f64>) {
    let found = form_find(&t, &Settings::default()).unwrap();
    t.fixed = held
        .iter()
        .map(|&i| FixedNode {
            node: i,
            position: found.nodes[i].into(),
        })
        .collect();
    let size = found
        .force_density
        .iter()
        .fold(0.0f64, |a, q| a.max(q.abs()));
    t.loads = (0..t.n_nodes)
        .filter(|i| !held.contains(i))
        .map(|i| NodeLoad {
            node: i,
            force: [
                0.05 * size * spread(3 * i),
                0.05 * size * spread(3 * i + 1),
                -0.1 * size,
            ],
        })
        .collect();
    let q = found
        .force_density
        .iter()
        .enumerate()
        .map(|(k, q)| {
            let kind = if t.is_bar(k) { bars } else { 1.0 };
            kind * q * (1.0 + 0.1 * spread(k + 11))
        })
        .collect();
    (t, q)
}

/// A cable net: a (k+1) × (k+1) grid of strings whose boundary is held on a saddle, every
/// inner node loaded downwards.
pub(crate) fn cable_net(k: usize) -> (Topology, Vec<f64>) {
    let id = |u: usize, v: usize| v * (k + 1) + u;
    let mut strings = Vec::new();
    for v in 0..=k {
        for u in 0..=k {
            if u < k {
                strings.push(Member::new(id(u, v), id(u + 1, v)));
            }
            if v < k {
                strings.push(Member::new(id(u, v), id(u, v + 1)));
            }
        }
    }
    let boundary = |u: usize, v: usize| u == 0 || v == 0 || u == k || v == k;
    let mut fixed = Vec::new();
    let mut loads = Vec::new();
    for v in 0..=k {
        for u in 0..=k {
            let (x, y) = (u as f64 / k as f64 - 0.5, v as f64 / k as f64 - 0.5);
            if boundary(u, v) {
                fixed.push(FixedNode {
                    node: id(u, v),
                    position: [x, y, x * x - y * y],
                });
            } else {
                loads.push(NodeLoad {
                    node: id(u, v),
                    force: [0.0, 0.0, -0.3],
                });
            }
        }
    }
    let q = (0..strings.len()).map(|k| 2.0 + spread(k)).collect();
    let t = Topology {
        n_nodes: (k + 1) * (k + 1),
        strings,
        fixed,
        loads,
        ..Topology::default()
    };
    (t, q)
}

/// The built-in grid (its boundary held) with a load on every free node.
fn loaded_grid(k: usize) -> (Topology, Vec<f64>) {
    let mut t = builtin(&format!("grid:{k}")).unwrap();
    let found = form_find(&t, &Settings::default()).unwrap();
    let held: Vec<usize> = t.fixed.iter().map(|f| f.node).collect();
    t.loads = (0..t.n_nodes)
        .filter(|i| !held.contains(i))
        .map(|i| NodeLoad {
            node: i,
            force: [0.0, 0.02 * spread(i), -0.05],
        })
        .collect();
    let q = found
        .force_density
        .iter()
        .enumerate()
        .map(|(k, q)| q * (1.0 + 0.05 * spread(k)))
        .collect();
    (t, q)
}

/// The five structures of the module docs.
pub(crate) fn structures() -> Vec<(&'static str, Topology, Vec<f64>)> {
    let (prism, q_prism) = held_form(builtin("prism:3").unwrap(), &[0, 1, 2], 0.5);
    let (octa, q_octa) = held_form(builtin("octahedron").unwrap(), &[0, 2, 4], 1.0);
    let tower = builtin("tower:3:2").unwrap();
    let base: Vec<usize> = (0..3).collect();
    let (tower, q_tower) = held_form(tower, &base, 1.0);
    let (net, q_net) = cable_net(4);
    let (grid, q_grid) = loaded_grid(2);
    vec![
        ("prism", prism, q_prism),
        ("octahedron", octa, q_octa),
        ("tower", tower, q_tower),
        ("cable net", net, q_net),
        ("loaded grid", grid, q_grid),
    ]
}

/// Every output of a form flattened: nodes, lengths, forces, reactions.
fn outputs(s: &FdmSensitivity) -> Vec<f64> {
    let mut v: Vec<f64> = s.nodes().iter().flat_map(|p| p.iter().copied()).collect();
    v.extend(s.lengths());
    v.extend(s.forces());
    v.extend(s.reactions().iter().flat_map(|p| p.iter().copied()));
    v
}

/// `t` and `q` with `parameter` moved by `h`.
fn moved(t: &Topology, q: &[f64], parameter: Parameter, h: f64) -> (Topology, Vec<f64>) {
    let (mut t, mut q) = (t.clone(), q.to_vec());
    match parameter {
        Parameter::ForceDensity(k) => q[k] += h,
        Parameter::Load { node, axis } => {
            t.loads.push(NodeLoad {
                node,
                force: std::array::from_fn(|a| if a == axis { h } else { 0.0 }),
            });
        }
        Parameter::Fixed { index, axis } => t.fixed[index].position[axis] += h,
    }
    (t, q)
}

/// The central difference of `f` (of a topology and force densities) at `parameter`,
/// extrapolated (Richardson: (4 D(h/2) − D(h)) / 3, error O(h⁴)) with h = 10⁻⁵ of the
/// parameter's scale: the held prism's form bends fast with its force densities (a plain
/// central difference at 10⁻⁵ is off by 8·10⁻⁵, at 10⁻⁶ by 8·10⁻⁷, falling as h²).
fn central<F: Fn(&Topology, &[f64]) -> Vec<f64>>(
    t: &Topology,
    q: &[f64],
    parameter: Parameter,
    scale: f64,
    f: F,
) -> Vec<f64> {
    let at = |h: f64| -> Vec<f64> {
        let (tp, qp) = moved(t, q, parameter, h);
        let (tm, qm) = moved(t, q, parameter, -h);
        let (a, b) = (f(&tp, &qp), f(&tm, &qm));
        a.iter().zip(&b).map(|(x, y)| (x - y) / (2.0 * h)).collect()
    };
    let h = 1e-5 * scale;
    let (coarse, fine) = (at(h), at(0.5 * h));
    fine.iter()
        .zip(&coarse)
        .map(|(f, c)| (4.0 * f - c) / 3.0)
        .collect()
}

/// The largest difference of `a` and `b` relative to the larger of their largest entries.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    let size = a.iter().chain(b).fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if size > 0.0 {
        gap / size
    } else {
        gap
    }
}

/// The parameters checked on `t`: every force density, the first two free nodes' loads and
/// the first two held nodes' positions (all three components).
fn parameters(t: &Topology) -> Vec<Parameter> {
    let mut p: Vec<Parameter> = (0..t.n_members()).map(Parameter::ForceDensity).collect();
    let held: Vec<usize> = t.fixed.iter().map(|f| f.node).collect();
    let free: Vec<usize> = (0..t.n_nodes)
        .filter(|i| !held.contains(i))
        .take(2)
        .collect();
    for axis in 0..3 {
        p.extend(free.iter().map(|&node| Parameter::Load { node, axis }));
        p.extend((0..2.min(held.len())).map(|index| Parameter::Fixed { index, axis }));
    }
    p
}

/// The scale of a parameter for its finite-difference step: the largest |q|, load or
/// coordinate of the structure.
fn scale_of(t: &Topology, q: &[f64], p: Parameter) -> f64 {
    match p {
        Parameter::ForceDensity(_) => q.iter().fold(0.0f64, |a, x| a.max(x.abs())),
        Parameter::Load { .. } => t
            .loads
            .iter()
            .flat_map(|l| l.force)
            .fold(0.0f64, |a, x| a.max(x.abs()))
            .max(1e-3),
        Parameter::Fixed { .. } => t
            .fixed
            .iter()
            .flat_map(|f| f.position)
            .fold(0.0f64, |a, x| a.max(x.abs()))
            .max(1e-3),
    }
}

#[test]
fn forward_derivatives_match_central_differences() {
    for (name, t, q) in structures() {
        let mut s = FdmSensitivity::new(&t, &q).unwrap();
        let mut worst = 0.0f64;
        for p in parameters(&t) {
            let d = s.forward(p).unwrap();
            let mut exact: Vec<f64> = d.nodes.iter().flat_map(|v| v.iter().copied()).collect();
            exact.extend(&d.lengths);
            exact.extend(&d.forces);
            exact.extend(d.reactions.iter().flat_map(|v| v.iter().copied()));
            let fd = central(&t, &q, p, scale_of(&t, &q, p), |t, q| {
                outputs(&FdmSensitivity::new(t, q).unwrap())
            });
            let r = relative(&exact, &fd);
            if r >= 1e-6 {
                let worst = (0..exact.len())
                    .max_by(|&a, &b| {
                        (exact[a] - fd[a])
                            .abs()
                            .total_cmp(&(exact[b] - fd[b]).abs())
                    })
                    .unwrap();
                println!(
                    "{name} {p:?}: entry {worst} of {} exact {} fd {}",
                    exact.len(),
                    exact[worst],
                    fd[worst]
                );
            }
            assert!(r < 1e-6, "{name} {p:?}: {r:.2e}");
            worst = worst.max(r);
        }
        println!("{name}: forward against central differences, worst {worst:.1e}");
    }
}

/// The objective f = Σ w_i · x_i + Σ c_k F_k (nodes and member forces, deterministic
/// weights) and its cotangent.
fn objective(s: &FdmSensitivity) -> f64 {
    let nodes: f64 = s
        .nodes()
        .iter()
        .enumerate()
        .map(|(i, x)| x.dot(&weight(i)))
        .sum();
    let forces: f64 = s
        .forces()
        .iter()
        .enumerate()
        .map(|(k, f)| spread(k + 5) * f)
        .sum();
    nodes + forces
}

fn weight(i: usize) -> Vector3<f64> {
    Vector3::new(spread(3 * i + 2), spread(3 * i + 3), spread(3 * i + 4))
}

fn cotangent(s: &FdmSensitivity, n_nodes: usize, n_members: usize) -> Cotangent {
    let mut c = Cotangent::zeros(n_nodes, n_members);
    for (i, v) in c.nodes.iter_mut().enumerate() {
        *v = weight(i);
    }
    let dg: Vec<f64> = (0..n_members).map(|k| spread(k + 5)).collect();
    c.forces(s, &dg).unwrap()
}

#[test]
fn the_adjoint_gradient_matches_the_forward_one_and_central_differences() {
    for (name, t, q) in structures() {
        let mut s = FdmSensitivity::new(&t, &q).unwrap();
        let c = cotangent(&s, t.n_nodes, t.n_members());
        let g = s.adjoint(&c).unwrap();
        let mut adjoint = Vec::new();
        let mut forward = Vec::new();
        let mut fd = Vec::new();
        for p in parameters(&t) {
            adjoint.push(match p {
                Parameter::ForceDensity(k) => g.force_densities[k],
                Parameter::Load { node, axis } => g.loads[node][axis],
                Parameter::Fixed { index, axis } => g.fixed[index][axis],
            });
            // the forward derivative of the same objective
            let d = s.forward(p).unwrap();
            let nodes: f64 = d
                .nodes
                .iter()
                .enumerate()
                .map(|(i, x)| x.dot(&weight(i)))
                .sum();
            let forces: f64 = d
                .forces
                .iter()
                .enumerate()
                .map(|(k, f)| spread(k + 5) * f)
                .sum();
            forward.push(nodes + forces);
            fd.push(
                central(&t, &q, p, scale_of(&t, &q, p), |t, q| {
                    vec![objective(&FdmSensitivity::new(t, q).unwrap())]
                })[0],
            );
        }
        // the forward-mode gradient of the objective alone (one solve per parameter)
        let gradient = s.forward_gradient(&c, &parameters(&t)).unwrap();
        let (r_forward, r_fd) = (relative(&adjoint, &forward), relative(&adjoint, &fd));
        let r_gradient = relative(&adjoint, &gradient);
        println!("{name}: adjoint against forward {r_forward:.1e} (gradient {r_gradient:.1e}), against central differences {r_fd:.1e}");
        assert!(r_forward < 1e-10, "{name}: {r_forward:.2e}");
        assert!(r_gradient < 1e-10, "{name}: {r_gradient:.2e}");
        assert!(r_fd < 1e-6, "{name}: {r_fd:.2e}");
    }
}

/// The form is the force density method's: the nodes and reactions `form_find` reports for
/// the loaded grid and the cable net, to round-off.
#[test]
fn the_form_is_the_one_form_find_reports() {
    let structures = structures();
    for (name, t, q) in structures.iter().skip(3) {
        let mut given = t.clone();
        for (k, m) in given
            .bars
            .iter_mut()
            .chain(given.strings.iter_mut())
            .enumerate()
        {
            m.force_density = Some(q[k]);
        }
        let found = form_find(&given, &Settings::default()).unwrap();
        let s = FdmSensitivity::new(t, q).unwrap();
        let size = s.nodes().iter().fold(0.0f64, |a, x| a.max(x.amax()));
        for (a, b) in s.nodes().iter().zip(&found.nodes) {
            assert!((a - b).amax() < 1e-12 * size, "{name}: {a} {b}");
        }
        assert_eq!(found.reactions.len(), t.fixed.len());
        for (r, f) in s.reactions().iter().zip(&found.reactions) {
            let gap = (r - Vector3::from(f.force)).amax();
            assert!(gap < 1e-9 * (1.0 + r.amax()), "{name}: {r} {:?}", f.force);
        }
    }
}

#[test]
fn what_is_not_covered_is_refused_by_name() {
    let err = |t: &Topology, q: &[f64]| FdmSensitivity::new(t, q).err().unwrap().to_string();
    let prism = builtin("prism:3").unwrap();
    let q = vec![1.0; prism.n_members()];
    assert!(err(&prism, &q).contains("fixed"), "{}", err(&prism, &q));
    let (net, q) = cable_net(2);
    assert!(err(&net, &q[1..]).contains("force_density"));
    let mut nan = q.clone();
    nan[3] = f64::NAN;
    assert!(err(&net, &nan).contains("member 3"));
    let mut heavy = net.clone();
    heavy.strings[0].weight = Some(1.0);
    assert!(err(&heavy, &q).contains("weight"));
    let mut s = FdmSensitivity::new(&net, &q).unwrap();
    let e = s
        .forward(Parameter::ForceDensity(99))
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("force_density") && e.contains("99"), "{e}");
    let wrong = Cotangent::zeros(1, 1);
    assert!(s
        .adjoint(&wrong)
        .err()
        .unwrap()
        .to_string()
        .contains("cotangent"));
    let e = Cotangent::zeros(net.n_nodes, net.n_members())
        .forces(&s, &[1.0])
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("forces") && e.contains("1 derivatives"), "{e}");
}

/// Dynamic relaxation's form with held nodes (`formfind::sensitivity::DrSensitivity`):
/// the cable net on its saddle, pretensioned by rest lengths 0.8 of the spacing, and the
/// self-stressed 3-bar prism held at its base (rest lengths that carry its self-stress).
fn relaxed_forms() -> Vec<(&'static str, Topology)> {
    let (mut net, _) = cable_net(3);
    let k = 3usize;
    net.nodes = Some(
        (0..(k + 1) * (k + 1))
            .map(|i| {
                let (u, v) = (i % (k + 1), i / (k + 1));
                let (x, y) = (u as f64 / k as f64 - 0.5, v as f64 / k as f64 - 0.5);
                [x, y, x * x - y * y]
            })
            .collect(),
    );
    net.loads.clear();
    for (j, m) in net.strings.iter_mut().enumerate() {
        m.length = Some(0.8 / k as f64 * (1.0 + 0.05 * spread(j)));
        m.stiffness = Some(50.0);
    }
    let mut prism = builtin("prism:3").unwrap();
    let found = form_find(&prism, &Settings::default()).unwrap();
    prism.nodes = Some(found.nodes.iter().map(|x| [x.x, x.y, x.z]).collect());
    prism.fixed = (0..3)
        .map(|i| FixedNode {
            node: i,
            position: found.nodes[i].into(),
        })
        .collect();
    let lengths: Vec<f64> = prism
        .member_nodes()
        .iter()
        .map(|&[a, b]| (found.nodes[b] - found.nodes[a]).norm())
        .collect();
    let n_bars = prism.bars.len();
    for (j, m) in prism
        .bars
        .iter_mut()
        .chain(prism.strings.iter_mut())
        .enumerate()
    {
        let ea = if j < n_bars { 1e4 } else { 1e2 };
        let t = found.force_density[j] * lengths[j];
        m.stiffness = Some(ea);
        m.length = Some(lengths[j] / (1.0 + t / ea));
    }
    vec![("cable net", net), ("prism", prism)]
}

#[test]
fn relaxed_form_derivatives_match_central_differences() {
    use formfind::sensitivity::{DrParameter, DrSensitivity};
    let settings = Settings::default();
    for (name, t) in relaxed_forms() {
        let mut s = DrSensitivity::find(&t, &settings).unwrap();
        let nodes_of = |t: &Topology| -> Vec<f64> {
            DrSensitivity::find(t, &settings)
                .unwrap()
                .nodes()
                .iter()
                .flat_map(|p| p.iter().copied())
                .collect()
        };
        // f = Σ w_i · x_i and its adjoint gradient
        let w: Vec<Vector3<f64>> = (0..t.n_nodes).map(weight).collect();
        let g = s.adjoint(&w).unwrap();
        let mut worst = 0.0f64;
        for k in 0..t.n_members() {
            for (parameter, exact_f) in [
                (DrParameter::RestLength(k), g.rest_lengths[k]),
                (DrParameter::Stiffness(k), g.stiffnesses[k]),
            ] {
                let d = s.forward(parameter).unwrap();
                let exact: Vec<f64> = d.nodes.iter().flat_map(|p| p.iter().copied()).collect();
                let base = match parameter {
                    DrParameter::RestLength(_) => t.given_lengths()[k].unwrap(),
                    DrParameter::Stiffness(_) => t.members().nth(k).unwrap().stiffness.unwrap(),
                };
                let at = |h: f64| -> Vec<f64> {
                    let moved = |sign: f64| {
                        let mut m = t.clone();
                        let member = m
                            .bars
                            .iter_mut()
                            .chain(m.strings.iter_mut())
                            .nth(k)
                            .unwrap();
                        match parameter {
                            DrParameter::RestLength(_) => member.length = Some(base + sign * h),
                            DrParameter::Stiffness(_) => member.stiffness = Some(base + sign * h),
                        }
                        nodes_of(&m)
                    };
                    let (a, b) = (moved(1.0), moved(-1.0));
                    a.iter().zip(&b).map(|(x, y)| (x - y) / (2.0 * h)).collect()
                };
                let h = 1e-4 * base;
                let fd: Vec<f64> = at(0.5 * h)
                    .iter()
                    .zip(&at(h))
                    .map(|(f, c)| (4.0 * f - c) / 3.0)
                    .collect();
                // against the largest derivative, at least the form's size over the parameter
                let floor = 1.0 / base;
                let r = relative(&exact, &fd).min(
                    exact
                        .iter()
                        .zip(&fd)
                        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
                        / floor,
                );
                assert!(r < 1e-6, "{name} {parameter:?}: {r:.2e}");
                worst = worst.max(r);
                // the adjoint's entry is the forward derivative of f
                let forward: f64 = d.nodes.iter().zip(&w).map(|(x, w)| x.dot(w)).sum();
                assert!(
                    (exact_f - forward).abs() <= 1e-9 * (1.0 + forward.abs()),
                    "{name} {parameter:?}: adjoint {exact_f} forward {forward}"
                );
            }
        }
        println!("{name}: relaxed form against central differences, worst {worst:.1e}");
    }
}

#[test]
fn relaxed_forms_without_held_nodes_or_with_loads_are_refused() {
    use formfind::sensitivity::DrSensitivity;
    let forms = relaxed_forms();
    let mut free = forms[1].1.clone();
    free.fixed.clear();
    let e = DrSensitivity::find(&free, &Settings::default())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("fixed"), "{e}");
    let mut loaded = forms[0].1.clone();
    loaded.loads.push(NodeLoad {
        node: 5,
        force: [0.0, 0.0, -1.0],
    });
    let e = DrSensitivity::find(&loaded, &Settings::default())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("loads"), "{e}");
}
