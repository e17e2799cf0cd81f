//! Fuzz target: the scene reader (`tensegrity_io::scene`). Any bytes are read as a scene the
//! way the commands read one: refused with an error, or accepted — and then an accepted scene
//! gives its simulation or an error, its statics estimate, and (small ones) its statics
//! report or an error. Never a panic, an abort or a hang.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tensegrity_engine::scene::SceneSource;
use tensegrity_engine::statics::{estimate, statics, StaticsCommand};
use tensegrity_io::scene::Scene;

/// Scenes up to this many nodes and members are also solved (the fuzzer's executions stay fast).
const SOLVE_MAX: usize = 48;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = Scene::from_str_named(text, "fuzz.toml") else {
        return;
    };
    let _ = scene.simulation();
    let command = StaticsCommand {
        scene: Some(SceneSource::Toml(text.to_string())),
        ..StaticsCommand::default()
    };
    let _ = estimate(&scene.structure, &command);
    let s = &scene.structure;
    if s.n_nodes() <= SOLVE_MAX && s.n_members() <= SOLVE_MAX {
        let _ = statics(&command);
    }
});
