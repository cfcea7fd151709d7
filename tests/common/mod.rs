//! Independent references shared by the integration tests.
//!
//! No expected value here comes from the code under test: the collision is resolved from
//! first principles (contact-point velocities, Coulomb friction opposing the slip, r x F
//! torques), in any frame, the force profiles' cumulative impulses are computed by their own
//! formulas or quadratures, a ball's roll-out on the cloth follows its physics (`table`), and
//! a scene file is read with a scene file is read with `toml`, not through the crate's scene code (`scene_file`). The
//! parts that use the crate are `collision`, which builds its input, a `Collision`, and
//! `cluster`, which sums a cluster's kinetic energy from its balls' masses and inertias. Each
//! test file uses a part of it (hence `dead_code`).
#![allow(dead_code)]

use nalgebra::Vector3;
use std::f64::consts::PI;

pub mod cluster;
pub mod collision;
pub mod compliant;
pub mod hertz_chain;
pub mod scene_file;
pub mod table;
pub mod unequal;

// ---------------------------------------------------------------------------------------
// The collision from first principles
// ---------------------------------------------------------------------------------------

/// Two identical balls: mass m (kg), radius r (m), I = alpha m r^2.
#[derive(Debug, Clone, Copy)]
pub struct Balls {
    pub m: f64,
    pub r: f64,
    pub alpha: f64,
}

/// How the normal impulse is fixed.
#[derive(Debug, Clone, Copy)]
pub enum Rule {
    /// P = (1 + e) m U(0): eq 52 (e = 1) and the family of eq 56.
    Restitution(f64),
    /// P given (eq 56: m U(0) <= P <= 2 m U(0)).
    Explicit(f64),
}

/// Contact: friction coefficient, impulse rule and the effects that change the physics.
#[derive(Debug, Clone, Copy)]
pub struct Law {
    pub mu: f64,
    pub rule: Rule,
    /// Friction between the balls at all.
    pub friction: bool,
    /// Sliding stops at S = 0 (docs/model.md#when-sliding-stops-during-contact); false: friction keeps acting along e0.
    pub stick: bool,
}

impl Law {
    pub fn new(mu: f64, rule: Rule) -> Self {
        Law {
            mu,
            rule,
            friction: true,
            stick: true,
        }
    }
}

/// Both balls in any frame: `n` the unit vector from A's centre to B's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    pub n: Vector3<f64>,
    pub va: Vector3<f64>,
    pub wa: Vector3<f64>,
    pub vb: Vector3<f64>,
    pub wb: Vector3<f64>,
}

impl Pair {
    /// The paper's centre-of-mass state: n = e_x, A moves with u, B with -u.
    pub fn cm(u: Vector3<f64>, omega_a: Vector3<f64>, omega_b: Vector3<f64>) -> Self {
        Pair {
            n: Vector3::x(),
            va: u,
            wa: omega_a,
            vb: -u,
            wb: omega_b,
        }
    }

    /// The slip of A's surface relative to B's at the contact point, tangential part.
    ///
    /// The contact point is at +r n from A's centre and -r n from B's, so the material
    /// velocities there are v_A + w_A x (r n) and v_B + w_B x (-r n); their difference,
    /// with the normal part removed, is the slip.
    pub fn slip(&self, r: f64) -> Vector3<f64> {
        let rel =
            (self.va + self.wa.cross(&(r * self.n))) - (self.vb + self.wb.cross(&(-r * self.n)));
        rel - self.n * rel.dot(&self.n)
    }

    /// Normal approach speed of the paper, U(0) = (v_A - v_B) . n / 2 (> 0: approaching).
    pub fn u0(&self) -> f64 {
        0.5 * (self.va - self.vb).dot(&self.n)
    }

    /// Reference speed (docs/model.md#scales-and-scaled-errors): max(|U(0)|, S(0), |U|, r |w_A|, r |w_B|), with
    /// U = (v_A - v_B)/2 (ball A's velocity in the centre-of-mass frame).
    pub fn v_ref(&self, r: f64) -> f64 {
        let u = 0.5 * (self.va - self.vb);
        self.u0()
            .abs()
            .max(norm(&self.slip(r)))
            .max(norm(&u))
            .max(r * norm(&self.wa))
            .max(r * norm(&self.wb))
    }

    /// Kinetic energy of both balls (J).
    pub fn kinetic_energy(&self, b: &Balls) -> f64 {
        let i = b.alpha * b.m * b.r * b.r;
        0.5 * b.m * (self.va.norm_squared() + self.vb.norm_squared())
            + 0.5 * i * (self.wa.norm_squared() + self.wb.norm_squared())
    }
}

/// The outcome of the reference.
#[derive(Debug, Clone, Copy)]
pub struct Expected {
    pub collision: bool,
    /// Normal impulse P (N s).
    pub impulse: f64,
    /// Incoming sliding speed S(0) (m/s).
    pub s0: f64,
    /// Tangential impulse J >= 0 (N s), along -slip on A.
    pub tangential: f64,
    /// Outgoing slip along the incoming slip direction (m/s), signed.
    pub s_out: f64,
    pub sticks: bool,
    /// The normal impulse at which sliding stops (or would): m S0 / (2 mu (1 + 1/alpha)).
    pub p_stick: Option<f64>,
    /// Total heat: the loss of kinetic energy (J).
    pub heat: f64,
    /// Heat of sliding friction (J).
    pub heat_sliding: f64,
    pub out: Pair,
}

/// Resolves a collision from first principles.
///
/// Impulses on A: -P n (normal) and -J t (friction, t the unit incoming slip of A relative
/// to B); B receives the opposite ones. Torque impulses about the centres: (r n) x (-J t)
/// on A and (-r n) x (J t) on B, equal (eq 11). With I = alpha m r^2 the slip then changes
/// by 2 dv_t + (dw_A + dw_B) x (r n) = -2 J t / m - 2 J ((n x t) x n) / (alpha m), and
/// (n x t) x n = t, so S = S(0) - 2 (1 + 1/alpha) J / m along the fixed t. While sliding,
/// Coulomb's law gives dJ = mu dp; the slip reaches 0 at J_stick = m S(0) / (2 (1 + 1/alpha)),
/// i.e. at p_stick = J_stick / mu, after which no tangential impulse is needed to keep it
/// zero (the normal impulse exerts no torque and does not move the slip): J = min(mu P, J_stick).
/// Without the stick rule, J = mu P. The heat of sliding is the integral of S dJ:
/// H_sfr = J S(0) - (1 + 1/alpha) J^2 / m.
pub fn resolve(b: &Balls, law: &Law, pair: &Pair) -> Expected {
    let u0 = pair.u0();
    let slip = pair.slip(b.r);
    let s0 = norm(&slip);
    let impulse = match law.rule {
        Rule::Restitution(e) if u0 > 0.0 => (1.0 + e) * b.m * u0,
        Rule::Restitution(_) => 0.0,
        Rule::Explicit(p) => {
            assert!(u0 > 0.0, "an explicit impulse needs approaching balls");
            p
        }
    };
    let collision = impulse > 0.0;
    let friction = law.friction && law.mu > 0.0 && collision;
    let slip_per_j = 2.0 * (1.0 + 1.0 / b.alpha) / b.m;
    let j_stick = s0 / slip_per_j;
    let p_stick = friction.then(|| j_stick / law.mu);
    let (tangential, sticks) = if !friction || s0 == 0.0 {
        (0.0, friction && law.stick)
    } else if law.stick && law.mu * impulse >= j_stick {
        (j_stick, true)
    } else {
        (law.mu * impulse, false)
    };
    let s_out = if sticks {
        0.0
    } else if friction {
        s0 - slip_per_j * tangential
    } else {
        s0
    };
    let t = if s0 > 0.0 {
        slip / s0
    } else {
        Vector3::zeros()
    };
    let lin = -impulse * pair.n - tangential * t;
    let inertia = b.alpha * b.m * b.r * b.r;
    let torque = (b.r * pair.n).cross(&(-tangential * t));
    let out = Pair {
        n: pair.n,
        va: pair.va + lin / b.m,
        vb: pair.vb - lin / b.m,
        wa: pair.wa + torque / inertia,
        wb: pair.wb + ((-b.r * pair.n).cross(&(tangential * t))) / inertia,
    };
    let heat = pair.kinetic_energy(b) - out.kinetic_energy(b);
    let heat_sliding = tangential * s0 - (1.0 + 1.0 / b.alpha) * tangential * tangential / b.m;
    Expected {
        collision,
        impulse,
        s0,
        tangential,
        s_out,
        sticks,
        p_stick,
        heat,
        heat_sliding,
        out,
    }
}

/// theta of eqs 5-6 for a centre-of-mass pair (n = e_x): atan2(slip_z, slip_y).
pub fn theta_cm(pair: &Pair, r: f64) -> Option<f64> {
    let s = pair.slip(r);
    (s.y != 0.0 || s.z != 0.0).then(|| s.z.atan2(s.y))
}

/// Euclidean norm without underflow or overflow of the squares (like `hypot`).
pub fn norm(v: &Vector3<f64>) -> f64 {
    let big = amax(v);
    if big == 0.0 || !big.is_finite() {
        big
    } else {
        big * (v / big).norm()
    }
}

/// Largest absolute component.
pub fn amax(v: &Vector3<f64>) -> f64 {
    v.iter().fold(0.0_f64, |a, x| a.max(x.abs()))
}

// ---------------------------------------------------------------------------------------
// Deterministic pseudo-random numbers (SplitMix64)
// ---------------------------------------------------------------------------------------

pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// Log-uniform in [lo, hi].
    pub fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }
    pub fn vector(&mut self, scale: f64) -> Vector3<f64> {
        Vector3::new(
            self.range(-scale, scale),
            self.range(-scale, scale),
            self.range(-scale, scale),
        )
    }
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

// ---------------------------------------------------------------------------------------
// Quadrature and the profiles' cumulative impulses
// ---------------------------------------------------------------------------------------

#[path = "quadrature.rs"]
mod quadrature;
pub use quadrature::gauss_legendre;

/// Composite Gauss-Legendre (16 nodes) of `f` over [a, b] in `panels` panels.
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    if a == b {
        return 0.0;
    }
    let nodes = gauss_legendre(16);
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for i in 0..panels {
        let lo = a + h * i as f64;
        let mut part = 0.0;
        for &(x, w) in &nodes {
            part += w * f(lo + 0.5 * h * (1.0 + x));
        }
        sum += 0.5 * h * part;
    }
    sum
}

/// The point in [lo, hi] where `below` turns from true (at lo) to false (at hi), by
/// bisection to round-off: it stops when the midpoint is one of the ends (or after 200
/// halvings).
pub fn bisect(mut lo: f64, mut hi: f64, below: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Inverts an increasing F on [0, 1] with F(0) = 0, F(1) = 1 by bisection to round-off.
pub fn invert(f: impl Fn(f64) -> f64, q: f64) -> f64 {
    bisect(0.0, 1.0, |s| f(s) < q)
}

/// Hunt-Crossley's restitution at x = beta v (f = k delta^(3/2) (1 + beta delta')): energy
/// along the contact gives the outgoing speed as the root y = e x in (0, 1) of
/// -y - ln(1 - y) = x - ln(1 + x) (docs/contact-law.md), found by bisection; e = y / x.
pub fn hunt_crossley_e(x: f64) -> f64 {
    let rhs = x - x.ln_1p();
    bisect(0.0, 1.0, |y| -y - (-y).ln_1p() < rhs) / x
}

/// Half-sine: p(t)/P = (1 - cos(pi t / tau))/2 (docs/model.md#the-exact-state-during-the-contact).
pub fn half_sine_fraction(s: f64) -> f64 {
    0.5 * (1.0 - (PI * s).cos())
}

/// Half-sine: the scaled time at which p = q P, (2/pi) asin(sqrt(q)) (the form that
/// keeps its digits for small q).
pub fn half_sine_time(q: f64) -> f64 {
    2.0 / PI * q.sqrt().asin()
}

/// Euler's Beta function from `libm::tgamma` (not the crate's own Beta code).
pub fn beta_fn(a: f64, b: f64) -> f64 {
    libm::tgamma(a) * libm::tgamma(b) / libm::tgamma(a + b)
}

/// sin^n pulse: p(s)/P = integral_0^s sin^n(pi x) dx / (B((n+1)/2, 1/2) / pi), by quadrature
/// in z = sqrt(x) on the rising half (smooth: sin^n(pi z^2) 2z ~ z^(2n+1)), symmetric after.
pub fn sine_power_fraction(n: f64, s: f64) -> f64 {
    let total = beta_fn(0.5 * (n + 1.0), 0.5) / PI;
    let rising = |s: f64| {
        integrate(
            |z: f64| (PI * z * z).sin().powf(n) * 2.0 * z,
            0.0,
            s.sqrt(),
            24,
        ) / total
    };
    if s <= 0.0 {
        0.0
    } else if s >= 1.0 {
        1.0
    } else if s <= 0.5 {
        rising(s)
    } else {
        1.0 - rising(1.0 - s)
    }
}

/// Hertz's elastic impact of two identical balls (Landau & Lifshitz, Theory of Elasticity,
/// section 9), written out from the textbook: effective modulus E* = E / (2 (1 - nu^2)),
/// effective radius r/2, reduced mass m/2, F = k delta^(3/2) with k = (4/3) E* sqrt(r/2);
/// energy conservation (m/2) v^2 / 2 = (2/5) k delta_max^(5/2) at the relative approach
/// speed v; contact time (4/5) B(2/5, 1/2) delta_max / v (the scaled Hertz equation's
/// 2 hertz_half() = (4/5) B(2/5, 1/2)); peak force k delta_max^(3/2); contact radius
/// sqrt((r/2) delta_max).
#[derive(Debug, Clone, Copy)]
pub struct HertzRef {
    pub duration: f64,
    pub max_compression: f64,
    pub peak_force: f64,
    pub contact_radius: f64,
}

pub fn hertz_identical(m: f64, r: f64, youngs: f64, poisson: f64, v: f64) -> HertzRef {
    let e_star = youngs / (2.0 * (1.0 - poisson * poisson));
    let radius = r / 2.0;
    let k = 4.0 / 3.0 * e_star * radius.sqrt();
    let delta = (5.0 * (m / 2.0) * v * v / (4.0 * k)).powf(2.0 / 5.0);
    HertzRef {
        duration: 4.0 / 5.0 * beta_fn(0.4, 0.5) * delta / v,
        max_compression: delta,
        peak_force: k * delta.powf(1.5),
        contact_radius: (radius * delta).sqrt(),
    }
}

/// Elastic Hertz impact, scaled (delta'' = -delta^(3/2), delta(0) = 0, delta'(0) = 1):
/// energy gives delta' = sqrt(1 - x^(5/2)) with x = delta / delta_max, delta_max = (5/4)^(2/5),
/// so t(x) = delta_max F(x), F(x) = integral_0^x dx' / sqrt(1 - x'^(5/2)), and the impulse
/// fraction (momentum change over twice the incoming momentum) is p/P = (1 - delta')/2.
/// F by quadrature: z = sqrt(x') for x <= 0.64, and x' = 1 - y^2 near the turning point,
/// where the integrand becomes 2 / sqrt(g(y)), g(y) = (1 - (1 - y^2)^(5/2)) / y^2 (smooth).
pub fn hertz_f(x: f64) -> f64 {
    hertz_f_split(x, 1.0 - x)
}

/// F(x) given both x and 1 - x (the latter to full relative accuracy near the turning point).
fn hertz_f_split(x: f64, one_minus_x: f64) -> f64 {
    let near_zero = |x: f64| {
        integrate(
            |z: f64| 2.0 * z / (1.0 - z.powi(5)).sqrt(),
            0.0,
            x.sqrt(),
            24,
        )
    };
    let near_top = |y_max: f64| {
        integrate(
            |y: f64| {
                let g = -(2.5 * (-y * y).ln_1p()).exp_m1() / (y * y);
                2.0 / g.sqrt()
            },
            0.0,
            y_max,
            24,
        )
    };
    static WHOLE: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
    let whole = *WHOLE.get_or_init(|| near_zero(0.64) + near_top(0.6));
    if x <= 0.64 {
        near_zero(x)
    } else {
        whole - near_top(one_minus_x.sqrt())
    }
}

/// F(1) = (2/5) B(2/5, 1/2): the half contact time over delta_max.
pub fn hertz_half() -> f64 {
    static HALF: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
    *HALF.get_or_init(|| hertz_f(1.0))
}

/// Hertz pulse: the scaled time s = t/tau at which p = q P. For q <= 1/2, delta' = w = 1 - 2q,
/// so x^(5/2) = 1 - w^2 = 4 q (1 - q), and 1 - x = -expm1(ln(1 - w^2) / 2.5) keeps its digits
/// near the peak; the pulse is symmetric.
pub fn hertz_time(q: f64) -> f64 {
    let rising = |q: f64| {
        let w = 1.0 - 2.0 * q;
        let x = (4.0 * q * (1.0 - q)).powf(0.4);
        let one_minus_x = -(0.4 * (-w * w).ln_1p()).exp_m1();
        hertz_f_split(x, one_minus_x) / (2.0 * hertz_half())
    };
    if q <= 0.0 {
        0.0
    } else if q >= 1.0 {
        1.0
    } else if q <= 0.5 {
        rising(q)
    } else {
        1.0 - rising(1.0 - q)
    }
}

/// A (time, force) table as docs/formats.md#tabulated-profile-csv describes it: linear between points, time axis
/// stretched to the duration, scaled to the impulse. `fraction(s)` is p/P at s = t/tau (exact
/// trapezoids and the quadratic inside a segment), `time(q)` its inverse.
pub struct Table {
    pub s: Vec<f64>,
    pub f: Vec<f64>,
    pub area: f64,
}

impl Table {
    pub fn read(path: &std::path::Path) -> Self {
        let text = std::fs::read_to_string(path).expect("profile table");
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        assert_eq!(lines.next().map(str::trim), Some("time,force"));
        let pts: Vec<(f64, f64)> = lines
            .map(|l| {
                let (t, f) = l.split_once(',').expect("two cells");
                (t.trim().parse().unwrap(), f.trim().parse().unwrap())
            })
            .collect();
        let span = pts.last().unwrap().0;
        let s: Vec<f64> = pts.iter().map(|p| p.0 / span).collect();
        let f: Vec<f64> = pts.iter().map(|p| p.1).collect();
        let area = (1..s.len())
            .map(|i| 0.5 * (s[i] - s[i - 1]) * (f[i] + f[i - 1]))
            .sum();
        Table { s, f, area }
    }

    /// p/P at scaled time s.
    pub fn fraction(&self, s: f64) -> f64 {
        let mut acc = 0.0;
        for i in 1..self.s.len() {
            let (a, b) = (self.s[i - 1], self.s[i]);
            if s >= b {
                acc += 0.5 * (b - a) * (self.f[i] + self.f[i - 1]);
            } else {
                if s > a {
                    let h = s - a;
                    let slope = (self.f[i] - self.f[i - 1]) / (b - a);
                    acc += h * (self.f[i - 1] + 0.5 * slope * h);
                }
                break;
            }
        }
        (acc / self.area).min(1.0)
    }

    /// Normalised force phi = f tau / P at scaled time s.
    pub fn shape(&self, s: f64) -> f64 {
        for i in 1..self.s.len() {
            if s <= self.s[i] {
                let x = (s - self.s[i - 1]) / (self.s[i] - self.s[i - 1]);
                return (self.f[i - 1] + x * (self.f[i] - self.f[i - 1])) / self.area;
            }
        }
        0.0
    }

    pub fn time(&self, q: f64) -> f64 {
        invert(|s| self.fraction(s), q)
    }
}
