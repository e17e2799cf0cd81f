//! The cyclic-symmetry descriptor: the generator g of Cₙ (the rotation R by 2π/n about an
//! axis through a centre c), the node permutation σ and the member permutation π it induces,
//! validated against a structure on construction.
//!
//! g maps node i to node σ(i): R (xᵢ − c) + c = x_σ(i), and member e = (i, j) to member π(e)
//! joining σ(i) and σ(j) (either orientation: a column of A does not depend on it), bars to
//! bars and strings to strings. Supports must be invariant: the free subspace Fᵢ of node i
//! (spanned by its free coordinate axes) must satisfy R Fᵢ = F_σ(i).
//!
//! Orbits: a node off the axis has an orbit of exactly n nodes; a node on the axis is fixed by
//! the rotation (orbit of one: σ(i) = i, which the position check allows only on the axis). A member's orbit has d nodes with d dividing n (n for a
//! generic member, n/2 for a diameter that the half-turn reverses, 1 for a member along the
//! axis). Every node (member) is stored as σᵖ(representative) with its phase p.

use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use std::collections::HashMap;
use tensegrity_core::error::Result;
pub use tensegrity_core::error::SymmetryError;
use tensegrity_core::structure::Structure;

/// Positions closer than this × the structure's size count as equal.
pub const SYMMETRY_TOLERANCE: f64 = 1e-9;

/// Where an item sits in its orbit: item = gᵖ(representative of `orbit`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Place {
    /// The orbit index.
    pub orbit: usize,
    /// The phase p.
    pub phase: usize,
}

/// A node orbit: n nodes off the axis, or one node on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeOrbit {
    /// The representative node (phase 0).
    pub rep: usize,
    /// Whether the node lies on the axis (orbit of one).
    pub on_axis: bool,
}

/// A member orbit of d members (d divides n).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemberOrbit {
    /// The representative member (phase 0), bars first.
    pub rep: usize,
    /// The orbit length d.
    pub size: usize,
    /// Whether the members are bars.
    pub bar: bool,
}

/// A validated cyclic symmetry Cₙ of one structure (see the module docs).
#[derive(Debug, Clone)]
pub struct CyclicSymmetry {
    n: usize,
    axis: Unit<Vector3<f64>>,
    centre: Vector3<f64>,
    node_perm: Vec<usize>,
    member_perm: Vec<usize>,
    node_orbits: Vec<NodeOrbit>,
    node_place: Vec<Place>,
    member_orbits: Vec<MemberOrbit>,
    member_place: Vec<Place>,
}

type SymResult<T> = std::result::Result<T, SymmetryError>;

fn finite_vector(what: &'static str, v: Vector3<f64>, nonzero: bool) -> SymResult<()> {
    let ok = v.iter().all(|x| x.is_finite()) && (!nonzero || v.norm() > 0.0);
    if ok {
        Ok(())
    } else {
        Err(SymmetryError::BadAxis {
            what,
            value: [v.x, v.y, v.z],
        })
    }
}

fn check_permutation(which: &'static str, perm: &[usize], expected: usize) -> SymResult<()> {
    if perm.len() != expected {
        return Err(SymmetryError::PermutationLength {
            which,
            expected,
            found: perm.len(),
        });
    }
    let mut hit = vec![false; expected];
    for (item, &image) in perm.iter().enumerate() {
        let reason = if image >= expected {
            "out of range"
        } else if hit[image] {
            "which another item already maps to"
        } else {
            hit[image] = true;
            continue;
        };
        return Err(SymmetryError::NotAPermutation {
            which,
            item,
            image,
            reason,
        });
    }
    Ok(())
}

/// Follows `perm` from every unvisited item: the orbits as (representative, length) and
/// every item's place.
fn orbits(perm: &[usize]) -> (Vec<(usize, usize)>, Vec<Place>) {
    let mut place = vec![
        Place {
            orbit: usize::MAX,
            phase: 0
        };
        perm.len()
    ];
    let mut out = Vec::new();
    for start in 0..perm.len() {
        if place[start].orbit != usize::MAX {
            continue;
        }
        let orbit = out.len();
        let (mut i, mut phase) = (start, 0);
        while place[i].orbit == usize::MAX {
            place[i] = Place { orbit, phase };
            i = perm[i];
            phase += 1;
        }
        out.push((start, phase));
    }
    (out, place)
}

fn kind(bar: bool) -> &'static str {
    if bar {
        "bar"
    } else {
        "string"
    }
}

impl CyclicSymmetry {
    /// Validates a descriptor: the rotation by 2π/`n` about `axis` through `centre`, the node
    /// permutation (`nodes[i]` = σ(i)) and the member permutation (`members[e]` = π(e), bars
    /// then strings). The error names the first item that fails.
    pub fn new(
        structure: &Structure,
        n: usize,
        axis: Vector3<f64>,
        centre: Vector3<f64>,
        nodes: Vec<usize>,
        members: Vec<usize>,
    ) -> Result<Self> {
        Ok(Self::validate(structure, n, axis, centre, nodes, members)?)
    }

    /// Builds σ by locating each rotated node (within [`SYMMETRY_TOLERANCE`] × the structure's
    /// size) and π from the members joining the images, then validates as [`Self::new`].
    pub fn from_positions(
        structure: &Structure,
        n: usize,
        axis: Vector3<f64>,
        centre: Vector3<f64>,
    ) -> Result<Self> {
        if n < 3 {
            return Err(SymmetryError::TooFewSides { n }.into());
        }
        finite_vector("axis", axis, true)?;
        finite_vector("centre", centre, false)?;
        let rot = rotation(&Unit::new_normalize(axis), n, 1);
        let nodes = node_permutation(structure, &rot, centre)?;
        let members = member_permutation(structure, &nodes)?;
        Self::new(structure, n, axis, centre, nodes, members)
    }

    fn validate(
        structure: &Structure,
        n: usize,
        axis: Vector3<f64>,
        centre: Vector3<f64>,
        node_perm: Vec<usize>,
        member_perm: Vec<usize>,
    ) -> SymResult<Self> {
        if n < 3 {
            return Err(SymmetryError::TooFewSides { n });
        }
        finite_vector("axis", axis, true)?;
        finite_vector("centre", centre, false)?;
        check_permutation("node", &node_perm, structure.n_nodes())?;
        check_permutation("member", &member_perm, structure.n_members())?;
        let axis = Unit::new_normalize(axis);
        let rot = rotation(&axis, n, 1);
        check_nodes(structure, &rot, centre, &node_perm)?;
        check_supports(structure, &rot, &node_perm)?;
        check_members(structure, &node_perm, &member_perm)?;
        let (raw, node_place) = orbits(&node_perm);
        let mut node_orbits = Vec::with_capacity(raw.len());
        for (rep, length) in raw {
            let on_axis = length == 1;
            if !(on_axis || length == n) {
                return Err(SymmetryError::BadNodeOrbit {
                    node: rep,
                    length,
                    n,
                });
            }
            node_orbits.push(NodeOrbit { rep, on_axis });
        }
        let (raw, member_place) = orbits(&member_perm);
        let nb = structure.n_bars();
        let mut member_orbits = Vec::with_capacity(raw.len());
        for (rep, size) in raw {
            if !n.is_multiple_of(size) {
                return Err(SymmetryError::BadMemberOrbit {
                    member: structure.member_id(rep),
                    length: size,
                    n,
                });
            }
            member_orbits.push(MemberOrbit {
                rep,
                size,
                bar: rep < nb,
            });
        }
        Ok(Self {
            n,
            axis,
            centre,
            node_perm,
            member_perm,
            node_orbits,
            node_place,
            member_orbits,
            member_place,
        })
    }

    /// The group order n.
    pub fn order(&self) -> usize {
        self.n
    }

    /// The unit rotation axis.
    pub fn axis(&self) -> Vector3<f64> {
        self.axis.into_inner()
    }

    /// The point the axis passes through.
    pub fn centre(&self) -> Vector3<f64> {
        self.centre
    }

    /// The rotation Rᵖ by 2πp/n.
    pub fn rotation(&self, p: usize) -> Matrix3<f64> {
        rotation(&self.axis, self.n, p)
    }

    /// The node permutation σ.
    pub fn node_permutation(&self) -> &[usize] {
        &self.node_perm
    }

    /// The member permutation π.
    pub fn member_permutation(&self) -> &[usize] {
        &self.member_perm
    }

    /// The node orbits.
    pub fn node_orbits(&self) -> &[NodeOrbit] {
        &self.node_orbits
    }

    /// Each node's orbit and phase.
    pub fn node_places(&self) -> &[Place] {
        &self.node_place
    }

    /// The member orbits.
    pub fn member_orbits(&self) -> &[MemberOrbit] {
        &self.member_orbits
    }

    /// Each member's orbit and phase.
    pub fn member_places(&self) -> &[Place] {
        &self.member_place
    }
}

/// Rᵖ: the rotation by 2πp/n about `axis`.
fn rotation(axis: &Unit<Vector3<f64>>, n: usize, p: usize) -> Matrix3<f64> {
    let angle = 2.0 * std::f64::consts::PI * (p % n) as f64 / n as f64;
    Rotation3::from_axis_angle(axis, angle).into_inner()
}

/// The size scale of the tolerance: the largest |x| (at least 1).
fn scale(structure: &Structure) -> f64 {
    structure
        .nodes()
        .iter()
        .map(|x| x.norm())
        .fold(1.0, f64::max)
}

fn check_nodes(
    structure: &Structure,
    rot: &Matrix3<f64>,
    centre: Vector3<f64>,
    perm: &[usize],
) -> SymResult<()> {
    let tol = SYMMETRY_TOLERANCE * scale(structure);
    let x = structure.nodes();
    for (i, &j) in perm.iter().enumerate() {
        let y = rot * (x[i] - centre) + centre;
        let distance = (y - x[j]).norm();
        if distance > tol || distance.is_nan() {
            return Err(SymmetryError::NodeNotMapped {
                node: i,
                image: j,
                rotated: [y.x, y.y, y.z],
                image_position: [x[j].x, x[j].y, x[j].z],
                distance,
            });
        }
    }
    Ok(())
}

fn check_supports(structure: &Structure, rot: &Matrix3<f64>, perm: &[usize]) -> SymResult<()> {
    let fixed = structure.fixed_dofs();
    let free = |f: [bool; 3]| Matrix3::from_diagonal(&Vector3::from_fn(|d, _| !f[d] as u8 as f64));
    for (i, &j) in perm.iter().enumerate() {
        if fixed[i] == [false; 3] && fixed[j] == [false; 3] {
            continue;
        }
        let carried = rot * free(fixed[i]) * rot.transpose();
        if (carried - free(fixed[j])).amax() > 1e-9 {
            return Err(SymmetryError::SupportNotSymmetric {
                node: i,
                fixed: fixed[i],
                image: j,
                image_fixed: fixed[j],
            });
        }
    }
    Ok(())
}

fn check_members(structure: &Structure, nodes: &[usize], members: &[usize]) -> SymResult<()> {
    let ends = structure.member_nodes();
    let nb = structure.n_bars();
    for (e, &f) in members.iter().enumerate() {
        let [a, b] = ends[e];
        let expected = [nodes[a], nodes[b]];
        let found = ends[f];
        let same_ends = found == expected || found == [expected[1], expected[0]];
        if !same_ends || (e < nb) != (f < nb) {
            return Err(SymmetryError::MemberNotMapped {
                member: structure.member_id(e),
                nodes: [a, b],
                expected,
                kind: kind(e < nb),
                image: structure.member_id(f),
                found,
            });
        }
    }
    Ok(())
}

/// σ from positions, through a hash grid of cell size 10⁴ × the tolerance.
fn node_permutation(
    structure: &Structure,
    rot: &Matrix3<f64>,
    centre: Vector3<f64>,
) -> SymResult<Vec<usize>> {
    let tol = SYMMETRY_TOLERANCE * scale(structure);
    let cell = 1e4 * tol;
    let key =
        |p: &Vector3<f64>| -> [i64; 3] { std::array::from_fn(|d| (p[d] / cell).floor() as i64) };
    let x = structure.nodes();
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, p) in x.iter().enumerate() {
        grid.entry(key(p)).or_default().push(i);
    }
    let mut perm = Vec::with_capacity(x.len());
    for (i, p) in x.iter().enumerate() {
        let y = rot * (p - centre) + centre;
        let k = key(&y);
        let found = (0..27).find_map(|c: i64| {
            let kk = [k[0] + c % 3 - 1, k[1] + (c / 3) % 3 - 1, k[2] + c / 9 - 1];
            grid.get(&kk)?
                .iter()
                .copied()
                .find(|&j| (x[j] - y).norm() <= tol)
        });
        match found {
            Some(j) => perm.push(j),
            None => {
                return Err(SymmetryError::NoImageNode {
                    node: i,
                    rotated: [y.x, y.y, y.z],
                })
            }
        }
    }
    Ok(perm)
}

/// π from σ: the member of the same kind joining the images of each member's nodes.
fn member_permutation(structure: &Structure, nodes: &[usize]) -> SymResult<Vec<usize>> {
    let ends = structure.member_nodes();
    let nb = structure.n_bars();
    let lookup: HashMap<(bool, usize, usize), usize> = ends
        .iter()
        .enumerate()
        .map(|(e, &[a, b])| ((e < nb, a.min(b), a.max(b)), e))
        .collect();
    ends.iter()
        .enumerate()
        .map(|(e, &[a, b])| {
            let (c, d) = (nodes[a], nodes[b]);
            lookup
                .get(&(e < nb, c.min(d), c.max(d)))
                .copied()
                .ok_or(SymmetryError::NoImageMember {
                    member: structure.member_id(e),
                    nodes: [a, b],
                    expected: [c, d],
                    kind: kind(e < nb),
                })
        })
        .collect()
}
