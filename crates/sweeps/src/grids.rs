//! The grid studies of the Michell truss and the toroid whose points are not whole reports:
//! the michell3d functions compute one row (one complexity, one polar angle of a sign map),
//! sequentially; this module fans the rows out over a rayon pool and puts them back in order,
//! so the result is the sequential one bit for bit (the same arithmetic per row).
//!
//! - [`sign_maps`]: q_j(φ, γ) = w₀ (q_j^x cos φ sin γ + q_j^y sin φ sin γ + q_j^z cos γ) of
//!   Figs. 4.14–4.16 (`tensegrity michell --sign-map`), one polar row per task;
//! - [`mass_vs_complexity`]: the Fig. 4.18 table (`tensegrity michell-table`), one complexity
//!   per task;
//! - [`friction_grid`]: F_f/F_e = −(σ + ε)/(1 − σ) of Fig. 3.13 (`tensegrity tipover
//!   --grid`), one σ per task.
//!
//! Each runs on rayon's global pool (one thread per core unless `RAYON_NUM_THREADS` says
//! otherwise); the linear algebra inside each row stays sequential.

use michell3d::signmap::{AngleGrid, SignMap, SignMapBasis};
use michell3d::{MassRow, Method, MichellTruss};
use rayon::prelude::*;
use tensegrity_core::Material;

/// Sign maps of `members` of a 3-D truss for a tip load of magnitude `w0` over the grids:
/// [`michell3d::sign_maps`] with the polar rows on threads.
pub fn sign_maps(
    truss: &MichellTruss,
    members: &[usize],
    w0: f64,
    azimuth: AngleGrid,
    polar: AngleGrid,
    method: Method,
) -> michell3d::Result<Vec<SignMap>> {
    let basis = SignMapBasis::new(truss, members, w0, azimuth, polar, method)?;
    Ok((0..members.len())
        .map(|slot| {
            let mut values = vec![0.0; azimuth.n * polar.n];
            values
                .par_chunks_mut(azimuth.n)
                .enumerate()
                .for_each(|(ip, row)| basis.fill_row(slot, ip, row));
            basis.map(slot, values)
        })
        .collect())
}

/// The Fig. 4.18 table: [`michell3d::mass_vs_complexity`] with the complexities on threads,
/// rows in the order of `qs` (planar first within each q).
pub fn mass_vs_complexity(
    qs: &[usize],
    deltas: &[f64],
    w0: f64,
    material: &Material,
) -> michell3d::Result<Vec<MassRow>> {
    let per_q: Vec<michell3d::Result<Vec<MassRow>>> = qs
        .par_iter()
        .map(|&q| michell3d::mass_rows(q, deltas, w0, material))
        .collect();
    let mut all = Vec::new();
    for rows in per_q {
        all.extend(rows?);
    }
    Ok(all)
}

/// Grid points per axis of [`friction_grid`] unless told (`tipover --grid`, Python's
/// `tipover(grid=True)`).
pub const FRICTION_GRID_POINTS: usize = 50;

/// The largest ε of [`friction_grid`] unless told.
pub const FRICTION_GRID_EPS_MAX: f64 = 1.0;

/// F_f/F_e over a σ × ε grid (Fig. 3.13): [`toroid::friction_grid`]'s rows `(σ, ε, F_f/F_e)`,
/// σ outer on `n` points of (0, 1), ε inner on `n` points of (0, `eps_max`], σ rows on threads.
pub fn friction_grid(n: usize, eps_max: f64) -> toroid::Result<Vec<(f64, f64, f64)>> {
    tensegrity_core::validate::count_at_least("grid_points", n, 2)?;
    tensegrity_core::validate::positive("eps_max", eps_max)?;
    let rows: Vec<toroid::Result<Vec<(f64, f64, f64)>>> = (1..=n)
        .into_par_iter()
        .map(|i| {
            let sigma = i as f64 / (n + 1) as f64;
            (1..=n)
                .map(|j| {
                    let eps = eps_max * j as f64 / n as f64;
                    Ok((sigma, eps, toroid::normalized_friction(sigma, eps)?))
                })
                .collect()
        })
        .collect();
    let mut all = Vec::with_capacity(n * n);
    for r in rows {
        all.extend(r?);
    }
    Ok(all)
}

#[cfg(test)]
mod tests {
    use super::*;
    use michell3d::MichellParams;

    #[test]
    fn the_threaded_grids_are_the_sequential_ones_bit_for_bit() {
        let t = MichellTruss::new(MichellParams::cylindrical(3, 1.0, 0.5, 0.4, 0.25)).unwrap();
        let (az, po) = (AngleGrid::new(0.0, 6.2, 37), AngleGrid::new(0.0, 3.1, 19));
        let a = sign_maps(&t, &[0, 1, 2, 5], 1000.0, az, po, Method::Recursive).unwrap();
        let b = michell3d::sign_maps(&t, &[0, 1, 2, 5], 1000.0, az, po, Method::Recursive).unwrap();
        assert_eq!(a, b);
        let steel = *tensegrity_core::MaterialTable::builtin()
            .lookup("steel", "material")
            .unwrap();
        let qs = [2, 3, 4, 5, 6];
        let a = mass_vs_complexity(&qs, &[0.1, 0.5], 1000.0, &steel).unwrap();
        let b = michell3d::mass_vs_complexity(&qs, &[0.1, 0.5], 1000.0, &steel).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.len(), 15);
        assert_eq!(
            friction_grid(7, 1.0).unwrap(),
            toroid::friction_grid(7, 1.0).unwrap()
        );
    }

    #[test]
    fn the_friction_grid_is_the_closed_form_and_bad_input_is_an_error() {
        for (s, e, f) in friction_grid(5, 0.8).unwrap() {
            assert!((f + (s + e) / (1.0 - s)).abs() < 1e-12, "{s} {e} {f}");
        }
        assert!(friction_grid(1, 1.0).is_err());
        assert!(friction_grid(4, -1.0).is_err());
    }
}
