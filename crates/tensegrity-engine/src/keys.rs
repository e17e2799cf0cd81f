//! One key convention for every report, added beside the keys the reports always had (no key
//! is renamed or removed: scripts read them). Every front end's JSON passes through
//! [`conventional`] (the registry's `run`, so the Python package and the sweeps, and the
//! CLI's `--json`); docs/OUTPUTS.md has the whole table of keys and units.
//!
//! The keys added, in every object of a report (nested ones included):
//!
//! | key | type | beside | rule |
//! |---|---|---|---|
//! | `node_count` | integer | `nodes`, `n_nodes` | `nodes` itself when it is a count, its length when it lists the nodes (Michell, formfind) |
//! | `bar_count`, `string_count` | integer | `bars`, `strings`, `n_bars`, `n_strings` | the count (as `nodes`) |
//! | `fidelity` | `"rigid"`/`"full"` | `model` | the rolling model, named as `roll` names it (`tbar roll` said `model`) |
//! | `yield_mass_kg`, `yield_buckling_mass_kg` | number (kg) | `mass_kg` | where `mass_kg` is an object of sizing criteria (`michell`), its members as numbers, named as `michell-table` names them |
//!
//! Elsewhere `mass_kg` is a number (kg), or `null` where no mass could be computed.

use serde_json::{Map, Value};

/// The fidelity names of the rolling model.
const FIDELITIES: [&str; 2] = ["rigid", "full"];

/// Adds the conventional keys to `report` (in place, recursively) and returns it.
///
/// ```
/// use serde_json::json;
/// let v = tensegrity_engine::keys::conventional(json!({
///     "model": "rigid", "nodes": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
///     "rows": [{"nodes": 24, "mass_kg": {"yield": 1.0, "yield_buckling": 2.0}}],
/// }));
/// assert_eq!(v["fidelity"], "rigid");
/// assert_eq!(v["node_count"], 2);
/// assert_eq!(v["rows"][0]["node_count"], 24);
/// assert_eq!(v["rows"][0]["yield_buckling_mass_kg"], 2.0);
/// assert_eq!(v["model"], "rigid"); // the old keys stay
/// // a member's end nodes are not a count
/// let m = tensegrity_engine::keys::conventional(json!({"nodes": [0, 1]}));
/// assert!(m.get("node_count").is_none());
/// ```
pub fn conventional(mut report: Value) -> Value {
    add(&mut report);
    report
}

fn add(v: &mut Value) {
    match v {
        Value::Object(map) => {
            for child in map.values_mut() {
                add(child);
            }
            add_keys(map);
        }
        Value::Array(items) => items.iter_mut().for_each(add),
        _ => {}
    }
}

/// The count of a `nodes`/`bars`/`strings` value: itself, or the length of its list of
/// positions or members (not a member's two end nodes, a list of numbers).
fn count(v: &Value) -> Option<Value> {
    match v {
        Value::Number(n) if n.is_u64() => Some(v.clone()),
        Value::Array(items) if items.iter().all(|x| x.is_array() || x.is_object()) => {
            Some(Value::from(items.len()))
        }
        _ => None,
    }
}

fn add_keys(map: &mut Map<String, Value>) {
    for (old, new) in [
        ("nodes", "node_count"),
        ("n_nodes", "node_count"),
        ("bars", "bar_count"),
        ("n_bars", "bar_count"),
        ("strings", "string_count"),
        ("n_strings", "string_count"),
    ] {
        if let Some(n) = map.get(old).and_then(count) {
            map.entry(new).or_insert(n);
        }
    }
    let model = map.get("model").and_then(Value::as_str);
    if let Some(m) = model.filter(|m| FIDELITIES.contains(m)) {
        let m = Value::from(m);
        map.entry("fidelity").or_insert(m);
    }
    let criteria = match map.get("mass_kg") {
        Some(Value::Object(m)) => m.clone(),
        _ => Map::new(),
    };
    for (key, new) in [
        ("yield", "yield_mass_kg"),
        ("yield_buckling", "yield_buckling_mass_kg"),
    ] {
        if let Some(x) = criteria.get(key).filter(|x| x.is_number()) {
            map.entry(new).or_insert(x.clone());
        }
    }
}
