//! The toroid built by indices (issue 25, item 3) is the toroid built before: the structure
//! (nodes, members in order, bar masses), the member labels and the axle equal a reference
//! built here the old way — the member list written out from the thesis's prism (bars
//! n1–n4, n2–n5, n3–n6; strings: the other twelve pairs of n1..n6, n6 of prism k being n3 of
//! prism k + 1), then the axle, the spokes, the inner and the outer rings, each member added
//! to the core builder one call at a time.

use nalgebra::Vector3;
use tensegrity_core::{Bar, StringMember, Structure};
use toroid::{build, prism_nodes, prism_rotation, MemberLabel, Role, Stabilize, ToroidParams};

const BARS: [(usize, usize); 3] = [(0, 3), (1, 4), (2, 5)];
const STRINGS: [(usize, usize); 12] = [
    (0, 1),
    (0, 2),
    (0, 4),
    (0, 5),
    (1, 2),
    (1, 3),
    (1, 5),
    (2, 3),
    (2, 4),
    (3, 4),
    (3, 5),
    (4, 5),
];

type Members = Vec<([usize; 2], MemberLabel)>;

fn label(prism: Option<usize>, role: Role) -> MemberLabel {
    MemberLabel { prism, role }
}

/// The reference: nodes, bars and strings with their labels, built member by member.
fn reference(p: &ToroidParams, opts: Stabilize, density: f64) -> (Structure, Members, Members) {
    let n = p.sides;
    let node = |k: usize, j: usize| {
        if j == 5 {
            5 * ((k + 1) % n) + 2
        } else {
            5 * k + j
        }
    };
    let local = prism_nodes(p);
    let mut nodes: Vec<Vector3<f64>> = (0..n)
        .flat_map(|k| local[..5].iter().map(move |x| prism_rotation(k, n) * x))
        .collect();
    let (mut bars, mut strings): (Members, Members) = (Vec::new(), Vec::new());
    for k in 0..n {
        for (a, b) in BARS {
            let role = if a == 2 { Role::RimBar } else { Role::TreadBar };
            bars.push(([node(k, a), node(k, b)], label(Some(k), role)));
        }
        for (a, b) in STRINGS {
            strings.push(([node(k, a), node(k, b)], label(Some(k), Role::PrismString)));
        }
    }
    if opts.spokes {
        let (l, r) = (nodes.len(), nodes.len() + 1);
        nodes.push(Vector3::new(-p.outer_tread / 2.0, 0.0, 0.0));
        nodes.push(Vector3::new(p.outer_tread / 2.0, 0.0, 0.0));
        bars.push(([l, r], label(None, Role::AxleBar)));
        for k in 0..n {
            for end in [l, r] {
                strings.push(([node(k, 2), end], label(Some(k), Role::Spoke)));
            }
        }
    }
    for (on, locals, role) in [
        (opts.inner, [3, 4], Role::InnerRing),
        (opts.outer, [0, 1], Role::OuterRing),
    ] {
        if on {
            for k in 0..n {
                for j in locals {
                    strings.push(([node(k, j), node((k + 1) % n, j)], label(Some(k), role)));
                }
            }
        }
    }
    let mut b = Structure::builder().nodes(nodes.iter().map(|x| [x.x, x.y, x.z]));
    for &([i, j], _) in &bars {
        b = b.bar(Bar::new(i, j).mass(density * (nodes[j] - nodes[i]).norm()));
    }
    for &([i, j], _) in &strings {
        b = b.string(StringMember::new(i, j));
    }
    (b.build().unwrap(), bars, strings)
}

#[test]
fn the_toroid_is_the_one_built_member_by_member() {
    for sides in [3, 5, 8, 12, 40] {
        for opts in [
            "none",
            "spokes",
            "inner",
            "outer",
            "spokes,inner",
            "spokes,inner,outer",
        ] {
            let p = ToroidParams {
                sides,
                ..ToroidParams::default()
            };
            let stabilize: Stabilize = opts.parse().unwrap();
            let t = build(&p, stabilize, 1.7).unwrap();
            let (s, bars, strings) = reference(&p, stabilize, 1.7);
            assert_eq!(t.structure, s, "n = {sides}, {opts}");
            let labels = |m: &Members| m.iter().map(|x| x.1).collect::<Vec<_>>();
            assert_eq!(t.bar_labels, labels(&bars));
            assert_eq!(t.string_labels, labels(&strings));
            assert_eq!(t.axle.is_some(), stabilize.spokes);
            // the count of the doc: 5n (+2) nodes, 3n (+1) bars, 12n + 2n per option strings
            let extra = [stabilize.spokes, stabilize.inner, stabilize.outer]
                .iter()
                .filter(|&&o| o)
                .count();
            assert_eq!(t.structure.n_strings(), 12 * sides + 2 * sides * extra);
        }
    }
}
