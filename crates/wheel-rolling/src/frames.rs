//! Node frames of the rigid model: the wheel's nodes placed by the rigid pose, streamed as
//! the samples come.
//!
//! The rigid model records the axle (s, h) and the spin ω; the wheel's turn is
//! ψ(t) = ∫₀ᵗ ω dt (trapezoidal rule on the samples), positive rolling downhill (a negative
//! turn about the axle x). A node at p₀ in the starting pose (the wheel standing on the side
//! of its contact pairs 0 and 1, hub at the origin, axle along x; for the toroid the built
//! wheel turned by −π/n) is at (x, s, h) = (0, s_hub(t), h_hub(t)) + R_x(−ψ(t)) p₀ in slope
//! coordinates, the same coordinates as the full model's frames ([`WheelFrame`]). A frame
//! asked at time t shows the sample nearest to t (the earlier one on a tie). Its node
//! velocities are the rigid body's, v = v_hub − ω x̂ × R_x(−ψ) p₀, with v_hub the hub's
//! velocity between the sample and the one before it (zero at the first); a rigid body has no
//! member forces.

use crate::frame::WheelFrame;
use crate::sample::RollingSample;
use nalgebra::{Rotation3, Vector3};

/// Places the rigid wheel's nodes at the frame times as the samples arrive.
#[derive(Debug, Clone)]
pub struct RigidFrames {
    p0: Vec<Vector3<f64>>,
    times: Vec<f64>,
    next: usize,
    /// The previous sample, the turn ψ at it and the hub's velocity (s, h) there.
    prev: Option<(RollingSample, f64, [f64; 2])>,
}

impl RigidFrames {
    /// Frames of the nodes `start_pose` at `times` (sorted here; none when either is empty).
    pub fn new(start_pose: &[Vector3<f64>], times: &[f64]) -> Self {
        let mut times = if start_pose.is_empty() {
            Vec::new()
        } else {
            times.to_vec()
        };
        times.sort_by(f64::total_cmp);
        Self {
            p0: start_pose.to_vec(),
            times,
            next: 0,
            prev: None,
        }
    }

    fn place(&self, s: &RollingSample, psi: f64, hub_velocity: [f64; 2]) -> WheelFrame {
        let r = Rotation3::from_axis_angle(&Vector3::x_axis(), -psi);
        let hub = Vector3::new(0.0, s.s, s.h);
        let v_hub = Vector3::new(0.0, hub_velocity[0], hub_velocity[1]);
        let spin = Vector3::new(-s.omega, 0.0, 0.0);
        WheelFrame {
            t: s.t,
            nodes: self.p0.iter().map(|p| hub + r * p).collect(),
            velocities: self
                .p0
                .iter()
                .map(|p| v_hub + spin.cross(&(r * p)))
                .collect(),
            member_forces: Vec::new(),
        }
    }

    /// Takes the next sample; returns the frames whose time it completes.
    pub fn push(&mut self, s: &RollingSample) -> Vec<WheelFrame> {
        let (psi, v) = match &self.prev {
            Some((p, psi, _)) if s.t > p.t => (
                psi + 0.5 * (s.t - p.t) * (s.omega + p.omega),
                [(s.s - p.s) / (s.t - p.t), (s.h - p.h) / (s.t - p.t)],
            ),
            Some((_, psi, v)) => (*psi, *v),
            None => (0.0, [0.0; 2]),
        };
        let mut out = Vec::new();
        while self.next < self.times.len() && self.times[self.next] <= s.t {
            let t = self.times[self.next];
            let frame = match &self.prev {
                Some((p, p_psi, p_v)) if (p.t - t).abs() <= (s.t - t).abs() => {
                    self.place(p, *p_psi, *p_v)
                }
                _ => self.place(s, psi, v),
            };
            out.push(frame);
            self.next += 1;
        }
        self.prev = Some((*s, psi, v));
        out
    }

    /// The frames still due after the last sample (at it), when `complete`; none otherwise.
    pub fn finish(self, complete: bool) -> Vec<WheelFrame> {
        match (&self.prev, complete) {
            (Some((s, psi, v)), true) => (self.next..self.times.len())
                .map(|_| self.place(s, *psi, *v))
                .collect(),
            _ => Vec::new(),
        }
    }
}

/// Node frames of a rigid run from its recorded samples: the wheel's nodes `start_pose` at
/// the sample nearest to each of `times` (in time order).
///
/// ```
/// use nalgebra::Vector3;
/// use wheel_rolling::{frames::rigid_frames, RollingSample};
/// let at = |t: f64, s: f64| RollingSample { t, s, h: 1.0, pivot: 0.0, omega: 1.0,
///     normal: 0.0, tangential: 0.0, energy: 0.0, slip: 0.0 };
/// let f = rigid_frames(&[Vector3::new(0.0, 0.0, -1.0)], &[at(0.0, 0.0), at(1.0, 1.0)], &[0.9]);
/// // the node under the hub, turned by ψ = 1 rad rolling downhill, lags behind the hub
/// assert!((f[0].nodes[0].y - (1.0 - 1f64.sin())).abs() < 1e-12);
/// ```
pub fn rigid_frames(
    start_pose: &[Vector3<f64>],
    samples: &[RollingSample],
    times: &[f64],
) -> Vec<WheelFrame> {
    let mut placer = RigidFrames::new(start_pose, times);
    let mut frames: Vec<WheelFrame> = samples.iter().flat_map(|s| placer.push(s)).collect();
    frames.extend(placer.finish(true));
    frames
}
