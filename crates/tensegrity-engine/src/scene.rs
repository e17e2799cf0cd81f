//! The scene of the scene commands (`statics`, `simulate`): a scene file (TOML, or JSON
//! when its name ends in `.json`), its text (JSON when it starts with `{`), or the scene as
//! data — the structure's arrays and the dynamics tables
//! ([`SceneSource`], [`tensegrity_io::scene::SceneArrays`]) — read and validated by
//! [`tensegrity_io::scene`]; and [`SceneError`], what a scene command fails with.
//!
//! A scene given as a string (a flag, a sweep value, a Python argument) is a file or TOML
//! text. The rule: a string naming an existing file is that file; one line ending in `.toml`
//! is a path (so `a=b.toml` that does not exist says it cannot be read); other text holding a
//! line break or an `=` is TOML text (every scene has at least one `key = value` line), and
//! text starting with `{` is JSON text; any
//! other string is a path, relative to the working directory. A scene given as an object (a front end that
//! holds the structure as arrays: the Python package's `Structure`) is data, validated as a
//! file is ([`tensegrity_io::scene::Scene::from_arrays`]); its errors name the item, with no
//! line.
//!
//! The serde form is the string, or the object of the arrays: it reads back as the same
//! source. No report echoes its request's scene, so the form of the data is the data itself
//! rather than a summary (a summary would not read back); messages name it `structure data`
//! ([`fmt::Display`]).
//!
//! ```
//! use tensegrity_engine::scene::SceneSource;
//! use serde_json::json;
//! let file = SceneSource::parse("examples/prism.toml");
//! assert_eq!(file, SceneSource::Path("examples/prism.toml".into()));
//! let text = SceneSource::parse("nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 1]\n");
//! assert!(matches!(text, SceneSource::Toml(_)));
//! let scene = text.load().unwrap();
//! assert_eq!(scene.structure.n_bars(), 1);
//! // the serde form is the string itself
//! assert_eq!(serde_json::to_value(&file).unwrap(), json!("examples/prism.toml"));
//! // an object is the scene as data: the same structure, and its own serde form
//! let data = json!({"nodes": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], "bars": [[0, 1]]});
//! let given: SceneSource = serde_json::from_value(data.clone()).unwrap();
//! assert_eq!((given.to_string(), given.load().unwrap().structure), ("structure data".into(), scene.structure));
//! assert_eq!(serde_json::to_value(&given).unwrap()["bars"], data["bars"]);
//! // a bad index names its bar
//! let bad: SceneSource = serde_json::from_value(json!({"nodes": [[0.0, 0.0, 0.0]], "bars": [[0, -1]]})).unwrap();
//! let e = bad.load().unwrap_err().to_string();
//! assert!(e.starts_with("structure data: bar 0: node index -1 is out of range"), "{e}");
//! ```

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::path::PathBuf;
use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;
use tensegrity_io::scene::{Scene, SceneArrays};
use tensegrity_io::IoError;

/// What messages call a scene given as data.
const DATA_NAME: &str = "structure data";

/// Where a scene comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneSource {
    /// A TOML scene file.
    Path(PathBuf),
    /// The text of a scene: TOML, or JSON of the same shape when it starts with `{`.
    Toml(String),
    /// The scene as data: the structure's arrays and the dynamics tables (validated when
    /// loaded).
    Data(Box<SceneArrays>),
}

impl SceneSource {
    /// The source a string names: an existing file is that file; one line ending in `.toml`
    /// is a path (so `a=b.toml`, missing, cannot be read); other text with a line break or an
    /// `=` is TOML (every scene has a `key = value` line); anything else is a path.
    pub fn parse(s: &str) -> Self {
        let path = std::path::Path::new(s);
        let one_line_toml_name = !s.contains(['\n', '\r']) && s.ends_with(".toml");
        let json = s.trim_start().starts_with('{');
        if path.is_file() || one_line_toml_name || !(json || s.contains(['\n', '='])) {
            SceneSource::Path(PathBuf::from(s))
        } else {
            SceneSource::Toml(s.to_string())
        }
    }

    /// Reads and validates the scene; errors name the file (or `scene text`, or `structure
    /// data`), the item and its line (data has none).
    pub fn load(&self) -> Result<Scene, IoError> {
        match self {
            SceneSource::Path(p) => Scene::from_path(p),
            SceneSource::Toml(text) if text.trim_start().starts_with('{') => {
                Scene::from_json_named(text, "scene text")
            }
            SceneSource::Toml(text) => Scene::from_str_named(text, "scene text"),
            SceneSource::Data(arrays) => Scene::from_arrays((**arrays).clone(), DATA_NAME),
        }
    }

    /// The string form (the path, or the text; `structure data` for data, whose serde form
    /// is the object of its arrays).
    pub fn as_str(&self) -> std::borrow::Cow<'_, str> {
        match self {
            SceneSource::Path(p) => p.to_string_lossy(),
            SceneSource::Toml(text) => text.as_str().into(),
            SceneSource::Data(_) => DATA_NAME.into(),
        }
    }
}

impl fmt::Display for SceneSource {
    /// The path, `scene text` or `structure data` (for messages).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneSource::Path(p) => write!(f, "{}", p.display()),
            SceneSource::Toml(_) => f.write_str("scene text"),
            SceneSource::Data(_) => f.write_str(DATA_NAME),
        }
    }
}

impl Serialize for SceneSource {
    /// The string (path or text), or the object of the data's arrays (module docs).
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            SceneSource::Data(arrays) => arrays.serialize(s),
            other => s.serialize_str(&other.as_str()),
        }
    }
}

impl<'de> Deserialize<'de> for SceneSource {
    /// A string is a path or TOML text ([`SceneSource::parse`]), an object the data.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(SourceVisitor)
    }
}

/// Reads a string or an object as a [`SceneSource`].
struct SourceVisitor;

impl<'de> Visitor<'de> for SourceVisitor {
    type Value = SceneSource;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a scene file's path, the scene's TOML text, or the scene as data (an object of its arrays)")
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<SceneSource, E> {
        Ok(SceneSource::parse(s))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<SceneSource, A::Error> {
        let arrays = SceneArrays::deserialize(de::value::MapAccessDeserializer::new(map))?;
        Ok(SceneSource::Data(Box::new(arrays)))
    }
}

/// The scene of a request whose `scene` is required.
pub(crate) fn required(scene: &Option<SceneSource>) -> Result<&SceneSource, InvalidParameter> {
    scene
        .as_ref()
        .ok_or_else(|| InvalidParameter::raw("scene", "(unset)", "must be given"))
}

/// Why a scene command gave no report.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// A value the request refuses.
    #[error(transparent)]
    InvalidParameter(#[from] InvalidParameter),
    /// The scene could not be read, or is invalid.
    #[error(transparent)]
    Io(#[from] IoError),
    /// The analysis failed.
    #[error(transparent)]
    Core(#[from] CoreError),
    /// A load path failed (or its model is not usable).
    #[error(transparent)]
    Path(#[from] tensegrity_path::PathError),
    /// A `strict` simulation whose invariants drifted past their limits.
    #[error("strict: {} warning(s): {}", warnings.len(), tensegrity_core::warning::joined(warnings))]
    Strict {
        /// The warnings of the run.
        warnings: Vec<tensegrity_core::Warning>,
    },
}

/// Refuses a scene that carries a key the dynamics does not read — a load path's drivers (a
/// rest-length change, a support displacement: `solve` only) or a support along directions
/// of any orientation or on a spring (`along`, `stiffness`: `solve` and `statics`) —, naming
/// the first and the command that would ignore it.
pub fn refuse_path_keys(
    scene: &tensegrity_io::scene::Scene,
    command: &str,
) -> Result<(), InvalidParameter> {
    refuse_driver_keys(scene, command)?;
    match scene.file.support_keys().first() {
        None => Ok(()),
        Some(key) => Err(InvalidParameter::text(
            "scene",
            key,
            format!("{key} is read by `solve`, `statics` and elastic `simulate` scenes only (a support of any orientation or on a spring); `{command}` would ignore it: remove it, or run `tensegrity solve` or `tensegrity statics`, or give the scene `[simulation] bars = \"elastic\"`"),
        )),
    }
}

/// Refuses a scene that carries a load path's driver (a rest-length change, a support
/// displacement), which `solve` reads (and `statics` a support's displacement,
/// [`refuse_rest_length_changes`]), naming the first and the command that would ignore it.
pub fn refuse_driver_keys(
    scene: &tensegrity_io::scene::Scene,
    command: &str,
) -> Result<(), InvalidParameter> {
    match scene.file.driver_keys().first() {
        None => Ok(()),
        Some(key) if key.ends_with(": displacement") => Err(InvalidParameter::text(
            "scene",
            key,
            format!("{key} is read by `solve` (a load path's driver) and `statics` (its linear response) only; `{command}` would ignore it: remove it, or run `tensegrity solve` or `tensegrity statics`"),
        )),
        Some(key) => Err(InvalidParameter::text(
            "scene",
            key,
            format!("{key} is read by `solve` only (a load path's driver); `{command}` would ignore it: remove it, or run `tensegrity solve`"),
        )),
    }
}

/// Refuses a scene that carries a rest-length change (a load path's driver, which only
/// `solve` reads), naming the first and the command that would ignore it: `statics`, which
/// reads a support's `displacement` (its linear response), refuses these.
pub fn refuse_rest_length_changes(
    scene: &tensegrity_io::scene::Scene,
    command: &str,
) -> Result<(), InvalidParameter> {
    match scene.file.rest_length_change_keys().first() {
        None => Ok(()),
        Some(key) => Err(InvalidParameter::text(
            "scene",
            key,
            format!("{key} is read by `solve` only (a load path's driver); `{command}` would ignore it: remove it, or run `tensegrity solve`"),
        )),
    }
}

impl Categorized for SceneError {
    /// An invalid value or an unreadable scene is bad input; the analysis's own error keeps
    /// its category; a `strict` run that drifted failed numerically.
    fn category(&self) -> Category {
        match self {
            SceneError::InvalidParameter(_) => Category::Input,
            SceneError::Io(e) => e.category(),
            SceneError::Core(CoreError::InvalidParameter { .. } | CoreError::TooLarge { .. }) => {
                Category::Input
            }
            SceneError::Core(CoreError::OverBudget(_)) => Category::Resource,
            SceneError::Core(CoreError::Interrupted { .. }) => Category::Interrupted,
            SceneError::Path(
                tensegrity_path::PathError::InvalidModel { .. }
                | tensegrity_path::PathError::InvalidSetting { .. },
            ) => Category::Input,
            SceneError::Core(_) | SceneError::Path(_) | SceneError::Strict { .. } => {
                Category::Numerical
            }
        }
    }
}
