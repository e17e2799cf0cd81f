//! A grid of rigid rolling runs over sides, slope, friction, restitution and inertia: every run
//! must finish without a warning, never pull, never penetrate and close its energy budget.
//! Slow (a few hundred runs): `cargo test -p wheel-rolling --test integration rigid_sweep:: -- --ignored`.

use std::f64::consts::PI;
use wheel_rolling::RigidRolling;

#[test]
#[ignore]
fn every_run_of_the_grid_is_admissible_and_closes_its_energy_budget() {
    let mut worst: f64 = 0.0;
    for n in [3, 4, 5, 6, 8, 12, 24] {
        for deg in [0.0, 5.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0] {
            for mu in [0.0, 0.05, 0.3, 0.8, 1.5] {
                for e in [0.0, 0.4, 0.9, 1.0] {
                    for i1 in [0.3, 1.0, 3.0] {
                        let model = RigidRolling {
                            sides: n,
                            outer_radius: 1.0,
                            mass: 10.0,
                            i1: i1 * 10.0,
                            incline: f64::to_radians(deg),
                            gravity: 9.81,
                            dt: 1e-4,
                            output_dt: 1e-3,
                            mu_static: mu,
                            mu_kinetic: 0.75 * mu,
                            restitution: e,
                        };
                        let r = match model.run(3.0) {
                            Ok(r) => r,
                            Err(err) => {
                                assert!(err.to_string().contains("Painlev"), "{err}");
                                continue;
                            }
                        };
                        let tag = format!("n {n} {deg}° μ {mu} e {e} I {i1}: {:?}", r.validity);
                        assert!(r.validity.warnings.is_empty(), "{tag}");
                        assert!(r.validity.min_normal_force >= 0.0, "{tag}");
                        assert!(r.validity.max_penetration < 1e-9, "{tag}");
                        assert!(r.validity.energy_balance_error < 1e-8, "{tag}");
                        assert!(r.samples.len() == 3001, "{tag}");
                        assert!(
                            r.samples.iter().all(|s| s.h.is_finite() && s.h > 0.0),
                            "{tag}"
                        );
                        assert!(r
                            .samples
                            .iter()
                            .all(|s| s.h >= (PI / n as f64).cos() - 1e-9));
                        // every term of the budget dissipates: the energy never rises
                        for w in r.samples.windows(2) {
                            assert!(w[1].energy <= w[0].energy + 1e-9, "{tag} t = {}", w[1].t);
                        }
                        worst = worst.max(r.validity.energy_balance_error);
                    }
                }
            }
        }
    }
    println!("worst energy error {worst:e}");
}
