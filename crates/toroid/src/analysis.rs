//! Statics of the toroid with the core definitions: self-stress, prestressability margin,
//! internal mechanisms (first-order flexes beyond the six rigid-body motions), a prestress
//! design, mass and inertia; and the rim-radius window of single-prism prestressability.
//!
//! A wheel is analysed in the symmetry-adapted basis of its Cₙ symmetry about ι₁
//! ([`crate::toroid_symmetry`], `tensegrity_statics::symmetry`): n blocks of at most
//! 17 rows and 21 columns instead of one SVD of 15n × 17n, so rank, self-stress dimension,
//! mechanisms (each per representation k) and the prestress margin (an LP over the fully
//! symmetric self-stresses) cost O(n); mass and inertia are sums over bars, O(n).
//! [`analyse_dense`] keeps the dense path for cross-checks. The max-margin self-stress of the
//! symmetric LP is constant on member orbits (every prism carries the same forces); when the
//! optimum is not unique it may differ from the dense LP's, with the same margin.

use crate::builder::{build_prism, Toroid};
use crate::error::{Result, ToroidError};
use crate::inertia::{wheel_inertia, wheel_mass};
use crate::params::ToroidParams;
use crate::symmetry::toroid_symmetry;
use nalgebra::{DVector, Matrix3};
use tensegrity_statics::symmetry::{CyclicStatics, RepCounts};
use tensegrity_statics::{Certification, SpectralGap, StaticsBackend};
use tensegrity_statics::{Prestressability, Statics};

/// The analysis of a toroid (or a single prism).
#[derive(Debug, Clone, PartialEq)]
pub struct ToroidAnalysis {
    /// Node count.
    pub nodes: usize,
    /// Bar count.
    pub bars: usize,
    /// String count.
    pub strings: usize,
    /// Rank of the equilibrium matrix.
    pub rank: usize,
    /// Dimension of the self-stress space.
    pub self_stress_dim: usize,
    /// Whether a self-stress tensions every string and compresses every bar.
    pub prestressable: bool,
    /// The prestressability LP margin.
    pub prestress_margin: f64,
    /// First-order flexes beyond the rigid-body motions.
    pub internal_mechanisms: usize,
    /// Total bar mass (kg).
    pub mass_kg: f64,
    /// Inertia tensor about the wheel centre (kg m²).
    pub inertia: Matrix3<f64>,
    /// I₁ = I(1,1), about the rolling axis.
    pub i1: f64,
    /// The max-margin self-stress (max|q| = 1), when prestressable.
    pub prestress: Option<DVector<f64>>,
    /// Rank, self-stress states and mechanisms per representation k = 0..n−1 of Cₙ (the
    /// symmetry-adapted path); empty from the dense path.
    pub representations: Vec<RepCounts>,
    /// The singular values on either side of the rank tolerance (the narrowest block's on
    /// the symmetry-adapted path).
    pub spectral_gap: SpectralGap,
    /// Set when the rank decision has no clear gap (a singular value within a factor 10 of
    /// the tolerance): the counts are then not certain.
    pub statics_warning: Option<String>,
}

/// Runs the statics, flex count, mass and inertia of a built toroid: a wheel (n ≥ 3 prisms)
/// through the symmetry-adapted path ([`CyclicStatics`], O(n)), a single prism through the
/// dense one ([`analyse_dense`]).
///
/// ```
/// use toroid::{analyse, build, ToroidParams};
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let a = analyse(&t).unwrap();
/// assert_eq!(a.internal_mechanisms, 0); // ERRATA 3.4: spokes + inner is first-order rigid
/// assert_eq!(a.self_stress_dim, 4 * 8 + 1);
/// ```
pub fn analyse(toroid: &Toroid) -> Result<ToroidAnalysis> {
    if is_prism(toroid) {
        return analyse_dense(toroid);
    }
    let s = &toroid.structure;
    let sym = toroid_symmetry(toroid)?;
    let statics = CyclicStatics::new(s, &sym)?;
    analysis_from(toroid, &statics, statics.representations().to_vec())
}

/// [`analyse`] through the dense SVD of the whole equilibrium matrix (O(n³)): the
/// cross-check of the symmetric path, and the path of a single prism.
///
/// ```
/// use toroid::{analyse, analyse_dense, build, ToroidParams};
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let (a, b) = (analyse(&t).unwrap(), analyse_dense(&t).unwrap());
/// assert_eq!((a.rank, a.internal_mechanisms), (b.rank, b.internal_mechanisms));
/// assert!((a.prestress_margin - b.prestress_margin).abs() < 1e-9);
/// ```
pub fn analyse_dense(toroid: &Toroid) -> Result<ToroidAnalysis> {
    analysis_from(toroid, &Statics::new(&toroid.structure)?, Vec::new())
}

/// The analysis of `toroid` from any statics back-end of its structure
/// ([`StaticsBackend`]: the dense SVD, the sparse QR or the cyclic blocks), with the
/// per-representation counts of the cyclic one (empty otherwise).
pub fn analysis_from(
    toroid: &Toroid,
    statics: &dyn StaticsBackend,
    representations: Vec<RepCounts>,
) -> Result<ToroidAnalysis> {
    let pre = statics.prestressability()?;
    Ok(assemble(
        toroid,
        Counts {
            rank: statics.rank(),
            self_stress_dim: statics.self_stress_dim(),
            internal_mechanisms: statics.internal_mechanisms()?,
            spectral_gap: statics.spectral_gap(),
            statics_warning: match statics.certification() {
                Certification::Certified => None,
                Certification::NotCertified { reason } => Some(reason),
            },
        },
        pre,
        representations,
    ))
}

/// Whether the toroid is a single prism (built by [`build_prism`]) rather than a wheel.
fn is_prism(toroid: &Toroid) -> bool {
    toroid.structure.n_nodes() < 5 * toroid.params.sides
}

struct Counts {
    rank: usize,
    self_stress_dim: usize,
    internal_mechanisms: usize,
    spectral_gap: SpectralGap,
    statics_warning: Option<String>,
}

fn assemble(
    toroid: &Toroid,
    counts: Counts,
    pre: Prestressability,
    representations: Vec<RepCounts>,
) -> ToroidAnalysis {
    let s = &toroid.structure;
    let inertia = wheel_inertia(s);
    ToroidAnalysis {
        nodes: s.n_nodes(),
        bars: s.n_bars(),
        strings: s.n_strings(),
        rank: counts.rank,
        self_stress_dim: counts.self_stress_dim,
        prestressable: pre.prestressable,
        prestress_margin: pre.margin,
        internal_mechanisms: counts.internal_mechanisms,
        mass_kg: wheel_mass(s),
        i1: inertia[(0, 0)],
        inertia,
        prestress: pre.prestressable.then_some(pre.stress),
        representations,
        spectral_gap: counts.spectral_gap,
        statics_warning: counts.statics_warning,
    }
}

/// A prestress: the max-margin self-stress scaled so the least-tensioned string carries
/// `min_string_tension` newtons.
#[derive(Debug, Clone, PartialEq)]
pub struct PrestressDesign {
    /// Force densities (N/m, tension positive), bars then strings.
    pub force_density: DVector<f64>,
    /// Member forces (N).
    pub member_force: DVector<f64>,
    /// The scale factor applied to the unit (max|q| = 1) stress.
    pub scale: f64,
}

/// Designs a prestress with the given minimum string tension (N), from the max-margin
/// self-stress of [`analyse`] (fully symmetric for a wheel).
///
/// ```
/// use toroid::{build, prestress_design, ToroidParams};
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let d = prestress_design(&t, 10.0).unwrap();
/// let nb = t.structure.n_bars();
/// let min = d.member_force.rows(nb, t.structure.n_strings()).min();
/// assert!((min - 10.0).abs() < 1e-9);
/// ```
pub fn prestress_design(toroid: &Toroid, min_string_tension: f64) -> Result<PrestressDesign> {
    check_tension(min_string_tension)?;
    let a = analyse(toroid)?;
    design_from(toroid, &a, min_string_tension)
}

fn check_tension(min_string_tension: f64) -> Result<()> {
    if !(min_string_tension.is_finite() && min_string_tension > 0.0) {
        return Err(ToroidError::InvalidParameter(
            tensegrity_core::request::InvalidParameter::new(
                "min_string_tension",
                min_string_tension,
                "must be a positive force (N)",
            ),
        ));
    }
    Ok(())
}

/// [`prestress_design`] from an analysis already run on `toroid`.
pub fn design_from(
    toroid: &Toroid,
    analysis: &ToroidAnalysis,
    min_string_tension: f64,
) -> Result<PrestressDesign> {
    check_tension(min_string_tension)?;
    let Some(stress) = analysis.prestress.as_ref() else {
        return Err(ToroidError::NotPrestressable {
            margin: analysis.prestress_margin,
        });
    };
    let s = &toroid.structure;
    let lengths = s.member_lengths();
    let nb = s.n_bars();
    let min_unit = (nb..s.n_members())
        .map(|k| stress[k] * lengths[k])
        .fold(f64::INFINITY, f64::min);
    let scale = min_string_tension / min_unit;
    let force_density = stress * scale;
    let member_force = DVector::from_iterator(
        lengths.len(),
        force_density.iter().zip(&lengths).map(|(q, l)| q * l),
    );
    Ok(PrestressDesign {
        force_density,
        member_force,
        scale,
    })
}

/// Whether the single prism of `params` is prestressable.
pub fn prism_prestressable(params: &ToroidParams) -> Result<bool> {
    let t = build_prism(params, 1.0)?;
    Ok(Statics::new(&t.structure)?
        .prestressability()?
        .prestressable)
}

/// The interval of rim radii R_m for which the single prism is prestressable, searched on
/// (`lo`, `hi`) with `samples` grid points and refined by bisection to `tol`. `None` when no
/// grid point is prestressable. When several disjoint intervals exist, the one containing the
/// first prestressable grid point is returned.
///
/// ```
/// use toroid::{rim_radius_window, ToroidParams};
/// let (a, b) = rim_radius_window(&ToroidParams::default(), 0.05, 1.5, 60, 1e-4).unwrap().unwrap();
/// // ERRATA 3.3: about [0.68, 0.89] for the reference wheel
/// assert!((a - 0.68).abs() < 0.02 && (b - 0.89).abs() < 0.02);
/// ```
pub fn rim_radius_window(
    params: &ToroidParams,
    lo: f64,
    hi: f64,
    samples: usize,
    tol: f64,
) -> Result<Option<(f64, f64)>> {
    let ok = |rm: f64| prism_prestressable(&params.rim_radius(rm));
    let grid: Vec<f64> = (0..samples)
        .map(|i| lo + (hi - lo) * i as f64 / (samples - 1).max(1) as f64)
        .collect();
    let mut first = None;
    for (i, &rm) in grid.iter().enumerate() {
        if ok(rm)? {
            first = Some(i);
            break;
        }
    }
    let Some(i0) = first else { return Ok(None) };
    let mut i1 = i0;
    while i1 + 1 < grid.len() && ok(grid[i1 + 1])? {
        i1 += 1;
    }
    // bisect each edge between a failing and a passing radius
    let bisect = |mut bad: f64, mut good: f64| -> Result<f64> {
        while (good - bad).abs() > tol {
            let mid = 0.5 * (bad + good);
            if ok(mid)? {
                good = mid;
            } else {
                bad = mid;
            }
        }
        Ok(0.5 * (bad + good))
    };
    let left = if i0 == 0 {
        grid[0]
    } else {
        bisect(grid[i0 - 1], grid[i0])?
    };
    let right = if i1 + 1 == grid.len() {
        grid[i1]
    } else {
        bisect(grid[i1 + 1], grid[i1])?
    };
    Ok(Some((left, right)))
}

/// The toroid's structure with every string given stiffness `k` (N/m) and the rest length
/// that realises `design` at the current geometry, s0 = l (1 − q/k).
///
/// ```
/// use toroid::{build, prestress_design, prestressed_structure, ToroidParams};
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let d = prestress_design(&t, 10.0).unwrap();
/// let s = prestressed_structure(&t, &d, 5e4).unwrap();
/// let q = tensegrity_statics::stiffness::string_force_densities(&s).unwrap();
/// let nb = s.n_bars();
/// assert!((q[nb] - d.force_density[nb]).abs() < 1e-9);
/// ```
pub fn prestressed_structure(
    toroid: &Toroid,
    design: &PrestressDesign,
    k: f64,
) -> Result<tensegrity_core::Structure> {
    if !(k.is_finite() && k > 0.0) {
        return Err(ToroidError::InvalidParameter(
            tensegrity_core::request::InvalidParameter::new(
                "string_stiffness",
                k,
                "must be a positive stiffness (N/m)",
            ),
        ));
    }
    let s = &toroid.structure;
    let nb = s.n_bars();
    let lengths = s.member_lengths();
    let mut b = s.to_builder_without_strings();
    for (i, st) in s.strings().iter().enumerate() {
        let q = design.force_density[nb + i];
        if q >= k {
            return Err(ToroidError::InvalidParameter(tensegrity_core::request::InvalidParameter::new(
                "string_stiffness",
                k,
                format!(
                    "string {i} needs force density {q:.6} N/m, which a stiffness of {k} N/m cannot give (rest length ≤ 0)"
                ),
            )));
        }
        b = b.string(
            tensegrity_core::StringMember::new(st.nodes[0], st.nodes[1])
                .stiffness(k)
                .rest_length(lengths[nb + i] * (1.0 - q / k)),
        );
    }
    Ok(b.build()?)
}
