//! Scratch probe (removed before finishing).
use toroid::{roll, FidelityChoice, RollRequest, WheelSpec};
fn main() {
    let args: Vec<f64> = std::env::args().skip(1).map(|a| a.parse().unwrap()).collect();
    let (n, deg, t_end, k, kg, dt) = (args[0] as usize, args[1], args[2], args[3], args[4], args[5]);
    let req = RollRequest {
        wheel: WheelSpec::with_sides(n),
        incline: deg.to_radians(),
        t_end,
        fidelity: FidelityChoice::Full,
        string_stiffness: k,
        ground_stiffness: kg,
        dt,
        ..Default::default()
    };
    let r = roll(&req).unwrap();
    let mut v = serde_json::to_value(&r).unwrap();
    v["impact_log"] = serde_json::Value::Null;
    println!("{}", serde_json::to_string_pretty(&v).unwrap());
    for i in r.impact_log.iter().take(5) { println!("{:?}", i); }
    let rr = roll(&RollRequest { fidelity: FidelityChoice::Rigid, ..req }).unwrap();
    println!("rigid: impacts {} mean_speed {} first {:?} valid {} {:?}", rr.impacts, rr.mean_speed, rr.first_impact, rr.valid, rr.warnings);
    for (a, b) in r.samples.iter().zip(&rr.samples).step_by(100) { println!("t {:.2} full s {:.4} h {:.4} w {:.3} | rigid s {:.4} h {:.4} w {:.3}", a.t, a.s, a.h, a.omega, b.s, b.h, b.omega); }
}
