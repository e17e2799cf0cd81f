//! The scalar result columns of every command's report (what a sweep writes), in the
//! report's key order; nested keys as `outer.inner`. The tests check each list against the
//! reports' JSON.

use crate::column::{col, Column};

/// The scalars of [`toroid::ToroidReport`].
pub const TOROID: [Column; 17] = [
    col("nodes", ""),
    col("bars", ""),
    col("strings", ""),
    col("stabilize", ""),
    col("rank", ""),
    col("self_stress_dim", ""),
    col("prestressable", ""),
    col("prestress_margin", ""),
    col("internal_mechanisms", ""),
    col("mass_kg", "kg"),
    col("I1", "kg m^2"),
    col("spectral_gap.tolerance", ""),
    col("spectral_gap.sigma_above", ""),
    col("spectral_gap.sigma_below", ""),
    col("spectral_gap.ratio", ""),
    col("spectral_gap.block", ""),
    col("statics_warning", ""),
];

/// The scalars of [`toroid::TipoverReport`].
pub const TIPOVER: [Column; 8] = [
    col("mass_kg", "kg"),
    col("rho", ""),
    col("epsilon", ""),
    col("sigma", ""),
    col("cot_theta", ""),
    col("critical_lateral_force", "N"),
    col("normalized_friction", ""),
    col("min_friction_to_tip", ""),
];

/// The scalars of [`toroid::tipover_dynamic::DynamicTipoverReport`].
pub const TIPOVER_DYNAMIC: [Column; 16] = [
    col("sides", ""),
    col("outer_tread", "m"),
    col("mass_kg", "kg"),
    col("hub_height", "m"),
    col("static_threshold", "N"),
    col("dynamic_threshold", "N"),
    col("relative_difference", ""),
    col("max_lean", "rad"),
    col("final_lean", "rad"),
    col("static_tip_angle", "rad"),
    col("tipped", ""),
    col("tip_time", "s"),
    col("max_penetration", "m"),
    col("valid", ""),
    col("convergence.refinement", ""),
    col("convergence.converged", ""),
];

/// The result scalars of [`toroid::rolling_lean::LeanRollingReport`] (its echo of the inputs
/// `sides`, `outer_tread`, `incline`, `side_slope` left out: they are axis or fixed values).
pub const TIPOVER_ROLLING: [Column; 12] = [
    col("mass_kg", "kg"),
    col("static_critical_side_slope", "rad"),
    col("max_lean", "rad"),
    col("final_lean", "rad"),
    col("static_tip_angle", "rad"),
    col("fell", ""),
    col("fall_time", "s"),
    col("downhill", "m"),
    col("max_penetration", "m"),
    col("valid", ""),
    col("convergence.refinement", ""),
    col("convergence.converged", ""),
];

/// The scalars of [`michell3d::MichellReport`] (nested objects flattened with `.`; the keys
/// of the extra strings' check are left out).
pub const MICHELL: [Column; 13] = [
    col("params.complexity", ""),
    col("params.r0", "m"),
    col("params.beta", "rad"),
    col("params.phi", "rad"),
    col("params.geometry.kind", ""),
    col("params.geometry.delta", ""),
    col("params.geometry.epsilon", "rad"),
    col("method", ""),
    col("material", ""),
    col("prestress", "N"),
    col("mass_kg.yield", "kg"),
    col("mass_kg.yield_buckling", "kg"),
    col("normalized_yield_mass", ""),
];

/// The scalars of [`michell3d::optimize::Optimum`].
pub const MICHELL_OPTIMIZE: [Column; 16] = [
    col("geometry.kind", ""),
    col("geometry.delta", ""),
    col("geometry.epsilon", "rad"),
    col("radius_ratio", ""),
    col("beta", "rad"),
    col("phi", "rad"),
    col("complexity", ""),
    col("mass_kg", "kg"),
    col("member_mass_kg", "kg"),
    col("joint_mass_kg", "kg"),
    col("joints", ""),
    col("normalized_yield_mass", ""),
    col("continuum_normalized_mass", ""),
    col("planar_mass_kg", "kg"),
    col("mass_penalty", ""),
    col("searched_to", ""),
];

/// [`michell3d::MichellTable`] has no scalar: its rows are the table (`michell-table`).
pub const MICHELL_TABLE: [Column; 0] = [];

/// The scalars of [`tbar_wheel::TbarReport`] (nested objects flattened with `.`; the keys
/// of every layout and parameterisation).
pub const TBAR: [Column; 50] = [
    col("params.michell.complexity", ""),
    col("params.michell.r0", "m"),
    col("params.michell.beta", "rad"),
    col("params.michell.phi", "rad"),
    col("params.michell.geometry.kind", ""),
    col("params.michell.geometry.delta", ""),
    col("params.michell.geometry.epsilon", "rad"),
    col("params.bar_base", ""),
    col("params.layout.kind", ""),
    col("params.layout.offset", "m"),
    col("params.rim", ""),
    col("nodes", ""),
    col("bars", ""),
    col("rim", ""),
    col("rim_bars", ""),
    col("strings", ""),
    col("treads", ""),
    col("rank", ""),
    col("self_stress_dim", ""),
    col("mechanisms", ""),
    col("internal_mechanisms", ""),
    col("statics_method", ""),
    col("prestressable", ""),
    col("prestress_margin", ""),
    col("load", "N"),
    col("ea", "N"),
    col("min_prestress", "N"),
    col("critical_member.member", ""),
    col("critical_member.kind", ""),
    col("critical_member.index", ""),
    col("critical_member.tread", ""),
    col("critical_member.azimuth", "rad"),
    col("critical_member.polar", "rad"),
    col("prestress", "N"),
    col("slack_fraction", ""),
    col("bar_always_compressed", ""),
    col("min_strings_carrying", ""),
    col("bar_always_carries", ""),
    col("mass_kg", "kg"),
    col("mass.material", ""),
    col("mass.mass_kg", "kg"),
    col("mass.yield_mass_kg", "kg"),
    col("mass.michell_mass_kg", "kg"),
    col("mass.mass_ratio", ""),
    col("spectral_gap.tolerance", ""),
    col("spectral_gap.sigma_above", ""),
    col("spectral_gap.sigma_below", ""),
    col("spectral_gap.ratio", ""),
    col("spectral_gap.block", ""),
    col("statics_warning", ""),
];

/// The fields of [`tensegrity_dynamics::work_precision::Point`].
pub const INTEGRATORS: [Column; 7] = [
    col("scene", ""),
    col("integrator", ""),
    col("parameter", ""),
    col("steps", ""),
    col("rhs_evals", ""),
    col("error", "m"),
    col("wall_time_s", "s"),
];

/// The scalars of [`toroid::RollReport`], in its key order (validity included; the first
/// impact as `first_impact.*`, empty when there is none).
pub const ROLL: [Column; 33] = [
    col("fidelity", ""),
    col("fidelity_reason", ""),
    col("contact", ""),
    col("sides", ""),
    col("incline_rad", "rad"),
    col("t_end", "s"),
    col("mass_kg", "kg"),
    col("I1", "kg m^2"),
    col("mu", ""),
    col("restitution", ""),
    col("ground_damping", "N s/m"),
    col("integrator", ""),
    col("dt", "s"),
    col("valid", ""),
    col("impacts", ""),
    col("first_impact.t", "s"),
    col("first_impact.omega_before", "rad/s"),
    col("first_impact.omega_after", "rad/s"),
    col("axle_height_oscillation", "m"),
    col("mean_axle_height", "m"),
    col("mean_speed", "m/s"),
    col("final_speed", "m/s"),
    col("max_reaction", "N"),
    col("min_normal_force", "N"),
    col("airborne_fraction", ""),
    col("slip_fraction", ""),
    col("max_penetration", "m"),
    col("energy_balance_error", ""),
    col("lift_off_time", "s"),
    col("required_friction", ""),
    col("mean_slip_speed", "m/s"),
    col("convergence.refinement", ""),
    col("convergence.converged", ""),
];

/// The scalars of [`tbar_wheel::TbarRollReport`] and of its first row (`rows.0.…`: the first
/// number of treads — a sweep over `treads` gives one row a case): the T-bar run, the toroid
/// column and the tip-over.
pub const TBAR_ROLL: [Column; 33] = [
    col("model", ""),
    col("fidelity", ""),
    col("full_tensegrity_rolling", ""),
    col("structure", ""),
    col("rim", ""),
    col("incline_rad", "rad"),
    col("t_end", "s"),
    col("valid", ""),
    col("rows.0.treads", ""),
    col("rows.0.phi", "rad"),
    col("rows.0.tbar.mass_kg", "kg"),
    col("rows.0.tbar.I1", "kg m^2"),
    col("rows.0.tbar.impact_ratio", ""),
    col("rows.0.tbar.valid", ""),
    col("rows.0.tbar.impacts", ""),
    col("rows.0.tbar.first_impact.t", "s"),
    col("rows.0.tbar.axle_height_oscillation", "m"),
    col("rows.0.tbar.mean_speed", "m/s"),
    col("rows.0.tbar.final_speed", "m/s"),
    col("rows.0.tbar.min_normal_force", "N"),
    col("rows.0.tbar.airborne_fraction", ""),
    col("rows.0.tbar.slip_fraction", ""),
    col("rows.0.tbar.max_penetration", "m"),
    col("rows.0.tbar.energy_balance_error", ""),
    col("rows.0.tbar.convergence.converged", ""),
    col("rows.0.toroid.mass_kg", "kg"),
    col("rows.0.toroid.I1", "kg m^2"),
    col("rows.0.toroid.valid", ""),
    col("rows.0.toroid.impacts", ""),
    col("rows.0.toroid.axle_height_oscillation", "m"),
    col("rows.0.toroid.mean_speed", "m/s"),
    col("rows.0.tipover.critical_lateral_force", "N"),
    col("rows.0.tipover.min_friction_to_tip", ""),
];

/// The scalars of [`tensegrity_statics::StaticsReport`] (the optional ones empty when the report
/// leaves them out: no loads, no materials, no modes).
pub const STATICS: [Column; 25] = [
    col("nodes", ""),
    col("bars", ""),
    col("strings", ""),
    col("rank", ""),
    col("self_stress_dim", ""),
    col("mechanisms", ""),
    col("internal_mechanisms", ""),
    col("prestressable", ""),
    col("prestress_margin", ""),
    col("prestress_stable", ""),
    col("smallest_singular_value", ""),
    col("rank_tolerance", ""),
    col("residual", "N"),
    col("load_carried", ""),
    col("mass_kg", "kg"),
    col("sizing_warning", ""),
    col("modal_error", ""),
    col("sizing_error", ""),
    col("statics_method", ""),
    col("statics_warning", ""),
    col("spectral_gap.tolerance", ""),
    col("spectral_gap.sigma_above", ""),
    col("spectral_gap.sigma_below", ""),
    col("spectral_gap.ratio", ""),
    col("spectral_gap.block", ""),
];

/// The scalars of [`tensegrity_dynamics::SimulationReport`] (`wall_time_s` is measured:
/// it differs from run to run).
pub const SIMULATE: [Column; 9] = [
    col("t_end", "s"),
    col("steps", ""),
    col("rhs_evals", ""),
    col("energy_drift", ""),
    col("bar_length_drift", "m"),
    col("constraint_drift", "m"),
    col("wall_time_s", "s"),
    col("convergence.refinement", ""),
    col("convergence.converged", ""),
];

/// [`crate::bench::WorkPrecisionReport`] has no scalar: its points are the study (the
/// `integrators` study sweeps them one by one).
pub const BENCH_WORK_PRECISION: [Column; 0] = [];

/// The scalars of [`crate::formfind::FormfindReport`] (its lists — nodes, force densities,
/// member forces, rest lengths, warnings — are not columns).
pub const FORMFIND: [Column; 13] = [
    col("source", ""),
    col("n_nodes", ""),
    col("n_bars", ""),
    col("n_strings", ""),
    col("method", ""),
    col("self_stress_dim", ""),
    col("prestressable", ""),
    col("prestress_stable", ""),
    col("residual", ""),
    col("iterations", ""),
    col("height", "m"),
    col("max_bar_length", "m"),
    col("prestress", "N"),
];
