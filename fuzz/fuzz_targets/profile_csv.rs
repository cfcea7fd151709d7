//! Fuzz target `profile_csv`: the promises are in `fuzz/checks.rs` (`check_profile_csv`).
#![no_main]

#[path = "../checks.rs"]
#[allow(dead_code)]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    checks::check_profile_csv(data);
});
