//! TOML tables as plain values, both ways: what a front end that holds a scene's or a sweep
//! spec's tables as data (the Python package's dicts) needs to write them as TOML and to read
//! the top-level tables of a TOML text back, without knowing the format itself.

use serde_json::{Map, Value};

/// A table that cannot be written as TOML (a `null`, or a value TOML has no form for).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("not writable as TOML: {reason}")]
pub struct NotToml {
    /// The writer's reason.
    pub reason: String,
}

/// TOML text of a table of values (keys → scalars, arrays, tables).
///
/// ```
/// use serde_json::json;
/// let text = tensegrity_io::tables::to_toml(&json!({"simulation": {"t_end": 0.5}})).unwrap();
/// assert_eq!(text.trim(), "[simulation]\nt_end = 0.5");
/// assert!(tensegrity_io::tables::to_toml(&json!({"a": null})).is_err());
/// ```
pub fn to_toml(table: &Value) -> Result<String, NotToml> {
    let bad = |e: &dyn std::fmt::Display| NotToml {
        reason: e.to_string(),
    };
    let t = toml::Value::try_from(table).map_err(|e| bad(&e))?;
    toml::to_string(&t).map_err(|e| bad(&e))
}

/// The top-level tables and keys of a TOML text as values (empty when it does not read: the
/// caller reads the text for its errors first).
///
/// ```
/// let t = tensegrity_io::tables::read("[ground]\nheight = 0.0\n");
/// assert_eq!(t["ground"]["height"], 0.0);
/// assert!(tensegrity_io::tables::read("not = = toml").is_empty());
/// ```
pub fn read(text: &str) -> Map<String, Value> {
    let raw: toml::Table = toml::from_str(text).unwrap_or_default();
    raw.into_iter()
        .filter_map(|(k, v)| Some((k, serde_json::to_value(v).ok()?)))
        .collect()
}
