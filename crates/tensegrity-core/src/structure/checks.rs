//! The member checks of [`StructureBuilder::build`](super::StructureBuilder::build), by
//! indices: no text and no hash map on the way; a name (`bar 3`, `node 7`) is formatted only
//! for the error that reports it.
//!
//! Members are checked in order (bars, then strings) and the first problem is reported, each
//! member in this order: its end nodes in range, not a self-loop, not a duplicate of an
//! earlier member (the same unordered pair {a, b}; the error names the first member with that
//! pair), not of zero length (‖n_b − n_a‖ ≤ 10⁻¹² · max(‖n_a‖, ‖n_b‖, 1)); then, unless
//! isolated nodes are allowed, every node on a member. The clusters come after
//! ([`check_clusters`]): each on its own ([`Cluster::check`]), then no segment duplicating a
//! member or an earlier segment, then every node on a member or a cluster.
//!
//! Duplicates are found without hashing: a counting sort of the pairs on their smaller node
//! (each bucket in member order), then each bucket scanned (small) or sorted on the larger
//! node (large): O(m + n) plus the sorts of the few large buckets, against one hash insertion
//! per member before.

use super::{Bar, StringMember};
use crate::cluster::Cluster;
use crate::error::{CoreError, ModelError, Result};
use crate::member_id::MemberId;
use nalgebra::Vector3;

/// Buckets up to this size are scanned pairwise (no sort, no allocation).
const SCAN_BUCKET: usize = 8;

/// The member checks of the module docs; the first problem as the error naming it.
pub(super) fn check_members(
    nodes: &[Vector3<f64>],
    bars: &[Bar],
    strings: &[StringMember],
    allow_isolated: bool,
) -> Result<()> {
    let n = nodes.len();
    let n_bars = bars.len();
    let id = |k: usize| {
        if k < n_bars {
            MemberId::Bar(k)
        } else {
            MemberId::String(k - n_bars)
        }
    };
    let pairs: Vec<[usize; 2]> = bars
        .iter()
        .map(|b| b.nodes)
        .chain(strings.iter().map(|s| s.nodes))
        .collect();
    // the first member failing a check of its own (range, self-loop, zero length)
    let own = pairs
        .iter()
        .enumerate()
        .find_map(|(k, &[a, b])| own_problem(nodes, id(k), a, b).map(|e| (k, e)));
    let checked = own.as_ref().map_or(pairs.len(), |(k, _)| k + 1);
    if let Some((j, i)) = first_duplicate(&pairs[..checked], n) {
        // range and self-loop problems of member j come before its duplication, its zero
        // length after
        let first = match &own {
            None => true,
            Some((k, e)) => j < *k || (j == *k && is_zero_length(e)),
        };
        if first {
            let [a, b] = pairs[j];
            return Err(ModelError::DuplicateMember {
                member: id(j),
                other: id(i),
                a: a.min(b),
                b: a.max(b),
            }
            .into());
        }
    }
    if let Some((_, e)) = own {
        return Err(e);
    }
    if !allow_isolated {
        let mut touched = vec![false; n];
        for &[a, b] in &pairs {
            touched[a] = true;
            touched[b] = true;
        }
        if let Some(node) = touched.iter().position(|&t| !t) {
            return Err(ModelError::IsolatedNode { node }.into());
        }
    }
    Ok(())
}

/// The first problem of member `id` (a → b) on its own: a node out of range, a self-loop, a
/// zero length.
fn own_problem(nodes: &[Vector3<f64>], id: MemberId, a: usize, b: usize) -> Option<CoreError> {
    let n = nodes.len();
    if let Some(node) = [a, b].into_iter().find(|&node| node >= n) {
        return Some(
            ModelError::NodeIndexOutOfRange {
                item: id.to_string(),
                node,
                n_nodes: n,
            }
            .into(),
        );
    }
    if a == b {
        return Some(
            ModelError::SelfLoop {
                member: id,
                node: a,
            }
            .into(),
        );
    }
    let length = (nodes[b] - nodes[a]).norm();
    if !length.is_finite() {
        return Some(ModelError::MemberLengthOverflow { member: id, a, b }.into());
    }
    let scale = nodes[a].norm().max(nodes[b].norm()).max(1.0);
    if length <= 1e-12 * scale {
        return Some(
            ModelError::ZeroLengthMember {
                member: id,
                a,
                b,
                length,
            }
            .into(),
        );
    }
    None
}

fn is_zero_length(e: &CoreError) -> bool {
    matches!(e, CoreError::Model(ModelError::ZeroLengthMember { .. }))
}

/// The first member (in order) that joins the same two nodes as an earlier one, with the
/// first member joining them: `(later, earlier)`. Pairs with a node at or past `n` are
/// skipped (their range error is reported instead).
pub(super) fn first_duplicate(pairs: &[[usize; 2]], n: usize) -> Option<(usize, usize)> {
    let in_range = |&[a, b]: &[usize; 2]| a < n && b < n;
    // counting sort on the smaller node: bucket lo holds its members in member order
    let mut start = vec![0usize; n + 1];
    for p in pairs.iter().filter(|p| in_range(p)) {
        start[p[0].min(p[1]) + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut next = start.clone();
    let mut order = vec![0usize; start[n]];
    for (k, p) in pairs.iter().enumerate().filter(|(_, p)| in_range(p)) {
        let lo = p[0].min(p[1]);
        order[next[lo]] = k;
        next[lo] += 1;
    }
    let hi = |k: usize| pairs[k][0].max(pairs[k][1]);
    let mut best: Option<(usize, usize)> = None;
    let mut sorted: Vec<(usize, usize)> = Vec::new();
    for lo in 0..n {
        let bucket = &order[start[lo]..start[lo + 1]];
        let found = if bucket.len() < 2 {
            None
        } else if bucket.len() <= SCAN_BUCKET {
            // the first later member repeating an earlier one, with the first such earlier
            bucket.iter().enumerate().find_map(|(x, &j)| {
                bucket[..x]
                    .iter()
                    .find(|&&i| hi(i) == hi(j))
                    .map(|&i| (j, i))
            })
        } else {
            sorted.clear();
            sorted.extend(bucket.iter().map(|&k| (hi(k), k)));
            sorted.sort_unstable();
            // in a run of equal larger nodes, the second member repeats the first (the later
            // ones have larger indices): the smallest such second member
            sorted
                .windows(2)
                .filter(|w| w[0].0 == w[1].0)
                .map(|w| (w[1].1, w[0].1))
                .min()
        };
        if let Some(c) = found {
            if best.is_none_or(|b| c.0 < b.0) {
                best = Some(c);
            }
        }
    }
    best
}

/// The clusters' checks (module docs): each on its own, no segment duplicating a bar, a
/// string or an earlier segment (the error names the cluster, the segment and the other),
/// then, unless isolated nodes are allowed, every node on a member or a cluster. A hash map
/// of the member pairs is built only when there are clusters.
pub(super) fn check_clusters(
    nodes: &[Vector3<f64>],
    bars: &[Bar],
    strings: &[StringMember],
    clusters: &[Cluster],
    allow_isolated: bool,
) -> Result<()> {
    for (k, c) in clusters.iter().enumerate() {
        c.check(k, nodes)?;
    }
    if !clusters.is_empty() {
        let key = |[a, b]: [usize; 2]| (a.min(b), a.max(b));
        let mut seen: std::collections::HashMap<(usize, usize), String> = bars
            .iter()
            .enumerate()
            .map(|(i, b)| (key(b.nodes), MemberId::Bar(i).to_string()))
            .chain(
                (strings.iter().enumerate())
                    .map(|(i, s)| (key(s.nodes), MemberId::String(i).to_string())),
            )
            .collect();
        for (k, c) in clusters.iter().enumerate() {
            for (i, pair) in c.segments().enumerate() {
                let name = format!("segment {i} of cluster {k}");
                if let Some(other) = seen.insert(key(pair), name) {
                    return Err(ModelError::InvalidCluster {
                        cluster: k,
                        reason: format!(
                            "segment {i} (nodes {} and {}) duplicates {other}",
                            pair[0], pair[1]
                        ),
                    }
                    .into());
                }
            }
        }
    }
    if !allow_isolated {
        let mut touched = vec![false; nodes.len()];
        let ends = bars
            .iter()
            .map(|b| b.nodes)
            .chain(strings.iter().map(|s| s.nodes));
        for i in ends
            .flatten()
            .chain(clusters.iter().flat_map(|c| c.nodes.iter().copied()))
        {
            touched[i] = true;
        }
        if let Some(node) = touched.iter().position(|&t| !t) {
            return Err(ModelError::IsolatedNode { node }.into());
        }
    }
    Ok(())
}
