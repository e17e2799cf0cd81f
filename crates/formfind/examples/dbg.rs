use formfind::*;
fn main() {
    for name in ["prism:3", "prism:12", "octahedron", "tower:4:3", "grid:3"] {
        let t = builtin(name).unwrap();
        let f = form_find(
            &t,
            &Settings {
                method: Method::Fdm,
                ..Settings::default()
            },
        )
        .unwrap();
        for ea in [1e4, 1e5, 1e6] {
            let r = rest_lengths(
                &t,
                &f,
                &Synthesis {
                    stiffness: ea,
                    ..Synthesis::default()
                },
            )
            .unwrap();
            let mut dr = t.with_lengths(&r.rest_length, &r.stiffness);
            dr.nodes = Some(
                t.nodes
                    .clone()
                    .unwrap()
                    .iter()
                    .map(|p| [p[0] * 1.1, p[1] * 0.9 + 0.05, p[2] * 1.05])
                    .collect(),
            );
            let g = form_find(
                &dr,
                &Settings {
                    method: Method::Dr,
                    ..Settings::default()
                },
            );
            match g {
                Ok(g) => println!(
                    "{name} EA={ea}: it={} stable={}",
                    g.iterations, g.prestress_stable
                ),
                Err(e) => println!("{name} EA={ea}: {e}"),
            }
        }
        let mut a = t.clone();
        for g in a.groups.values_mut() {
            g.force_density = None;
        }
        a.fixed.clear();
        let g = form_find(
            &a,
            &Settings {
                method: Method::Adaptive,
                ..Settings::default()
            },
        );
        match g {
            Ok(g) => println!(
                "{name} adaptive: it={} stable={} dim={}",
                g.iterations, g.prestress_stable, g.self_stress_dim
            ),
            Err(e) => println!("{name} adaptive: {e}"),
        }
    }
}
