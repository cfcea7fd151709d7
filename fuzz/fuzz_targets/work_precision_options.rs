//! Fuzz target `work_precision_options`: the promises are in `fuzz/checks.rs` (`check_work_precision`).
#![no_main]

#[path = "../checks.rs"]
#[allow(dead_code)]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    checks::check_work_precision(data);
});
