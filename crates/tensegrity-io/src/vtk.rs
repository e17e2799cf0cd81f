//! VTK export for ParaView: one ASCII `.vtu` (UnstructuredGrid of line cells, one per member)
//! per frame and a `.pvd` collection that indexes the frames by time.
//!
//! Points are the node positions (m, file numbering), cells are VTK_LINE (type 3) from start to
//! end node of every member (bars first, then strings, then each segment of each clustered
//! string), cell data `member_kind` (0 bar, 1 string, 2 a cluster's segment) and
//! `member_index` (its index among its kind: a segment carries its cluster's), and `force [N]`
//! when the frame gives one per member and per cluster (a cluster's tension on each of its
//! segments); point data `velocity [m/s]` and `contact_force [N]` (the ground's force on each
//! node, zero off the ground) when recorded. Every array of a physical quantity carries its
//! unit in its name, as ParaView shows it. Numbers are written with `{:e}`,
//! the shortest text that reads back to the same f64. Series are written through the
//! [`VtkSeriesSink`] (frames renamed into place one by one, `series.pvd` rewritten atomically).

use crate::error::Result;
pub use crate::sink::VtkSeriesSink;
use nalgebra::Vector3;
use std::fmt::Write as _;
use std::path::Path;
use tensegrity_core::Structure;

/// The XML text of one frame: the members of `structure` at node positions `nodes`.
///
/// ```
/// use tensegrity_core::{Bar, Structure};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1))
///     .build()
///     .unwrap();
/// let xml = tensegrity_io::vtk::vtu(&s, &s.nodes());
/// assert!(xml.contains(r#"NumberOfPoints="2" NumberOfCells="1""#));
/// ```
pub fn vtu(structure: &Structure, nodes: &[Vector3<f64>]) -> String {
    vtu_with(structure, nodes, &FrameData::default())
}

/// The name of the cell data of axial member forces (tension positive).
pub const FORCE: &str = "force [N]";
/// The name of the point data of node velocities.
pub const VELOCITY: &str = "velocity [m/s]";
/// The name of the point data of the ground's force on each node.
pub const CONTACT_FORCE: &str = "contact_force [N]";

/// Recorded quantities written with a frame: node velocities as point data [`VELOCITY`],
/// the ground's forces on the nodes as point data [`CONTACT_FORCE`] and axial member forces,
/// tension positive, as cell data [`FORCE`].
#[derive(Debug, Clone, Copy, Default)]
pub struct FrameData<'a> {
    /// Node velocities (file numbering).
    pub velocities: Option<&'a [Vector3<f64>]>,
    /// Member forces, bars then strings.
    pub member_forces: Option<&'a [f64]>,
    /// The ground's force on the contact nodes: (file node, force); nodes not listed get 0.
    pub contact_forces: Option<&'a [(usize, Vector3<f64>)]>,
}

/// [`vtu`] with the recorded quantities of `data`.
///
/// ```
/// use nalgebra::Vector3;
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_io::vtk::{vtu_with, FrameData};
/// let s = Structure::builder().nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1)).build().unwrap();
/// let v = [Vector3::new(0.0, 0.0, -1.0); 2];
/// let ground = [(0, Vector3::new(0.0, 0.0, 9.81))];
/// let data = FrameData {
///     velocities: Some(&v),
///     member_forces: Some(&[-5.0]),
///     contact_forces: Some(&ground),
/// };
/// let xml = vtu_with(&s, &s.nodes(), &data);
/// assert!(xml.contains(r#"Name="velocity [m/s]""#) && xml.contains(r#"Name="force [N]""#));
/// assert!(xml.contains("0e0 0e0 -1e0") && xml.contains("-5e0"));
/// // the ground's force on node 0, none on node 1
/// assert!(xml.contains(r#"Name="contact_force [N]""#) && xml.contains("0e0 0e0 9.81e0\n0e0 0e0 0e0"));
/// ```
pub fn vtu_with(structure: &Structure, nodes: &[Vector3<f64>], data: &FrameData<'_>) -> String {
    let n_members = structure.n_members();
    // cells: the members, then every segment of every cluster (its cluster's index kept)
    let segments: Vec<(usize, [usize; 2])> = (structure.clusters().iter().enumerate())
        .flat_map(|(c, cluster)| cluster.segments().map(move |pair| (c, pair)))
        .collect();
    let mut members = structure.member_nodes();
    members.extend(segments.iter().map(|&(_, pair)| pair));
    let nb = structure.n_bars();
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0"?>"#);
    let _ = writeln!(
        s,
        r#"<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">"#
    );
    let _ = writeln!(s, "<UnstructuredGrid>");
    let _ = writeln!(
        s,
        r#"<Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
        nodes.len(),
        members.len()
    );
    let _ = writeln!(
        s,
        r#"<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">"#
    );
    for p in nodes {
        let _ = writeln!(s, "{:e} {:e} {:e}", p.x, p.y, p.z);
    }
    let _ = writeln!(s, "</DataArray></Points>");
    let _ = writeln!(s, "<Cells>");
    let _ = writeln!(
        s,
        r#"<DataArray type="Int64" Name="connectivity" format="ascii">"#
    );
    for [i, j] in &members {
        let _ = writeln!(s, "{i} {j}");
    }
    let _ = writeln!(s, "</DataArray>");
    let _ = writeln!(
        s,
        r#"<DataArray type="Int64" Name="offsets" format="ascii">"#
    );
    let offsets: Vec<String> = (1..=members.len()).map(|k| (2 * k).to_string()).collect();
    let _ = writeln!(s, "{}", offsets.join(" "));
    let _ = writeln!(s, "</DataArray>");
    let _ = writeln!(s, r#"<DataArray type="UInt8" Name="types" format="ascii">"#);
    let _ = writeln!(s, "{}", vec!["3"; members.len()].join(" "));
    let _ = writeln!(s, "</DataArray>");
    let _ = writeln!(s, "</Cells>");
    let _ = writeln!(s, r#"<CellData Scalars="member_kind">"#);
    let _ = writeln!(
        s,
        r#"<DataArray type="Int32" Name="member_kind" format="ascii">"#
    );
    let kinds: Vec<&str> = (0..members.len())
        .map(|k| match k {
            _ if k < nb => "0",
            _ if k < n_members => "1",
            _ => "2",
        })
        .collect();
    let _ = writeln!(s, "{}", kinds.join(" "));
    let _ = writeln!(s, "</DataArray>");
    let _ = writeln!(
        s,
        r#"<DataArray type="Int32" Name="member_index" format="ascii">"#
    );
    let index: Vec<String> = (0..members.len())
        .map(|k| match k {
            _ if k < nb => k,
            _ if k < n_members => k - nb,
            _ => segments[k - n_members].0,
        })
        .map(|i| i.to_string())
        .collect();
    let _ = writeln!(s, "{}", index.join(" "));
    let _ = writeln!(s, "</DataArray>");
    // one force per member then per cluster (each cluster's on all its segments); forces
    // of another length cannot be matched to the cells and are left out
    let per_cell = data
        .member_forces
        .filter(|f| f.len() == n_members + structure.clusters().len())
        .map(|f| {
            let clusters = segments.iter().map(|&(c, _)| f[n_members + c]);
            f[..n_members]
                .iter()
                .copied()
                .chain(clusters)
                .collect::<Vec<f64>>()
        });
    if let Some(f) = per_cell {
        let _ = writeln!(
            s,
            r#"<DataArray type="Float64" Name="{FORCE}" format="ascii">"#
        );
        let text: Vec<String> = f.iter().map(|v| format!("{v:e}")).collect();
        let _ = writeln!(s, "{}", text.join(" "));
        let _ = writeln!(s, "</DataArray>");
    }
    let _ = writeln!(s, "</CellData>");
    // the ground's force on every node: zero off the ground
    let contact = data.contact_forces.map(|c| {
        let mut all = vec![Vector3::zeros(); nodes.len()];
        for &(node, f) in c.iter().filter(|(node, _)| *node < nodes.len()) {
            all[node] = f;
        }
        all
    });
    let vectors: Vec<(&str, &[Vector3<f64>])> = [
        (VELOCITY, data.velocities),
        (CONTACT_FORCE, contact.as_deref()),
    ]
    .into_iter()
    .filter_map(|(name, v)| v.filter(|v| v.len() == nodes.len()).map(|v| (name, v)))
    .collect();
    if let Some((first, _)) = vectors.first() {
        let _ = writeln!(s, r#"<PointData Vectors="{first}">"#);
        for (name, v) in &vectors {
            let _ = writeln!(
                s,
                r#"<DataArray type="Float64" Name="{name}" NumberOfComponents="3" format="ascii">"#
            );
            for p in v.iter() {
                let _ = writeln!(s, "{:e} {:e} {:e}", p.x, p.y, p.z);
            }
            let _ = writeln!(s, "</DataArray>");
        }
        let _ = writeln!(s, "</PointData>");
    }
    let _ = writeln!(s, "</Piece>\n</UnstructuredGrid>\n</VTKFile>");
    s
}

/// Writes `frame_NNNNN.vtu` for every `(time, nodes)` and `series.pvd` into `dir` (created if
/// missing, its parent must exist) through a [`VtkSeriesSink`]; returns the number of frames.
///
/// ```
/// use tensegrity_core::{Bar, Structure};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1))
///     .build()
///     .unwrap();
/// let dir = std::env::temp_dir().join(format!("tensegrity-io-vtk-doc-{}", std::process::id()));
/// let nodes = s.nodes();
/// let n = tensegrity_io::vtk::write_series(&dir, &s, [(0.0, &nodes[..]), (0.5, &nodes[..])])?;
/// assert_eq!(n, 2);
/// assert!(dir.join("series.pvd").exists() && dir.join("frame_00001.vtu").exists());
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn write_series<'a>(
    dir: &Path,
    structure: &Structure,
    frames: impl IntoIterator<Item = (f64, &'a [Vector3<f64>])>,
) -> Result<usize> {
    let mut series = VtkSeriesSink::open(dir, structure)?;
    for (t, nodes) in frames {
        series.frame(t, nodes)?;
    }
    series.finish()
}

/// The former name of [`VtkSeriesSink`] (its `create` is [`VtkSeriesSink::open`]).
pub type SeriesWriter<'a> = VtkSeriesSink<'a>;
