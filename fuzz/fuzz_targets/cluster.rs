//! Fuzz target `cluster`: the promises are in `fuzz/checks.rs` (`check_cluster`).
#![no_main]

#[path = "../checks.rs"]
#[allow(dead_code)]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    checks::check_cluster(data);
});
