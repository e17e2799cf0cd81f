//! NTRT's YAML models ([`structure_from_ntrt`]): the NASA Tensegrity Robotics Toolkit's
//! `nodes` (a name and [x, y, z] each), `pair_groups` (a tag and its node pairs) and
//! `builders` (per tag, a `class` and its `parameters`).
//!
//! A tag built by `tgRodInfo` gives bars: mass ρ π r² L from its `density` and `radius` (in
//! the model's units). A tag built by an actuator class (`tgBasicActuatorInfo`,
//! `tgKinematicActuatorInfo`) gives strings: its `stiffness` k, its `damping`, and the rest
//! length that carries its `pretension` t₀ at the drawn length, L₀ = L − t₀/k (NTRT sets the
//! actuators' rest lengths so). Nodes keep the file's order (the scene numbers them from 0;
//! [`NtrtModel::names`] keeps the names), bars and strings the order of the pair groups and
//! their pairs. Contact, friction and control parameters (`friction`, `restitution`,
//! `history`, `max_tension`, `target_velocity`, …) are not read. A model built from
//! `substructures` (NTRT's offsets, rotations and bonds) is refused naming the key, as is any
//! other unknown key, a pair naming an unknown node, a tag without a builder, or a builder of
//! another class. NTRT's lengths are usually decimetres (gravity 98.1): the numbers are taken
//! as they are.

use crate::error::IoError;
use tensegrity_core::{Bar, StringMember, Structure, Support};
use yaml_rust2::{Yaml, YamlLoader};

/// A structure read from an NTRT model, with its node names.
#[derive(Debug, Clone, PartialEq)]
pub struct NtrtModel {
    /// The structure (bars, then strings, in the pair groups' order).
    pub structure: Structure,
    /// The node names, in the structure's node order.
    pub names: Vec<String>,
}

/// The model of an NTRT YAML file's text (module docs); `file` labels the errors; `pinned`
/// names nodes held in all three directions.
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
    let bad = |item: &str, why: String| IoError::InvalidModel {
        file: file.to_string(),
        item: item.to_string(),
        reason: why,
    };
    let docs = YamlLoader::load_from_str(text).map_err(|e| IoError::Parse {
        file: file.to_string(),
        line: e.marker().line(),
        column: e.marker().col() + 1,
        message: e.info().to_string(),
    })?;
    let root = docs.first().and_then(Yaml::as_hash).ok_or_else(|| {
        bad(
            "the file",
            "expected a map with `nodes`, `pair_groups` and `builders`".into(),
        )
    })?;
    for key in root.keys() {
        match key.as_str() {
            Some("nodes" | "pair_groups" | "builders") => {}
            Some("substructures" | "bond_groups") => {
                return Err(bad(
                    key.as_str().unwrap_or_default(),
                    "substructures (offsets, rotations, bonds) are not imported: give the model as one structure of nodes, pair groups and builders".into(),
                ))
            }
            other => {
                return Err(bad(
                    other.unwrap_or("a key"),
                    "not an NTRT model key (nodes, pair_groups, builders)".into(),
                ))
            }
        }
    }
    let section = |key: &str| root.get(&Yaml::String(key.into())).and_then(Yaml::as_hash);
    let nodes_yaml = section("nodes").ok_or_else(|| bad("nodes", "missing".into()))?;
    let mut names = Vec::with_capacity(nodes_yaml.len());
    let mut nodes = Vec::with_capacity(nodes_yaml.len());
    for (name, value) in nodes_yaml {
        let name = scalar_name(name);
        let xyz: Option<Vec<f64>> = value
            .as_vec()
            .map(|v| v.iter().filter_map(number).collect());
        match xyz {
            Some(p) if p.len() == 3 => nodes.push([p[0], p[1], p[2]]),
            _ => return Err(bad(&format!("node {name}"), "give [x, y, z]".into())),
        }
        names.push(name);
    }
    let index = |group: &str, name: &Yaml| -> Result<usize, IoError> {
        let name = scalar_name(name);
        names.iter().position(|n| *n == name).ok_or_else(|| {
            bad(
                &format!("pair group {group}"),
                format!("node {name} is not among the nodes"),
            )
        })
    };
    let builders = section("builders").ok_or_else(|| bad("builders", "missing".into()))?;
    let groups = section("pair_groups").ok_or_else(|| bad("pair_groups", "missing".into()))?;
    let mut builder = Structure::builder().nodes(nodes.clone());
    for (tag, pairs) in groups {
        let tag = scalar_name(tag);
        let spec = builders.get(&Yaml::String(tag.clone())).ok_or_else(|| {
            bad(
                &format!("pair group {tag}"),
                "no builder of this tag".into(),
            )
        })?;
        let class = spec["class"].as_str().unwrap_or("");
        let parameter = |key: &str| number(&spec["parameters"][key]);
        let pairs = pairs.as_vec().ok_or_else(|| {
            bad(
                &format!("pair group {tag}"),
                "give a list of [node, node]".into(),
            )
        })?;
        for pair in pairs {
            let ends = pair.as_vec().filter(|v| v.len() == 2).ok_or_else(|| {
                bad(
                    &format!("pair group {tag}"),
                    "a pair is [node, node]".into(),
                )
            })?;
            let (i, j) = (index(&tag, &ends[0])?, index(&tag, &ends[1])?);
            let length = distance(nodes[i], nodes[j]);
            builder = match class {
                "tgRodInfo" => {
                    let (rho, r) = (parameter("density"), parameter("radius"));
                    let mut bar = Bar::new(i, j);
                    if let (Some(rho), Some(r)) = (rho, r) {
                        bar = bar.mass(rho * std::f64::consts::PI * r * r * length);
                    }
                    builder.bar(bar)
                }
                "tgBasicActuatorInfo" | "tgKinematicActuatorInfo" => {
                    let k = parameter("stiffness").ok_or_else(|| {
                        bad(&format!("builder {tag}"), "an actuator needs its stiffness".into())
                    })?;
                    let mut string = StringMember::new(i, j).stiffness(k);
                    if let Some(c) = parameter("damping") {
                        string = string.damping(c);
                    }
                    let t0 = parameter("pretension").unwrap_or(0.0);
                    if k > 0.0 && t0 / k >= length {
                        return Err(bad(
                            &format!("builder {tag}"),
                            format!("pretension {t0} stretches pair [{}, {}] (length {length}) past its whole length at stiffness {k}: its rest length would not be positive", names[i], names[j]),
                        ));
                    }
                    string = string.rest_length(length - t0 / k);
                    builder.string(string)
                }
                other => {
                    return Err(bad(
                        &format!("builder {tag}"),
                        format!("class `{other}` is not imported (tgRodInfo, tgBasicActuatorInfo, tgKinematicActuatorInfo)"),
                    ))
                }
            };
        }
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
    Ok(NtrtModel { structure, names })
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

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
