//! Node and member counts, tuple merging and numbering (ERRATA 4.6).

use michell3d::nodes::{self, NodeTuple};
use michell3d::{MichellParams, MichellTruss};
use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::FRAC_PI_6;

/// Grows the tuples with the offspring rule, as the thesis describes it, with or without merging.
fn grow(q: usize, merge: bool) -> Vec<Vec<NodeTuple>> {
    let mut levels = vec![vec![NodeTuple::new(0, 0, 0, 0)]];
    for _ in 0..q {
        let mut next: Vec<NodeTuple> = levels
            .last()
            .unwrap()
            .iter()
            .flat_map(|t| t.children())
            .collect();
        if merge {
            next = next
                .into_iter()
                .collect::<BTreeSet<_>>()
                .into_iter()
                .collect();
        }
        levels.push(next);
    }
    levels
}

#[test]
fn nodes_per_level_after_merging() {
    let q = 9;
    let merged = grow(q, true);
    let unmerged = grow(q, false);
    for l in 0..=q {
        assert_eq!(merged[l].len(), (l + 1) * (l + 2) / 2, "level {l}");
        assert_eq!(
            unmerged[l].len(),
            3usize.pow(l as u32),
            "level {l} unmerged"
        );
    }
    // e.g. (1,1,1,0) is reached from (1,0,1,0) via D+1 and from (0,1,0,0) via U+1, L+1.
    let t = NodeTuple::new(1, 1, 1, 0);
    assert_eq!(NodeTuple::new(1, 0, 1, 0).children()[2], t);
    assert_eq!(NodeTuple::new(0, 1, 0, 0).children()[0], t);
}

#[test]
fn truss_counts_match_closed_forms() {
    for q in 1..=12 {
        let expect_nodes = (q + 1) * (q + 2) * (q + 3) / 6;
        let expect_members = q * (q + 1) * (q + 2) / 2;
        for p in [
            MichellParams::cylindrical(q, 1.0, FRAC_PI_6, 0.1, 0.3),
            MichellParams::spherical(q, 1.0, FRAC_PI_6, 0.1, 0.5 / q as f64),
        ] {
            let t = MichellTruss::new(p).unwrap();
            assert_eq!(t.nodes().len(), expect_nodes, "q = {q}");
            assert_eq!(t.members().len(), expect_members, "q = {q}");
            let supports = (0..t.nodes().len()).filter(|&i| t.is_support(i)).count();
            assert_eq!(supports, (q + 1) * (q + 2) / 2);
            // Per level, and the numbering matches the merged offspring set.
            let mut per_level = BTreeMap::new();
            for n in t.nodes() {
                *per_level.entry(n.tuple.level()).or_insert(0usize) += 1;
            }
            for (l, count) in per_level {
                assert_eq!(count, (l + 1) * (l + 2) / 2);
            }
            let grown: BTreeSet<NodeTuple> = grow(q, true).into_iter().flatten().collect();
            let numbered: BTreeSet<NodeTuple> = t.nodes().iter().map(|n| n.tuple).collect();
            assert_eq!(grown, numbered);
        }
        let planar = MichellTruss::new(MichellParams::planar(q, 1.0, FRAC_PI_6, 0.1)).unwrap();
        assert_eq!(planar.nodes().len(), (q + 1) * (q + 2) / 2);
        assert_eq!(planar.members().len(), q * (q + 1));
    }
}

#[test]
fn numbering_round_trips_and_members_link_parent_to_child() {
    let t = MichellTruss::new(MichellParams::cylindrical(7, 1.0, FRAC_PI_6, 0.2, 0.3)).unwrap();
    for (i, n) in t.nodes().iter().enumerate() {
        assert_eq!(nodes::index_3d(&n.tuple), i);
        assert_eq!(t.find(&n.tuple), Some(i));
    }
    assert_eq!(t.find(&NodeTuple::new(1, 0, 0, 0)), None); // L + R ≠ U
    assert_eq!(t.find(&NodeTuple::new(8, 0, 8, 0)), None); // beyond q
    for (j, m) in t.members().iter().enumerate() {
        assert_eq!(m.parent, j / 3);
        let (p, c) = (t.nodes()[m.parent].tuple, t.nodes()[m.child].tuple);
        assert_eq!(c, p.children()[j % 3]);
        assert_eq!(c.level(), p.level() + 1);
        let v = t.nodes()[m.parent].position - t.nodes()[m.child].position;
        assert!((v - m.vector).norm() == 0.0);
    }
}
