//! Fuzz target `scene_toml`: the promises are in `fuzz/checks.rs` (`check_scene`).
#![no_main]

#[path = "../checks.rs"]
#[allow(dead_code)]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    checks::check_scene(data);
});
