//! What the signal handler does to the open sinks when the command does not stop by itself:
//! every sink finished as incomplete at once (one test in its own process: the registry of
//! open sinks is process-wide).

use std::path::PathBuf;
use tensegrity_core::{Bar, Structure};
use tensegrity_io::interrupt;
use tensegrity_io::sink::{CsvSink, FigureSink, OutputDir, VtkSeriesSink};
use tensegrity_io::IoError;

fn names(dir: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn the_handler_finishes_every_open_sink_as_incomplete() {
    let dir = std::env::temp_dir().join(format!("io-interrupt-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1))
        .build()
        .unwrap();
    let mut csv = CsvSink::with_header(&dir.join("h.csv"), "history", &["t", "x"]).unwrap();
    csv.record(["0", "1"]).unwrap();
    csv.record(["0.001", "1.5"]).unwrap();
    let mut series = VtkSeriesSink::open(&dir.join("vtk"), &s).unwrap();
    series.frame(0.0, s.nodes()).unwrap();
    let figure = FigureSink::open(&dir.join("f.svg")).unwrap();
    let empty_dir = OutputDir::create(&dir.join("empty")).unwrap();
    let nothing = CsvSink::open(&dir.join("never.csv"), "table").unwrap();

    let mut kept = interrupt::finish_open_sinks("interrupted");
    kept.sort();
    let want: Vec<PathBuf> = vec![dir.join("h.csv"), dir.join("vtk").join("series.pvd")];
    assert_eq!(kept, want);
    assert_eq!(
        std::fs::read_to_string(dir.join("h.csv")).unwrap(),
        "t,x\n0,1\n0.001,1.5\n# incomplete: interrupted\n"
    );
    let pvd = std::fs::read_to_string(dir.join("vtk").join("series.pvd")).unwrap();
    assert!(pvd.contains("<!-- incomplete: interrupted -->") && pvd.contains("frame_00000.vtu"));
    // the whole-file outputs, the empty table and the directory this run created are gone
    assert_eq!(names(&dir), ["h.csv", "vtk"]);
    assert_eq!(names(&dir.join("vtk")), ["frame_00000.vtu", "series.pvd"]);
    // the command's thread finds its sinks closed
    assert!(matches!(
        csv.record(["1", "2"]),
        Err(IoError::Closed { .. })
    ));
    assert!(matches!(
        series.frame(0.1, s.nodes()),
        Err(IoError::Closed { .. })
    ));
    assert!(csv.finish().is_err());
    drop((series, figure, empty_dir, nothing));
    assert_eq!(names(&dir), ["h.csv", "vtk"]);
    assert!(interrupt::finish_open_sinks("again").is_empty());
}
