//! The data of a figure, written beside it: one table ([`FigureData`]) whose header names each
//! column with its unit (`x [m]`, `force [N]`, `sides` for a pure number), one row per
//! drawn item (a point of a curve, a node or a member of a structure drawing), so that every
//! number a figure shows can be read back and checked. Numbers are written in Rust's
//! shortest round-trip form (`0.1`, `1e-5`), so a value read back equals the one drawn.
//!
//! [`FigureData::of_series`] makes the table of any line figure from its panels (panel,
//! series label, x, y); figures with more to say (a structure's member forces, a wheel's
//! prestressability margin) build their own.
//!
//! ```
//! use tensegrity_io::figure_data::{FigureData, Value};
//! let mut data = FigureData::new(&[("panel", ""), ("t", "s"), ("h", "m")]);
//! data.push(vec![Value::from(0usize), 0.5.into(), 0.125.into()]);
//! assert_eq!(data.header(), ["panel", "t [s]", "h [m]"]);
//! assert_eq!(data.to_csv(), "panel,t [s],h [m]\n0,0.5,0.125\n");
//! assert_eq!(data.numbers("h"), vec![0.125]);
//! ```

use crate::error::Result;
use crate::figure::Figure;
use crate::sink::CsvSink;

/// One cell.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number (written in its shortest round-trip form; NaN and infinities as text).
    Number(f64),
    /// A count or an index.
    Integer(i64),
    /// Text (a label, a kind).
    Text(String),
    /// Nothing (an empty cell: the column does not apply to this row).
    Missing,
}

impl From<f64> for Value {
    fn from(v: f64) -> Self {
        Value::Number(v)
    }
}

impl From<usize> for Value {
    fn from(v: usize) -> Self {
        Value::Integer(i64::try_from(v).unwrap_or(i64::MAX))
    }
}

impl From<bool> for Value {
    fn from(v: bool) -> Self {
        Value::Text(v.to_string())
    }
}

impl From<&str> for Value {
    fn from(v: &str) -> Self {
        Value::Text(v.to_string())
    }
}

impl From<String> for Value {
    fn from(v: String) -> Self {
        Value::Text(v)
    }
}

impl<T: Into<Value>> From<Option<T>> for Value {
    fn from(v: Option<T>) -> Self {
        v.map_or(Value::Missing, Into::into)
    }
}

impl Value {
    /// The cell's text.
    pub fn text(&self) -> String {
        match self {
            Value::Number(v) => format!("{v:?}")
                .trim_end_matches(".0")
                .to_string()
                .replace("inf", "Infinity"),
            Value::Integer(v) => v.to_string(),
            Value::Text(s) => s.clone(),
            Value::Missing => String::new(),
        }
    }

    /// The cell as a number, where it is one.
    pub fn number(&self) -> Option<f64> {
        match self {
            Value::Number(v) => Some(*v),
            Value::Integer(v) => Some(*v as f64),
            _ => None,
        }
    }
}

/// A column: its name and unit (`""`: a pure number or text).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Column {
    /// Name, snake_case (`force_density`).
    pub name: String,
    /// SI unit (`N/m`), or `""`.
    pub unit: String,
}

impl Column {
    /// The header text: `name [unit]`, or `name` without a unit.
    pub fn header(&self) -> String {
        if self.unit.is_empty() {
            self.name.clone()
        } else {
            format!("{} [{}]", self.name, self.unit)
        }
    }
}

/// The table of one figure's data.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FigureData {
    /// The columns.
    pub columns: Vec<Column>,
    /// The rows, each as long as `columns` (shorter rows are padded with empty cells).
    pub rows: Vec<Vec<Value>>,
}

impl FigureData {
    /// An empty table of `columns` (name, unit).
    pub fn new(columns: &[(&str, &str)]) -> Self {
        Self {
            columns: columns
                .iter()
                .map(|&(name, unit)| Column {
                    name: name.into(),
                    unit: unit.into(),
                })
                .collect(),
            rows: Vec::new(),
        }
    }

    /// Appends one row.
    pub fn push(&mut self, mut row: Vec<Value>) {
        row.resize(self.columns.len().max(row.len()), Value::Missing);
        self.rows.push(row);
    }

    /// The header: `name [unit]` per column.
    pub fn header(&self) -> Vec<String> {
        self.columns.iter().map(Column::header).collect()
    }

    /// The index of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c.name == name)
    }

    /// The numbers of column `name`, row by row (rows where it is not a number left out).
    pub fn numbers(&self, name: &str) -> Vec<f64> {
        let Some(k) = self.column(name) else {
            return Vec::new();
        };
        self.rows
            .iter()
            .filter_map(|r| r.get(k).and_then(Value::number))
            .collect()
    }

    /// The table of a line figure: one row per point of every series, `panel` (0-based),
    /// `panel_title`, `series` (its legend label) and the point, its coordinates named
    /// `x` and `y` with their units (a log axis holds the values, not their logarithms).
    ///
    /// ```
    /// use tensegrity_io::figure::{Figure, Panel, Series};
    /// use tensegrity_io::figure_data::FigureData;
    /// let fig = Figure::new(vec![Panel::new("drop", "time [s]", "height [m]")
    ///     .series(Series::new("z", vec![(0.0, 1.0), (0.5, 0.75)]))]);
    /// let data = FigureData::of_series(&fig, ("t", "s"), ("z", "m"));
    /// assert_eq!(data.to_csv().lines().nth(2), Some("0,drop,z,1,0.5,0.75"));
    /// ```
    pub fn of_series(figure: &Figure, x: (&str, &str), y: (&str, &str)) -> Self {
        let mut data = Self::new(&[
            ("panel", ""),
            ("panel_title", ""),
            ("series", ""),
            ("point", ""),
            x,
            y,
        ]);
        for (k, panel) in figure.panels.iter().enumerate() {
            for s in &panel.series {
                for (i, &(px, py)) in s.points.iter().enumerate() {
                    data.push(vec![
                        k.into(),
                        panel.title.as_str().into(),
                        s.label.as_str().into(),
                        i.into(),
                        px.into(),
                        py.into(),
                    ]);
                }
            }
        }
        data
    }

    /// The table as CSV text (header first).
    pub fn to_csv(&self) -> String {
        let mut w = ::csv::WriterBuilder::new().from_writer(Vec::new());
        let mut write = |fields: Vec<String>| w.write_record(fields).is_ok();
        let mut ok = write(self.header());
        for row in &self.rows {
            ok &= write(row.iter().map(Value::text).collect());
        }
        let bytes = w.into_inner().unwrap_or_default();
        debug_assert!(ok);
        String::from_utf8(bytes).unwrap_or_default()
    }

    /// Writes the table into `sink` (opened with no header, [`CsvSink::open_records`]) and
    /// finishes it; returns the number of rows.
    pub fn write(&self, mut sink: CsvSink) -> Result<usize> {
        sink.record(self.header())?;
        for row in &self.rows {
            sink.record(row.iter().map(Value::text))?;
        }
        sink.finish().map(|n| n.saturating_sub(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip_through_their_text() {
        for v in [0.1, 1.0 / 3.0, 1.4e-5, -2.5e10, 0.0, 3.0] {
            let t = Value::Number(v).text();
            assert_eq!(t.parse::<f64>().unwrap(), v, "{t}");
        }
        assert_eq!(Value::Number(3.0).text(), "3");
        assert_eq!(Value::Missing.text(), "");
        assert_eq!(Value::from(Some(2usize)).text(), "2");
    }

    #[test]
    fn short_rows_are_padded_and_text_is_quoted() {
        let mut d = FigureData::new(&[("label", ""), ("x", "m")]);
        d.push(vec!["a, b".into()]);
        assert_eq!(d.to_csv(), "label,x [m]\n\"a, b\",\n");
    }
}
