//! Resource estimates of the toroid commands, from the parameters alone (O(1): nothing is
//! built), for the guard of [`tensegrity_core::budget`].
//!
//! Sizes (builder, thesis §3.1): 5n nodes + 2 axle ends with spokes; 3n bars + the axle;
//! 12n prism strings + 2n spokes + 2n inner + 2n outer ring strings; no supports, so the
//! equilibrium matrix is 3·nodes × members. [`statics`] estimates what [`crate::analyse`]
//! runs: [`dense_statics`] (O(n³) work, O(n²) memory) or, for the symmetry-adapted path,
//! [`cyclic_statics`] (O(n) work and memory). [`roll`] adds the time integration of the model the
//! fidelity policy picks ([`RollRequest::fidelity_for`]) and its samples.

use crate::params::ToroidParams;
use crate::report::{ToroidRequest, WheelSpec};
use crate::roll::RollRequest;
use crate::rolling::RollingSample;
use crate::rolling_full::Fidelity;
use tensegrity_core::budget::{self, Estimate};

/// Node, bar and string counts of the wheel (or of the single prism).
pub fn counts(wheel: &WheelSpec, prism_only: bool) -> (usize, usize, usize) {
    if prism_only {
        return (6, 3, 12);
    }
    let n = wheel.params.sides;
    let s = &wheel.stabilize;
    let spokes = usize::from(s.spokes);
    let rings = 2 * usize::from(s.inner) + 2 * usize::from(s.outer);
    (
        5usize.saturating_mul(n).saturating_add(2 * spokes),
        3usize.saturating_mul(n).saturating_add(spokes),
        (12 + 2 * spokes + rings).saturating_mul(n),
    )
}

/// Estimate of the statics of the wheel (`tensegrity toroid`) along the path
/// [`crate::analyse`] takes: the symmetry-adapted blocks ([`cyclic_statics`]; the dense SVD
/// statics, [`dense_statics`], for a single prism).
///
/// ```
/// use toroid::{budget, ToroidRequest};
/// let mut r = ToroidRequest::default();
/// assert!(budget::statics(&r).work_s < 1.0);
/// r.wheel.params.sides = 100_000;
/// let e = budget::statics(&r);
/// assert!(e.memory_bytes < 8e9 && e.parameter == "--sides 100000");
/// r.wheel.params.sides = 100_000_000;
/// assert!(budget::statics(&r).memory_bytes > 1e11);
/// ```
pub fn statics(request: &ToroidRequest) -> Estimate {
    cyclic_statics(request)
}

fn parameter(request: &ToroidRequest) -> String {
    if request.prism_only {
        "--prism-only".to_string()
    } else {
        format!("--sides {}", request.wheel.params.sides)
    }
}

/// The dense statics: the SVD of the 3·nodes × members equilibrium matrix with full U and V,
/// the prestress LP and the flexes (O(n²) memory, O(n³) work).
pub fn dense_statics(request: &ToroidRequest) -> Estimate {
    let (nodes, bars, strings) = counts(&request.wheel, request.prism_only);
    budget::dense_statics(3 * nodes, bars + strings, parameter(request))
}

/// The symmetry-adapted statics: n complex blocks of one sector's size (3·nodes/n rows ×
/// members/n columns; complex arithmetic ≈ 4 real flops a flop), O(n) memory for the
/// structure, its members and the blocks.
pub fn cyclic_statics(request: &ToroidRequest) -> Estimate {
    if request.prism_only {
        return dense_statics(request);
    }
    let (nodes, bars, strings) = counts(&request.wheel, false);
    let n = request.wheel.params.sides.max(1);
    let (rows, cols) = ((3 * nodes).div_ceil(n), (bars + strings).div_ceil(n));
    let work = 4.0 * n as f64 * budget::svd_flops(rows, cols) * budget::DENSE_OVERHEAD;
    let memory = 256.0 * (nodes + bars + strings) as f64
        + n as f64 * budget::dense_statics_bytes(rows, cols) * 2.0;
    Estimate::new(
        format!("the symmetry-adapted statics ({n} blocks of {rows} × {cols})"),
        parameter(request),
    )
    .memory(memory)
    .work(work / budget::DENSE_FLOP_RATE)
}

/// Total bar mass of the wheel from the parameters (one prism's bar lengths × n, plus the
/// axle of length T with spokes).
pub fn wheel_mass(wheel: &WheelSpec) -> f64 {
    let p: &ToroidParams = &wheel.params;
    let x = crate::builder::prism_nodes(p);
    let prism: f64 = [(0, 3), (1, 4), (2, 5)]
        .iter()
        .map(|&(a, b)| (x[b] - x[a]).norm())
        .sum();
    let axle = if wheel.stabilize.spokes {
        p.outer_tread
    } else {
        0.0
    };
    wheel.bar_density * (p.sides as f64 * prism + axle)
}

/// Estimate of `tensegrity roll`: the wheel's statics, then the time integration of the model
/// the fidelity policy picks (rigid: one degree of freedom; full: the class-1 model with its
/// rim-joint constraints, 4 right-hand sides a step) and the samples kept in memory
/// (one per [`crate::defaults::ROLL_OUTPUT_DT`]).
pub fn roll(request: &RollRequest) -> Estimate {
    let wheel = &request.wheel;
    let statics = statics(&ToroidRequest {
        wheel: *wheel,
        ..ToroidRequest::default()
    });
    let parameter = format!(
        "--t-end {} --dt {} --sides {}",
        request.t_end, request.dt, wheel.params.sides
    );
    let steps = (request.t_end / request.dt).ceil();
    let samples = (request.t_end / crate::defaults::ROLL_OUTPUT_DT).floor() + 2.0;
    let (nodes, bars, strings) = counts(wheel, false);
    let fidelity = request.fidelity_for(wheel_mass(wheel), wheel.params.outer_radius);
    let (run, sample_bytes) = match fidelity {
        Fidelity::Rigid => (
            budget::integration(steps, 1.0, 200.0, 3, parameter.clone()),
            std::mem::size_of::<RollingSample>() as f64,
        ),
        Fidelity::Full => {
            // one constraint row per rim joint and direction
            let rows = 3 * wheel.params.sides;
            let flops = budget::rhs_flops(bars, strings, rows);
            (
                budget::integration(steps, 4.0, flops, 12 * bars, parameter.clone()),
                std::mem::size_of::<RollingSample>() as f64 + 48.0 * nodes as f64,
            )
        }
    };
    let kept = budget::table(samples, sample_bytes, true, parameter.clone());
    Estimate {
        parameter,
        ..statics.then(run).then(kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_match_the_builder() {
        for (stabilize, n) in [("spokes,inner", 8), ("none", 5), ("spokes,inner,outer", 12)] {
            let mut w = WheelSpec::default();
            w.params.sides = n;
            w.stabilize = stabilize.parse().unwrap();
            let t = crate::build(&w.params, w.stabilize, w.bar_density).unwrap();
            let s = &t.structure;
            assert_eq!(
                counts(&w, false),
                (s.n_nodes(), s.n_bars(), s.n_strings()),
                "{stabilize} n = {n}"
            );
            let m = crate::wheel_mass(s);
            assert!((wheel_mass(&w) - m).abs() <= 1e-12 * m, "{stabilize}");
        }
    }

    #[test]
    fn a_billion_seconds_of_rolling_is_refused_for_its_samples_and_its_work() {
        let r = RollRequest {
            t_end: 1e9,
            ..RollRequest::default()
        };
        let e = roll(&r);
        // 1e12 samples kept in memory
        assert!(e.memory_bytes > 1e13, "{}", e.memory_bytes);
        assert!(e.work_s > 1e6, "{}", e.work_s);
        assert!(tensegrity_core::budget::Limits::default()
            .check(&e)
            .is_err());
        // the default run is well inside the limits
        let e = roll(&RollRequest::default());
        assert!(tensegrity_core::budget::Limits::default().check(&e).is_ok());
    }
}
