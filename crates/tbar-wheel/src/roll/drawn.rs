//! The T-bar wheel of one row of `tbar roll` drawn over its run (an animation): the
//! structure whose members are drawn ([`TbarRollRequest::drawing`]) and the node frames of
//! its run handed to an observer ([`Watch`], [`TbarRollRequest::tbar_row_watched`]).
//!
//! The full model's frames are its nodes. The rigid model places the wheel's nodes by its
//! pose: the nodes in the starting pose p⁰ (the built wheel turned about ι̂₁ by
//! −π/2 − π/n, so that it stands on the tips of treads 0 and 1, hub at the origin, the same
//! pose as the full model's structure) move as a rigid body,
//! p(t) = c(t) + R(θ(t)) p⁰ with c the hub and θ the wheel's turn
//! ([`wheel_rolling::frames::rigid_frames`]).

use super::TbarRollRequest;
use crate::error::Result;
use crate::geometry::TbarGeometry;
use crate::params::RimMode;
use crate::rolling::MassProperties;
use crate::rolling_full::full_wheel;
use nalgebra::{Rotation3, Vector3};
use std::f64::consts::PI;
use tensegrity_core::Structure;
use wheel_rolling::{
    Fidelity, FidelityChoice, Observer, Polygon, RollingError, Wheel, WheelRun, WheelScene,
};

/// What a front end watches of a run: the times (s) of the node frames it wants and the
/// observer the frames are handed to.
pub struct Watch<'a> {
    /// Frame times (s).
    pub times: &'a [f64],
    /// Gets the frames (and the samples).
    pub observer: &'a mut dyn Observer,
}

/// The rigid polygon of a T-bar wheel with its nodes in the starting pose.
struct Posed {
    polygon: Polygon,
    nodes: Vec<Vector3<f64>>,
}

impl Wheel for Posed {
    type Error = RollingError;

    fn polygon(&self) -> Polygon {
        self.polygon
    }

    fn start_pose(&self) -> Vec<Vector3<f64>> {
        self.nodes.clone()
    }

    fn scene(&self) -> std::result::Result<WheelScene, RollingError> {
        self.polygon.scene()
    }
}

/// The nodes of `g` in the starting pose (module docs): turned about ι̂₁ by −π/2 − π/n.
pub fn start_pose(g: &TbarGeometry) -> Result<Vec<Vector3<f64>>> {
    let n = g.params.treads_per_wheel()?;
    let turn = Rotation3::from_axis_angle(&Vector3::x_axis(), -0.5 * PI - PI / n as f64);
    Ok(g.nodes.iter().map(|p| turn * p).collect())
}

impl TbarRollRequest {
    /// The structure of the row of `n` treads whose members an animation draws, numbered as
    /// the node frames of [`TbarRollRequest::tbar_row_watched`]: the T-bar geometry (rigid
    /// model) or the full model's wheel with its rim body (`full`, `auto`).
    pub fn drawing(&self, n: usize, rim: RimMode) -> Result<Structure> {
        let p = self.tbar_params(n, rim);
        match self.fidelity {
            FidelityChoice::Rigid => TbarGeometry::new(p)?.structure(),
            FidelityChoice::Full | FidelityChoice::Auto => {
                Ok(full_wheel(&p, &self.full_wheel_request())?.structure)
            }
        }
    }

    /// The rigid run of the polygon of `mp`, the nodes of `g` placed by its pose when
    /// watched.
    pub(super) fn posed_run(
        &self,
        g: &TbarGeometry,
        mp: &MassProperties,
        watch: Option<Watch>,
    ) -> Result<WheelRun> {
        let polygon = mp.polygon();
        let nodes = match watch {
            Some(_) => start_pose(g)?,
            None => Vec::new(),
        };
        let wheel = Posed { polygon, nodes };
        let r = self.checked_run(&wheel, FidelityChoice::Rigid, watch)?;
        Ok(WheelRun::of(Fidelity::Rigid, &polygon, &r.result, self.t_end()).because(r.reason))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wheel_rolling::{Flow, WheelFrame};

    /// Keeps the frames it is handed.
    struct Kept(Vec<WheelFrame>);

    impl Observer for Kept {
        fn frame(&mut self, frame: &WheelFrame) -> Flow {
            self.0.push(frame.clone());
            Flow::Continue
        }
    }

    #[test]
    fn the_rigid_run_places_the_nodes_as_a_rigid_body_standing_on_two_tips() {
        let r = TbarRollRequest {
            t_end: Some(0.5),
            ..TbarRollRequest::default()
        };
        let (n, rim) = (8, RimMode::Fixed);
        let times = [0.0, 0.25, 0.5];
        let mut kept = Kept(Vec::new());
        let watch = Watch {
            times: &times,
            observer: &mut kept,
        };
        let watched = r.tbar_row_watched(n, rim, Some(watch));
        // watching changes nothing in the row
        let plain = r.tbar_row(n, rim);
        assert_eq!(format!("{:?}", watched.tbar), format!("{:?}", plain.tbar));
        let frames = kept.0;
        assert_eq!(frames.len(), 3);
        let drawn = r.drawing(n, rim).unwrap();
        assert!(frames.iter().all(|f| f.nodes.len() == drawn.n_nodes()));
        // at t = 0 the tips of treads 0 and 1 touch the slope (h = 0), the others are above
        let g = TbarGeometry::new(r.tbar_params(n, rim)).unwrap();
        let p0 = &frames[0].nodes;
        for (k, &tip) in g.tips.iter().enumerate() {
            let h = p0[tip].z;
            match k {
                0 | 1 => assert!(h.abs() < 1e-9, "tip {k}: h = {h}"),
                _ => assert!(h > 1e-3, "tip {k}: h = {h}"),
            }
        }
        // later frames: the same distances between nodes (a rigid body), moved downhill
        let last = &frames[2].nodes;
        for i in 0..p0.len() {
            for j in 0..i {
                let (d0, d1) = ((p0[i] - p0[j]).norm(), (last[i] - last[j]).norm());
                assert!((d0 - d1).abs() < 1e-9, "nodes {i}, {j}: {d0} vs {d1}");
            }
        }
        let centre = |p: &[Vector3<f64>]| p.iter().sum::<Vector3<f64>>() / p.len() as f64;
        assert!(centre(last).y > centre(p0).y + 1e-3);
    }
}
