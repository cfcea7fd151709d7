//! Shared helpers of the hard-case and property tests: an independent closed form (written
//! from the paper's eqs 24-35, 49-50, 52, 56 and docs/model.md#when-sliding-stops-during-contact, not calling the library's
//! `ClosedForm`), exact profile integrals, and scene builders.
#![allow(dead_code)]

use crate::common::collision::CollisionSpec;
use billiard_contact::profile::ForceProfile;
use billiard_contact::{solve, CmState, Collision, Method, Outcome, SolverSettings};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// Methods that step in time.
pub const STEPPERS: [Method; 3] = [Method::Rk4, Method::Dopri5, Method::Dop853];

/// Pool-ball values.
pub const M: f64 = 0.17;
pub const R: f64 = 0.028575;
pub const MU: f64 = 0.06;
pub const TAU: f64 = 2.5e-4;

/// The exact outcome of a collision with constant mu (independent derivation).
///
/// With k = 2 (1 + 1/alpha) / m, S(0) = |slip0|, slip0 = (2V + r Omega_z, 2W - r Omega_y)
/// (eqs 5-6), e = slip0 / S(0): sliding stops at p_stick = S(0) / (k mu) (eq 48 = 0), the
/// tangential impulse after a normal impulse p is J = mu min(p, p_stick) (docs/model.md#when-sliding-stops-during-contact),
/// U -= p/m (24), (V, W) -= J e / m (25-26), Omega^{A,B}_y += J e_z / (alpha m r) (32),
/// Omega^{A,B}_z -= J e_y / (alpha m r) (33), H_sfr = J S(0) - (1 + 1/alpha) J^2 / m (49
/// with the stick rule) and H = H_sfr + 2 U(0) p - p^2 / m (50).
#[derive(Debug, Clone, Copy)]
pub struct Exact {
    pub m: f64,
    pub r: f64,
    pub alpha: f64,
    pub mu: f64,
    pub incoming: CmState,
    /// Impulse P (N s).
    pub p: f64,
    pub s0: f64,
    /// Unit slip direction (0 when S(0) = 0).
    pub e: [f64; 2],
    /// p_stick (N s), infinite without friction.
    pub p_stick: f64,
    /// (a, b, c) of a speed-dependent mu(S) = a + b exp(-c S) (c in s/m); `None`: constant
    /// `mu`. With it, `mu` is mu(0) = a + b.
    pub speed_law: Option<(f64, f64, f64)>,
}

/// The slide potential G(S) = integral_0^S dS' / mu(S') of mu(S) = a + b exp(-c S), derived
/// here: 1/mu = e^(cS) / (a e^(cS) + b), so G = ln(1 + a (e^(cS) - 1) / (a + b)) / (a c),
/// written with ln_1p / expm1 so that a -> 0 (G = (e^(cS) - 1) / ((a + b) c)) and c -> 0
/// (G = S / (a + b)) keep their digits. Checked against quadrature in
/// tests/friction_speed_dependent.rs.
pub fn slide_potential(a: f64, b: f64, c: f64, s: f64) -> f64 {
    let cs = c * s;
    let em1_over_c = if cs == 0.0 { s } else { cs.exp_m1() / c };
    let x = a * c * em1_over_c / (a + b);
    let ln1p_over_x = if x == 0.0 { 1.0 } else { x.ln_1p() / x };
    ln1p_over_x * em1_over_c / (a + b)
}

/// The slip S with G(S) = g (the inverse of [`slide_potential`]):
/// S = ln(1 + (a + b) (e^(a c g) - 1) / a) / c, with the same limits.
pub fn slip_of_potential(a: f64, b: f64, c: f64, g: f64) -> f64 {
    let z = a * c * g;
    let em1_over_z = if z == 0.0 { 1.0 } else { z.exp_m1() / z };
    // y / c with y = (a + b) (e^z - 1) / a.
    let y_over_c = em1_over_z * g * (a + b);
    let y = y_over_c * c;
    let ln1p_over_y = if y == 0.0 { 1.0 } else { y.ln_1p() / y };
    ln1p_over_y * y_over_c
}

/// The state and sliding after a normal impulse p.
#[derive(Debug, Clone, Copy)]
pub struct ExactAt {
    pub state: CmState,
    pub j: f64,
    pub slip: f64,
    pub heat_sliding: f64,
    pub heat: f64,
}

impl Exact {
    /// `impulse`: `None` for P = (1 + e) m U(0) with restitution `e_rest`.
    pub fn new(
        m: f64,
        r: f64,
        alpha: f64,
        mu: f64,
        e_rest: f64,
        impulse: Option<f64>,
        incoming: CmState,
    ) -> Self {
        let u0 = incoming.u_cm.x;
        let p = impulse.unwrap_or(if u0 > 0.0 {
            (1.0 + e_rest) * m * u0
        } else {
            0.0
        });
        let o = incoming.omega_a + incoming.omega_b;
        let sy = 2.0 * incoming.u_cm.y + r * o.z;
        let sz = 2.0 * incoming.u_cm.z - r * o.y;
        let s0 = sy.hypot(sz);
        let e = if s0 > 0.0 {
            [sy / s0, sz / s0]
        } else {
            [0.0, 0.0]
        };
        let k = 2.0 * (1.0 + 1.0 / alpha) / m;
        let p_stick = if s0 == 0.0 { 0.0 } else { s0 / (k * mu) };
        Exact {
            m,
            r,
            alpha,
            mu,
            incoming,
            p,
            s0,
            e,
            p_stick,
            speed_law: None,
        }
    }

    /// The same with mu(S) = a + b exp(-c S): dS/dp = -k mu(S) (eqs 25-33 along e0) gives
    /// G(S(0)) - G(S(p)) = k p, so sliding stops at p_stick = G(S(0)) / k, and the
    /// tangential impulse is J = (S(0) - S(p)) / k; the heat of eq 49 is
    /// integral S dJ = J S(0) - k J^2 / 2, the same expression in J as for constant mu.
    pub fn speed_dependent(
        m: f64,
        r: f64,
        alpha: f64,
        (a, b, c): (f64, f64, f64),
        e_rest: f64,
        impulse: Option<f64>,
        incoming: CmState,
    ) -> Self {
        let mut x = Exact::new(m, r, alpha, a + b, e_rest, impulse, incoming);
        x.speed_law = Some((a, b, c));
        if x.s0 > 0.0 && a + b > 0.0 {
            x.p_stick = slide_potential(a, b, c, x.s0) / x.k();
        }
        x
    }

    pub fn k(&self) -> f64 {
        2.0 * (1.0 + 1.0 / self.alpha) / self.m
    }

    pub fn sticks(&self) -> bool {
        self.p > 0.0 && self.mu > 0.0 && self.p_stick <= self.p
    }

    /// The exact state after normal impulse `p`.
    pub fn at(&self, p: f64) -> ExactAt {
        let (m, r, alpha) = (self.m, self.r, self.alpha);
        let j = match self.speed_law {
            _ if self.mu <= 0.0 || self.s0 == 0.0 => 0.0,
            None => self.mu * p.min(self.p_stick),
            Some(_) if p >= self.p_stick => self.s0 / self.k(),
            Some((a, b, c)) => {
                let g = slide_potential(a, b, c, self.s0) - self.k() * p;
                (self.s0 - slip_of_potential(a, b, c, g)) / self.k()
            }
        };
        let mut s = self.incoming;
        s.u_cm.x -= p / m;
        s.u_cm.y -= j * self.e[0] / m;
        s.u_cm.z -= j * self.e[1] / m;
        let w = j / (alpha * m * r);
        for om in [&mut s.omega_a, &mut s.omega_b] {
            om.y += w * self.e[1];
            om.z -= w * self.e[0];
        }
        let slip = if self.mu > 0.0 {
            (self.s0 - self.k() * j).max(0.0)
        } else {
            self.s0
        };
        let heat_sliding = j * self.s0 - (1.0 + 1.0 / alpha) * j * j / m;
        let u0 = self.incoming.u_cm.x;
        ExactAt {
            state: s,
            j,
            slip,
            heat_sliding,
            heat: heat_sliding + 2.0 * u0 * p - p * p / m,
        }
    }

    pub fn out(&self) -> ExactAt {
        self.at(self.p)
    }

    /// v_ref of docs/model.md#scales-and-scaled-errors.
    pub fn v_ref(&self) -> f64 {
        let i = self.incoming;
        i.u_cm
            .x
            .abs()
            .max(self.s0)
            .max(i.u_cm.norm())
            .max(self.r * i.omega_a.norm())
            .max(self.r * i.omega_b.norm())
    }

    /// Scaled error of a state against the exact outgoing state (docs/formats.md).
    pub fn scaled_error(&self, got: &CmState, want: &CmState) -> f64 {
        let v = self.v_ref();
        let w = v / self.r;
        ((got.u_cm - want.u_cm).amax() / v)
            .max((got.omega_a - want.omega_a).amax() / w)
            .max((got.omega_b - want.omega_b).amax() / w)
    }
}

// The first-principles references of tests/common/mod.rs, which the test program that
// loads this file declares as `common` at its root.
use crate::common as first_principles;

/// Phi(s) of the Hertz pulse: the inverse of tests/common's `hertz_time`, the quadrature of
/// the energy integral of delta'' = -delta^(3/2) (not the library's `Hertz`), by the
/// Illinois variant of regula falsi (a dozen evaluations where bisection takes 50).
pub fn hertz_phi(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    let g = |q: f64| first_principles::hertz_time(q) - s;
    let (mut a, mut b, mut ga, mut gb) = (0.0, 1.0, -s, 1.0 - s);
    if ga == 0.0 {
        return 0.0;
    }
    if gb == 0.0 {
        return 1.0;
    }
    let mut side = 0;
    for _ in 0..100 {
        let c = (a * gb - b * ga) / (gb - ga);
        let gc = g(c);
        if gc == 0.0 || (b - a).abs() <= 4.0 * f64::EPSILON {
            return c;
        }
        if (gc < 0.0) == (ga < 0.0) {
            (a, ga) = (c, gc);
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        } else {
            (b, gb) = (c, gc);
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

/// Phi(s) of the half-sine: sin^2(pi s / 2).
pub fn half_sine_phi(s: f64) -> f64 {
    (0.5 * PI * s.clamp(0.0, 1.0)).sin().powi(2)
}

/// Inverse of the half-sine Phi: (2/pi) asin(sqrt(q)) (not the arccos form).
pub fn half_sine_time(q: f64) -> f64 {
    if q <= 0.5 {
        2.0 / PI * q.sqrt().asin()
    } else {
        1.0 - 2.0 / PI * (1.0 - q).sqrt().asin()
    }
}

/// Phi(s) of sin^4: (8/3) integral_0^s sin^4(pi x) dx, with
/// integral sin^4 = 3x/8 - sin(2 pi x)/(4 pi) + sin(4 pi x)/(32 pi), B(5/2, 1/2) = 3 pi / 8.
pub fn sin4_phi(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    8.0 / 3.0
        * (3.0 * s / 8.0 - (2.0 * PI * s).sin() / (4.0 * PI) + (4.0 * PI * s).sin() / (32.0 * PI))
}

/// The default tolerance settings of a method (rk4: the default 1000 steps).
pub fn settings(method: Method) -> SolverSettings {
    SolverSettings::default().with_method(method)
}

/// The default scene (data/scenes/default.toml: rolling ball, 30 degree cut, half-sine)
/// in the centre-of-mass frame, written out: line of centres +x, A at 1.5 m/s at 30
/// degrees, rolling (spin = up x v / r), B at rest. U = v_A / 2, Omega^A = spin, Omega^B = 0.
pub fn default_collision() -> Collision {
    let v = 1.5;
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let va = Vector3::new(v * c, v * s, 0.0);
    let spin = Vector3::z().cross(&va) / R;
    CollisionSpec::ball(M, R, 0.4)
        .mu(MU)
        .restitution(1.0)
        .incoming(CmState::new(va / 2.0, spin, Vector3::zeros()))
        .build()
}

/// Right-hand-side evaluations of the default scene with `settings`: the cost unit of the
/// hard cases (each must stay within 20 times it).
pub fn default_cost(settings: &SolverSettings) -> u64 {
    let profile = billiard_contact::profile::HalfSine::new(TAU).unwrap();
    let o = solve(&default_collision(), &profile, settings, None).unwrap();
    o.stats.rhs_evaluations
}

/// Cost bound of the hard cases: 20 times the default scene's evaluations.
pub const COST_FACTOR: u64 = 20;

/// Runs `c` with `settings` and checks the cost bound, returning the outcome.
pub fn run_bounded<P: ForceProfile + ?Sized>(
    label: &str,
    c: &Collision,
    profile: &P,
    settings: &SolverSettings,
    baseline: u64,
) -> Outcome {
    let o = solve(c, profile, settings, None)
        .unwrap_or_else(|e| panic!("{label} ({}): {e}", settings.method()));
    let evals = o.stats.rhs_evaluations;
    eprintln!(
        "cost {label:<48} {:>8}: {evals:>7} rhs evaluations ({:.2} x default {baseline})",
        settings.method().name(),
        evals as f64 / baseline as f64
    );
    assert!(
        evals <= COST_FACTOR * baseline,
        "{label} ({}): {evals} rhs evaluations > {COST_FACTOR} x {baseline}",
        settings.method()
    );
    o
}

/// Scaled accuracy each method must reach on the hard cases (state against the exact
/// outgoing state, docs/model.md#scales-and-scaled-errors), at the default settings: rtol = atol = 1e-10 for
/// the adaptive methods, 1000 steps for rk4.
pub fn state_tolerance(method: Method) -> f64 {
    match method {
        Method::ClosedForm => 1e-14,
        Method::Dop853 => 1e-10,
        Method::Dopri5 => 1e-9,
        Method::Rk4 => 1e-9,
    }
}

/// Largest relative component of the tangential impulse across e0 (no friction in a
/// random direction).
pub const DIRECTION_TOL: f64 = 1e-8;

/// Event accuracy (docs/model.md#locating-the-stop-of-sliding): |p(t_stick) - p_stick| <= 1e-10 P.
pub const EVENT_IMPULSE_TOL: f64 = 1e-10;

/// What a case expects, checked for one method.
pub struct Expect<'a> {
    pub label: &'a str,
    pub exact: Exact,
    /// Independent Phi(s) of the profile.
    pub phi: &'a dyn Fn(f64) -> f64,
    /// Whether the closed form sticks clearly (false: within round-off of the boundary,
    /// both answers are accepted).
    pub sticks_decided: bool,
}

/// Checks one outcome against the independent closed form and the documented sticking rules.
pub fn check_outcome(x: &Expect<'_>, o: &Outcome, tau: f64) {
    check_outcome_with(x, o, tau, state_tolerance(o.method))
}

/// [`check_outcome`] with a given scaled tolerance.
pub fn check_outcome_with(x: &Expect<'_>, o: &Outcome, tau: f64, tol: f64) {
    let ex = &x.exact;
    let method = o.method;
    let label = format!("{} ({})", x.label, method.name());
    let want = ex.out();
    let err = ex.scaled_error(&o.result.out, &want.state);
    assert!(err <= tol, "{label}: scaled state error {err:e} > {tol:e}");
    assert!(o.result.out.is_finite(), "{label}: non-finite state");
    let v = ex.v_ref();
    let e_ref = ex.m * v * v;
    // Heats: H from eq 50 and H_sfr (eq 49 with the stick rule).
    assert!(
        (o.result.heat - want.heat).abs() <= 10.0 * tol * e_ref,
        "{label}: H = {:e}, exact {:e}",
        o.result.heat,
        want.heat
    );
    assert!(
        (o.result.heat_sliding - want.heat_sliding).abs() <= 10.0 * tol * e_ref,
        "{label}: H_sfr = {:e}, exact {:e}",
        o.result.heat_sliding,
        want.heat_sliding
    );
    assert!(
        o.result.heat >= -10.0 * tol * e_ref,
        "{label}: H = {:e} < 0",
        o.result.heat
    );
    assert!(
        o.result.heat_sliding >= -10.0 * tol * e_ref,
        "{label}: H_sfr < 0"
    );
    assert!(
        o.result.s_out >= 0.0,
        "{label}: S_out = {:e} < 0",
        o.result.s_out
    );
    assert!(
        (o.result.s_out - want.slip).abs() <= 10.0 * tol * v,
        "{label}: S_out = {:e}, exact {:e}",
        o.result.s_out,
        want.slip
    );
    // Tangential impulse J (scalar, >= 0) to the same scaled accuracy (impulse m v_ref).
    assert!(o.result.tangential_impulse >= 0.0);
    assert!(
        (o.result.tangential_impulse - want.j).abs() <= 10.0 * tol * ex.m * v,
        "{label}: J = {:e}, exact {:e}",
        o.result.tangential_impulse,
        want.j
    );
    // theta: null exactly when S(0) = 0, never NaN, in (-pi, pi].
    match o.result.theta {
        None => assert_eq!(ex.s0, 0.0, "{label}: theta null with S(0) > 0"),
        Some(t) => {
            assert!(ex.s0 > 0.0, "{label}: theta {t} with S(0) = 0");
            assert!(t.is_finite() && t > -PI && t <= PI, "{label}: theta = {t}");
            // The direction of e0 (an angle differs from it by a multiple of 2 pi).
            let d = (t.cos() - ex.e[0]).abs().max((t.sin() - ex.e[1]).abs());
            assert!(d <= 4e-16, "{label}: theta {t} vs e0 {:?}", ex.e);
        }
    }
    // No friction in a random direction: the tangential velocity change is along -e0,
    // and no larger than the stick rule allows (J <= m S(0) / (2 (1 + 1/alpha))).
    let dv = (
        o.result.out.u_cm.y - ex.incoming.u_cm.y,
        o.result.out.u_cm.z - ex.incoming.u_cm.z,
    );
    let across = (dv.0 * ex.e[1] - dv.1 * ex.e[0]).abs();
    let along = -(dv.0 * ex.e[0] + dv.1 * ex.e[1]);
    let dv_norm = dv.0.hypot(dv.1);
    // Round-off of the difference out - in of velocities of size |V|, |W|.
    let rounding = 4.0 * f64::EPSILON * (ex.incoming.u_cm.yz().amax() + dv_norm);
    assert!(
        across <= DIRECTION_TOL * dv_norm + rounding + 1e-300,
        "{label}: tangential change {dv:?} not along e0 = {:?}",
        ex.e
    );
    if ex.s0 == 0.0 || ex.mu == 0.0 {
        assert_eq!(dv_norm, 0.0, "{label}: friction acted without slip: {dv:?}");
    } else {
        let j_max = ex.s0 / ex.k();
        assert!(along >= 0.0, "{label}: friction along +e0");
        assert!(
            along * ex.m <= j_max * (1.0 + 1e-9) + 10.0 * tol * ex.m * v,
            "{label}: J = {:e} beyond the stick bound {j_max:e}",
            along * ex.m
        );
    }
    // Sticking and the event (docs/formats.md).
    if ex.p > 0.0 && ex.s0 == 0.0 && ex.mu > 0.0 {
        assert!(o.result.sticks, "{label}: S(0) = 0 must stick");
        assert_eq!(o.stick_time, Some(0.0), "{label}");
        assert_eq!(o.result.stick_impulse, Some(0.0), "{label}");
        return;
    }
    if x.sticks_decided {
        assert_eq!(o.result.sticks, ex.sticks(), "{label}: sticks");
    }
    if o.result.sticks {
        let t = o.stick_time.expect("stick time when sticking");
        assert!((0.0..=tau).contains(&t), "{label}: stick time {t:e}");
        let p_at = ex.p * (x.phi)(t / tau);
        assert!(
            (p_at - ex.p_stick).abs() <= EVENT_IMPULSE_TOL * ex.p,
            "{label}: p(t_stick) = {p_at:e}, p_stick = {:e}",
            ex.p_stick
        );
        let p_rep = o.result.stick_impulse.expect("stick impulse when sticking");
        assert!(
            (p_rep - ex.p_stick).abs() <= EVENT_IMPULSE_TOL * ex.p,
            "{label}: stick_impulse {p_rep:e} vs {:e}",
            ex.p_stick
        );
    } else {
        assert_eq!(o.stick_time, None, "{label}");
    }
}

// The one copy of the nodes: tests/common/mod.rs's.
pub use first_principles::gauss_legendre;

/// Composite Gauss-Legendre quadrature of `f` over [a, b].
pub fn quad(f: &dyn Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let nodes = gauss_legendre(20);
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for i in 0..panels {
        let lo = a + h * i as f64;
        for &(x, w) in &nodes {
            sum += 0.5 * h * w * f(lo + 0.5 * h * (1.0 + x));
        }
    }
    sum
}

/// Phi(s) of sin^n(pi s) by quadrature, independent of the library's incomplete Beta
/// function: x = y^2 near 0 and x = 1 - y^2 near 1 make the integrand smooth at the ends.
pub fn sine_power_phi(n: f64, s: f64) -> f64 {
    let raw = |s: f64| -> f64 {
        let s = s.clamp(0.0, 1.0);
        let rise = |y: f64| (PI * y * y).sin().max(0.0).powf(n) * 2.0 * y;
        let fall = |y: f64| (PI * y * y).sin().max(0.0).powf(n) * 2.0 * y; // x = 1 - y^2
        let a = s.min(0.5);
        let mut v = quad(&rise, 0.0, a.sqrt(), 40);
        if s > 0.5 {
            v += quad(&fall, (1.0 - s).sqrt(), 0.5f64.sqrt(), 40);
        }
        v
    };
    raw(s) / raw(1.0)
}

/// Phi(s) of a linearly interpolated (time, force) table, its time axis mapped to [0, 1]:
/// exact trapezoids (and the quadratic inside a segment).
pub fn table_phi(points: &[(f64, f64)], s: f64) -> f64 {
    let span = points.last().unwrap().0;
    let t = s.clamp(0.0, 1.0) * span;
    let (mut total, mut upto) = (0.0, 0.0);
    for w in points.windows(2) {
        let ((t0, f0), (t1, f1)) = (w[0], w[1]);
        total += 0.5 * (t1 - t0) * (f0 + f1);
        if t > t0 {
            let h = t.min(t1) - t0;
            let slope = (f1 - f0) / (t1 - t0);
            upto += h * (f0 + 0.5 * slope * h);
        }
    }
    upto / total
}
