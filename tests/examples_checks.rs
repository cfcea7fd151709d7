//! The examples' own checks (the default scene's outgoing state against the closed form
//! run separately, theta constant over the trace's states by eq 23; the bar-table scene of
//! unequal balls against the closed form and the lab momentum), each computed by the
//! example from the runs' states rather than read from the library's report of its own
//! run, run here, so that `cargo test` fails when an
//! example's check would: each example's `run` is the one `cargo run --example` calls.

// Each example is a program of its own and declares `mod common;` itself, so the shared
// examples/common/mod.rs is loaded once per example here.
#![allow(clippy::duplicate_mod)]

macro_rules! example {
    ($module:ident, $file:literal) => {
        #[path = $file]
        #[allow(dead_code)]
        mod $module;

        #[test]
        fn $module() {
            $module::run().unwrap_or_else(|e| panic!("{}: {e}", $file));
        }
    };
}

example!(default_half_sine, "../examples/default_half_sine.rs");
example!(default_hertz, "../examples/default_hertz.rs");
example!(default_rectangle, "../examples/default_rectangle.rs");
example!(default_sine_power, "../examples/default_sine_power.rs");
example!(default_tabulated, "../examples/default_tabulated.rs");
example!(unequal_balls, "../examples/unequal_balls.rs");
