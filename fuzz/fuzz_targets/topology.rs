//! Fuzz target: the topology reader (`tensegrity_io::topology`, form-finding input files).
//! Any bytes are read as a topology file: refused with an error or accepted, never a panic,
//! an abort or a hang.
//!
//! Pending: enabled in fuzz/Cargo.toml (the commented `[[bin]] topology`) once
//! crates/tensegrity-io/src/topology.rs is on the branch; the call below is that reader's
//! text entry (rename it to the reader's actual function if it differs).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = tensegrity_io::topology::Topology::from_str_named(text, "fuzz.toml");
});
