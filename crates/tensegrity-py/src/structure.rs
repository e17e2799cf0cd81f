//! The structure model between Python and the core: a `Structure` crosses as data — a dict
//! of its arrays (`Structure._arrays()`: the keys of [`SceneArrays`], with the scene's
//! `simulation`, `ground` and `actuation` tables) — validated by the io crate exactly as a
//! scene file is ([`Scene::from_arrays`]: the core's builder, the checks of the dynamics
//! tables; errors name the item); the connectivity and equilibrium matrices of the core from
//! the same data; the structures of the topology crates (toroid, Michell truss, T-bar, form
//! finding) as data. Scene TOML appears only as the explicit export and import
//! (`Structure.to_toml`, `Structure.from_toml`: the io crate's writer and reader).

use crate::errors::Failure;
use serde::Deserialize;
use tensegrity_core::connectivity::Connectivity;
use tensegrity_core::request::{Categorized, Category, Request};
use tensegrity_engine::value::{json, to_value, Map, Value};
use tensegrity_io::scene::{Scene, SceneArrays};
use tensegrity_statics::{equilibrium_matrix, DofMap};

/// The tables of a scene that are not the structure's: kept as given, written after it.
pub const TABLES: &[&str] = &["simulation", "ground", "actuation", "actuators"];

/// What the errors of a structure's data are labelled with.
const NAME: &str = "structure";

fn io_failure(e: &tensegrity_io::IoError) -> Failure {
    Failure::new(e.category(), e.to_string())
}

/// The validated scene of a structure's data (errors name the item, or the key of a value
/// that does not read).
pub fn scene(data: &Map<String, Value>) -> Result<Scene, Failure> {
    let arrays = SceneArrays::deserialize(Value::Object(data.clone()))
        .map_err(|e| Failure::new(Category::Input, format!("{NAME}: {e}")))?;
    Scene::from_arrays(arrays, NAME).map_err(|e| io_failure(&e))
}

/// The data of a scene as the engine gives it back (the columns of its structure, the
/// materials its members name, its tables in full): what two equal structures share.
pub fn canonical(data: &Map<String, Value>) -> Result<Value, Failure> {
    let scene = scene(data)?;
    as_value(&SceneArrays::of(&scene))
}

fn as_value(arrays: &SceneArrays) -> Result<Value, Failure> {
    to_value(arrays).map_err(|e| Failure::new(Category::Input, format!("{NAME}: {e}")))
}

/// Scene TOML of a structure's data (the explicit export): the io crate's writer, then the
/// tables as given.
pub fn scene_text(data: &Map<String, Value>) -> Result<String, Failure> {
    let scene = scene(data)?;
    let mut text = tensegrity_io::scene::scene_to_toml(&scene);
    let tables: Map<String, Value> = TABLES
        .iter()
        .filter_map(|t| Some((t.to_string(), data.get(*t)?.clone())))
        .collect();
    let extra = toml_text(&Value::Object(tables))?;
    if !extra.trim().is_empty() {
        text.push('\n');
        text.push_str(&extra);
    }
    Ok(text)
}

/// TOML text of a JSON object (a dict of Python scalars, lists and dicts): a sweep spec or
/// the tables of a scene.
pub fn toml_text(value: &Value) -> Result<String, Failure> {
    tensegrity_io::tables::to_toml(value).map_err(|e| Failure::new(Category::Input, e.to_string()))
}

/// The data of scene TOML (the import): the columns of its structure and its other tables
/// as written.
pub fn read(text: &str, name: &str) -> Result<Value, Failure> {
    // JSON of the same shape when the file's name ends in `.json` or the text is an object
    let json = name.to_ascii_lowercase().ends_with(".json") || text.trim_start().starts_with('{');
    let scene = if json {
        Scene::from_json_named(text, name)
    } else {
        Scene::from_str_named(text, name)
    }
    .map_err(|e| io_failure(&e))?;
    let mut data = as_value(&SceneArrays::with_file_keys(&scene))?;
    let raw = tensegrity_io::tables::read(text);
    if let Value::Object(m) = &mut data {
        for t in TABLES {
            if let Some(v) = raw.get(*t) {
                m.insert(t.to_string(), v.clone());
            }
        }
    }
    Ok(data)
}

/// A dense matrix as JSON: `{"shape": [r, c], "data": row-major}`.
fn dense(m: &nalgebra::DMatrix<f64>) -> Value {
    let data: Vec<f64> = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect();
    json!({"shape": [m.nrows(), m.ncols()], "data": data})
}

/// The connectivity matrices C_b, C_s (members × nodes; −1 at the first node, +1 at the
/// second), the clusters' segment connectivity C_c (their segments in order, cluster after
/// cluster) and clustering matrix S (clusters × segments: 1 where a segment belongs to a
/// cluster; CTSFEM's S), and the equilibrium matrix A (free degrees of freedom × columns:
/// bars, strings, then one per cluster, `tensegrity_statics::cluster_columns`; node-major
/// rows, supported directions removed) with its free degrees of freedom `(node,
/// direction)`, of a structure's data.
pub fn matrices(data: &Map<String, Value>) -> Result<Value, Failure> {
    let scene = scene(data)?;
    let s = &scene.structure;
    let c = Connectivity::of(s);
    let dofs = DofMap::of(s);
    let segments: Vec<(usize, [usize; 2])> = s
        .clusters()
        .iter()
        .enumerate()
        .flat_map(|(k, cl)| cl.segments().map(move |seg| (k, seg)))
        .collect();
    let mut c_c = nalgebra::DMatrix::zeros(segments.len(), s.n_nodes());
    let mut clustering = nalgebra::DMatrix::zeros(s.clusters().len(), segments.len());
    for (i, (k, [a, b])) in segments.iter().enumerate() {
        c_c[(i, *a)] = -1.0;
        c_c[(i, *b)] = 1.0;
        clustering[(*k, i)] = 1.0;
    }
    Ok(json!({
        "C_b": dense(&c.C_b()),
        "C_s": dense(&c.C_s()),
        "C_c": dense(&c_c),
        "S": dense(&clustering),
        "A": dense(&equilibrium_matrix(s, &dofs)),
        "free_dofs": dofs.free,
    }))
}

/// The structure of MOTES's or TsgFEM's matrices given as lists (`N`, `C_b`, `C_s`,
/// `bar_mass`, `stiffness`, `rest_length`, `pinned`): [`tensegrity_io::matrices`].
fn matrices_structure(values: &Map<String, Value>) -> Result<tensegrity_core::Structure, Failure> {
    fn field<T: serde::de::DeserializeOwned>(
        values: &Map<String, Value>,
        key: &str,
    ) -> Result<Option<T>, Failure> {
        match values.get(key) {
            None | Some(Value::Null) => Ok(None),
            Some(v) => tensegrity_engine::value::from_value(v.clone())
                .map(Some)
                .map_err(|e| Failure::new(Category::Input, format!("{key}: {e}"))),
        }
    }
    let rows = |key: &str| -> Result<Vec<Vec<f64>>, Failure> {
        Ok(field::<Vec<Vec<f64>>>(values, key)?.unwrap_or_default())
    };
    let options = tensegrity_io::matrices::MatrixOptions {
        bar_masses: field(values, "bar_mass")?,
        string_stiffness: field(values, "stiffness")?,
        string_rest_lengths: field(values, "rest_length")?,
        pinned: field(values, "pinned")?.unwrap_or_default(),
    };
    tensegrity_io::matrices::structure_from_rows(
        &rows("N")?,
        &rows("C_b")?,
        &rows("C_s")?,
        &options,
    )
    .map_err(|e| Failure::new(Category::Input, e.to_string()))
}

/// The structure of a topology crate as data (its columns): `toroid` (the `toroid` request,
/// with stiff prestressed strings when it gives `string_stiffness`, as `--export-scene`
/// writes it), `michell` (the truss of the `michell` request: members as bars, extra strings as
/// strings, the last level pinned), `tbar` (the tread or wheel of the `tbar` request),
/// `formfind` (the prestressed structure of the `formfind` request, as its `--out` writes it).
pub fn topology(kind: &str, values: Map<String, Value>) -> Result<Value, Failure> {
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
                let why = tensegrity_core::warning::joined(&found.report.warnings);
                Failure::new(
                    Category::Numerical,
                    format!("the form has no prestressed structure: {why}"),
                )
            })?
        }
        "matrices" => matrices_structure(&values)?,
        other => {
            return Err(Failure::new(
                Category::Input,
                format!("no topology `{other}` (known: toroid, michell, tbar, formfind, matrices)"),
            ))
        }
    };
    as_value(&SceneArrays::from_structure(&structure))
}
