//! What a figure's builder returns: the figure and its data ([`Drawn`]), the table written
//! beside it (`fig_3_9.csv` beside `fig_3_9.svg`, header with units).
//!
//! A line figure's data is its points ([`Drawn::plot`]: panel, series, x, y with units). A
//! structure drawing's data ([`StructureData`]) is, per panel, one row per node — its
//! coordinates x, y, z (m) and the drawn, projected coordinates u, v (m: equal scales, so
//! the picture's aspect can be checked against them) — and one row per member — its end
//! nodes, its legend group, its length, and the axial force (N, tension positive) and force
//! density q = force/length (N/m) the drawing used, where the figure has them — then the
//! figure's own columns (a wheel's prestressability margin, the time of a rolling frame).

use crate::draw::{Group, View};
use nalgebra::Vector3;
use tensegrity_io::figure::Figure;
use tensegrity_io::figure_data::{FigureData, Value};

/// A built figure and the data it was drawn from.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawn {
    /// The figure.
    pub figure: Figure,
    /// Its data, written beside it as CSV.
    pub data: FigureData,
}

impl Drawn {
    /// A figure with its own data table.
    pub fn new(figure: Figure, data: FigureData) -> Self {
        Self { figure, data }
    }

    /// A line figure whose data is its points: x and y named with their units.
    pub fn plot(figure: Figure, x: (&str, &str), y: (&str, &str)) -> Self {
        let data = FigureData::of_series(&figure, x, y);
        Self { figure, data }
    }
}

/// The columns every structure table starts with.
pub const STRUCTURE_COLUMNS: [(&str, &str); 15] = [
    ("panel", ""),
    ("panel_title", ""),
    ("item", ""),
    ("id", ""),
    ("group", ""),
    ("node_a", ""),
    ("node_b", ""),
    ("x", "m"),
    ("y", "m"),
    ("z", "m"),
    ("u", "m"),
    ("v", "m"),
    ("length", "m"),
    ("force", "N"),
    ("force_density", "N/m"),
];

/// The data of a structure drawing, panel by panel.
#[derive(Debug, Clone, PartialEq)]
pub struct StructureData {
    table: FigureData,
}

/// One panel of a structure drawing, as [`StructureData::panel`] records it.
pub struct PanelData<'a> {
    /// The panel's number (0-based) and title.
    pub panel: (usize, &'a str),
    /// The projection drawn.
    pub view: View,
    /// The nodes (m).
    pub nodes: &'a [Vector3<f64>],
    /// The member groups drawn.
    pub groups: &'a [Group],
    /// The figure's own columns' values for this panel (the same on every row).
    pub extra: Vec<Value>,
    /// A label per node, written in the `group` column of its row (empty: none), e.g. a
    /// node's name or its height class.
    pub node_labels: &'a [String],
}

impl StructureData {
    /// An empty table: [`STRUCTURE_COLUMNS`], then `extra` (name, unit).
    pub fn new(extra: &[(&str, &str)]) -> Self {
        let mut columns = STRUCTURE_COLUMNS.to_vec();
        columns.extend_from_slice(extra);
        Self {
            table: FigureData::new(&columns),
        }
    }

    /// Records one panel: every node, then every member of every group, its axial force
    /// `force(group, k, [a, b])` (N, tension positive; `None`: not known) of member `k` of
    /// group `group`.
    pub fn panel(
        &mut self,
        p: PanelData<'_>,
        force: &dyn Fn(usize, usize, [usize; 2]) -> Option<f64>,
    ) {
        let (number, title) = p.panel;
        // the title as the figure code wrote it, without the dollars that mark its math
        let title = title.replace('$', "");
        let title = title.as_str();
        for (i, n) in p.nodes.iter().enumerate() {
            let (u, v) = p.view.project(n);
            let mut row: Vec<Value> = vec![
                number.into(),
                title.into(),
                "node".into(),
                i.into(),
                p.node_labels.get(i).cloned().into(),
                Value::Missing,
                Value::Missing,
                n.x.into(),
                n.y.into(),
                n.z.into(),
                u.into(),
                v.into(),
                Value::Missing,
                Value::Missing,
                Value::Missing,
            ];
            row.extend(p.extra.iter().cloned());
            self.table.push(row);
        }
        let mut id = 0;
        for (g, group) in p.groups.iter().enumerate() {
            for (k, &[a, b]) in group.edges.iter().enumerate() {
                let length = (p.nodes[b] - p.nodes[a]).norm();
                let f = force(g, k, [a, b]);
                let mut row: Vec<Value> = vec![
                    number.into(),
                    title.into(),
                    "member".into(),
                    id.into(),
                    group.label.as_str().into(),
                    a.into(),
                    b.into(),
                    Value::Missing,
                    Value::Missing,
                    Value::Missing,
                    Value::Missing,
                    Value::Missing,
                    length.into(),
                    f.into(),
                    f.map(|f| f / length).into(),
                ];
                row.extend(p.extra.iter().cloned());
                self.table.push(row);
                id += 1;
            }
        }
    }

    /// The table.
    pub fn finish(self) -> FigureData {
        self.table
    }
}

/// A structure drawing being built: its panels and their data.
pub struct StructureFigure {
    /// The panels so far (a builder may add series to them, e.g. the ground).
    pub panels: Vec<tensegrity_io::figure::Panel>,
    data: StructureData,
    /// Labels of the nodes of the next panels ([`PanelData::node_labels`]).
    pub node_labels: Vec<String>,
}

impl StructureFigure {
    /// No panel yet; the data's own columns `extra` (name, unit).
    pub fn new(extra: &[(&str, &str)]) -> Self {
        Self {
            panels: Vec::new(),
            data: StructureData::new(extra),
            node_labels: Vec::new(),
        }
    }

    /// Draws `groups` of members between `nodes` in `view` as the next panel and records its
    /// data (`force`: see [`StructureData::panel`]; `extra`: the figure's own columns).
    pub fn add(
        &mut self,
        title: &str,
        view: View,
        nodes: &[Vector3<f64>],
        groups: &[Group],
        force: &dyn Fn(usize, usize, [usize; 2]) -> Option<f64>,
        extra: Vec<Value>,
    ) {
        let panel = crate::draw::structure_panel(title, view, nodes, groups);
        let p = PanelData {
            panel: (self.panels.len(), title),
            view,
            nodes,
            groups,
            extra,
            node_labels: &self.node_labels,
        };
        self.data.panel(p, force);
        self.panels.push(panel);
    }

    /// The drawing (to scale) and its data.
    pub fn finish(self) -> Drawn {
        Drawn::new(crate::draw::drawing_figure(self.panels), self.data.finish())
    }
}

/// No member forces known.
pub fn no_forces(_: usize, _: usize, _: [usize; 2]) -> Option<f64> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::{BLUE, RED};

    #[test]
    fn a_panel_is_its_nodes_then_its_members_with_lengths_and_force_densities() {
        let nodes = [Vector3::new(0.0, 0.0, 0.0), Vector3::new(0.0, 3.0, 4.0)];
        let groups = [
            Group::new("bars", BLUE, vec![[0, 1]]),
            Group::new("strings", RED, vec![]),
        ];
        let mut d = StructureData::new(&[("margin", "N/m")]);
        d.panel(
            PanelData {
                panel: (0, "p"),
                view: View::Side,
                nodes: &nodes,
                groups: &groups,
                extra: vec![0.5.into()],
                node_labels: &[],
            },
            &|_, _, _| Some(-10.0),
        );
        let t = d.finish();
        assert_eq!(t.rows.len(), 3);
        assert_eq!(t.numbers("u"), vec![0.0, 3.0]);
        assert_eq!(t.numbers("v"), vec![0.0, 4.0]);
        assert_eq!(t.numbers("length"), vec![5.0]);
        assert_eq!(t.numbers("force_density"), vec![-2.0]);
        assert_eq!(t.numbers("margin"), vec![0.5; 3]);
        assert!(t
            .to_csv()
            .starts_with("panel,panel_title,item,id,group,node_a,node_b,x [m],"));
    }
}
