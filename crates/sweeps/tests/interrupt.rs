//! A sweep stopped by an interrupt: whole rows in order and an `# incomplete` line, which
//! `resume` cuts off to finish the single run's file; `merge` refuses such a file; a second
//! sweep of the same file is refused while the first runs. One test, in a test binary of its
//! own: the interrupt flag is process-wide (in the shared binary it stopped another test's
//! sweep running beside it).

use std::path::Path;
use sweeps::{merge, run, Progress, RunOptions, Silent, Spec, SweepError};
use tensegrity_io::interrupt;

const TIPOVER: &str = r#"
study = "tipover"
[fixed]
outer_radius = 1.0
[axes]
sides = [6, 8, 10, 12]
sigma = { from = 0.2, to = 0.8, step = 0.1 }
epsilon = [0.25, 0.5]
"#;

/// Requests a stop after `after` rows, and tries a second sweep of the same file meanwhile.
struct StopAfter<'a> {
    after: usize,
    rows: usize,
    spec: &'a Spec,
    out: &'a Path,
    second: Option<String>,
}

impl Progress for StopAfter<'_> {
    fn row(&mut self, _error: bool) {
        self.rows += 1;
        if self.rows == 1 {
            let e = run(self.spec, self.out, &RunOptions::default(), &mut Silent).unwrap_err();
            self.second = Some(e.to_string());
        }
        if self.rows == self.after {
            interrupt::request();
        }
    }
}

#[test]
fn an_interrupted_sweep_is_marked_incomplete_and_resumes_to_the_single_run() {
    let dir = tempfile::tempdir().unwrap();
    let spec = Spec::parse(TIPOVER).unwrap();
    let single = dir.path().join("single.csv");
    let opts = RunOptions {
        threads: Some(3),
        ..RunOptions::default()
    };
    run(&spec, &single, &opts, &mut Silent).unwrap();
    let want = std::fs::read_to_string(&single).unwrap();

    let cut = dir.path().join("cut.csv");
    let mut progress = StopAfter {
        after: 5,
        rows: 0,
        spec: &spec,
        out: &cut,
        second: None,
    };
    let e = run(&spec, &cut, &opts, &mut progress).unwrap_err();
    let second = progress.second.take().unwrap();
    assert!(
        second.contains("another run") && second.contains("cut.csv"),
        "{second}"
    );
    let SweepError::Interrupted { done, total, .. } = e else {
        panic!("{e:?}")
    };
    assert!((5..total).contains(&done), "{done} of {total}");
    let text = std::fs::read_to_string(&cut).unwrap();
    let (body, last) = text.trim_end().rsplit_once('\n').unwrap();
    assert!(
        last.starts_with("# incomplete: interrupted after "),
        "{last}"
    );
    assert!(
        want.starts_with(&format!("{body}\n")),
        "whole rows, in case order"
    );
    assert_eq!(body.lines().count(), done + 1);
    let e = merge(std::slice::from_ref(&cut), &dir.path().join("merged.csv")).unwrap_err();
    assert!(e.to_string().contains("interrupted"), "{e}");

    interrupt::clear();
    let resume = RunOptions {
        resume: true,
        ..opts
    };
    let s = run(&spec, &cut, &resume, &mut Silent).unwrap();
    assert_eq!((s.resumed, s.resumed + s.written), (done, total));
    assert_eq!(std::fs::read_to_string(&cut).unwrap(), want);
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(names.len(), 2, "no lock file left: {names:?}");
}
