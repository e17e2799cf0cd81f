//! The prestressability margin in the fully symmetric subspace.
//!
//! The margin LP `max t  s.t.  q ∈ null A,  q_s ≥ t (strings),  q_b ≤ −t (bars),  |q| ≤ 1`
//! is invariant under the member permutation π (A π = g A maps null A onto itself, and π maps
//! bars to bars and strings to strings), and its feasible set is convex: the average
//! (1/n) Σ_p πᵖ q* of an optimum is feasible with the same t. So an optimum is constant on
//! member orbits, i.e. lies in the self-stresses of representation 0, and the LP over that
//! space, one variable per basis state and two rows per member orbit, has the dense LP's
//! optimum. The margin is recomputed exactly from the returned stress scaled to max|q| = 1, as
//! in the dense path.

use super::cyclic::CyclicStatics;
use crate::error::Result;
use crate::statics::{solve_lp, Prestressability, PRESTRESS_TOLERANCE};
use nalgebra::{DMatrix, DVector};

impl CyclicStatics<'_> {
    /// The prestressability LP solved in the fully symmetric subspace (see the module docs);
    /// `stress` is expanded to every member (bars then strings).
    pub fn prestressability(&self) -> Result<Prestressability> {
        let basis = self.symmetric_basis();
        let orbits = self.symmetry().member_orbits();
        let (m, d) = (basis.nrows(), basis.ncols());
        let members = self.structure().n_members();
        let none = Prestressability {
            margin: 0.0,
            prestressable: false,
            stress: DVector::zeros(members),
        };
        if d == 0 {
            return Ok(none);
        }
        // rows of block 0 are the orbits present in it: all of them (k·d ≡ 0 for k = 0)
        let rows = 2 * m + 1;
        let mut g = DMatrix::zeros(rows, d + 1);
        let mut h = DVector::zeros(rows);
        for e in 0..m {
            let sign = if orbits[e].bar { 1.0 } else { -1.0 };
            for j in 0..d {
                g[(2 * e, j)] = sign * basis[(e, j)];
                g[(2 * e + 1, j)] = -sign * basis[(e, j)];
            }
            g[(2 * e, d)] = 1.0;
            h[2 * e + 1] = 1.0;
        }
        g[(2 * m, d)] = -1.0;
        let mut c = DVector::zeros(d + 1);
        c[d] = -1.0;
        let z = solve_lp(&g, &h, &c, "symmetric prestressability LP")?;
        let mut q = basis * z.rows(0, d);
        let scale = q.amax();
        if scale <= 0.0 {
            return Ok(none);
        }
        q /= scale;
        let margin = (0..m)
            .map(|e| if orbits[e].bar { -q[e] } else { q[e] })
            .fold(f64::INFINITY, f64::min)
            .max(0.0);
        let places = self.symmetry().member_places();
        Ok(Prestressability {
            margin,
            prestressable: margin > PRESTRESS_TOLERANCE,
            stress: DVector::from_fn(members, |e, _| q[places[e].orbit]),
        })
    }
}
