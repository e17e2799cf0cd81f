//! Convergence of a dynamic result: each headline quantity re-estimated by a companion run at
//! another resolution (half the step, or twice it where the coarser run is inside the method's
//! stability; for a penalty contact the ground stiffness moves with the step) and its error
//! extrapolated with the method's documented order; and, where a motion may be chaotic, a
//! twin run started 10⁻⁶ away that tells a chaotic quantity from a converging one.
//!
//! **Relative change.** For a quantity q with value q_h at the run's resolution and q_c at the
//! companion's, r = |q_c − q_h| / max(|q_h|, |q_c|, s), with s the quantity's scale floor (so
//! that a quantity near zero is judged absolutely, e.g. s = 1 for a fraction of the run). A
//! quantity compared as a whole (the final nodes or velocities, [`Convergence::compare_change`])
//! takes the largest difference d between the two runs against its magnitude m and its scale
//! s, r = d / max(m, s): a structure come to rest is judged on the speed √(g L) of its size L,
//! not against its own noise. Each caller states its scales.
//!
//! **Extrapolated error** (Richardson). If q_h = q* + C hᵖ with the documented order p, the
//! error of the run's value is
//!
//! > e = r · 2ᵖ / (2ᵖ − 1)   with a refined companion (h/2),
//! > e = r / (kᵖ − 1)        with a coarse companion (kh, k = 2, 4 or 8),
//!
//! and the quantity is `converged` when e ≤ τ, its tolerance. A finer run (h/4, h/8, …) then
//! differs from the run's value by at most e (1 − 4⁻ᵖ) < τ. The order p is the caller's
//! ([`Convergence::order`], documented where it is chosen): 1 for a step halved through
//! contact events (every fixed-step scheme is first order at a landing), ½ where a penalty
//! ground's stiffness doubles with it (a touch-down lasts π√(m/k), so event times and
//! pivots move as k^(−½)). With p = 1 and a refined companion this is the old rule r ≤ τ/2.
//!
//! **Chaotic quantities** ([`Convergence::twin`], [`Convergence::twin_of_companion`]). A twin
//! run started from a state turned by 10⁻⁶ (rad) moves a quantity by r_twin against the run
//! it is compared with at its own resolution (the run itself, or the companion where the twin
//! runs at the companion's step). A quantity with r_twin > τ/8 is `chaotic`: the gap between
//! two draws of a chaotic motion (another start, another step) is about 2.5 r_twin on average,
//! so a single run cannot show it within τ. It is not `converged`, its value is one draw, and
//! its answer is an ensemble's interval (`--ensemble K`); it does not by itself make a result
//! unconverged, since no refinement could make it so ([`Convergence::converged`] judges the
//! other quantities). What the check has already run gives it an interval at no extra cost:
//! its three draws (the run, the companion at another step, the twin at another start) are a
//! small ensemble at two resolutions, and another draw (another start, or a finer step whose
//! bias is of the size the companion showed) lies with 95 % probability within the prediction
//! interval m ± t₀.₉₇₅,₂ · s · √(1 + 1/3) of their mean m and sample deviation s (Student's t
//! at 2 degrees of freedom, 4.303, for a spread estimated from three draws): `interval`.
//!
//! **The lazy twin** ([`Convergence::twin_needed`]). A caller that may meet chaos starts its
//! companion from the twin's start (turned by 10⁻⁶): the companion then differs from the run
//! by both a step and a start, and its change r of a quantity holds both effects, the step's
//! bias c and the start's t (r = |c + t|). Where every quantity has r ≤ τ/8 (and none is
//! missing from one run only), the start moved none by more than the twin's threshold τ/8 and
//! the step's error e = r·2ᵖ/(2ᵖ − 1) or r/(kᵖ − 1) is within τ (for p ≥ ½): every quantity
//! is converged and none is chaotic, and no twin runs. The rule holds barring a cancellation
//! of c and t to within τ/8 where both exceed it, as unlikely as a chaotic quantity's single
//! twin landing within τ/8 of the run. Why the companion must carry the perturbation rather
//! than stand in for it: a step change is not a larger perturbation than 10⁻⁶ everywhere. The
//! rigid rolling model locates its events to round-off and integrates its smooth phases by
//! RK4, so halving its step moves the first impact by 10⁻¹⁴ (the default n = 8 wheel on 50°:
//! 1.6·10⁻¹⁴ of its time) where the twin moves it by 5·10⁻⁷; there the impact count agreed at
//! both steps (16) and the twin's was 17 (a chaotic quantity the step change alone does not
//! show). Where some quantity moved by more than τ/8, a second run separates the two effects:
//! the companion from the run's own start (at the companion's step, so that the perturbed run
//! is the twin, compared with it at the same resolution: [`Convergence::twin_of_companion`]),
//! or, where that would cost more than a twin at the run's step (a refined companion), the
//! twin at the run's step ([`Convergence::twin`]). Without a twin no quantity has
//! `twin_change` or `interval` (null: a converged quantity needs no interval).
//!
//! **Which companion.** A coarse companion (kh) serves where kh stays inside the method's
//! stability with a margin, kh · λ ≤ [`STABILITY_MARGIN`] × [`stability_bound`] for the
//! fastest rate λ its explicit part must resolve ([`explicit_rate`]), and inside the run
//! (kh ≤ t_end, and no longer than an output interval where the steps are cut at the samples).
//! Each caller takes the coarsest of the ratios it allows ([`Companion::COARSE`]) and states
//! why: `simulate` 4h, else 2h; the rigid rolling model 8h; the full rolling model 4h where
//! 4h is within half its default step, else 2h (its estimate deciding only within τ/2:
//! `wheel_rolling::convergence`). The
//! coarser the companion, the cheaper (¼ of the run at 4h, ⅛ at 8h), and the more the
//! order-1 rule over-states the error of a higher-order method (RK4 on a smooth scene: 85-fold
//! at 4h, 15-fold at 2h): a caller whose quantity is past its tolerance at 4h or 8h checks it
//! again with a finer companion, whose verdict stands. Otherwise, and for adaptive methods,
//! it is refined (h/2). A coarse run that fails or leaves its regime (its state not finite, a
//! drift or validity warning the run does not carry) is followed by the refined one, its cost
//! added.
//!
//! A quantity that is neither converged nor chaotic makes the whole result unconverged
//! ([`Convergence::converged`]), which a result then reports as not valid
//! ([`Convergence::warnings`]). The error bar's cost is stated ([`Convergence::cost`]: the
//! companion and twin runs' work relative to the run's: 2 for h/2, 1/k for kh (½, ¼, ⅛), +1
//! for a twin at the run's step, +1/k for a second run at kh, +1/k for a coarse run that
//! failed before a refined one).

use serde::{Deserialize, Serialize};
use tensegrity_core::warning::Warning;
use tensegrity_derive::Columns;

use crate::IntegratorKind;

/// The fraction of its tolerance a twin run may move a quantity before it is chaotic
/// (module docs).
pub const CHAOS_FRACTION: f64 = 0.125;

/// The relative perturbation of a twin run's start (rad for a turned pose).
pub const TWIN_PERTURBATION: f64 = 1e-6;

/// The fraction of a method's stability bound a coarse companion's step may use
/// (2h · λ ≤ margin × bound, module docs): it keeps the coarse run where its error behaves as
/// C (2h)ᵖ; near the edge of the stability region the amplification of the fastest mode, not
/// the truncation error, sets the difference.
pub const STABILITY_MARGIN: f64 = 0.5;

/// The largest h·λ of an explicit step (the edge of its stability region, module docs), for
/// the fixed-step methods; `None` for the adaptive ones and Newmark (their companion is
/// refined). Taken as the smallest radius over the rays of the damped oscillations
/// λ(−ζ + i√(1−ζ²)), 0 ≤ ζ ≤ 1, that a string or a penalty ground makes: RK4 2.6 (2.83 on the
/// imaginary axis, 2.79 on the real one, 2.62 at ζ = ½), ARK3(2)4L\[2\]SA's explicit tableau
/// 2.4 (2.49 on the imaginary axis), RATTLE (Störmer–Verlet) 2 (ω h < 2). IMEX's explicit
/// part is one RK4 step, and rk4-flight's inner method is RK4.
///
/// ```
/// use tensegrity_dynamics::{convergence::stability_bound, IntegratorKind};
/// assert_eq!(stability_bound(IntegratorKind::Rk4), Some(2.6));
/// assert_eq!(stability_bound(IntegratorKind::Sdirk), None);
/// ```
pub fn stability_bound(kind: IntegratorKind) -> Option<f64> {
    match kind {
        IntegratorKind::Rk4 | IntegratorKind::Imex | IntegratorKind::Rk4Flight => Some(2.6),
        IntegratorKind::ImexArk => Some(2.4),
        IntegratorKind::Rattle => Some(2.0),
        IntegratorKind::Rk45 | IntegratorKind::Sdirk | IntegratorKind::Newmark => None,
    }
}

/// The fastest rate λ (1/s) the explicit part of `kind` must resolve on `model` (module
/// docs), with m a quarter of the lightest bar's mass (a bar end's effective mass): √(2k/m)
/// of every string's and the ground's spring (a penalty or stick ground's normal stiffness,
/// and the stick's tangential one), and 2c/m of their dampers where the method treats them
/// explicitly. IMEX and IMEX-ARK take the ground's dampers (normal, tangential, the
/// regularised friction's slope) in their implicit part, so only the ground's springs count
/// for them; for every other method this is
/// [`fastest_rate`](crate::estimate::fastest_rate) (and the stick's tangential spring and
/// damper). A thesis ground's damping counts for every method (conservative). The regularised
/// friction's slope μN/v_reg, which depends on the load, is not counted: an explicit method
/// whose step it bounds shows it as a coarse run that fails or drifts, and the refined
/// companion follows.
pub fn explicit_rate(model: &crate::Model, kind: IntegratorKind) -> f64 {
    let Some((rate, strings)) = crate::estimate::spring_rates(model) else {
        return 0.0;
    };
    let implicit_damping = matches!(kind, IntegratorKind::Imex | IntegratorKind::ImexArk);
    let damping = |c: f64| if implicit_damping { 0.0 } else { c };
    let ground = match model.ground.as_ref().map(|g| &g.model) {
        Some(crate::GroundModel::Penalty {
            stiffness,
            damping: c,
            ..
        }) => rate(*stiffness, damping(*c)),
        Some(crate::GroundModel::Stick {
            stiffness,
            damping: c,
            tangential_stiffness,
            tangential_damping,
            ..
        }) => rate(*stiffness, damping(*c))
            .max(rate(*tangential_stiffness, damping(*tangential_damping))),
        Some(crate::GroundModel::Thesis { damping: c, .. }) => rate(0.0, *c),
        None => 0.0,
    };
    strings.max(ground)
}

/// Which resolution the companion run has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Companion {
    /// Half the step (costs twice the run).
    #[default]
    Refined,
    /// Twice the step (costs half the run); used where 2h stays inside the method's stability
    /// (module docs, "Which companion").
    Coarse,
    /// Four times the step (costs a quarter of the run); used where 4h stays inside the
    /// method's stability and the caller's other conditions (module docs, "Which companion").
    Coarser,
    /// Eight times the step (costs an eighth of the run); used by the rigid rolling model,
    /// whose events are located to round-off whatever the step (`wheel_rolling::convergence`).
    Coarsest,
}

impl Companion {
    /// The companion's step over the run's: ½, 2, 4 or 8.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Companion;
    /// assert_eq!(Companion::Coarser.step_ratio(), 4.0);
    /// assert_eq!(Companion::Refined.step_ratio(), 0.5);
    /// ```
    pub fn step_ratio(self) -> f64 {
        match self {
            Companion::Refined => 0.5,
            Companion::Coarse => 2.0,
            Companion::Coarser => 4.0,
            Companion::Coarsest => 8.0,
        }
    }

    /// The coarse companions, the cheapest first: 8h, 4h, then 2h (each caller states which
    /// it allows).
    pub const COARSE: [Companion; 3] = [Companion::Coarsest, Companion::Coarser, Companion::Coarse];

    /// The companion run's work relative to the run's: the inverse of its step ratio.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Companion;
    /// assert_eq!(
    ///     Companion::COARSE.map(Companion::cost),
    ///     [0.125, 0.25, 0.5]
    /// );
    /// ```
    pub fn cost(self) -> f64 {
        1.0 / self.step_ratio()
    }

    /// e / r for a method of order `p` (module docs): 2ᵖ/(2ᵖ − 1) for h/2, and 1/(kᵖ − 1)
    /// for a coarse step kh (1/(2ᵖ − 1) for 2h, 1/(4ᵖ − 1) for 4h).
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Companion;
    /// assert_eq!(Companion::Refined.error_factor(1.0), 2.0);
    /// assert_eq!(Companion::Coarse.error_factor(1.0), 1.0);
    /// assert!((Companion::Coarser.error_factor(1.0) - 1.0 / 3.0).abs() < 1e-15);
    /// ```
    pub fn error_factor(self, p: f64) -> f64 {
        match self {
            Companion::Refined => {
                let g = 2f64.powf(p);
                g / (g - 1.0)
            }
            Companion::Coarse | Companion::Coarser | Companion::Coarsest => {
                1.0 / (self.step_ratio().powf(p) - 1.0)
            }
        }
    }

    /// How the companion's run differs from the run, for a label: `dt/2`, `2 dt`, `4 dt`,
    /// `8 dt`.
    pub fn step_label(self) -> &'static str {
        match self {
            Companion::Refined => "dt/2",
            Companion::Coarse => "2 dt",
            Companion::Coarser => "4 dt",
            Companion::Coarsest => "8 dt",
        }
    }
}

/// What the checks concluded about one quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Its extrapolated error is within its tolerance.
    #[default]
    Converged,
    /// Its extrapolated error exceeds its tolerance (or one run lacks it).
    NotConverged,
    /// A twin run 10⁻⁶ away moved it by more than [`CHAOS_FRACTION`] of its tolerance: one draw.
    Chaotic,
}

/// One headline quantity at the run's and at the companion's resolution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuantityConvergence {
    /// The quantity's report key (e.g. `mean_speed`, `first_impact.t`).
    pub name: String,
    /// Its value in the result (null when the run has none, e.g. no impact).
    pub value: Option<f64>,
    /// Its value at the companion resolution (the refined one, or the coarse one where
    /// the convergence's `companion` is `coarse`).
    pub refined: Option<f64>,
    /// |companion − value| / max(|value|, |companion|, scale) (module docs); null when one of
    /// the two is missing.
    pub relative_change: Option<f64>,
    /// The value's error extrapolated with the documented order (module docs), relative as
    /// `relative_change`; null when one of the two is missing.
    #[serde(default)]
    pub estimated_error: Option<f64>,
    /// The tolerance τ of this quantity: converged when the estimated error is at most τ.
    pub tolerance: f64,
    /// Whether the quantity held within its tolerance (false for a chaotic one).
    pub converged: bool,
    /// The twin run's relative change of it (module docs): against the run, or against the
    /// companion where the twin ran at the companion's step; null where no twin ran (the
    /// lazy twin, module docs).
    #[serde(default)]
    pub twin_change: Option<f64>,
    /// `converged`, `not_converged` or `chaotic` (module docs).
    #[serde(default)]
    pub status: Status,
    /// For a chaotic quantity, the 95 % prediction interval of another draw (another start or
    /// a finer step) from its three draws: the run, the companion run (another step) and the
    /// twin (another start), m ± t₀.₉₇₅,₂ · s · √(1 + 1/3) with their mean m, their sample
    /// deviation s and Student's t at 2 degrees of freedom (4.303) (module docs). Null
    /// otherwise (a converged quantity needs none), or when a draw is missing.
    #[serde(default)]
    pub interval: Option<[f64; 2]>,
    /// The scale floor s of the relative changes (module docs), kept for the twin's.
    #[serde(skip)]
    scale: f64,
}

impl QuantityConvergence {
    /// The scale floor s of its relative changes (module docs; 0 after a round trip through
    /// JSON, which does not carry it).
    ///
    /// ```
    /// use tensegrity_dynamics::{convergence::Companion, Convergence};
    /// let mut c = Convergence::with("2 dt", Companion::Coarse, 1.0);
    /// c.compare("airborne_fraction", Some(0.01), Some(0.02), 0.02, 1.0);
    /// let q = &c.quantities[0];
    /// assert_eq!(q.scale(), 1.0);
    /// assert_eq!(q.relative_change, Some(0.01));
    /// ```
    pub fn scale(&self) -> f64 {
        self.scale
    }
}

/// Student's t at 2 degrees of freedom, two-sided 95 %.
const STUDENT_T_975_2: f64 = 4.302_652_729_911_275;

/// The 95 % prediction interval of a fourth draw of a chaotic quantity from its three draws
/// (the run's value, the companion's, the twin's): m ± t · s · √(1 + 1/3) (module docs);
/// `None` when a draw is missing or not finite.
fn prediction_interval(value: Option<f64>, companion: Option<f64>, twin: f64) -> Option<[f64; 2]> {
    let draws = [value?, companion?, twin];
    if !draws.iter().all(|v| v.is_finite()) {
        return None;
    }
    let mean = draws.iter().sum::<f64>() / 3.0;
    let variance = draws.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 2.0;
    let half = STUDENT_T_975_2 * variance.sqrt() * (4.0f64 / 3.0).sqrt();
    Some([mean - half, mean + half])
}

/// The convergence of a result's headline quantities (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Columns, Deserialize)]
pub struct Convergence {
    /// What the companion run changed, e.g. `dt/2`.
    pub refinement: String,
    /// Whether every quantity that is not chaotic held within its tolerance.
    pub converged: bool,
    /// Whether the companion is finer (`refined`) or coarser (`coarse`).
    #[serde(default)]
    pub companion: Companion,
    /// The documented order p used to extrapolate the error (module docs).
    #[serde(default = "one")]
    pub order: f64,
    /// The error bar's work: the companion (and twin) runs relative to the run itself.
    #[serde(default)]
    pub cost: f64,
    /// Each headline quantity.
    pub quantities: Vec<QuantityConvergence>,
}

fn one() -> f64 {
    1.0
}

impl Convergence {
    /// An empty comparison against a refined companion (h/2) of a first-order refinement
    /// described by `refinement`: converged when a quantity moves by at most τ/2.
    pub fn new(refinement: impl Into<String>) -> Self {
        Self::with(refinement, Companion::Refined, 1.0)
    }

    /// An empty comparison against `companion` for a refinement of documented order `order`.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::{Companion, Convergence};
    /// // a coarse companion (2h) of a first-order method: the error is the change itself
    /// let mut c = Convergence::with("2 dt", Companion::Coarse, 1.0);
    /// c.compare("mean_speed", Some(10.0), Some(10.15), 0.02, 0.0);
    /// assert!(c.converged);
    /// assert!((c.quantities[0].estimated_error.unwrap() - 0.15 / 10.15).abs() < 1e-12);
    /// // order ½ (a penalty ground refined with the step): 2.41 times the change
    /// let mut k = Convergence::with("2 dt, ground stiffness / 2", Companion::Coarse, 0.5);
    /// k.compare("mean_speed", Some(10.0), Some(10.15), 0.02, 0.0);
    /// assert!(!k.converged);
    /// ```
    pub fn with(refinement: impl Into<String>, companion: Companion, order: f64) -> Self {
        Self {
            refinement: refinement.into(),
            converged: true,
            companion,
            order,
            cost: companion.cost(),
            quantities: Vec::new(),
        }
    }

    /// Compares `value` with the companion's value `refined` (module docs): relative to the
    /// larger of the two and of `scale`, extrapolated with the order, within `tolerance`. Both
    /// missing counts as converged (nothing to compare), one missing as not converged (the
    /// companion run found, or lost, an event).
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Convergence;
    /// let mut c = Convergence::new("dt/2");
    /// c.compare("mean_speed", Some(10.0), Some(10.05), 0.02, 0.0);
    /// assert!(c.converged);
    /// c.compare("final_speed", Some(10.0), Some(10.2), 0.02, 0.0);
    /// assert!(!c.converged && !c.quantities[1].converged);
    /// assert_eq!(c.warnings().len(), 1);
    /// ```
    pub fn compare(
        &mut self,
        name: &str,
        value: Option<f64>,
        refined: Option<f64>,
        tolerance: f64,
        scale: f64,
    ) -> &mut Self {
        let relative_change = match (value, refined) {
            (Some(a), Some(b)) => {
                let denominator = a.abs().max(b.abs()).max(scale);
                Some(if denominator > 0.0 {
                    (b - a).abs() / denominator
                } else {
                    0.0
                })
            }
            _ => None,
        };
        let both_missing = value.is_none() && refined.is_none();
        self.push(
            name,
            [value, refined],
            relative_change,
            [tolerance, scale],
            both_missing,
        );
        self
    }

    /// Records a quantity whose change was measured directly (e.g. the largest distance
    /// between two runs' final nodes): `change` against the larger of its `magnitude` and
    /// its `scale` (module docs), extrapolated with the order, within `tolerance`, with no
    /// single value to show. A NaN change counts as unconverged; a zero denominator as no
    /// change.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Convergence;
    /// let mut c = Convergence::new("dt/2");
    /// // final speeds of 1 mm/s that moved by 0.5 mm/s, judged against a 3 m/s scale
    /// c.compare_change("final_velocities", 5e-4, 1e-3, 3.0, 0.02);
    /// assert!(c.converged);
    /// assert!((c.quantities[0].relative_change.unwrap() - 5e-4 / 3.0).abs() < 1e-15);
    /// // the same change against the speeds alone: 50 %
    /// c.compare_change("final_velocities", 5e-4, 1e-3, 0.0, 0.02);
    /// assert!(!c.converged);
    /// ```
    pub fn compare_change(
        &mut self,
        name: &str,
        change: f64,
        magnitude: f64,
        scale: f64,
        tolerance: f64,
    ) -> &mut Self {
        let denominator = magnitude.abs().max(scale);
        let relative_change = if denominator > 0.0 {
            change / denominator
        } else if change == 0.0 {
            0.0
        } else {
            f64::INFINITY
        };
        self.push(
            name,
            [None, None],
            Some(relative_change),
            [tolerance, scale],
            false,
        );
        self
    }

    fn push(
        &mut self,
        name: &str,
        [value, refined]: [Option<f64>; 2],
        relative_change: Option<f64>,
        [tolerance, scale]: [f64; 2],
        nothing_to_compare: bool,
    ) {
        let estimated_error = relative_change.map(|r| r * self.companion.error_factor(self.order));
        // NaN errors count as unconverged
        let converged = nothing_to_compare || estimated_error.is_some_and(|e| e <= tolerance);
        self.converged &= converged;
        self.quantities.push(QuantityConvergence {
            name: name.to_string(),
            value,
            refined,
            relative_change,
            estimated_error,
            tolerance,
            converged,
            twin_change: None,
            interval: None,
            status: if converged {
                Status::Converged
            } else {
                Status::NotConverged
            },
            scale,
        });
    }

    /// Judges the quantities against a twin run at the run's own resolution started
    /// [`TWIN_PERTURBATION`] away (module docs): `twin` gives, per quantity name, the twin's
    /// value (`compare`d quantities) or its measured change (`compare_change`d ones, relative
    /// as there). A quantity the twin moves by more than [`CHAOS_FRACTION`] of its tolerance is
    /// `chaotic`, no longer converged, and no longer counts against [`Convergence::converged`].
    /// Adds the twin's cost (1).
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::{Convergence, Status};
    /// let mut c = Convergence::new("dt/2");
    /// c.compare("first_impact.t", Some(0.70), Some(0.7001), 0.01, 0.0)
    ///     .compare("final_speed", Some(44.4), Some(47.3), 0.02, 1e-3);
    /// assert!(!c.converged);
    /// // a start turned by 1e-6 rad moves the final speed by 6 %: chaotic, a single draw
    /// c.twin(|name| match name {
    ///     "first_impact.t" => Some(0.70000001),
    ///     _ => Some(47.1),
    /// });
    /// assert_eq!(c.quantities[1].status, Status::Chaotic);
    /// assert!(c.converged && c.warnings().is_empty());
    /// assert_eq!(c.chaotic(), vec!["final_speed"]);
    /// assert_eq!(c.cost, 3.0);
    /// // its three draws (run 44.4, refined 47.3, twin 47.1): mean 46.27, deviation 1.62,
    /// // another draw within 46.27 ± 4.303 · 1.62 · 1.155 = 46.27 ± 8.05 (95 %)
    /// let [lo, hi] = c.quantities[1].interval.unwrap();
    /// assert!((lo - 38.22).abs() < 0.01 && (hi - 54.31).abs() < 0.01);
    /// assert_eq!(c.quantities[0].interval, None);
    /// // a fraction near zero is judged on its scale (1) by the twin too: 10⁻⁴ of the run
    /// let mut f = Convergence::new("dt/2");
    /// f.compare("airborne_fraction", Some(0.0), Some(0.0), 0.02, 1.0);
    /// f.twin(|_| Some(1e-4));
    /// assert_eq!(f.quantities[0].status, Status::Converged);
    /// assert_eq!(f.quantities[0].twin_change, Some(1e-4));
    /// ```
    pub fn twin(&mut self, twin: impl Fn(&str) -> Option<f64>) -> &mut Self {
        self.cost += 1.0;
        self.judge_twin(false, twin)
    }

    /// As [`Convergence::twin`] for a twin run at the companion's resolution (module docs:
    /// the lazy twin): each quantity's twin value is compared with the companion's value
    /// (`refined`), at the same step, and the twin's cost is the companion's.
    /// `compare_change`d quantities take the twin's change against the companion as given.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::{Companion, Convergence, Status};
    /// let mut c = Convergence::with("2 dt", Companion::Coarse, 1.0);
    /// c.compare("mean_speed", Some(10.0), Some(10.01), 0.02, 0.0)
    ///     .compare("final_speed", Some(44.4), Some(45.0), 0.02, 0.0);
    /// assert!(c.twin_needed());
    /// // the twin at 2 dt moves the final speed by 4 % from the companion: chaotic
    /// c.twin_of_companion(|name| match name {
    ///     "mean_speed" => Some(10.0101),
    ///     _ => Some(46.8),
    /// });
    /// assert_eq!(c.cost, 1.0);
    /// assert_eq!(c.quantities[0].status, Status::Converged);
    /// assert_eq!(c.quantities[1].status, Status::Chaotic);
    /// assert!((c.quantities[1].twin_change.unwrap() - 1.8 / 46.8).abs() < 1e-12);
    /// ```
    pub fn twin_of_companion(&mut self, twin: impl Fn(&str) -> Option<f64>) -> &mut Self {
        self.cost += self.companion.cost();
        self.judge_twin(true, twin)
    }

    /// Whether a twin must run (module docs, the lazy twin): some quantity's change against a
    /// companion that started from the twin's start exceeds [`CHAOS_FRACTION`] of its
    /// tolerance, or is missing (one run has the quantity, the other not; a NaN change too).
    /// Otherwise every quantity is converged and none can be chaotic.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::{Companion, Convergence};
    /// let mut c = Convergence::with("2 dt", Companion::Coarse, 1.0);
    /// c.compare("mean_speed", Some(10.0), Some(10.02), 0.02, 0.0);
    /// assert!(!c.twin_needed() && c.converged);
    /// // 1.5 % is converged (e ≤ 2 %) but more than τ/8: it could be a chaotic draw
    /// c.compare("final_speed", Some(10.0), Some(10.15), 0.02, 0.0);
    /// assert!(c.converged && c.twin_needed());
    /// ```
    pub fn twin_needed(&self) -> bool {
        self.quantities.iter().any(|q| match q.relative_change {
            Some(r) => r.is_nan() || r > CHAOS_FRACTION * q.tolerance,
            None => !q.converged,
        })
    }

    fn judge_twin(&mut self, of_companion: bool, twin: impl Fn(&str) -> Option<f64>) -> &mut Self {
        for q in &mut self.quantities {
            let Some(t) = twin(&q.name) else { continue };
            let reference = if of_companion { q.refined } else { q.value };
            let change = match reference {
                Some(v) => {
                    let d = v.abs().max(t.abs()).max(q.scale);
                    if d > 0.0 {
                        (t - v).abs() / d
                    } else {
                        0.0
                    }
                }
                // a `compare_change`d quantity: the twin's change as given
                None => t,
            };
            q.twin_change = Some(change);
            // a NaN change counts as chaotic (nothing certain about it)
            if change.is_nan() || change > CHAOS_FRACTION * q.tolerance {
                q.status = Status::Chaotic;
                q.converged = false;
                q.interval = prediction_interval(q.value, q.refined, t);
            }
        }
        self.converged = self
            .quantities
            .iter()
            .all(|q| q.converged || q.status == Status::Chaotic);
        self
    }

    /// Clips the interval of each quantity in `names` to the range `[lo, hi]` its values can
    /// take (a count or a largest magnitude is never negative, a fraction or a yes/no at most
    /// 1): the prediction interval assumes a spread symmetric about the draws' mean, which
    /// such a quantity's cannot be near its bound. Call after [`Convergence::twin`].
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Convergence;
    /// let mut c = Convergence::new("dt/2");
    /// c.compare("max_lean", Some(0.09), Some(0.22), 0.05, 0.01);
    /// c.twin(|_| Some(0.02));
    /// assert!(c.quantities[0].interval.unwrap()[0] < 0.0);
    /// c.bound(&["max_lean"], [0.0, f64::INFINITY]);
    /// assert_eq!(c.quantities[0].interval.unwrap()[0], 0.0);
    /// ```
    pub fn bound(&mut self, names: &[&str], [lo, hi]: [f64; 2]) -> &mut Self {
        for q in self.quantities.iter_mut() {
            if let (true, Some([a, b])) = (names.contains(&q.name.as_str()), q.interval) {
                q.interval = Some([a.clamp(lo, hi), b.clamp(lo, hi)]);
            }
        }
        self
    }

    /// Marks `name` chaotic because it is decided by a chaotic quantity whose interval
    /// straddles the decision's threshold (e.g. whether a wobbling wheel ends past its tip
    /// angle): no refinement can settle it either. Its interval stays unset (a decision has
    /// none); the result's `converged` is judged again. Unknown names are ignored.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::{Convergence, Status};
    /// let mut c = Convergence::new("dt/2");
    /// c.compare("fell", Some(1.0), Some(0.0), 0.5, 1.0);
    /// assert!(!c.converged);
    /// c.mark_chaotic("fell");
    /// assert_eq!(c.quantities[0].status, Status::Chaotic);
    /// assert!(c.converged && c.warnings().is_empty());
    /// ```
    pub fn mark_chaotic(&mut self, name: &str) -> &mut Self {
        for q in self.quantities.iter_mut().filter(|q| q.name == name) {
            q.status = Status::Chaotic;
            q.converged = false;
        }
        self.converged = self
            .quantities
            .iter()
            .all(|q| q.converged || q.status == Status::Chaotic);
        self
    }

    /// The names of the chaotic quantities (module docs).
    pub fn chaotic(&self) -> Vec<&str> {
        self.quantities
            .iter()
            .filter(|q| q.status == Status::Chaotic)
            .map(|q| q.name.as_str())
            .collect()
    }

    /// One warning per quantity that did not converge and is not chaotic
    /// ([`Warning::NotConverged`]); for a result marked unconverged with no such quantity (its
    /// companion run failed), one [`Warning::RefinementFailed`] naming the refinement.
    pub fn warnings(&self) -> Vec<Warning> {
        let unconverged = |q: &&QuantityConvergence| q.status == Status::NotConverged;
        if !self.converged && !self.quantities.iter().any(|q| unconverged(&q)) {
            return vec![Warning::RefinementFailed {
                refinement: self.refinement.clone(),
            }];
        }
        self.quantities
            .iter()
            .filter(unconverged)
            .map(|q| Warning::NotConverged {
                quantity: q.name.clone(),
                value: q.value,
                refined: q.refined,
                relative_change: q.relative_change,
                estimated_error: q.estimated_error,
                tolerance: q.tolerance,
                refinement: self.refinement.clone(),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_implicit_methods_leave_the_ground_damper_out_of_the_explicit_rate() {
        use crate::test_models::{dropped_prism, dropped_prism_ground};
        let s = dropped_prism(0.1, 0.0).unwrap();
        let mut model = crate::Model::new(&s, None).unwrap();
        let bare = explicit_rate(&model, IntegratorKind::Rk4);
        assert_eq!(bare, crate::estimate::fastest_rate(&model));
        // a ground whose damper is far faster than its spring
        model.set_ground(dropped_prism_ground(1e4, 1e4)).unwrap();
        let rk4 = explicit_rate(&model, IntegratorKind::Rk4);
        assert_eq!(rk4, crate::estimate::fastest_rate(&model));
        let ark = explicit_rate(&model, IntegratorKind::ImexArk);
        assert_eq!(ark, explicit_rate(&model, IntegratorKind::Imex));
        assert!(ark < rk4 / 10.0 && ark >= bare, "{ark} {rk4} {bare}");
        // the spring counts for every method
        let mut stiff = crate::Model::new(&s, None).unwrap();
        stiff.set_ground(dropped_prism_ground(1e9, 0.0)).unwrap();
        let spring = explicit_rate(&stiff, IntegratorKind::ImexArk);
        assert!(spring > 10.0 * bare, "{spring} {bare}");
    }

    #[test]
    fn the_lazy_twin_runs_only_where_a_quantity_moved_past_an_eighth_of_its_tolerance() {
        let mut c = Convergence::with("2 dt", Companion::Coarse, 1.0);
        c.compare("a", Some(1.0), Some(1.001), 0.01, 0.0);
        assert!(!c.twin_needed());
        // an event found by one run only needs the twin
        let mut e = Convergence::with("2 dt", Companion::Coarse, 1.0);
        e.compare("first_impact.t", None, Some(0.7), 0.01, 0.0);
        assert!(e.twin_needed());
        // both missing: nothing moved
        let mut n = Convergence::with("2 dt", Companion::Coarse, 1.0);
        n.compare("first_impact.t", None, None, 0.01, 0.0);
        assert!(!n.twin_needed());
        // a NaN change needs it
        let mut x = Convergence::with("2 dt", Companion::Coarse, 1.0);
        x.compare("a", Some(f64::NAN), Some(1.0), 0.01, 0.0);
        assert!(x.twin_needed());
        // the twin at the companion's step is compared with the companion: the same
        // value as the companion is no change, whatever the run's value
        let mut t = Convergence::with("2 dt", Companion::Coarse, 1.0);
        t.compare("b", Some(1.0), Some(1.2), 0.1, 0.0);
        t.twin_of_companion(|_| Some(1.2));
        assert_eq!(t.quantities[0].twin_change, Some(0.0));
        assert_eq!(t.quantities[0].status, Status::NotConverged);
        assert_eq!(t.cost, 1.0);
    }

    #[test]
    fn a_change_within_half_the_tolerance_converges() {
        let mut c = Convergence::new("dt/2");
        c.compare("a", Some(1.0), Some(1.004), 0.01, 0.0);
        assert!(c.converged);
        c.compare("b", Some(1.0), Some(1.006), 0.01, 0.0);
        assert!(!c.converged);
        // a fraction near zero is compared on its scale
        let mut f = Convergence::new("dt/2");
        f.compare("airborne_fraction", Some(0.0), Some(0.004), 0.01, 1.0);
        assert!(f.converged, "{f:?}");
        // an event found by one run only
        let mut e = Convergence::new("dt/2");
        e.compare("first_impact.t", None, Some(0.7), 0.01, 0.0);
        assert!(!e.converged && e.warnings()[0].to_string().contains("none"));
        e.compare("x", None, None, 0.01, 0.0);
        assert_eq!(e.quantities.len(), 2);
        let nan = Convergence::new("dt/2")
            .compare("n", Some(f64::NAN), Some(1.0), 0.01, 0.0)
            .converged;
        assert!(!nan);
    }

    #[test]
    fn a_change_near_zero_is_judged_against_its_scale() {
        // velocities of a structure come to rest: 0.5 mm/s moved at the refined run of a
        // largest final speed of 2 mm/s (25 %), on a scale of 3 m/s
        let mut c = Convergence::new("dt/2");
        c.compare_change("final_velocities", 5e-4, 2e-3, 3.0, 0.02);
        assert!(c.converged, "{c:?}");
        let r = c.quantities[0].relative_change.unwrap();
        assert!((r - 5e-4 / 3.0).abs() < 1e-15, "{r}");
        // a change as large as the scale does not converge
        c.compare_change("final_nodes", 0.5, 0.0, 1.0, 0.01);
        assert!(!c.converged);
        // nothing to compare: converged; a NaN change: not
        let mut z = Convergence::new("dt/2");
        z.compare_change("x", 0.0, 0.0, 0.0, 0.01);
        assert!(z.converged && z.quantities[0].relative_change == Some(0.0));
        z.compare_change("y", f64::NAN, 1.0, 1.0, 0.01);
        assert!(!z.converged);
    }
}
