//! Property tests: invariants over thousands of random collisions spanning the
//! hard-case ranges (masses 1e-4..1e3 kg, radii 1e-4..10 m, speeds 1e-8..1e4 m/s, spins
//! up to ~1e8 rad/s, durations 1e-9..1 s, mu 1e-12..10 and speed-dependent, alpha
//! 1e-3..2/3, e in [0, 1] or explicit impulses m U(0)..2 m U(0), slips from exactly 0 and
//! 1e-300 of the speed up, every profile, every method).
//!
//! Checked against independent formulas written here and in tests/common: the impulse of
//! eqs 52/56, momentum (eq 24 and the lab sum), the angular momentum of eq 36, H >= 0,
//! H_sfr >= 0, S_out >= 0, eq 50, theta constant while sliding (from the trace's states),
//! the closed form and the stop of sliding (tests/common/hard.rs, for constant and
//! speed-dependent mu, with each profile's p(t) from its own formula or quadrature), unit
//! scaling, and a global rotation of a lab scene.
//!
//! Cases per property: `BILLIARD_PROPTEST_CASES` (default 1,200, and 12,000 for
//! `theta_constant_while_sliding`, enough to reach coarse rk4 steps that cross the stop of
//! sliding (tests/hard_cases_rk4_coarse.rs); the others check against independent
//! quadratures of p(t), too slow for 12,000 in CI). Failures are shrunk and saved under
//! proptest-regressions/.

use crate::common::collision::CollisionSpec;
use crate::hard as common;

use billiard_contact::profile::Profile;
use billiard_contact::profile::{HalfSine, Hertz, Rectangle, SinePower, Tabulated};
use billiard_contact::run_scene;
use billiard_contact::Effects;
use billiard_contact::LabScene;
use billiard_contact::TraceRow;
use billiard_contact::{
    solve, Ball, CmState, Contact, Friction, ImpulseRule, LabBall, Method, Sampling, SolverSettings,
};
use billiard_contact::{Incoming, Scene, TangentialLaw};
use common::Exact;
use nalgebra::{Rotation3, Unit, Vector3};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence, TestCaseError};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Mutex;

/// The largest value each checked quantity reached, per class of case, printed whenever it
/// grows (`cargo test --release --test suite properties_invariants:: -- --nocapture`): the
/// measurements the tolerances below are set from.
fn reached(class: &str, what: &str, x: f64) {
    static WORST: Mutex<BTreeMap<String, f64>> = Mutex::new(BTreeMap::new());
    let key = format!("{class} {what}");
    let mut worst = WORST.lock().unwrap_or_else(|e| e.into_inner());
    let w = worst.entry(key.clone()).or_insert(0.0);
    if x > *w {
        *w = x;
        eprintln!("worst {key}: {x:.2e}");
    }
}

/// Cases per property: the environment variable, else `default`.
fn cases(default: u32) -> Config {
    let n = std::env::var("BILLIARD_PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default);
    Config {
        cases: n,
        // Shrinking a failure of a cheap property is fast; bound it anyway.
        max_shrink_iters: 2000,
        // Shrunk failures are kept (and committed) here and replayed first.
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/properties_invariants.txt",
        ))),
        ..Config::default()
    }
}

fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.log10()..hi.log10()).prop_map(|x| 10f64.powf(x))
}

/// How the slip is chosen.
#[derive(Debug, Clone, Copy)]
enum SlipKind {
    /// Random velocities and spins.
    General,
    /// S(0) = 0 exactly: V = W = 0, spin only about the line of centres.
    Zero,
    /// S(0) a tiny fraction of the speed, no spin about y, z.
    Tiny(f64),
}

#[derive(Debug, Clone)]
enum ProfileKind {
    HalfSine,
    Hertz,
    SinePower(f64),
    Rectangle,
    Table(Vec<(f64, f64)>),
}

#[derive(Debug, Clone)]
struct Case {
    m: f64,
    r: f64,
    alpha: f64,
    /// Constant mu, or (a, b, c) of the speed-dependent law.
    mu: Result<f64, (f64, f64, f64)>,
    /// Restitution e, or the explicit impulse as a multiple of m U(0).
    rule: Result<f64, f64>,
    v: f64,
    tau: f64,
    /// Incoming U, W in units of v; spins in units of v / r.
    u: [f64; 3],
    wa: [f64; 3],
    wb: [f64; 3],
    slip: SlipKind,
    profile: ProfileKind,
    method: Method,
}

fn table_strategy() -> impl Strategy<Value = Vec<(f64, f64)>> {
    // Segments of at least 1/40 of the span: rk4 at its default 1000 steps then covers
    // every ramp with several steps (a whole impulse in 2 rk4 steps of a nonlinear mu(S)
    // misses eq 50 by 7e-5; the hard cases cover the single spike with every method).
    prop::collection::vec((0.15..1.0f64, prop_oneof![Just(0.0), 0.0..10.0f64]), 1..6).prop_map(
        |steps| {
            let mut t = 0.0;
            let mut pts = vec![(0.0, 0.0)];
            for (dt, f) in steps {
                t += dt;
                pts.push((t, f));
            }
            // A positive impulse: lift one point when all forces are 0.
            if pts.iter().all(|p| p.1 == 0.0) {
                pts[1].1 = 1.0;
            }
            pts
        },
    )
}

fn profile_strategy() -> impl Strategy<Value = ProfileKind> {
    prop_oneof![
        3 => Just(ProfileKind::HalfSine),
        1 => Just(ProfileKind::Hertz),
        2 => (0.5..4.0f64).prop_map(ProfileKind::SinePower),
        1 => Just(ProfileKind::Rectangle),
        2 => table_strategy().prop_map(ProfileKind::Table),
    ]
}

fn unit3() -> impl Strategy<Value = [f64; 3]> {
    [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64]
}

fn case_strategy(methods: &'static [Method]) -> impl Strategy<Value = Case> {
    (
        (
            log_uniform(1e-4, 1e3),
            log_uniform(1e-4, 10.0),
            prop_oneof![log_uniform(1e-3, 0.4), 0.4..=2.0 / 3.0],
        ),
        prop_oneof![
            4 => log_uniform(1e-12, 10.0).prop_map(Ok),
            1 => Just(Ok(0.0)),
            1 => (0.0..0.05f64, 0.0..0.2f64, 0.0..3.0f64).prop_map(Err),
        ],
        prop_oneof![3 => (0.0..=1.0f64).prop_map(Ok), 1 => (1.0..=2.0f64).prop_map(Err)],
        (log_uniform(1e-8, 1e4), log_uniform(1e-9, 1.0)),
        (0.02..1.0f64, unit3(), unit3(), unit3()),
        prop_oneof![
            6 => Just(SlipKind::General),
            1 => Just(SlipKind::Zero),
            2 => (-300.0..-1.0f64).prop_map(|x| SlipKind::Tiny(10f64.powf(x))),
        ],
        profile_strategy(),
        prop::sample::select(methods),
    )
        .prop_map(
            |((m, r, alpha), mu, rule, (v, tau), (u0, u, wa, wb), slip, profile, method)| {
                let (mut u, mut wa, mut wb) = (u, wa.map(|x| 3.0 * x), wb.map(|x| 3.0 * x));
                u[0] = u0;
                match slip {
                    SlipKind::General => {}
                    SlipKind::Zero => {
                        u[1] = 0.0;
                        u[2] = 0.0;
                        wa = [wa[0], 0.0, 0.0];
                        wb = [wb[0], 0.0, 0.0];
                    }
                    SlipKind::Tiny(f) => {
                        let n = u[1].hypot(u[2]).max(1e-300);
                        u[1] *= 0.5 * f / n;
                        u[2] *= 0.5 * f / n;
                        wa = [wa[0], 0.0, 0.0];
                        wb = [wb[0], 0.0, 0.0];
                    }
                }
                Case {
                    m,
                    r,
                    alpha,
                    mu,
                    rule,
                    v,
                    tau,
                    u,
                    wa,
                    wb,
                    slip,
                    profile,
                    method,
                }
            },
        )
}

impl Case {
    fn incoming(&self) -> CmState {
        let (v, w) = (self.v, self.v / self.r);
        CmState::new(
            Vector3::from(self.u) * v,
            Vector3::from(self.wa) * w,
            Vector3::from(self.wb) * w,
        )
    }

    fn friction(&self) -> Friction {
        match self.mu {
            Ok(mu) => Friction::constant(mu).unwrap(),
            Err((a, b, c)) => Friction::speed_dependent(a, b, c / self.v).unwrap(),
        }
    }

    fn impulse(&self) -> Option<f64> {
        self.rule.err().map(|f| f * self.m * self.incoming().u_cm.x)
    }

    fn rule(&self) -> ImpulseRule {
        match self.rule {
            Ok(e) => ImpulseRule::restitution(e).unwrap(),
            Err(_) => ImpulseRule::explicit(self.impulse().unwrap()).unwrap(),
        }
    }

    fn profile(&self) -> Profile {
        match &self.profile {
            ProfileKind::HalfSine => Profile::HalfSine(HalfSine::new(self.tau).unwrap()),
            ProfileKind::Hertz => Profile::Hertz(Hertz::new(self.tau).unwrap()),
            ProfileKind::SinePower(n) => Profile::SinePower(SinePower::new(self.tau, *n).unwrap()),
            ProfileKind::Rectangle => Profile::Rectangle(Rectangle::new(self.tau).unwrap()),
            ProfileKind::Table(pts) => Profile::Tabulated(
                Tabulated::new(pts, Some(self.tau), Path::new("random.csv")).unwrap(),
            ),
        }
    }

    fn settings(&self) -> SolverSettings {
        SolverSettings::default().with_method(self.method)
    }

    /// Scaled accuracy of the state (the closed form, normal momentum, eq 50, theta's
    /// drift, the trace) at the default settings (rtol = atol = 1e-10, rk4 1000 steps):
    /// ten times the worst measured over 50,000 cases of each property (`reached` prints
    /// them). With the time transform every pulse is stepped like the half-sine, so the
    /// profile does not matter; speed-dependent mu makes the slip nonlinear in p.
    fn tolerance(&self) -> f64 {
        match (self.method, self.mu.is_ok()) {
            // Measured worst 7.7e-16 (eq 50), 1.3e-15 (closed form, mu(S)).
            (Method::ClosedForm, _) => 1e-14,
            // Measured worst 1.6e-13 (eq 50).
            (Method::Rk4, true) => 2e-12,
            // The fixed step's error in the nonlinear S(p), growing like sigma^4
            // ([`Case::rk4_sigma`]): measured worst 2.0e-11 + 0.025 sigma^4 over 70,000 rk4
            // cases with mu(S) (below).
            (Method::Rk4, false) => 2e-10 + 0.25 * self.rk4_sigma().powi(4),
            // The adaptive methods: most cases within 6.6e-10 (dop853) and 2.2e-9 (dopri5)
            // over 50,000 cases, but small alpha with large mu (alpha 0.02, mu 6.4, an
            // explicit impulse of 1.75 m U(0)) reached 5.7e-9 with dop853, and a steep mu(S)
            // at alpha 0.01 1.4e-8 (dop853 through the contact in 5 steps; its steps are now
            // at most a quarter of the contact: worst 8.2e-10 over 200,000 cases since, 2.1e-9
            // dopri5): held to 1e-8.
            (Method::Dop853 | Method::Dopri5, _) => 1e-8,
        }
    }

    /// Eq 50's balance (and the signs of H and H_sfr): the state's tolerance, except for rk4
    /// with speed-dependent mu, where the heat of sliding integrates mu(S) S: measured worst
    /// 1.0e-9 + 0.02 sigma^4.
    fn eq50_tolerance(&self) -> f64 {
        if self.method == Method::Rk4 && self.mu.is_err() {
            1e-8 + 0.2 * self.rk4_sigma().powi(4)
        } else {
            self.tolerance()
        }
    }

    /// How far rk4 at its fixed 1000 steps is from resolving a speed-dependent
    /// mu(S) = a + b e^(-c S): sigma = c k mu(0) P dq, the e-folds of the exponential the
    /// slip crosses in the largest step, with dS/dp = -k mu(S) (k = 2 (1 + 1/alpha) / m,
    /// eq 22) and dq the largest fraction of the impulse one step delivers: (pi/2) / 1000
    /// for the curved pulses (the half-sine, and the others stepped in its impulse by the
    /// time transform), 1/1000 for the rectangle, f_max tau / (1000 P) for a table. The
    /// method's error in S(p) falls like sigma^4 (a fixed step of order 4); where sigma
    /// exceeds 1 the slip collapses within a step or two and rk4 resolves nothing of the
    /// nonlinear law (a table whose impulse sits in its last 6%, alpha 1e-3: sigma 7, the
    /// stop of sliding 2e-5 P off; [`rk4_unresolved_stop_converges`]). Measured over 50,000
    /// cases of this distribution and 20,000 with the impulse in the last 3-15% of a table
    /// and alpha 1e-3..5e-3 (sigma up to 100).
    fn rk4_sigma(&self) -> f64 {
        let Err((a, b, c)) = self.mu else {
            return 0.0;
        };
        let k = 2.0 * (1.0 + 1.0 / self.alpha) / self.m;
        let u0 = self.incoming().u_cm.x;
        let p = self
            .impulse()
            .unwrap_or((1.0 + self.rule.unwrap_or(0.0)) * self.m * u0.max(0.0));
        // Peak of the normalised force f tau / P.
        let peak = match &self.profile {
            ProfileKind::Rectangle => 1.0,
            ProfileKind::Table(pts) => {
                let area: f64 = pts
                    .windows(2)
                    .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
                    .sum();
                let f_max = pts.iter().map(|q| q.1).fold(0.0, f64::max);
                f_max * pts[pts.len() - 1].0 / area
            }
            _ => std::f64::consts::FRAC_PI_2,
        };
        // c carries 1/speed (Case::friction).
        (c / self.v) * k * (a + b) * p * peak / f64::from(SolverSettings::default().steps())
    }

    /// The class of case each worst value is printed under by [`reached`].
    fn class(&self) -> String {
        let ends = match self.profile {
            ProfileKind::Table(_) | ProfileKind::Rectangle => "linear",
            _ => "curved",
        };
        let mu = if self.mu.is_err() { "mu(S)" } else { "mu" };
        format!("{:?}/{ends}/{mu}", self.method)
    }

    /// The independent closed form of tests/common/hard.rs (constant or speed-dependent mu).
    fn exact(&self) -> Exact {
        let e = self.rule.unwrap_or(0.0);
        let (m, r, alpha, inc) = (self.m, self.r, self.alpha, self.incoming());
        match self.mu {
            Ok(mu) => Exact::new(m, r, alpha, mu, e, self.impulse(), inc),
            // c carries 1/speed (Case::friction).
            Err((a, b, c)) => {
                Exact::speed_dependent(m, r, alpha, (a, b, c / self.v), e, self.impulse(), inc)
            }
        }
    }

    /// p(t)/P at s = t / tau from the independent formulas and quadratures of
    /// tests/common/hard.rs (not the library's `cumulative`).
    fn phi(&self, s: f64) -> f64 {
        match &self.profile {
            ProfileKind::HalfSine => common::half_sine_phi(s),
            ProfileKind::Hertz => common::hertz_phi(s),
            ProfileKind::SinePower(n) => common::sine_power_phi(*n, s),
            ProfileKind::Rectangle => s.clamp(0.0, 1.0),
            ProfileKind::Table(pts) => common::table_phi(pts, s),
        }
    }
}

/// Angular momentum of eq 36 about the centre of mass: I (Omega^A + Omega^B)
/// + (-r e_x) x (m U) + (r e_x) x (-m U).
fn angular_momentum(s: &CmState, m: f64, r: f64, alpha: f64) -> Vector3<f64> {
    let ex = Vector3::x();
    alpha * m * r * r * (s.omega_a + s.omega_b)
        + (-r * ex).cross(&(m * s.u_cm))
        + (r * ex).cross(&(-m * s.u_cm))
}

const ALL: &[Method] = &[
    Method::ClosedForm,
    Method::Rk4,
    Method::Dopri5,
    Method::Dop853,
    Method::Dop853,
];
const ADAPTIVE: &[Method] = &[Method::Dopri5, Method::Dop853];

/// Conservation laws, signs of the heats and of S_out, eq 50 and the closed form.
fn check_invariants(case: &Case) -> Result<(), TestCaseError> {
    let c = CollisionSpec::ball(case.m, case.r, case.alpha)
        .friction(case.friction())
        .impulse(case.rule())
        .incoming(case.incoming())
        .build();
    let profile = case.profile();
    let o = solve(&c, &profile, &case.settings(), None).unwrap();
    let tol = case.tolerance();
    let cls = case.class();
    let (m, r) = (case.m, case.r);
    let inc = case.incoming();
    let v_ref = c.scales.speed;
    let u0 = inc.u_cm.x;
    // Impulse: eq 52 family / eq 56, and none for separating balls.
    let p = case.impulse().unwrap_or(if u0 > 0.0 {
        (1.0 + case.rule.unwrap_or(0.0)) * m * u0
    } else {
        0.0
    });
    prop_assert!((o.result.impulse - p).abs() <= 1e-15 * p.max(1e-300) * 4.0);
    prop_assert!(o.result.out.is_finite());
    // Normal momentum of A (eq 24): m (U_out - U(0)) = -P.
    let dp = (m * (o.result.out.u_cm.x - u0) + p).abs() / (m * v_ref);
    reached(&cls, "normal momentum", dp);
    prop_assert!(dp <= tol, "normal momentum error {dp:e}");
    // Angular momentum of eq 36: conserved by every method to round-off (the torques of
    // eq 11 are equal on both balls), measured worst 7.3e-15.
    let dl = (angular_momentum(&o.result.out, m, r, case.alpha)
        - angular_momentum(&inc, m, r, case.alpha))
    .amax()
        / (m * v_ref * r);
    reached(&cls, "angular momentum", dl);
    prop_assert!(dl <= 1e-13, "angular momentum error {dl:e}");
    // Heats and the outgoing slip (measured: never below -1e-29 of m v_ref^2).
    let e_ref = m * v_ref * v_ref;
    let eq50_tol = case.eq50_tolerance();
    prop_assert!(
        o.result.heat >= -eq50_tol * e_ref,
        "H = {:e}",
        o.result.heat
    );
    prop_assert!(
        o.result.heat_sliding >= -eq50_tol * e_ref,
        "H_sfr = {:e}",
        o.result.heat_sliding
    );
    prop_assert!(o.result.s_out >= 0.0, "S_out = {:e}", o.result.s_out);
    // Eq 50: H = H_sfr + 2 U(0) P - P^2 / m, H from the kinetic energies (eq 37).
    let ke = |s: &CmState| {
        m * s.u_cm.norm_squared()
            + 0.5 * case.alpha * m * r * r * (s.omega_a.norm_squared() + s.omega_b.norm_squared())
    };
    let h = ke(&inc) - ke(&o.result.out);
    let balance = (h - o.result.heat_sliding - (2.0 * u0 * p - p * p / m)).abs() / e_ref;
    reached(&cls, "eq 50", balance);
    prop_assert!(balance <= eq50_tol, "eq 50 off by {balance:e}");
    // The slip's direction, measured worst 5.5e-12 (dop853, mu(S)).
    reached(&cls, "theta drift", o.check.theta_drift);
    prop_assert!(
        o.check.theta_drift <= 5e-11,
        "theta drift {:e}",
        o.check.theta_drift
    );
    // The independent closed form (constant or speed-dependent mu).
    let ex = case.exact();
    let err = ex.scaled_error(&o.result.out, &ex.out().state);
    reached(&cls, "closed form", err);
    prop_assert!(err <= tol, "closed form error {err:e}");
    if p > 0.0 && ex.mu > 0.0 && (ex.p_stick - p).abs() > 10.0 * tol * p {
        prop_assert_eq!(o.result.sticks, ex.sticks());
    }
    // The event rule: the promise is |p(t_stick) - p_stick| <= 1e-10 P
    // (docs/model.md#locating-the-stop-of-sliding) for constant mu, where the slip is
    // affine in p: measured worst 1.6e-14 P (rk4), held to 2e-13 P. With speed-dependent
    // mu the located stop carries the integration error of the nonlinear S(p): there
    // the reported time and impulse agree (measured worst 4.0e-15 P, held to 5e-14 P),
    // and the impulse is p_stick to the method's accuracy: 1.4e-9 P with the adaptive
    // methods over 50,000 cases, held to 1.5e-8 P; rk4 at its fixed 1000 steps to what
    // its steps resolve of the nonlinear S(p) (Case::rk4_sigma). p(t) from the
    // independent Phi.
    if let (true, Some(t)) = (o.result.sticks, o.stick_time) {
        let at = p * case.phi(t / case.tau);
        let reported = o.result.stick_impulse.unwrap();
        let ps = ex.p_stick;
        match case.mu {
            Ok(_) => {
                reached(&cls, "p(t_stick) - p_stick", (at - ps).abs() / p);
                reached(&cls, "stick_impulse - p_stick", (reported - ps).abs() / p);
                prop_assert!(
                    (at - ps).abs() <= 2e-13 * p,
                    "p(t_stick) {at:e} vs p_stick {ps:e}"
                );
                prop_assert!(
                    (reported - ps).abs() <= 2e-13 * p,
                    "stick_impulse {reported:e} vs p_stick {ps:e}"
                );
            }
            Err(_) => {
                reached(
                    &cls,
                    "p(t_stick) - stick_impulse",
                    (at - reported).abs() / p,
                );
                reached(&cls, "stick_impulse - p_stick", (reported - ps).abs() / p);
                prop_assert!(
                    (at - reported).abs() <= 5e-14 * p,
                    "p(t_stick) {at:e} vs stick_impulse {reported:e}"
                );
                // rk4: measured worst 1.0e-8 + 3e-3 sigma^4 (Case::rk4_sigma).
                let loose = if case.method == Method::Rk4 {
                    1e-7 + 0.03 * case.rk4_sigma().powi(4)
                } else {
                    1.5e-8
                };
                prop_assert!(
                    (reported - ps).abs() <= loose * p,
                    "stick_impulse {reported:e} vs p_stick {ps:e}"
                );
            }
        }
    }
    if matches!(case.slip, SlipKind::Zero) && p > 0.0 {
        prop_assert_eq!(o.result.theta, None);
        prop_assert_eq!(o.result.out.u_cm.y, inc.u_cm.y);
        prop_assert_eq!(o.result.out.omega_a, inc.omega_a);
    }
    Ok(())
}

proptest! {
    #![proptest_config(cases(1200))]

    /// Conservation laws, signs of the heats and of S_out, eq 50 and the closed form.
    #[test]
    fn invariants(case in case_strategy(ALL)) {
        check_invariants(&case)?;
    }

    /// Time stepping equals the closed form at P = p(t) at every sample, not only at the
    /// end (docs/model.md#the-exact-state-during-the-contact), p(t) from the independent Phi.
    #[test]
    fn trace_equals_closed_form_at_p_of_t(case in case_strategy(ADAPTIVE)) {
        let ex = case.exact();
        let c = CollisionSpec::ball(case.m, case.r, case.alpha)
            .friction(case.friction())
            .impulse(case.rule())
            .incoming(case.incoming())
            .build();
        let profile = case.profile();
        let mut rows: Vec<TraceRow> = Vec::new();
        solve(&c, &profile, &case.settings(), Some((&mut rows, Sampling::Uniform(16)))).unwrap();
        for row in &rows {
            let p_t = ex.p * case.phi(row.t / case.tau);
            let want = ex.at(p_t).state;
            let err = ex.scaled_error(&row.state, &want);
            reached(&case.class(), "trace", err);
            prop_assert!(err <= case.tolerance(), "t = {:e}: error {err:e}", row.t);
        }
    }

    /// Consistent units (mass x A, length x L, time x T) leave scaled outputs unchanged.
    #[test]
    fn unit_scaling(case in case_strategy(&[Method::ClosedForm, Method::Rk4, Method::Dopri5, Method::Dop853]),
                    a in log_uniform(1e-3, 1e3), l in log_uniform(1e-3, 1e3), t in log_uniform(1e-3, 1e3)) {
        let c = CollisionSpec::ball(case.m, case.r, case.alpha)
            .friction(case.friction())
            .impulse(case.rule())
            .incoming(case.incoming())
            .build();
        let base = solve(&c, &case.profile(), &case.settings(), None).unwrap();
        let base_slips = c.s0 > 0.0;
        let mut scaled = case.clone();
        scaled.m *= a;
        scaled.r *= l;
        scaled.v *= l / t;
        scaled.tau *= t;
        if let Err((aa, b, cc)) = case.mu {
            // mu(S) = a + b exp(-c S / v): c carries 1/speed, Case::friction divides by v.
            scaled.mu = Err((aa, b, cc));
        }
        let c = CollisionSpec::ball(scaled.m, scaled.r, scaled.alpha)
            .friction(scaled.friction())
            .impulse(scaled.rule())
            .incoming(scaled.incoming())
            .build();
        // A slip below the smallest normal double is no slip (docs/model.md, "No slip at
        // all"): a slip of 1e-300 of the speed can be normal in one unit system and
        // subnormal in the other (9.5e-308 m/s against 5.6e-309 m/s), and then the two are
        // different collisions: the first slides until its force begins (a table with a
        // zero-force start: 0.84 tau) and the second sticks from t = 0.
        prop_assume!(base_slips == (c.s0 > 0.0));
        let o = solve(&c, &scaled.profile(), &scaled.settings(), None).unwrap();
        let (v0, v1) = (case.v, scaled.v);
        let (w0, w1) = (case.v / case.r, scaled.v / scaled.r);
        let pairs = [
            (base.result.out.u_cm / v0, o.result.out.u_cm / v1),
            (base.result.out.omega_a / w0, o.result.out.omega_a / w1),
            (base.result.out.omega_b / w0, o.result.out.omega_b / w1),
        ];
        // Scaled outputs are O(1) multiples of v_ref / v.
        let unit = base.exact.result.out.u_cm.amax().max(1.0);
        for (x, y) in pairs {
            // Measured worst 1.4e-11 (dop853).
            reached(&case.class(), "unit scaling: state", (x - y).amax() / unit);
            prop_assert!((x - y).amax() <= 1.5e-10 * unit, "{x:?} vs {y:?}");
        }
        prop_assert_eq!(o.result.sticks, base.result.sticks);
        if let (Some(t0), Some(t1)) = (base.stick_time, o.stick_time) {
            // Measured worst 1.9e-13 of the duration (dopri5, mu(S)).
            reached(&case.class(), "unit scaling: stick time", (t0 / case.tau - t1 / scaled.tau).abs());
            prop_assert!((t0 / case.tau - t1 / scaled.tau).abs() <= 2e-12, "stick times {t0:e} {t1:e}");
        }
        let e0 = case.m * v0 * v0;
        let e1 = scaled.m * v1 * v1;
        // Measured worst 5.9e-14 (rk4, mu(S)).
        let dh = (base.result.heat / e0 - o.result.heat / e1).abs() / (unit * unit);
        reached(&case.class(), "unit scaling: heat", dh);
        prop_assert!(dh <= 6e-13, "heat {dh:e}");
    }

    /// A lab scene and the same scene rotated as a whole: the outgoing lab motions rotate
    /// with it, and the lab momentum of both balls is conserved.
    #[test]
    fn global_rotation(case in case_strategy(&[Method::ClosedForm, Method::Dop853]),
                       axis in unit3(), angle in -3.2..3.2f64,
                       line in unit3(), up_tilt in -1.0..1.0f64, drift in unit3()) {
        let line = Vector3::from(line);
        if line.norm() < 0.1 || Vector3::from(axis).norm() < 0.1 {
            return Ok(());
        }
        let ex = line.normalize();
        // `up` perpendicular to the line of centres, tilted out of it by up_tilt.
        let any = if ex.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
        let ez = (any - ex * any.dot(&ex)).normalize();
        let up = ez + ex * up_tilt;
        // The case's centre-of-mass state in this frame, plus a common drift.
        let ey = ez.cross(&ex);
        let basis = nalgebra::Matrix3::from_columns(&[ex, ey, ez]);
        let inc = case.incoming();
        let v_cm = Vector3::from(drift) * case.v;
        let r = case.r;
        let lab = LabScene {
            a: LabBall { position: -r * ex, velocity: v_cm + basis * inc.u_cm, spin: basis * inc.omega_a },
            b: LabBall { position: r * ex, velocity: v_cm - basis * inc.u_cm, spin: basis * inc.omega_b },
            up,
        };
        let rot = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::from(axis)), angle);
        let turned = LabScene {
            a: LabBall { position: rot * lab.a.position, velocity: rot * lab.a.velocity, spin: rot * lab.a.spin },
            b: LabBall { position: rot * lab.b.position, velocity: rot * lab.b.velocity, spin: rot * lab.b.spin },
            up: rot * lab.up,
        };
        let scene = |l: LabScene| Scene {
            name: "rotation".into(),
            balls: Ball::new(case.m, r, case.alpha).unwrap().into(),
            material: None,
            contact: Contact { friction: case.friction(), impulse: case.rule() },
            profile: case.profile(),
            law: None,
            tangential: TangentialLaw::Rigid,
            incoming: Incoming::Lab(l),
            solver: case.settings(),
            solver_given: Default::default(),
            effects: Effects::default(),
            source: None,
            table: None,
            table_size: None,
        };
        let s0 = scene(lab);
        let s1 = scene(turned);
        let o0 = run_scene(&s0, &s0.solver, None).unwrap();
        let o1 = run_scene(&s1, &s1.solver, None).unwrap();
        let (a0, b0) = o0.lab_out.unwrap();
        let (a1, b1) = o1.lab_out.unwrap();
        let v_ref = o0.outcome.exact.result.out.u_cm.amax().max(case.v).max(v_cm.amax());
        let w_ref = v_ref / r;
        // The two runs differ by round-off in their centre-of-mass inputs; where the slip
        // is itself round-off that moves the stop, and the results differ by the method's
        // accuracy.
        // Measured worst 8.6e-15 (closed form), 1.8e-9 (dop853: alpha 0.02, mu 6.4, an
        // explicit impulse of 1.75 m U(0), where most cases reach 5e-12).
        let tol = if case.method == Method::ClosedForm { 1e-13 } else { 2e-8 };
        let d = ((rot * a0.velocity - a1.velocity).amax() / v_ref)
            .max((rot * b0.velocity - b1.velocity).amax() / v_ref)
            .max((rot * a0.spin - a1.spin).amax() / w_ref)
            .max((rot * b0.spin - b1.spin).amax() / w_ref);
        reached(&case.class(), "rotation", d);
        prop_assert!(d <= tol, "rotated scene {d:e} off: {:?} vs {:?}", rot * a0.velocity, a1.velocity);
        // Lab momentum of both balls.
        let before = lab.a.velocity + lab.b.velocity;
        let after = a0.velocity + b0.velocity;
        // Measured worst 4.2e-16.
        reached(&case.class(), "lab momentum", (after - before).amax() / v_ref);
        prop_assert!((after - before).amax() <= 5e-15 * v_ref, "momentum {before:?} -> {after:?}");
        // The throw angle is measured about `up`, which turns with the scene.
        // Measured worst 1.4e-12 degrees (closed form), 3.8e-9 (dop853, alpha 0.02, mu 6.4).
        let throw_tol = if case.method == Method::ClosedForm { 2e-11 } else { 5e-8 };
        match (o0.throw_angle_deg, o1.throw_angle_deg) {
            (Some(x), Some(y)) => {
                let d = (x - y).abs().min(360.0 - (x - y).abs());
                reached(&case.class(), "rotation: throw (degrees)", d);
                prop_assert!(d <= throw_tol, "throw {x} vs {y}");
            }
            (x, y) => prop_assert_eq!(x.is_some(), y.is_some()),
        }
    }
}

/// theta is constant while sliding: every trace row before the stop has its slip
/// (2V + r Omega_z, 2W - r Omega_y), recomputed from the row's state, along e0; and the
/// trace's theta, the angle of the carried slip, agrees with e0 to what that slip's error
/// across e0 allows.
fn check_theta_constant(case: &Case) -> Result<(), TestCaseError> {
    let c = CollisionSpec::ball(case.m, case.r, case.alpha)
        .friction(case.friction())
        .impulse(case.rule())
        .incoming(case.incoming())
        .build();
    let profile = case.profile();
    let mut rows: Vec<TraceRow> = Vec::new();
    let o = solve(
        &c,
        &profile,
        &case.settings().with_steps(200).unwrap(),
        Some((&mut rows, Sampling::Steps)),
    )
    .unwrap();
    if !(c.collides() && c.s0 > 0.0 && c.active_friction().is_some()) {
        return Ok(());
    }
    let e0 = c.direction.unwrap();
    let v_ref = c.scales.speed;
    let t_stop = o.stick_time.unwrap_or(f64::INFINITY);
    for row in rows.iter().filter(|r| r.t < t_stop) {
        let slip = row.state.slip(case.r);
        // The slip recomputed from the state inherits the state's integration error,
        // relative to the size of its terms |V|, r |Omega| (with small alpha the spins
        // change 1/alpha times faster than the velocities).
        let size = row.state.u_cm.yz().amax() + case.r * row.state.omega_sum().yz().amax();
        // Measured worst 1.0e-9 of v_ref.max(size) (dop853, alpha 0.02, mu 6.4; most
        // cases stay below 1.3e-12).
        let bound = 1e-8 * v_ref.max(size) + 8.0 * f64::EPSILON * size;
        let across = (slip.x * e0.y - slip.y * e0.x).abs();
        reached(
            &case.class(),
            "theta: slip across e0",
            across / v_ref.max(size),
        );
        prop_assert!(
            across <= bound,
            "slip {slip:?} off e0 {e0:?} at t = {:e}",
            row.t
        );
        prop_assert!(slip.dot(&e0) >= -bound);
        // The trace's theta is the angle of the carried slip (taken while |S| is above
        // 1e-6 S(0), else kept from the last step that was): off e0 by the carried slip's
        // error across e0 over |S|. That error is the one bounded above; near the stop |S|
        // divides it. A step that takes the slip from S(0) to 5e-5 S(0) (a table rising
        // steeply, alpha 0.012, mu 5.8) evaluates stages at slips near zero whose direction
        // is uncertain by eps S(0) / |S|, which leaves 2.3e-10 S(0) across e0 in the slip
        // and the angle 4.8e-6 rad off (`trace_theta_near_the_stop`). So the angle is
        // checked through |S| sin(theta - theta0): within the bound above, and within
        // 1e-8 rad where |S| is of the size of the speeds.
        let (th, th0) = (row.theta.unwrap(), o.result.theta.unwrap());
        let d = (th - th0).sin().abs().max((th.cos() - th0.cos()).abs());
        let s = row.slip_speed.abs();
        reached(
            &case.class(),
            "theta: |S| x trace's angle",
            d * s / v_ref.max(size),
        );
        prop_assert!(d * s <= bound, "trace theta {th} vs {th0} at |S| = {s:e}");
    }
    Ok(())
}

proptest! {
    // 12,000 cases: enough to reach coarse rk4 steps that cross the stop of sliding.
    #![proptest_config(cases(12_000))]

    /// theta is constant while sliding ([`check_theta_constant`]).
    #[test]
    fn theta_constant_while_sliding(case in case_strategy(&[Method::Rk4, Method::Dopri5, Method::Dop853])) {
        check_theta_constant(&case)?;
    }
}

/// One dop853 step from S(0) to 4.7e-5 S(0): the trace's angle held through the slip across e0.
#[test]
fn trace_theta_near_the_stop() {
    let case = Case {
        m: 1.0,
        r: 1.0,
        alpha: 0.011803232900166029,
        mu: Ok(5.775927375266369),
        rule: Err(1.6585715402634236),
        v: 1.0,
        tau: 1.0,
        u: [0.9063978422807275, -0.7517067680088969, -0.7700239795549226],
        wa: [0.0, 1.3996323485828253, -1.0005876468024508],
        wb: [0.0, 0.05016201568345903, -2.0968870446825454],
        slip: SlipKind::General,
        profile: ProfileKind::Table(vec![
            (0.0, 0.0),
            (0.1617871311795982, 1.0),
            (0.8509939689926058, 0.0),
            (1.7517127708675182, 0.0),
            (2.585914246478691, 0.0),
        ]),
        method: Method::Dop853,
    };
    check_theta_constant(&case).unwrap();
}

/// rk4 at sigma = 7 (the slip collapses in two steps): within the sigma bound, and it converges.
#[test]
fn rk4_unresolved_stop_converges() {
    let case = Case {
        m: 1.0,
        r: 1.0,
        alpha: 0.001,
        mu: Err((0.0, 0.18706420746993352, 2.369278553827863)),
        rule: Ok(0.0),
        v: 1.0,
        tau: 1.0,
        u: [0.8819492147073986, 0.0, 0.8978486747944435],
        wa: [0.0; 3],
        wb: [0.0; 3],
        slip: SlipKind::General,
        profile: ProfileKind::Table(vec![
            (0.0, 0.0),
            (0.85, 0.0),
            (0.9329524306788881, 0.1),
            (1.0, 0.1),
        ]),
        method: Method::Rk4,
    };
    assert!(case.rk4_sigma() > 5.0, "sigma {}", case.rk4_sigma());
    check_invariants(&case).unwrap();
    let ex = case.exact();
    let off = |steps: u32| {
        let settings = case.settings().with_steps(steps).unwrap();
        let c = CollisionSpec::ball(case.m, case.r, case.alpha)
            .friction(case.friction())
            .impulse(case.rule())
            .incoming(case.incoming())
            .build();
        let o = solve(&c, &case.profile(), &settings, None).unwrap();
        assert!(o.result.sticks);
        (o.result.stick_impulse.unwrap() - ex.p_stick).abs() / ex.p
    };
    // Measured 2.0e-5 P at 1000 steps (within the sigma bound above), 1.6e-9 P at 16,000.
    let fine = off(16_000);
    assert!(fine <= 2e-8, "the resolved stop: {fine:e} P");
}
