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
use crate::prestress::{check_signs, margin_lp};
use crate::{MemberSign, Prestressability};
use tensegrity_core::error::{CoreError, Result};

impl CyclicStatics<'_> {
    /// The prestressability LP solved in the fully symmetric subspace (see the module docs);
    /// `stress` is expanded to every member (bars then strings).
    pub fn prestressability(&self) -> Result<Prestressability> {
        self.prestressability_with(&MemberSign::standard(self.structure()))
    }

    /// The margin LP with the given member signs ([`MemberSign`]) in the fully symmetric
    /// subspace. The signs must be the same on every member of an orbit (otherwise the LP is
    /// not invariant and its optimum need not be symmetric:
    /// [`CoreError::InvalidParameter`] naming `signs`).
    pub fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability> {
        let members = self.structure().n_members();
        check_signs(signs, members)?;
        let orbits = self.symmetry().member_orbits();
        let places = self.symmetry().member_places();
        if let Some(e) = (0..members).find(|&e| signs[e] != signs[orbits[places[e].orbit].rep]) {
            return Err(CoreError::invalid_parameter(
                "signs",
                e as f64,
                "the member signs of the symmetric margin LP must be the same on every member of an orbit",
            ));
        }
        let basis = self.symmetric_basis();
        if basis.ncols() == 0 {
            return Ok(Prestressability::none(members));
        }
        // rows of block 0 are the orbits present in it: all of them (k·d ≡ 0 for k = 0)
        let orbit_signs: Vec<MemberSign> = orbits.iter().map(|o| signs[o.rep]).collect();
        let x = margin_lp(
            basis,
            &orbit_signs,
            self.settings().lp_solver,
            "symmetric prestressability LP",
        )?;
        let q = basis * x;
        let expanded = nalgebra::DVector::from_fn(members, |e, _| q[places[e].orbit]);
        Ok(Prestressability::from_signed(expanded, signs))
    }
}
