//! Fuzz target: the topology reader (`tensegrity_io::topology`, form-finding input files).
//! Any bytes are read as a topology file: refused with an error or accepted, never a panic,
//! an abort or a hang. An accepted small topology is also form-found (the library's
//! estimate first, as every front end does), so the methods see what the reader lets through.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(topology) = tensegrity_io::topology::from_str_named(text, "fuzz.toml") else {
        return;
    };
    if topology.n_nodes <= 24 && topology.n_members() <= 96 {
        let settings = formfind::Settings::default();
        let _ = formfind::estimate(&topology, &settings);
        let _ = formfind::form_find(&topology, &settings);
    }
});
