//! Samples a run at requested output times only, and only the requested quantities.

use super::model::{Model, Workspace};
use crate::error::CoreError;
use nalgebra::Vector3;

/// Which quantities to record at each output time.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Quantities {
    /// Node positions (file numbering).
    pub nodes: bool,
    /// Node velocities (file numbering).
    pub velocities: bool,
    /// Axial member forces, tension positive, bars then strings (N).
    pub member_forces: bool,
    /// Kinetic and total energy (J).
    pub energy: bool,
    /// Ground contact forces on the contact nodes (N).
    pub contact_forces: bool,
}

impl Quantities {
    /// Positions only.
    pub fn nodes() -> Self {
        Self {
            nodes: true,
            ..Self::default()
        }
    }

    /// Everything.
    pub fn all() -> Self {
        Self {
            nodes: true,
            velocities: true,
            member_forces: true,
            energy: true,
            contact_forces: true,
        }
    }
}

/// One recorded sample.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Node positions, if requested.
    pub nodes: Option<Vec<Vector3<f64>>>,
    /// Node velocities, if requested.
    pub velocities: Option<Vec<Vector3<f64>>>,
    /// Member forces, if requested.
    pub member_forces: Option<Vec<f64>>,
    /// (kinetic, total) energy, if requested.
    pub energy: Option<(f64, f64)>,
    /// `(file node, force)` for every contact node, if requested.
    pub contact_forces: Option<Vec<(usize, Vector3<f64>)>>,
}

/// Collects samples at the requested times.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Recorder {
    times: Vec<f64>,
    next: usize,
    quantities: Quantities,
    /// The samples taken so far.
    pub samples: Vec<Sample>,
}

impl Recorder {
    /// A recorder for sorted output `times` (unsorted input is sorted, duplicates removed).
    pub fn new(mut times: Vec<f64>, quantities: Quantities) -> Self {
        times.retain(|t| t.is_finite());
        times.sort_by(f64::total_cmp);
        times.dedup();
        Self {
            samples: Vec::with_capacity(times.len()),
            times,
            next: 0,
            quantities,
        }
    }

    /// The next output time not yet sampled.
    pub fn next_time(&self) -> Option<f64> {
        self.times.get(self.next).copied()
    }

    /// The requested output times.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Records the state `y` at the next output time `t` and advances.
    pub fn record(
        &mut self,
        t: f64,
        y: &[f64],
        model: &Model,
        ws: &mut Workspace,
    ) -> Result<(), CoreError> {
        let q = self.quantities;
        let evals = ws.rhs_evals;
        let sample = Sample {
            t,
            nodes: q.nodes.then(|| model.nodes_of(y)),
            velocities: q.velocities.then(|| model.velocities_of(y)),
            member_forces: if q.member_forces {
                Some(model.member_forces(t, y, ws)?)
            } else {
                None
            },
            energy: q.energy.then(|| (model.kinetic_energy(y), model.energy(y))),
            contact_forces: q.contact_forces.then(|| model.contact_forces(t, y, ws)),
        };
        ws.rhs_evals = evals; // diagnostics do not count as integration work
        self.samples.push(sample);
        self.next += 1;
        Ok(())
    }
}
