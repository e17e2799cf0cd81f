//! Unit tests of the sinks: finish, finish incomplete, dropped unfinished, locked, bad paths.

use super::*;
use crate::error::IoError;
use std::path::{Path, PathBuf};
use tensegrity_core::{Bar, Structure};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("io-sink-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[derive(serde::Serialize)]
struct Row {
    #[serde(rename = "t [s]")]
    t: f64,
    #[serde(rename = "x [m]")]
    x: f64,
}

fn bar() -> Structure {
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1))
        .build()
        .unwrap()
}

#[test]
fn csv_finish_renames_the_table_into_place_and_leaves_nothing_else() {
    let dir = scratch("csv-finish");
    let path = dir.join("a.csv");
    let mut sink = CsvSink::open(&path, "table").unwrap();
    assert_eq!(listing(&dir), [".a.csv.lock", ".a.csv.tmp"]);
    assert_eq!(
        sink.extend((0..3).map(|k| Row {
            t: k as f64,
            x: 0.5 * k as f64
        }))
        .unwrap(),
        3
    );
    assert_eq!(sink.rows(), 3);
    assert_eq!(sink.finish().unwrap(), 3);
    assert_eq!(listing(&dir), ["a.csv"]);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text, "t [s],x [m]\n0.0,0.0\n1.0,0.5\n2.0,1.0\n");
}

#[test]
fn csv_incomplete_keeps_the_rows_so_far_and_a_trailer() {
    let dir = scratch("csv-incomplete");
    let path = dir.join("b.csv");
    let mut sink = CsvSink::with_header(&path, "table", &["t [s]", "x [m]"]).unwrap();
    sink.record(["0", "1"]).unwrap();
    sink.record(["0.5", "2"]).unwrap();
    assert_eq!(
        sink.finish_incomplete("interrupted\nat t = 0.5 s").unwrap(),
        2
    );
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        text,
        "t [s],x [m]\n0,1\n0.5,2\n# incomplete: interrupted at t = 0.5 s\n"
    );
    assert_eq!(listing(&dir), ["b.csv"]);
    // an incomplete table with nothing in it leaves no file
    let empty = dir.join("c.csv");
    assert_eq!(
        CsvSink::open(&empty, "table")
            .unwrap()
            .finish_incomplete("x")
            .unwrap(),
        0
    );
    assert_eq!(listing(&dir), ["b.csv"]);
}

#[test]
fn a_sink_dropped_unfinished_removes_its_temporary_file_and_lock() {
    let dir = scratch("drop");
    let path = dir.join("d.csv");
    std::fs::write(&path, "old\n").unwrap();
    {
        let mut sink = CsvSink::open(&path, "table").unwrap();
        sink.serialize(&Row { t: 0.0, x: 0.0 }).unwrap();
        let mut file = FileSink::open(&dir.join("e.toml")).unwrap();
        std::io::Write::write_all(&mut file, b"x = 1\n").unwrap();
        let _json = JsonSink::open(&dir.join("f.json")).unwrap();
        let _figure = FigureSink::open(&dir.join("g.svg")).unwrap();
    }
    assert_eq!(listing(&dir), ["d.csv"]);
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        "old\n",
        "the old file is untouched"
    );
}

#[test]
fn a_second_writer_of_the_same_path_is_refused_at_open() {
    let dir = scratch("busy");
    let path = dir.join("h.csv");
    let first = CsvSink::open(&path, "table").unwrap();
    for second in [
        CsvSink::open(&path, "table").map(drop),
        FileSink::open(&path).map(drop),
    ] {
        match second {
            Err(e @ IoError::Busy { .. }) => {
                let text = e.to_string();
                assert!(
                    text.contains("h.csv") && text.contains("another run"),
                    "{text}"
                );
                assert!(
                    text.contains(&format!("pid {}", std::process::id())),
                    "{text}"
                );
            }
            other => panic!("{other:?}"),
        }
    }
    first.finish().unwrap();
    CsvSink::open(&path, "table").unwrap().finish().unwrap();
}

#[test]
fn bad_paths_fail_at_open_naming_the_path() {
    let dir = scratch("bad");
    std::fs::write(dir.join("file"), "").unwrap();
    std::fs::create_dir(dir.join("adir")).unwrap();
    let s = bar();
    let bad = [
        dir.join("missing").join("x.csv"),
        dir.join("file").join("x.csv"),
        dir.join("adir"),
    ];
    for path in &bad {
        let e = CsvSink::open(path, "table").unwrap_err();
        assert!(matches!(e, IoError::Write { .. }), "{e:?}");
        assert!(e.to_string().contains(&path.display().to_string()), "{e}");
    }
    let e = FigureSink::open(&dir.join("fig.bmp")).unwrap_err();
    assert!(matches!(e, IoError::UnsupportedFormat { .. }), "{e:?}");
    for series in [dir.join("missing").join("vtk"), dir.join("file")] {
        let e = VtkSeriesSink::open(&series, &s).unwrap_err();
        assert!(e.to_string().contains(&series.display().to_string()), "{e}");
    }
    assert_eq!(listing(&dir), ["adir", "file"], "nothing left behind");
}

#[test]
fn vtk_series_finish_lists_every_frame() {
    let dir = scratch("vtk-finish");
    let s = bar();
    let out = dir.join("vtk");
    let mut series = VtkSeriesSink::open(&out, &s).unwrap();
    for k in 0..3 {
        series.frame(0.5 * k as f64, s.nodes()).unwrap();
    }
    // the first frame wrote a readable collection already (marked as still being written)
    let pvd = std::fs::read_to_string(out.join("series.pvd")).unwrap();
    assert!(pvd.contains("frame_00000.vtu") && pvd.contains("<!-- incomplete"));
    assert_eq!(series.finish().unwrap(), 3);
    let pvd = std::fs::read_to_string(out.join("series.pvd")).unwrap();
    assert!(!pvd.contains("incomplete"));
    assert_eq!(pvd.matches("<DataSet").count(), 3);
    assert_eq!(
        listing(&out),
        [
            "frame_00000.vtu",
            "frame_00001.vtu",
            "frame_00002.vtu",
            "series.pvd"
        ]
    );
}

#[test]
fn vtk_series_incomplete_and_dropped_keep_their_frames_under_a_marked_collection() {
    let dir = scratch("vtk-incomplete");
    let s = bar();
    for (name, finish) in [("a", true), ("b", false)] {
        let out = dir.join(name);
        let mut series = VtkSeriesSink::open(&out, &s).unwrap();
        series.frame(0.0, s.nodes()).unwrap();
        series.frame(0.1, s.nodes()).unwrap();
        if finish {
            assert_eq!(
                series
                    .finish_incomplete("interrupted -- at t = 0.1 s")
                    .unwrap(),
                2
            );
        } else {
            drop(series);
        }
        let pvd = std::fs::read_to_string(out.join("series.pvd")).unwrap();
        assert_eq!(pvd.matches("<DataSet").count(), 2, "{pvd}");
        assert!(pvd.contains("<!-- incomplete: "), "{pvd}");
        assert!(!pvd.contains("-- at"), "no `--` inside a comment");
        assert_eq!(
            listing(&out),
            ["frame_00000.vtu", "frame_00001.vtu", "series.pvd"]
        );
    }
}

#[test]
fn a_vtk_series_without_frames_removes_the_directory_it_created() {
    let dir = scratch("vtk-empty");
    let s = bar();
    drop(VtkSeriesSink::open(&dir.join("a"), &s).unwrap());
    assert_eq!(
        VtkSeriesSink::open(&dir.join("b"), &s)
            .unwrap()
            .finish_incomplete("x")
            .unwrap(),
        0
    );
    assert!(listing(&dir).is_empty());
    // an existing directory stays; a second writer of the same series is refused
    let first = VtkSeriesSink::open(&dir, &s).unwrap();
    assert!(matches!(
        VtkSeriesSink::open(&dir, &s),
        Err(IoError::Busy { .. })
    ));
    drop(first);
    assert!(dir.is_dir() && listing(&dir).is_empty());
}

#[test]
fn json_and_figure_sinks_write_whole_files() {
    let dir = scratch("whole");
    let json = JsonSink::open(&dir.join("r.json")).unwrap();
    json.finish(&serde_json::json!({"a": [1, 2]})).unwrap();
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("r.json")).unwrap()).unwrap();
    assert_eq!(value["a"][1], 2);
    let panel = crate::figure::Panel::new("p", "x", "y").series(crate::figure::Series::new(
        "s",
        vec![(0.0, 0.0), (1.0, 1.0)],
    ));
    let figure = crate::figure::Figure::new(vec![panel]);
    FigureSink::open(&dir.join("f.PNG"))
        .unwrap()
        .finish(&figure)
        .unwrap();
    assert!(std::fs::read(dir.join("f.PNG"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    // a figure that cannot be drawn leaves nothing
    let empty = crate::figure::Figure::new(vec![]);
    assert!(FigureSink::open(&dir.join("e.svg"))
        .unwrap()
        .finish(&empty)
        .is_err());
    assert_eq!(listing(&dir), ["f.PNG", "r.json"]);
}

#[test]
fn a_rolling_history_streamed_through_a_csv_sink_is_the_file_of_write_rolling_history() {
    use wheel_rolling::RollingSample;
    let dir = scratch("rolling");
    let samples: Vec<RollingSample> = (0..4)
        .map(|k| {
            let t = 1e-3 * k as f64;
            RollingSample {
                t,
                s: 0.1 * t,
                h: 0.9,
                pivot: 0.0,
                omega: -2.0 * t,
                normal: 12.5,
                tangential: -0.25,
                energy: 3.0,
                slip: 0.0,
            }
        })
        .collect();
    let path = dir.join("r.csv");
    let mut sink = CsvSink::open(&path, "rolling history CSV").unwrap();
    for s in &samples {
        sink.serialize(&crate::csv::RollingRow::from(s)).unwrap();
    }
    sink.finish().unwrap();
    let mut want = Vec::new();
    crate::csv::write_rolling_history(&mut want, &samples).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), want);
    assert!(String::from_utf8(want)
        .unwrap()
        .starts_with("t,axle_s,axle_h,omega,pivot_m,normal_N,tangential_N,energy_J,slip_m_s\n"));
}

#[test]
fn a_rolling_run_streamed_through_its_outputs_writes_the_files_of_its_samples_and_frames() {
    use wheel_rolling::{roll_wheel, FidelityChoice, Polygon, RunSpec, Wheel};
    /// An octagon whose two nodes (the bar's) are drawn.
    struct Drawn(Polygon);
    impl Wheel for Drawn {
        type Error = wheel_rolling::RollingError;
        fn polygon(&self) -> Polygon {
            self.0
        }
        fn start_pose(&self) -> Vec<nalgebra::Vector3<f64>> {
            bar().nodes().to_vec()
        }
        fn scene(&self) -> std::result::Result<wheel_rolling::WheelScene, Self::Error> {
            self.0.scene()
        }
    }
    let wheel = Drawn(Polygon {
        sides: 8,
        outer_radius: 1.0,
        mass: 12.0,
        i1: 7.5,
    });
    let spec = RunSpec {
        fidelity: FidelityChoice::Rigid,
        t_end: 0.2,
        ..RunSpec::default()
    };
    let times: Vec<f64> = (0..=20).map(|k| 0.01 * k as f64).collect();
    let structure = bar();
    for incomplete in [None, Some("interrupted at t = 0.2 s")] {
        let dir = scratch("rolling-outputs");
        let (csv, vtk) = (dir.join("r.csv"), dir.join("vtk"));
        let mut outputs = RollingOutputs::new(
            Some(CsvSink::open(&csv, "rolling history CSV").unwrap()),
            Some(VtkSeriesSink::open(&vtk, &structure).unwrap()),
        )
        .keeping(&[0.1], 1e-4);
        let run = roll_wheel(&wheel, &spec, &times, Some(&mut outputs)).unwrap();
        // the run kept no frame; the outputs kept the one asked for
        assert!(run.frames.is_empty());
        let kept = outputs.take_frames();
        assert_eq!(kept.len(), 1);
        assert!((kept[0].t - 0.1).abs() < 1e-12);
        let written = outputs.finish(incomplete).unwrap();
        assert_eq!((written.rows, written.frames), (201, 21));
        let mut want = Vec::new();
        crate::csv::write_rolling_history(&mut want, &run.result.samples).unwrap();
        if let Some(reason) = incomplete {
            want.extend(format!("# incomplete: {reason}\n").bytes());
        }
        assert_eq!(std::fs::read(&csv).unwrap(), want);
        let pvd = std::fs::read_to_string(vtk.join("series.pvd")).unwrap();
        assert_eq!(pvd.matches("<DataSet").count(), 21);
        assert_eq!(pvd.contains("<!-- incomplete: "), incomplete.is_some());
        assert_eq!(listing(&dir), ["r.csv", "vtk"]);
    }
}
