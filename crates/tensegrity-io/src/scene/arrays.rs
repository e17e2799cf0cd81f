//! [`SceneArrays`]: a scene as data — the structure as columns, with the scene's dynamics
//! tables — for a front end that holds a structure as arrays (the Python package), so that it
//! reaches the reader without being written as TOML text; [`Scene::from_arrays`] validates it
//! as [`Scene::from_str_named`] validates a file, and [`SceneArrays::of`] /
//! [`SceneArrays::from_structure`] give the columns of a scene or structure back.

use super::{
    ActuationSpec, ActuatorSpec, BarSpec, ClusterSpec, GravitySpec, GroundSpec, LoadSpec,
    MaterialSpec, PointMassSpec, Scene, SceneFile, SimulationSpec, StringSpec, SupportSpec,
};
use crate::error::{IoError, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use tensegrity_core::Structure;
use toml::Spanned;

/// A scene as data: node positions, member node pairs and one optional column per member
/// property (each with one entry per member, `null` leaving it unset for that member), the
/// supports, loads and gravity, and the `[simulation]`, `[ground]` and `[[actuation]]` tables
/// of a scene file ([`SimulationSpec`], [`GroundSpec`], [`ActuationSpec`]). Unknown keys are
/// refused.
///
/// Its serde form is an object of these keys, e.g. (JSON):
///
/// ```json
/// {"nodes": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "bars": [[0, 1]], "strings": [[1, 2], [2, 0]],
///  "stiffness": [100.0, null], "supports": [[0, [true, true, true]]],
///  "loads": [[1, [0.0, 0.0, -5.0]]], "ground": {"stiffness": 1e4}}
/// ```
///
/// Node indices are signed so that a negative one is an error naming its member rather than
/// a type error of the whole value. A number may also be given as the text of a non-finite
/// float (`nan`, `inf`, `-inf`: how a value tree such as JSON carries one), so that the
/// structure's own check names the node, load or member holding it.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneArrays {
    /// Node positions (m), n × 3.
    #[serde(deserialize_with = "number::points")]
    pub nodes: Vec<[f64; 3]>,
    /// Initial node velocities (m/s), n × 3.
    #[serde(
        default,
        deserialize_with = "number::opt_points",
        skip_serializing_if = "Option::is_none"
    )]
    pub velocities: Option<Vec<[f64; 3]>>,
    /// User materials by name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub materials: BTreeMap<String, MaterialSpec>,
    /// Bars: start and end node, 0-based.
    #[serde(default)]
    pub bars: Vec<[i64; 2]>,
    /// Strings: start and end node, 0-based.
    #[serde(default)]
    pub strings: Vec<[i64; 2]>,
    /// Bar masses (kg), one per bar.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub bar_mass: Option<Vec<Option<f64>>>,
    /// Bar cross-section radii (m), one per bar.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub bar_radius: Option<Vec<Option<f64>>>,
    /// Bar material names, one per bar.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bar_material: Option<Vec<Option<String>>>,
    /// String axial stiffnesses (N/m), one per string.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub stiffness: Option<Vec<Option<f64>>>,
    /// String rest lengths (m), one per string.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub rest_length: Option<Vec<Option<f64>>>,
    /// String damping (N·s/m; unset: 0), one per string.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub damping: Option<Vec<Option<f64>>>,
    /// String material names, one per string.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub string_material: Option<Vec<Option<String>>>,
    /// Clustered strings: the nodes each passes through, in order, 0-based.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub clusters: Vec<Vec<i64>>,
    /// Cluster axial stiffnesses (N/m, of the whole cluster), one per cluster.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub cluster_stiffness: Option<Vec<Option<f64>>>,
    /// Cluster rest lengths (m, of the whole cluster), one per cluster.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub cluster_rest_length: Option<Vec<Option<f64>>>,
    /// Cluster damping (N·s/m; unset: 0), one per cluster.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub cluster_damping: Option<Vec<Option<f64>>>,
    /// The pulleys' friction coefficients of each cluster (one per inner node; `null`:
    /// frictionless), one entry per cluster.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cluster_friction: Option<Vec<Option<Vec<f64>>>>,
    /// Cluster material names, one per cluster.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cluster_material: Option<Vec<Option<String>>>,
    /// Supports: the node and its fixed directions x, y, z.
    #[serde(default)]
    pub supports: Vec<(i64, [bool; 3])>,
    /// Supports' `along` directions of any orientation (unit vectors), one entry per
    /// support (`null`: none; a support with some and no fixed axis holds them alone).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub support_along: Option<Vec<Option<Vec<[f64; 3]>>>>,
    /// Supports' spring stiffness (N/m, `null`: held rigidly), one entry per support.
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub support_stiffness: Option<Vec<Option<f64>>>,
    /// Supports' prescribed displacements (m, `null`: none), one entry per support
    /// (`statics`' linear response; `solve`: at load factor 1).
    #[serde(
        default,
        deserialize_with = "number::opt_column_points",
        skip_serializing_if = "Option::is_none"
    )]
    pub support_displacement: Option<Vec<Option<[f64; 3]>>>,
    /// Bar rest lengths as elastic bars (m), one per bar (`solve`, elastic `simulate`).
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub bar_rest_length: Option<Vec<Option<f64>>>,
    /// Bar rest-length changes at load factor 1 (m), one per bar (`solve`).
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub bar_rest_length_change: Option<Vec<Option<f64>>>,
    /// String rest-length changes at load factor 1 (m), one per string (`solve`).
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub rest_length_change: Option<Vec<Option<f64>>>,
    /// Cluster rest-length changes at load factor 1 (m), one per cluster (`solve`).
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub cluster_rest_length_change: Option<Vec<Option<f64>>>,
    /// Per bar: elastic (`true`) or rigid (`false`) in `simulate`, over `[simulation] bars`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bar_elastic: Option<Vec<Option<bool>>>,
    /// String masses (kg), one per string (elastic `simulate`; a dead load in `solve`).
    #[serde(
        default,
        deserialize_with = "number::opt_column",
        skip_serializing_if = "Option::is_none"
    )]
    pub string_mass: Option<Vec<Option<f64>>>,
    /// Point masses: the node and its mass (kg) (elastic `simulate`; a dead load in
    /// `solve`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub masses: Vec<(i64, f64)>,
    /// Nodal loads: the node and the force (N).
    #[serde(default, deserialize_with = "number::loads")]
    pub loads: Vec<(i64, [f64; 3])>,
    /// Gravitational acceleration (m/s²).
    #[serde(
        default,
        deserialize_with = "number::opt_point",
        skip_serializing_if = "Option::is_none"
    )]
    pub gravity: Option<[f64; 3]>,
    /// The `[simulation]` table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulation: Option<SimulationSpec>,
    /// The `[ground]` table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<GroundSpec>,
    /// The `[[actuation]]` tables.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub actuation: Vec<ActuationSpec>,
    /// The `[[actuators]]` tables.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub actuators: Vec<ActuatorSpec>,
}

/// An item of the data: no text, so no span (and no line in its errors).
fn unspanned<T>(value: T) -> Spanned<T> {
    Spanned::new(0..0, value)
}

/// Entry `k` of an optional per-member column.
fn entry<T: Clone>(column: &Option<Vec<Option<T>>>, k: usize) -> Option<T> {
    column.as_ref().and_then(|c| c.get(k).cloned().flatten())
}

/// A node index of the data, or the error naming its item.
fn node_index(file: &str, item: impl Fn() -> String, index: i64, n_nodes: usize) -> Result<usize> {
    usize::try_from(index).map_err(|_| IoError::NegativeIndex {
        file: file.to_string(),
        item: item(),
        index,
        n_nodes,
    })
}

impl SceneArrays {
    /// The columns of a structure (no dynamics tables): a column is given when some member
    /// sets its property; the materials are those the members name, as the structure's table
    /// holds them (written out in full, as [`super::to_toml`] writes them).
    ///
    /// ```
    /// use tensegrity_core::{Bar, StringMember, Structure, Support};
    /// use tensegrity_io::scene::{Scene, SceneArrays};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    ///     .bar(Bar::new(0, 1).mass(2.0).material("steel"))
    ///     .string(StringMember::new(1, 2).stiffness(100.0))
    ///     .string(StringMember::new(2, 0))
    ///     .support(Support::directions(0, [true, false, true]))
    ///     .build()?;
    /// let a = SceneArrays::from_structure(&s);
    /// assert_eq!(a.strings, vec![[1, 2], [2, 0]]);
    /// assert_eq!(a.stiffness, Some(vec![Some(100.0), None]));
    /// assert_eq!((a.rest_length.is_none(), a.materials.contains_key("steel")), (true, true));
    /// assert_eq!(Scene::from_arrays(a, "back")?.structure, s);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_structure(structure: &Structure) -> SceneArrays {
        let index = |i: usize| i64::try_from(i).unwrap_or(i64::MAX);
        let pair = |n: [usize; 2]| n.map(index);
        let v3 = |v: &nalgebra::Vector3<f64>| [v.x, v.y, v.z];
        let (bars, strings) = (structure.bars(), structure.strings());
        let damped = strings.iter().any(|s| s.damping != 0.0);
        SceneArrays {
            nodes: structure.nodes().iter().map(v3).collect(),
            velocities: structure.velocities().map(|v| v.iter().map(v3).collect()),
            materials: used_materials(structure),
            bars: bars.iter().map(|b| pair(b.nodes)).collect(),
            strings: strings.iter().map(|s| pair(s.nodes)).collect(),
            bar_mass: column(bars.iter().map(|b| b.mass)),
            bar_radius: column(bars.iter().map(|b| b.radius)),
            bar_material: column(bars.iter().map(|b| b.material.clone())),
            stiffness: column(strings.iter().map(|s| s.stiffness)),
            rest_length: column(strings.iter().map(|s| s.rest_length)),
            damping: damped.then(|| strings.iter().map(|s| Some(s.damping)).collect()),
            string_material: column(strings.iter().map(|s| s.material.clone())),
            clusters: (structure.clusters().iter())
                .map(|c| c.nodes.iter().map(|&i| index(i)).collect())
                .collect(),
            cluster_stiffness: column(structure.clusters().iter().map(|c| c.stiffness)),
            cluster_rest_length: column(structure.clusters().iter().map(|c| c.rest_length)),
            cluster_damping: (structure.clusters().iter().any(|c| c.damping != 0.0)).then(|| {
                structure
                    .clusters()
                    .iter()
                    .map(|c| Some(c.damping))
                    .collect()
            }),
            cluster_friction: column(structure.clusters().iter().map(|c| c.friction.clone())),
            cluster_material: column(structure.clusters().iter().map(|c| c.material.clone())),
            supports: (structure.supports().iter())
                .map(|s| (index(s.node), s.fixed))
                .collect(),
            support_along: column(
                structure
                    .supports()
                    .iter()
                    .map(|s| (!s.along.is_empty()).then(|| s.along.iter().map(v3).collect())),
            ),
            support_stiffness: column(structure.supports().iter().map(|s| s.stiffness)),
            loads: (structure.loads().iter())
                .map(|l| (index(l.node), v3(&l.force)))
                .collect(),
            gravity: structure.gravity().map(|g| v3(&g)),
            ..SceneArrays::default()
        }
    }

    /// The columns of a scene: its structure ([`SceneArrays::from_structure`]) and its
    /// `[simulation]`, `[ground]` and `[[actuation]]` tables.
    ///
    /// ```
    /// use tensegrity_io::scene::{Scene, SceneArrays};
    /// let text = "nodes = [[0.0, 0.0, 0.1], [1.0, 0.0, 0.1]]\n[[bars]]\nnodes = [0, 1]\nmass = 1.0\n\
    ///             [simulation]\nt_end = 0.5\n[ground]\nstiffness = 1e4\n";
    /// let scene = Scene::from_str_named(text, "bar.toml")?;
    /// let a = SceneArrays::of(&scene);
    /// assert_eq!((a.bars.clone(), a.bar_mass.clone()), (vec![[0, 1]], Some(vec![Some(1.0)])));
    /// assert_eq!(a.simulation.as_ref().map(|s| s.t_end), Some(0.5));
    /// let back = Scene::from_arrays(a, "data")?;
    /// assert_eq!(back.structure, scene.structure);
    /// assert_eq!(back.simulation()?.settings.t_end, 0.5);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn of(scene: &Scene) -> SceneArrays {
        let file = &scene.file;
        SceneArrays {
            simulation: file.simulation.clone(),
            ground: file.ground.as_ref().map(|g| g.get_ref().clone()),
            actuation: file.actuation.iter().map(|a| a.get_ref().clone()).collect(),
            actuators: file.actuators.iter().map(|a| a.get_ref().clone()).collect(),
            ..SceneArrays::with_file_keys(scene)
        }
    }

    /// The columns of a scene's structure ([`SceneArrays::from_structure`]) with the keys its
    /// file holds beside the structure: bars' `rest_length`, `rest_length_change` and
    /// `elastic`, strings' `mass` and `rest_length_change`, clusters' `rest_length_change`,
    /// supports' `displacement`, the
    /// `[[masses]]`; not its dynamics tables.
    ///
    /// ```
    /// use tensegrity_io::scene::{Scene, SceneArrays};
    /// let text = "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n[[strings]]\nnodes = [0, 1]\n\
    ///             stiffness = 10.0\nmass = 0.5\n[[supports]]\nnode = 0\n\
    ///             displacement = [0.0, 0.0, 0.1]\n[[masses]]\nnode = 1\nmass = 2.0\n";
    /// let scene = Scene::from_str_named(text, "net.toml")?;
    /// let a = SceneArrays::with_file_keys(&scene);
    /// assert_eq!(a.string_mass, Some(vec![Some(0.5)]));
    /// assert_eq!(a.support_displacement, Some(vec![Some([0.0, 0.0, 0.1])]));
    /// assert_eq!(a.masses, vec![(1, 2.0)]);
    /// let back = Scene::from_arrays(a, "data")?;
    /// assert_eq!(back.file.point_masses(), vec![(1, 2.0)]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_file_keys(scene: &Scene) -> SceneArrays {
        let file = &scene.file;
        let index = |i: usize| i64::try_from(i).unwrap_or(i64::MAX);
        let bars = || file.bars.iter().map(|b| b.get_ref());
        let strings = || file.strings.iter().map(|s| s.get_ref());
        SceneArrays {
            support_displacement: column(file.supports.iter().map(|s| s.get_ref().displacement)),
            bar_rest_length: column(bars().map(|b| b.rest_length)),
            bar_rest_length_change: column(bars().map(|b| b.rest_length_change)),
            rest_length_change: column(strings().map(|s| s.rest_length_change)),
            cluster_rest_length_change: column(
                file.clusters.iter().map(|c| c.get_ref().rest_length_change),
            ),
            bar_elastic: column(bars().map(|b| b.elastic)),
            string_mass: column(strings().map(|s| s.mass)),
            masses: (file.masses.iter())
                .map(|m| (index(m.get_ref().node), m.get_ref().mass))
                .collect(),
            ..SceneArrays::from_structure(&scene.structure)
        }
    }

    /// Every per-member column holds one entry per member, and every per-support column
    /// one per support.
    fn check_columns(&self, file: &str) -> Result<()> {
        let numbers = |c: &Option<Vec<Option<f64>>>| c.as_ref().map(Vec::len);
        let names = |c: &Option<Vec<Option<String>>>| c.as_ref().map(Vec::len);
        let lengths = [
            ("bar_mass", numbers(&self.bar_mass)),
            ("bar_radius", numbers(&self.bar_radius)),
            ("bar_material", names(&self.bar_material)),
            ("stiffness", numbers(&self.stiffness)),
            ("rest_length", numbers(&self.rest_length)),
            ("damping", numbers(&self.damping)),
            ("string_material", names(&self.string_material)),
            ("bar_rest_length", numbers(&self.bar_rest_length)),
            (
                "bar_rest_length_change",
                numbers(&self.bar_rest_length_change),
            ),
            ("rest_length_change", numbers(&self.rest_length_change)),
            ("bar_elastic", self.bar_elastic.as_ref().map(Vec::len)),
            ("string_mass", numbers(&self.string_mass)),
        ];
        let clusters = [
            ("cluster_stiffness", numbers(&self.cluster_stiffness)),
            ("cluster_rest_length", numbers(&self.cluster_rest_length)),
            ("cluster_damping", numbers(&self.cluster_damping)),
            (
                "cluster_friction",
                self.cluster_friction.as_ref().map(Vec::len),
            ),
            ("cluster_material", names(&self.cluster_material)),
            (
                "cluster_rest_length_change",
                numbers(&self.cluster_rest_length_change),
            ),
        ];
        for (column, got) in clusters {
            match got {
                Some(got) if got != self.clusters.len() => {
                    return Err(IoError::ColumnLength {
                        file: file.to_string(),
                        column,
                        member: "cluster",
                        expected: self.clusters.len(),
                        got,
                    })
                }
                _ => {}
            }
        }
        let supports = [
            ("support_along", self.support_along.as_ref().map(Vec::len)),
            ("support_stiffness", numbers(&self.support_stiffness)),
            (
                "support_displacement",
                self.support_displacement.as_ref().map(Vec::len),
            ),
        ];
        for (column, got) in supports {
            match got {
                Some(got) if got != self.supports.len() => {
                    return Err(IoError::ColumnLength {
                        file: file.to_string(),
                        column,
                        member: "support",
                        expected: self.supports.len(),
                        got,
                    })
                }
                _ => {}
            }
        }
        for (column, got) in lengths {
            let (member, expected) = match column.starts_with("bar_") {
                true => ("bar", self.bars.len()),
                false => ("string", self.strings.len()),
            };
            match got {
                Some(got) if got != expected => {
                    return Err(IoError::ColumnLength {
                        file: file.to_string(),
                        column,
                        member,
                        expected,
                        got,
                    })
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The scene file these columns describe (items without spans: data has no lines);
    /// `file` labels the errors of a column's length or a negative node index.
    fn into_file(self, file: &str) -> Result<SceneFile> {
        self.check_columns(file)?;
        let n = self.nodes.len();
        let ends = |kind: &str, k: usize, [a, b]: [i64; 2]| -> Result<Vec<usize>> {
            let item = || format!("{kind} {k}");
            Ok(vec![
                node_index(file, item, a, n)?,
                node_index(file, item, b, n)?,
            ])
        };
        let mut bars = Vec::with_capacity(self.bars.len());
        for (k, &pair) in self.bars.iter().enumerate() {
            bars.push(unspanned(BarSpec {
                nodes: ends("bar", k, pair)?,
                mass: entry(&self.bar_mass, k),
                material: entry(&self.bar_material, k),
                radius: entry(&self.bar_radius, k),
                rest_length_change: entry(&self.bar_rest_length_change, k),
                rest_length: entry(&self.bar_rest_length, k),
                elastic: entry(&self.bar_elastic, k),
            }));
        }
        let mut strings = Vec::with_capacity(self.strings.len());
        for (k, &pair) in self.strings.iter().enumerate() {
            strings.push(unspanned(StringSpec {
                nodes: ends("string", k, pair)?,
                stiffness: entry(&self.stiffness, k),
                rest_length: entry(&self.rest_length, k),
                damping: entry(&self.damping, k),
                material: entry(&self.string_material, k),
                rest_length_change: entry(&self.rest_length_change, k),
                mass: entry(&self.string_mass, k),
            }));
        }
        let mut clusters = Vec::with_capacity(self.clusters.len());
        for (k, path) in self.clusters.iter().enumerate() {
            let mut nodes = Vec::with_capacity(path.len());
            for &i in path {
                nodes.push(node_index(file, || format!("cluster {k}"), i, n)?);
            }
            clusters.push(unspanned(ClusterSpec {
                nodes,
                stiffness: entry(&self.cluster_stiffness, k),
                rest_length: entry(&self.cluster_rest_length, k),
                damping: entry(&self.cluster_damping, k),
                friction: entry(&self.cluster_friction, k),
                material: entry(&self.cluster_material, k),
                rest_length_change: entry(&self.cluster_rest_length_change, k),
            }));
        }
        let (supports, loads) = self.nodal_items(file)?;
        let mut masses = Vec::with_capacity(self.masses.len());
        for (k, &(node, mass)) in self.masses.iter().enumerate() {
            let node = node_index(file, || format!("point mass {k}"), node, n)?;
            masses.push(unspanned(PointMassSpec { node, mass }));
        }
        Ok(SceneFile {
            nodes: self.nodes.into_iter().map(unspanned).collect(),
            velocities: self.velocities,
            materials: self.materials,
            bars,
            strings,
            clusters,
            supports,
            loads,
            gravity: self
                .gravity
                .map(|acceleration| GravitySpec { acceleration }),
            simulation: self.simulation,
            ground: self.ground.map(unspanned),
            actuation: self.actuation.into_iter().map(unspanned).collect(),
            actuators: self.actuators.into_iter().map(unspanned).collect(),
            masses,
        })
    }

    /// The supports and loads as the scene file's entries.
    #[allow(clippy::type_complexity)]
    fn nodal_items(
        &self,
        file: &str,
    ) -> Result<(Vec<Spanned<SupportSpec>>, Vec<Spanned<LoadSpec>>)> {
        let n = self.nodes.len();
        let mut supports = Vec::with_capacity(self.supports.len());
        for (k, &(node, fixed)) in self.supports.iter().enumerate() {
            let along: Option<Vec<[f64; 3]>> = entry(&self.support_along, k);
            supports.push(unspanned(SupportSpec {
                node: node_index(file, || format!("support {k}"), node, n)?,
                directions: None,
                // `along` alone holds its own directions only, as in a scene file
                fixed: (along.is_none() || fixed != [false; 3]).then_some(fixed),
                displacement: entry(&self.support_displacement, k),
                along,
                stiffness: entry(&self.support_stiffness, k),
            }));
        }
        let mut loads = Vec::with_capacity(self.loads.len());
        for (k, &(node, force)) in self.loads.iter().enumerate() {
            loads.push(unspanned(LoadSpec {
                node: node_index(file, || format!("load {k}"), node, n)?,
                force,
            }));
        }
        Ok((supports, loads))
    }
}

/// A per-member column: `None` when no member sets the property.
fn column<T>(values: impl Iterator<Item = Option<T>>) -> Option<Vec<Option<T>>> {
    let values: Vec<Option<T>> = values.collect();
    values.iter().any(Option::is_some).then_some(values)
}

/// The materials the members of a structure name, as its material table holds them.
fn used_materials(structure: &Structure) -> BTreeMap<String, MaterialSpec> {
    let bars = structure
        .bars()
        .iter()
        .filter_map(|b| b.material.as_deref());
    let strings = structure
        .strings()
        .iter()
        .filter_map(|s| s.material.as_deref());
    let clusters = (structure.clusters().iter()).filter_map(|c| c.material.as_deref());
    bars.chain(strings)
        .chain(clusters)
        .filter_map(|name| {
            let m = structure.materials().get(name)?;
            let spec = MaterialSpec {
                density: m.density,
                youngs_modulus: m.youngs_modulus,
                yield_strength: m.yield_strength,
            };
            Some((name.to_string(), spec))
        })
        .collect()
}

impl Scene {
    /// A scene from data, validated exactly as [`Scene::from_str_named`] validates a file
    /// (the same core builder, the same checks of the dynamics tables); `name` labels the
    /// errors, which name the item (`bar 3`, `string 0`, `support 1`, `ground`) and no line:
    /// data has none. A node index that is negative or out of range, or a per-member column
    /// that does not hold one entry per member, is an error naming the member or the column.
    ///
    /// ```
    /// use tensegrity_io::scene::{Scene, SceneArrays};
    /// let prism = Scene::from_path("../../examples/prism.toml".as_ref())?;
    /// let mut a = SceneArrays::of(&prism);
    /// assert_eq!(Scene::from_arrays(a.clone(), "prism")?.structure, prism.structure);
    /// a.strings[4] = [4, 9];
    /// let e = Scene::from_arrays(a.clone(), "prism").unwrap_err().to_string();
    /// assert_eq!(e, "prism: string 4: node index 9 is out of range (the structure has 6 nodes, 0-based)");
    /// a.strings[4] = [-1, 5];
    /// let e = Scene::from_arrays(a, "prism").unwrap_err().to_string();
    /// assert!(e.starts_with("prism: string 4: node index -1 is out of range"), "{e}");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_arrays(arrays: SceneArrays, name: &str) -> Result<Scene> {
        let file = arrays.into_file(name)?;
        let structure = file.validate(None, name)?;
        Ok(Scene { structure, file })
    }
}

/// The numbers of the data: a number, or the text of a non-finite float ([`SceneArrays`]).
mod number {
    use serde::de::{self, Deserialize, Deserializer, Unexpected, Visitor};
    use std::fmt;

    /// One number.
    #[derive(Clone, Copy)]
    struct Number(f64);

    impl<'de> Deserialize<'de> for Number {
        fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            d.deserialize_any(NumberVisitor)
        }
    }

    struct NumberVisitor;

    impl Visitor<'_> for NumberVisitor {
        type Value = Number;

        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("a number (or nan, inf, -inf)")
        }

        fn visit_f64<E: de::Error>(self, x: f64) -> Result<Number, E> {
            Ok(Number(x))
        }

        fn visit_i64<E: de::Error>(self, x: i64) -> Result<Number, E> {
            Ok(Number(x as f64))
        }

        fn visit_u64<E: de::Error>(self, x: u64) -> Result<Number, E> {
            Ok(Number(x as f64))
        }

        fn visit_str<E: de::Error>(self, s: &str) -> Result<Number, E> {
            let x = match s.trim().to_ascii_lowercase().as_str() {
                "nan" | "+nan" | "-nan" => f64::NAN,
                "inf" | "+inf" | "infinity" | "+infinity" => f64::INFINITY,
                "-inf" | "-infinity" => f64::NEG_INFINITY,
                _ => return Err(E::invalid_value(Unexpected::Str(s), &self)),
            };
            Ok(Number(x))
        }
    }

    fn point(p: [Number; 3]) -> [f64; 3] {
        p.map(|x| x.0)
    }

    /// n × 3 numbers.
    pub(super) fn points<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[f64; 3]>, D::Error> {
        Ok(Vec::<[Number; 3]>::deserialize(d)?
            .into_iter()
            .map(point)
            .collect())
    }

    /// n × 3 numbers, or none.
    pub(super) fn opt_points<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<Vec<[f64; 3]>>, D::Error> {
        let given = Option::<Vec<[Number; 3]>>::deserialize(d)?;
        Ok(given.map(|v| v.into_iter().map(point).collect()))
    }

    /// Three numbers, or none.
    pub(super) fn opt_point<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 3]>, D::Error> {
        Ok(Option::<[Number; 3]>::deserialize(d)?.map(point))
    }

    /// A column of numbers and nulls, or none.
    pub(super) fn opt_column<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<Vec<Option<f64>>>, D::Error> {
        let given = Option::<Vec<Option<Number>>>::deserialize(d)?;
        Ok(given.map(|v| v.into_iter().map(|x| x.map(|x| x.0)).collect()))
    }

    /// A column of three numbers or null each, or none.
    #[allow(clippy::type_complexity)]
    pub(super) fn opt_column_points<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<Vec<Option<[f64; 3]>>>, D::Error> {
        let given = Option::<Vec<Option<[Number; 3]>>>::deserialize(d)?;
        Ok(given.map(|v| v.into_iter().map(|p| p.map(point)).collect()))
    }

    /// Nodes with a force each.
    #[allow(clippy::type_complexity)]
    pub(super) fn loads<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<(i64, [f64; 3])>, D::Error> {
        let given = Vec::<(i64, [Number; 3])>::deserialize(d)?;
        Ok(given.into_iter().map(|(n, f)| (n, point(f))).collect())
    }
}
