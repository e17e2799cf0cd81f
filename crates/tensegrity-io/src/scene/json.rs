//! JSON scenes: the scene file's description ([`SceneFile`]) read from and written as JSON of
//! the same shape as the TOML (`nodes`, `bars: [{"nodes": [0, 4], "mass": 1.0}]`,
//! `simulation: {"t_end": 1.0}`, …), and its JSON Schema ([`json_schema`]), derived from
//! the same serde description (its descriptions are the fields' documentation), so the two
//! formats and the schema cannot disagree.
//!
//! A JSON scene is read by turning its value into the TOML value of the same tables and
//! reading that as a scene file is read, so every check applies; an error names the item
//! (`bar 2: …`) but no line (the lines would be those of the intermediate TOML). A `null`
//! stands for an absent key.

use super::{Scene, SceneFile};
use crate::error::{IoError, Result};

/// The JSON Schema (draft 2020-12) of a scene, generated from [`SceneFile`].
///
/// ```
/// let schema = tensegrity_io::scene::json_schema();
/// assert_eq!(schema["title"], "SceneFile");
/// assert!(schema["properties"]["bars"].is_object());
/// assert_eq!(schema["required"][0], "nodes");
/// ```
pub fn json_schema() -> serde_json::Value {
    let schema = schemars::schema_for!(SceneFile);
    serde_json::to_value(&schema).unwrap_or_default()
}

/// Drops every `null` (an absent key) from objects, recursively.
fn without_nulls(v: serde_json::Value) -> serde_json::Value {
    use serde_json::Value;
    match v {
        Value::Object(map) => Value::Object(
            map.into_iter()
                .filter(|(_, x)| !x.is_null())
                .map(|(k, x)| (k, without_nulls(x)))
                .collect(),
        ),
        Value::Array(items) => Value::Array(items.into_iter().map(without_nulls).collect()),
        other => other,
    }
}

impl Scene {
    /// Parses and validates a JSON scene (module docs); `name` labels error messages.
    ///
    /// ```
    /// use tensegrity_io::scene::Scene;
    /// let text = r#"{"nodes": [[0, 0, 0], [2, 0, 0]], "bars": [{"nodes": [0, 1], "mass": 1.0}]}"#;
    /// let scene = Scene::from_json_named(text, "bar.json")?;
    /// assert_eq!(scene.structure.n_bars(), 1);
    /// let bad = r#"{"nodes": [[0, 0, 0], [2, 0, 0]], "bars": [{"nodes": [0, 7]}]}"#;
    /// let e = Scene::from_json_named(bad, "bad.json").unwrap_err().to_string();
    /// assert!(e.contains("bad.json") && e.contains("bar 0"), "{e}");
    /// # Ok::<(), tensegrity_io::IoError>(())
    /// ```
    pub fn from_json_named(text: &str, name: &str) -> Result<Scene> {
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| IoError::Parse {
            file: name.to_string(),
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
        let invalid = |message: String| IoError::InvalidJsonScene {
            file: name.to_string(),
            message,
        };
        if !value.is_object() {
            return Err(invalid(
                "a scene is a JSON object (`nodes`, `bars`, `strings`, …)".into(),
            ));
        }
        let table = toml::Value::try_from(without_nulls(value))
            .map_err(|e| invalid(format!("not a scene value: {e}")))?;
        let file: SceneFile =
            SceneFile::deserialize_from(table).map_err(|e| invalid(e.message().to_string()))?;
        let structure = file.validate(None, name)?;
        Ok(Scene { structure, file })
    }

    /// The scene as JSON of the same shape as its file (absent keys left out): what
    /// [`Scene::from_json_named`] reads back to the same scene.
    ///
    /// ```
    /// use tensegrity_io::scene::Scene;
    /// let scene = Scene::from_path("../../examples/prism.toml".as_ref())?;
    /// let back = Scene::from_json_named(&scene.to_json(), "prism.json")?;
    /// assert_eq!(back.structure, scene.structure);
    /// # Ok::<(), tensegrity_io::IoError>(())
    /// ```
    pub fn to_json(&self) -> String {
        let mut value = without_nulls(serde_json::to_value(&self.file).unwrap_or_default());
        // the tables a scene does not have (an empty list of them reads back the same)
        if let serde_json::Value::Object(map) = &mut value {
            map.retain(|_, v| !matches!(v, serde_json::Value::Array(a) if a.is_empty()));
            map.retain(|_, v| !matches!(v, serde_json::Value::Object(o) if o.is_empty()));
        }
        serde_json::to_string_pretty(&value).unwrap_or_default() + "\n"
    }
}

impl SceneFile {
    /// The scene file of a TOML value (the tables of a JSON scene).
    fn deserialize_from(table: toml::Value) -> std::result::Result<SceneFile, toml::de::Error> {
        // through the text: the reader's spans and custom readers see what a file gives them
        let text = toml::to_string(&table).unwrap_or_default();
        toml::from_str(&text)
    }
}
