//! The statics estimate bounds the real allocation (issue 26): the kernel's peak resident
//! memory of this test process (Linux: /proc/self/status, reset through clear_refs) measures
//! what the statics of a zig-zag chain holds on the dense path (the SVD with its U and V) and
//! on the sparse path (the QR's profile and the mechanisms' basis), and each stays below the
//! engine's estimate from the matrix dimensions — within a factor that keeps the estimate
//! honest.

use tensegrity_core::statics::StaticsMethod;
use tensegrity_engine::scene::SceneSource;
use tensegrity_engine::statics::{estimate, statics, StaticsCommand};

/// A field of /proc/self/status in bytes (`VmRSS`, `VmHWM`).
fn status(key: &str) -> f64 {
    let text = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = text.lines().find(|l| l.starts_with(key)).unwrap();
    let kb: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    1024.0 * kb
}

/// A planar zig-zag chain of `n` nodes: bars between neighbours, strings between every other
/// node (rank 2n − 3, n + 3 mechanisms out of its plane).
fn chain(n: usize) -> String {
    let mut s = String::from("nodes = [\n");
    for i in 0..n {
        s += &format!("  [{i}.0, {}, 0.0],\n", 0.5 * (i % 2) as f64);
    }
    s += "]\n";
    for i in 0..n - 1 {
        s += &format!("[[bars]]\nnodes = [{i}, {}]\n", i + 1);
    }
    for i in 0..n - 2 {
        s += &format!("[[strings]]\nnodes = [{i}, {}]\n", i + 2);
    }
    s
}

/// The estimate, the measured peak resident memory above what was resident before (the
/// kernel's high-water mark, reset first), and the rank of the statics of a chain of `n`
/// nodes by `method`.
fn measured(n: usize, method: StaticsMethod) -> (f64, f64, usize) {
    let command = StaticsCommand {
        scene: Some(SceneSource::Toml(chain(n))),
        method,
        ..StaticsCommand::default()
    };
    let scene = command.source().unwrap().load().unwrap();
    let e = estimate(&scene.structure, &command).unwrap();
    drop(scene);
    std::fs::write("/proc/self/clear_refs", "5").unwrap();
    let before = status("VmRSS");
    let report = statics(&command).unwrap();
    let peak = status("VmHWM") - before;
    (e.memory_bytes, peak, report.rank)
}

#[test]
fn the_statics_estimate_bounds_the_measured_peak_on_both_paths() {
    if std::fs::write("/proc/self/clear_refs", "5").is_err() {
        // no kernel high-water mark to reset (not Linux, or a restricted /proc): nothing to measure
        eprintln!("note: /proc/self/clear_refs is not writable here; the measurement is skipped");
        return;
    }
    // dense: 600 nodes, the SVD of 1800 dofs × 1197 members with U and V (109 MB estimated)
    let (estimated, peak, rank) = measured(600, StaticsMethod::Dense);
    eprintln!("dense: estimated {estimated:.3e} B, peak {peak:.3e} B");
    assert_eq!(rank, 2 * 600 - 3);
    assert!(
        peak <= estimated,
        "dense: peak {peak} B above the estimate {estimated} B"
    );
    assert!(
        estimated <= 20.0 * peak,
        "dense: {estimated} B for a peak of {peak} B"
    );
    // sparse: 3000 nodes, 9000 dofs × 5997 members, 3003 mechanisms
    let (estimated, peak, rank) = measured(3000, StaticsMethod::Auto);
    eprintln!("sparse: estimated {estimated:.3e} B, peak {peak:.3e} B");
    assert_eq!(rank, 2 * 3000 - 3);
    assert!(
        peak <= estimated,
        "sparse: peak {peak} B above the estimate {estimated} B"
    );
    assert!(
        estimated <= 20.0 * peak,
        "sparse: {estimated} B for a peak of {peak} B"
    );
}
