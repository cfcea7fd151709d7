//! Fuzz target `batch_lab`: the promises are in `fuzz/checks.rs` (`check_batch_lab`).
#![no_main]

#[path = "../checks.rs"]
#[allow(dead_code)]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    checks::check_batch_lab(data);
});
