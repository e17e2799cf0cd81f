//! The structure model between Python and the core: a `Structure` spec (a dict of plain
//! lists, from the numpy arrays of `tensegrity.Structure`) built through the core's
//! validating builder and written as scene TOML by the io crate's writer
//! ([`tensegrity_io::scene::to_toml`]); scene TOML read back by the io crate's reader into the
//! same spec; the connectivity and equilibrium matrices of the core; the structures of the
//! topology crates (toroid, Michell truss, T-bar) as scene TOML.

use crate::errors::Failure;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tensegrity_core::connectivity::Connectivity;
use tensegrity_core::request::{Categorized, Category, Request};
use tensegrity_core::{Bar, Material, StringMember, Structure, Support};
use tensegrity_engine::value::{json, Map, Value};
use tensegrity_io::scene::Scene;
use tensegrity_statics::{equilibrium_matrix, DofMap};

/// The tables of a scene that are not the structure's: kept as given, written after it.
pub const TABLES: &[&str] = &["simulation", "ground", "actuation"];

fn item<'py, T: FromPyObjectOwned<'py>>(
    spec: &Bound<'py, PyDict>,
    key: &str,
) -> PyResult<Option<T>> {
    match spec.get_item(key)? {
        Some(v) if !v.is_none() => Ok(Some(v.extract::<T>().map_err(Into::into)?)),
        _ => Ok(None),
    }
}

/// A member's two node indices, negative ones refused as out of range (the core's message).
fn ends(nodes: (i64, i64), what: &str, k: usize, n_nodes: usize) -> Result<[usize; 2], Failure> {
    let one = |i: i64| {
        usize::try_from(i).map_err(|_| {
            Failure::new(
                Category::Input,
                format!("{what} {k}: node index {i} is out of range (the structure has {n_nodes} nodes, 0-based)"),
            )
        })
    };
    Ok([one(nodes.0)?, one(nodes.1)?])
}

type BarRow = ((i64, i64), Option<f64>, Option<String>, Option<f64>);
type StringRow = ((i64, i64), Option<f64>, Option<f64>, f64, Option<String>);

/// The core structure of a spec: `nodes` (n × 3), `velocities`, `materials` ({name:
/// (density, E, yield)}), `bars` ([(i, j), mass, material, radius]), `strings` ([(i, j),
/// stiffness, rest length, damping, material]), `supports` ([node, (fx, fy, fz)]), `loads`
/// ([node, force]), `gravity`; validated by the core's builder (errors name the item).
pub fn build(spec: &Bound<'_, PyDict>) -> PyResult<Result<Structure, Failure>> {
    let nodes: Vec<[f64; 3]> = item(spec, "nodes")?.unwrap_or_default();
    let n = nodes.len();
    let mut b = Structure::builder().nodes(nodes);
    if let Some(v) = item::<Vec<[f64; 3]>>(spec, "velocities")? {
        b = b.velocities(v);
    }
    let materials: Vec<(String, (f64, f64, f64))> = item(spec, "materials")?.unwrap_or_default();
    for (name, (rho, e, y)) in materials {
        b = b.material(&name, Material::new(rho, e, y));
    }
    let bars: Vec<BarRow> = item(spec, "bars")?.unwrap_or_default();
    for (k, (pair, mass, material, radius)) in bars.into_iter().enumerate() {
        let nodes = match ends(pair, "bar", k, n) {
            Ok(e) => e,
            Err(f) => return Ok(Err(f)),
        };
        b = b.bar(Bar {
            nodes,
            mass,
            material,
            radius,
        });
    }
    let strings: Vec<StringRow> = item(spec, "strings")?.unwrap_or_default();
    for (k, (pair, stiffness, rest_length, damping, material)) in strings.into_iter().enumerate() {
        let nodes = match ends(pair, "string", k, n) {
            Ok(e) => e,
            Err(f) => return Ok(Err(f)),
        };
        b = b.string(StringMember {
            nodes,
            stiffness,
            rest_length,
            damping,
            material,
        });
    }
    let supports: Vec<(i64, [bool; 3])> = item(spec, "supports")?.unwrap_or_default();
    for (k, (node, fixed)) in supports.into_iter().enumerate() {
        let Ok(node) = usize::try_from(node) else {
            return Ok(Err(Failure::new(
                Category::Input,
                format!("support {k}: node index {node} is out of range (the structure has {n} nodes, 0-based)"),
            )));
        };
        b = b.support(Support::directions(node, fixed));
    }
    let loads: Vec<(i64, [f64; 3])> = item(spec, "loads")?.unwrap_or_default();
    for (k, (node, force)) in loads.into_iter().enumerate() {
        let Ok(node) = usize::try_from(node) else {
            return Ok(Err(Failure::new(
                Category::Input,
                format!("load {k}: node index {node} is out of range (the structure has {n} nodes, 0-based)"),
            )));
        };
        b = b.load(node, force);
    }
    if let Some(g) = item::<[f64; 3]>(spec, "gravity")? {
        b = b.gravity(g);
    }
    Ok(b.build()
        .map_err(|e| Failure::new(e.category(), e.to_string())))
}

/// Scene TOML of a structure and its other tables (`tables`: JSON of `[simulation]`,
/// `[ground]`, `[[actuation]]`), read back once so that the tables are checked as a scene
/// file's are.
pub fn scene_text(structure: &Structure, tables: &Map<String, Value>) -> Result<String, Failure> {
    let mut text = tensegrity_io::scene::to_toml(structure);
    let extra = toml_text(&Value::Object(tables.clone()))?;
    if !extra.trim().is_empty() {
        text.push('\n');
        text.push_str(&extra);
    }
    Scene::from_str_named(&text, "structure")
        .map_err(|e| Failure::new(e.category(), e.to_string()))?;
    Ok(text)
}

/// TOML text of a JSON object (a dict of Python scalars, lists and dicts): a sweep spec or
/// the tables of a scene.
pub fn toml_text(value: &Value) -> Result<String, Failure> {
    tensegrity_io::tables::to_toml(value).map_err(|e| Failure::new(Category::Input, e.to_string()))
}

/// The spec of a scene (as [`build`] takes it, in JSON) and its other tables.
pub fn read(text: &str, name: &str) -> Result<Value, Failure> {
    let scene =
        Scene::from_str_named(text, name).map_err(|e| Failure::new(e.category(), e.to_string()))?;
    let s = &scene.structure;
    let v3 = |v: &nalgebra::Vector3<f64>| json!([v.x, v.y, v.z]);
    let raw = tensegrity_io::tables::read(text);
    let materials: Map<String, Value> = raw
        .get("materials")
        .and_then(Value::as_object)
        .into_iter()
        .flat_map(|t| t.keys())
        .filter_map(|k| {
            let m = s.materials().get(k)?;
            Some((
                k.clone(),
                json!([m.density, m.youngs_modulus, m.yield_strength]),
            ))
        })
        .collect();
    let tables: Map<String, Value> = TABLES
        .iter()
        .filter_map(|t| {
            let v = raw.get(*t)?.clone();
            Some((t.to_string(), v))
        })
        .collect();
    Ok(json!({
        "nodes": s.nodes().iter().map(v3).collect::<Vec<_>>(),
        "velocities": s.velocities().map(|v| v.iter().map(v3).collect::<Vec<_>>()),
        "materials": materials,
        "bars": s.bars().iter().map(|b| json!([b.nodes, b.mass, b.material, b.radius])).collect::<Vec<_>>(),
        "strings": s.strings().iter().map(|x| json!([x.nodes, x.stiffness, x.rest_length, x.damping, x.material])).collect::<Vec<_>>(),
        "supports": s.supports().iter().map(|x| json!([x.node, x.fixed])).collect::<Vec<_>>(),
        "loads": s.loads().iter().map(|l| json!([l.node, v3(&l.force)])).collect::<Vec<_>>(),
        "gravity": s.gravity().map(|g| v3(&g)),
        "tables": tables,
    }))
}

/// A dense matrix as JSON: `{"shape": [r, c], "data": row-major}`.
fn dense(m: &nalgebra::DMatrix<f64>) -> Value {
    let data: Vec<f64> = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect();
    json!({"shape": [m.nrows(), m.ncols()], "data": data})
}

/// The connectivity matrices C_b, C_s (members × nodes; −1 at the first node, +1 at the
/// second) and the equilibrium matrix A (free degrees of freedom × members, node-major rows,
/// supported directions removed) with its free degrees of freedom `(node, direction)`.
pub fn matrices(text: &str) -> Result<Value, Failure> {
    let scene = Scene::from_str_named(text, "structure")
        .map_err(|e| Failure::new(e.category(), e.to_string()))?;
    let s = &scene.structure;
    let c = Connectivity::of(s);
    let dofs = DofMap::of(s);
    Ok(json!({
        "C_b": dense(&c.C_b()),
        "C_s": dense(&c.C_s()),
        "A": dense(&equilibrium_matrix(s, &dofs)),
        "free_dofs": dofs.free,
    }))
}

/// The structure of a topology crate as scene TOML: `toroid` (the `toroid` request, with
/// stiff prestressed strings when it gives `string_stiffness`, as `--export-scene` writes
/// it), `michell` (the truss of the `michell` request: members as bars, extra strings as
/// strings, the last level pinned), `tbar` (the tread or wheel of the `tbar` request),
/// `formfind` (the prestressed structure of the `formfind` request, as its `--out` writes it).
pub fn topology(kind: &str, values: Map<String, Value>) -> Result<String, Failure> {
    let failed = |e: &dyn std::fmt::Display, c: Category| Failure::new(c, e.to_string());
    let structure = match kind {
        "toroid" => {
            let r = toroid::ToroidRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
            toroid::toroid_report(&r)
                .map_err(|e| failed(&e, e.category()))?
                .structure
        }
        "michell" => {
            let r =
                michell3d::MichellRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
            let run = r.run().map_err(|e| failed(&e, e.category()))?;
            let truss = &run.analysis.truss;
            let built = match run.request.extra_strings {
                Some(_) => michell3d::extra_strings::ExtraStrings::new(truss)
                    .and_then(|x| x.to_structure(truss)),
                None => truss.structure(),
            };
            built.map_err(|e| failed(&e, e.category()))?
        }
        "tbar" => {
            let r = tbar_wheel::TbarStaticRequest::from_values(values)
                .map_err(|e| Failure::invalid(&e))?;
            tbar_wheel::TbarGeometry::new(r.request().params)
                .and_then(|g| g.structure())
                .map_err(|e| failed(&e, e.category()))?
        }
        "formfind" => {
            let r = tensegrity_engine::formfind::FormfindRequest::from_values(values)
                .map_err(|e| Failure::invalid(&e))?;
            let found = r.run().map_err(|e| failed(&e, e.category()))?;
            found.structure.ok_or_else(|| {
                let why = found.report.warnings.join("; ");
                Failure::new(
                    Category::Numerical,
                    format!("the form has no prestressed structure: {why}"),
                )
            })?
        }
        other => {
            return Err(Failure::new(
                Category::Input,
                format!("no topology `{other}` (known: toroid, michell, tbar, formfind)"),
            ))
        }
    };
    Ok(tensegrity_io::scene::to_toml(&structure))
}
