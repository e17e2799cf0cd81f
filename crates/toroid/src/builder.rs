//! Builds the toroid as a core [`Structure`] (thesis §3.1, corrected by ERRATA 3.1–3.2).
//!
//! Prism 0 has nodes
//! n1 = [T/2, 0, −R_o], n2 = [−T/2, 0, −R_o], n3 = [0, −R_m tan(π/n), −R_m],
//! n4 = [−t/2, −D, −R_i], n5 = [t/2, D, −R_i], n6 = [0, R_m tan(π/n), −R_m];
//! prism k is prism 0 rotated by 2πk/n about the x axis (ι₁, the rolling axis), so n6 of prism
//! k is n3 of prism k+1 (a class-2 rim joint). Bars n1–n4, n2–n5 (tread) and n3–n6 (rim); the
//! 12 strings are the other pairs of the six nodes. Node numbering: prism k owns nodes
//! 5k..5k+4 = n1, n2, n3, n4, n5; with spokes the axle ends (∓T/2, 0, 0) are nodes 5n, 5n+1.

use crate::error::Result;
use crate::params::{Stabilize, ToroidParams};
use nalgebra::{Rotation3, Vector3};
use std::f64::consts::PI;
use tensegrity_core::{Bar, StringMember, Structure};

/// What a member does in the wheel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Role {
    /// A tread bar n1–n4 or n2–n5.
    TreadBar,
    /// The rim bar n3–n6.
    RimBar,
    /// The axle bar (spokes option).
    AxleBar,
    /// One of the 12 strings of a prism.
    PrismString,
    /// A spoke from a rim node to an axle end.
    Spoke,
    /// An inner tread ring string.
    InnerRing,
    /// An outer tread ring string.
    OuterRing,
}

/// The prism a member belongs to (if any) and its role.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemberLabel {
    /// Prism index k (the ring strings belong to the prism they start from).
    pub prism: Option<usize>,
    /// Role.
    pub role: Role,
}

/// A built toroid: the structure plus labels.
#[derive(Debug, Clone)]
pub struct Toroid {
    /// The parameters it was built from.
    pub params: ToroidParams,
    /// The stabilising options used.
    pub stabilize: Stabilize,
    /// The core structure (bars carry mass = bar density × length; strings are bare).
    pub structure: Structure,
    /// One label per bar.
    pub bar_labels: Vec<MemberLabel>,
    /// One label per string.
    pub string_labels: Vec<MemberLabel>,
    /// Axle end nodes when the spokes option is on.
    pub axle: Option<[usize; 2]>,
}

/// The six nodes n1..n6 of prism 0.
///
/// ```
/// use toroid::{prism_nodes, ToroidParams};
/// let p = ToroidParams::default();
/// let n = prism_nodes(&p);
/// assert_eq!(n[0].z, -p.outer_radius);
/// assert_eq!(n[5].z, -p.rim_radius); // ERRATA 3.1: −R_m, not −R_i
/// ```
pub fn prism_nodes(p: &ToroidParams) -> [Vector3<f64>; 6] {
    let tan = (PI / p.sides as f64).tan();
    [
        Vector3::new(p.outer_tread / 2.0, 0.0, -p.outer_radius),
        Vector3::new(-p.outer_tread / 2.0, 0.0, -p.outer_radius),
        Vector3::new(0.0, -p.rim_radius * tan, -p.rim_radius),
        Vector3::new(-p.inner_tread / 2.0, -p.offset, -p.inner_radius),
        Vector3::new(p.inner_tread / 2.0, p.offset, -p.inner_radius),
        Vector3::new(0.0, p.rim_radius * tan, -p.rim_radius),
    ]
}

/// Pairs (0-based local indices into n1..n6) of the three bars and the twelve strings.
const BARS: [(usize, usize); 3] = [(0, 3), (1, 4), (2, 5)];
const STRINGS: [(usize, usize); 12] = [
    (0, 1),
    (0, 2),
    (0, 4),
    (0, 5),
    (1, 2),
    (1, 3),
    (1, 5),
    (2, 3),
    (2, 4),
    (3, 4),
    (3, 5),
    (4, 5),
];

/// Rotation by 2πk/n about the x axis.
pub fn prism_rotation(k: usize, n: usize) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::x_axis(), 2.0 * PI * k as f64 / n as f64)
}

/// Builds the whole toroid with the given stabilising options; bars get mass
/// `bar_density` (kg/m) × length.
///
/// ```
/// use toroid::{build, Stabilize, ToroidParams};
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let s = &t.structure;
/// // 5n nodes + 2 axle ends, 3n + 1 bars, 12n + 2n spokes + 2n inner-ring strings
/// assert_eq!((s.n_nodes(), s.n_bars(), s.n_strings()), (42, 25, 128));
/// ```
pub fn build(p: &ToroidParams, stabilize: Stabilize, bar_density: f64) -> Result<Toroid> {
    p.validate()?;
    check_density(bar_density)?;
    let n = p.sides;
    let local = prism_nodes(p);
    // global index of local node j (0..6) of prism k
    let node = |k: usize, j: usize| -> usize {
        if j == 5 {
            5 * ((k + 1) % n) + 2
        } else {
            5 * k + j
        }
    };
    let mut positions: Vec<[f64; 3]> = Vec::with_capacity(5 * n + 2);
    for k in 0..n {
        let rot = prism_rotation(k, n);
        for x in &local[..5] {
            let y = rot * x;
            positions.push([y.x, y.y, y.z]);
        }
    }
    let mut bars: Vec<([usize; 2], MemberLabel)> = Vec::new();
    let mut strings: Vec<([usize; 2], MemberLabel)> = Vec::new();
    for k in 0..n {
        for (a, b) in BARS {
            let role = if a == 2 { Role::RimBar } else { Role::TreadBar };
            bars.push(([node(k, a), node(k, b)], label(k, role)));
        }
        for (a, b) in STRINGS {
            strings.push(([node(k, a), node(k, b)], label(k, Role::PrismString)));
        }
    }
    let mut axle = None;
    if stabilize.spokes {
        let (left, right) = (positions.len(), positions.len() + 1);
        positions.push([-p.outer_tread / 2.0, 0.0, 0.0]);
        positions.push([p.outer_tread / 2.0, 0.0, 0.0]);
        bars.push((
            [left, right],
            MemberLabel {
                prism: None,
                role: Role::AxleBar,
            },
        ));
        for k in 0..n {
            for end in [left, right] {
                strings.push(([node(k, 2), end], label(k, Role::Spoke)));
            }
        }
        axle = Some([left, right]);
    }
    let mut rings = |local_nodes: [usize; 2], role: Role| {
        for k in 0..n {
            for j in local_nodes {
                strings.push(([node(k, j), node((k + 1) % n, j)], label(k, role)));
            }
        }
    };
    if stabilize.inner {
        rings([3, 4], Role::InnerRing);
    }
    if stabilize.outer {
        rings([0, 1], Role::OuterRing);
    }
    finish(*p, stabilize, positions, bars, strings, axle, bar_density)
}

/// Builds one prism alone (six nodes, three bars, twelve strings: the complete graph K6).
///
/// ```
/// use toroid::{build_prism, ToroidParams};
/// let t = build_prism(&ToroidParams::default(), 1.0).unwrap();
/// assert_eq!((t.structure.n_nodes(), t.structure.n_bars(), t.structure.n_strings()), (6, 3, 12));
/// ```
pub fn build_prism(p: &ToroidParams, bar_density: f64) -> Result<Toroid> {
    p.validate()?;
    check_density(bar_density)?;
    let positions = prism_nodes(p).map(|x| [x.x, x.y, x.z]).to_vec();
    let bars = BARS
        .iter()
        .map(|&(a, b)| {
            let role = if a == 2 { Role::RimBar } else { Role::TreadBar };
            ([a, b], label(0, role))
        })
        .collect();
    let strings = STRINGS
        .iter()
        .map(|&(a, b)| ([a, b], label(0, Role::PrismString)))
        .collect();
    finish(
        *p,
        Stabilize::NONE,
        positions,
        bars,
        strings,
        None,
        bar_density,
    )
}

fn label(k: usize, role: Role) -> MemberLabel {
    MemberLabel {
        prism: Some(k),
        role,
    }
}

fn check_density(bar_density: f64) -> Result<()> {
    if !(bar_density.is_finite() && bar_density > 0.0) {
        return Err(crate::ToroidError::InvalidParameter(
            tensegrity_core::request::InvalidParameter::new(
                "bar_density",
                bar_density,
                "must be a positive mass per length (kg/m)",
            ),
        ));
    }
    Ok(())
}

fn finish(
    params: ToroidParams,
    stabilize: Stabilize,
    positions: Vec<[f64; 3]>,
    bars: Vec<([usize; 2], MemberLabel)>,
    strings: Vec<([usize; 2], MemberLabel)>,
    axle: Option<[usize; 2]>,
    bar_density: f64,
) -> Result<Toroid> {
    // members appended in bulk, by index (no per-member move of the builder)
    let structure = Structure::builder()
        .nodes(positions.iter().copied())
        .bars(bars.iter().map(|&([i, j], _)| {
            let l = (Vector3::from(positions[j]) - Vector3::from(positions[i])).norm();
            Bar::new(i, j).mass(bar_density * l)
        }))
        .strings(strings.iter().map(|&([i, j], _)| StringMember::new(i, j)))
        .build()?;
    Ok(Toroid {
        params,
        stabilize,
        structure,
        bar_labels: bars.into_iter().map(|(_, l)| l).collect(),
        string_labels: strings.into_iter().map(|(_, l)| l).collect(),
        axle,
    })
}
