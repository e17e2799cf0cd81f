//! scratch comparison (to be turned into the real test)
use michell3d::MichellParams;
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::{tbar_report, tbar_report_dense, Layout, RimMode, TbarParams, TbarRequest};

#[test]
fn scratch() {
    for rim in [RimMode::Fixed, RimMode::Body] {
        for q in [1usize, 2] {
            for n in [3usize, 4, 5, 8, 12, 16, 32].into_iter().filter(|&n| q == 1 || n <= 16) {
                for layout in [Layout::Wheel, Layout::Extended { offset: 0.5 }] {
                    let m = MichellParams::cylindrical(q, 1.0, FRAC_PI_6, PI / n as f64, 0.25);
                    let p = TbarParams::tread(m).with_layout(layout).with_rim(rim);
                    let req = TbarRequest::new(p);
                    eprintln!("start {rim:?} q{q} n{n} {layout:?}");
                    let a = tbar_report(&req).unwrap();
                    eprintln!("cyclic done");
                    let b = tbar_report_dense(&req).unwrap();
                    println!(
                        "{rim:?} q{q} n{n} {layout:?}: {:?} rank {} {} ssd {} {} mech {} {} int {} {} margin {:.3e} {:.3e} P {:?} {:?} mass {:?} {:?} crit {:?}/{:?} active {}/{} warn {:?}",
                        a.statics_method,
                        a.rank, b.rank, a.self_stress_dim, b.self_stress_dim, a.mechanisms, b.mechanisms,
                        a.internal_mechanisms, b.internal_mechanisms,
                        a.prestress_margin - b.prestress_margin, a.prestress_margin,
                        a.min_prestress.map(|x| x - b.min_prestress.unwrap_or(f64::NAN)), b.min_prestress,
                        a.mass_kg.map(|x| x / b.mass_kg.unwrap_or(f64::NAN) - 1.0), b.mass_kg,
                        a.critical_member.as_ref().map(|c| (c.member, c.tread)), b.critical_member.as_ref().map(|c| (c.member, c.tread)),
                        a.active_members.len(), b.active_members.len(),
                        a.warnings.len()
                    );
                }
            }
        }
    }
}
