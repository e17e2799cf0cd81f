//! JSON scenes: every example scene written as JSON reads back to the same structure and
//! tables; the published JSON Schema is the generated one, accepts every example and refuses
//! what the reader refuses (a small validator of the schema's keywords used here); bad JSON
//! is named.

use serde_json::Value;
use std::path::{Path, PathBuf};
use tensegrity_io::scene::{json_schema, Scene};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every scene file among the examples (the top level and the scene folders; the
/// `formfind_*` files are form-finding topologies).
fn example_scenes() -> Vec<PathBuf> {
    let mut out = Vec::new();
    for dir in [
        "examples",
        "examples/anchors",
        "examples/ctsfem",
        "examples/mjcf",
        "examples/robots",
    ] {
        for e in std::fs::read_dir(root().join(dir)).unwrap() {
            let p = e.unwrap().path();
            let topology = p
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("formfind"));
            if p.extension().is_some_and(|x| x == "toml") && !topology {
                out.push(p);
            }
        }
    }
    out.sort();
    assert!(out.len() > 30, "{}", out.len());
    out
}

#[test]
fn every_example_reads_back_from_its_json() {
    for path in example_scenes() {
        let scene = Scene::from_path(&path).unwrap();
        let json = scene.to_json();
        let back = Scene::from_json_named(&json, "back.json")
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(back.structure, scene.structure, "{}", path.display());
        assert_eq!(back.to_json(), json, "{}", path.display());
        assert_eq!(
            back.simulation().map(|s| s.settings).ok(),
            scene.simulation().map(|s| s.settings).ok(),
            "{}",
            path.display()
        );
    }
}

/// A validator of the keywords the generated schema uses: `$ref` into `$defs`, `type`
/// (one or a list), `properties` with `additionalProperties: false`, `required`, `items`,
/// `minItems`/`maxItems`, `enum`, `minimum`, `anyOf`/`oneOf`. Returns the first violation.
fn validate(schema: &Value, defs: &Value, v: &Value, at: &str) -> Result<(), String> {
    if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
        let name = r.trim_start_matches("#/$defs/");
        return validate(&defs[name], defs, v, at);
    }
    for key in ["anyOf", "oneOf"] {
        if let Some(options) = schema.get(key).and_then(Value::as_array) {
            let errors: Vec<String> = options
                .iter()
                .filter_map(|o| validate(o, defs, v, at).err())
                .collect();
            if errors.len() == options.len() {
                return Err(format!(
                    "{at}: matches none of {key}: {}",
                    errors.join(" | ")
                ));
            }
        }
    }
    if let Some(t) = schema.get("type") {
        let types: Vec<&str> = match t {
            Value::String(s) => vec![s.as_str()],
            Value::Array(a) => a.iter().filter_map(Value::as_str).collect(),
            _ => vec![],
        };
        let is = |ty: &str| match ty {
            "object" => v.is_object(),
            "array" => v.is_array(),
            "string" => v.is_string(),
            "boolean" => v.is_boolean(),
            "null" => v.is_null(),
            "integer" => v.is_i64() || v.is_u64(),
            "number" => v.is_number(),
            _ => false,
        };
        if !types.iter().any(|t| is(t)) {
            return Err(format!("{at}: {v} is not {types:?}"));
        }
    }
    if let Some(e) = schema.get("enum").and_then(Value::as_array) {
        if !e.contains(v) {
            return Err(format!("{at}: {v} is not one of {e:?}"));
        }
    }
    if let (Some(m), Some(x)) = (schema.get("minimum").and_then(Value::as_f64), v.as_f64()) {
        if x < m {
            return Err(format!("{at}: {x} < {m}"));
        }
    }
    if let Value::Object(map) = v {
        let props = schema.get("properties").and_then(Value::as_object);
        for r in schema
            .get("required")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            if !map.contains_key(r.as_str().unwrap_or_default()) {
                return Err(format!("{at}: missing {r}"));
            }
        }
        for (k, x) in map {
            match props.and_then(|p| p.get(k)) {
                Some(s) => validate(s, defs, x, &format!("{at}.{k}"))?,
                None if schema.get("additionalProperties") == Some(&Value::Bool(false)) => {
                    return Err(format!("{at}: unknown key {k}"))
                }
                None => match schema.get("additionalProperties") {
                    Some(s) if s.is_object() => validate(s, defs, x, &format!("{at}.{k}"))?,
                    _ => {}
                },
            }
        }
    }
    if let Value::Array(items) = v {
        let n = items.len() as u64;
        if schema
            .get("minItems")
            .and_then(Value::as_u64)
            .is_some_and(|m| n < m)
            || schema
                .get("maxItems")
                .and_then(Value::as_u64)
                .is_some_and(|m| n > m)
        {
            return Err(format!("{at}: {n} items"));
        }
        if let Some(s) = schema.get("items") {
            for (i, x) in items.iter().enumerate() {
                validate(s, defs, x, &format!("{at}[{i}]"))?;
            }
        }
    }
    Ok(())
}

#[test]
fn the_published_schema_is_generated_and_accepts_every_example() {
    let schema = json_schema();
    let published: Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("docs/schema/scene.schema.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(
        published, schema,
        "run: tensegrity export schema --out docs/schema/scene.schema.json"
    );
    let defs = &schema["$defs"];
    for path in example_scenes() {
        let v: Value = serde_json::from_str(&Scene::from_path(&path).unwrap().to_json()).unwrap();
        validate(&schema, defs, &v, "scene").unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
    // and refuses what the reader refuses: an unknown key, a string where a number goes,
    // a node with two coordinates, a bad integrator name
    let bad = [
        (
            r#"{"nodes": [[0,0,0]], "bars": [{"nodes": [0, 0], "color": 1}]}"#,
            "unknown key color",
        ),
        (
            r#"{"nodes": [[0,0,0]], "gravity": {"acceleration": [0, 0, "down"]}}"#,
            "scene.gravity",
        ),
        (r#"{"nodes": [[0,0]]}"#, "2 items"),
        (
            r#"{"nodes": [[0,0,0]], "simulation": {"t_end": 1, "integrator": "euler"}}"#,
            "not one of",
        ),
    ];
    for (text, expected) in bad {
        let v: Value = serde_json::from_str(text).unwrap();
        let e = validate(&schema, defs, &v, "scene").unwrap_err();
        assert!(e.contains(expected), "{text}: {e}");
        assert!(Scene::from_json_named(text, "bad.json").is_err(), "{text}");
    }
}

#[test]
fn bad_json_scenes_are_named() {
    let cases = [
        ("[1, 2]", "a scene is a JSON object"),
        (
            r#"{"nodes": [[0, 0, 0]], "bars": [{"nodes": [0, 1], "colour": 2}]}"#,
            "unknown field `colour`",
        ),
        (
            "{\"nodes\": [[0, 0, 0]],\n \"bars\": [}",
            "bad.json: line 2, column",
        ),
        (
            r#"{"nodes": [[0, 0, 0], [1, 0, 0]], "strings": [{"nodes": [0, 5]}]}"#,
            "string 0",
        ),
    ];
    for (text, expected) in cases {
        let e = Scene::from_json_named(text, "bad.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains(expected), "{text}: {e}");
    }
    // a null is an absent key
    let ok = r#"{"nodes": [[0, 0, 0], [1, 0, 0]], "bars": [{"nodes": [0, 1], "mass": null}], "gravity": null}"#;
    assert_eq!(
        Scene::from_json_named(ok, "null.json")
            .unwrap()
            .structure
            .n_bars(),
        1
    );
}
