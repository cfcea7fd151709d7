//! "No heap allocation per step when no trace is requested" (docs/formats.md): count
//! the allocations of runs whose step counts differ by thousands. The solver's own output
//! vectors grow amortised (a logarithmic number of reallocations), which the contract
//! accepts; anything per step would show up as thousands.

use billiard_contact::profile::ForceProfile;
use billiard_contact::profile::{HalfSine, Profile};
use billiard_contact::Scene;
use billiard_contact::{solve, Method, SolverSettings};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations and accepted steps of one solve (no trace).
fn count(profile: &Profile, settings: &SolverSettings, scene: &Scene) -> (u64, u64) {
    let (c, _) = scene.collision().unwrap();
    let before = ALLOCATIONS.with(Cell::get);
    let o = solve(&c, profile, settings, None).unwrap();
    let after = ALLOCATIONS.with(Cell::get);
    (after - before, o.stats.accepted_steps)
}

/// Extra allocations allowed for `steps` more steps: amortised doubling of the solver's
/// output vectors, about log2(steps) reallocations per vector, with slack.
fn amortised_bound(steps: u64) -> u64 {
    8 + 4 * (64 - steps.leading_zeros() as u64)
}

fn check(profile: &Profile, method: Method, loose: SolverSettings, tight: SolverSettings) {
    for scene in [
        Scene::default_scene(),
        Scene::load(std::path::Path::new("data/scenes/stun_cut_sticks.toml")).unwrap(),
    ] {
        let (a_loose, s_loose) = count(profile, &loose, &scene);
        let (a_tight, s_tight) = count(profile, &tight, &scene);
        assert!(
            s_tight >= s_loose + 1000 || method != Method::Rk4,
            "{method}: steps {s_loose} vs {s_tight}"
        );
        assert!(s_tight > s_loose, "{method}: steps {s_loose} vs {s_tight}");
        let extra = a_tight.saturating_sub(a_loose);
        eprintln!(
            "{method} on {}: {a_loose} allocations / {s_loose} steps, {a_tight} / {s_tight}",
            scene.name
        );
        assert!(
            extra <= amortised_bound(s_tight - s_loose),
            "{method} on {}: {a_loose} allocations for {s_loose} steps, {a_tight} for {s_tight}",
            scene.name
        );
    }
}

#[test]
fn rk4_allocations_do_not_grow_with_steps() {
    let p = Profile::HalfSine(HalfSine::new(2.5e-4).unwrap());
    let s = |n| SolverSettings::new(Method::Rk4, 1e-10, 1e-10, n).unwrap();
    check(&p, Method::Rk4, s(10), s(20_000));
}

#[test]
fn adaptive_allocations_do_not_grow_with_steps() {
    let p = Profile::HalfSine(HalfSine::new(2.5e-4).unwrap());
    for m in [Method::Dopri5, Method::Dop853] {
        let s = |r| SolverSettings::new(m, r, r, 1000).unwrap();
        check(&p, m, s(1e-3), s(1e-13));
    }
}

/// A profile with breakpoints: the work per segment (the solver is restarted at each knot)
/// is bounded by the knots, not by the steps.
#[test]
fn tabulated_allocations_do_not_grow_with_steps() {
    let scene = Scene::load(std::path::Path::new("data/scenes/tabulated_pulse.toml")).unwrap();
    let p = scene.profile.clone();
    assert!(!p.breakpoints().is_empty());
    let s = |n| SolverSettings::new(Method::Rk4, 1e-10, 1e-10, n).unwrap();
    check(&p, Method::Rk4, s(20), s(20_000));
}
