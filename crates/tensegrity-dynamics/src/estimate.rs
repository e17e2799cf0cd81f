//! The resource estimate of a [`Simulation`](crate::Simulation) run, from its settings and
//! the model's sizes (the core's `budget` types and flop counts).

use tensegrity_core::budget::{integration, rhs_flops, Estimate, Parameters, SCALAR_FLOP_RATE};

/// Estimate of a [`Simulation`](crate::Simulation) run from its settings and model
/// sizes: fixed-step methods take t_end / min(dt, output interval) steps (they land on every
/// output time), adaptive ones at least t_end / dt, and RK45 at least t_end · λ / 3 for the
/// fastest rate λ of the model ([`fastest_rate`]: its stability interval is about 3.3 along
/// the real and imaginary axes); right-hand sides per step: RK4 4 (with
/// flight steps at most that),
/// RATTLE 2, RK45 6, SDIRK 12; the samples hold the recorded quantities and are kept in
/// memory unless `streamed`, and written at `bytes_per_number` when `written`; each sample
/// is computed (an interpolation and its quantities: 8 flops a number), which bounds an
/// adaptive run's work from below however long its steps.
pub fn simulation(
    sim: &crate::Simulation,
    streamed: bool,
    written: bool,
    bytes_per_number: f64,
    parameters: impl Into<Parameters>,
) -> Estimate {
    use crate::IntegratorKind as K;
    let (s, model) = (&sim.settings, &sim.model);
    let samples = s.output_times.len() as f64
        + s.output_interval
            .map_or(0.0, |dt_out| (s.t_end / dt_out).floor() + 1.0);
    let step = match (s.integrator.is_adaptive(), s.output_interval) {
        (false, Some(dt_out)) => s.dt.min(dt_out),
        _ => s.dt,
    };
    let mut steps = (s.t_end / step).ceil();
    if s.integrator == K::Rk45 {
        // an explicit adaptive method cannot step past its stability limit on the fastest
        // mode, however smooth the motion: a lower bound that a stiff scene makes large
        steps = steps.max((s.t_end * fastest_rate(model) / RK45_STABILITY).ceil());
    }
    let rhs_per_step = match s.integrator {
        // flight steps: at most every step at dt (a run that never leaves the ground)
        K::Rk4 | K::Rk4Flight => 4.0,
        K::Rattle => 2.0,
        K::Rk45 => 6.0,
        K::Sdirk => 12.0,
        // two right-hand sides and the contact response columns
        K::Imex => 3.0,
        // four right-hand sides, four responses and the Newton solves of the stages
        K::ImexArk => 6.0,
        // (elastic models only: a rigid model refuses it before any estimate)
        K::Newmark => 3.0,
    };
    let flops = rhs_flops(
        model.bars.len(),
        model.strings.len(),
        model.n_constraint_rows(),
    );
    let q = &s.quantities;
    let nodes = model.node_map.len() as f64;
    let numbers = 1.0
        + 3.0 * nodes * (f64::from(u8::from(q.nodes)) + f64::from(u8::from(q.velocities)))
        + (model.bars.len() + model.strings.len()) as f64 * f64::from(u8::from(q.member_forces))
        + 3.0 * f64::from(u8::from(q.energy))
        + 4.0 * model.contact.len() as f64 * f64::from(u8::from(q.contact_forces));
    let run = integration(steps, rhs_per_step, flops, model.state_len(), parameters);
    // every sample is computed, however long an adaptive step is: its interpolation and its
    // recorded quantities, at least the numbers it holds a few times over
    let sampling = samples * 8.0 * (model.state_len() as f64 + numbers) / SCALAR_FLOP_RATE;
    let sample_bytes = numbers * if streamed { 0.0 } else { 8.0 };
    Estimate {
        work_s: run.work_s + sampling,
        memory_bytes: run.memory_bytes + samples * sample_bytes,
        output_bytes: if written {
            samples * numbers * bytes_per_number
        } else {
            0.0
        },
        what: format!("{} and {samples:.3e} output samples", run.what),
        ..run
    }
}

/// The length of RK45's stability interval used by the estimate (the Dormand–Prince method's
/// reaches about 3.3 along the negative real axis and 3.4 along the imaginary one).
pub const RK45_STABILITY: f64 = 3.0;

/// The rate of a spring k and damper c at a bar end's effective mass m (a quarter of the
/// lightest bar's), √(2k/m) or 2c/m, whichever is larger, and the fastest of the strings' and
/// clusters' rates; `None` for a model without bars (nothing to resolve).
pub(crate) fn spring_rates(model: &crate::Model) -> Option<(impl Fn(f64, f64) -> f64, f64)> {
    let lightest = model
        .bars
        .iter()
        .map(|b| b.mass)
        .fold(f64::INFINITY, f64::min);
    let m = lightest / 4.0;
    if !(m.is_finite() && m > 0.0) {
        return None;
    }
    let rate = move |k: f64, c: f64| (2.0 * k / m).sqrt().max(2.0 * c / m);
    let strings = model
        .strings
        .iter()
        .map(|s| rate(s.law.stiffness, s.law.damping))
        .chain(model.clusters.iter().map(|c| rate(c.stiffness, c.damping)))
        .fold(0.0, f64::max);
    Some((rate, strings))
}

/// The fastest rate λ (1/s) an explicit method must resolve: over the strings and a penalty
/// ground, √(2k/m) for a stiffness k and 2c/m for a damping c, with m a quarter of the
/// lightest bar's mass (a bar end's effective mass); 0 for a model without bars.
pub fn fastest_rate(model: &crate::Model) -> f64 {
    let Some((rate, strings)) = spring_rates(model) else {
        return 0.0;
    };
    let ground = match model.ground.as_ref().map(|g| &g.model) {
        Some(crate::GroundModel::Penalty {
            stiffness, damping, ..
        }) => rate(*stiffness, *damping),
        _ => 0.0,
    };
    strings.max(ground)
}
