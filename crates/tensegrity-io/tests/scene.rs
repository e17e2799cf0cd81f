//! Scene files: the bundled examples parse, and bad files give errors with the item and line.

use std::path::Path;
use tensegrity_io::scene::Scene;
use tensegrity_statics::Statics;

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

#[test]
fn bundled_examples_parse_with_the_expected_counts() {
    for (file, nodes, bars, strings, dim) in [
        ("dbar.toml", 4, 4, 2, 1),
        ("dbar_loaded.toml", 4, 4, 1, 0),
        ("prism.toml", 6, 3, 9, 1),
        ("tbar.toml", 5, 4, 4, 1),
        ("tower.toml", 9, 6, 15, 2),
    ] {
        let scene = Scene::from_path(&examples().join(file)).unwrap();
        let s = &scene.structure;
        assert_eq!(
            (s.n_nodes(), s.n_bars(), s.n_strings()),
            (nodes, bars, strings),
            "{file}"
        );
        assert_eq!(Statics::new(s).unwrap().self_stress_dim(), dim, "{file}");
    }
}

#[test]
fn the_prism_scene_rest_lengths_realise_its_self_stress() {
    let scene = Scene::from_path(&examples().join("prism.toml")).unwrap();
    let s = &scene.structure;
    let q = tensegrity_statics::stiffness::string_force_densities(s).unwrap();
    // ring strings 10 N/m, verticals 10√3 N/m (ERRATA P.1 ratios)
    for k in 3..9 {
        assert!((q[k] - 10.0).abs() < 1e-9);
    }
    for k in 9..12 {
        assert!((q[k] - 10.0 * 3f64.sqrt()).abs() < 1e-9);
    }
}

fn err(text: &str) -> String {
    Scene::from_str_named(text, "bad.toml")
        .unwrap_err()
        .to_string()
}

const HEADER: &str = "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\n";

#[test]
fn unknown_keys_are_rejected_with_a_line_number() {
    let e = err(&format!("{HEADER}[[bars]]\nnodes = [0, 1]\nmas = 1.0\n"));
    assert!(
        e.contains("bad.toml") && e.contains("line 4") && e.contains("mas"),
        "{e}"
    );
    let e = err(&format!("{HEADER}[simulations]\nt_end = 1.0\n"));
    assert!(e.contains("simulations"), "{e}");
}

#[test]
fn validation_errors_carry_the_item_line() {
    let text = format!(
        "{HEADER}\n[[bars]]\nnodes = [0, 1]\n\n[[strings]]\nnodes = [1, 2]\n\n[[strings]]\nnodes = [2, 2]\n"
    );
    let e = err(&text);
    assert!(
        e.contains("string 1") && e.contains("line 9") && e.contains("itself"),
        "{e}"
    );
    let e = err(&format!(
        "{HEADER}[[bars]]\nnodes = [0, 1]\nmaterial = \"unobtainium\"\n[[bars]]\nnodes = [1, 2]\n"
    ));
    assert!(
        e.contains("bar 0") && e.contains("line 2") && e.contains("unobtainium"),
        "{e}"
    );
    let e = err(&format!("{HEADER}[[bars]]\nnodes = [0, 1]\n[[bars]]\nnodes = [1, 2]\n[[supports]]\nnode = 1\ndirections = [\"x\", \"w\"]\n"));
    assert!(e.contains("line 8") && e.contains('w'), "{e}");
    let e = err("nodes = [[0.0, 0.0, 0.0],\n [1.0, nan, 0.0]]\n[[bars]]\nnodes = [0, 1]\n");
    assert!(e.contains("node 1") && e.contains("line 2"), "{e}");
    let e = err(&format!("{HEADER}[[bars]]\nnodes = [0, 1]\n"));
    assert!(
        e.contains("node 2") && e.contains("line 1") && e.contains("isolated"),
        "{e}"
    );
}

#[test]
fn partial_supports_and_gravity_are_read() {
    let text = format!(
        "{HEADER}[[bars]]\nnodes = [0, 1]\nmass = 2.0\n[[bars]]\nnodes = [1, 2]\n[[supports]]\nnode = 0\ndirections = [\"z\"]\n[gravity]\nacceleration = [0.0, 0.0, -9.81]\n"
    );
    let scene = Scene::from_str_named(&text, "ok.toml").unwrap();
    assert_eq!(scene.structure.supports()[0].fixed, [false, false, true]);
    assert!((scene.structure.W()[(2, 1)] + 9.81).abs() < 1e-12);
}

#[test]
fn unreadable_files_name_the_path() {
    let e = Scene::from_path(Path::new("/nonexistent/scene.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("/nonexistent/scene.toml") && e.contains("cannot read"),
        "{e}"
    );
}
