//! Bad input names the offending item; impossible forms are reported, not returned.

use formfind::{
    builtin, form_find, FixedNode, FormFindError, Group, Member, Method, Settings, Topology,
};
use tensegrity_core::request::{Categorized, Category};

fn err(t: &Topology, method: Method) -> FormFindError {
    form_find(
        t,
        &Settings {
            method,
            ..Settings::default()
        },
    )
    .unwrap_err()
}

fn prism3() -> Topology {
    builtin("prism:3").unwrap()
}

#[test]
fn bad_topologies_name_the_item() {
    let mut t = prism3();
    t.strings[4].nodes[1] = 17;
    let e = err(&t, Method::Fdm);
    assert!(
        e.to_string().contains("strings[4]") && e.to_string().contains("17"),
        "{e}"
    );
    assert_eq!(e.category(), Category::Input);

    let mut t = prism3();
    t.bars[1].group = Some("struts".into());
    let e = err(&t, Method::Fdm).to_string();
    assert!(e.contains("bars[1].group") && e.contains("struts"), "{e}");

    let mut t = prism3();
    t.strings[0].force_density = Some(f64::NAN);
    let e = err(&t, Method::Fdm).to_string();
    assert!(e.contains("strings[0].force_density"), "{e}");

    let mut t = prism3();
    t.groups.insert(
        "top".into(),
        Group {
            force_density: Some(f64::INFINITY),
            length: None,
            weight: None,
        },
    );
    let e = err(&t, Method::Fdm).to_string();
    assert!(e.contains("groups.top.force_density"), "{e}");

    let mut t = prism3();
    t.nodes.as_mut().unwrap()[2][1] = f64::NAN;
    let e = err(&t, Method::Fdm).to_string();
    assert!(e.contains("nodes[2]"), "{e}");

    let mut t = prism3();
    t.fixed.push(FixedNode {
        node: 9,
        position: [0.0; 3],
    });
    let e = err(&t, Method::Fdm).to_string();
    assert!(e.contains("fixed[0]"), "{e}");

    let mut t = prism3();
    t.strings.push(Member::new(1, 0));
    let e = err(&t, Method::Fdm).to_string();
    assert!(e.contains("strings[9]") && e.contains("strings[0]"), "{e}");

    let mut t = prism3();
    t.bars[2].force_density = Some(0.5);
    let e = err(&t, Method::Fdm).to_string();
    assert!(
        e.contains("bars[2].force_density") && e.contains("negative"),
        "{e}"
    );

    let mut t = prism3();
    t.groups.get_mut("vertical").unwrap().force_density = None;
    let e = err(&t, Method::Fdm).to_string();
    assert!(e.contains("strings[6].force_density"), "{e}");
}

#[test]
fn force_densities_without_a_form_are_a_rank_deficiency() {
    let mut t = prism3();
    t.groups.get_mut("top").unwrap().force_density = Some(2.0);
    match err(&t, Method::Fdm) {
        FormFindError::RankDeficiency {
            found,
            required,
            hint,
        } => {
            assert!(found < 4 && required == 4);
            assert!(hint.contains("adaptive"), "{hint}");
        }
        e => panic!("{e}"),
    }
}

#[test]
fn a_topology_without_prestress_is_reported() {
    // A single bar held by two strings in a line: no free-standing 3-D form.
    let t = Topology {
        n_nodes: 4,
        nodes: Some(vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [-1.0, 0.0, 0.3],
        ]),
        bars: vec![Member::new(0, 1)],
        strings: vec![Member::new(1, 2), Member::new(0, 3), Member::new(2, 3)],
        ..Topology::default()
    };
    let e = err(&t, Method::Adaptive);
    assert!(
        matches!(
            e,
            FormFindError::NotConverged { .. } | FormFindError::NoPrestress { .. }
        ),
        "{e}"
    );
    assert_eq!(e.category(), Category::Numerical);
}

#[test]
fn dynamic_relaxation_needs_nodes_and_lengths_and_refuses_force_densities() {
    let mut t = prism3();
    // the built-in's force densities: dynamic relaxation would ignore them
    let e = err(&t, Method::Dr).to_string();
    assert!(
        e.starts_with("bars[0].force_density: dynamic relaxation ignores"),
        "{e}"
    );
    for m in t.bars.iter_mut().chain(t.strings.iter_mut()) {
        m.force_density = None;
    }
    for g in t.groups.values_mut() {
        g.force_density = None;
    }
    let e = err(&t, Method::Dr).to_string();
    assert!(e.contains("bars[0].length"), "{e}");
    t.nodes = None;
    let e = err(&t, Method::Dr).to_string();
    assert!(e.starts_with("nodes: dynamic relaxation"), "{e}");
}

#[test]
fn builtin_names_are_checked() {
    for (name, needle) in [
        ("prism:2", "N"),
        ("prism:x", "N"),
        ("prism:100000", "N"),
        ("tower:4:0", "M"),
        ("grid:0", "K"),
        ("grid:100000", "K"),
    ] {
        match builtin(name) {
            Err(FormFindError::InvalidParameter(p)) => {
                assert!(p.name.contains(needle), "{name}: {p}");
                assert!(p.to_string().contains(name.rsplit(':').next().unwrap()));
            }
            other => panic!("{name}: {other:?}"),
        }
    }
    match builtin("dodecahedron") {
        Err(e @ FormFindError::UnknownBuiltin { .. }) => {
            assert!(e.to_string().contains("prism:N"));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn settings_are_checked() {
    let t = prism3();
    for s in [
        Settings {
            tolerance: 0.0,
            ..Settings::default()
        },
        Settings {
            max_iterations: 0,
            ..Settings::default()
        },
        Settings {
            stiffness: f64::NAN,
            ..Settings::default()
        },
    ] {
        let e = form_find(&t, &s).unwrap_err();
        assert_eq!(e.category(), Category::Input, "{e}");
    }
}
