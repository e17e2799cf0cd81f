//! Fuzz target: the sweep-spec reader (`sweeps::spec`). Any bytes are parsed as a spec:
//! refused with an error, or accepted — and then its first and last cases are formed (the
//! fixed values, the axes, the derived rules) and estimated by their study the way a sweep
//! admits a case before it runs (an estimate or an error). Never a panic, an abort or a hang.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sweeps::Spec;

/// The cases formed from each accepted spec: the first ones and the last.
const CASES: usize = 8;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(spec) = Spec::parse(text) else {
        return;
    };
    let Ok(count) = spec.case_count() else {
        return;
    };
    // a study reading a scene would read whatever file the fuzzer names: formed, not estimated
    let reads_files = spec.study.param("scene").is_some();
    let last = count.checked_sub(1);
    for id in (0..count.min(CASES)).chain(last) {
        let case = spec.case(id);
        if let (Ok(params), false) = (case.params, reads_files) {
            let _ = spec.study.estimate(params);
        }
    }
});
