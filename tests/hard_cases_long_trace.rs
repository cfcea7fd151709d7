//! Long traces in constant memory: 1,000,000 samples streamed to a sink, and a
//! million rk4 steps in one segment, measured by peak heap allocation (a counting global
//! allocator in this test binary), not by time. One test function, so that no other test
//! of this binary allocates concurrently.
//!
//! Bound: the peak heap in use during a run with 1,000,000 rows stays within
//! `PEAK_GROWTH_LIMIT` bytes of the same run with 1,000 rows. A trace kept in memory would
//! need 1e6 rows x 15 numbers x 8 bytes = 120 MB; the solver's own per-call output vector
//! (one entry per step of one segment) is what the limit leaves room for.

mod common;
#[path = "common/hard.rs"]
mod hard;

use billiard_contact::profile::HalfSine;
use billiard_contact::{solve, CmState, Error, Method, Sampling, SolverSettings};
use billiard_contact::{CsvTrace, TraceRow, TraceSink};
use common::collision::CollisionSpec;
use hard::*;
use nalgebra::Vector3;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = IN_USE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        IN_USE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                let now = IN_USE.fetch_add(new_size - layout.size(), Ordering::Relaxed)
                    + (new_size - layout.size());
                PEAK.fetch_max(now, Ordering::Relaxed);
            } else {
                IN_USE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Peak heap growth (bytes) above the level at the start of `f`.
fn peak_growth<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = IN_USE.load(Ordering::SeqCst);
    PEAK.store(base, Ordering::SeqCst);
    let out = f();
    (out, PEAK.load(Ordering::SeqCst) - base)
}

/// Counts rows and checks they arrive in time order with finite, physical values.
struct Counter {
    rows: u64,
    last_t: f64,
    tau: f64,
}

impl TraceSink for Counter {
    fn row(&mut self, r: &TraceRow) -> Result<(), Error> {
        assert!(
            r.t > self.last_t || self.rows == 0,
            "rows out of order at {}",
            r.t
        );
        assert!(r.t >= 0.0 && r.t <= self.tau * (1.0 + 1e-15));
        assert!(r.state.is_finite() && r.slip_speed >= 0.0);
        self.last_t = r.t;
        self.rows += 1;
        Ok(())
    }
}

/// Extra room for the solver's per-call vectors and rounding of the allocator's counts.
const PEAK_GROWTH_LIMIT: usize = 4 << 20;

#[test]
fn a_million_samples_in_constant_memory() {
    // A stun cut that sticks mid-contact (one extra row at the stop).
    let incoming = CmState::new(
        Vector3::new(1.0, 0.1, 0.02),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    let c = CollisionSpec::ball(M, R, 0.4)
        .mu(MU)
        .restitution(1.0)
        .incoming(incoming)
        .build();
    let profile = HalfSine::new(TAU).unwrap();
    for method in [Method::ClosedForm, Method::Rk4, Method::Dop853] {
        // One rk4 step per sample at 1e6 samples.
        let s = SolverSettings::default()
            .with_method(method)
            .with_steps(1)
            .unwrap();
        let mut results = Vec::new();
        for n in [1_000u64, 1_000_000] {
            let mut sink = Counter {
                rows: 0,
                last_t: -1.0,
                tau: TAU,
            };
            let (o, peak) = peak_growth(|| {
                solve(&c, &profile, &s, Some((&mut sink, Sampling::Uniform(n)))).unwrap()
            });
            // n + 1 sample rows and the stop of sliding.
            assert_eq!(sink.rows, n + 2, "{method}: rows");
            eprintln!(
                "{method}: {n} samples, {} rows, peak heap growth {peak} bytes, {} rhs evaluations",
                sink.rows, o.stats.rhs_evaluations
            );
            results.push((peak, o));
        }
        let (small, big) = (results[0].0, results[1].0);
        assert!(
            big <= small + PEAK_GROWTH_LIMIT,
            "{method}: peak heap {big} bytes with 1e6 samples, {small} with 1e3"
        );
        // The answer does not depend on the sampling beyond the method's accuracy.
        let exact = Exact::new(M, R, 0.4, MU, 1.0, None, incoming);
        let err = exact.scaled_error(&results[1].1.result.out, &exact.out().state);
        assert!(err <= state_tolerance(method), "{method}: error {err:e}");
    }

    // The CSV writer streams too: 1e6 rows written to io::sink.
    let s = SolverSettings::default().with_method(Method::ClosedForm);
    let (rows, peak) = peak_growth(|| {
        let mut csv = CsvTrace::new(std::io::sink()).unwrap();
        solve(
            &c,
            &profile,
            &s,
            Some((&mut csv, Sampling::Uniform(1_000_000))),
        )
        .unwrap();
        csv.rows()
    });
    eprintln!("csv: {rows} rows, peak heap growth {peak} bytes");
    assert_eq!(rows, 1_000_002);
    assert!(
        peak <= PEAK_GROWTH_LIMIT,
        "CSV trace: peak heap {peak} bytes"
    );

    // A million rk4 steps in a single segment (no samples): the solver's output must not
    // grow with the step count.
    let s = SolverSettings::default()
        .with_method(Method::Rk4)
        .with_steps(1_000_000)
        .unwrap();
    let (o, peak) = peak_growth(|| solve(&c, &profile, &s, None).unwrap());
    eprintln!("rk4, 1e6 steps in one segment: peak heap growth {peak} bytes");
    assert!(o.stats.accepted_steps >= 1_000_000);
    let exact = Exact::new(M, R, 0.4, MU, 1.0, None, incoming);
    let err = exact.scaled_error(&o.result.out, &exact.out().state);
    // Truncation is negligible at h = 1e-6; round-off of a million additions (about
    // 1e6 eps) remains.
    assert!(err <= 1e-9, "rk4 1e6 steps: error {err:e}");
    assert!(
        peak <= PEAK_GROWTH_LIMIT,
        "rk4 1e6 steps: peak heap {peak} bytes"
    );
}
