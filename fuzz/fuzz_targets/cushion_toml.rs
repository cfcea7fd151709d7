//! Fuzz target `cushion_toml`: the promises are in `fuzz/checks.rs` (`check_cushion`).
#![no_main]

#[path = "../checks.rs"]
#[allow(dead_code)]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    checks::check_cushion(data);
});
