//! A result column of a command's report ([`Column`]): the scalar's JSON key and its unit;
//! every command's list is in [`crate::columns`].

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
