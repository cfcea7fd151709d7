//! The table phase (effect `table`): what each ball does on the cloth after the balls
//! separate, the paper's last section ("Complications associated with the table") worked
//! out.
//!
//! Lab frame, n = unit `up`, ball of mass m, radius r, inertia alpha m r^2, centre x,
//! velocity v, spin w. The contact point with the cloth is x - r n and its velocity is
//! v + w x (-r n); its horizontal part is the slip
//!
//! ```text
//! u = v_h - r (w x n)          (v_h = v - (v.n) n)
//! ```
//!
//! The ball-ball contact takes O(tau); the cloth's impulse during it is O(tau) too and is
//! neglected (paper, and ERRATA.md slip 2), so the phase starts from the outgoing lab motions.
//! For each ball, at t = 0 at the separation point:
//!
//! 1. **Flight.** v.n > 0: the ball leaves the cloth, flies under gravity (a = -g n, spin
//!    unchanged) and lands after t_hop = 2 (v.n) / g, having risen h = (v.n)^2 / (2 g).
//! 2. **Impact with the cloth** (at once for v.n <= 0, on landing otherwise), impulsive,
//!    applied at the contact point:
//!    ```text
//!    P_n = (1 + e_t) m |v.n|                         normal impulse (0 when v.n >= 0)
//!    J_t = min(mu_t P_n, m |u| / (1 + 1/alpha))       Coulomb, with the one-body stick rule
//!    v'  = v + (P_n n - J_t u/|u|) / m
//!    w'  = w + r J_t (n x u/|u|) / (alpha m r^2)
//!    u'  = u (1 - J_t (1 + 1/alpha) / (m |u|))        (the slip keeps its direction)
//!    ```
//!    With e_t > 0 the ball bounces (flight of 2 e_t |v.n| / g, impact again) until its
//!    vertical speed after an impact falls below [`SETTLE_SPEED`], then it is settled.
//! 3. **Sliding until rolling.** On the cloth the normal force is m g and friction
//!    -mu_t m g u/|u| acts at the contact point:
//!    ```text
//!    dv/dt = -mu_t g u/|u|,   dw/dt = mu_t g (n x u/|u|) / (alpha r),
//!    du/dt = -mu_t g (1 + 1/alpha) u/|u|
//!    ```
//!    so u keeps its direction and its length falls at the constant rate
//!    mu_t g (1 + 1/alpha): the ball rolls after t_slide = |u| / (mu_t g (1 + 1/alpha))
//!    (2 |u| / (7 mu_t g) for a solid ball) on a parabolic path. The angular momentum about
//!    the contact point, alpha m r^2 w + m r n x v, has a constant horizontal part through
//!    flights, impacts and sliding (every cloth force acts at the contact point, gravity
//!    along n), so the rolling velocity is
//!    ```text
//!    v_roll = (v_h + alpha r w x n) / (1 + alpha)      = 5/7 v_h + 2/7 r w x n (solid ball)
//!    ```
//!    whatever mu_t and e_t: the basis of the 30-degree rule.
//!
//! Optional, off by default: rolling resistance mu_r (a rolling ball decelerates at
//! mu_r g along its velocity and stays rolling, until rest) and spin decay about the
//! vertical mu_sp (on the cloth a torque mu_sp m g r opposes the spin about n, so
//! |w.n| falls at mu_sp g / (alpha r) until 0). Neither acts in flight; rolling
//! resistance does not act while sliding (sliding friction dominates).
//!
//! Energy E = m |v|^2 / 2 + alpha m r^2 |w|^2 / 2 + m g (x.n - h_table - r) never increases;
//! the balls' later paths are independent (a second collision between them is not
//! modelled).

use crate::error::{finite, Error};
use crate::model::params::Ball;
use crate::model::state::LabBall;
use nalgebra::Vector3;
use serde::Serialize;

/// Vertical speed (m/s) below which a bouncing ball counts as settled on the cloth.
pub const SETTLE_SPEED: f64 = 1e-3;
/// Most bounces one ball may make before the run is refused as unphysical.
pub const MAX_BOUNCES: u32 = 10_000;
/// Relative tolerance (of 2r) on the line of centres being horizontal and on the ball
/// centres' height r above the cloth.
pub const LEVEL_TOLERANCE: f64 = 1e-9;

/// Parameters of the cloth (`[table]` in scene files).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TableParams {
    /// Ball-cloth sliding friction mu_t (dimensionless), > 0.
    pub mu: f64,
    /// Ball-cloth restitution e_t in [0, 1): 0 is the paper's idealisation (no bounce).
    pub restitution: f64,
    /// Gravitational acceleration g (m/s^2), > 0.
    pub g: f64,
    /// Rolling resistance mu_r >= 0 (dimensionless): a rolling ball decelerates at mu_r g.
    pub rolling_resistance: f64,
    /// Spin decay about the vertical mu_sp >= 0 (dimensionless): on the cloth |w.n|
    /// falls at mu_sp g / (alpha r).
    pub spin_decay: f64,
    /// Height of the cloth along `up` (m): points p of the cloth have p.up = height.
    /// `None`: the plane r below the balls' centres at contact.
    pub height: Option<f64>,
}

impl Default for TableParams {
    /// mu = 0.2, restitution = 0, g = 9.81, no rolling resistance, no spin decay, the
    /// plane under the balls.
    fn default() -> Self {
        TableParams {
            mu: 0.2,
            restitution: 0.0,
            g: 9.81,
            rolling_resistance: 0.0,
            spin_decay: 0.0,
            height: None,
        }
    }
}

impl TableParams {
    /// Validated parameters (see the fields for the accepted ranges).
    ///
    /// ```
    /// use billiard_contact::table_phase::TableParams;
    /// let p = TableParams::new(0.2, 0.0, 9.81, 0.0, 0.0, None).unwrap();
    /// assert_eq!(p, TableParams::default());
    /// assert!(TableParams::new(0.2, 1.0, 9.81, 0.0, 0.0, None).is_err()); // bounces forever
    /// ```
    pub fn new(
        mu: f64,
        restitution: f64,
        g: f64,
        rolling_resistance: f64,
        spin_decay: f64,
        height: Option<f64>,
    ) -> Result<Self, Error> {
        finite("table.mu", mu)?;
        if mu <= 0.0 {
            return Err(Error::invalid(
                "table.mu",
                mu,
                "> 0 (on a frictionless cloth a sliding ball never starts to roll)",
            ));
        }
        finite("table.restitution", restitution)?;
        if !(0.0..1.0).contains(&restitution) {
            return Err(Error::invalid(
                "table.restitution",
                restitution,
                "in [0, 1) (1 would bounce forever)",
            ));
        }
        finite("table.g", g)?;
        if g <= 0.0 {
            return Err(Error::invalid("table.g", g, "> 0 m/s^2"));
        }
        for (name, v) in [
            ("table.rolling_resistance", rolling_resistance),
            ("table.spin_decay", spin_decay),
        ] {
            finite(name, v)?;
            if v < 0.0 {
                return Err(Error::invalid(name, v, ">= 0 (0: off)"));
            }
        }
        if let Some(h) = height {
            finite("table.height", h)?;
        }
        Ok(TableParams {
            mu,
            restitution,
            g,
            rolling_resistance,
            spin_decay,
            height,
        })
    }
}

/// The cloth under a collision: parameters, `up` and the plane's height, validated
/// against the balls' positions at contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Table {
    /// Parameters.
    pub params: TableParams,
    /// Unit vector away from the cloth.
    pub up: Vector3<f64>,
    /// Height of the cloth along `up` (m).
    pub height: f64,
}

impl Table {
    /// The cloth under balls of radius `radius` (m) touching at `pos_a`, `pos_b` (lab):
    /// the line of centres must be horizontal (perpendicular to `up`) and, when the
    /// parameters give a height, both centres must be r above it.
    pub fn new(
        params: TableParams,
        up: Vector3<f64>,
        pos_a: Vector3<f64>,
        pos_b: Vector3<f64>,
        radius: f64,
    ) -> Result<Self, Error> {
        let norm = up.norm();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(Error::invalid(
                "incoming.lab.up",
                format!("[{}, {}, {}]", up.x, up.y, up.z),
                "a non-zero direction",
            ));
        }
        let n = up / norm;
        let tol = LEVEL_TOLERANCE * 2.0 * radius;
        let rise = (pos_b - pos_a).dot(&n);
        if rise.abs() > tol {
            return Err(Error::invalid(
                "incoming.lab.b.position",
                format!(
                    "[{}, {}, {}] ((p_B - p_A).up = {rise:e} m)",
                    pos_b.x, pos_b.y, pos_b.z
                ),
                "a horizontal line of centres for the table effect: both balls on the cloth, \
                 (p_B - p_A) perpendicular to up",
            ));
        }
        let height = match params.height {
            None => pos_a.dot(&n) - radius,
            Some(h) => {
                for (field, p) in [
                    ("incoming.lab.a.position", pos_a),
                    ("incoming.lab.b.position", pos_b),
                ] {
                    let above = p.dot(&n) - h;
                    if (above - radius).abs() > tol {
                        return Err(Error::invalid(
                            field,
                            format!("[{}, {}, {}] (centre {above} m above the cloth)", p.x, p.y, p.z),
                            format!(
                                "the centre r = {radius} m above the cloth (table.height = {h} m along up) \
                                 for the table effect"
                            ),
                        ));
                    }
                }
                h
            }
        };
        Ok(Table {
            params,
            up: n,
            height,
        })
    }

    /// Gravitational potential energy (J) of a ball centred at `position`, zero on the
    /// cloth: m g (x.n - height - r).
    pub fn potential_energy(&self, ball: &Ball, position: &Vector3<f64>) -> f64 {
        ball.mass * self.params.g * (position.dot(&self.up) - self.height - ball.radius)
    }
}

/// Kinetic energy (J) of one ball.
pub fn kinetic_energy(ball: &Ball, velocity: &Vector3<f64>, spin: &Vector3<f64>) -> f64 {
    0.5 * ball.mass * velocity.norm_squared() + 0.5 * ball.inertia() * spin.norm_squared()
}

/// The horizontal slip u = v_h - r (w x n) of the contact point with the cloth (m/s).
pub fn cloth_slip(
    ball: &Ball,
    up: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> Vector3<f64> {
    let vh = crate::model::frame::horizontal(velocity, up);
    vh - ball.radius * spin.cross(up)
}

/// The rolling velocity (v_h + alpha r w x n) / (1 + alpha) (m/s) a ball reaches on the
/// cloth: 5/7 v_h + 2/7 r w x n for a solid ball.
///
/// ```
/// use billiard_contact::{table_phase::rolling_velocity, Ball};
/// use nalgebra::Vector3;
/// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
/// // A stun ball (no spin) ends rolling at 5/7 of its speed.
/// let v = rolling_velocity(&ball, &Vector3::z(), &Vector3::new(1.4, 0.0, 0.0), &Vector3::zeros());
/// assert!((v - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
/// ```
pub fn rolling_velocity(
    ball: &Ball,
    up: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> Vector3<f64> {
    let a = ball.alpha;
    let vh = crate::model::frame::horizontal(velocity, up);
    (vh + a * ball.radius * spin.cross(up)) / (1.0 + a)
}

/// One impact with the cloth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClothImpact {
    /// When it happens (s after separation).
    pub time: f64,
    /// Velocity after it (m/s, lab).
    pub velocity: Vector3<f64>,
    /// Spin after it (rad/s, lab).
    pub spin: Vector3<f64>,
    /// Normal impulse (1 + e_t) m |v.n| (N s), along +n.
    pub normal_impulse: f64,
    /// Tangential impulse J_t >= 0 (N s), along -u/|u|.
    pub tangential_impulse: f64,
    /// Whether the impact stopped the slip (the stick rule bounded J_t).
    pub sticks: bool,
    /// Slip u of the contact point before it (m/s, lab, horizontal).
    pub slip_before: Vector3<f64>,
}

/// The impact of a ball with velocity `velocity` and spin `spin` on the cloth, at `time`
/// (module docs, step 2). A ball not moving down gets zero impulses.
pub fn cloth_impact(
    ball: &Ball,
    params: &TableParams,
    up: &Vector3<f64>,
    time: f64,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> ClothImpact {
    let m = ball.mass;
    let vn = velocity.dot(up);
    let normal = if vn < 0.0 {
        (1.0 + params.restitution) * m * -vn
    } else {
        0.0
    };
    let u = cloth_slip(ball, up, velocity, spin);
    let s = u.norm();
    let stop = m * s / (1.0 + 1.0 / ball.alpha);
    let coulomb = params.mu * normal;
    let (jt, sticks) = if s == 0.0 {
        (0.0, normal > 0.0)
    } else if coulomb >= stop {
        (stop, true)
    } else {
        (coulomb, false)
    };
    let mut v = *velocity + up * (normal / m);
    let mut w = *spin;
    if jt > 0.0 {
        let dir = u / s;
        v -= dir * (jt / m);
        w += up.cross(&dir) * (ball.radius * jt / ball.inertia());
    }
    if sticks && s > 0.0 {
        // The slip is zero up to rounding: make it exactly rolling (w.n is unchanged).
        w = roll_spin(ball, up, &v, &w);
    }
    ClothImpact {
        time,
        velocity: v,
        spin: w,
        normal_impulse: normal,
        tangential_impulse: jt,
        sticks,
        slip_before: u,
    }
}

/// The spin with the horizontal part that rolls with `velocity`, n x v_h / r, and the
/// vertical part of `spin`.
fn roll_spin(
    ball: &Ball,
    up: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> Vector3<f64> {
    let vh = crate::model::frame::horizontal(velocity, up);
    up.cross(&vh) / ball.radius + up * spin.dot(up)
}

/// What a ball is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Phase {
    /// In the air (hop or bounce).
    Flight,
    /// On the cloth, the contact point slipping.
    Sliding,
    /// On the cloth, rolling without slipping.
    Rolling,
    /// At rest (spin about the vertical may still decay).
    Rest,
}

impl Phase {
    /// The name used in the path CSV.
    pub fn name(&self) -> &'static str {
        match self {
            Phase::Flight => "flight",
            Phase::Sliding => "sliding",
            Phase::Rolling => "rolling",
            Phase::Rest => "rest",
        }
    }
}

/// A stretch of motion with constant accelerations: the exact state anywhere on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// What the ball does.
    pub phase: Phase,
    /// Start time (s).
    pub t0: f64,
    /// End time (s); infinite for the last segment.
    pub t1: f64,
    /// State at `t0`.
    pub start: LabBall,
    /// Acceleration of the centre (m/s^2).
    pub accel: Vector3<f64>,
    /// Angular acceleration perpendicular to `up` (rad/s^2).
    pub spin_accel: Vector3<f64>,
    /// Rate (rad/s^2) at which |w.n| falls to 0 (spin decay about the vertical).
    pub spin_decay_rate: f64,
}

impl Segment {
    /// The state at time `t` (clamped to the segment), `up` the unit vertical.
    pub fn at(&self, up: &Vector3<f64>, t: f64) -> LabBall {
        let dt = (t.min(self.t1) - self.t0).max(0.0);
        let s = &self.start;
        let mut spin = s.spin + self.spin_accel * dt;
        if self.spin_decay_rate > 0.0 {
            let wn = s.spin.dot(up);
            let decayed = wn.signum() * (wn.abs() - self.spin_decay_rate * dt).max(0.0);
            spin += up * (decayed - wn);
        }
        LabBall {
            position: s.position + s.velocity * dt + self.accel * (0.5 * dt * dt),
            velocity: s.velocity + self.accel * dt,
            spin,
        }
    }

    /// Whether `t` lies in [t0, t1].
    pub fn contains(&self, t: f64) -> bool {
        t >= self.t0 && t <= self.t1
    }
}

/// One ball's motion on the table after separation.
#[derive(Debug, Clone, PartialEq)]
pub struct RollOut {
    /// State at separation (lab).
    pub start: LabBall,
    /// Duration of the initial hop (s): 2 v.n / g, 0 for a ball not moving up.
    pub hop_time: f64,
    /// Highest rise of the centre during the hop (m): (v.n)^2 / (2 g).
    pub hop_height: f64,
    /// Impacts with the cloth in order (the first is the reported `impact`).
    pub impacts: Vec<ClothImpact>,
    /// Times the ball left the cloth again after an impact (restitution > 0).
    pub bounces: u32,
    /// Time (s) from which the ball stays on the cloth.
    pub settle_time: f64,
    /// Duration of the slide until rolling (s), from `settle_time`.
    pub slide_time: f64,
    /// Displacement of the centre during the slide (m, lab).
    pub slide_displacement: Vector3<f64>,
    /// Time (s) at which the ball starts to roll: settle_time + slide_time.
    pub roll_time: f64,
    /// State when it starts to roll.
    pub rolling: LabBall,
    /// With rolling resistance: when (s) and where (m) the ball comes to rest.
    pub rest: Option<(f64, Vector3<f64>)>,
    /// Total impulse of the cloth on the ball up to `end_time` (N s, lab): impacts,
    /// friction, rolling resistance and the normal support while on the cloth.
    pub table_impulse: Vector3<f64>,
    /// The time the roll-out is followed to: `rest` when there is one, else `roll_time`.
    pub end_time: f64,
    /// The motion, segment by segment (the last one open-ended).
    pub segments: Vec<Segment>,
}

impl RollOut {
    /// The state at time `t` >= 0; `after` picks the state just after an impact at `t`.
    pub fn at(&self, up: &Vector3<f64>, t: f64, after: bool) -> (Phase, LabBall) {
        let seg = if after {
            self.segments.iter().rev().find(|s| s.t0 <= t)
        } else {
            self.segments.iter().find(|s| s.t1 >= t)
        }
        .unwrap_or(&self.segments[self.segments.len() - 1]);
        (seg.phase, seg.at(up, t))
    }

    /// Impact times (s): where velocity and spin jump.
    pub fn impact_times(&self) -> impl Iterator<Item = f64> + '_ {
        self.impacts.iter().map(|i| i.time)
    }
}

/// Follows one ball from separation (`start`, lab) until it rolls (and, with rolling
/// resistance, until it rests): module docs, steps 1-3.
///
/// ```
/// use billiard_contact::{table_phase::{roll_out, Table, TableParams}, Ball, LabBall};
/// use nalgebra::Vector3;
/// let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
/// let up = Vector3::z();
/// let table = Table { params: TableParams::default(), up, height: 0.0 };
/// let start = LabBall { position: Vector3::new(0.0, 0.0, 0.028575),
///                       velocity: Vector3::new(1.4, 0.0, 0.0), spin: Vector3::zeros() };
/// let r = roll_out(&ball, &table, &start).unwrap();
/// // A stun ball rolls after 2 v / (7 mu g) at 5/7 of its speed.
/// assert!((r.slide_time - 2.0 * 1.4 / (7.0 * 0.2 * 9.81)).abs() < 1e-15);
/// assert!((r.rolling.velocity.x - 1.0).abs() < 1e-14);
/// ```
pub fn roll_out(ball: &Ball, table: &Table, start: &LabBall) -> Result<RollOut, Error> {
    let n = table.up;
    let p = &table.params;
    let (m, r, g) = (ball.mass, ball.radius, p.g);
    let gravity = -n * g;
    let cloth_level = table.height + r;
    let decay_rate = p.spin_decay * g / (ball.alpha * r);
    let mut segments = Vec::new();
    let mut impacts = Vec::new();
    let mut impulse = Vector3::zeros();
    let mut state = *start;
    let mut t = 0.0;

    let fly = |state: &mut LabBall, t: &mut f64, segments: &mut Vec<Segment>| -> f64 {
        let vn = state.velocity.dot(&n);
        let dt = 2.0 * vn / g;
        let seg = Segment {
            phase: Phase::Flight,
            t0: *t,
            t1: *t + dt,
            start: *state,
            accel: gravity,
            spin_accel: Vector3::zeros(),
            spin_decay_rate: 0.0,
        };
        segments.push(seg);
        *t += dt;
        // Land exactly: back on the cloth, vertical velocity reversed.
        let mut land = seg.at(&n, *t);
        land.position += n * (cloth_level - land.position.dot(&n));
        land.velocity += n * (-vn - land.velocity.dot(&n));
        *state = land;
        dt
    };

    // 1. Flight.
    let vn0 = state.velocity.dot(&n);
    let (hop_time, hop_height) = if vn0 > 0.0 {
        let dt = fly(&mut state, &mut t, &mut segments);
        (dt, vn0 * vn0 / (2.0 * g))
    } else {
        (0.0, 0.0)
    };
    // 2. Impacts, bouncing until settled.
    let mut bounces = 0u32;
    loop {
        let imp = cloth_impact(ball, p, &n, t, &state.velocity, &state.spin);
        impacts.push(imp);
        if imp.tangential_impulse > 0.0 {
            impulse -= imp.slip_before.normalize() * imp.tangential_impulse;
        }
        impulse += n * imp.normal_impulse;
        state.velocity = imp.velocity;
        state.spin = imp.spin;
        let vn = state.velocity.dot(&n);
        if vn >= SETTLE_SPEED {
            bounces += 1;
            if bounces > MAX_BOUNCES {
                return Err(Error::invalid(
                    "table.restitution",
                    p.restitution,
                    format!("a restitution that settles within {MAX_BOUNCES} bounces"),
                ));
            }
            fly(&mut state, &mut t, &mut segments);
        } else {
            // Settled: the residual vertical speed (< SETTLE_SPEED) is absorbed by the cloth.
            impulse -= n * (m * vn);
            state.velocity -= n * vn;
            break;
        }
    }
    let settle_time = t;
    // 3. Sliding until rolling.
    let u = cloth_slip(ball, &n, &state.velocity, &state.spin);
    let s = u.norm();
    let slide_start = state.position;
    let mut slide_time = 0.0;
    if s > 0.0 {
        let dir = u / s;
        slide_time = s / (p.mu * g * (1.0 + 1.0 / ball.alpha));
        let seg = Segment {
            phase: Phase::Sliding,
            t0: t,
            t1: t + slide_time,
            start: state,
            accel: -dir * (p.mu * g),
            spin_accel: n.cross(&dir) * (p.mu * g / (ball.alpha * r)),
            spin_decay_rate: decay_rate,
        };
        segments.push(seg);
        t += slide_time;
        state = seg.at(&n, t);
        state.spin = roll_spin(ball, &n, &state.velocity, &state.spin);
        impulse += -dir * (p.mu * m * g * slide_time);
    }
    let slide_displacement = state.position - slide_start;
    let roll_time = t;
    let rolling = state;
    // Rolling (with resistance, until rest), then rest.
    let speed = state.velocity.norm();
    let mut rest = None;
    if speed > 0.0 && p.rolling_resistance > 0.0 {
        let dir = state.velocity / speed;
        let dt = speed / (p.rolling_resistance * g);
        let accel = -dir * (p.rolling_resistance * g);
        let seg = Segment {
            phase: Phase::Rolling,
            t0: t,
            t1: t + dt,
            start: state,
            accel,
            spin_accel: n.cross(&accel) / r,
            spin_decay_rate: decay_rate,
        };
        segments.push(seg);
        t += dt;
        state = seg.at(&n, t);
        state.velocity = Vector3::zeros();
        state.spin = n * state.spin.dot(&n);
        impulse += accel * (m * dt);
        rest = Some((t, state.position));
    }
    let end_time = t;
    segments.push(Segment {
        phase: if state.velocity == Vector3::zeros() {
            Phase::Rest
        } else {
            Phase::Rolling
        },
        t0: t,
        t1: f64::INFINITY,
        start: state,
        accel: Vector3::zeros(),
        spin_accel: Vector3::zeros(),
        spin_decay_rate: decay_rate,
    });
    // The cloth carries the weight while the ball is on it.
    let airborne: f64 = segments
        .iter()
        .filter(|s| s.phase == Phase::Flight)
        .map(|s| s.t1 - s.t0)
        .sum();
    impulse += n * (m * g * (end_time - airborne));
    Ok(RollOut {
        start: *start,
        hop_time,
        hop_height,
        impacts,
        bounces,
        settle_time,
        slide_time,
        slide_displacement,
        roll_time,
        rolling,
        rest,
        table_impulse: impulse,
        end_time,
        segments,
    })
}

/// Self-checks of a table phase (scaled like the contact's checks, CONTRACTS.md).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct TableChecks {
    /// Largest increase of a ball's energy (kinetic + gravitational) between consecutive
    /// evaluation points (segment ends, impacts, 16 points inside each segment), over
    /// m v_ref^2; 0 when it never increases.
    pub energy_increase: f64,
    /// Largest component of m (v_end - v_0) - (table impulse - m g n t_end) over both
    /// balls, over m v_ref: linear momentum changes only by the cloth's impulses and
    /// gravity.
    pub momentum_error: f64,
}

/// Both balls on the table.
#[derive(Debug, Clone, PartialEq)]
pub struct TableOutcome {
    /// The cloth.
    pub table: Table,
    /// Unit horizontal line of centres, A to B (lab).
    pub line: Vector3<f64>,
    /// Ball A.
    pub a: RollOut,
    /// Ball B.
    pub b: RollOut,
    /// Incoming lab velocities of A and B (before the collision), for deflections.
    pub incoming: [Vector3<f64>; 2],
    /// Self-checks.
    pub check: TableChecks,
}

impl TableOutcome {
    /// Runs the table phase for balls starting at `a`, `b` (lab, at separation) with
    /// incoming velocities `incoming` (before the collision); `speed_scale` (m/s) scales the
    /// checks.
    pub fn new(
        ball: &Ball,
        table: Table,
        a: &LabBall,
        b: &LabBall,
        incoming: [Vector3<f64>; 2],
        speed_scale: f64,
    ) -> Result<Self, Error> {
        let ra = roll_out(ball, &table, a)?;
        let rb = roll_out(ball, &table, b)?;
        let d = b.position - a.position;
        let line = crate::model::frame::horizontal(&d, &table.up).normalize();
        let mut out = TableOutcome {
            table,
            line,
            a: ra,
            b: rb,
            incoming,
            check: TableChecks::default(),
        };
        out.check = out.checks(ball, speed_scale);
        Ok(out)
    }

    /// The later of the two balls' end times (s): the path runs until both roll (or rest).
    pub fn end_time(&self) -> f64 {
        self.a.end_time.max(self.b.end_time)
    }

    /// The signed angle (degrees, counter-clockwise about up) from `from` to `to`, both
    /// projected on the cloth; `None` when either is zero there.
    pub fn angle_deg(&self, from: &Vector3<f64>, to: &Vector3<f64>) -> Option<f64> {
        let n = self.table.up;
        let f = from - n * from.dot(&n);
        let t = to - n * to.dot(&n);
        if f.norm() == 0.0 || t.norm() == 0.0 {
            return None;
        }
        Some(f.cross(&t).dot(&n).atan2(f.dot(&t)).to_degrees())
    }

    /// Direction of travel once rolling (degrees, counter-clockwise about up from the line
    /// of centres A to B): the object ball's throw after the roll-out.
    pub fn direction_deg(&self, r: &RollOut) -> Option<f64> {
        self.angle_deg(&self.line, &r.rolling.velocity)
    }

    /// Deflection (degrees, counter-clockwise about up) from a ball's incoming direction of
    /// travel to its rolling direction: the cue ball's deflection. `None` for a ball that
    /// came in at rest or ends at rest.
    pub fn deflection_deg(&self, which: usize, r: &RollOut) -> Option<f64> {
        self.angle_deg(&self.incoming[which], &r.rolling.velocity)
    }

    fn checks(&self, ball: &Ball, speed_scale: f64) -> TableChecks {
        let n = self.table.up;
        let m = ball.mass;
        let g = self.table.params.g;
        let energy = |s: &LabBall| {
            kinetic_energy(ball, &s.velocity, &s.spin)
                + self.table.potential_energy(ball, &s.position)
        };
        let mut increase: f64 = 0.0;
        let mut momentum: f64 = 0.0;
        for r in [&self.a, &self.b] {
            let mut last = energy(&r.start);
            let mut visit = |s: &LabBall| {
                let e = energy(s);
                increase = increase.max(e - last);
                last = e;
            };
            for seg in &r.segments {
                let t1 = if seg.t1.is_finite() {
                    seg.t1
                } else {
                    seg.t0 + (r.end_time - seg.t0).max(0.0) + 1.0
                };
                for i in 0..=16 {
                    let t = seg.t0 + (t1 - seg.t0) * f64::from(i) / 16.0;
                    visit(&seg.at(&n, t));
                }
            }
            let (_, end) = r.at(&n, r.end_time, true);
            let dp = m * (end.velocity - r.start.velocity)
                - (r.table_impulse - n * (m * g * r.end_time));
            momentum = momentum.max(dp.amax());
        }
        let ev = m * speed_scale * speed_scale;
        let pv = m * speed_scale;
        TableChecks {
            energy_increase: if increase <= 0.0 { 0.0 } else { increase / ev },
            momentum_error: if momentum == 0.0 { 0.0 } else { momentum / pv },
        }
    }
}
