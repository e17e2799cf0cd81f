//! The scene of the scene commands (`statics`, `simulate`): a TOML scene file, or the TOML
//! text itself ([`SceneSource`]), read by [`tensegrity_io::scene`]; and [`SceneError`], what
//! a scene command fails with.
//!
//! A scene travels as one string (a flag, a sweep value, a Python argument). The rule: a
//! string holding a line break or an `=` is TOML text (no scene file is named that way, and
//! every scene has at least one `key = value` line); any other string is a path, relative to
//! the working directory.
//!
//! ```
//! use tensegrity_engine::scene::SceneSource;
//! let file = SceneSource::parse("examples/prism.toml");
//! assert_eq!(file, SceneSource::Path("examples/prism.toml".into()));
//! let text = SceneSource::parse("nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 1]\n");
//! assert!(matches!(text, SceneSource::Toml(_)));
//! let scene = text.load().unwrap();
//! assert_eq!(scene.structure.n_bars(), 1);
//! // the serde form is the string itself
//! assert_eq!(serde_json::to_value(&file).unwrap(), serde_json::json!("examples/prism.toml"));
//! ```

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::path::PathBuf;
use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;
use tensegrity_io::scene::Scene;
use tensegrity_io::IoError;

/// Where a scene comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SceneSource {
    /// A TOML scene file.
    Path(PathBuf),
    /// The TOML text of a scene.
    Toml(String),
}

impl SceneSource {
    /// The source a string names (module docs: text with a line break or `=` is TOML).
    pub fn parse(s: &str) -> Self {
        if s.contains(['\n', '=']) {
            SceneSource::Toml(s.to_string())
        } else {
            SceneSource::Path(PathBuf::from(s))
        }
    }

    /// Reads and validates the scene; errors name the file (or `scene text`), the item and
    /// its line.
    pub fn load(&self) -> Result<Scene, IoError> {
        match self {
            SceneSource::Path(p) => Scene::from_path(p),
            SceneSource::Toml(text) => Scene::from_str_named(text, "scene text"),
        }
    }

    /// The string form (the path, or the text).
    pub fn as_str(&self) -> std::borrow::Cow<'_, str> {
        match self {
            SceneSource::Path(p) => p.to_string_lossy(),
            SceneSource::Toml(text) => text.as_str().into(),
        }
    }
}

impl fmt::Display for SceneSource {
    /// The path, or `scene text` (for messages).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneSource::Path(p) => write!(f, "{}", p.display()),
            SceneSource::Toml(_) => f.write_str("scene text"),
        }
    }
}

impl Serialize for SceneSource {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.as_str())
    }
}

impl<'de> Deserialize<'de> for SceneSource {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        Ok(SceneSource::parse(&s))
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
    /// A `strict` simulation whose invariants drifted past their limits.
    #[error("strict: {} warning(s): {}", warnings.len(), warnings.join("; "))]
    Strict {
        /// The warnings of the run.
        warnings: Vec<String>,
    },
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
            SceneError::Core(_) | SceneError::Strict { .. } => Category::Numerical,
        }
    }
}
