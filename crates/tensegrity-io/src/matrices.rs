//! The matrix form of MOTES and TsgFEM models ([`structure_from_matrices`]): the node matrix
//! N (3 × n, a node per column) and the connectivity matrices C_b (bars × n) and C_s
//! (strings × n), as text or CSV.
//!
//! A member's row of C has −1 at its first node i and +1 at its second node j (MOTES's and
//! TsgFEM's convention: the member vectors are the columns of N Cᵀ, n_j − n_i), zeros
//! elsewhere. A matrix is one row per line, its numbers separated by commas and/or white
//! space; empty lines and lines starting with `#` or `%` (MATLAB's comment) are skipped, and
//! MATLAB's brackets and semicolons are ignored, so `[0 1; 2 3]` pasted over two lines reads
//! too. N may also be given n × 3 (a node per row: the transpose is taken when the file has
//! three columns and not three rows). Optional per-member values (bar masses, string
//! stiffnesses and rest lengths) are read in order from their own text, one number per
//! member. Every error names the matrix, the row and what is wrong with it.

use crate::error::IoError;
use tensegrity_core::{Bar, StringMember, Structure, Support};

/// What [`structure_from_matrices`] reads besides N, C_b and C_s.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MatrixOptions {
    /// One mass per bar (kg).
    pub bar_masses: Option<Vec<f64>>,
    /// One stiffness per string (N/m).
    pub string_stiffness: Option<Vec<f64>>,
    /// One rest length per string (m).
    pub string_rest_lengths: Option<Vec<f64>>,
    /// Nodes held in all three directions.
    pub pinned: Vec<usize>,
}

/// Reads the numbers of a matrix's text: one row per line (module docs). `name` labels the
/// errors.
///
/// ```
/// use tensegrity_io::matrices::read_matrix;
/// let m = read_matrix("% N\n[0 1 2;\n 3,4,5]\n", "N").unwrap();
/// assert_eq!(m, vec![vec![0.0, 1.0, 2.0], vec![3.0, 4.0, 5.0]]);
/// assert!(read_matrix("1 2\n3\n", "N").unwrap_err().to_string().contains("row 2 has 1 number"));
/// ```
pub fn read_matrix(text: &str, name: &str) -> Result<Vec<Vec<f64>>, IoError> {
    let mut rows = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with('%') {
            continue;
        }
        let mut row = Vec::new();
        for token in line
            .split(|c: char| c == ',' || c == ';' || c == '[' || c == ']' || c.is_whitespace())
            .filter(|t| !t.is_empty())
        {
            let v: f64 = token.parse().map_err(|_| {
                invalid(
                    name,
                    format!("row {}: '{token}' is not a number", rows.len() + 1),
                )
            })?;
            if !v.is_finite() {
                return Err(invalid(
                    name,
                    format!("row {}: {v} is not finite", rows.len() + 1),
                ));
            }
            row.push(v);
        }
        if row.is_empty() {
            continue;
        }
        rows.push(row);
    }
    if let Some(first) = rows.first() {
        let width = first.len();
        if let Some((k, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != width) {
            return Err(invalid(
                name,
                format!(
                    "row {} has {} number(s), row 1 has {width}: give every row the same length",
                    k + 1,
                    r.len()
                ),
            ));
        }
    }
    Ok(rows)
}

/// The numbers of a text in order (a per-member list in any layout).
pub fn read_values(text: &str, name: &str) -> Result<Vec<f64>, IoError> {
    Ok(read_matrix(text, name)?.into_iter().flatten().collect())
}

/// The structure of MOTES's or TsgFEM's matrices (module docs): the nodes of `n` (3 × n or
/// n × 3), a bar per row of `c_b`, a string per row of `c_s` (`None`: no strings), with
/// `options`' masses, stiffnesses, rest lengths and pinned nodes; checked by the structure's
/// builder.
///
/// ```
/// use tensegrity_io::matrices::{structure_from_matrices, MatrixOptions};
/// // a bar 0 → 1 and a string 1 → 2 (N: a node per column)
/// let n = "0 1 1\n0 0 1\n0 0 0\n";
/// let s = structure_from_matrices(n, "-1 1 0\n", Some("0 -1 1\n"), &MatrixOptions::default())?;
/// assert_eq!((s.n_nodes(), s.bars()[0].nodes, s.strings()[0].nodes), (3, [0, 1], [1, 2]));
/// # Ok::<(), tensegrity_io::error::IoError>(())
/// ```
pub fn structure_from_matrices(
    n: &str,
    c_b: &str,
    c_s: Option<&str>,
    options: &MatrixOptions,
) -> Result<Structure, IoError> {
    let c_s = match c_s {
        Some(text) => read_matrix(text, "C_s")?,
        None => Vec::new(),
    };
    structure_from_rows(
        &read_matrix(n, "N")?,
        &read_matrix(c_b, "C_b")?,
        &c_s,
        options,
    )
}

/// [`structure_from_matrices`] of matrices already read, row by row (from Python's arrays).
pub fn structure_from_rows(
    n: &[Vec<f64>],
    c_b: &[Vec<f64>],
    c_s: &[Vec<f64>],
    options: &MatrixOptions,
) -> Result<Structure, IoError> {
    let nodes = node_matrix(n)?;
    let bars = members(c_b, nodes.len(), "C_b")?;
    let strings = members(c_s, nodes.len(), "C_s")?;
    let per = |values: &Option<Vec<f64>>, count: usize, name: &str| match values {
        Some(v) if v.len() != count => Err(invalid(
            name,
            format!(
                "{} value(s) for {count} member(s): give one per member",
                v.len()
            ),
        )),
        _ => Ok(()),
    };
    per(&options.bar_masses, bars.len(), "bar masses")?;
    per(
        &options.string_stiffness,
        strings.len(),
        "string stiffnesses",
    )?;
    per(
        &options.string_rest_lengths,
        strings.len(),
        "string rest lengths",
    )?;
    let mut builder = Structure::builder().nodes(nodes);
    for (k, [i, j]) in bars.into_iter().enumerate() {
        let mut bar = Bar::new(i, j);
        if let Some(m) = &options.bar_masses {
            bar = bar.mass(m[k]);
        }
        builder = builder.bar(bar);
    }
    for (k, [i, j]) in strings.into_iter().enumerate() {
        let mut string = StringMember::new(i, j);
        if let Some(v) = &options.string_stiffness {
            string = string.stiffness(v[k]);
        }
        if let Some(v) = &options.string_rest_lengths {
            string = string.rest_length(v[k]);
        }
        builder = builder.string(string);
    }
    for &node in &options.pinned {
        builder = builder.support(Support::pinned(node));
    }
    builder.build().map_err(|source| IoError::InvalidStructure {
        file: "the matrices".into(),
        line: None,
        source,
    })
}

/// The nodes of N: 3 × n (a node per column), or n × 3 when it has three columns and not
/// three rows.
fn node_matrix(rows: &[Vec<f64>]) -> Result<Vec<[f64; 3]>, IoError> {
    let width = rows.first().map_or(0, Vec::len);
    if let Some((k, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != width) {
        return Err(invalid(
            "N",
            format!("row {} has {} number(s), row 1 has {width}", k + 1, r.len()),
        ));
    }
    if rows.len() == 3 {
        return Ok((0..width)
            .map(|c| [rows[0][c], rows[1][c], rows[2][c]])
            .collect());
    }
    if width == 3 {
        return Ok(rows.iter().map(|r| [r[0], r[1], r[2]]).collect());
    }
    Err(invalid(
        "N",
        format!(
            "{} × {width}: give the nodes as 3 × n (a node per column, as MOTES and TsgFEM) or n × 3",
            rows.len()
        ),
    ))
}

/// The members of a connectivity matrix: per row, the node of its −1 and the node of its +1.
fn members(rows: &[Vec<f64>], n: usize, name: &str) -> Result<Vec<[usize; 2]>, IoError> {
    let mut out = Vec::with_capacity(rows.len());
    for (k, row) in rows.iter().enumerate() {
        let bad = |why: String| invalid(name, format!("row {} (member {k}): {why}", k + 1));
        if row.len() != n {
            return Err(bad(format!(
                "{} column(s) for {n} node(s): give one column per node",
                row.len()
            )));
        }
        let (mut from, mut to) = (None, None);
        for (node, &v) in row.iter().enumerate() {
            match v {
                0.0 => {}
                -1.0 if from.is_none() => from = Some(node),
                1.0 if to.is_none() => to = Some(node),
                _ => {
                    return Err(bad(format!(
                        "{v} at node {node}: a row holds one −1 (the first node), one +1 (the second) and zeros"
                    )))
                }
            }
        }
        match (from, to) {
            (Some(i), Some(j)) => out.push([i, j]),
            _ => {
                return Err(bad(
                    "it needs one −1 (the first node) and one +1 (the second)".into(),
                ))
            }
        }
    }
    Ok(out)
}

fn invalid(name: &str, reason: String) -> IoError {
    IoError::InvalidMatrix {
        matrix: name.to_string(),
        reason,
    }
}
