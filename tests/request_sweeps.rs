//! Requests are data (issue 20): every field of the `toroid`, `tbar`, `roll` and `tbar_roll`
//! requests is a sweep axis of the study of the same name, with no per-field code in the
//! sweeps crate. Each field (enumerated from `R::params()`) is swept over two valid values
//! through the binary (`tensegrity sweep SPEC --out …`): two rows, the two (different) values
//! in the axis column, no error row.
//!
//! The two values come from the field's description: a switch `false`, `true`; a choice its
//! first two names; a count its default and the next; a number or an angle its default and
//! 1.1 × it (0.1 from 0); a list one and two elements. A field without a default, a text and a
//! value the physics refuses come from the request's small table of overrides. The rolling
//! requests run short (`t_end` fixed small, the rigid model, one tread count) so that a sweep
//! takes a fraction of a second (the four requests' every field: a few seconds).

use crate::common;

use serde_json::Value;
use tensegrity_core::request::{Kind, Param, Request};

/// What a request's sweeps need beyond the descriptions.
struct Table {
    /// Fixed values of every spec (the required fields), TOML text.
    base: &'static [(&'static str, &'static str)],
    /// A field and the base value it excludes (drop it from the base when sweeping the field).
    excludes: &'static [(&'static str, &'static str)],
    /// The two values of a field the generic rule cannot give, TOML text.
    overrides: &'static [(&'static str, [&'static str; 2])],
}

const TOROID: Table = Table {
    base: &[],
    excludes: &[],
    overrides: &[
        ("stabilize", ["\"spokes,inner\"", "\"inner,outer\""]),
        // a prestress design's rest lengths need a string stiff against its tension
        ("string_stiffness", ["1e4", "2e4"]),
    ],
};

const TBAR: Table = Table {
    base: &[
        ("beta", "\"pi/6\""),
        ("phi", "\"pi/8\""),
        ("cylindrical", "0.25"),
    ],
    excludes: &[("spherical", "cylindrical")],
    overrides: &[
        ("beta", ["\"pi/6\"", "\"pi/5\""]),
        ("phi", ["\"pi/8\"", "\"pi/6\""]),
        ("cylindrical", ["0.25", "0.3"]),
        ("spherical", ["\"pi/12\"", "\"pi/16\""]),
        ("extended", ["0.5", "1.0"]),
        ("prestress", ["4.0", "5.0"]),
        ("material", ["\"steel\"", "\"aluminium\""]),
    ],
};

const ROLL: Table = Table {
    base: &[("t_end", "0.05"), ("fidelity", "\"rigid\"")],
    excludes: &[],
    overrides: &[
        ("stabilize", ["\"spokes,inner\"", "\"inner,outer\""]),
        ("t_end", ["0.05", "0.06"]),
        ("ground_damping", ["100.0", "200.0"]),
        // unset by default (each model's own step)
        ("dt", ["0.0001", "0.0002"]),
    ],
};

const TBAR_ROLL: Table = Table {
    base: &[
        ("t_end", "0.05"),
        ("fidelity", "\"rigid\""),
        ("treads", "\"8\""),
    ],
    excludes: &[],
    overrides: &[
        ("beta", ["\"pi/6\"", "\"pi/5\""]),
        ("cylindrical", ["0.25", "0.3"]),
        ("spherical", ["\"pi/12\"", "\"pi/16\""]),
        ("extended", ["0.5", "1.0"]),
        ("t_end", ["0.05", "0.06"]),
        ("mu_kinetic", ["0.5", "0.6"]),
        ("rim_density", ["1.0", "2.0"]),
        ("min_tension", ["50.0", "60.0"]),
        ("ground_damping", ["100.0", "200.0"]),
        ("dt", ["0.0001", "0.0002"]),
    ],
};

/// A number in TOML (always with a decimal point or exponent, so it reads as a float).
fn float(x: f64) -> String {
    format!("{x:?}")
}

/// The two values of `p` from its description and default (TOML text).
fn two_values(p: &Param, default: &Value, table: &Table) -> [String; 2] {
    if let Some((_, v)) = table.overrides.iter().find(|(n, _)| *n == p.name) {
        return v.map(str::to_string);
    }
    match (p.kind, default) {
        (Kind::Flag, _) => ["false".into(), "true".into()],
        (Kind::Choice(c), _) => [format!("\"{}\"", c[0]), format!("\"{}\"", c[1])],
        (Kind::Count, Value::Number(n)) => {
            let d = n.as_u64().unwrap();
            [d.to_string(), (d + 1).to_string()]
        }
        (Kind::Number | Kind::Angle, Value::Number(n)) => {
            let d = n.as_f64().unwrap();
            let next = if d == 0.0 { 0.1 } else { 1.1 * d };
            [float(d), float(next)]
        }
        (Kind::Counts, _) => ["\"8\"".into(), "\"8,12\"".into()],
        (Kind::Numbers, _) => ["\"0.5\"".into(), "\"0.5,1.5\"".into()],
        (kind, d) => panic!("`{}` ({kind:?}, default {d}) needs an override", p.name),
    }
}

/// The axis column's text of a TOML value (a string's contents, a number as written).
fn axis_text(toml: &str) -> String {
    toml.trim_matches('"').to_string()
}

/// Sweeps every field of `R` over its two values; returns the fields swept.
fn sweep_every_field<R: Request>(table: &Table) -> Vec<&'static str> {
    let dir = common::scratch("request-sweeps", R::NAME);
    let defaults = R::defaults();
    let mut swept = Vec::new();
    for p in R::params() {
        let values = two_values(&p, &defaults[p.name], table);
        let dropped = table
            .excludes
            .iter()
            .find(|(n, _)| *n == p.name)
            .map(|e| e.1);
        let fixed: Vec<String> = table
            .base
            .iter()
            .filter(|(n, _)| *n != p.name && Some(*n) != dropped)
            .map(|(n, v)| format!("{n} = {v}\n"))
            .collect();
        let spec = format!(
            "study = \"{}\"\n[fixed]\n{}[axes]\n{} = [{}, {}]\n",
            R::NAME,
            fixed.concat(),
            p.name,
            values[0],
            values[1]
        );
        let (spec_path, out) = (dir.join(format!("{}.toml", p.name)), dir.join("out.csv"));
        std::fs::write(&spec_path, &spec).unwrap();
        let args = [
            "sweep",
            spec_path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        common::assert_ok(&common::run(&args));
        let mut reader = csv::Reader::from_path(&out).unwrap();
        let header = reader.headers().unwrap().clone();
        assert_eq!(&header[1], p.name, "{spec}");
        let status = header.iter().position(|h| h == "status").unwrap();
        let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 2, "{spec}");
        assert_ne!(rows[0][1], rows[1][1], "{spec}: the swept column differs");
        for (row, value) in rows.iter().zip(&values) {
            assert_eq!(row[1], axis_text(value), "{spec}");
            assert_eq!(&row[status], "ok", "{spec}: {:?}", &row[status + 1]);
        }
        swept.push(p.name);
    }
    swept
}

#[test]
fn every_field_of_the_toroid_request_is_a_sweep_axis() {
    let swept = sweep_every_field::<toroid::ToroidRequest>(&TOROID);
    assert_eq!(swept.len(), toroid::ToroidRequest::defaults().len());
    assert!(swept.contains(&"sides") && swept.contains(&"string_stiffness"));
}

#[test]
fn every_field_of_the_tbar_request_is_a_sweep_axis() {
    let swept = sweep_every_field::<tbar_wheel::TbarStaticRequest>(&TBAR);
    assert_eq!(swept.len(), tbar_wheel::TbarStaticRequest::defaults().len());
    assert!(swept.contains(&"rim") && swept.contains(&"spherical"));
}

#[test]
fn every_field_of_the_roll_request_is_a_sweep_axis() {
    let swept = sweep_every_field::<toroid::RollRequest>(&ROLL);
    assert_eq!(swept.len(), toroid::RollRequest::defaults().len());
    assert!(swept.contains(&"integrator") && swept.contains(&"restitution"));
}

#[test]
fn every_field_of_the_tbar_roll_request_is_a_sweep_axis() {
    use tbar_wheel::roll::TbarRollRequest;
    let swept = sweep_every_field::<TbarRollRequest>(&TBAR_ROLL);
    assert_eq!(swept.len(), TbarRollRequest::defaults().len());
    assert!(swept.contains(&"restitution") && swept.contains(&"rim_density"));
}
