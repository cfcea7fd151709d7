//! The compliant impact of a sphere on a plane (docs/tangential.md).
//!
//! State, in the plane's frame (n the unit normal towards the ball, t1, t2 the tangent
//! plane): the compression delta, its rate delta' (the approach speed), the centre's
//! tangential velocity v_t, the spin w and the tangential spring's force S. With
//! k_n = (4/3) E* sqrt(R) and k_t = 8 G* sqrt(R delta):
//!
//! ```text
//! F_n   = k_n delta^1.5                    m delta'' = -F_n
//! u     = v_t - R (w x n)                  slip of the contact point
//! stick:  S' = -k_t u + S min(delta', 0) / (2 delta)
//! slide:  S' = (S'_stick)_perp + mu F_n' e,  e = S/|S|   (S stays on |S| = mu F_n)
//! F_t   = S capped to |F_t| <= mu F_n      m v_t' = F_t,   I w' = (-R n) x F_t
//! ```
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
use crate::model::material::{sphere_plane_stiffness, Material};
use crate::model::params::{Ball, MU_MAX};
use crate::tangential::outcome::{CompliantOutcome, CompliantTraceRow};
use crate::tangential::stepper::{next_step, step, Z};
use nalgebra::Vector3;

/// Most steps (accepted and rejected) of one impact.
const MAX_STEPS: u64 = 1_000_000;
/// Events are located to this fraction of Hertz's contact time.
const EVENT_FRACTION: f64 = 1e-9;
/// The first step, as a fraction of Hertz's contact time.
const FIRST_STEP_FRACTION: f64 = 1e-3;
/// The largest step, as a fraction of Hertz's contact time.
const MAX_STEP_FRACTION: f64 = 0.05;
/// Relative margin of |S| over mu F_n before a sticking step counts as having slid.
const CAP_MARGIN: f64 = 1e-10;

/// The contact's constants.
struct Contact {
    mass: f64,
    radius: f64,
    inertia: f64,
    mu: f64,
    /// k_n = (4/3) E* sqrt(R) (N / m^1.5).
    k_n: f64,
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
    fn normal_force(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            self.k_n * delta * delta.sqrt()
        } else {
            0.0
        }
    }

    fn tangential_stiffness(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            self.k_t0 * delta.sqrt()
        } else {
            0.0
        }
    }

    fn spin(y: &Z) -> Vector3<f64> {
        Vector3::new(y[4], y[5], y[6])
    }

    /// The slip u = v_t - R (w x n) in (t1, t2).
    fn slip(&self, y: &Z) -> [f64; 2] {
        let rot = self.radius * Contact::spin(y).cross(&self.n);
        [y[2] - rot.dot(&self.t1), y[3] - rot.dot(&self.t2)]
    }

    /// The force on the ball: the spring's, capped by mu F_n.
    fn applied(&self, y: &Z) -> [f64; 2] {
        let cap = self.mu * self.normal_force(y[0]);
        let s = (y[7] * y[7] + y[8] * y[8]).sqrt();
        if s > cap {
            if s > 0.0 {
                [y[7] * cap / s, y[8] * cap / s]
            } else {
                [0.0, 0.0]
            }
        } else {
            [y[7], y[8]]
        }
    }

    /// The spring's rate while it sticks.
    fn stick_rate(&self, y: &Z) -> [f64; 2] {
        let k = self.tangential_stiffness(y[0]);
        let u = self.slip(y);
        let shrink = if y[0] > 0.0 && y[1] < 0.0 {
            y[1] / (2.0 * y[0])
        } else {
            0.0
        };
        [-k * u[0] + y[7] * shrink, -k * u[1] + y[8] * shrink]
    }

    /// The rate of the cap mu F_n.
    fn cap_rate(&self, y: &Z) -> f64 {
        if y[0] > 0.0 {
            self.mu * 1.5 * self.k_n * y[0].sqrt() * y[1]
        } else {
            0.0
        }
    }

    /// Whether the spring slides in state `y`: it is on the cap and sticking would carry it
    /// past.
    fn slides(&self, y: &Z) -> bool {
        let cap = self.mu * self.normal_force(y[0]);
        let s = (y[7] * y[7] + y[8] * y[8]).sqrt();
        if cap <= 0.0 || s <= 0.0 || s < cap * (1.0 - 1e-9) {
            return false;
        }
        let r = self.stick_rate(y);
        (r[0] * y[7] + r[1] * y[8]) / s > self.cap_rate(y)
    }

    fn rhs(&self, y: &Z, mode: Mode) -> Z {
        let f_n = self.normal_force(y[0]);
        let f = self.applied(y);
        let f_lab = f[0] * self.t1 + f[1] * self.t2;
        let torque = (-self.radius * self.n).cross(&f_lab);
        let mut rate = if self.mu > 0.0 {
            self.stick_rate(y)
        } else {
            [0.0, 0.0]
        };
        if mode == Mode::Slide {
            let s = (y[7] * y[7] + y[8] * y[8]).sqrt();
            let e = [y[7] / s, y[8] / s];
            let radial = rate[0] * e[0] + rate[1] * e[1];
            let cap_rate = self.cap_rate(y);
            rate = [
                rate[0] - radial * e[0] + cap_rate * e[0],
                rate[1] - radial * e[1] + cap_rate * e[1],
            ];
        }
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
        ]
    }

    /// Puts the spring back on the cap when it is past it, or (`sliding`: a step that slid
    /// and slides on) when it has drifted off it by the step's error.
    fn project(&self, y: &mut Z, sliding: bool) {
        let cap = self.mu * self.normal_force(y[0]);
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
            normal_force: self.normal_force(y[0]),
            tangential_force: lab(f),
            displacement: lab(xi),
            slip: lab(u),
            sliding: mode == Mode::Slide,
        }
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

fn finite_vector(field: &str, v: &Vector3<f64>) -> Result<(), Error> {
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
    finite("friction.mu", mu)?;
    if !(0.0..=MU_MAX).contains(&mu) {
        return Err(Error::invalid("friction.mu", mu, "in [0, 1e6]"));
    }
    finite_vector("plane.normal", &normal)?;
    if !(normal.norm() > 0.0 && normal.norm().is_finite()) {
        return Err(Error::invalid(
            "plane.normal",
            format!("[{}, {}, {}]", normal.x, normal.y, normal.z),
            "a non-zero vector (the plane's normal, towards the ball)",
        ));
    }
    let n = normal.normalize();
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

    let (e_star, radius, k_n) =
        sphere_plane_stiffness(ball, &ball_material, plane_material.as_ref());
    let g_star = 1.0
        / (shear_compliance(&ball_material)
            + plane_material.as_ref().map_or(0.0, shear_compliance));
    let mass = ball.mass();
    let speed = -v_n0;
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

    // The tangent basis: t1 along the incoming slip when there is one.
    let slip0 = (v - v_n0 * n) - radius * w.cross(&n);
    let t1 = if slip0.norm() > 1e-300 {
        (slip0 - slip0.dot(&n) * n).normalize()
    } else {
        perpendicular(&n)
    };
    let t2 = n.cross(&t1);
    let c = Contact {
        mass,
        radius,
        inertia: ball.inertia(),
        mu,
        k_n,
        k_t0: 8.0 * g_star * radius.sqrt(),
        n,
        t1,
        t2,
    };

    let v_ref = v.norm().max(radius * w.norm());
    let scale: Z = [
        delta_max,
        v_ref,
        v_ref,
        v_ref,
        v_ref / radius,
        v_ref / radius,
        v_ref / radius,
        f_max,
        f_max,
    ];
    let (rtol, atol) = (settings.rtol(), settings.atol());
    let h_event = EVENT_FRACTION * t_hertz;
    let h_max = MAX_STEP_FRACTION * t_hertz;

    let mut y: Z = [0.0, speed, v.dot(&t1), v.dot(&t2), w.x, w.y, w.z, 0.0, 0.0];
    let mut t = 0.0;
    let mut h = FIRST_STEP_FRACTION * t_hertz;
    let mut mode = Mode::Stick;
    let mut trace = vec![c.row(t, &y, mode)];
    let (mut steps, mut rejected) = (0u64, 0u64);
    let mut max_compression = 0.0f64;
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
        let f = |z: &Z| c.rhs(z, mode);
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
        let ended = y_new[0] <= 0.0;
        let turned = y[1] > 0.0 && y_new[1] <= 0.0;
        let switched = c.mu > 0.0
            && match mode {
                Mode::Stick => {
                    let s = (y_new[7] * y_new[7] + y_new[8] * y_new[8]).sqrt();
                    s > c.mu * c.normal_force(y_new[0]) * (1.0 + CAP_MARGIN)
                }
                Mode::Slide => !c.slides(&y_new),
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
        if ended {
            // The zero of delta inside the last (tiny) step, from its rate.
            let end = t - y[0] / y[1].min(-f64::MIN_POSITIVE);
            trace.push(c.row(end, &y, mode));
            break end;
        }
        trace.push(c.row(t, &y, mode));
        h = next_step(h, err).min(h_max);
    };

    let velocity = -y[1] * n + y[2] * t1 + y[3] * t2;
    let spin = Contact::spin(&y);
    let slip_out = c.slip(&y);
    let (u0, u_out_s) = (slip0.norm(), slip_out[0]);
    let v_n_out = -y[1];
    let chi = if mu > 0.0 {
        4.0 * g_star / (mu * e_star)
    } else {
        f64::NAN
    };
    let energy = |v: &Vector3<f64>, w: &Vector3<f64>| {
        0.5 * mass * v.norm_squared() + 0.5 * ball.inertia() * w.norm_squared()
    };
    let out = CompliantOutcome {
        velocity,
        spin,
        contact_time,
        normal_impulse: mass * (velocity - v).dot(&n),
        tangential_impulse: mass * ((velocity - v) - (velocity - v).dot(&n) * n),
        max_normal_force: c.normal_force(max_compression),
        max_compression,
        incidence_angle: u0.atan2(speed),
        rebound_angle: if u0 > 0.0 {
            u_out_s.atan2(v_n_out)
        } else {
            0.0
        },
        normalised_incidence: chi * u0 / speed,
        normalised_rebound: chi * u_out_s / v_n_out,
        kinetic_energy_in: energy(&v, &w),
        kinetic_energy_out: energy(&velocity, &spin),
        steps,
        rejected,
        trace,
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

/// The shear compliance (2 - nu) / G of a material, G = E / (2 (1 + nu)): its share of 1/G*.
fn shear_compliance(m: &Material) -> f64 {
    let nu = m.poisson_ratio();
    (2.0 - nu) * 2.0 * (1.0 + nu) / m.youngs_modulus()
}
