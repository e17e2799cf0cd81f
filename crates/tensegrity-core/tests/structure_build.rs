//! Structure building by indices (issue 25, item 3): the builder's member checks, which no
//! longer use a hash map or format a name per member, give the same structure and the same
//! first error as the checks they replaced. The replaced checks are written out here as the
//! reference (a `HashMap` of unordered pairs, every member's name formatted up front), and
//! both are run on random member lists with duplicates, self-loops, zero-length members and
//! nodes out of range, in every proportion.

use nalgebra::Vector3;
use proptest::prelude::*;
use std::collections::HashMap;
use tensegrity_core::error::ModelError;
use tensegrity_core::{Bar, CoreError, MemberId, StringMember, Structure};

/// The member checks as `StructureBuilder::build` did them before: one pass in member order,
/// range, self-loop, duplicate (hash map), zero length; then isolated nodes.
fn old_checks(
    nodes: &[Vector3<f64>],
    bars: &[[usize; 2]],
    strings: &[[usize; 2]],
) -> Option<ModelError> {
    let n = nodes.len();
    let mut seen: HashMap<(usize, usize), MemberId> = HashMap::new();
    let mut touched = vec![false; n];
    let members = bars
        .iter()
        .enumerate()
        .map(|(i, p)| (MemberId::Bar(i), *p))
        .chain(
            strings
                .iter()
                .enumerate()
                .map(|(i, p)| (MemberId::String(i), *p)),
        );
    for (id, [a, b]) in members {
        let item = id.to_string();
        for node in [a, b] {
            if node >= n {
                return Some(ModelError::NodeIndexOutOfRange {
                    item,
                    node,
                    n_nodes: n,
                });
            }
        }
        if a == b {
            return Some(ModelError::SelfLoop {
                member: id,
                node: a,
            });
        }
        let key = (a.min(b), a.max(b));
        if let Some(&other) = seen.get(&key) {
            return Some(ModelError::DuplicateMember {
                member: id,
                other,
                a: key.0,
                b: key.1,
            });
        }
        seen.insert(key, id);
        let length = (nodes[b] - nodes[a]).norm();
        if !length.is_finite() {
            return Some(ModelError::MemberLengthOverflow { member: id, a, b });
        }
        let scale = nodes[a].norm().max(nodes[b].norm()).max(1.0);
        if length <= 1e-12 * scale {
            return Some(ModelError::ZeroLengthMember {
                member: id,
                a,
                b,
                length,
            });
        }
        touched[a] = true;
        touched[b] = true;
    }
    touched
        .iter()
        .position(|&t| !t)
        .map(|node| ModelError::IsolatedNode { node })
}

fn build(
    nodes: &[Vector3<f64>],
    bars: &[[usize; 2]],
    strings: &[[usize; 2]],
) -> Result<Structure, CoreError> {
    let mut b = Structure::builder().nodes(nodes.iter().map(|p| [p.x, p.y, p.z]));
    for &[i, j] in bars {
        b = b.bar(Bar::new(i, j).mass(1.0));
    }
    for &[i, j] in strings {
        b = b.string(StringMember::new(i, j).stiffness(10.0));
    }
    b.build()
}

/// Nodes on a coarse grid so that some coincide (zero-length members).
fn nodes(n: usize, seed: u64) -> Vec<Vector3<f64>> {
    (0..n)
        .map(|i| {
            let h = (i as u64 ^ seed).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40;
            Vector3::new((h % 3) as f64, ((h / 3) % 3) as f64, ((h / 9) % 2) as f64)
        })
        .collect()
}

fn compare(nodes: &[Vector3<f64>], bars: &[[usize; 2]], strings: &[[usize; 2]]) {
    let old = old_checks(nodes, bars, strings);
    match (build(nodes, bars, strings), old) {
        (Ok(s), None) => {
            assert_eq!(s.n_nodes(), nodes.len());
            let expected: Vec<[usize; 2]> = bars.iter().chain(strings).copied().collect();
            assert_eq!(s.member_nodes(), expected);
            assert_eq!(s.nodes(), nodes);
        }
        (Err(CoreError::Model(new)), Some(old)) => {
            assert_eq!(new.to_string(), old.to_string());
            assert_eq!(format!("{new:?}"), format!("{old:?}"));
        }
        (new, old) => panic!("new {new:?}, old {old:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Small node sets and many members: duplicates and coincident nodes are frequent; a few
    /// indices run past the last node.
    #[test]
    fn the_first_error_is_the_old_one(
        n in 2usize..14,
        seed in any::<u64>(),
        bars in prop::collection::vec((0usize..15, 0usize..15), 0..12),
        strings in prop::collection::vec((0usize..15, 0usize..15), 1..40),
    ) {
        let pairs = |v: &[(usize, usize)]| v.iter().map(|&(a, b)| [a, b]).collect::<Vec<_>>();
        compare(&nodes(n, seed), &pairs(&bars), &pairs(&strings));
    }

    /// One hub node in many members (the spokes of a wheel): the large buckets, which are
    /// sorted rather than scanned.
    #[test]
    fn hubs_with_duplicates(
        spokes in 9usize..40,
        repeat in prop::option::of((0usize..40, 0usize..40)),
        flip in any::<bool>(),
    ) {
        let n = spokes + 1;
        let nodes: Vec<_> = (0..n)
            .map(|i| Vector3::new((i as f64).cos(), (i as f64).sin(), i as f64))
            .collect();
        let mut strings: Vec<[usize; 2]> = (1..n).map(|i| if flip { [i, 0] } else { [0, i] }).collect();
        if let Some((at, copy)) = repeat {
            let at = at % strings.len();
            let copy = copy % strings.len();
            let [a, b] = strings[copy];
            strings.insert(at, [b, a]);
        }
        compare(&nodes, &[[1, 2]], &strings);
    }
}

#[test]
fn a_valid_structure_keeps_its_members_and_a_duplicate_names_the_first() {
    let nodes = nodes(6, 1)
        .into_iter()
        .enumerate()
        .map(|(i, _)| Vector3::new(i as f64, (i * i) as f64, 0.0))
        .collect::<Vec<_>>();
    compare(&nodes, &[[0, 1], [2, 3]], &[[1, 2], [3, 4], [4, 5], [5, 0]]);
    compare(
        &nodes,
        &[[0, 1], [2, 3]],
        &[[1, 2], [3, 4], [1, 0], [0, 1], [5, 0]],
    );
    let e = build(
        &nodes,
        &[[0, 1], [2, 3]],
        &[[1, 2], [3, 4], [1, 0], [4, 5], [5, 0]],
    )
    .unwrap_err();
    assert!(e.to_string().contains("string 2: duplicates bar 0"), "{e}");
}
