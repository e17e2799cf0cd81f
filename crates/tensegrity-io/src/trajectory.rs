//! Streamed trajectory CSV: one row per recorded sample, written as the run produces it
//! (bounded memory) through a [`CsvSink`] — locked, into a temporary file beside the target
//! that is renamed into place when the run ends — so a killed process never leaves a
//! truncated file at the requested path.
//!
//! Columns (all numbers `{:.17e}`, exact round trip), each group present when recorded:
//! `t [s]`; positions `n{i}_x [m]`, `n{i}_y [m]`, `n{i}_z [m]`; velocities `v{i}_x [m/s]`…;
//! axial member forces, tension positive, `{member}_force [N]` with members named
//! `bar{k}` / `string{k}`, then one per clustered string `cluster{c}` (its one tension), and
//! with positions their force densities `{member}_force_density [N/m]` (force over current
//! length; a cluster's over its whole length); `kinetic_energy [J]`, `total_energy [J]`; ground contact forces
//! `c{node}_x [N]`… of every contact node. With positions only, the file is exactly the one
//! [`crate::csv::write_trajectory`] writes.
//!
//! An interrupted run ends with [`TrajectoryWriter::finish_incomplete`]: the rows so far, then a
//! trailer line starting with `#` that says why the file is incomplete.

use crate::error::Result;
use crate::sink::CsvSink;
use std::path::Path;
use tensegrity_core::{MemberId, Structure};
use tensegrity_dynamics::Sample;

/// A trajectory CSV being written (see the module documentation).
///
/// ```
/// use tensegrity_dynamics::{Quantities, Simulation, SimulationSettings};
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_io::trajectory::TrajectoryWriter;
/// let s = Structure::builder().nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1).mass(1.0)).build().unwrap();
/// let settings = SimulationSettings {
///     t_end: 0.1,
///     output_interval: Some(0.05),
///     quantities: Quantities { nodes: true, energy: true, ..Default::default() },
///     ..Default::default()
/// };
/// let path = std::env::temp_dir().join(format!("traj-doc-{}.csv", std::process::id()));
/// let mut w = TrajectoryWriter::create(&path, &s)?; // fails here, before any work, on a bad path
/// let sim = Simulation::new(&s, settings).unwrap();
/// let mut sink = Vec::new();
/// sim.run_streaming(&mut sink).unwrap();
/// for sample in &sink { w.write(sample)?; }
/// assert_eq!(w.finish()?, 3);
/// let text = std::fs::read_to_string(&path).unwrap();
/// assert!(text.starts_with("t [s],n0_x [m],n0_y [m],n0_z [m],n1_x [m],n1_y [m],n1_z [m],kinetic_energy [J],total_energy [J]\n"));
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct TrajectoryWriter {
    sink: CsvSink,
    members: Vec<String>,
    /// The nodes of every member, then of every cluster (its length: the path through them).
    ends: Vec<Vec<usize>>,
    header_written: bool,
}

impl TrajectoryWriter {
    /// Opens the output now (a [`CsvSink`]: locked, temporary file beside `path`), so a
    /// missing directory, an unwritable path or another writer fails before the run starts.
    pub fn create(path: &Path, structure: &Structure) -> Result<Self> {
        let sink = CsvSink::open_records(path, "trajectory CSV")?;
        let clusters = structure.clusters();
        let members = (0..structure.n_members())
            .map(|k| match structure.member_id(k) {
                MemberId::Bar(i) => format!("bar{i}"),
                MemberId::String(i) => format!("string{i}"),
            })
            .chain((0..clusters.len()).map(|c| format!("cluster{c}")))
            .collect();
        let ends = structure
            .member_nodes()
            .into_iter()
            .map(|e| e.to_vec())
            .chain(clusters.iter().map(|c| c.nodes.clone()))
            .collect();
        Ok(Self {
            sink,
            members,
            ends,
            header_written: false,
        })
    }

    /// Appends one sample (the header is written from the first sample's recorded groups).
    pub fn write(&mut self, s: &Sample) -> Result<()> {
        if !self.header_written {
            let header = self.header(s);
            self.sink.record(&header)?;
            self.header_written = true;
        }
        self.sink.record(row(s, &self.ends))
    }

    /// Rows written so far (the header not counted).
    pub fn rows(&self) -> usize {
        self.sink
            .rows()
            .saturating_sub(usize::from(self.header_written))
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        self.sink.path()
    }

    /// Flushes and renames the file into place; returns the number of rows.
    pub fn finish(self) -> Result<usize> {
        let rows = self.rows();
        self.sink.finish()?;
        Ok(rows)
    }

    /// Ends an interrupted run: the rows so far, then `# incomplete: {note}`, renamed into
    /// place as a complete, valid file (nothing written yet: no file). Returns the rows kept.
    pub fn finish_incomplete(self, note: &str) -> Result<usize> {
        let rows = self.rows();
        self.sink.finish_incomplete(note)?;
        Ok(rows)
    }

    fn header(&self, s: &Sample) -> Vec<String> {
        let mut h = vec!["t [s]".to_string()];
        let xyz = |h: &mut Vec<String>, prefix: &str, n: usize, unit: &str| {
            for i in 0..n {
                for axis in ["x", "y", "z"] {
                    h.push(format!("{prefix}{i}_{axis} [{unit}]"));
                }
            }
        };
        if let Some(n) = &s.nodes {
            xyz(&mut h, "n", n.len(), "m");
        }
        if let Some(v) = &s.velocities {
            xyz(&mut h, "v", v.len(), "m/s");
        }
        if s.member_forces.is_some() {
            h.extend(self.members.iter().map(|m| format!("{m}_force [N]")));
            if s.nodes.is_some() {
                h.extend(
                    self.members
                        .iter()
                        .map(|m| format!("{m}_force_density [N/m]")),
                );
            }
        }
        if s.energy.is_some() {
            h.extend(["kinetic_energy [J]".into(), "total_energy [J]".into()]);
        }
        for (node, _) in s.contact_forces.iter().flatten() {
            for axis in ["x", "y", "z"] {
                h.push(format!("c{node}_{axis} [N]"));
            }
        }
        h
    }
}

fn row(s: &Sample, ends: &[Vec<usize>]) -> Vec<String> {
    let f = |v: f64| format!("{v:.17e}");
    let mut r = vec![f(s.t)];
    for p in s.nodes.iter().chain(&s.velocities).flatten() {
        r.extend([p.x, p.y, p.z].map(f));
    }
    r.extend(s.member_forces.iter().flatten().map(|&v| f(v)));
    if let (Some(forces), Some(nodes)) = (&s.member_forces, &s.nodes) {
        // q = force / current length (tension positive)
        r.extend(forces.iter().zip(ends).map(|(&force, path)| {
            let length: f64 = path
                .windows(2)
                .map(|w| (nodes[w[1]] - nodes[w[0]]).norm())
                .sum();
            f(force / length)
        }));
    }
    if let Some((k, e)) = s.energy {
        r.extend([f(k), f(e)]);
    }
    for (_, c) in s.contact_forces.iter().flatten() {
        r.extend([c.x, c.y, c.z].map(f));
    }
    r
}
