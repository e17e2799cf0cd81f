//! Run monitors: total energy, bar-length drift, ‖N P − D‖, and the NaN / blow-up guard.
//!
//! Energy E = Σ_bars (m/6)(‖v_a‖² + ‖v_b‖² + v_a·v_b) (that is ½m‖ṙ‖² + ½J‖ḃ‖², J = m/12)
//! plus Σ_strings ½k(‖s‖ − s0)₊² and Σ_clusters ½k(L − L₀)₊² (module `cluster_forces`), minus Σ_nodes w·x (constant loads and gravity), plus
//! Σ ½k_g δ² (penalty ground). It is conserved without damping, friction, actuation or the
//! thesis ground model.

use super::model::{vec3, Model, NodeRef};
use nalgebra::Vector3;
use tensegrity_core::error::{CoreError, DynamicsError, StepHint};
use tensegrity_core::structure::MemberId;

impl Model {
    /// Kinetic energy (J) of a state.
    pub fn kinetic_energy(&self, y: &[f64]) -> f64 {
        let v = &y[3 * self.n1..];
        self.bars
            .iter()
            .enumerate()
            .map(|(k, b)| {
                let va = vec3(v, 2 * k);
                let vb = vec3(v, 2 * k + 1);
                b.mass / 6.0 * (va.norm_squared() + vb.norm_squared() + va.dot(&vb))
            })
            .sum()
    }

    /// Potential energy (J): strings (static rest lengths), clusters, constant loads and
    /// gravity, ground.
    pub fn potential_energy(&self, y: &[f64]) -> f64 {
        self.potential_energy_with(y, None)
    }

    /// Potential energy (J) with the string and cluster rest lengths `rest` (one per string,
    /// then one per cluster; `None`: the static ones).
    pub fn potential_energy_with(&self, y: &[f64], rest: Option<&[f64]>) -> f64 {
        let x = &y[..3 * self.n1];
        let pos = |r: NodeRef| match r {
            NodeRef::Free(i) => vec3(x, i),
            NodeRef::Anchor(p) => p,
        };
        let n_s = self.strings.len();
        let rest_of = |k: usize, fixed: f64| rest.map_or(fixed, |r| r[k]);
        let strings: f64 = self
            .strings
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let s0 = rest_of(k, s.law.rest_length);
                s.law.potential(&(pos(s.ends[1]) - pos(s.ends[0])), s0)
            })
            .sum();
        let loads: f64 = self
            .w_const
            .iter()
            .enumerate()
            .map(|(i, w)| -w.dot(&vec3(x, i)))
            .sum();
        let ground: f64 = match &self.ground {
            Some(g) => self
                .contact
                .iter()
                .map(|&(_, c)| g.potential(&vec3(x, c)))
                .sum(),
            None => 0.0,
        };
        let clusters: f64 = self
            .clusters
            .iter()
            .enumerate()
            .map(|(k, c)| c.potential_at(x, rest_of(n_s + k, c.rest_length)))
            .sum();
        strings + clusters + loads + ground
    }

    /// Total energy (J).
    pub fn energy(&self, y: &[f64]) -> f64 {
        self.kinetic_energy(y) + self.potential_energy(y)
    }

    /// max_k |‖b_k‖ − l_k| (m).
    pub fn bar_length_error(&self, y: &[f64]) -> f64 {
        self.bars
            .iter()
            .enumerate()
            .map(|(k, b)| ((vec3(y, 2 * k + 1) - vec3(y, 2 * k)).norm() - b.length0).abs())
            .fold(0.0, f64::max)
    }

    /// max |N P − D| over all constraint components (m).
    pub fn constraint_error(&self, y: &[f64]) -> f64 {
        if let Some(rows) = &self.axis_rows {
            // Σ s x − target = −(−Σ s x) − target, exact for finite states (s = ±1); a
            // non-finite row is skipped, as the NaN of the general form below is by `max`
            return rows
                .iter()
                .zip(&self.linear_rows)
                .map(|(a, r)| (-a.neg_dot(y) - r.target).abs())
                .filter(|e| !e.is_infinite())
                .fold(0.0, f64::max);
        }
        self.linear_rows
            .iter()
            .map(|r| {
                (r.row
                    .entries
                    .iter()
                    .flatten()
                    .map(|e| e.grad.dot(&vec3(y, e.node)))
                    .sum::<f64>()
                    - r.target)
                    .abs()
            })
            .fold(0.0, f64::max)
    }

    /// Checks a state for NaN/∞ and for nodes farther than `limit` from their initial
    /// position; the error names the time and the bar owning the node (for a blow-up, the
    /// node that moved farthest).
    pub fn check_state(&self, t: f64, y: &[f64], limit: f64) -> Result<(), CoreError> {
        let v = &y[3 * self.n1..];
        // squared distances: no square root per node and step
        let limit2 = limit * limit;
        let mut worst: Option<(usize, f64)> = None;
        let nodes = y[..3 * self.n1]
            .chunks_exact(3)
            .zip(v.chunks_exact(3))
            .zip(self.x0.chunks_exact(3));
        for (i, ((x, v), x0)) in nodes.enumerate() {
            if !(x.iter().all(|c| c.is_finite()) && v.iter().all(|c| c.is_finite())) {
                return Err(DynamicsError::NonFiniteState {
                    t,
                    member: MemberId::Bar(i / 2),
                    hint: StepHint::Unknown,
                }
                .into());
            }
            let d2 =
                (Vector3::new(x[0], x[1], x[2]) - Vector3::new(x0[0], x0[1], x0[2])).norm_squared();
            if d2 > limit2 && worst.is_none_or(|(_, d)| d2 > d) {
                worst = Some((i, d2));
            }
        }
        match worst {
            Some((i, d2)) => Err(DynamicsError::BlowUp {
                t,
                member: MemberId::Bar(i / 2),
                distance: d2.sqrt(),
                limit,
                hint: StepHint::Unknown,
            }
            .into()),
            None => Ok(()),
        }
    }

    /// A default blow-up distance: 10⁶ × (1 m + the initial extent of the structure).
    pub fn default_blowup_limit(&self) -> f64 {
        let n = self.n1.max(1);
        let c = (0..self.n1)
            .map(|i| vec3(&self.x0, i))
            .sum::<Vector3<f64>>()
            / n as f64;
        let extent = (0..self.n1)
            .map(|i| (vec3(&self.x0, i) - c).norm())
            .fold(0.0, f64::max);
        1e6 * (1.0 + extent)
    }
}

/// Running maxima of the monitored quantities.
#[derive(Debug, Clone, PartialEq)]
pub struct Monitor {
    /// Initial total energy.
    pub energy0: f64,
    /// Largest |E − E₀|.
    pub max_energy_error: f64,
    /// Largest E − E₀ (≥ 0): the energy gained.
    pub max_energy_gain: f64,
    /// Largest kinetic energy seen (energy scale when E₀ ≈ 0).
    pub max_kinetic: f64,
    /// Largest bar-length error (m).
    pub bar_length_drift: f64,
    /// Largest ‖N P − D‖ component (m).
    pub constraint_drift: f64,
}

impl Monitor {
    /// Starts monitoring at the initial state.
    pub fn new(model: &Model, y0: &[f64]) -> Self {
        let ke = model.kinetic_energy(y0);
        Self {
            energy0: ke + model.potential_energy(y0),
            max_energy_error: 0.0,
            max_energy_gain: 0.0,
            max_kinetic: ke,
            bar_length_drift: model.bar_length_error(y0),
            constraint_drift: model.constraint_error(y0),
        }
    }

    /// Updates the maxima with a new state.
    pub fn observe(&mut self, model: &Model, y: &[f64]) {
        let ke = model.kinetic_energy(y);
        let e = ke + model.potential_energy(y);
        self.max_kinetic = self.max_kinetic.max(ke);
        self.max_energy_error = self.max_energy_error.max((e - self.energy0).abs());
        self.max_energy_gain = self.max_energy_gain.max(e - self.energy0);
        self.bar_length_drift = self.bar_length_drift.max(model.bar_length_error(y));
        self.constraint_drift = self.constraint_drift.max(model.constraint_error(y));
    }

    /// Max relative energy drift: max|E − E₀| / max(|E₀|, max kinetic energy).
    pub fn energy_drift(&self) -> f64 {
        self.relative(self.max_energy_error)
    }

    /// Max relative energy gain: max(E − E₀) / max(|E₀|, max kinetic energy).
    pub fn energy_gain(&self) -> f64 {
        self.relative(self.max_energy_gain)
    }

    /// `x` over the energy scale max(|E₀|, max kinetic energy) (itself when that is 0).
    fn relative(&self, x: f64) -> f64 {
        let scale = self.energy0.abs().max(self.max_kinetic);
        if scale > 0.0 {
            x / scale
        } else {
            x
        }
    }
}
