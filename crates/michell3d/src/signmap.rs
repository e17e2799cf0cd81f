//! Sign maps of member force densities over load directions (Fig. 4.14–4.16).
//!
//! The truss is linear, so for a tip load w = w₀[cos φ sin γ, sin φ sin γ, cos γ] (eq. 4.13)
//! every force density is q_j(φ, γ) = w₀ (q_j^x cos φ sin γ + q_j^y sin φ sin γ + q_j^z cos γ),
//! with q^x, q^y, q^z the responses to unit tip loads (three propagations). The grid is then
//! filled row by row ([`SignMapBasis::fill_row`]), sequentially here; the sweeps crate fans
//! the rows out over threads (`sweeps::grids::sign_maps`) with the same arithmetic, so both
//! give the same bits. A value counts as zero (sign 0) when
//! |q_j| ≤ [`ZERO_FORCE_RTOL`]·w₀‖(q_j^x, q_j^y, q_j^z)‖, the largest |q_j| over all directions.
//!
//! For q = 1 the signs reproduce eq. 4.21–4.22 and the corrected eq. 4.23 (ERRATA 4.13).
//! ERRATA 4.22: sweeping γ over [0, 2π] covers the sphere twice; [0, π] suffices.

use crate::error::{invalid, MichellError, Result};
use crate::propagation::{unit_tip_responses, Method};
use crate::sizing::ZERO_FORCE_RTOL;
use crate::truss::MichellTruss;
use serde::Serialize;

/// `n` evenly spaced angles from `start` to `end`, both included (n ≥ 2), or just `start`
/// (n = 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleGrid {
    /// First angle (rad).
    pub start: f64,
    /// Last angle (rad).
    pub end: f64,
    /// Number of angles.
    pub n: usize,
}

impl AngleGrid {
    /// A grid from `start` to `end` with `n` points.
    pub fn new(start: f64, end: f64, n: usize) -> Self {
        Self { start, end, n }
    }

    /// The i-th angle.
    pub fn at(&self, i: usize) -> f64 {
        if self.n <= 1 {
            self.start
        } else {
            self.start + (self.end - self.start) * i as f64 / (self.n - 1) as f64
        }
    }

    /// All angles.
    pub fn values(&self) -> Vec<f64> {
        (0..self.n).map(|i| self.at(i)).collect()
    }

    fn validate(&self, name: &'static str) -> Result<()> {
        if self.n == 0 {
            return Err(MichellError::EmptyGrid { name });
        }
        if !(self.start.is_finite() && self.end.is_finite()) {
            return Err(invalid(name, self.start, "grid bounds must be finite"));
        }
        Ok(())
    }
}

/// Force density of one member over an (azimuth φ, polar γ) grid.
#[derive(Debug, Clone, PartialEq)]
pub struct SignMap {
    /// Member index.
    pub member: usize,
    /// Azimuth grid (φ).
    pub azimuth: AngleGrid,
    /// Polar grid (γ).
    pub polar: AngleGrid,
    /// q (N/m), row-major: entry `ip * azimuth.n + ia`.
    pub force_density: Vec<f64>,
    /// |q| at or below this counts as zero (N/m).
    pub zero_threshold: f64,
}

impl SignMap {
    /// q at polar index `ip`, azimuth index `ia`.
    pub fn value(&self, ip: usize, ia: usize) -> f64 {
        self.force_density[ip * self.azimuth.n + ia]
    }

    /// Sign (+1 tension, −1 compression, 0 zero) at polar index `ip`, azimuth index `ia`.
    pub fn sign(&self, ip: usize, ia: usize) -> i8 {
        let v = self.value(ip, ia);
        if v.abs() <= self.zero_threshold {
            0
        } else if v > 0.0 {
            1
        } else {
            -1
        }
    }

    /// Fraction of grid points where the member is in tension.
    pub fn tension_fraction(&self) -> f64 {
        let n = self.force_density.len();
        let t = (0..self.polar.n)
            .flat_map(|ip| (0..self.azimuth.n).map(move |ia| (ip, ia)))
            .filter(|&(ip, ia)| self.sign(ip, ia) > 0)
            .count();
        t as f64 / n as f64
    }
}

/// What a sign map needs before its grid is filled: the validated grids and, per member,
/// w₀ times its responses to unit tip loads along ι̂₁, ι̂₂, ι̂₃.
#[derive(Debug, Clone, PartialEq)]
pub struct SignMapBasis {
    /// The members, in the order asked for.
    pub members: Vec<usize>,
    /// w₀ (q_j^x, q_j^y, q_j^z) per member (N/m).
    pub coefficients: Vec<[f64; 3]>,
    /// Azimuth grid (φ).
    pub azimuth: AngleGrid,
    /// Polar grid (γ).
    pub polar: AngleGrid,
    /// (sin, cos) of every azimuth.
    azimuth_sin_cos: Vec<(f64, f64)>,
}

impl SignMapBasis {
    /// Validates the request and propagates the three unit tip loads (3-D trusses only).
    pub fn new(
        truss: &MichellTruss,
        members: &[usize],
        w0: f64,
        azimuth: AngleGrid,
        polar: AngleGrid,
        method: Method,
    ) -> Result<Self> {
        if truss.is_planar() {
            // a planar truss: see planar::force_regions instead
            return Err(MichellError::NeedsThreeD {
                what: "sign maps over (azimuth, polar)",
            });
        }
        if !(w0.is_finite() && w0 > 0.0) {
            return Err(invalid(
                "load",
                w0,
                "the load magnitude w0 must be finite and > 0",
            ));
        }
        azimuth.validate("azimuth")?;
        polar.validate("polar")?;
        let count = truss.members().len();
        if let Some(&bad) = members.iter().find(|&&j| j >= count) {
            return Err(MichellError::UnknownMember { index: bad, count });
        }
        let [qx, qy, qz] = unit_tip_responses(truss, method)?;
        Ok(Self {
            members: members.to_vec(),
            coefficients: members
                .iter()
                .map(|&j| [w0 * qx[j], w0 * qy[j], w0 * qz[j]])
                .collect(),
            azimuth,
            polar,
            azimuth_sin_cos: azimuth.values().iter().map(|a| a.sin_cos()).collect(),
        })
    }

    /// Fills `row` (length `azimuth.n`) with q of the `slot`-th member at polar index `ip`.
    pub fn fill_row(&self, slot: usize, ip: usize, row: &mut [f64]) {
        let [bx, by, bz] = self.coefficients[slot];
        let (sg, cg) = self.polar.at(ip).sin_cos();
        for (v, &(sa, ca)) in row.iter_mut().zip(&self.azimuth_sin_cos) {
            *v = bx * ca * sg + by * sa * sg + bz * cg;
        }
    }

    /// The map of the `slot`-th member from its filled values (row-major, polar outer).
    pub fn map(&self, slot: usize, force_density: Vec<f64>) -> SignMap {
        let [bx, by, bz] = self.coefficients[slot];
        SignMap {
            member: self.members[slot],
            azimuth: self.azimuth,
            polar: self.polar,
            force_density,
            zero_threshold: ZERO_FORCE_RTOL * (bx * bx + by * by + bz * bz).sqrt(),
        }
    }
}

/// Sign maps of `members` for a tip load of magnitude `w0` over the grids (3-D trusses only),
/// filled sequentially.
pub fn sign_maps(
    truss: &MichellTruss,
    members: &[usize],
    w0: f64,
    azimuth: AngleGrid,
    polar: AngleGrid,
    method: Method,
) -> Result<Vec<SignMap>> {
    let basis = SignMapBasis::new(truss, members, w0, azimuth, polar, method)?;
    Ok((0..members.len())
        .map(|slot| {
            let mut values = vec![0.0; azimuth.n * polar.n];
            for (ip, row) in values.chunks_mut(azimuth.n).enumerate() {
                basis.fill_row(slot, ip, row);
            }
            basis.map(slot, values)
        })
        .collect())
}

/// One row of a sign-map table: a member at one (azimuth, polar) load direction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignMapRow {
    /// Member index.
    pub member: usize,
    /// Parent node tuple as `U-D-L-R`.
    pub parent: String,
    /// Child node tuple as `U-D-L-R`.
    pub child: String,
    /// Azimuth φ of the load (rad).
    pub azimuth_rad: f64,
    /// Polar angle γ of the load (rad).
    pub polar_rad: f64,
    /// Force density q (N/m, tension positive).
    #[serde(rename = "force_density_N_per_m")]
    pub force_density_n_per_m: f64,
    /// Sign: +1 tension, −1 compression, 0 zero.
    pub sign: i8,
}

/// The rows of `maps`, member by member, polar angle outer, azimuth inner (streamed: a large
/// grid is never held in memory as rows).
pub fn sign_map_rows<'a>(
    truss: &'a MichellTruss,
    maps: &'a [SignMap],
) -> impl Iterator<Item = SignMapRow> + 'a {
    let tuple = move |n: usize| {
        truss
            .label(n)
            .iter()
            .map(|v| v.to_string())
            .collect::<Vec<_>>()
            .join("-")
    };
    maps.iter().flat_map(move |map| {
        let m = &truss.members()[map.member];
        let (parent, child) = (tuple(m.parent), tuple(m.child));
        (0..map.polar.n).flat_map(move |ip| {
            let (parent, child) = (parent.clone(), child.clone());
            (0..map.azimuth.n).map(move |ia| SignMapRow {
                member: map.member,
                parent: parent.clone(),
                child: child.clone(),
                azimuth_rad: map.azimuth.at(ia),
                polar_rad: map.polar.at(ip),
                force_density_n_per_m: map.value(ip, ia),
                sign: map.sign(ip, ia),
            })
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::loads::{tip_load, NodalLoads};
    use crate::params::MichellParams;
    use crate::propagation::propagate_recursive;

    #[test]
    fn superposition_equals_direct_solves() {
        let t = MichellTruss::new(MichellParams::spherical(4, 1.2, 0.5, 0.3, 0.2)).unwrap();
        let az = AngleGrid::new(0.1, 6.0, 7);
        let po = AngleGrid::new(0.2, 3.0, 5);
        let members = [0, 7, 29, 59];
        let maps = sign_maps(&t, &members, 300.0, az, po, Method::Global).unwrap();
        for ip in 0..po.n {
            for ia in 0..az.n {
                let w = tip_load(300.0, az.at(ia), po.at(ip)).unwrap();
                let q = propagate_recursive(&t, &NodalLoads::tip(w))
                    .unwrap()
                    .force_density;
                for (map, &j) in maps.iter().zip(&members) {
                    assert!((map.value(ip, ia) - q[j]).abs() < 1e-9 * q[j].abs().max(1.0));
                    let expect = if q[j] > 0.0 { 1 } else { -1 };
                    assert_eq!(map.sign(ip, ia), expect);
                }
            }
        }
        let rows: Vec<SignMapRow> = sign_map_rows(&t, &maps).collect();
        assert_eq!(rows.len(), members.len() * az.n * po.n);
        assert_eq!(
            (
                rows[0].member,
                rows[0].parent.as_str(),
                rows[0].child.as_str()
            ),
            (0, "0-0-0-0", "1-0-1-0")
        );
        assert_eq!(rows[1].azimuth_rad, az.at(1));
        assert_eq!(rows[az.n].polar_rad, po.at(1));
    }
}
