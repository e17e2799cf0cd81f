//! The texts of `tensegrity export` that a front end other than the command line writes: the
//! JSON Schema of scene files as the CLI prints it (pretty JSON and a final line break).

/// The JSON Schema of scene files ([`tensegrity_io::scene::json_schema`]) as `tensegrity
/// export schema` writes it.
///
/// ```
/// let text = tensegrity_engine::exports::schema_text().unwrap();
/// assert!(text.starts_with('{') && text.ends_with("}\n"));
/// ```
pub fn schema_text() -> Result<String, serde_json::Error> {
    Ok(serde_json::to_string_pretty(&tensegrity_io::scene::json_schema())? + "\n")
}
