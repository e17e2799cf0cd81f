//! Bond groups between adjacent structures of a series: `node_node` strings and NTRT's
//! `node_edge` attachment (module docs of [`super`], "Bonds").

use super::geometry::*;
use super::*;

impl Loader {
    /// The file's bond groups: `tag: {a/b/…/node_node: pairs}` or `a/b/…/node_node: {tag:
    /// pairs}`.
    pub(super) fn bond_groups(
        &mut self,
        tree: &Tree,
        groups: &Yaml,
        file: &str,
    ) -> Result<(), IoError> {
        let groups = groups.as_hash().ok_or_else(|| {
            bad(
                file,
                "bond_groups",
                "give a map of tag: {a/b/node_node: pairs}",
            )
        })?;
        for (outer, inner) in groups {
            let outer = scalar_name(outer);
            let inner = inner.as_hash().ok_or_else(|| {
                bad(
                    file,
                    &format!("bond group {outer}"),
                    "give a map of a/b/node_node (or tag): pairs",
                )
            })?;
            for (key, pairs) in inner {
                let key = scalar_name(key);
                let (tags, bond) = match (outer.contains('/'), key.contains('/')) {
                    (false, true) => (&outer, &key),
                    (true, false) => (&key, &outer),
                    _ => {
                        return Err(bad(
                            file,
                            &format!("bond group {outer}: {key}"),
                            "a bond (a/b/node_node) is nested in a tag or a tag in a bond",
                        ))
                    }
                };
                self.bonds(tree, tags, bond, pairs, file)?;
            }
        }
        Ok(())
    }

    /// One bond `a/b/…/type` of `tags`.
    pub(super) fn bonds(
        &mut self,
        tree: &Tree,
        tags: &str,
        bond: &str,
        pairs: &Yaml,
        file: &str,
    ) -> Result<(), IoError> {
        let item = format!("bond group {tags}: {bond}");
        let mut parts: Vec<&str> = bond.split('/').collect();
        let kind = parts.pop().unwrap_or_default();
        if parts.len() < 2 {
            return Err(bad(
                file,
                &item,
                "a bond names two or more structures and its type (a/b/node_node)",
            ));
        }
        let pairs =
            node_pairs(pairs).ok_or_else(|| bad(file, &item, "give a list of [node, node]"))?;
        match kind {
            "node_node" => {}
            "node_edge" => {
                for w in parts.windows(2) {
                    self.node_edge(tree, tags, [w[0], w[1]], &pairs, file, &item)?;
                }
                return Ok(());
            }
            other => {
                return Err(bad(
                    file,
                    &item,
                    format!("`{other}` is not a bond type (node_node, node_edge)"),
                ))
            }
        }
        for w in parts.windows(2) {
            let a = find_structure(tree, w[0]).map_err(|e| bad(file, &item, e))?;
            let b = find_structure(tree, w[1]).map_err(|e| bad(file, &item, e))?;
            let mut words: Vec<String> = tags.split_whitespace().map(str::to_string).collect();
            words.extend([
                w[0].to_string(),
                w[1].to_string(),
                format!("{}/{}", w[0], w[1]),
            ]);
            for ends in &pairs {
                let i = resolve(a, &ends[0], self)
                    .map_err(|e| bad(file, &item, format!("in {}: {e}", w[0])))?;
                let j = resolve(b, &ends[1], self)
                    .map_err(|e| bad(file, &item, format!("in {}: {e}", w[1])))?;
                self.push_pair([i, j], words.clone(), file, &item)?;
            }
        }
        Ok(())
    }

    /// A `node_edge` bond between structures `names` (module docs): moves and turns the
    /// second to fit, takes out the edges and the strings between the attached nodes, and
    /// joins each node to its edge's ends.
    pub(super) fn node_edge(
        &mut self,
        tree: &Tree,
        tags: &str,
        names: [&str; 2],
        pairs: &[[String; 2]],
        file: &str,
        item: &str,
    ) -> Result<(), IoError> {
        let fail = |why: String| bad(file, item, why);
        if pairs.len() < 3 {
            return Err(fail(
                "a node_edge bond needs three or more [node, node1/node2] pairs".into(),
            ));
        }
        let s = [
            find_structure(tree, names[0]).map_err(fail)?,
            find_structure(tree, names[1]).map_err(fail)?,
        ];
        let (mut refs, mut ligands, mut receptors) =
            ([Vec::new(), Vec::new()], Vec::new(), Vec::new());
        for pair in pairs {
            if pair[0].contains('/') == pair[1].contains('/') {
                return Err(fail(format!(
                    "[{}, {}] is not a node and an edge (node1/node2)",
                    pair[0], pair[1]
                )));
            }
            for side in 0..2 {
                let find = |r: &str| {
                    resolve(s[side], r, self).map_err(|e| fail(format!("in {}: {e}", names[side])))
                };
                match pair[side].split_once('/') {
                    Some((a, b)) => {
                        let (i, j) = (find(a)?, find(b)?);
                        let (p, q) = (self.points[i], self.points[j]);
                        refs[side].push(std::array::from_fn(|d| 0.5 * (p[d] + q[d])));
                        receptors.push([i, j]);
                    }
                    None => {
                        let k = find(&pair[side])?;
                        refs[side].push(self.points[k]);
                        ligands.push(k);
                    }
                }
            }
        }
        self.fit(s[1].nodes.clone(), &refs).map_err(|why| {
            fail(format!(
                "{} cannot be fitted to {}: {why}",
                names[1], names[0]
            ))
        })?;
        let words: Vec<String> = tags.split_whitespace().map(str::to_string).collect();
        for (&l, &[a, b]) in ligands.iter().zip(&receptors) {
            for t in s {
                if !self.take_out(t.pairs.clone(), [a, b], true) {
                    return Err(fail(format!(
                        "the edge {}/{} is a rod: a node_edge bond attaches to strings",
                        self.names[a], self.names[b]
                    )));
                }
                for &m in &ligands {
                    self.take_out(t.pairs.clone(), [l, m], false);
                }
            }
            self.push_pair([a, l], words.clone(), file, item)?;
            self.push_pair([l, b], words.clone(), file, item)?;
        }
        Ok(())
    }

    /// Moves and turns the nodes `moving` as NTRT does to fit the attachment points
    /// `refs[1]` (theirs) to `refs[0]`: the normal of the plane of their first three onto
    /// the other's about their centre, then their centre onto the other's, then about that
    /// normal to bring the first point's direction from the centre onto the other's.
    pub(super) fn fit(
        &mut self,
        moving: Range<usize>,
        refs: &[Vec<[f64; 3]>; 2],
    ) -> Result<(), String> {
        let c = [centroid(&refs[0]), centroid(&refs[1])];
        let n = [plane_normal(&refs[0])?, plane_normal(&refs[1])?];
        let fallback = unit(sub(refs[1][1], refs[1][0])).ok_or("two attachments coincide")?;
        let (axis, angle) = between(n[1], n[0], fallback)?;
        let shift = sub(c[0], c[1]);
        for p in &mut self.points[moving.clone()] {
            *p = add(rotate(*p, c[1], axis, angle), shift);
        }
        let first = add(rotate(refs[1][0], c[1], axis, angle), shift);
        let (axis, angle) = between(sub(first, c[0]), sub(refs[0][0], c[0]), n[0])?;
        for p in &mut self.points[moving] {
            *p = rotate(*p, c[0], axis, angle);
        }
        Ok(())
    }

    /// Takes out the pairs in `range` between the nodes `ends` (either way), unless a rod
    /// builder defined so far matches the first such: false for a rod (then nothing is
    /// taken out) when `edge`.
    pub(super) fn take_out(&mut self, range: Range<usize>, ends: [usize; 2], edge: bool) -> bool {
        let joins = |p: &Pair| !p.removed && (p.ends == ends || p.ends == [ends[1], ends[0]]);
        let Some(first) = self.pairs[range.clone()].iter().find(|p| joins(p)) else {
            return true;
        };
        let rod = (self.builders.iter()).any(|b| {
            ROD_CLASSES.contains(&b.class.as_str())
                && b.words.iter().all(|w| first.tags.contains(w))
        });
        if rod {
            return !edge;
        }
        for p in &mut self.pairs[range] {
            if joins(p) {
                p.removed = true;
            }
        }
        true
    }
}
