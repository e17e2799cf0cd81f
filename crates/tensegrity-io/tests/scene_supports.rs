//! The supports' `along` (unit directions of any orientation) and `stiffness` (a spring along
//! each held direction) in scene files and scene data: read into the core's supports, written
//! back by `to_toml` and `SceneArrays`, and refused with the support's name and line when a
//! direction is not a unit vector, not finite or dependent, when a stiffness is not positive
//! and finite, or when `along` comes with `directions`/`fixed`.

use nalgebra::Vector3;
use tensegrity_io::scene::{to_toml, Scene, SceneArrays};

/// A bar from a pinned node to node 1, whose support table (starting on line 6) ends with
/// `support`.
fn scene(support: &str) -> String {
    format!(
        "nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 1]\n[[supports]]\nnode = 0\n[[supports]]\nnode = 1\n{support}\n[[loads]]\nnode = 1\nforce = [0.0, 0.0, -1.0]\n"
    )
}

#[test]
fn along_and_stiffness_reach_the_supports_and_come_back() {
    let text = scene("along = [[0.0, 0.6, 0.8]]\nstiffness = 1.5e4");
    let s = Scene::from_str_named(&text, "a.toml").unwrap();
    let support = &s.structure.supports()[1];
    assert_eq!(support.fixed, [false; 3]);
    assert_eq!(support.along, vec![Vector3::new(0.0, 0.6, 0.8)]);
    assert_eq!(support.stiffness, Some(1.5e4));
    assert_eq!(s.structure.supports()[0].stiffness, None);
    assert_eq!(
        s.file.support_keys(),
        ["support 1: along", "support 1: stiffness"]
    );
    assert!(s.file.driver_keys().is_empty());
    // written back and read again: the same structure
    let back = Scene::from_str_named(&to_toml(&s.structure), "back").unwrap();
    assert_eq!(back.structure, s.structure);
    // as data and back
    let arrays = SceneArrays::of(&s);
    assert_eq!(
        arrays.support_along,
        Some(vec![None, Some(vec![[0.0, 0.6, 0.8]])])
    );
    assert_eq!(arrays.support_stiffness, Some(vec![None, Some(1.5e4)]));
    let data = Scene::from_arrays(arrays.clone(), "data").unwrap();
    assert_eq!(data.structure, s.structure);
    // an elastic support along the axes
    let s = Scene::from_str_named(&scene("directions = [\"z\"]\nstiffness = 10.0"), "b").unwrap();
    assert_eq!(s.structure.supports()[1].fixed, [false, false, true]);
    assert_eq!(s.structure.supports()[1].stiffness, Some(10.0));
    assert_eq!(
        Scene::from_str_named(&to_toml(&s.structure), "back")
            .unwrap()
            .structure,
        s.structure
    );
    // a data column of the wrong length names itself
    let mut short = arrays;
    short.support_stiffness = Some(vec![None]);
    let e = Scene::from_arrays(short, "data").unwrap_err().to_string();
    assert_eq!(
        e,
        "data: support_stiffness: expected one entry per support (2), got 1"
    );
}

#[test]
fn a_bad_direction_or_stiffness_names_the_support_and_its_line() {
    let cases = [
        (
            "along = [[0.6, 0.6, 0.0]]",
            "support 1: along direction 0 [0.6, 0.6, 0.0] has norm 0.848528, not 1: give a unit vector (to 1e-6), e.g. [0.7071067811865475, 0.7071067811865475, 0.0]",
        ),
        (
            "along = [[0.0, 0.0, 0.0]]",
            "support 1: along direction 0 [0.0, 0.0, 0.0] has norm 0.000000, not 1: give a unit vector (to 1e-6)",
        ),
        (
            "along = [[inf, 0.0, 0.0]]",
            "support 1: along direction 0 [inf, 0.0, 0.0] is not finite",
        ),
        (
            "along = [[0.6, 0.8, 0.0], [0.0, 0.0, 1.0], [0.8, -0.6, 0.0], [1.0, 0.0, 0.0]]",
            "support 1: along direction 3 [1.0, 0.0, 0.0] is dependent on the held directions before it",
        ),
        (
            "fixed = [true, false, false]\nstiffness = -1.0",
            "support 1: stiffness must be positive and finite, got -1",
        ),
        (
            "stiffness = nan",
            "support 1: stiffness must be positive and finite, got NaN",
        ),
        (
            "stiffness = 0.0",
            "support 1: stiffness must be positive and finite, got 0",
        ),
        (
            "along = [[0.0, 0.0, 1.0]]\nfixed = [true, false, false]",
            "support 1: give either along (any orientation) or directions/fixed (x, y, z), not both",
        ),
    ];
    for (support, message) in cases {
        let e = Scene::from_str_named(&scene(support), "s.toml")
            .unwrap_err()
            .to_string();
        let expected = format!("s.toml (line 6): {message}");
        assert!(e.starts_with(&expected), "{support}: {e}");
    }
    // a direction close enough to a unit vector is taken (and normalised by the analyses)
    let ok = Scene::from_str_named(&scene("along = [[0.0, 0.7071068, 0.7071068]]"), "s");
    assert!(ok.is_ok());
    // data: the same check, no line
    let mut arrays = SceneArrays::of(&Scene::from_str_named(&scene(""), "s").unwrap());
    arrays.support_along = Some(vec![None, Some(vec![[2.0, 0.0, 0.0]])]);
    arrays.supports[1].1 = [false; 3];
    let e = Scene::from_arrays(arrays, "data").unwrap_err().to_string();
    assert!(
        e.starts_with("data: support 1: along direction 0 [2.0, 0.0, 0.0] has norm 2.000000"),
        "{e}"
    );
}
