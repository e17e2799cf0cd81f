//! NTRT's YAML models ([`structure_from_ntrt`]): the NASA Tensegrity Robotics Toolkit's
//! `nodes` (a name and [x, y, z] each), `pair_groups` (tags and their node pairs), `builders`
//! (per tag, a `class` and its `parameters`), and its combined structures: `substructures`
//! (other model files placed by `rotation`, `scale`, `translation` and `offset`) joined by
//! `bond_groups` (`node_node` strings, `node_edge` attachments).
//!
//! **Members.** A pair takes the builder whose tag words are all among the pair's tags (a
//! group `prism rod` has the tags `prism` and `rod`); where several match, a rod class wins
//! over a string class, and among those the builder defined last wins, as in NTRT. Builders
//! are defined in load order: NTRT's defaults `rod` (`tgRodInfo`) and `string`
//! (`tgBasicActuatorInfo`) first, then each substructure's (recursively, in order), then the
//! file's own, so that a parent's builder overrides a child's of the same tag. A rod class
//! (`tgRodInfo`) gives bars: mass ρ π r² L from its `density` and `radius` (in the model's
//! units). An actuator or cable class (`tgBasicActuatorInfo`, `tgBasicContactCableInfo`,
//! `tgKinematicActuatorInfo`, `tgKinematicContactCableInfo`) gives strings: its `stiffness`
//! k, its `damping`, and the rest length that carries its `pretension` t₀ at the drawn
//! length, L₀ = L − t₀/k (NTRT sets the actuators' rest lengths so). A parameter left out
//! takes NTRT's default (density 1, radius 0.5; stiffness 1000, damping 10, pretension 0).
//! Contact, friction and control parameters (`friction`, `restitution`, `history`,
//! `max_tension`, `target_velocity`, …) are not read. NTRT's lengths are usually decimetres
//! (gravity 98.1): the numbers are taken as they are.
//!
//! **Substructures.** `substructures` maps names to a `path` (relative to the file that
//! names it) and transforms; `t1/t2/t3` gives the same attributes to several children, and
//! a child may take attributes from several entries. As in NTRT, every child's `rotation`
//! (`axis`, `angle` in degrees, about `reference`, by default the child's centre: the mean
//! of all its nodes, its substructures' included) comes first; then, per child, `scale`
//! (about its centre at that point), `offset` (the k-th name of a slash series, from 0,
//! moves by k times it) and `translation`. A child's nodes are named `child.node` (and
//! `child.grandchild.node`); a reference to a node in `pair_groups` or `bond_groups` is a
//! dot path or a bare name, which means the nearest node of that name (the structure's own,
//! then its children's, then theirs); two such nodes at the same depth make it ambiguous,
//! which is refused (NTRT would take the first). Structure names in a dot path or a bond
//! are found the same way. Nodes come in load order: each substructure's (recursively),
//! then the file's own.
//!
//! **Bonds.** `bond_groups` maps tags to bonds (or bonds to tags) of the form
//! `a/b/c/TYPE`, each a list of pairs, bonding each two adjacent structures of the series
//! (a–b, b–c). `node_node`: a string per `[node of a, node of b]` pair, with the builder
//! matching the bond's tags, the structure names and `a/b`. `node_edge` (NTRT's algorithm,
//! three or more `[node, node1/node2]` pairs, either way round): the second structure is
//! turned about the centre of its attachment points (nodes, or edge middles) so that the
//! normal of the plane of its first three is the first structure's, moved so that the
//! centres agree, and turned about that normal so that its first attachment point lies in
//! the first one's direction from the centre; then each edge and each string between
//! attached nodes is taken out (an edge that is a rod is refused, as in NTRT) and each node
//! is joined to both ends of its edge by strings of the bond's tags.
//!
//! Refused, naming the file and the item: an unknown key, a missing or unreadable
//! substructure file, a file that includes itself (directly or not), nesting deeper than
//! [`MAX_DEPTH`] or a model of more than [`MAX_NODES`] nodes, an unknown or ambiguous node or
//! structure name, a pair without a matching builder, a builder of another class, a bond
//! type other than `node_node` and `node_edge`.

use crate::error::IoError;
use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use tensegrity_core::{Bar, StringMember, Structure, Support};
use yaml_rust2::{Yaml, YamlLoader};

mod bonds;
mod builders;
mod geometry;
mod substructures;

use geometry::distance;

/// The deepest nesting of substructures read (the top file is depth 0).
pub const MAX_DEPTH: usize = 16;

/// The most nodes a model may expand to, its substructures' copies included.
pub const MAX_NODES: usize = 1 << 20;

/// The most pairs (members) a model may expand to.
const MAX_PAIRS: usize = 1 << 22;

/// The most substructures a model may expand to.
const MAX_STRUCTURES: usize = 1 << 16;

/// A structure read from an NTRT model, with its node names.
#[derive(Debug, Clone, PartialEq)]
pub struct NtrtModel {
    /// The structure (bars, then strings, in the order their pairs were read).
    pub structure: Structure,
    /// The node names, in the structure's node order: a substructure's nodes with their dot
    /// path (`t2.front`, `leg.hip.center`).
    pub names: Vec<String>,
}

/// The model of an NTRT YAML file's text (module docs); `file` labels the errors and is the
/// path that substructure paths are relative to (their files are read from disk, each under
/// [`crate::read::MAX_SCENE_BYTES`]); `pinned` names nodes held in all three directions.
///
/// ```
/// use tensegrity_io::ntrt::structure_from_ntrt;
/// let yaml = "nodes:\n  a: [0, 0, 0]\n  b: [0, 0, 2]\n  c: [1, 0, 0]\n\
///             pair_groups:\n  rod:\n    - [a, b]\n  cable:\n    - [b, c]\n\
///             builders:\n  rod:\n    class: tgRodInfo\n    parameters: {density: 1.0, radius: 0.5}\n\
///             \x20 cable:\n    class: tgBasicActuatorInfo\n    parameters: {stiffness: 100, pretension: 10}\n";
/// let m = structure_from_ntrt(yaml, "m.yaml", &[])?;
/// assert_eq!(m.names, ["a", "b", "c"]);
/// // ρ π r² L = π/2 for the rod; L₀ = √5 − 10/100 for the cable
/// assert!((m.structure.bars()[0].mass.unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// assert!((m.structure.strings()[0].rest_length.unwrap() - (5f64.sqrt() - 0.1)).abs() < 1e-15);
/// # Ok::<(), tensegrity_io::error::IoError>(())
/// ```
pub fn structure_from_ntrt(text: &str, file: &str, pinned: &[usize]) -> Result<NtrtModel, IoError> {
    let root = parse(text, file)?;
    let mut loader = Loader::default();
    if let Ok(path) = std::fs::canonicalize(file) {
        loader.stack.push(path);
    }
    let dir = Path::new(file)
        .parent()
        .unwrap_or(Path::new(""))
        .to_path_buf();
    loader.load(&root, file, &dir, "", 0)?;
    loader.finish(file, pinned)
}

/// The model's connectivity as a form-finding topology (`tensegrity import ntrt
/// --topology`): its nodes as the start, its bars and strings with nothing else given, so
/// that `formfind` finds their self-stressed form (the adaptive force density method, or
/// force densities set in the file).
///
/// ```
/// use tensegrity_io::ntrt::{structure_from_ntrt, topology_of};
/// let yaml = "nodes:\n  a: [0, 0, 0]\n  b: [0, 0, 2]\npair_groups:\n  rod:\n    - [a, b]\n\
///             builders:\n  rod:\n    class: tgRodInfo\n    parameters: {density: 1, radius: 0.1}\n";
/// let t = topology_of(&structure_from_ntrt(yaml, "m.yaml", &[])?);
/// assert_eq!((t.n_nodes, t.bars.len(), t.strings.len()), (2, 1, 0));
/// # Ok::<(), tensegrity_io::error::IoError>(())
/// ```
pub fn topology_of(model: &NtrtModel) -> formfind::Topology {
    let s = &model.structure;
    formfind::Topology {
        n_nodes: s.n_nodes(),
        nodes: Some(s.nodes().iter().map(|p| [p.x, p.y, p.z]).collect()),
        bars: s
            .bars()
            .iter()
            .map(|b| formfind::Member::new(b.nodes[0], b.nodes[1]))
            .collect(),
        strings: (s.strings().iter())
            .map(|m| formfind::Member::new(m.nodes[0], m.nodes[1]))
            .collect(),
        groups: Default::default(),
        fixed: Vec::new(),
        loads: Vec::new(),
        clusters: Vec::new(),
    }
}

/// An `InvalidModel` error.
fn bad(file: &str, item: &str, reason: impl Into<String>) -> IoError {
    IoError::InvalidModel {
        file: file.to_string(),
        item: item.to_string(),
        reason: reason.into(),
    }
}

/// The YAML document of a model file's text.
fn parse(text: &str, file: &str) -> Result<Yaml, IoError> {
    let docs = YamlLoader::load_from_str(text).map_err(|e| IoError::Parse {
        file: file.to_string(),
        line: e.marker().line(),
        column: e.marker().col() + 1,
        message: e.info().to_string(),
    })?;
    Ok(docs.into_iter().next().unwrap_or(Yaml::Null))
}

/// A loaded structure: a file's nodes and its substructures', placed.
struct Tree {
    /// Its name among its parent's substructures ("" for the top file).
    name: String,
    /// Its nodes and its substructures', in the loader's node list.
    nodes: Range<usize>,
    /// Its substructures.
    children: Vec<Tree>,
    /// The nodes of the whole tree by their own name: (depth, node), nearest first.
    index: HashMap<String, Vec<(usize, usize)>>,
    /// Its pairs and its substructures' (its pair groups and bonds included).
    pairs: Range<usize>,
}

/// A `substructures` entry: its names (`a/b/c`) and attributes.
type Entry<'y> = (Vec<String>, &'y yaml_rust2::yaml::Hash);

/// A pair of nodes to be built as a bar or a string.
struct Pair {
    ends: [usize; 2],
    tags: Vec<String>,
    file: String,
    item: String,
    /// Taken out by a `node_edge` bond.
    removed: bool,
}

/// A builder: its tag, its words, its class and parameters, the file that defines it.
struct BuilderSpec {
    tag: String,
    words: Vec<String>,
    class: String,
    parameters: Yaml,
    file: String,
}

/// The state of loading a model and its substructures.
#[derive(Default)]
struct Loader {
    points: Vec<[f64; 3]>,
    names: Vec<String>,
    pairs: Vec<Pair>,
    builders: Vec<BuilderSpec>,
    /// The canonical paths of the files being loaded, outermost first.
    stack: Vec<PathBuf>,
    /// Parsed substructure files by canonical path.
    cache: HashMap<PathBuf, Yaml>,
    structures: usize,
}

const ROD_CLASSES: [&str; 3] = ["tgRodInfo", "tgBoxInfo", "tgSphereInfo"];
const STRING_CLASSES: [&str; 4] = [
    "tgBasicActuatorInfo",
    "tgBasicContactCableInfo",
    "tgKinematicActuatorInfo",
    "tgKinematicContactCableInfo",
];

impl Loader {
    /// Loads one file's model (`root`, labelled `file`, in directory `dir`) with its
    /// substructures, its nodes named `prefix` + name.
    fn load(
        &mut self,
        root: &Yaml,
        file: &str,
        dir: &Path,
        prefix: &str,
        depth: usize,
    ) -> Result<Tree, IoError> {
        if self.builders.is_empty() {
            self.default_builders();
        }
        let root =
            match root {
                Yaml::Hash(h) => h.clone(),
                Yaml::Null => Default::default(),
                _ => return Err(bad(
                    file,
                    "the file",
                    "expected a map of nodes, pair_groups, builders, substructures, bond_groups",
                )),
            };
        for key in root.keys() {
            match key.as_str() {
                Some("nodes" | "pair_groups" | "builders" | "substructures" | "bond_groups") => {}
                other => {
                    return Err(bad(
                        file,
                        other.unwrap_or("a key"),
                        "not an NTRT model key (nodes, pair_groups, builders, substructures, bond_groups)",
                    ))
                }
            }
        }
        let section = |key: &str| root.get(&Yaml::String(key.into())).filter(|y| !y.is_null());
        let (start, first_pair) = (self.points.len(), self.pairs.len());
        let children = match section("substructures") {
            Some(subs) => self.substructures(subs, file, dir, prefix, depth)?,
            None => Vec::new(),
        };
        if let Some(builders) = section("builders") {
            self.add_builders(builders, file)?;
        }
        let mut own = Vec::new();
        if let Some(nodes) = section("nodes") {
            let nodes = nodes
                .as_hash()
                .ok_or_else(|| bad(file, "nodes", "give a map of name: [x, y, z]"))?;
            for (name, value) in nodes {
                let name = scalar_name(name);
                let item = format!("node {name}");
                if name.is_empty() || name.contains(['.', '/']) {
                    return Err(bad(
                        file,
                        &item,
                        "a node name is not empty and has no `.` or `/`",
                    ));
                }
                let p = vec3(value).ok_or_else(|| bad(file, &item, "give [x, y, z]"))?;
                if self.points.len() >= MAX_NODES {
                    return Err(bad(
                        file,
                        &item,
                        format!("the model has more than {MAX_NODES} nodes"),
                    ));
                }
                own.push((name.clone(), self.points.len()));
                self.points.push(p);
                self.names.push(format!("{prefix}{name}"));
            }
        }
        let mut index: HashMap<String, Vec<(usize, usize)>> = HashMap::new();
        for (name, k) in own {
            index.entry(name).or_default().push((0, k));
        }
        for child in &children {
            for (name, list) in &child.index {
                let entry = index.entry(name.clone()).or_default();
                entry.extend(list.iter().map(|&(d, k)| (d + 1, k)));
            }
        }
        for list in index.values_mut() {
            list.sort_by_key(|&(d, _)| d);
        }
        let mut tree = Tree {
            name: String::new(),
            nodes: start..self.points.len(),
            children,
            index,
            pairs: 0..0,
        };
        if let Some(groups) = section("pair_groups") {
            self.pair_groups(&tree, groups, file)?;
        }
        if let Some(bonds) = section("bond_groups") {
            self.bond_groups(&tree, bonds, file)?;
        }
        tree.pairs = first_pair..self.pairs.len();
        Ok(tree)
    }

    /// A pair of `tags` between two referenced nodes.
    fn push_pair(
        &mut self,
        ends: [usize; 2],
        tags: Vec<String>,
        file: &str,
        item: &str,
    ) -> Result<(), IoError> {
        if self.pairs.len() >= MAX_PAIRS {
            return Err(bad(
                file,
                item,
                format!("the model has more than {MAX_PAIRS} pairs"),
            ));
        }
        self.pairs.push(Pair {
            ends,
            tags,
            file: file.to_string(),
            item: item.to_string(),
            removed: false,
        });
        Ok(())
    }

    /// The file's pair groups: pairs of nodes of this structure or its substructures.
    fn pair_groups(&mut self, tree: &Tree, groups: &Yaml, file: &str) -> Result<(), IoError> {
        let groups = groups
            .as_hash()
            .ok_or_else(|| bad(file, "pair_groups", "give a map of tag: [[node, node], …]"))?;
        for (tags, pairs) in groups {
            let tags = scalar_name(tags);
            let item = format!("pair group {tags}");
            for ends in
                node_pairs(pairs).ok_or_else(|| bad(file, &item, "give a list of [node, node]"))?
            {
                let a = resolve(tree, &ends[0], self).map_err(|e| bad(file, &item, e))?;
                let b = resolve(tree, &ends[1], self).map_err(|e| bad(file, &item, e))?;
                let words = tags.split_whitespace().map(str::to_string).collect();
                self.push_pair([a, b], words, file, &item)?;
            }
        }
        Ok(())
    }

    /// The structure of the loaded model.
    fn finish(self, file: &str, pinned: &[usize]) -> Result<NtrtModel, IoError> {
        let mut builder = Structure::builder().nodes(self.points.clone());
        for pair in self.pairs.iter().filter(|p| !p.removed) {
            let spec = self.builder_of(pair).ok_or_else(|| {
                bad(
                    &pair.file,
                    &pair.item,
                    format!("no builder matches its tags ({})", pair.tags.join(" ")),
                )
            })?;
            let item = format!("builder {}", spec.tag);
            let parameter = |key: &str, default: f64| -> Result<f64, IoError> {
                match &spec.parameters[key] {
                    Yaml::BadValue | Yaml::Null => Ok(default),
                    y => number(y)
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| bad(&spec.file, &item, format!("its {key} is a number"))),
                }
            };
            let [i, j] = pair.ends;
            let length = distance(self.points[i], self.points[j]);
            builder = match spec.class.as_str() {
                "tgRodInfo" => {
                    let (rho, r) = (parameter("density", 1.0)?, parameter("radius", 0.5)?);
                    builder.bar(Bar::new(i, j).mass(rho * std::f64::consts::PI * r * r * length))
                }
                c if STRING_CLASSES.contains(&c) => {
                    let k = parameter("stiffness", 1000.0)?;
                    let c = parameter("damping", 10.0)?;
                    let t0 = parameter("pretension", 0.0)?;
                    if k <= 0.0 {
                        return Err(bad(&spec.file, &item, format!("its stiffness {k} is not positive")));
                    }
                    if t0 / k >= length {
                        return Err(bad(
                            &spec.file,
                            &item,
                            format!("pretension {t0} stretches pair [{}, {}] (length {length}) past its whole length at stiffness {k}: its rest length would not be positive", self.names[i], self.names[j]),
                        ));
                    }
                    builder.string(StringMember::new(i, j).stiffness(k).damping(c).rest_length(length - t0 / k))
                }
                other => {
                    return Err(bad(
                        &spec.file,
                        &item,
                        format!("class `{other}` is not imported (tgRodInfo; tgBasicActuatorInfo, tgBasicContactCableInfo, tgKinematicActuatorInfo, tgKinematicContactCableInfo)"),
                    ))
                }
            };
        }
        for &node in pinned {
            builder = builder.support(Support::pinned(node));
        }
        let structure = builder
            .build()
            .map_err(|source| IoError::InvalidStructure {
                file: file.to_string(),
                line: None,
                source,
            })?;
        Ok(NtrtModel {
            structure,
            names: self.names,
        })
    }
}

/// The index of the child `name` (one given a path in this file).
fn child(children: &[Tree], name: &str, file: &str) -> Result<usize, IoError> {
    children.iter().position(|c| c.name == name).ok_or_else(|| {
        bad(
            file,
            &format!("substructure {name}"),
            "no path is given for it in this file",
        )
    })
}

/// A list of `[node, node]` pairs as names.
fn node_pairs(pairs: &Yaml) -> Option<Vec<[String; 2]>> {
    (pairs.as_vec()?.iter())
        .map(|p| match p.as_vec()?.as_slice() {
            [a, b] => Some([scalar_name(a), scalar_name(b)]),
            _ => None,
        })
        .collect()
}

/// The nearest substructure of `tree` named `name` (its children, then theirs, …).
fn find_structure<'t>(tree: &'t Tree, name: &str) -> Result<&'t Tree, String> {
    let mut level: Vec<&Tree> = tree.children.iter().collect();
    while !level.is_empty() {
        let found: Vec<&Tree> = level.iter().copied().filter(|t| t.name == name).collect();
        match found.len() {
            0 => level = level.iter().flat_map(|t| t.children.iter()).collect(),
            1 => return Ok(found[0]),
            n => return Err(format!("structure `{name}` is ambiguous: {n} substructures at the same depth have this name")),
        }
    }
    Err(format!("no substructure `{name}`"))
}

/// The node of `tree` that `reference` names: `a.b.node` (a dot path) or `node` (the
/// nearest node of that name).
fn resolve(tree: &Tree, reference: &str, loader: &Loader) -> Result<usize, String> {
    let mut parts: Vec<&str> = reference.split('.').collect();
    let name = parts.pop().unwrap_or_default();
    let mut t = tree;
    for part in parts {
        t = find_structure(t, part).map_err(|e| format!("node {reference}: {e}"))?;
    }
    let list = t.index.get(name).map(Vec::as_slice).unwrap_or_default();
    match list {
        [] => Err(format!("node {reference} is not among the nodes")),
        [(_, k)] => Ok(*k),
        [(d0, k), (d1, _), ..] if d0 < d1 => Ok(*k),
        _ => {
            let d0 = list[0].0;
            let same: Vec<&str> = (list.iter())
                .take_while(|(d, _)| *d == d0)
                .map(|(_, k)| loader.names[*k].as_str())
                .collect();
            Err(format!(
                "node {reference} is ambiguous: {} nodes at the same depth have this name ({}); give its dot path",
                same.len(),
                same.join(", ")
            ))
        }
    }
}

/// A finite [x, y, z].
fn vec3(y: &Yaml) -> Option<[f64; 3]> {
    match y.as_vec()?.as_slice() {
        [x, y, z] => {
            let p = [number(x)?, number(y)?, number(z)?];
            p.iter().all(|v| v.is_finite()).then_some(p)
        }
        _ => None,
    }
}

/// A YAML scalar as a name (NTRT's node and tag names may be numbers).
fn scalar_name(y: &Yaml) -> String {
    match y {
        Yaml::String(s) | Yaml::Real(s) => s.clone(),
        Yaml::Integer(i) => i.to_string(),
        Yaml::Boolean(b) => b.to_string(),
        _ => String::new(),
    }
}

/// A YAML number (an integer or a real).
fn number(y: &Yaml) -> Option<f64> {
    match y {
        Yaml::Integer(i) => Some(*i as f64),
        Yaml::Real(_) => y.as_f64(),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::geometry::rotate;
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn rotation_is_right_handed_about_the_reference() {
        // +90° about z through (1, 1, 0): (2, 1, 5) − c = (1, 0, 5) → (0, 1, 5)
        let p = rotate([2.0, 1.0, 5.0], [1.0, 1.0, 0.0], [0.0, 0.0, 3.0], FRAC_PI_2);
        assert!(
            (0..3).all(|d| (p[d] - [1.0, 2.0, 5.0][d]).abs() < 1e-15),
            "{p:?}"
        );
        // +120° about (1, 1, 1) permutes the axes: x → y
        let p = rotate(
            [1.0, 0.0, 0.0],
            [0.0; 3],
            [1.0; 3],
            2.0 * std::f64::consts::FRAC_PI_3,
        );
        assert!(
            (0..3).all(|d| (p[d] - [0.0, 1.0, 0.0][d]).abs() < 1e-15),
            "{p:?}"
        );
    }

    /// A bare name means the nearest node of that name: the file's own `a` over its child's
    /// `a`; the child's `b` over its grandchild's.
    #[test]
    fn a_bare_name_is_the_nearest_node_of_that_name() {
        let dir = std::env::temp_dir().join(format!("tensegrity-ntrt-unit-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        std::fs::write(
            dir.join("sub/leaf.yaml"),
            "nodes:\n  b: [0, 0, 0]\n  c: [0, 0, 1]\n",
        )
        .unwrap();
        std::fs::write(
            dir.join("sub/mid.yaml"),
            "substructures:\n  leaf:\n    path: leaf.yaml\n    translation: [0, 5, 0]\nnodes:\n  a: [1, 0, 0]\n  b: [2, 0, 0]\n",
        )
        .unwrap();
        let top = "substructures:\n  m:\n    path: sub/mid.yaml\nnodes:\n  a: [0, 9, 0]\n\
                   pair_groups:\n  string:\n    - [a, b]\n    - [a, c]\n    - [m.a, m.leaf.b]\n";
        let file = dir.join("top.yaml");
        let m = structure_from_ntrt(top, file.to_str().unwrap(), &[]).unwrap();
        assert_eq!(m.names, ["m.leaf.b", "m.leaf.c", "m.a", "m.b", "a"]);
        let ends: Vec<[usize; 2]> = m.structure.strings().iter().map(|s| s.nodes).collect();
        assert_eq!(ends, [[4, 3], [4, 1], [2, 0]]);
        assert_eq!(m.structure.nodes()[1].y, 5.0);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
