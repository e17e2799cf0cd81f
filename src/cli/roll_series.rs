//! The wheels of `fig-rolling`, rolled in parallel (one thread per wheel, each a
//! [`toroid::roll`] call), and their summary: the validity of each run and the impact
//! impulse per new contact against n (the §3.3.1 claim that more sides mean gentler impacts).

use anyhow::Result;
use toroid::{RollReport, RollRequest};

/// Rolls `request` once per entry of `sides`, in parallel; the reports in the order of
/// `sides`.
pub fn parallel_series(request: &RollRequest, sides: &[usize]) -> Result<Vec<RollReport>> {
    std::thread::scope(|scope| {
        let handles: Vec<_> = sides
            .iter()
            .map(|&n| {
                let mut r = *request;
                r.wheel.params.sides = n;
                scope.spawn(move || toroid::roll(&r))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| match h.join() {
                Ok(report) => Ok(report?),
                Err(_) => Err(anyhow::anyhow!("a rolling run panicked")),
            })
            .collect()
    })
}

/// Mean of the normal impulse, tangential impulse and ω⁺/ω⁻ over a run's impacts.
fn impact_means(r: &RollReport) -> (f64, f64, f64) {
    let n = r.impact_log.len().max(1) as f64;
    let sum = r.impact_log.iter().fold((0.0, 0.0, 0.0), |acc, i| {
        let ratio = if i.omega_before != 0.0 {
            i.omega_after / i.omega_before
        } else {
            f64::NAN
        };
        (
            acc.0 + i.normal_impulse,
            acc.1 + i.tangential_impulse,
            acc.2 + ratio,
        )
    });
    (sum.0 / n, sum.1 / n, sum.2 / n)
}

/// Prints one line per wheel (model, validity, axle height, speed) and the impulse table.
pub fn print_series(runs: &[RollReport]) {
    for r in runs {
        println!(
            "n = {:>2} ({:?}, {}): mean axle height {:.4} m, oscillation {:.5} m, mean speed {:.3} m/s, airborne {:.1} %{}",
            r.sides,
            r.fidelity,
            r.contact,
            r.mean_axle_height,
            r.axle_height_oscillation,
            r.mean_speed,
            100.0 * r.airborne_fraction,
            if r.valid { "" } else { "  NOT VALID" }
        );
        for w in &r.warnings {
            eprintln!("warning (n = {}): {w}", r.sides);
        }
    }
    println!("\nimpact impulse per new contact (§3.3.1), means over each run's impacts:");
    println!(
        "{:>4} {:>8} {:>14} {:>18} {:>16} {:>14}",
        "n", "impacts", "normal [N s]", "tangential [N s]", "normal/m [m/s]", "omega+/omega-"
    );
    for r in runs {
        let (normal, tangential, ratio) = impact_means(r);
        println!(
            "{:>4} {:>8} {:>14.5} {:>18.5} {:>16.5} {:>14.5}",
            r.sides,
            r.impacts,
            normal,
            tangential,
            normal / r.mass_kg,
            ratio
        );
    }
}
