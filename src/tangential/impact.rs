//! The compliant impact of a sphere on a plane or on another sphere (docs/tangential.md).
//!
//! State, in the contact's frame (n the unit normal from the partner towards ball 1, t1, t2
//! the tangent plane): the compression delta, its rate delta' (the approach speed), the
//! tangential velocity g_t of ball 1's centre relative to the partner's, both spins w1, w2
//! and the tangential spring's force S on ball 1. With k_n = (4/3) E* sqrt(R*),
//! k_t = 8 G* sqrt(R* delta) and the reduced mass m* = m1 m2 / (m1 + m2):
//!
//! ```text
//! F_n   = k_n delta^1.5                    m* delta'' = -F_n
//! u     = g_t - (R1 w1 + R2 w2) x n        slip of ball 1's contact point over the partner's
//! stick:  S' = -k_t u + S min(delta', 0) / (2 delta)
//! slide:  S' = (S'_stick)_perp + mu F_n' e,  e = S/|S|   (S stays on |S| = mu F_n)
//! F_t   = S capped to |F_t| <= mu F_n
//! m* g_t' = F_t,   I1 w1' = (-R1 n) x F_t,   I2 w2' = (-R2 n) x F_t
//! ```
//!
//! The plane is the partner's limit of infinite radius, mass and inertia: R* = R1, m* = m1,
//! and its spin stays 0 (I2 infinite), so its lever arm R2 never enters; the kernel carries
//! it as `Partner::Plane`, whose spin components are not stepped.
//!
//! The spring loads incrementally (dF_t = -k_t u dt) and, while the contact shrinks, its
//! force is scaled with the stiffness (F_t = -k_t xi at fixed xi): the rule of Thornton,
//! Cummins and Cleary (2011) under which the spring never creates energy. The spring slides
//! when the stick rate would carry |S| past mu F_n, and sticks again when it would bring it
//! back inside. The stepping lands on the events (the slide starting and ending, the
//! largest compression, F_n returning to 0) by halving the step to within 1e-9 of the
//! contact time.

use crate::base::beta::beta;
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::SolverSettings;
use crate::base::validate::finite;
use crate::integrator::law::damping_within_bound;
use crate::model::contact_law::{ContactLaw, Damping};
use crate::model::material::{sphere_plane_stiffness, Material};
use crate::model::params::{check_stepped_alpha, energy_in, kinetic_energy, Ball, MU_MAX};
use crate::tangential::outcome::{CompliantOutcome, CompliantTraceRow};
use crate::tangential::stepper::{next_step, step, Z};
use nalgebra::Vector3;

/// A slip below this fraction of the speed scale sets no direction for the tangent basis
/// (rounding: the velocities are known to about 1e-16 of it).
const SLIP_BASIS_FLOOR: f64 = 1e-12;

/// Most steps (accepted and rejected) of one impact.
const MAX_STEPS: u64 = 1_000_000;
/// Events are located to this fraction of Hertz's contact time.
const EVENT_FRACTION: f64 = 1e-9;
/// The first step, as a fraction of Hertz's contact time.
const FIRST_STEP_FRACTION: f64 = 1e-3;
/// The largest step, as a fraction of Hertz's contact time.
const MAX_STEP_FRACTION: f64 = 0.05;
/// Smallest normal approach, relative to the speed scale, of a contact the kernel steps:
/// approaches down to 1e-70 of it resolve in a few hundred steps, 1e-80 stalled past 1e6
/// steps (found by the `tangential` fuzz target at 1e-96 m/s with 6 mm/s of slip).
const GRAZING: f64 = 1e-40;
/// Smallest Hertz compression, relative to the effective radius, of a contact the kernel
/// steps: the cluster's bound (a pool ball at 1e-3 m/s on steel compresses 1.7e-5 of its
/// radius; alumina spheres of 2.5 mm at 1e-6 m/s 2e-8).
const MIN_COMPRESSION: f64 = 1e-8;
/// A friction coefficient below which the contact is stepped without friction. The
/// tangential impulse is at most mu P, a change of the velocities below 1e-20 of the normal
/// one's, four orders under a double's rounding (1.1e-16), so the answer is the frictionless
/// one to the last bit. Stepping it costs work that grows as mu falls (the spring's cap
/// mu F_n is the scale its error is judged on): 290 steps at 1e-20, 530 at 1e-50, and past
/// 1e6 steps at 1e-100 and below (found by the tangential target at mu = 5e-312).
pub(crate) const NEGLIGIBLE_MU: f64 = 1e-20;
/// Relaxation times of the sliding spring's direction (|S| / |rate|) in a step beyond which
/// the step starts with the spring along its rate and keeps that direction
/// ([`Contact::align`]): 2, inside DOPRI5's stability bound (3.3 step-rates on the negative
/// axis), where the step control otherwise holds the step once the turn is the fastest
/// motion. At 10 it never engaged there: the step sat at 3.4 relaxation times and shrank with
/// the cap (a heavily damped contact at 1e-10 of its contact time a step). At 2 Chung and
/// Ooi's Test 4 takes half the steps (87 instead of 183 at rtol 1e-8, 30 degrees) with the
/// same error against rtol 1e-13 (4.5e-7 of Psi_2 at rtol 1e-10 before and after).
pub(crate) const ALIGN_TURNS: f64 = 2.0;
/// Relative margin of |S| over mu F_n before a sticking step counts as having slid.
const CAP_MARGIN: f64 = 1e-10;

/// What ball 1 meets.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Partner {
    /// A plane: infinite radius, mass and inertia; its spin stays 0.
    Plane,
    /// A sphere of radius `radius` (m) and moment of inertia `inertia` (kg m^2).
    Sphere { radius: f64, inertia: f64 },
}

/// The contact's constants.
pub(crate) struct Contact {
    /// The mass of the relative motion m* = m1 m2 / (m1 + m2) (kg); m1 on a plane.
    mass: f64,
    /// Ball 1's radius R1 (m).
    radius: f64,
    /// Ball 1's moment of inertia I1 (kg m^2).
    inertia: f64,
    partner: Partner,
    mu: f64,
    /// k_n = (4/3) E* sqrt(R) (N / m^1.5).
    k_n: f64,
    /// The normal law: Hertz's k_n with its damping (none: elastic Hertz).
    law: ContactLaw,
    /// 8 G* sqrt(R) (N / m^1.5): k_t = this sqrt(delta).
    k_t0: f64,
    n: Vector3<f64>,
    t1: Vector3<f64>,
    t2: Vector3<f64>,
}

/// What the spring does over a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Stick,
    Slide,
}

impl Contact {
    /// F_n (N) in state `y`: k_n delta^1.5 with the law's damping on delta' (clipped at 0).
    fn normal_force(&self, y: &Z) -> f64 {
        self.law.force(y[0], y[1])
    }

    fn tangential_stiffness(&self, delta: f64) -> f64 {
        mindlin_stiffness(self.k_t0, delta)
    }

    pub(crate) fn spin(y: &Z) -> Vector3<f64> {
        Vector3::new(y[4], y[5], y[6])
    }

    /// The partner's spin (rad/s): 0 for a plane.
    pub(crate) fn partner_spin(y: &Z) -> Vector3<f64> {
        Vector3::new(y[9], y[10], y[11])
    }

    /// The slip u = g_t - (R1 w1 + R2 w2) x n in (t1, t2).
    fn slip(&self, y: &Z) -> [f64; 2] {
        let mut rot = self.radius * Contact::spin(y).cross(&self.n);
        if let Partner::Sphere { radius, .. } = self.partner {
            rot += radius * Contact::partner_spin(y).cross(&self.n);
        }
        [y[2] - rot.dot(&self.t1), y[3] - rot.dot(&self.t2)]
    }

    /// The force on the ball: the spring's, capped by mu F_n.
    fn applied(&self, y: &Z) -> [f64; 2] {
        capped([y[7], y[8]], self.mu * self.normal_force(y))
    }

    /// The spring's rate while it sticks.
    fn stick_rate(&self, y: &Z) -> [f64; 2] {
        let k = self.tangential_stiffness(y[0]);
        spring_stick_rate(k, self.slip(y), [y[7], y[8]], y[0], y[1])
    }

    /// The rate of the cap mu F_n.
    fn cap_rate(&self, y: &Z) -> f64 {
        if y[0] <= 0.0 {
            0.0
        } else if self.law.damping() == Damping::None {
            self.mu * 1.5 * self.k_n * y[0].sqrt() * y[1]
        } else if self.normal_force(y) > 0.0 {
            self.mu * self.law.force_rate(y[0], y[1], self.mass)
        } else {
            0.0
        }
    }

    /// A sliding spring turned onto the direction sticking would drive it (`stick_rate`)
    /// when that turn relaxes within half a step of `h` (s) or less: |rate| h >
    /// [`ALIGN_TURNS`] |S|, the rate pointing outwards (a rate against the spring unloads
    /// it through stick, never flips it). On the cap the spring's direction relaxes towards
    /// the rate's at the rate |rate| / |S|; near first touch the cap (mu F_n) is tiny, the
    /// direction the spring had is the rounding's, and the relaxation is so fast against the
    /// contact (1e14 /s at 573 m/s of slip, mu 0.02, 1 mm balls) that the stepping followed
    /// it with steps of 1e-11 of the contact time past 1e6 steps.
    fn align(&self, y: &mut Z, h: f64) -> bool {
        let s = (y[7] * y[7] + y[8] * y[8]).sqrt();
        let r = self.stick_rate(y);
        let rn = (r[0] * r[0] + r[1] * r[1]).sqrt();
        if s > 0.0 && r[0] * y[7] + r[1] * y[8] > 0.0 && rn * h > ALIGN_TURNS * s && rn.is_finite()
        {
            y[7] = s * r[0] / rn;
            y[8] = s * r[1] / rn;
            true
        } else {
            false
        }
    }

    /// Whether the spring slides in state `y`: it is on the cap and sticking would carry it
    /// past.
    fn slides(&self, y: &Z) -> bool {
        let cap = self.mu * self.normal_force(y);
        let s = (y[7] * y[7] + y[8] * y[8]).sqrt();
        if cap <= 0.0 || s <= 0.0 || s < cap * (1.0 - 1e-9) {
            return false;
        }
        spring_slides([y[7], y[8]], self.stick_rate(y), self.cap_rate(y))
    }

    /// `aligned`: a sliding spring started the step along its rate ([`Contact::align`]) and
    /// keeps that direction through the step: only its length follows the cap. Its turn
    /// towards the rate relaxes at |rate| / |S|, ten or more times a step, and an explicit
    /// step cannot follow it (1e15 /s late in a heavily damped contact whose cap fell to
    /// 1e-7 N: steps of 1e-10 of the contact time).
    fn rhs(&self, y: &Z, mode: Mode, aligned: bool) -> Z {
        let f_n = self.normal_force(y);
        let f = self.applied(y);
        let f_lab = f[0] * self.t1 + f[1] * self.t2;
        let torque = (-self.radius * self.n).cross(&f_lab);
        let partner_rate = match self.partner {
            Partner::Plane => Vector3::zeros(),
            Partner::Sphere { radius, inertia } => (-radius * self.n).cross(&f_lab) / inertia,
        };
        let mut rate = if self.mu > 0.0 {
            self.stick_rate(y)
        } else {
            [0.0, 0.0]
        };
        if mode == Mode::Slide {
            rate = spring_slide_rate(rate, [y[7], y[8]], self.cap_rate(y), aligned);
        }
        // The power the tangential force takes from the balls: -F_t.u (the force on ball 1
        // at its contact point, -F_t on the partner's, so the pair's kinetic energy changes
        // by F_t.u).
        let u = self.slip(y);
        let taken = -(f[0] * u[0] + f[1] * u[1]);
        [
            y[1],
            -f_n / self.mass,
            f[0] / self.mass,
            f[1] / self.mass,
            torque.x / self.inertia,
            torque.y / self.inertia,
            torque.z / self.inertia,
            rate[0],
            rate[1],
            partner_rate.x,
            partner_rate.y,
            partner_rate.z,
            taken,
        ]
    }

    /// Puts the spring back on the cap when it is past it, or (`sliding`: a step that slid
    /// and slides on) when it has drifted off it by the step's error.
    fn project(&self, y: &mut Z, sliding: bool) {
        let cap = self.mu * self.normal_force(y);
        let s = (y[7] * y[7] + y[8] * y[8]).sqrt();
        if (s > cap || sliding) && s > 0.0 {
            y[7] *= cap / s;
            y[8] *= cap / s;
        }
    }

    fn row(&self, t: f64, y: &Z, mode: Mode) -> CompliantTraceRow {
        let f = self.applied(y);
        let k = self.tangential_stiffness(y[0]);
        let u = self.slip(y);
        let lab = |a: [f64; 2]| a[0] * self.t1 + a[1] * self.t2;
        let xi = if k > 0.0 {
            [-f[0] / k, -f[1] / k]
        } else {
            [0.0, 0.0]
        };
        CompliantTraceRow {
            time: t,
            compression: y[0],
            normal_force: self.normal_force(y),
            tangential_force: lab(f),
            displacement: lab(xi),
            slip: lab(u),
            sliding: mode == Mode::Slide,
            relative_velocity: -y[1] * self.n + lab([y[2], y[3]]),
            spin: Contact::spin(y),
            partner_spin: Contact::partner_spin(y),
            tangential_work: y[12],
        }
    }
}

/// Mindlin's no-slip stiffness k_t = `k_t0` sqrt(delta) (N/m) at the compression `delta`
/// (m), `k_t0` = 8 G* sqrt(R*) (N/m^1.5); 0 once the balls no longer touch.
pub(crate) fn mindlin_stiffness(k_t0: f64, delta: f64) -> f64 {
    if delta > 0.0 {
        k_t0 * delta.sqrt()
    } else {
        0.0
    }
}

/// The force (N) the spring `s` (N, two components in the tangent plane) applies under
/// Coulomb's cap `cap` = mu F_n (N): `s`, scaled down onto the cap when it is past it.
pub(crate) fn capped(s: [f64; 2], cap: f64) -> [f64; 2] {
    let n = (s[0] * s[0] + s[1] * s[1]).sqrt();
    if n > cap {
        if n > 0.0 {
            [s[0] * cap / n, s[1] * cap / n]
        } else {
            [0.0, 0.0]
        }
    } else {
        s
    }
}

/// The spring's rate (N/s) while it sticks: S' = -k_t u + S min(delta', 0) / (2 delta)
/// (docs/tangential.md#the-equations), `k` = k_t (N/m), `u` the slip of ball 1's contact
/// point over the partner's (m/s), `s` the spring (N), `delta` (m) and `delta_dot` (m/s).
pub(crate) fn spring_stick_rate(
    k: f64,
    u: [f64; 2],
    s: [f64; 2],
    delta: f64,
    delta_dot: f64,
) -> [f64; 2] {
    let shrink = if delta > 0.0 && delta_dot < 0.0 {
        delta_dot / (2.0 * delta)
    } else {
        0.0
    };
    [-k * u[0] + s[0] * shrink, -k * u[1] + s[1] * shrink]
}

/// Whether a spring `s` (N) on its cap slides: sticking (its rate `stick`, N/s) would carry
/// it past the cap, whose rate is `cap_rate` (N/s): S'_stick . e > (mu F_n)', e = S / |S|.
pub(crate) fn spring_slides(s: [f64; 2], stick: [f64; 2], cap_rate: f64) -> bool {
    let n = (s[0] * s[0] + s[1] * s[1]).sqrt();
    (stick[0] * s[0] + stick[1] * s[1]) / n > cap_rate
}

/// The sliding spring's rate (N/s): the stick rate `rate` across the spring's direction e
/// plus the cap's rate `cap_rate` along it, (S'_stick - (S'_stick . e) e) + (mu F_n)' e;
/// `aligned` ([`Contact::align`]): along e only.
pub(crate) fn spring_slide_rate(
    rate: [f64; 2],
    s: [f64; 2],
    cap_rate: f64,
    aligned: bool,
) -> [f64; 2] {
    let n = (s[0] * s[0] + s[1] * s[1]).sqrt();
    let e = [s[0] / n, s[1] / n];
    let radial = rate[0] * e[0] + rate[1] * e[1];
    if aligned {
        [cap_rate * e[0], cap_rate * e[1]]
    } else {
        [
            rate[0] - radial * e[0] + cap_rate * e[0],
            rate[1] - radial * e[1] + cap_rate * e[1],
        ]
    }
}

/// A unit vector perpendicular to the unit vector `n`.
fn perpendicular(n: &Vector3<f64>) -> Vector3<f64> {
    let axis = if n.x.abs() <= n.y.abs() && n.x.abs() <= n.z.abs() {
        Vector3::x()
    } else if n.y.abs() <= n.z.abs() {
        Vector3::y()
    } else {
        Vector3::z()
    };
    n.cross(&axis).normalize()
}

pub(crate) fn finite_vector(field: &str, v: &Vector3<f64>) -> Result<(), Error> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            format!("[{}, {}, {}]", v.x, v.y, v.z),
            "three finite numbers",
        ))
    }
}

/// The friction coefficient `mu`, checked: finite, in [0, 1e6].
pub(crate) fn check_mu(mu: f64) -> Result<(), Error> {
    finite("friction.mu", mu)?;
    if !(0.0..=MU_MAX).contains(&mu) {
        return Err(Error::invalid("friction.mu", mu, "in [0, 1e6]"));
    }
    Ok(())
}

/// The unit vector along `normal`, named `field` when it is not finite or zero.
/// `accepted` says what it must be.
pub(crate) fn unit_normal(
    field: &str,
    normal: &Vector3<f64>,
    accepted: &str,
) -> Result<Vector3<f64>, Error> {
    finite_vector(field, normal)?;
    if !(normal.norm() > 0.0 && normal.norm().is_finite()) {
        return Err(Error::invalid(
            field,
            format!("[{}, {}, {}]", normal.x, normal.y, normal.z),
            accepted,
        ));
    }
    Ok(normal.normalize())
}

/// Ball 1 and its partner, as the kernel steps them.
pub(crate) struct Bodies {
    /// m* (kg).
    pub(crate) mass: f64,
    /// R1 (m).
    pub(crate) radius: f64,
    /// I1 (kg m^2).
    pub(crate) inertia: f64,
    pub(crate) partner: Partner,
    /// Hertz's k_n = (4/3) E* sqrt(R*) (N / m^1.5).
    pub(crate) k_n: f64,
    /// R* (m).
    pub(crate) effective_radius: f64,
    /// G* (Pa): 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2.
    pub(crate) g_star: f64,
    /// The factor on Mindlin's k_t (1: Mindlin).
    pub(crate) shear_factor: f64,
    /// The damping of the normal force and its coefficient (beta in s/m, gamma in s).
    pub(crate) damping: (Damping, f64),
}

/// What the stepping returns: the final state in the contact's basis and the contact's
/// scalars.
pub(crate) struct Run {
    pub(crate) y: Z,
    pub(crate) n: Vector3<f64>,
    pub(crate) t1: Vector3<f64>,
    pub(crate) t2: Vector3<f64>,
    /// Ball 1's incoming relative velocity (m/s).
    pub(crate) g_in: Vector3<f64>,
    /// |u(0)| (m/s).
    pub(crate) slip_in: f64,
    /// The outgoing slip along t1, the incoming slip's direction (m/s).
    pub(crate) slip_out: f64,
    pub(crate) contact_time: f64,
    pub(crate) max_compression: f64,
    pub(crate) max_normal_force: f64,
    pub(crate) steps: u64,
    pub(crate) rejected: u64,
    pub(crate) trace: Vec<CompliantTraceRow>,
}

impl Run {
    /// Ball 1's outgoing velocity relative to the partner's (m/s).
    pub(crate) fn g_out(&self) -> Vector3<f64> {
        -self.y[1] * self.n + self.y[2] * self.t1 + self.y[3] * self.t2
    }

    /// The outcome as ball 1 sees it, with its outgoing `velocity`, the mass `mass` of the
    /// relative motion m* (kg: the impulse on ball 1 is m* times the change of g), the
    /// normalisation `chi` = 4 G* / (mu E*) and the kinetic energies in and out (J).
    pub(crate) fn outcome(
        self,
        velocity: Vector3<f64>,
        mass: f64,
        chi: f64,
        kinetic_energy: (f64, f64),
    ) -> Result<CompliantOutcome, Error> {
        let speed = -self.g_in.dot(&self.n);
        let v_n_out = -self.y[1];
        let dg = self.g_out() - self.g_in;
        let out = CompliantOutcome {
            velocity,
            spin: Contact::spin(&self.y),
            contact_time: self.contact_time,
            normal_impulse: mass * dg.dot(&self.n),
            tangential_impulse: mass * (dg - dg.dot(&self.n) * self.n),
            max_normal_force: self.max_normal_force,
            max_compression: self.max_compression,
            incidence_angle: self.slip_in.atan2(speed),
            rebound_angle: if self.slip_in > 0.0 {
                self.slip_out.atan2(v_n_out)
            } else {
                0.0
            },
            normalised_incidence: chi * self.slip_in / speed,
            normalised_rebound: chi * self.slip_out / v_n_out,
            kinetic_energy_in: kinetic_energy.0,
            kinetic_energy_out: kinetic_energy.1,
            tangential_work: self.y[12],
            steps: self.steps,
            rejected: self.rejected,
            trace: self.trace,
        };
        for (name, x) in [
            ("velocity", out.velocity.norm()),
            ("spin", out.spin.norm()),
            ("contact_time", out.contact_time),
            ("max_normal_force", out.max_normal_force),
        ] {
            crate::base::validate::finite_output(x, || name.to_string())?;
        }
        Ok(out)
    }
}

/// Steps one impact: ball 1 arriving at the relative velocity `g` with spin `w1`, the
/// partner with spin `w2`, along the unit normal `n` (from the partner towards ball 1), with
/// Coulomb's `mu`.
pub(crate) fn run(
    b: &Bodies,
    mu: f64,
    g: Vector3<f64>,
    w1: Vector3<f64>,
    w2: Vector3<f64>,
    n: Vector3<f64>,
    settings: &SolverSettings,
) -> Result<Run, Error> {
    let (mass, radius, k_n) = (b.mass, b.effective_radius, b.k_n);
    let speed = -g.dot(&n);
    let delta_max = (5.0 * mass * speed * speed / (4.0 * k_n)).powf(0.4);
    // Hertz's contact time, (4/5) B(2/5, 1/2) delta_max / v = 2.9433 delta_max / v.
    let t_hertz = 0.8 * beta(0.4, 0.5) * delta_max / speed;
    let f_max = k_n * delta_max * delta_max.sqrt();
    if ![delta_max, t_hertz, f_max].iter().all(|x| x.is_normal()) {
        return Err(Error::invalid(
            "contact.profile.duration",
            format!("{t_hertz} s from the materials at {speed} m/s"),
            "a contact time, compression and force that are normal positive numbers",
        ));
    }

    // Hertz's theory is for a contact small against the spheres: a compression beyond the
    // effective radius (a contact radius sqrt(R delta) beyond R) is no Hertz contact. The
    // fuzz target's overrides reached E = 1e-270 Pa, a compression of 1.3e104 m, where the
    // spring's cap (1e-115 N) sat at the doubles' rounding and the stepping switched
    // between stick and slide past 1e6 steps.
    // Nor so stiff that the compression is no length at all against the spheres: below
    // MIN_COMPRESSION of the effective radius (the cluster's bound) the spring's cap sat at
    // 1e-161 N beside a compression of 2e-112 m and the stepping switched between stick and
    // slide past 1e6 steps (an override of the fuzz target).
    if delta_max < MIN_COMPRESSION * radius {
        return Err(Error::invalid(
            "contact.profile.duration",
            format!(
                "{t_hertz:e} s from the materials at {speed} m/s, with a compression of \
                 {delta_max:e} m against an effective radius of {radius:e} m"
            ),
            format!(
                "materials soft enough that Hertz's compression is at least \
                 {MIN_COMPRESSION:e} of the effective radius"
            ),
        ));
    }
    if delta_max > radius {
        return Err(Error::invalid(
            "contact.profile.duration",
            format!(
                "{t_hertz:e} s from the materials at {speed} m/s, with a compression of \
                 {delta_max:e} m against an effective radius of {radius:e} m"
            ),
            "materials stiff enough that Hertz's compression stays below the effective \
             radius (Hertz's theory is for a contact small against the spheres)",
        ));
    }

    // The tangent basis: t1 along the incoming slip when there is one.
    let mut rot0 = b.radius * w1.cross(&n);
    let mut v_ref = g.norm().max(b.radius * w1.norm());
    let mut partner_scale = 0.0;
    if let Partner::Sphere { radius: r2, .. } = b.partner {
        rot0 += r2 * w2.cross(&n);
        v_ref = v_ref.max(r2 * w2.norm());
        partner_scale = v_ref / r2;
    }
    // A grazing touch whose normal approach is below GRAZING of the speed scale changes
    // nothing to double precision (the impulses are that fraction of the momentum), and its
    // compression, ~1e-64 m at 1e-80 m/s, is too small for the stepping to follow.
    if speed < GRAZING * v_ref {
        return Err(Error::invalid(
            "incoming.velocity",
            format!("a normal approach of {speed:e} m/s at a speed scale of {v_ref:e} m/s"),
            format!(
                "a normal approach of at least {GRAZING:e} of the speed scale (a grazing touch \
                 below it changes no velocity to double precision)"
            ),
        ));
    }
    let slip0 = (g + speed * n) - rot0;
    // The basis must be orthonormal whatever the slip: the tangential part of a slip at
    // the rounding of the velocities (head on along a normal that is no axis) is rounding
    // in every direction, along n too, and normalised it was no tangent: friction along it
    // pushed along the normal, and a head-on impact on the plane of normal (1, 1, 1) / sqrt 3
    // left with restitution 1.79 at mu 1 (0.40 at mu 0.2; found by fuzzing the Python
    // package). Below SLIP_BASIS_FLOOR of the speed scale the slip sets no direction.
    let tangential = slip0 - slip0.dot(&n) * n;
    let t1 = if tangential.norm() > SLIP_BASIS_FLOOR * v_ref {
        let t = tangential.normalize();
        (t - t.dot(&n) * n).normalize()
    } else {
        perpendicular(&n)
    };
    let t2 = n.cross(&t1);
    // The two-ball law's bounds on the damping (docs/contact-law.md), at this contact's
    // approach speed and elastic contact time: far past them the contact either creeps
    // on for longer than it may last or ends at once, lost in the steps' rounding (gamma =
    // 4e67 tau_0 left the compression frozen at -9e-44 m for 1e6 steps; found by fuzzing).
    let law = ContactLaw::new(k_n, b.damping.0, b.damping.1)?;
    damping_within_bound(&law, speed, t_hertz)?;
    // Friction below NEGLIGIBLE_MU moves no velocity by more than its rounding: stepped as 0.
    let mu = if mu < NEGLIGIBLE_MU { 0.0 } else { mu };
    let c = Contact {
        mass,
        radius: b.radius,
        inertia: b.inertia,
        partner: b.partner,
        mu,
        k_n,
        law,
        k_t0: b.shear_factor * 8.0 * b.g_star * radius.sqrt(),
        n,
        t1,
        t2,
    };

    let w_scale = v_ref / b.radius;
    // The spring's force is at most mu F_n, so its scale is mu F_max (F_max when mu > 1):
    // with Hertz's F_max for a small mu its error would be judged against a force it never
    // reaches, the drift off the cap would outgrow the cap's band and every step would read
    // as a switch. Without friction it stays 0, and scale 0 leaves it out of the error norm,
    // as the plane's spin, which is not stepped.
    let s_scale = f_max * mu.min(1.0);
    let scale: Z = [
        delta_max,
        v_ref,
        v_ref,
        v_ref,
        w_scale,
        w_scale,
        w_scale,
        s_scale,
        s_scale,
        partner_scale,
        partner_scale,
        partner_scale,
        0.0,
    ];
    let (rtol, atol) = (settings.rtol(), settings.atol());
    let h_event = EVENT_FRACTION * t_hertz;
    let h_max = MAX_STEP_FRACTION * t_hertz;

    let mut y: Z = [
        0.0,
        speed,
        g.dot(&t1),
        g.dot(&t2),
        w1.x,
        w1.y,
        w1.z,
        0.0,
        0.0,
        w2.x,
        w2.y,
        w2.z,
        0.0,
    ];
    let mut t = 0.0;
    let mut h = FIRST_STEP_FRACTION * t_hertz;
    let mut mode = Mode::Stick;
    let mut trace = vec![c.row(t, &y, mode)];
    let (mut steps, mut rejected) = (0u64, 0u64);
    let mut max_compression = 0.0f64;
    let mut max_normal_force = 0.0f64;
    let contact_time = loop {
        if steps + rejected >= MAX_STEPS {
            return Err(Error::TooManySteps {
                method: Method::Dopri5,
                scaled_time: t / t_hertz,
                segment_start: 0.0,
                steps: MAX_STEPS as u32,
            });
        }
        mode = if c.slides(&y) {
            Mode::Slide
        } else {
            Mode::Stick
        };
        let aligned = mode == Mode::Slide && c.align(&mut y, h);
        let f = |z: &Z| c.rhs(z, mode, aligned);
        let (mut y_new, err) = step(&f, &y, h, &scale, rtol, atol);
        if err.is_nan() || err > 1.0 {
            rejected += 1;
            h = if err.is_finite() {
                next_step(h, err)
            } else {
                h / 10.0
            };
            continue;
        }
        // The contact ends where the law's force returns to 0 for good: delta = 0, or
        // delta + gamma delta' = 0 under Kuwabara-Kono (its separation function).
        let ended = c.law.separation(y_new[0], y_new[1]) <= 0.0;
        let turned = y[1] > 0.0 && y_new[1] <= 0.0;
        let switched = c.mu > 0.0
            && match mode {
                Mode::Stick => {
                    let s = (y_new[7] * y_new[7] + y_new[8] * y_new[8]).sqrt();
                    s > c.mu * c.normal_force(&y_new) * (1.0 + CAP_MARGIN)
                }
                // Judged on the cap, where the step's projection puts the spring: the
                // stepped |S| drifts off mu F_n by the error allowed on the spring's scale,
                // mu F_max, which late in a heavily damped contact (a cap 3e-5 of it) is
                // far outside the cap's band, and read as a stop at every step.
                Mode::Slide => {
                    let mut on_cap = y_new;
                    c.project(&mut on_cap, true);
                    !c.slides(&on_cap)
                }
            };
        if (ended || turned || switched) && h > h_event {
            rejected += 1;
            h /= 2.0;
            continue;
        }
        c.project(&mut y_new, mode == Mode::Slide && !switched);
        steps += 1;
        t += h;
        y = y_new;
        max_compression = max_compression.max(y[0]);
        max_normal_force = max_normal_force.max(c.normal_force(&y));
        if ended {
            // The zero of the separation inside the last (tiny) step, from its rate (delta';
            // the damped term's rate is gamma delta'' = -gamma F_n / m*, and F_n = 0 there),
            // within that step: at a creeping separation's delta' of 1e-16 m/s the line
            // through the end put the zero 1e7 s before the start (found by fuzzing).
            let sep = c.law.separation(y[0], y[1]);
            let end = (t - sep / y[1].min(-f64::MIN_POSITIVE)).clamp(t - h, t);
            trace.push(c.row(end, &y, mode));
            break end;
        }
        // A damped contact separating with its elastic energy spent to rtol^2 of the normal
        // approach's is over: whatever force is left can give back no more than rtol of the
        // normal momentum (a damped force is below the elastic one while the balls
        // separate, so the kinetic energy it returns is at most the stored energy), and
        // under heavy damping the separation creeps towards its zero without reaching it
        // (Kuwabara-Kono at gamma = 3e9 tau_0: 1e6 steps at a separation speed of 8e-18
        // m/s with 1e-16 of the energy stored, found by fuzzing). An elastic contact ends
        // at delta = 0 as before.
        //
        // Kuwabara-Kono bounds it tighter: while the balls separate (delta' < 0) its force
        // k sqrt(delta) (delta + gamma delta') is positive only below the separating speed
        // delta / gamma, which falls with delta, so the separating speed -delta' can still
        // grow by at most delta / gamma + delta'. At gamma = 3e9 tau_0 and rtol 1e-11 the
        // creep held 3.7e-17 of the energy, above rtol^2, for 1e6 steps, with 7.3e-17 m/s
        // (3e-17 of the approach speed) left to give (found by fuzzing; now 180 steps).
        //
        // Hunt-Crossley likewise: its force k delta^1.5 (1 + c delta') is positive only while
        // the balls separate slower than 1/c, so the separating speed can still grow by at
        // most 1/c + delta'. A steel ball of 2 mm at 0.35 m/s under c = 5.3e5 s/m (1/c = 1.9e-6
        // m/s, below rtol 1e-4 of the speed) crept apart past 500 contact times and 1e6 steps,
        // its spring's cap falling with the force (found by fuzzing).
        let stored = 0.4 * k_n * y[0].max(0.0).powf(2.5);
        let left = match c.law.damping() {
            Damping::KuwabaraKono => y[0].max(0.0) / c.law.coefficient() + y[1],
            Damping::HuntCrossley => 1.0 / c.law.coefficient() + y[1],
            Damping::None => f64::INFINITY,
        };
        if c.law.damping() != Damping::None
            && y[1] <= 0.0
            && (stored <= rtol * rtol * 0.5 * mass * speed * speed || left <= rtol * speed)
        {
            trace.push(c.row(t, &y, mode));
            break t;
        }
        trace.push(c.row(t, &y, mode));
        h = next_step(h, err).min(h_max);
    };
    Ok(Run {
        slip_out: c.slip(&y)[0],
        y,
        n,
        t1,
        t2,
        g_in: g,
        slip_in: slip0.norm(),
        contact_time,
        max_compression,
        max_normal_force,
        steps,
        rejected,
        trace,
    })
}

/// Maw, Barber and Fawcett's chi = 4 G* / (mu E*); NaN without friction.
pub(crate) fn chi(g_star: f64, e_star: f64, mu: f64) -> f64 {
    if mu > 0.0 {
        4.0 * g_star / (mu * e_star)
    } else {
        f64::NAN
    }
}

/// A `ball` of `ball_material` meeting a plane of `plane_material` (`None`: rigid) with
/// Coulomb friction `mu`, arriving with velocity `v` and spin `w` (lab frame) on the plane
/// of unit normal `normal` (out of the plane towards the ball; normalised here), resolved
/// with Hertz's normal force and Mindlin's no-slip tangential spring under Coulomb's cap
/// (docs/tangential.md). The kernel steps with its own Dormand-Prince 5(4) at
/// `settings`' rtol and atol (atol on the state over its scale: the approach speed, Hertz's
/// compression and force); `settings`' method and step count are not used.
///
/// Errors: [`Error::InvalidParameter`] naming `friction.mu` (finite, in [0, 1e6]),
/// `plane.normal` (finite, not zero), `incoming.velocity` (finite, approaching: v.n < 0),
/// `incoming.spin` (finite) or `contact.profile.duration` (a material so extreme that Hertz's
/// contact time is not a normal number); [`Error::TooManySteps`] past 1e6 steps;
/// [`Error::NonFinite`] when a result is not finite.
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::*;
/// // An aluminium-oxide sphere (R = 2.5 mm, 4000 kg/m3) at 3.9 m/s, 45 degrees, on a rigid
/// // plane with mu = 0.092: gross sliding, so the tangential speed falls by 2 mu v_n.
/// let r = 0.0025;
/// let ball = Ball::new(4000.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r, r, 0.4)?;
/// let alumina = Material::new(3.8e11, 0.23)?;
/// let v = 3.9 * Vector3::new(45f64.to_radians().sin(), -45f64.to_radians().cos(), 0.0);
/// let out = resolve_sphere_plane_compliant(
///     &ball, alumina, None, 0.092, v, Vector3::zeros(), Vector3::y(), &SolverSettings::default(),
/// )?;
/// assert!((out.velocity.y + v.y).abs() < 1e-7 * v.norm()); // elastic: e = 1
/// assert!((v.x - out.velocity.x - 2.0 * 0.092 * (-v.y)).abs() < 1e-6 * v.norm());
/// # Ok::<(), billiard_contact::Error>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn resolve_sphere_plane_compliant(
    ball: &Ball,
    ball_material: Material,
    plane_material: Option<Material>,
    mu: f64,
    v: Vector3<f64>,
    w: Vector3<f64>,
    normal: Vector3<f64>,
    settings: &SolverSettings,
) -> Result<CompliantOutcome, Error> {
    resolve_sphere_plane_compliant_damped(
        ball,
        ball_material,
        plane_material,
        (Damping::None, 0.0),
        mu,
        v,
        w,
        normal,
        settings,
    )
}

/// [`resolve_sphere_plane_compliant`] with a damped normal force: `damping` is the law and
/// its coefficient (Hunt and Crossley's beta in s/m, Kuwabara and Kono's gamma in s;
/// docs/contact-law.md), on Hertz's stiffness k_n = (4/3) E* sqrt(R) of the materials; the
/// contact ends where the force returns to zero (delta + gamma delta' = 0 under
/// Kuwabara-Kono), and Coulomb's cap follows the damped force. To reach a restitution e at
/// an approach speed, calibrate the coefficient with [`ContactLaw::calibrated`] on the
/// stiffness [`HertzContact::sphere_plane`](crate::HertzContact::sphere_plane) gives and
/// the ball's mass. `(Damping::None, 0.0)` is the elastic kernel, bit for bit.
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::*;
/// // Chung and Ooi's Test 3: an aluminium-oxide sphere at 3.9 m/s along the normal of a
/// // rigid plane, damped to a restitution of 0.6.
/// let r = 0.0025;
/// let ball = Ball::new(4000.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r, r, 0.4)?;
/// let alumina = Material::new(3.8e11, 0.23)?;
/// let k = HertzContact::sphere_plane(&ball, &alumina, None, 3.9)?.stiffness;
/// let law = ContactLaw::calibrated(k, Damping::HuntCrossley, 0.6, 3.9, ball.mass())?;
/// let v = Vector3::new(0.0, -3.9, 0.0);
/// let out = resolve_sphere_plane_compliant_damped(
///     &ball, alumina, None, (law.damping(), law.coefficient()), 0.0, v, Vector3::zeros(),
///     Vector3::y(), &SolverSettings::default(),
/// )?;
/// assert!((out.velocity.y - 0.6 * 3.9).abs() < 1e-6 * 3.9);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn resolve_sphere_plane_compliant_damped(
    ball: &Ball,
    ball_material: Material,
    plane_material: Option<Material>,
    damping: (Damping, f64),
    mu: f64,
    v: Vector3<f64>,
    w: Vector3<f64>,
    normal: Vector3<f64>,
    settings: &SolverSettings,
) -> Result<CompliantOutcome, Error> {
    check_mu(mu)?;
    check_alpha("balls.alpha", ball)?;
    let n = unit_normal(
        "plane.normal",
        &normal,
        "a non-zero vector (the plane's normal, towards the ball)",
    )?;
    finite_vector("incoming.velocity", &v)?;
    finite_vector("incoming.spin", &w)?;
    let v_n0 = v.dot(&n);
    if v_n0 >= 0.0 {
        return Err(Error::invalid(
            "incoming.velocity",
            format!("[{}, {}, {}] (v.n = {v_n0} m/s)", v.x, v.y, v.z),
            "a ball approaching the plane: v.n < 0",
        ));
    }
    let e_in = energy_in(&[(ball, &v, &w, "incoming.velocity", "incoming.spin")])?;
    let (e_star, radius, k_n) =
        sphere_plane_stiffness(ball, &ball_material, plane_material.as_ref());
    let g_star = 1.0
        / (shear_compliance(&ball_material)
            + plane_material.as_ref().map_or(0.0, shear_compliance));
    let bodies = Bodies {
        mass: ball.mass(),
        radius,
        inertia: ball.inertia(),
        partner: Partner::Plane,
        k_n,
        effective_radius: radius,
        g_star,
        shear_factor: 1.0,
        damping,
    };
    let r = run(&bodies, mu, v, w, Vector3::zeros(), n, settings)?;
    let velocity = r.g_out();
    let energy = (e_in, kinetic_energy(ball, &velocity, &Contact::spin(&r.y)));
    r.outcome(velocity, ball.mass(), chi(g_star, e_star, mu), energy)
}

/// Refuses a ball whose alpha is below [`crate::model::params::STEPPED_ALPHA_MIN`], naming
/// `field`.
pub(crate) fn check_alpha(field: &str, ball: &Ball) -> Result<(), Error> {
    check_stepped_alpha(
        field,
        ball,
        "in a compliant contact",
        "the tangential spring moves the ball's spin 1/alpha times faster than its velocity",
    )
}

/// The shear compliance (2 - nu) / G of a material, G = E / (2 (1 + nu)): its share of 1/G*.
pub(crate) fn shear_compliance(m: &Material) -> f64 {
    let nu = m.poisson_ratio();
    (2.0 - nu) * 2.0 * (1.0 + nu) / m.youngs_modulus()
}
