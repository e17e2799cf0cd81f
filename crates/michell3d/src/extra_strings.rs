//! Extra strings and prestress (§4.6, ERRATA 4.30).
//!
//! For q ≥ 2, every node whose children are not supports (levels 0..q−2) gets a triangle of
//! strings between its three children (1, 4, 10, … triangles: 3, 12, 30 strings for q = 2, 3, 4).
//! The base truss is statically determinate, so each extra string adds exactly one self-stress:
//! the state with force density 1 in string j (and 0 in the other extra strings) is the string's
//! pull, s_j (n_b − n_a) on node a and s_j (n_a − n_b) on node b, carried by the base truss to
//! the supports. A prestress t (N) puts tension t in every extra string (s_j = t / l_j); with an
//! external load W the member forces are the base solution for W plus the string pulls.
//!
//! The γ sweep (Fig. 4.20) evaluates the forces for tip loads w₀[cos φ sin γ, sin φ sin γ, cos γ]
//! by superposition and lists which members keep their sign over the sweep: with a high
//! prestress every member except the three tip members does.

use crate::error::{invalid, MichellError, Result};
use crate::loads::NodalLoads;
use crate::propagation::{propagate, unit_tip_responses, ForceSolution, Method};
use crate::signmap::AngleGrid;
use crate::sizing::ZERO_FORCE_RTOL;
use crate::truss::MichellTruss;
use serde::Serialize;
use std::collections::BTreeSet;
use tensegrity_core::{StringMember, Structure};

/// The extra strings of a 3-D truss.
#[derive(Debug, Clone, PartialEq)]
pub struct ExtraStrings {
    pairs: Vec<[usize; 2]>,
    lengths: Vec<f64>,
}

impl ExtraStrings {
    /// The strings on the sub-triangles of the children of every node of levels 0..q−2.
    pub fn new(truss: &MichellTruss) -> Result<Self> {
        let q = truss.params().complexity;
        if truss.is_planar() {
            return Err(MichellError::NeedsThreeD {
                what: "extra strings",
            });
        }
        if q < 2 {
            return Err(invalid(
                "complexity",
                q as f64,
                "extra strings need q ≥ 2 (for q = 1 every child is a support)",
            ));
        }
        let members = truss.members();
        let mut set = BTreeSet::new();
        for p in 0..truss.n_free() {
            let ch = [0, 1, 2].map(|s| members[3 * p + s].child);
            if truss.is_support(ch[0]) {
                continue;
            }
            for (a, b) in [(0, 1), (1, 2), (0, 2)] {
                let (x, y) = (ch[a].min(ch[b]), ch[a].max(ch[b]));
                set.insert([x, y]);
            }
        }
        let nodes = truss.nodes();
        let pairs: Vec<[usize; 2]> = set.into_iter().collect();
        let lengths = pairs
            .iter()
            .map(|&[a, b]| (nodes[a].position - nodes[b].position).norm())
            .collect();
        Ok(Self { pairs, lengths })
    }

    /// Node pairs `[a, b]` (a < b) of the strings.
    pub fn pairs(&self) -> &[[usize; 2]] {
        &self.pairs
    }

    /// String lengths (m).
    pub fn lengths(&self) -> &[f64] {
        &self.lengths
    }

    /// Number of extra strings.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// The nodal loads that string force densities `s` exert on the base truss.
    fn pulls(&self, truss: &MichellTruss, s: &[f64]) -> NodalLoads {
        let nodes = truss.nodes();
        let mut loads = NodalLoads::new();
        for (&[a, b], &sj) in self.pairs.iter().zip(s) {
            let d = nodes[b].position - nodes[a].position;
            loads = loads.add(a, sj * d).add(b, -sj * d);
        }
        loads
    }

    /// Base-member force densities of the self-stress with unit force density in string `j`.
    pub fn self_stress(&self, truss: &MichellTruss, j: usize, method: Method) -> Result<Vec<f64>> {
        if j >= self.len() {
            return Err(MichellError::UnknownMember {
                index: j,
                count: self.len(),
            });
        }
        let mut s = vec![0.0; self.len()];
        s[j] = 1.0;
        Ok(propagate(truss, &self.pulls(truss, &s), method)?.force_density)
    }

    /// A `tensegrity_core::Structure` of the base truss (as bars) plus the extra strings, with
    /// the level-q nodes pinned; members are numbered base members, then extra strings.
    pub fn to_structure(&self, truss: &MichellTruss) -> Result<Structure> {
        let mut b = truss.structure_builder();
        for &[x, y] in &self.pairs {
            b = b.string(StringMember::new(x, y));
        }
        Ok(b.build()?)
    }
}

/// Forces with prestressed extra strings.
#[derive(Debug, Clone, PartialEq)]
pub struct PrestressedSolution {
    /// Base members (force densities and support reactions).
    pub base: ForceSolution,
    /// Force density of each extra string (N/m).
    pub extra_force_density: Vec<f64>,
}

fn check_prestress(prestress: f64) -> Result<()> {
    if prestress.is_finite() && prestress >= 0.0 {
        Ok(())
    } else {
        Err(invalid(
            "extra-strings",
            prestress,
            "the prestress (tension in every extra string, N) must be finite and ≥ 0",
        ))
    }
}

/// Member forces under `loads` when every extra string is pretensioned to `prestress` (N).
pub fn solve_prestressed(
    truss: &MichellTruss,
    strings: &ExtraStrings,
    loads: &NodalLoads,
    prestress: f64,
    method: Method,
) -> Result<PrestressedSolution> {
    check_prestress(prestress)?;
    let s: Vec<f64> = strings.lengths.iter().map(|l| prestress / l).collect();
    let mut all = loads.clone();
    for &(n, w) in strings.pulls(truss, &s).entries() {
        all = all.add(n, w);
    }
    Ok(PrestressedSolution {
        base: propagate(truss, &all, method)?,
        extra_force_density: s,
    })
}

/// Member forces over a sweep of the polar angle γ (Fig. 4.20).
#[derive(Debug, Clone, PartialEq)]
pub struct GammaSweep {
    /// The γ values (rad).
    pub polar: Vec<f64>,
    /// Base member forces (N) per γ: `base_force[i][j]`.
    pub base_force: Vec<Vec<f64>>,
    /// Extra string forces (N) per γ (constant: a tip load does not change them).
    pub extra_force: Vec<Vec<f64>>,
    /// Whether each base member keeps its sign over the sweep.
    pub base_keeps_sign: Vec<bool>,
    /// Whether each extra string keeps its sign (stays in tension) over the sweep.
    pub extra_keeps_sign: Vec<bool>,
}

impl GammaSweep {
    /// Indices of the base members whose sign changes over the sweep.
    pub fn base_sign_changers(&self) -> Vec<usize> {
        (0..self.base_keeps_sign.len())
            .filter(|&j| !self.base_keeps_sign[j])
            .collect()
    }
}

/// Forces for tip loads of magnitude `w0` (N), azimuth `azimuth`, polar angles `polar`, with the
/// extra strings pretensioned to `prestress` (N).
pub fn gamma_sweep(
    truss: &MichellTruss,
    strings: &ExtraStrings,
    w0: f64,
    azimuth: f64,
    polar: AngleGrid,
    prestress: f64,
    method: Method,
) -> Result<GammaSweep> {
    check_prestress(prestress)?;
    crate::loads::check_magnitude_and_azimuth(w0, azimuth)?;
    if polar.n == 0 {
        return Err(MichellError::EmptyGrid { name: "polar" });
    }
    let pre = solve_prestressed(truss, strings, &NodalLoads::new(), prestress, method)?;
    let [qx, qy, qz] = unit_tip_responses(truss, method)?;
    let lengths = truss.lengths();
    let (sa, ca) = azimuth.sin_cos();
    let gammas = polar.values();
    let base_force: Vec<Vec<f64>> = gammas
        .iter()
        .map(|g| {
            let (sg, cg) = g.sin_cos();
            let w = [w0 * ca * sg, w0 * sa * sg, w0 * cg];
            (0..lengths.len())
                .map(|j| {
                    (pre.base.force_density[j] + w[0] * qx[j] + w[1] * qy[j] + w[2] * qz[j])
                        * lengths[j]
                })
                .collect()
        })
        .collect();
    let extra: Vec<f64> = pre
        .extra_force_density
        .iter()
        .zip(strings.lengths())
        .map(|(s, l)| s * l)
        .collect();
    let extra_force = vec![extra; gammas.len()];
    let f_max = base_force
        .iter()
        .chain(&extra_force)
        .flatten()
        .fold(0.0f64, |m, f| m.max(f.abs()));
    let thr = ZERO_FORCE_RTOL * f_max;
    let keeps = |rows: &[Vec<f64>], j: usize| {
        let pos = rows.iter().any(|r| r[j] > thr);
        let neg = rows.iter().any(|r| r[j] < -thr);
        !(pos && neg)
    };
    Ok(GammaSweep {
        base_keeps_sign: (0..lengths.len()).map(|j| keeps(&base_force, j)).collect(),
        extra_keeps_sign: (0..strings.len()).map(|j| keeps(&extra_force, j)).collect(),
        polar: gammas,
        base_force,
        extra_force,
    })
}

/// Which kind of member a γ-sweep row holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepMember {
    /// A member of the base truss.
    Base,
    /// An extra string.
    Extra,
}

/// One row of a γ sweep: the force of one member at one polar angle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GammaSweepRow {
    /// Polar angle γ of the load (rad).
    pub polar_rad: f64,
    /// Index among the base members or among the extra strings (see `kind`).
    pub member: usize,
    /// Base member or extra string.
    pub kind: SweepMember,
    /// Axial force (N, tension positive).
    #[serde(rename = "force_N")]
    pub force_n: f64,
}

impl GammaSweep {
    /// The table rows: for every γ, the base members, then the extra strings.
    pub fn rows(&self) -> impl Iterator<Item = GammaSweepRow> + '_ {
        self.polar.iter().enumerate().flat_map(move |(i, &g)| {
            let row = move |kind, (member, &force_n): (usize, &f64)| GammaSweepRow {
                polar_rad: g,
                member,
                kind,
                force_n,
            };
            let base = self.base_force[i]
                .iter()
                .enumerate()
                .map(move |m| row(SweepMember::Base, m));
            let extra = self.extra_force[i]
                .iter()
                .enumerate()
                .map(move |m| row(SweepMember::Extra, m));
            base.chain(extra)
        })
    }
}
