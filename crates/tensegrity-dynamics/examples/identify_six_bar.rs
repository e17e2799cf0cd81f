//! System identification of the six-bar icosahedron (issue 47, item 5): its 24 string
//! stiffnesses and 24 dampings recovered from a noisy measurement of its motion by
//! Levenberg–Marquardt on the forward sensitivities (`tensegrity_dynamics::identify`); the
//! problem is `test_models::six_bar_identification`. Prints each parameter's truth, start,
//! identified value, standard error and error, then the iterations and the time, and the
//! cost of one run with and without the sensitivities.
//!
//! `cargo run --release -p tensegrity-dynamics --example identify_six_bar -- [SIGMA_M]`

use std::time::Instant;
use tensegrity_dynamics::identify::identify;
use tensegrity_dynamics::sensitivity::forward_sensitivities;
use tensegrity_dynamics::test_models::six_bar_identification;

fn main() {
    let sigma: f64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(2e-5);
    let case = six_bar_identification(sigma).expect("the identification problem");
    let clock = Instant::now();
    let id = identify(
        &case.start,
        None,
        &case.parameters,
        &case.observed,
        &case.measured,
        &case.settings,
    )
    .expect("identification");
    let seconds = clock.elapsed().as_secs_f64();
    // the cost of the sensitivities: one run of the measurement's length, plain and with the
    // 48 sensitivities (best of 5 each)
    let time = |params: &[tensegrity_dynamics::sensitivity::DynamicsParameter]| {
        (0..5)
            .map(|_| {
                let c = Instant::now();
                let r = forward_sensitivities(&case.start, None, params, 1e-3, 0.4, 2);
                std::hint::black_box(r.expect("run"));
                c.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let (plain, with) = (time(&[]), time(&case.parameters));
    println!("parameter                 true      start   identified   std error   error %");
    let mut worst = 0.0f64;
    for (j, p) in case.parameters.iter().enumerate() {
        let start = tensegrity_dynamics::identify::parameter_value(&case.start, *p).unwrap();
        let (v, t) = (id.values[j], case.true_values[j]);
        let e = 100.0 * (v - t).abs() / t;
        worst = worst.max(e);
        println!(
            "{:<22} {t:>9.4} {start:>9.4} {v:>12.4} {:>11.2e} {e:>9.3}",
            p.to_string(),
            id.standard_errors[j]
        );
    }
    println!(
        "noise {sigma:.1e} m; rms residual {:.3e} m at the start, {:.3e} m identified; {} \
         iterations ({}); worst error {worst:.3} %; {seconds:.2} s",
        id.rms_start,
        id.rms,
        id.iterations,
        if id.converged {
            "converged"
        } else {
            "NOT converged"
        }
    );
    // the fit is that of a model whose bars kept their lengths only within this
    println!(
        "bar-length drift of the final run {:.1e}",
        id.bar_length_drift
    );
    for w in &id.warnings {
        println!("warning: {w}");
    }
    println!(
        "one 0.4 s run (400 RK4 steps): {:.2} ms plain, {:.1} ms with the sensitivities to {} \
         parameters ({:.0}×, {:.2}× per parameter)",
        1e3 * plain,
        1e3 * with,
        case.parameters.len(),
        with / plain,
        with / plain / case.parameters.len() as f64
    );
}
