//! Streamed trajectory CSV: one row per recorded sample, written as the run produces it
//! (bounded memory), into a temporary file beside the target that is renamed into place when
//! the run ends — so a killed process never leaves a truncated file at the requested path.
//!
//! Columns (all numbers `{:.17e}`, exact round trip), each group present when recorded:
//! `t [s]`; positions `n{i}_x [m]`, `n{i}_y [m]`, `n{i}_z [m]`; velocities `v{i}_x [m/s]`…;
//! axial member forces, tension positive, `{member}_force [N]` with members named
//! `bar{k}` / `string{k}`, and with positions their force densities
//! `{member}_force_density [N/m]` (force over current length); `kinetic_energy [J]`, `total_energy [J]`; ground contact forces
//! `c{node}_x [N]`… of every contact node. With positions only, the file is exactly the one
//! [`crate::csv::write_trajectory`] writes.
//!
//! An interrupted run ends with [`TrajectoryWriter::finish_incomplete`]: the rows so far, then a
//! trailer line starting with `#` that says why the file is incomplete.

use crate::error::{IoError, Result};
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use tensegrity_core::dynamics::Sample;
use tensegrity_core::{MemberId, Structure};

/// A trajectory CSV being written (see the module documentation).
///
/// ```
/// use tensegrity_core::dynamics::{Quantities, Simulation, SimulationSettings};
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
    path: PathBuf,
    tmp: PathBuf,
    out: Option<::csv::Writer<File>>,
    members: Vec<String>,
    ends: Vec<[usize; 2]>,
    header_written: bool,
    rows: usize,
}

impl TrajectoryWriter {
    /// Opens the temporary file beside `path` now, so a missing directory or an unwritable
    /// path fails before the run starts.
    pub fn create(path: &Path, structure: &Structure) -> Result<Self> {
        let tmp = crate::temporary_path(path);
        let file = File::create(&tmp).map_err(|source| IoError::Write {
            path: path.to_path_buf(),
            source,
        })?;
        let members = (0..structure.n_members())
            .map(|k| match structure.member_id(k) {
                MemberId::Bar(i) => format!("bar{i}"),
                MemberId::String(i) => format!("string{i}"),
            })
            .collect();
        Ok(Self {
            path: path.to_path_buf(),
            tmp,
            out: Some(::csv::Writer::from_writer(file)),
            members,
            ends: structure.member_nodes(),
            header_written: false,
            rows: 0,
        })
    }

    /// Appends one sample (the header is written from the first sample's recorded groups).
    pub fn write(&mut self, s: &Sample) -> Result<()> {
        if !self.header_written {
            let header = self.header(s);
            self.record(&header)?;
            self.header_written = true;
        }
        let row = row(s, &self.ends);
        self.record(&row)?;
        self.rows += 1;
        Ok(())
    }

    /// Rows written so far.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Flushes and renames the file into place; returns the number of rows.
    pub fn finish(mut self) -> Result<usize> {
        self.close()
    }

    /// Ends an interrupted run: the rows so far, then `# incomplete: {note}`, renamed into
    /// place as a complete, valid file.
    pub fn finish_incomplete(mut self, note: &str) -> Result<usize> {
        let path = &self.path;
        let write_err = |source| IoError::Write {
            path: path.clone(),
            source,
        };
        let out = self.out.take().expect("open until finished");
        // a comment line, outside the CSV grammar: written past the csv writer
        let mut file = out.into_inner().map_err(|e| write_err(e.into_error()))?;
        let note = note.replace('\n', " ");
        writeln!(file, "# incomplete: {note}").map_err(write_err)?;
        drop(file);
        self.close()
    }

    fn close(&mut self) -> Result<usize> {
        let write_err = |source| IoError::Write {
            path: self.path.clone(),
            source,
        };
        if let Some(mut out) = self.out.take() {
            out.flush().map_err(write_err)?;
        }
        std::fs::rename(&self.tmp, &self.path).map_err(write_err)?;
        Ok(self.rows)
    }

    fn record(&mut self, fields: &[String]) -> Result<()> {
        let out = self.out.as_mut().expect("open until finished");
        out.write_record(fields).map_err(|e| IoError::Write {
            path: self.path.clone(),
            source: e.into(),
        })
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

impl Drop for TrajectoryWriter {
    /// A writer dropped without `finish` (an error elsewhere) removes its temporary file.
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

fn row(s: &Sample, ends: &[[usize; 2]]) -> Vec<String> {
    let f = |v: f64| format!("{v:.17e}");
    let mut r = vec![f(s.t)];
    for p in s.nodes.iter().chain(&s.velocities).flatten() {
        r.extend([p.x, p.y, p.z].map(f));
    }
    r.extend(s.member_forces.iter().flatten().map(|&v| f(v)));
    if let (Some(forces), Some(nodes)) = (&s.member_forces, &s.nodes) {
        // q = force / current length (tension positive)
        r.extend(
            forces
                .iter()
                .zip(ends)
                .map(|(&force, &[i, j])| f(force / (nodes[j] - nodes[i]).norm())),
        );
    }
    if let Some((k, e)) = s.energy {
        r.extend([f(k), f(e)]);
    }
    for (_, c) in s.contact_forces.iter().flatten() {
        r.extend([c.x, c.y, c.z].map(f));
    }
    r
}
