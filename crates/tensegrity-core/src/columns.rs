//! The scalar result columns of a report ([`Column`]: a JSON key and its unit), declared once
//! on the report's fields with `#[derive(Columns)]` (crate `tensegrity-derive`), which
//! implements [`Columns`]. A sweep writes these columns, one row a case.
//!
//! ```
//! use tensegrity_core::columns::{col, nested, Column, Columns};
//! struct Gap;
//! impl Columns for Gap {
//!     fn columns() -> &'static [Column] {
//!         const GAP: [Column; 2] = [col("tolerance", ""), col("ratio", "")];
//!         &GAP
//!     }
//! }
//! let under = nested("spectral_gap", <Option<Gap>>::columns(), &["ratio"]);
//! assert_eq!(under, [col("spectral_gap.ratio", "")]);
//! ```

/// A result column: a scalar of the report, named by its JSON key (a nested key as
/// `outer.inner`), with its SI unit (`""` when dimensionless or not a number).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Column {
    /// The JSON key path.
    pub name: &'static str,
    /// SI unit.
    pub unit: &'static str,
}

/// A column.
pub const fn col(name: &'static str, unit: &'static str) -> Column {
    Column { name, unit }
}

/// A report with scalar result columns: its scalar JSON keys in key order, nested keys as
/// `outer.inner`. Derived with `#[derive(Columns)]` of `tensegrity-derive` (its docs give the
/// field attributes); the list is built once and lives for the program.
pub trait Columns {
    /// The columns, in the report's key order.
    fn columns() -> &'static [Column];
}

/// An optional value has the columns of its value (empty when it is `None`).
impl<T: Columns> Columns for Option<T> {
    fn columns() -> &'static [Column] {
        T::columns()
    }
}

/// A boxed value has the columns of its value.
impl<T: Columns> Columns for Box<T> {
    fn columns() -> &'static [Column] {
        T::columns()
    }
}

/// The columns `of` a nested value under `prefix` (`prefix.name`; none for `""`, a flattened
/// value), only those named in `only` when it is not empty, in their order in `of`. The
/// prefixed names are leaked: the derived [`Columns`] call it once per type.
///
/// # Panics
/// When `only` names a column that is not in `of` (a typo in a `#[column(only = …)]`).
pub fn nested(prefix: &str, of: &'static [Column], only: &[&str]) -> Vec<Column> {
    if let Some(missing) = only.iter().find(|n| !of.iter().any(|c| c.name == **n)) {
        panic!("`{missing}` is not a column under `{prefix}`");
    }
    of.iter()
        .filter(|c| only.is_empty() || only.contains(&c.name))
        .map(|c| match prefix {
            "" => *c,
            _ => col(
                Box::leak(format!("{prefix}.{}", c.name).into_boxed_str()),
                c.unit,
            ),
        })
        .collect()
}

/// The columns without repeats (the first of each name kept): the union of the fields of an
/// internally tagged enum's variants.
pub fn dedup(columns: Vec<Column>) -> Vec<Column> {
    let mut out: Vec<Column> = Vec::with_capacity(columns.len());
    for c in columns {
        if !out.iter().any(|o| o.name == c.name) {
            out.push(c);
        }
    }
    out
}
