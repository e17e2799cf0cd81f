//! Minimum-mass sizing of members (thesis eq. 4.54–4.61).
//!
//! For an axial force f = q·l (tension positive) on a member of length l made of a material
//! (ρ, E, σ_Y), with solid round cross-sections:
//!
//! - yield (strings, and bars in either sign): area |f|/σ_Y, so
//!   r_Y = √(|f| / (π σ_Y)) and m_Y = (ρ/σ_Y) |f| l  (eq. 4.54–4.56, 4.58);
//! - Euler buckling of a pinned–pinned solid rod in compression, |f| = π³ E r⁴ / (4 l²):
//!   r_B = (4 |f| l² / (π³ E))^¼ and m_B = 2 ρ l² √(|f| / (π E))  (eq. 4.57, 4.59);
//! - a bar in compression takes r = max(r_Y, r_B); a bar in tension only yields; a string must
//!   be in tension ([`tensegrity_core::error::StaticsError::StringInCompression`] otherwise).
//!
//! Total mass is Σ ρ π r² l (eq. 4.60–4.61 times density).
//!
//! A clustered string ([`tensegrity_core::Cluster`]) is sized like a string from its tension
//! t_c (its force, after the strings) and its material, over its total length L_c: r_Y =
//! √(t_c / (π σ_Y)), m = (ρ/σ_Y) t_c L_c; in compression it is an error (the lenient sizing
//! lists it in [`SizingReport::compressed_clusters`]).

use nalgebra::DVector;
use std::f64::consts::PI;
use tensegrity_core::error::{ModelError, Result, StaticsError};
use tensegrity_core::material::Material;
use tensegrity_core::structure::{MemberId, Structure};

/// Which failure mode sets a member's size (serialised as `yield`, `buckling`, `unloaded`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Governing {
    /// Material yield.
    Yield,
    /// Euler buckling.
    Buckling,
    /// The member carries no force (zero size).
    Unloaded,
}

impl Governing {
    /// The name in reports: `yield`, `buckling` or `unloaded`.
    pub fn as_str(self) -> &'static str {
        match self {
            Governing::Yield => "yield",
            Governing::Buckling => "buckling",
            Governing::Unloaded => "unloaded",
        }
    }
}

impl std::fmt::Display for Governing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.as_str())
    }
}

/// Yield-limited radius r_Y = √(|f| / (π σ_Y)).
///
/// ```
/// use tensegrity_core::Material;
/// use tensegrity_statics::sizing;
/// let steel = Material::new(7862.0, 210e9, 690e6);
/// let r = sizing::yield_radius(&steel, 1000.0);
/// assert!((std::f64::consts::PI * r * r * 690e6 - 1000.0).abs() < 1e-9);
/// ```
pub fn yield_radius(material: &Material, force: f64) -> f64 {
    (force.abs() / (PI * material.yield_strength)).sqrt()
}

/// Yield-limited mass m_Y = (ρ/σ_Y) |f| l.
///
/// ```
/// use tensegrity_core::Material;
/// use tensegrity_statics::sizing;
/// let alu = Material::new(2700.0, 60e9, 110e6);
/// assert!((sizing::yield_mass(&alu, 1e4, 2.0) - 2700.0 / 110e6 * 2e4).abs() < 1e-15);
/// ```
pub fn yield_mass(material: &Material, force: f64, length: f64) -> f64 {
    material.density / material.yield_strength * force.abs() * length
}

/// Buckling-limited radius r_B = (4 |f| l² / (π³ E))^¼ (pinned–pinned solid rod).
///
/// ```
/// use tensegrity_core::Material;
/// use tensegrity_statics::sizing;
/// let alu = Material::new(2700.0, 60e9, 110e6);
/// let r = sizing::buckling_radius(&alu, 1e4, 2.0);
/// let euler = std::f64::consts::PI.powi(3) * 60e9 * r.powi(4) / (4.0 * 4.0);
/// assert!((euler - 1e4).abs() < 1e-6);
/// ```
pub fn buckling_radius(material: &Material, force: f64, length: f64) -> f64 {
    (4.0 * force.abs() * length * length / (PI.powi(3) * material.youngs_modulus)).powf(0.25)
}

/// Buckling-limited mass m_B = 2 ρ l² √(|f| / (π E)).
///
/// ```
/// use tensegrity_core::Material;
/// use tensegrity_statics::sizing;
/// let alu = Material::new(2700.0, 60e9, 110e6);
/// // one 2 m aluminium bar under 10 kN: 4.975116 kg (published benchmark)
/// assert!((sizing::buckling_mass(&alu, 1e4, 2.0) - 4.975116).abs() < 1e-6);
/// ```
pub fn buckling_mass(material: &Material, force: f64, length: f64) -> f64 {
    2.0 * material.density * length * length * (force.abs() / (PI * material.youngs_modulus)).sqrt()
}

/// The minimum size of one member.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MemberSize {
    /// Axial force f (N, tension positive).
    pub force: f64,
    /// Length l (m).
    pub length: f64,
    /// Radius (m).
    pub radius: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Mass for yield alone (kg).
    pub yield_mass: f64,
    /// Mass for buckling alone (kg), for bars in compression.
    pub buckling_mass: Option<f64>,
    /// The governing failure mode.
    pub governing: Governing,
}

/// Sizes a string (tension only, yield).
///
/// ```
/// use tensegrity_core::Material;
/// use tensegrity_statics::sizing;
/// let alu = Material::new(2700.0, 60e9, 110e6);
/// let s = sizing::size_string(&alu, 1e4, 2.0).unwrap();
/// assert!((s.mass - 0.490909).abs() < 1e-6);
/// assert!(sizing::size_string(&alu, -1.0, 2.0).is_none());
/// ```
pub fn size_string(material: &Material, force: f64, length: f64) -> Option<MemberSize> {
    if force < 0.0 {
        return None;
    }
    let governing = if force == 0.0 {
        Governing::Unloaded
    } else {
        Governing::Yield
    };
    let m = yield_mass(material, force, length);
    Some(MemberSize {
        force,
        length,
        radius: yield_radius(material, force),
        mass: m,
        yield_mass: m,
        buckling_mass: None,
        governing,
    })
}

/// Sizes a bar: yield in tension, max(yield, buckling) in compression.
///
/// ```
/// use tensegrity_core::Material;
/// use tensegrity_statics::{sizing, sizing::Governing};
/// let alu = Material::new(2700.0, 60e9, 110e6);
/// let b = sizing::size_bar(&alu, -1e4, 2.0);
/// assert_eq!(b.governing, Governing::Buckling);
/// assert!((b.mass - 4.975116).abs() < 1e-6);
/// ```
pub fn size_bar(material: &Material, force: f64, length: f64) -> MemberSize {
    let m_y = yield_mass(material, force, length);
    let r_y = yield_radius(material, force);
    if force >= 0.0 {
        return MemberSize {
            force,
            length,
            radius: r_y,
            mass: m_y,
            yield_mass: m_y,
            buckling_mass: None,
            governing: if force == 0.0 {
                Governing::Unloaded
            } else {
                Governing::Yield
            },
        };
    }
    let m_b = buckling_mass(material, force, length);
    let r_b = buckling_radius(material, force, length);
    let (radius, mass, governing) = if m_b > m_y {
        (r_b, m_b, Governing::Buckling)
    } else {
        (r_y, m_y, Governing::Yield)
    };
    MemberSize {
        force,
        length,
        radius,
        mass,
        yield_mass: m_y,
        buckling_mass: Some(m_b),
        governing,
    }
}

/// Sizes of every member of a structure for given member forces.
#[derive(Debug, Clone, PartialEq)]
pub struct SizingReport {
    /// One entry per column: bars, strings, then clusters (a cluster sized like a string
    /// from its tension, over its total length).
    pub members: Vec<MemberSize>,
    /// Σ mass of the bars (kg).
    pub bar_mass: f64,
    /// Σ mass of the strings and clusters (kg).
    pub string_mass: f64,
    /// Total mass (kg).
    pub total_mass: f64,
    /// Total mass if only yield were considered (kg).
    pub yield_only_mass: f64,
    /// The clusters (indices among the clusters) that the lenient sizing found in
    /// compression and sized for yield on |t| ([`size_structure_lenient`]).
    pub compressed_clusters: Vec<usize>,
}

/// Sizes every member of `structure` for the axial forces `member_force` (bars then strings,
/// tension positive). Every loaded member needs a material; every string must be in tension
/// (forces within 1e-12 of the largest force count as zero).
pub fn size_structure(structure: &Structure, member_force: &DVector<f64>) -> Result<SizingReport> {
    size_members(structure, member_force, false).map(|(report, _)| report)
}

/// Like [`size_structure`], but a string in compression is sized for yield on |f| (its only
/// failure mode) instead of being an error; the strings so treated are returned, so that the
/// caller can warn that the design needs them replaced or prestressed.
///
/// ```
/// use nalgebra::DVector;
/// use tensegrity_core::{Bar, Material, MemberId, StringMember, Structure};
/// use tensegrity_statics::sizing;
/// let s = Structure::builder()
///     .material("alu", Material::new(2700.0, 60e9, 110e6))
///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]])
///     .bar(Bar::new(0, 1).material("alu"))
///     .string(StringMember::new(1, 2).material("alu"))
///     .string(StringMember::new(2, 0).material("alu"))
///     .build()
///     .unwrap();
/// let f = DVector::from_row_slice(&[-1e3, -1e4, 2e3]);
/// assert!(sizing::size_structure(&s, &f).is_err());
/// let (report, compressed) = sizing::size_structure_lenient(&s, &f).unwrap();
/// assert_eq!(compressed, vec![MemberId::String(0)]);
/// assert!((report.members[1].mass - 2700.0 / 110e6 * 1e4 * 2f64.sqrt()).abs() < 1e-12);
/// ```
pub fn size_structure_lenient(
    structure: &Structure,
    member_force: &DVector<f64>,
) -> Result<(SizingReport, Vec<MemberId>)> {
    size_members(structure, member_force, true)
}

fn size_members(
    structure: &Structure,
    member_force: &DVector<f64>,
    lenient: bool,
) -> Result<(SizingReport, Vec<MemberId>)> {
    let mut compressed = Vec::new();
    let mut compressed_clusters = Vec::new();
    let lengths = crate::column_lengths(structure);
    let f_scale = member_force.amax();
    let mut members = Vec::with_capacity(lengths.len());
    let (mut bar_mass, mut string_mass, mut yield_only) = (0.0, 0.0, 0.0);
    for (k, &l) in lengths.iter().enumerate() {
        let mut f = member_force[k];
        if f.abs() <= 1e-12 * f_scale {
            f = 0.0;
        }
        let Some(material) = column_material(structure, k, f)? else {
            members.push(MemberSize {
                force: 0.0,
                length: l,
                radius: 0.0,
                mass: 0.0,
                yield_mass: 0.0,
                buckling_mass: None,
                governing: Governing::Unloaded,
            });
            continue;
        };
        let size = match crate::cluster_columns::column_member(structure, k) {
            Some(MemberId::Bar(_)) => {
                let s = size_bar(material, f, l);
                bar_mass += s.mass;
                s
            }
            id => {
                let s = match size_string(material, f, l) {
                    Some(s) => s,
                    None if lenient => {
                        match id {
                            Some(id) => compressed.push(id),
                            None => compressed_clusters.push(k - structure.n_members()),
                        }
                        MemberSize {
                            force: f,
                            ..size_bar(material, -f, l)
                        }
                    }
                    None => return Err(in_compression(structure, k, f)),
                };
                string_mass += s.mass;
                s
            }
        };
        yield_only += size.yield_mass;
        members.push(size);
    }
    let report = SizingReport {
        members,
        bar_mass,
        string_mass,
        total_mass: bar_mass + string_mass,
        yield_only_mass: yield_only,
        compressed_clusters,
    };
    Ok((report, compressed))
}

/// The material of column `k` (a member's, or a cluster's `material`); `None` for an
/// unloaded column without one; an error naming a loaded one without.
fn column_material(structure: &Structure, k: usize, f: f64) -> Result<Option<&Material>> {
    let material = match crate::cluster_columns::column_member(structure, k) {
        Some(id) => structure.member_material(id),
        None => structure.clusters()[k - structure.n_members()]
            .material
            .as_deref()
            .and_then(|name| structure.materials().get(name)),
    };
    match (material, f == 0.0) {
        (Some(m), _) => Ok(Some(m)),
        (None, true) => Ok(None),
        (None, false) => Err(match crate::cluster_columns::column_member(structure, k) {
            Some(member) => ModelError::MissingProperty {
                member,
                analysis: "sizing",
                property: "material",
            }
            .into(),
            None => crate::stiffness::missing_cluster_property(
                k - structure.n_members(),
                "sizing",
                "material",
            ),
        }),
    }
}

/// The error of a string or cluster (column `k`) in compression `f`.
fn in_compression(structure: &Structure, k: usize, f: f64) -> tensegrity_core::CoreError {
    match crate::cluster_columns::column_member(structure, k) {
        Some(member) => StaticsError::StringInCompression { member, force: f }.into(),
        None => ModelError::InvalidCluster {
            cluster: k - structure.n_members(),
            reason: format!(
                "in compression ({f:.6e} N) for the loads: a cluster carries tension only; add prestress (a self-stress) or replace it with bars"
            ),
        }
        .into(),
    }
}
