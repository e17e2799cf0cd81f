//! The toroid as a wheel description for the rolling models of wheel-rolling
//! ([`wheel_rolling::Wheel`]): its contact polygon (n prisms, R_o, m, I₁), its nodes in the
//! starting pose (the built wheel turned by −π/n about the axle x, standing on prisms 0 and
//! 1), and for the full model its [`WheelScene`]: the prestressed structure (prestress design
//! with a smallest string tension, strings of a given stiffness) in that pose, contact group
//! k = the outer tread nodes n1, n2 of prism k, ω from the rim joints n3, the axle ends as the
//! hub.

use crate::analysis::{prestress_design, prestressed_structure, ToroidAnalysis};
use crate::builder::Toroid;
use crate::error::{Result, ToroidError};
use nalgebra::{Rotation3, Vector3};
use std::f64::consts::PI;
use wheel_rolling::{Polygon, RollingSample, WheelFrame, WheelScene};

/// A built toroid with what its full model needs.
#[derive(Debug, Clone)]
pub struct ToroidWheel<'a> {
    /// The built wheel.
    pub toroid: &'a Toroid,
    /// Its analysis (mass and I₁).
    pub analysis: &'a ToroidAnalysis,
    /// String stiffness of the full model (N/m).
    pub string_stiffness: f64,
    /// Smallest string tension of the full model's prestress design (N).
    pub min_tension: f64,
}

impl wheel_rolling::Wheel for ToroidWheel<'_> {
    type Error = ToroidError;

    fn polygon(&self) -> Polygon {
        Polygon {
            sides: self.toroid.params.sides,
            outer_radius: self.toroid.params.outer_radius,
            mass: self.analysis.mass_kg,
            i1: self.analysis.i1,
        }
    }

    fn start_pose(&self) -> Vec<Vector3<f64>> {
        start_pose(self.toroid)
    }

    fn scene(&self) -> Result<WheelScene> {
        scene(self.toroid, self.string_stiffness, self.min_tension)
    }
}

/// The toroid's nodes turned by −π/n about x: the wheel standing on prisms 0 and 1, hub at
/// the origin.
pub fn start_pose(toroid: &Toroid) -> Vec<Vector3<f64>> {
    let turn = Rotation3::from_axis_angle(&Vector3::x_axis(), -PI / toroid.params.sides as f64);
    toroid.structure.nodes().iter().map(|p| turn * p).collect()
}

/// The toroid as a [`WheelScene`] (module docs): prestress design with `min_tension` (N),
/// strings of `string_stiffness` (N/m).
///
/// ```
/// use toroid::{roll::scene, WheelSpec};
/// let t = WheelSpec::with_sides(8).build().unwrap();
/// let s = scene(&t, 2e4, 20.0).unwrap();
/// assert!(s.validate().is_ok());
/// assert_eq!((s.sides(), s.contact_groups[1].clone()), (8, vec![5, 6]));
/// ```
pub fn scene(toroid: &Toroid, string_stiffness: f64, min_tension: f64) -> Result<WheelScene> {
    let design = prestress_design(toroid, min_tension)?;
    let n = toroid.params.sides;
    let turn = Rotation3::from_axis_angle(&Vector3::x_axis(), -PI / n as f64);
    let prestressed = prestressed_structure(toroid, &design, string_stiffness)?;
    let nodes = prestressed.nodes().iter().map(|p| turn * p).collect();
    let s = &toroid.structure;
    Ok(WheelScene {
        structure: prestressed.with_nodes(nodes)?,
        contact_groups: (0..n).map(|k| vec![5 * k, 5 * k + 1]).collect(),
        rim: (0..n).map(|k| 5 * k + 2).collect(),
        axle: toroid.axle,
        outer_radius: toroid.params.outer_radius,
        mass: crate::wheel_mass(s),
        i1: crate::wheel_inertia(s)[(0, 0)],
    })
}

/// The rigid wheel's nodes at the sample nearest to each of `times` (in time order; see
/// [`wheel_rolling::frames`]).
///
/// ```
/// use toroid::roll::rigid_frames;
/// use toroid::{build, ToroidParams};
/// use wheel_rolling::RollingSample;
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let r = (std::f64::consts::PI / 8.0).cos();
/// let at_rest = RollingSample { t: 0.0, s: -(std::f64::consts::PI / 8.0).sin(), h: r,
///     pivot: 0.0, omega: 0.0, normal: 0.0, tangential: 0.0, energy: 0.0, slip: 0.0 };
/// let f = rigid_frames(&t, &[at_rest], &[0.0]);
/// // prisms 0 and 1 stand on the slope (h = 0) at s = −2 R_o sin(π/8) and s = 0
/// assert!(f[0].nodes[0].z.abs() < 1e-12 && f[0].nodes[5].z.abs() < 1e-12);
/// assert!(f[0].nodes[5].y.abs() < 1e-12);
/// ```
pub fn rigid_frames(toroid: &Toroid, samples: &[RollingSample], times: &[f64]) -> Vec<WheelFrame> {
    wheel_rolling::frames::rigid_frames(&start_pose(toroid), samples, times)
}
