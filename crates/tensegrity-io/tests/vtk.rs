//! VTK series: the .vtu frames and the .pvd collection parse as XML and hold what was written.

use nalgebra::Vector3;
use tensegrity_core::{Bar, StringMember, Structure};
use tensegrity_io::vtk;

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("tensegrity-io-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn numbers<T: std::str::FromStr>(node: roxmltree::Node) -> Vec<T>
where
    T::Err: std::fmt::Debug,
{
    node.text()
        .unwrap_or("")
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

fn array<'a>(doc: &'a roxmltree::Document, name: &str) -> roxmltree::Node<'a, 'a> {
    doc.descendants()
        .find(|n| n.has_tag_name("DataArray") && n.attribute("Name") == Some(name))
        .unwrap_or_else(|| panic!("no DataArray {name}"))
}

#[test]
fn frames_and_the_series_parse_back() {
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1.0 / 3.0, 0.0]])
        .bar(Bar::new(0, 1))
        .string(StringMember::new(1, 2))
        .string(StringMember::new(2, 0))
        .build()
        .unwrap();
    let moved: Vec<Vector3<f64>> = s
        .nodes()
        .iter()
        .map(|p| p * 1.1 + Vector3::z() * 0.1)
        .collect();
    let dir = scratch("vtk");
    let frames = [(0.0, s.nodes()), (0.25, &moved[..])];
    let n = vtk::write_series(&dir, &s, frames).unwrap();
    assert_eq!(n, 2);

    let pvd = std::fs::read_to_string(dir.join("series.pvd")).unwrap();
    let doc = roxmltree::Document::parse(&pvd).unwrap();
    let sets: Vec<(f64, &str)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("DataSet"))
        .map(|n| {
            (
                n.attribute("timestep").unwrap().parse().unwrap(),
                n.attribute("file").unwrap(),
            )
        })
        .collect();
    assert_eq!(
        sets,
        vec![(0.0, "frame_00000.vtu"), (0.25, "frame_00001.vtu")]
    );

    let text = std::fs::read_to_string(dir.join("frame_00001.vtu")).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let piece = doc.descendants().find(|n| n.has_tag_name("Piece")).unwrap();
    assert_eq!(piece.attribute("NumberOfPoints"), Some("3"));
    assert_eq!(piece.attribute("NumberOfCells"), Some("3"));
    let points = doc
        .descendants()
        .find(|n| n.has_tag_name("Points"))
        .and_then(|p| p.children().find(|n| n.has_tag_name("DataArray")))
        .unwrap();
    let xyz: Vec<f64> = numbers(points);
    let expected: Vec<f64> = moved.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    assert_eq!(xyz, expected); // exact: `{:e}` is the shortest round-trip text
    assert_eq!(
        numbers::<usize>(array(&doc, "connectivity")),
        vec![0, 1, 1, 2, 2, 0]
    );
    assert_eq!(numbers::<usize>(array(&doc, "offsets")), vec![2, 4, 6]);
    assert_eq!(numbers::<u8>(array(&doc, "types")), vec![3, 3, 3]);
    assert_eq!(numbers::<i32>(array(&doc, "member_kind")), vec![0, 1, 1]);
    assert_eq!(numbers::<i32>(array(&doc, "member_index")), vec![0, 0, 1]);
    // nothing is left behind but the frames and the series
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["frame_00000.vtu", "frame_00001.vtu", "series.pvd"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unwritable_directory_is_named() {
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1))
        .build()
        .unwrap();
    let blocker = scratch("vtk-blocked");
    std::fs::write(&blocker, "a file, not a directory").unwrap();
    let e = vtk::write_series(&blocker.join("sub"), &s, [(0.0, s.nodes())]).unwrap_err();
    assert!(e.to_string().contains("vtk-blocked"), "{e}");
    std::fs::remove_file(&blocker).unwrap();
}

/// A clustered string is drawn segment by segment after the members: kind 2, its cluster's
/// index, its tension on every segment; forces of a length that does not count the clusters
/// are left out rather than shifted onto the wrong cells.
#[test]
fn a_clusters_segments_are_cells_with_its_tension() {
    use tensegrity_core::Cluster;
    use tensegrity_io::vtk::{vtu_with, FrameData};
    let s = Structure::builder()
        .nodes([
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 1.0],
        ])
        .bar(Bar::new(0, 1))
        .cluster(Cluster::new([1, 2, 3, 0]))
        .build()
        .unwrap();
    let forces = [-5.0, 7.5];
    let data = FrameData {
        member_forces: Some(&forces),
        ..FrameData::default()
    };
    let xml = vtu_with(&s, s.nodes(), &data);
    let doc = roxmltree::Document::parse(&xml).unwrap();
    assert_eq!(numbers::<i64>(array(&doc, "member_kind")), vec![0, 2, 2, 2]);
    assert_eq!(
        numbers::<i64>(array(&doc, "member_index")),
        vec![0, 0, 0, 0]
    );
    assert_eq!(
        numbers::<i64>(array(&doc, "connectivity")),
        vec![0, 1, 1, 2, 2, 3, 3, 0]
    );
    assert_eq!(
        numbers::<f64>(array(&doc, "force [N]")),
        vec![-5.0, 7.5, 7.5, 7.5]
    );
    let short = FrameData {
        member_forces: Some(&forces[..1]),
        ..FrameData::default()
    };
    assert!(!vtu_with(&s, s.nodes(), &short).contains(r#"Name="force [N]""#));
}
