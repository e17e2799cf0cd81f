//! TOML scene files: nodes, materials, bars, strings, supports, loads and gravity, plus the
//! dynamics tables of [`dynamics`]; or the same scene as data ([`SceneArrays`]: the
//! structure as columns, for a front end that holds it as arrays; [`Scene::from_arrays`]).
//!
//! The file schema ([`SceneFile`] and its `*Spec` tables) is mapped onto the core's builders
//! ([`Structure::builder`], [`tensegrity_dynamics::Simulation::new`],
//! [`tensegrity_dynamics::Ground::new`]); the core itself knows no file format.
//!
//! Node indices are 0-based. Unknown keys are rejected, and every error names the offending
//! item and its line (structure data has no lines: its errors name the item alone). A
//! support's `along` directions must be unit vectors (to
//! [`UNIT_TOLERANCE`](tensegrity_core::structure::UNIT_TOLERANCE)), finite and independent,
//! and its `stiffness` positive and finite (`support 2: ...`); `along` and `stiffness` are
//! read by `statics` and `solve` ([`SceneFile::support_keys`]), a load path's drivers by
//! `solve` ([`SceneFile::driver_keys`]), a support's `displacement` also by `statics` (its
//! linear response, [`SceneFile::support_displacements`]):
//!
//! ```toml
//! nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]]
//! velocities = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]   # optional
//! [materials.alu]
//! density = 2700.0          # kg/m^3
//! youngs_modulus = 60e9     # Pa
//! yield_strength = 110e6    # Pa
//! [[bars]]
//! nodes = [0, 1]
//! mass = 1.0                # kg, optional
//! material = "alu"          # optional
//! radius = 0.01             # m, optional
//! elastic = true            # optional: this bar elastic (true) or rigid (false) in
//!                           # `simulate`, whatever `[simulation] bars` says
//! [[strings]]
//! nodes = [0, 2]
//! stiffness = 100.0         # N/m, optional
//! rest_length = 0.9         # m, optional
//! damping = 0.0             # N s/m, optional
//! material = "alu"          # optional
//! [[supports]]
//! node = 0
//! directions = ["x", "y", "z"]   # optional, all three by default (or fixed = [true, true, true])
//! [[supports]]
//! node = 2
//! along = [[0.0, 0.6, 0.8]]      # optional: held along unit directions of any orientation
//!                                # (one to three, independent), in place of directions/fixed
//! stiffness = 1e4                # N/m, optional: a spring along each held direction
//! [[loads]]
//! node = 1
//! force = [-1.0e4, 0.0, 0.0]
//! [gravity]
//! acceleration = [0.0, 0.0, -9.81]
//! ```

mod actuators;
mod arrays;
mod checks;
pub mod dynamics;
mod json;
mod write;

pub use actuators::{actuators, ActuatorSpec};
pub use arrays::SceneArrays;
pub use json::json_schema;
pub use write::{scene_to_toml, to_toml};

pub use dynamics::{
    build_simulation, ActuationSpec, BarModel, GroundModelKind, GroundSpec, MassMatrixKind,
    RecordQuantity, SimulationSpec, GROUND_START_TOLERANCE,
};

use crate::error::{IoError, Result};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;
use tensegrity_core::{Bar, CoreError, Material, ModelError, StringMember, Structure, Support};
use tensegrity_dynamics::Simulation;
use toml::Spanned;

/// The raw contents of a scene file (TOML, or JSON of the same shape: [`Scene::from_json_named`];
/// its JSON Schema: [`json_schema`]).
#[derive(Debug, Clone, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Node positions (m).
    #[schemars(with = "Vec<[f64; 3]>")]
    pub nodes: Vec<Spanned<[f64; 3]>>,
    /// Initial node velocities (m/s), one per node.
    #[serde(default)]
    pub velocities: Option<Vec<[f64; 3]>>,
    /// User materials by name.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialSpec>,
    /// Bars.
    #[serde(default)]
    #[schemars(with = "Vec<BarSpec>")]
    pub bars: Vec<Spanned<BarSpec>>,
    /// Strings.
    #[serde(default)]
    #[schemars(with = "Vec<StringSpec>")]
    pub strings: Vec<Spanned<StringSpec>>,
    /// Clustered strings: one continuous string through several nodes (pulleys).
    #[serde(default)]
    #[schemars(with = "Vec<ClusterSpec>")]
    pub clusters: Vec<Spanned<ClusterSpec>>,
    /// Supports.
    #[serde(default)]
    #[schemars(with = "Vec<SupportSpec>")]
    pub supports: Vec<Spanned<SupportSpec>>,
    /// Nodal loads.
    #[serde(default)]
    #[schemars(with = "Vec<LoadSpec>")]
    pub loads: Vec<Spanned<LoadSpec>>,
    /// Gravity.
    #[serde(default)]
    pub gravity: Option<GravitySpec>,
    /// `[simulation]`: integrator, end time, tolerances, output times.
    #[serde(default)]
    pub simulation: Option<SimulationSpec>,
    /// `[ground]`: a plane, its contact model and the nodes that can touch it.
    #[serde(default)]
    #[schemars(with = "Option<GroundSpec>")]
    pub ground: Option<Spanned<GroundSpec>>,
    /// `[[actuation]]`: time tables of string rest lengths or nodal loads.
    #[serde(default)]
    #[schemars(with = "Vec<ActuationSpec>")]
    pub actuation: Vec<Spanned<ActuationSpec>>,
    /// `[[actuators]]`: the rest lengths a controller of a stepped simulation sets, and
    /// their limits (module [`actuators`](fn@actuators)).
    #[serde(default)]
    #[schemars(with = "Vec<ActuatorSpec>")]
    pub actuators: Vec<Spanned<ActuatorSpec>>,
    /// `[[masses]]`: point masses at nodes, read by the elastic dynamics only
    /// ([`SceneFile::elastic_keys`]).
    #[serde(default)]
    #[schemars(with = "Vec<PointMassSpec>")]
    pub masses: Vec<Spanned<PointMassSpec>>,
}

/// A `[[masses]]` entry: a point mass at a node (kg).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointMassSpec {
    /// The node.
    pub node: usize,
    /// Its mass (kg).
    pub mass: f64,
}

/// A `[materials.NAME]` table.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// kg/m³.
    pub density: f64,
    /// Pa.
    pub youngs_modulus: f64,
    /// Pa.
    pub yield_strength: f64,
}

/// A `[[bars]]` entry.
#[derive(Debug, Clone, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BarSpec {
    /// Start and end node (exactly two; checked when the structure is built).
    pub nodes: Vec<usize>,
    /// kg.
    pub mass: Option<f64>,
    /// Material name.
    pub material: Option<String>,
    /// Cross-section radius (m).
    pub radius: Option<f64>,
    /// The change of its rest length at load factor 1 along a load path (m), read by
    /// `solve` only ([`SceneFile::path_keys`]).
    pub rest_length_change: Option<f64>,
    /// Its rest length as an elastic bar (m; default its length in the scene: unstressed),
    /// read by `solve` and the elastic dynamics only ([`SceneFile::elastic_keys`]).
    pub rest_length: Option<f64>,
    /// Whether `simulate` runs it elastic (`true`: an axial spring, which needs a material
    /// and a radius) or rigid (`false`), over `[simulation] bars`; read by `simulate` only
    /// ([`SceneFile::bar_model_keys`]). Another value than a boolean is an error naming
    /// the bar and the key.
    #[serde(default, deserialize_with = "bar_model_flag")]
    pub elastic: Option<bool>,
}

/// A bar's `elastic`: a boolean, else an error naming the key (the bar is named by
/// [`Scene::from_str_named`] from the error's position).
fn bar_model_flag<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Option<bool>, D::Error> {
    match toml::Value::deserialize(d)? {
        toml::Value::Boolean(b) => Ok(Some(b)),
        other => Err(serde::de::Error::custom(format!(
            "{BAR_MODEL_KEY} = {other}: give true (an elastic bar) or false (a rigid one)"
        ))),
    }
}

/// The key of [`BarSpec::elastic`].
const BAR_MODEL_KEY: &str = "elastic";

/// The `[[bars]]` entry that holds byte `offset` of `text` (its index), if any: the number
/// of `[[bars]]` headers before it, provided the last table header before it is one.
fn bar_at(text: &str, offset: usize) -> Option<usize> {
    let before = text.get(..offset)?;
    let mut bar = None;
    let mut count = 0;
    for line in before.lines() {
        let line = line.trim_start();
        if line.starts_with('[') {
            bar = (line.trim_end() == "[[bars]]").then_some(count);
            if bar.is_some() {
                count += 1;
            }
        }
    }
    bar
}

/// A `[[strings]]` entry.
#[derive(Debug, Clone, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StringSpec {
    /// Start and end node (exactly two; checked when the structure is built).
    pub nodes: Vec<usize>,
    /// N/m.
    pub stiffness: Option<f64>,
    /// m.
    pub rest_length: Option<f64>,
    /// N·s/m.
    pub damping: Option<f64>,
    /// Material name.
    pub material: Option<String>,
    /// The change of its rest length at load factor 1 along a load path (m), read by
    /// `solve` only ([`SceneFile::path_keys`]).
    pub rest_length_change: Option<f64>,
    /// Its mass (kg), read by the elastic dynamics only ([`SceneFile::elastic_keys`]).
    pub mass: Option<f64>,
}

/// A `[[clusters]]` entry: a clustered string ([`tensegrity_core::Cluster`]).
#[derive(Debug, Clone, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ClusterSpec {
    /// The nodes it passes through, in order (at least three; inner nodes are pulleys).
    pub nodes: Vec<usize>,
    /// Axial stiffness of the whole cluster (N/m: EA/L₀).
    pub stiffness: Option<f64>,
    /// Rest length of the whole cluster (m).
    pub rest_length: Option<f64>,
    /// N·s/m, on the rate of its length.
    pub damping: Option<f64>,
    /// The friction coefficient μ of the pulley at each inner node (capstan law); absent:
    /// frictionless.
    pub friction: Option<Vec<f64>>,
    /// The change of its whole rest length at load factor 1 (m; `solve` only: one actuator
    /// reeling every segment along a load path).
    #[serde(default)]
    pub rest_length_change: Option<f64>,
    /// Material name.
    pub material: Option<String>,
}

/// A direction letter in a support.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

/// A `[[supports]]` entry.
#[derive(Debug, Clone, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SupportSpec {
    /// The supported node.
    pub node: usize,
    /// Fixed directions (default: all three).
    pub directions: Option<Vec<Axis>>,
    /// Alternative to `directions`: fixed flags for x, y, z.
    pub fixed: Option<[bool; 3]>,
    /// The node's prescribed motion (m; along its held directions; on an elastic support,
    /// its springs' anchor moves): at load factor 1 along a load path (`solve`), and the
    /// linear response of `statics` ([`SceneFile::support_displacements`]); refused by the
    /// dynamics ([`SceneFile::driver_keys`]).
    pub displacement: Option<[f64; 3]>,
    /// Directions of any orientation the node is held along (unit vectors, one to three,
    /// independent), in place of `directions`: read by `solve` and `statics`
    /// ([`SceneFile::support_keys`]).
    pub along: Option<Vec<[f64; 3]>>,
    /// The stiffness k (N/m) of a spring along each held direction (an elastic support;
    /// default: held rigidly): read by `solve` and `statics` ([`SceneFile::support_keys`]).
    pub stiffness: Option<f64>,
}

/// A `[[loads]]` entry.
#[derive(Debug, Clone, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// The loaded node.
    pub node: usize,
    /// Force (N).
    pub force: [f64; 3],
}

/// The `[gravity]` table.
#[derive(Debug, Clone, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GravitySpec {
    /// Acceleration (m/s²).
    pub acceleration: [f64; 3],
}

/// A parsed and validated scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The structure.
    pub structure: Structure,
    /// The file contents as parsed (for the tables other analyses read); for a scene given
    /// as data ([`Scene::from_arrays`]) the same tables, their spans empty (`0..0`: data has
    /// no text, and its errors no line).
    pub file: SceneFile,
}

impl SceneFile {
    /// The items that carry a key the dynamics does not read: a load path's drivers
    /// ([`SceneFile::driver_keys`]) and the supports' `along` and `stiffness`
    /// ([`SceneFile::support_keys`]), as `bar 0: rest_length_change`: `simulate` refuses a
    /// scene that has one rather than ignore it.
    ///
    /// ```
    /// use tensegrity_io::scene::Scene;
    /// let text = "nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 1]\nrest_length_change = -0.1\n[[supports]]\nnode = 0\nstiffness = 1e4\n";
    /// let scene = Scene::from_str_named(text, "a.toml").unwrap();
    /// assert_eq!(scene.file.path_keys(), ["bar 0: rest_length_change", "support 0: stiffness"]);
    /// assert_eq!(scene.file.driver_keys(), ["bar 0: rest_length_change"]);
    /// ```
    pub fn path_keys(&self) -> Vec<String> {
        let mut keys = self.driver_keys();
        keys.extend(self.support_keys());
        keys
    }

    /// The supports that carry `along` (directions of any orientation) or `stiffness` (an
    /// elastic support), as `support 2: along`: read by `solve` and `statics`.
    pub fn support_keys(&self) -> Vec<String> {
        let mut keys = Vec::new();
        for (i, s) in self.supports.iter().enumerate() {
            let s = s.get_ref();
            if s.along.is_some() {
                keys.push(format!("support {i}: along"));
            }
            if s.stiffness.is_some() {
                keys.push(format!("support {i}: stiffness"));
            }
        }
        keys
    }

    /// The items that carry a load path's driver (`rest_length_change` on a bar or a string,
    /// `displacement` on a support), as `bar 0: rest_length_change`: read by `solve` (and a
    /// support's `displacement` by `statics`, [`SceneFile::rest_length_change_keys`]); the
    /// dynamics refuses a scene that has one rather than ignore it.
    pub fn driver_keys(&self) -> Vec<String> {
        let mut keys = self.rest_length_change_keys();
        for (i, s) in self.supports.iter().enumerate() {
            if s.get_ref().displacement.is_some() {
                keys.push(format!("support {i}: displacement"));
            }
        }
        keys
    }

    /// The bars and strings that carry a `rest_length_change` (a load path's driver, read by
    /// `solve` only), as `string 2: rest_length_change`: `statics`, which reads a support's
    /// `displacement`, refuses these.
    ///
    /// ```
    /// use tensegrity_io::scene::Scene;
    /// let text = "nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 1]\n[[supports]]\nnode = 0\n[[supports]]\nnode = 1\ndisplacement = [0.01, 0.0, 0.0]\n";
    /// let scene = Scene::from_str_named(text, "a.toml").unwrap();
    /// assert!(scene.file.rest_length_change_keys().is_empty());
    /// assert_eq!(scene.file.driver_keys(), ["support 1: displacement"]);
    /// assert_eq!(scene.file.support_displacements(), [None, Some([0.01, 0.0, 0.0])]);
    /// ```
    pub fn rest_length_change_keys(&self) -> Vec<String> {
        let bars = self.bars.iter().enumerate();
        let strings = self.strings.iter().enumerate();
        let mut keys: Vec<String> = bars
            .filter(|(_, b)| b.get_ref().rest_length_change.is_some())
            .map(|(i, _)| format!("bar {i}: rest_length_change"))
            .collect();
        keys.extend(
            strings
                .filter(|(_, s)| s.get_ref().rest_length_change.is_some())
                .map(|(i, _)| format!("string {i}: rest_length_change")),
        );
        keys.extend(
            self.clusters
                .iter()
                .enumerate()
                .filter(|(_, c)| c.get_ref().rest_length_change.is_some())
                .map(|(i, _)| format!("cluster {i}: rest_length_change")),
        );
        keys
    }

    /// Each cluster's `rest_length_change` (m at λ = 1; 0 where not given), in cluster
    /// order: a load path's driver of its whole rest length.
    pub fn cluster_rest_length_changes(&self) -> Vec<f64> {
        self.clusters
            .iter()
            .map(|c| c.get_ref().rest_length_change.unwrap_or(0.0))
            .collect()
    }

    /// Each support's `displacement` (m), in support order (`None` where not given): the
    /// prescribed displacements of `statics`' linear response.
    pub fn support_displacements(&self) -> Vec<Option<[f64; 3]>> {
        self.supports
            .iter()
            .map(|s| s.get_ref().displacement)
            .collect()
    }

    /// The items that carry a key only the elastic models read (a bar's `rest_length`: `solve`
    /// and the elastic dynamics; a string's `mass`, a `[[masses]]` entry: the elastic
    /// dynamics), as `string 2: mass`: the rigid-bar dynamics and the static analyses refuse
    /// a scene that has one rather than ignore it.
    ///
    /// ```
    /// use tensegrity_io::scene::Scene;
    /// let text = "nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]\n[[strings]]\nnodes = [0, 1]\nmass = 0.1\n[[masses]]\nnode = 1\nmass = 2.0\n";
    /// let scene = Scene::from_str_named(text, "a.toml").unwrap();
    /// assert_eq!(scene.file.elastic_keys(), vec!["string 0: mass", "point mass 0"]);
    /// ```
    pub fn elastic_keys(&self) -> Vec<String> {
        let mut keys: Vec<String> = self
            .bars
            .iter()
            .enumerate()
            .filter(|(_, b)| b.get_ref().rest_length.is_some())
            .map(|(i, _)| format!("bar {i}: rest_length"))
            .collect();
        keys.extend(
            self.strings
                .iter()
                .enumerate()
                .filter(|(_, s)| s.get_ref().mass.is_some())
                .map(|(i, _)| format!("string {i}: mass")),
        );
        keys.extend((0..self.masses.len()).map(|i| format!("point mass {i}")));
        keys
    }

    /// Whether the scene is run by the elastic (node-mass) dynamics: some bar is elastic
    /// ([`SceneFile::elastic_bars`]), or the scene has no bar and asks for elastic bars
    /// (`[simulation] bars = "elastic"`) or has some point mass (a net of strings whose mass
    /// is at its nodes). Its rigid bars are then length constraints of that model.
    ///
    /// ```
    /// use tensegrity_io::scene::Scene;
    /// let bars = "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\n[[bars]]\nnodes = [0, 1]\nmass = 1.0\n[[bars]]\nnodes = [1, 2]\nmass = 1.0\n";
    /// let rigid = Scene::from_str_named(bars, "a.toml").unwrap();
    /// assert!(!rigid.file.is_elastic());
    /// let one = format!("{bars}elastic = true\n");
    /// let mixed = Scene::from_str_named(&one, "a.toml").unwrap();
    /// assert_eq!((mixed.file.is_elastic(), mixed.file.elastic_bars()), (true, vec![false, true]));
    /// assert_eq!(mixed.file.bar_model_keys(), ["bar 1: elastic"]);
    /// ```
    pub fn is_elastic(&self) -> bool {
        let asked = self
            .simulation
            .as_ref()
            .is_some_and(|s| s.bars == dynamics::BarModel::Elastic);
        if self.bars.is_empty() {
            return asked || !self.masses.is_empty();
        }
        self.elastic_bars().contains(&true)
    }

    /// Whether each bar is elastic: its `elastic` key, else `[simulation] bars`.
    pub fn elastic_bars(&self) -> Vec<bool> {
        let asked = self
            .simulation
            .as_ref()
            .is_some_and(|s| s.bars == dynamics::BarModel::Elastic);
        self.bars
            .iter()
            .map(|b| b.get_ref().elastic.unwrap_or(asked))
            .collect()
    }

    /// The bars that carry an `elastic` key, as `bar 2: elastic`: read by `simulate` only
    /// (the static analyses refuse it; `solve`, whose bars are all elastic, refuses
    /// `elastic = false`).
    pub fn bar_model_keys(&self) -> Vec<String> {
        self.bars
            .iter()
            .enumerate()
            .filter(|(_, b)| b.get_ref().elastic.is_some())
            .map(|(i, _)| format!("bar {i}: elastic"))
            .collect()
    }

    /// Each bar's `rest_length` (`None` where not given).
    pub fn bar_rest_lengths(&self) -> Vec<Option<f64>> {
        self.bars.iter().map(|b| b.get_ref().rest_length).collect()
    }

    /// The `[[masses]]` entries as (node, mass in kg), unchecked (the elastic dynamics
    /// checks them against the structure, naming the entry).
    pub fn point_masses(&self) -> Vec<(usize, f64)> {
        self.masses
            .iter()
            .map(|m| (m.get_ref().node, m.get_ref().mass))
            .collect()
    }

    /// The supports held along directions of any orientation (`along`): node and directions.
    pub fn held_along(&self) -> Vec<(usize, Vec<[f64; 3]>)> {
        self.supports
            .iter()
            .filter_map(|s| {
                let s = s.get_ref();
                s.along.clone().map(|a| (s.node, a))
            })
            .collect()
    }

    /// The rest-length changes of the members (bars then strings, 0 where not given) and the
    /// motion of every node (from its supports' `displacement`, added), for a load path.
    pub fn path_drivers(&self, n_nodes: usize) -> (Vec<f64>, Vec<[f64; 3]>) {
        let changes = self
            .bars
            .iter()
            .map(|b| b.get_ref().rest_length_change.unwrap_or(0.0))
            .chain(
                self.strings
                    .iter()
                    .map(|s| s.get_ref().rest_length_change.unwrap_or(0.0)),
            )
            .collect();
        let mut motion = vec![[0.0; 3]; n_nodes];
        for s in &self.supports {
            let s = s.get_ref();
            if let (Some(d), Some(m)) = (s.displacement, motion.get_mut(s.node)) {
                for a in 0..3 {
                    m[a] += d[a];
                }
            }
        }
        (changes, motion)
    }
}

impl Scene {
    /// Reads and validates a scene file (TOML; JSON when its name ends in `.json`: module
    /// `json`); errors name the file, the item and its line (JSON: no line). A
    /// file over [`crate::read::MAX_SCENE_BYTES`] (or a stream giving more) is refused
    /// before it is read in full.
    pub fn from_path(path: &Path) -> Result<Scene> {
        let text = crate::read::read_text(path, crate::read::MAX_SCENE_BYTES, "a scene file")?;
        let name = path.display().to_string();
        if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"))
        {
            return Self::from_json_named(&text, &name);
        }
        Self::from_str_named(&text, &name)
    }

    /// Parses and validates scene text; `name` labels error messages.
    ///
    /// ```
    /// use tensegrity_io::scene::Scene;
    /// let text = "nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 7]\n";
    /// let err = Scene::from_str_named(text, "demo.toml").unwrap_err().to_string();
    /// assert!(err.contains("line 2") && err.contains("bar 0") && err.contains("7"), "{err}");
    /// ```
    pub fn from_str_named(text: &str, name: &str) -> Result<Scene> {
        let file: SceneFile = toml::from_str(text).map_err(|e| {
            let offset = e.span().map_or(0, |s| s.start);
            let (line, column) = line_column(text, offset);
            let mut message = e.message().trim_end().to_string();
            if message.starts_with(&format!("{BAR_MODEL_KEY} = ")) {
                if let Some(k) = bar_at(text, offset) {
                    message = format!("bar {k}: {message}");
                }
            }
            IoError::Parse {
                file: name.to_string(),
                line,
                column,
                message,
            }
        })?;
        let structure = file.validate(Some(text), name)?;
        Ok(Scene { structure, file })
    }

    /// The actuators of a stepped simulation of this scene: its `[[actuators]]` tables, or
    /// every string then every cluster without limits (see [`actuators`](fn@actuators)).
    pub fn actuators(&self) -> Result<Vec<tensegrity_dynamics::Actuator>> {
        let tables: Vec<ActuatorSpec> = self
            .file
            .actuators
            .iter()
            .map(|a| a.get_ref().clone())
            .collect();
        actuators(&tables, &self.structure)
    }

    /// The runnable simulation of this scene: its structure with the `[simulation]`,
    /// `[ground]` and `[[actuation]]` tables (see [`build_simulation`]).
    pub fn simulation(&self) -> Result<Simulation> {
        let actuation: Vec<ActuationSpec> = self
            .file
            .actuation
            .iter()
            .map(|a| a.get_ref().clone())
            .collect();
        build_simulation(
            &self.structure,
            self.file.simulation.as_ref(),
            self.file.ground.as_ref().map(Spanned::get_ref),
            &actuation,
        )
    }
}

impl SceneFile {
    /// Builds and validates the structure; errors carry the line of the item they name
    /// (`text` is the scene text these tables were parsed from, `name` labels the errors).
    pub fn build_structure(&self, text: &str, name: &str) -> Result<Structure> {
        self.structure_at(Some(text), name)
    }

    /// The structure, validated, and the dynamics tables checked against it: what every
    /// scene passes, read from text (`Some(text)`: errors carry the line of their item) or
    /// given as data (`None`: no line).
    pub(crate) fn validate(&self, text: Option<&str>, name: &str) -> Result<Structure> {
        let structure = self.structure_at(text, name)?;
        self.check_dynamics(&structure, text, name)?;
        self.check_masses(structure.n_nodes(), text, name)?;
        Ok(structure)
    }

    /// [`SceneFile::build_structure`], with the line of an error where `text` is given.
    fn structure_at(&self, text: Option<&str>, name: &str) -> Result<Structure> {
        self.to_builder(text, name)?.build().map_err(|source| {
            let line = self
                .line_of(&error_item(&source))
                .and_then(|start| line_at(text, start));
            IoError::InvalidStructure {
                file: name.to_string(),
                line,
                source,
            }
        })
    }

    /// The core builder holding every table of the file (not yet validated).
    fn to_builder(
        &self,
        text: Option<&str>,
        name: &str,
    ) -> Result<tensegrity_core::StructureBuilder> {
        let mut b = Structure::builder().nodes(self.nodes.iter().map(|n| *n.get_ref()));
        if let Some(v) = &self.velocities {
            b = b.velocities(v.iter().copied());
        }
        for (name, m) in &self.materials {
            b = b.material(
                name,
                Material::new(m.density, m.youngs_modulus, m.yield_strength),
            );
        }
        for (i, bar) in self.bars.iter().enumerate() {
            let s = bar.get_ref();
            let nodes = two_nodes(
                &s.nodes,
                || format!("bar {i}"),
                bar.span().start,
                text,
                name,
            )?;
            b = b.bar(Bar {
                nodes,
                mass: s.mass,
                material: s.material.clone(),
                radius: s.radius,
            });
        }
        for (i, string) in self.strings.iter().enumerate() {
            let s = string.get_ref();
            let nodes = two_nodes(
                &s.nodes,
                || format!("string {i}"),
                string.span().start,
                text,
                name,
            )?;
            b = b.string(StringMember {
                nodes,
                stiffness: s.stiffness,
                rest_length: s.rest_length,
                damping: s.damping.unwrap_or(0.0),
                material: s.material.clone(),
            });
        }
        for c in &self.clusters {
            let c = c.get_ref();
            b = b.cluster(tensegrity_core::Cluster {
                nodes: c.nodes.clone(),
                stiffness: c.stiffness,
                rest_length: c.rest_length,
                damping: c.damping.unwrap_or(0.0),
                friction: c.friction.clone(),
                material: c.material.clone(),
            });
        }
        for (i, sup) in self.supports.iter().enumerate() {
            let s = sup.get_ref();
            let fixed = match (&s.directions, s.fixed) {
                (Some(_), Some(_)) => {
                    return Err(IoError::ConflictingSupport {
                        file: name.to_string(),
                        line: line_at(text, sup.span().start),
                        support: i,
                    })
                }
                _ if s.along.is_some() && (s.directions.is_some() || s.fixed.is_some()) => {
                    return Err(IoError::AmbiguousSupport {
                        file: name.to_string(),
                        line: line_at(text, sup.span().start),
                        support: i,
                    })
                }
                (Some(dirs), None) => [Axis::X, Axis::Y, Axis::Z].map(|a| dirs.contains(&a)),
                (None, Some(flags)) => flags,
                // `along` holds its own directions only
                (None, None) if s.along.is_some() => [false; 3],
                (None, None) => [true; 3],
            };
            let mut support = Support::directions(s.node, fixed);
            support.along = (s.along.iter().flatten().copied())
                .map(nalgebra::Vector3::from)
                .collect();
            support.stiffness = s.stiffness;
            b = b.support(support);
        }
        for load in &self.loads {
            let l = load.get_ref();
            b = b.load(l.node, l.force);
        }
        if let Some(g) = &self.gravity {
            b = b.gravity(g.acceleration);
        }
        Ok(b)
    }

    /// Byte offset where the item named like `bar 3`, `string 0`, `support 1`, `load 2` or
    /// `node 4` starts.
    fn line_of(&self, item: &Option<(String, usize)>) -> Option<usize> {
        let (kind, i) = item.as_ref()?;
        let span = match kind.as_str() {
            "bar" => self.bars.get(*i)?.span(),
            "string" => self.strings.get(*i)?.span(),
            "cluster" => self.clusters.get(*i)?.span(),
            "support" => self.supports.get(*i)?.span(),
            "load" => self.loads.get(*i)?.span(),
            "node" => self.nodes.get(*i)?.span(),
            _ => return None,
        };
        Some(span.start)
    }
}

/// The two node indices of a member, or the error naming it (`member`) and its line.
fn two_nodes(
    nodes: &[usize],
    member: impl Fn() -> String,
    start: usize,
    text: Option<&str>,
    name: &str,
) -> Result<[usize; 2]> {
    <[usize; 2]>::try_from(nodes).map_err(|_| IoError::NodeCount {
        file: name.to_string(),
        line: line_at(text, start),
        member: member(),
        count: nodes.len(),
        nodes: nodes.to_vec(),
    })
}

/// The `(kind, index)` of the item an error names, when it is a numbered item.
fn error_item(e: &CoreError) -> Option<(String, usize)> {
    let text = match e {
        CoreError::Model(ModelError::NodeIndexOutOfRange { item, .. })
        | CoreError::Model(ModelError::NonFinite { item, .. })
        | CoreError::Model(ModelError::NonPositiveConstant { item, .. })
        | CoreError::Model(ModelError::NegativeConstant { item, .. })
        | CoreError::Model(ModelError::UnknownMaterial { item, .. }) => item.clone(),
        CoreError::Model(ModelError::SelfLoop { member, .. })
        | CoreError::Model(ModelError::DuplicateMember { member, .. })
        | CoreError::Model(ModelError::ZeroLengthMember { member, .. })
        | CoreError::Model(ModelError::MemberLengthOverflow { member, .. }) => member.to_string(),
        CoreError::Model(ModelError::IsolatedNode { node }) => format!("node {node}"),
        CoreError::Model(ModelError::InvalidCluster { cluster, .. }) => {
            format!("cluster {cluster}")
        }
        CoreError::Model(ModelError::DuplicateSupport { support, .. })
        | CoreError::Model(ModelError::EmptySupport { support })
        | CoreError::Model(ModelError::InvalidSupport { support, .. }) => {
            format!("support {support}")
        }
        _ => return None,
    };
    let mut words = text.split_whitespace();
    let kind = words.next()?.to_string();
    let index = words.next()?.parse().ok()?;
    Some((kind, index))
}

/// The 1-based line of a byte offset of the scene text; `None` without text (structure data
/// has no lines, and none is made up for it).
pub(crate) fn line_at(text: Option<&str>, offset: usize) -> Option<usize> {
    text.map(|t| line_column(t, offset).0)
}

/// 1-based line and column (in characters) of a byte offset.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (
        before.matches('\n').count() + 1,
        before[line_start..].chars().count() + 1,
    )
}
