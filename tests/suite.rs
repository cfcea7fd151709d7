//! The integration tests, one test binary: each file beside this one is a module of it
//! (`cargo test --release --test suite NAME` runs the tests whose path contains NAME, for
//! instance `properties_invariants::`). One binary instead of one per file: a change to the
//! library relinks one test program rather than thirty-six, which is most of the rebuild
//! time of `cargo test` and of each mutant of `cargo mutants`.
//!
//! Two tests stay programs of their own (Cargo.toml): `allocation_per_step` and
//! `hard_cases_long_trace` count the heap with a global allocator of their own, which would
//! count every other test running beside them here.

// The independent references (nothing in them calls the code under test).
mod cli_common;
mod common;
#[path = "common/hard.rs"]
mod hard;
mod scenes;

mod bad_input_cli;
mod bad_input_sizes;
mod batch_rows;
mod chung_ooi;
mod cli_batch_values;
mod cli_contact_law_options;
mod cli_error_messages;
mod cli_nothing_ignored;
mod cli_run_options;
mod cli_scenes;
mod cli_study_batch;
mod cli_summary_text;
mod cli_table;
mod cli_work_precision_laws;
mod cli_work_precision_values;
mod closed_form_paper;
mod cluster;
mod cluster_cloth;
mod cluster_frozen_throw;
mod cluster_mindlin;
mod cluster_scenes;
mod cluster_trace;
mod contact_law_checks;
mod contact_law_scenes;
mod convergence_profiles;
mod cushion;
mod cushion_scenes;
mod effects_switches;
mod examples_checks;
mod friction_speed_dependent;
mod fuzz_corpus;
mod fuzz_smoke;
mod hard_cases_rk4_coarse;
mod hard_cases_scales_profiles;
mod hard_cases_slip;
mod hertz_material;
mod lab_rows_errors;
mod lab_rows_methods;
mod layering;
mod plane_contact;
mod plane_scenes;
mod plot_trace;
mod properties_invariants;
mod stick_half_sine;
mod table_closed_forms;
mod tangential;
mod tangential_pair;
mod tangential_pair_damped;
mod tangential_scenes;
mod theta_constant_states;
mod throw_stun_cuts;
mod throw_sweep;
mod unequal_balls_closed_form;
mod unequal_balls_methods;
mod unequal_balls_scenes;
