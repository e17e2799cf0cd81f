//! The CSV layout of a sweep (the CLI contract of `tensegrity sweep`).
//!
//! Columns: `case` (0-based id in the full product order), one column per axis named as in
//! the spec (the values as the spec writes them), the result columns named by the
//! single-point report's JSON keys (nested keys joined with `.`; scalars only: arrays are
//! left out), then `status` (`ok` or `error`) and `message` (empty for `ok`). Every name
//! appears once: a result key that is also an axis (e.g. `sides`, `t_end`, `integrator` of
//! `roll`, which the report echoes) is left out of the result columns — the axis column holds
//! that value, as the spec writes it — and so is a result key named like the table's own
//! columns ([`RESERVED`]) or repeated in `[output] columns` (kept at its first place); a
//! `[fixed]` value has no column of its own and stays in the result columns. Numbers in result columns are written in Rust's shortest
//! round-trip form (`{}` of f64: parsing the text gives back the same f64), integers as
//! integers, booleans as `true`/`false`, JSON `null` (a missing optional, or a NaN) as an
//! empty field; an error row leaves every result column empty.
//!
//! Optionally a leading comment line `# units: …` gives one unit per column (`-` for none).
//! The file of one shard of a sharded sweep (`shard` K/N with N > 1) starts with a line
//! `# spec: <16 hex digits>`, the [`spec_hash`] of its spec, which `merge` compares across
//! the shards (and leaves out of the merged file, which is byte for byte the single run's).
//! Every row is one line (`\n`-terminated, quoted where the CSV rules need it, messages on
//! one line), so a file cut anywhere is its complete rows plus at most one partial line.

use crate::spec::Spec;
pub use crate::spec::RESERVED;

/// The header row's fields.
pub fn header(spec: &Spec) -> Vec<String> {
    let mut h = vec!["case".to_string()];
    h.extend(spec.axes.iter().map(|a| a.name.clone()));
    h.extend(spec.columns.iter().map(|c| c.name.to_string()));
    h.push("status".into());
    h.push("message".into());
    h
}

/// The `# units: …` line's fields, aligned with [`header`].
pub fn units(spec: &Spec) -> Vec<String> {
    let unit = |u: &str| {
        if u.is_empty() {
            "-".to_string()
        } else {
            u.to_string()
        }
    };
    let mut h = vec!["-".to_string()];
    h.extend(
        spec.axes
            .iter()
            .map(|a| unit(spec.study.param(&a.name).map_or("", |p| p.unit))),
    );
    h.extend(spec.columns.iter().map(|c| unit(c.unit)));
    h.push("-".into());
    h.push("-".into());
    h
}

/// The bytes before the first row: the optional units line and the header.
pub fn preamble(spec: &Spec, with_units: bool) -> Vec<u8> {
    let mut out = Vec::new();
    if with_units {
        let mut line = b"# units: ".to_vec();
        line.extend(record(&units(spec)));
        out.extend(line);
    }
    out.extend(record(&header(spec)));
    out
}

/// The start of the last line of an interrupted sweep's file.
pub const INCOMPLETE: &str = "# incomplete:";

/// The start of the spec-hash line of a shard's file.
pub const SPEC_LINE: &str = "# spec: ";

/// A 64-bit FNV-1a hash of what the spec asks for: its study, fixed values, axes (values and
/// texts), derived rules and columns (not its formatting or comments). Two specs with the
/// same hash give the same rows.
pub fn spec_hash(spec: &Spec) -> u64 {
    use std::fmt::Write;
    let mut text = format!("study={}\n", spec.study.name);
    for (k, v) in &spec.fixed {
        let _ = writeln!(text, "fixed {k}={v}");
    }
    for a in &spec.axes {
        let _ = write!(text, "axis {}", a.name);
        for v in &a.values {
            let _ = write!(text, "\x1f{}\x1e{}", v.value, v.text);
        }
        text.push('\n');
    }
    for (k, e) in &spec.derived {
        let _ = writeln!(text, "derived {k}={e:?}");
    }
    for c in &spec.columns {
        let _ = writeln!(text, "column {}", c.name);
    }
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The `# spec: …` line of a shard's file.
pub fn spec_line(spec: &Spec) -> Vec<u8> {
    format!("{SPEC_LINE}{:016x}\n", spec_hash(spec)).into_bytes()
}

/// One CSV record, `\n`-terminated, fields quoted only where needed.
pub fn record<S: AsRef<[u8]>>(fields: &[S]) -> Vec<u8> {
    let mut w = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .from_writer(Vec::new());
    // writing to a Vec cannot fail
    let _ = w.write_record(fields);
    w.into_inner().unwrap_or_default()
}

/// A JSON scalar as a CSV field (see the module docs); `None` for arrays and objects.
pub fn scalar(v: &serde_json::Value) -> Option<String> {
    use serde_json::Value as J;
    Some(match v {
        J::Null => String::new(),
        J::Bool(b) => b.to_string(),
        J::Number(n) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
            (Some(u), _, _) => u.to_string(),
            (None, Some(i), _) => i.to_string(),
            (None, None, Some(x)) => x.to_string(),
            _ => n.to_string(),
        },
        J::String(s) => s.clone(),
        J::Array(_) | J::Object(_) => return None,
    })
}

/// The value at a `.`-joined key path of a JSON object; a number indexes an array
/// (`rows.0.tbar.mean_speed`: the first row's).
pub fn lookup<'a>(v: &'a serde_json::Value, path: &str) -> Option<&'a serde_json::Value> {
    path.split('.').try_fold(v, |v, key| match v {
        serde_json::Value::Array(items) => key.parse::<usize>().ok().and_then(|i| items.get(i)),
        _ => v.get(key),
    })
}

/// The row of one case: `case`, the axis texts, the results (or empty fields and the error).
pub fn row(
    spec: &Spec,
    id: usize,
    axis_texts: &[String],
    result: &Result<serde_json::Value, crate::CaseError>,
) -> Vec<u8> {
    let mut fields = Vec::with_capacity(3 + axis_texts.len() + spec.columns.len());
    fields.push(id.to_string());
    fields.extend(axis_texts.iter().cloned());
    match result {
        Ok(report) => {
            fields.extend(
                spec.columns
                    .iter()
                    .map(|c| lookup(report, c.name).and_then(scalar).unwrap_or_default()),
            );
            fields.push("ok".into());
            fields.push(String::new());
        }
        Err(error) => {
            fields.extend(spec.columns.iter().map(|_| String::new()));
            fields.push("error".into());
            fields.push(one_line(&error.to_string()));
        }
    }
    record(&fields)
}

/// The message on one line (CR/LF become spaces).
fn one_line(message: &str) -> String {
    message
        .split(['\n', '\r'])
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn scalars_round_trip_and_quote() {
        assert_eq!(scalar(&json!(0.1)).unwrap(), "0.1");
        assert_eq!(scalar(&json!(1.0)).unwrap(), "1");
        assert_eq!(scalar(&json!(42u64)).unwrap(), "42");
        assert_eq!(scalar(&json!(-3)).unwrap(), "-3");
        assert_eq!(scalar(&json!(null)).unwrap(), "");
        assert_eq!(scalar(&json!(true)).unwrap(), "true");
        assert!(scalar(&json!([1, 2])).is_none());
        for x in [1.0 / 3.0, 6.02214076e23, 1e-300, -2.5e-7, f64::MAX] {
            let s = scalar(&json!(x)).unwrap();
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
        assert_eq!(
            record(&["a", "spokes,inner", "x\"y"]),
            b"a,\"spokes,inner\",\"x\"\"y\"\n"
        );
        assert_eq!(one_line("a\nb\r\nc"), "a b c");
        let v = json!({"mass_kg": {"yield": 2.5}, "n": 3});
        assert_eq!(lookup(&v, "mass_kg.yield"), Some(&json!(2.5)));
        assert_eq!(lookup(&v, "mass_kg.none"), None);
    }
}
