//! Resolving a cluster of balls as one system of ODEs (docs/cluster.md): the positions,
//! velocities and spins of every ball, the normal force of each contact from its compression
//! under the pair's law (`ContactLaw::force`, docs/contact-law.md), Coulomb friction at each
//! contact with the stick rule, stepped by Dormand-Prince 5(4) with events.
//!
//! Each contact keeps the geometry it had when it closed, as the paper does for two balls
//! (its eqs 14-19 hold the line of centres and the lever arms r fixed through the contact):
//! the normal n from ball i to ball j, the compression measured along it from the positions,
//! delta = r_i + r_j - n . (x_j - x_i), closing at delta' = n . (v_i - v_j), and the contact
//! points at r_i n and -r_j n from the centres. The slip of the contact points is
//! s = v_i - v_j + r_i w_i x n + r_j w_j x n, its tangential part s_t = s - (s . n) n
//! (eqs 5-6 of two balls).

use super::params::{
    first_touch, pair_index, Cluster, ClusterTangential, CLUSTER_GRAZING, CLUSTER_TOUCH_TOLERANCE,
};
use super::rosenbrock;
use crate::base::error::Error;
use crate::base::root::{illinois_update, Bound, Side};
use crate::cushion::tableau::{StepControl, DOPRI5_A, DOPRI5_CONTROL, DOPRI5_E};
use crate::model::contact_law::ContactLaw;
use crate::model::contact_law::Damping;
use crate::model::material::elastic_impact;
use crate::tangential::impact::{
    capped, mindlin_stiffness, spring_slide_rate, spring_stick_rate, ALIGN_TURNS, NEGLIGIBLE_MU,
};
use nalgebra::{DMatrix, DVector, Dyn, Matrix2, Vector2, Vector3, LU};
use std::cell::{Cell, RefCell};

/// Default relative tolerance of the step control.
pub const CLUSTER_DEFAULT_RTOL: f64 = 1e-8;

/// Most accepted and rejected steps (and free flights) of one run: a 16-ball break at rtol
/// 1e-10 takes a few thousand; a run still going after this many is chattering, and stops
/// with [`StopReason::WorkBound`].
pub const CLUSTER_MAX_STEPS: u64 = 1_000_000;

/// Slip (relative to the reference speed) under which a contact's sliding direction is taken
/// from its last known direction rather than from the slip itself: near 1e-13 the direction
/// of a slip is rounding.
const SLIP_FLOOR: f64 = 1e-13;

/// Bracket width (relative to the elastic contact time) at which an event is located: a few
/// ulps of the time unit, as for two balls (the integrator's law events).
const EVENT_X_TOL: f64 = 1e-14;

/// Most trials of one event location.
const EVENT_TRIALS: usize = 100;

/// A stuck contact is released when the friction it needs exceeds mu f by this fraction: the
/// needed friction comes out of a linear solve accurate to about 1e-12.
const RELEASE_SLACK: f64 = 1e-9;

/// Most sweeps over the contacts released together for their sliding directions.
const RELEASE_SWEEPS: usize = 30;

/// Change of a released contact's sliding direction (a unit vector) at which the sweeps
/// stop: well below the step control's tolerances.
const RELEASE_DIRECTION_TOL: f64 = 1e-12;

/// What a frozen step's held friction directions may leave off, in rtol v_ref of velocity,
/// before the step is halved (`Run::go`): as much as a located stop may leave across its
/// direction ([`STOP_RESIDUE`]). At 1 rtol v_ref the held error, second order in the step,
/// took the rolling break at rtol 1e-12 from 46,154 steps to 143,232.
const FROZEN_TURN: f64 = 100.0;

/// Bisection steps of [`slide_direction`]'s secular equation, each halving a bracket of
/// lambda: 200 reach any double's rounding from any bracket.
const SECULAR_STEPS: usize = 200;

/// Normal impulse (relative to the lighter ball's momentum at the reference speed) under
/// which a contact is not recorded: the touching balls of a rack at rest press on each other
/// by the rounding of their positions (1e-22 N s), which is no contact.
const RECORD_FLOOR: f64 = 1e-14;

/// Normal force (relative to the impact's force scale, the lighter ball's momentum at the
/// reference speed over the elastic contact time) under which a contact does not press for
/// the stick rule: touching balls of a rack at rest press by the rounding of their
/// positions (1e-17 N against a scale of 7e3 N at 8 m/s: 1e-21), and the friction such a
/// contact needs to stick, and its bound, are rounding too; their difference changed sign
/// at random and held the location of a release for a hundred trials. Kept far below any
/// force that matters: at 1e-12 (7e-9 N) the 16-ball break's answer moved by 4e-7.
const PRESS_FLOOR: f64 = 1e-16;

/// Position ulps whose compression is rounding: a contact pressing no harder than the
/// stiffest pair's law at this compression (about 1e-16 m of a rack's 0.2 m) presses by the
/// rounding of the positions, and does not press for the stick rule either. At 1 mm/s the
/// impact's force scale is 0.2 N, so [`PRESS_FLOOR`] of it (2e-17 N) sat below the 9e-17 N a
/// resting rack's touching pairs press with at 7e-18 m of rounding: their stick and release
/// changed at every step, 1e6 steps of 3e-10 s (an 8-ball rack struck at 1 mm/s ran 252 s to
/// the work bound; found by fuzzing).
const ROUNDING_ULPS: f64 = 8.0;

/// The longest step through pressing ball pairs, in radians of the stiffest one's
/// oscillation ([`Run::oscillation_bound`]). The step's error estimate is asymptotic: it
/// holds once the step resolves the contact, and past that it can pass by chance. Two
/// balls at 1 mm/s under Kuwabara-Kono at rtol 1e-3 were stepped through their contact in
/// three steps of 0.43 elastic contact times, the estimate 0.66 of the tolerance, and left
/// with a restitution of 1.016 against 0.987 (energy made; 0.987116 in 10 steps now); a
/// line of eight such balls with gaps gained 4 % of its energy, its heat -5.6e-8 J of 8.5e-8
/// J put in (1.3e-6 of its balance now). At 1 radian the pair still ended 1.8e-3 off.
const OSCILLATION_STEP: f64 = 0.5;

/// Sweeps per ball over the spent contacts of a free cluster, bouncing off those still
/// closing, before they are stepped on instead ([`Run::bounce_spent`]).
const BOUNCE_SWEEPS: usize = 4;

/// The most slip (in rtol of the reference speed) a located stop of sliding may leave
/// across the direction it stopped along. A step taken with friction along each sliding
/// contact's direction at its start (a slip reversed inside the step) locates the stop
/// where the slip along that direction crosses zero; in three dimensions the slip also
/// turns, and a long step's crossing can leave the slip turned, not stopped: the 16-ball
/// break with a rolling cue ball located stops leaving up to 5.6e-4 m/s across at rtol
/// 1e-10 (6.6e5 rtol v_ref), and the contact then stuck holding that slip. Such a step is
/// halved until its crossing leaves no more than this (the stops of short steps left 10 to
/// 100). That break then converges with the tolerance (1.4e-6 / 2.8e-7 / 1.2e-8 m/s off at
/// rtol 1e-9 / 1e-10 / 1e-11, 4.7e-4 / 1.2e-4 / 6.0e-5 before), and the break 1e-12 m/s off
/// the plane comes within 4.6e-5 m/s of the planar one at rtol 1e-8 (5.0e-3 before).
const STOP_RESIDUE: f64 = 100.0;

/// Shortest step (in units of the contact time) halved for a stop that left the slip
/// turned ([`STOP_RESIDUE`]); shorter, the stop is taken as located.
const TURN_MIN_STEP: f64 = 1e3 * MIN_STEP;

/// First step, in elastic contact times: the force starts as t^(3/2) (or t^(1/2)).
const FIRST_STEP: f64 = 1e-3;

/// On a cloth, how far ahead (in elastic contact times) a run steps on to a pair that will
/// touch once every contact between balls has opened: the balls roll and slide on the cloth
/// rather than fly, so a later collision is the table simulation's (docs/cluster.md#the-cloth).
const CLOTH_HORIZON: f64 = 100.0;

/// Smallest step, in elastic contact times, before the run stops with
/// [`StopReason::StepTooSmall`].
const MIN_STEP: f64 = 1e-15;

/// A sliding contact's direction relaxes at lambda = mu f G / |s| (G the slip's rate under a
/// unit tangential force, its isotropic compliance): stiff where the slip is small. Once a
/// step h of a contact whose slip keeps at least [`HOVER_KEEP`] of its size over it (at its
/// rate at the step's start: a slip running down to a stop is located as an event instead)
/// reaches h lambda = [`STIFF_SLIP`], the explicit step is at the edge of its stability
/// (about 3.3 for Dormand-Prince on the real axis), where the direction chatters from step
/// to step and the error estimate lets it pass (a 7-ball rack's cue ball converged to
/// -0.47388152 m/s in 2.9e6 steps at rtol 1e-12, the value being -0.47387948). Such a step
/// is ROS34PW2's, linearly implicit in those directions ([`System::step`]), unless that
/// method's last step proposed less than STIFF_SLIP / lambda: in mildly stiff stretches the
/// explicit step, of order 5 against 3, goes further (for [`STIFF_RETRY`] steps, then
/// ROS34PW2 is tried again; docs/cluster.md, "Stiff slips"). A heavily damped normal force
/// is stiff the same way, damping the closing rate at its own lambda
/// ([`damping_stiffness`]), and takes the same step.
const STIFF_SLIP: f64 = 3.0;

/// A slip that keeps this fraction of its size over a step may be stiff ([`STIFF_SLIP`]);
/// kept within this factor both ways, and within rtol of the reference speed, it stops
/// ([`Run::stop_hovering`]).
const HOVER_KEEP: f64 = 0.5;

/// Explicit steps past [`STIFF_SLIP`] / lambda taken, after ROS34PW2 last proposed a step
/// shorter than that, before ROS34PW2 is tried again.
const STIFF_RETRY: usize = 10;

/// The step control of ROS34PW2 (error of order 3): safety 0.9, ratios in [0.2, 6].
const STIFF_CONTROL: StepControl = StepControl {
    safety: 0.9,
    fac_min: 0.2,
    fac_max: 6.0,
    exponent: 1.0 / 3.0,
};

/// The step control after a step of either kind.
fn control(stiff: bool) -> StepControl {
    if stiff {
        STIFF_CONTROL
    } else {
        DOPRI5_CONTROL
    }
}

/// Components of the state per ball: position, velocity, spin.
const PER_BALL: usize = 9;
/// Components of the state per open contact: normal impulse, friction impulse (3), heat.
const PER_CONTACT: usize = 5;
/// Components per open contact under Mindlin's spring: the five above, then the spring's
/// force S (N) along the contact's two tangent vectors.
const PER_SPRING_CONTACT: usize = PER_CONTACT + 2;

/// Relative shortfall of |S| under mu f at which a spring still counts as on its cap, for
/// the decision to slide: the pair kernel's band (docs/tangential.md#stepping).
const SPRING_CAP_BAND: f64 = 1e-9;

/// Why a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// No contact is compressed and no pair will touch again: the result is final. Between
    /// free balls, contacts that can give no more than rtol of the reference speed over the
    /// number of balls end there (those still closing bounced off first;
    /// docs/cluster.md, "Spent contacts").
    Separated,
    /// [`CLUSTER_MAX_STEPS`] steps (and free flights) were taken; the state is where the
    /// run stopped.
    WorkBound,
    /// The step control asked for a step below 1e-15 elastic contact times.
    StepTooSmall,
}

/// Settings of a cluster run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterSettings {
    /// Relative tolerance of the step control (also the absolute one, on the natural scales).
    pub rtol: f64,
    /// Static friction once a contact's slip stops (the stick rule); off: friction keeps
    /// acting along the direction the contact slid in when its slip stopped, while the slip
    /// reverses (the two-ball law's `stick = false`; its heat can then fall, eq 57).
    pub stick: bool,
}

impl Default for ClusterSettings {
    fn default() -> Self {
        ClusterSettings {
            rtol: CLUSTER_DEFAULT_RTOL,
            stick: true,
        }
    }
}

/// A ball after the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallOut {
    /// Position (m) when the run ended.
    pub position: Vector3<f64>,
    /// Velocity (m/s).
    pub velocity: Vector3<f64>,
    /// Spin (rad/s).
    pub spin: Vector3<f64>,
}

/// A contact that carried force, from its closing to its opening.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRecord {
    /// The balls (i < j).
    pub pair: (usize, usize),
    /// Its normal, from ball i to ball j.
    pub normal: Vector3<f64>,
    /// Normal impulse (N s) on ball j (on i, minus it).
    pub normal_impulse: f64,
    /// Friction impulse (N s) on ball i (on j, minus it).
    pub friction_impulse: Vector3<f64>,
    /// Time it closed (s, from the start of the run).
    pub start: f64,
    /// Its duration (s).
    pub duration: f64,
    /// Energy it dissipated (J): the work of its normal force on the compression and of its
    /// friction on the slip.
    pub heat: f64,
    /// Time (s, from its closing) its slip last stopped; `None` if it never did.
    pub stick_time: Option<f64>,
}

/// Work done.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ClusterStats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Right-hand-side evaluations.
    pub evaluations: u64,
    /// Events located (stops and releases of slip, contacts opening and closing).
    pub events: u64,
}

/// The result of a cluster run.
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterOutcome {
    /// Every ball, in the input's order.
    pub balls: Vec<BallOut>,
    /// Every contact between balls that carried force, in the order they opened (a run
    /// that stopped, [`StopReason::WorkBound`] or [`StopReason::StepTooSmall`], ends with
    /// those still in the set at the stop, as they stood).
    pub contacts: Vec<ContactRecord>,
    /// On a cloth ([`Cluster::with_cloth`]), each ball's contact with it (pair (ball, N), N
    /// the number of balls; normal -z, from the ball into the cloth; the normal impulse
    /// pushes the ball up), recorded when the run ends or the ball leaves the cloth; a
    /// ball's weight alone gives m g times the run's time. Empty without a cloth.
    pub cloth: Vec<ContactRecord>,
    /// Why the run ended.
    pub stop: StopReason,
    /// Time (s) the run covered.
    pub time: f64,
    /// Time (s) two balls first touched while approaching: [`Cluster::first_touch_time`]
    /// for free balls; on a cloth, later when the cloth's friction slowed the balls on their
    /// way (the run's own closing).
    pub first_touch: f64,
    /// Work done.
    pub stats: ClusterStats,
}

impl ClusterOutcome {
    /// The energy (J) the cloth and gravity hold at the end of this run of `cluster`:
    /// over the balls, V(delta_out) - V(delta_s) with the cloth's Hertz spring and the
    /// weight, V(delta) = (2/5) k max(delta, 0)^(5/2) - m g delta, and delta = r - (z -
    /// height) + delta_s the ball's compression of the cloth (a ball resting at its input
    /// height compresses it by delta_s, k delta_s^(3/2) = m g; a ball off the cloth has
    /// delta < 0 and holds m g times its height). The energy balance on the cloth is K_in =
    /// K_out + heat + held; without a cloth, 0.
    ///
    /// ```
    /// use billiard_contact::nalgebra::Vector3;
    /// use billiard_contact::*;
    /// let (m, r) = (0.17, 0.028575);
    /// let ball = |x: f64, v: f64| ClusterBall {
    ///     ball: Ball::new(m, r, 0.4).unwrap(),
    ///     position: Vector3::new(x, 0.0, r),
    ///     velocity: Vector3::new(v, 0.0, 0.0),
    ///     spin: Vector3::zeros(),
    /// };
    /// let resin = Material::new(5.4e9, 0.34)?;
    /// let slate = Material::new(5.0e10, 0.25)?;
    /// let law = ClusterLaw::Materials(vec![resin; 2], PairDamping::None);
    /// let cloth = ClusterCloth { height: 0.0, material: slate, mu: 0.2, gravity: 9.81 };
    /// let cluster = Cluster::new(vec![ball(0.0, 1.0), ball(2.0 * r, 0.0)], law, 0.06)?
    ///     .with_cloth(cloth)?;
    /// let out = resolve_cluster(&cluster, &ClusterSettings::default())?;
    /// let kinetic = |v: Vector3<f64>, w: Vector3<f64>| {
    ///     0.5 * m * v.norm_squared() + 0.5 * 0.4 * m * r * r * w.norm_squared()
    /// };
    /// let k_out: f64 = out.balls.iter().map(|b| kinetic(b.velocity, b.spin)).sum();
    /// let heat: f64 = out.contacts.iter().chain(&out.cloth).map(|c| c.heat).sum();
    /// let k_in = 0.5 * m * 1.0;
    /// assert!((k_in - k_out - heat - out.cloth_held(&cluster)).abs() < 1e-6 * k_in);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn cloth_held(&self, cluster: &Cluster) -> f64 {
        let Some(cloth) = cluster.cloth else {
            return 0.0;
        };
        let mut held = 0.0;
        for (i, (b, o)) in cluster.balls.iter().zip(&self.balls).enumerate() {
            let (law, preload) = (cluster.cloth_laws[i], cluster.cloth_preloads[i]);
            let m = b.ball.mass();
            let v = |d: f64| law.elastic_energy(d) - m * cloth.gravity * d;
            let delta = b.ball.radius() - (o.position.z - cloth.height) + preload;
            held += v(delta) - v(preload);
        }
        held
    }
}

/// One contact of the set in a trace row: its state at the row's time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactTrace {
    /// The balls (i < j).
    pub pair: (usize, usize),
    /// Time (s, from the start of the run) the contact closed: a pair that closes again is
    /// a new contact, whose accumulators start from zero.
    pub start: f64,
    /// Compression delta = r_i + r_j - n . (x_j - x_i) (m), n the normal held from the
    /// closing; negative once the balls have moved apart.
    pub compression: f64,
    /// Normal force (N) of the pair's law, pushing ball j along n (ball i, minus it).
    pub normal_force: f64,
    /// Normal impulse (N s) on ball j since the contact closed.
    pub normal_impulse: f64,
    /// Friction force (N) on ball i (on j, minus it).
    pub friction_force: Vector3<f64>,
    /// Friction impulse (N s) on ball i since the contact closed.
    pub friction_impulse: Vector3<f64>,
    /// Tangential slip s_t (m/s) of ball i's contact point over ball j's.
    pub slip: Vector3<f64>,
    /// Whether friction holds the slip at zero (the stick rule).
    pub stuck: bool,
    /// Energy dissipated (J) since the contact closed.
    pub heat: f64,
}

/// One row of a cluster trace: the time, every ball, every contact in the set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterTraceRow<'a> {
    /// Time (s, from the start of the run).
    pub t: f64,
    /// Every ball in the input's order: position (m, lab frame), velocity, spin.
    pub balls: &'a [BallOut],
    /// The contacts in the set at `t`, in no particular order; a pair not among them is
    /// apart (or touching without a contact yet).
    pub contacts: &'a [ContactTrace],
    /// The contacts that left the set since the previous row, with their final impulses and
    /// heat (also those too small for the outcome's records): between samples a contact's
    /// last row need not be its end.
    pub opened: &'a [ContactRecord],
}

/// When a cluster trace takes its rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClusterSampling<'a> {
    /// When stepping starts (the first touch, and again after a free flight) and after
    /// every accepted step, before the contacts that open at its end leave the set.
    Steps,
    /// At these times (s from the start of the run, ascending): inside a step from its
    /// continuous extension (order 4; the cubic Hermite interpolant, order 3, in a step
    /// linearly implicit in stiff slips), at a step's end its state, in a free flight the
    /// flight's state.
    Times(&'a [f64]),
}

/// A trace of a cluster run: where its rows go and when they are taken.
pub struct ClusterTrace<'a> {
    /// When the rows are taken.
    pub sampling: ClusterSampling<'a>,
    /// Receives each row as it is made.
    pub sink: &'a mut dyn FnMut(&ClusterTraceRow<'_>),
}

/// How a contact's friction acts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// Coulomb's mu f against the slip.
    Sliding,
    /// Whatever keeps the slip zero (solved jointly with the other stuck contacts).
    Stuck,
    /// Without the stick rule, once the slip has stopped: mu f along the direction the
    /// contact slid in when it stopped (`seed`), whatever the slip does after (the two-ball
    /// law's literal continuation of eqs 22-23 past the stop). Following the reversed slip
    /// instead would flip the friction at every zero of the slip, and the steps would chase
    /// that chatter to the work bound.
    Continued,
    /// Mindlin's spring (docs/cluster.md#tangential-compliance-in-clusters), sticking: its
    /// force S follows S' = -k_t u + S min(delta', 0) / (2 delta).
    SpringStick,
    /// Mindlin's spring on Coulomb's cap, sliding: |S| = mu f, turning with the slip.
    SpringSlide,
}

impl Mode {
    fn spring(self) -> bool {
        matches!(self, Mode::SpringStick | Mode::SpringSlide)
    }
}

/// A contact in the current set.
#[derive(Debug, Clone, Copy)]
struct Active {
    i: usize,
    j: usize,
    /// Radii (m) and normal frozen at the closing.
    ri: f64,
    rj: f64,
    n: Vector3<f64>,
    /// An orthonormal basis of the tangent plane.
    t: [Vector3<f64>; 2],
    law: ContactLaw,
    /// Coulomb's mu of the contact (the cluster's between balls, the cloth's on the cloth).
    mu: f64,
    /// Compression (m) the contact had at the start beyond its geometry: a ball's static
    /// compression of the cloth under its weight (0 between balls).
    preload: f64,
    /// Mindlin's 8 G* sqrt(R*) of the pair (N/m^1.5; 0 under the rigid rule).
    k_t0: f64,
    mode: Mode,
    /// A sliding spring stepped as Coulomb's friction through the step: its force, rates
    /// and turn read with the spring along -u, the slip's opposite, at every stage
    /// (`Run::align`).
    aligned: bool,
    /// Direction of sliding used when the slip is below [`SLIP_FLOOR`], and the direction
    /// friction keeps while a step is located: the slip's at the start of the step.
    seed: Vector3<f64>,
    /// The slip (m/s) the contact had when it last stuck or was released: the residue of
    /// the located stop (its part across the direction that stopped, in 3D) and of the
    /// stick solve's rounding, which s_t' = 0 then holds. The contact's slip is measured
    /// from it (s_t - offset): a released contact slides along its slip since the release,
    /// not along this residue of arbitrary direction. (The heat is friction's work on the
    /// whole slip, so that the energy balances exactly.)
    offset: Vector3<f64>,
    /// Whether the force has been positive.
    loaded: bool,
    /// Time of the closing (s).
    start: f64,
    stick_time: Option<f64>,
    /// Serial number of the closing, unique in the run ([`StickLu`]).
    id: u64,
}

/// The stick solve's last factorization (the forces' for two or more stuck contacts, one
/// alone solving its 2 x 2 system on the stack; ROS34PW2's columns' for any number). Its
/// matrix depends only on which contacts are stuck (their normals and tangent bases are
/// frozen at the closing, the balls' masses and inertias fixed), so it is built and
/// factorized again only when that set changes: in the 16-ball break, building and
/// factorizing it at every evaluation took a tenth of the run.
#[derive(Default)]
struct StickLu {
    /// The stuck contacts' ids ([`Active::id`]), in the set's order.
    ids: Vec<u64>,
    /// The LU of their matrix ([`System::stick_matrix`]).
    lu: Option<LU<f64, Dyn, Dyn>>,
}

/// Index in the state of the spring S (two components) of contact `k`, with `nb` bodies
/// and `pc` components per contact.
fn spring_index(nb: usize, pc: usize, k: usize) -> usize {
    PER_BALL * nb + pc * k + PER_CONTACT
}

/// The components (m/s) of the tangential vector `v` in contact `c`'s tangent basis.
fn in_basis(c: &Active, v: &Vector3<f64>) -> [f64; 2] {
    [c.t[0].dot(v), c.t[1].dot(v)]
}

/// Of a sliding spring `s` (N) with stick rate `stick` (N/s) and cap rate `cap_rate`
/// (N/s): where its stick rate turns back inside the cap, S'_stick . e - (mu f)' (positive
/// while it slides on; 0 for a spring of no force), and the scale of those rates,
/// |S'_stick . e| + |(mu f)'|.
fn spring_turn_of(s: [f64; 2], stick: [f64; 2], cap_rate: f64) -> (f64, f64) {
    let n = (s[0] * s[0] + s[1] * s[1]).sqrt();
    if n > 0.0 {
        let along = (stick[0] * s[0] + stick[1] * s[1]) / n;
        (along - cap_rate, along.abs() + cap_rate.abs())
    } else {
        (0.0, cap_rate.abs())
    }
}

/// A spring's force `s` (N, tangent basis) turned against the slip `u` (m/s) at its
/// length: -|s| u / |u|; `s` itself when the slip is zero.
fn against_slip(s: [f64; 2], u: [f64; 2]) -> [f64; 2] {
    let un = u[0].hypot(u[1]);
    if un > 0.0 {
        let m = s[0].hypot(s[1]);
        [-m * u[0] / un, -m * u[1] / un]
    } else {
        s
    }
}

/// Mass, radius and moment of inertia (kg, m, kg m^2).
#[derive(Debug, Clone, Copy)]
struct Body {
    m: f64,
    r: f64,
    inertia: f64,
}

/// The force of one contact: normal force (N), friction on ball i (N), tangential slip
/// (m/s), closing rate (m/s), compression (m).
type ContactForce = (f64, Vector3<f64>, Vector3<f64>, f64, f64);

/// The forces of one state.
#[derive(Default)]
struct Forces {
    /// Per ball: acceleration (m/s^2), angular acceleration (rad/s^2).
    acc: Vec<[Vector3<f64>; 2]>,
    /// Per contact: normal force (N), friction on ball i (N), tangential slip (m/s),
    /// closing rate (m/s), compression (m).
    contact: Vec<ContactForce>,
    /// Per contact, once a stuck contact needs more than mu f (empty otherwise,
    /// [`Forces::need`]): the friction (N) it needs.
    need: Vec<Vector3<f64>>,
    /// The stuck contacts the stick solve took (kept for the vector's reuse).
    stuck: Vec<usize>,
}

impl Forces {
    /// The friction (N) contact `k` needs, which the events and releases read: a stuck
    /// contact's from the stick solve, which may pass mu f (its friction is then held to mu
    /// f along it), any other contact's its friction.
    fn need(&self, k: usize) -> Vector3<f64> {
        self.need.get(k).copied().unwrap_or(self.contact[k].1)
    }
}

/// Whether a slip `s` (m/s) moving at the rate `rate` (m/s^2) keeps its size within a
/// factor 1 / [`HOVER_KEEP`] over a step of `h` (s), the whole vector: how a hovering slip
/// is told ([`Run::stop_hovering`]).
fn keeps_its_size(s: Vector3<f64>, rate: Vector3<f64>, h: f64) -> bool {
    let (now, next) = (s.norm(), (s + rate * h).norm());
    next >= HOVER_KEEP * now && next * HOVER_KEEP <= now
}

/// The direction e (a unit vector of the tangent plane) along which a contact released from
/// sticking slides, given its slip's rate a - Q e under its friction along e (Q e: what its
/// own friction -mu f e takes off the rate; a: the rest): the slip must grow along e,
/// a - Q e = lambda e with lambda >= 0, so e = (lambda I + Q)^(-1) a with |e| = 1, the
/// secular equation of lambda. With Q positive definite (the contact's compliance to its
/// own friction, times mu f) |e(lambda)| falls with lambda, and the root is unique when
/// |Q^(-1) a| >= 1, the friction needed to stick, -Q^(-1) a in units of mu f, at or past
/// the bound. Below it (a release located where the need reaches mu f, read at a state
/// just before: the rate's direction there is rounding) lambda = 0: e = Q^(-1) a / |Q^(-1)
/// a|, the excess's direction -F / |F|. `None` when Q is singular or a is zero (the
/// contact keeps its direction) or the root is not bracketed (Q far from definite).
fn slide_direction(q: Matrix2<f64>, a: Vector2<f64>) -> Option<Vector2<f64>> {
    let at = |lambda: f64| (q + Matrix2::identity() * lambda).lu().solve(&a);
    let x0 = at(0.0)?;
    let n0 = x0.norm();
    if !(n0 > 0.0 && n0.is_finite()) {
        return None;
    }
    if n0 <= 1.0 {
        return Some(x0 / n0);
    }
    // |e(lambda)| <= |a| / (lambda - |Q|) past |Q|: 1 at lambda = |a| + |Q| at the most.
    let (mut lo, mut hi) = (0.0, a.norm() + q.norm());
    if at(hi)?.norm() > 1.0 {
        return None;
    }
    for _ in 0..SECULAR_STEPS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if at(mid)?.norm() > 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let x = at(hi)?;
    Some(x / x.norm())
}

/// The relaxation rate lambda = mu f G / |s| (1/s) of sliding contact `c`'s direction, G its
/// isotropic compliance, under the normal force `f` (N) with the slip `sr` (m/s, from its
/// offset) moving at `rate` (m/s^2), if it counts for a step of `h` (s): pressed, its slip
/// above `floor` (m/s) and keeping at least [`HOVER_KEEP`] of its size over the step
/// ([`STIFF_SLIP`]).
fn direction_stiffness(
    bodies: &[Body],
    c: &Active,
    f: f64,
    sr: Vector3<f64>,
    rate: Vector3<f64>,
    h: f64,
    floor: f64,
) -> Option<f64> {
    let sn = sr.norm();
    if c.mu <= 0.0 || f <= 0.0 || sn <= floor || (sr + rate * h).norm() < HOVER_KEEP * sn {
        return None;
    }
    let (bi, bj) = (&bodies[c.i], &bodies[c.j]);
    let g = 1.0 / bi.m + 1.0 / bj.m + c.ri * c.ri / bi.inertia + c.rj * c.rj / bj.inertia;
    Some(c.mu * f * g / sn)
}

/// The rate d f / d delta' (N s/m) of contact `c`'s damped normal force at compression `d`
/// (m) where the force `f` (N) presses, and the rate lambda = (d f / d delta') (1/m_i +
/// 1/m_j) (1/s) at which it damps the closing rate: the normal force's own stiffness under
/// heavy damping ([`STIFF_SLIP`]). `None` for an elastic law or a contact not pressing.
fn damping_stiffness(bodies: &[Body], c: &Active, d: f64, f: f64) -> Option<(f64, f64)> {
    if d <= 0.0 || f <= 0.0 {
        return None;
    }
    let (k, g) = (c.law.stiffness(), c.law.coefficient());
    let rate = match c.law.damping() {
        Damping::None => return None,
        Damping::HuntCrossley => k * d * d.sqrt() * g,
        Damping::KuwabaraKono => k * d.sqrt() * g,
    };
    let lambda = rate * (1.0 / bodies[c.i].m + 1.0 / bodies[c.j].m);
    (lambda > 0.0).then_some((rate, lambda))
}

/// The tangential slip rate s_t' (m/s^2) of contact `c` under the accelerations `acc`.
fn slip_rate(acc: &[[Vector3<f64>; 2]], c: &Active) -> Vector3<f64> {
    let r = acc[c.i][0] - acc[c.j][0] + (acc[c.i][1] * c.ri + acc[c.j][1] * c.rj).cross(&c.n);
    r - c.n * r.dot(&c.n)
}

/// The system of one segment: its balls, its contact set and the friction.
struct System<'a> {
    bodies: &'a [Body],
    active: &'a [Active],
    /// The balls (the first bodies; a cloth is the last, immovable one).
    nballs: usize,
    /// Gravity (m/s^2) along -z on every ball (0 without a cloth).
    gravity: f64,
    /// Coulomb's mu of the springs: `mu`, or 0 below [`NEGLIGIBLE_MU`] (as the pair kernel:
    /// such a friction moves no velocity by more than its rounding).
    spring_mu: f64,
    /// Components of the state per contact.
    pc: usize,
    /// Reference speed (m/s).
    v_ref: f64,
    /// Normal force (N) under which a contact does not press for the stick rule
    /// ([`PRESS_FLOOR`] of the impact's force scale).
    f_floor: f64,
    /// Friction along the `seed` of each sliding contact `held` marks (the located step).
    frozen: bool,
    /// Per contact of the set: held along its seed in a frozen step.
    held: &'a [bool],
    /// Per contact of the set: set when a stage saw its slip reversed against its seed (a
    /// contact past the end of the slice is not marked).
    flips: &'a [Cell<bool>],
    /// Whether a step may be ROS34PW2's ([`System::step`]).
    implicit: bool,
    /// The stick solve's last factorization, shared by the run's systems.
    stick_lu: &'a RefCell<StickLu>,
    evaluations: Cell<u64>,
}

fn pos(y: &[f64], b: usize) -> Vector3<f64> {
    Vector3::new(y[3 * b], y[3 * b + 1], y[3 * b + 2])
}

impl System<'_> {
    fn nb(&self) -> usize {
        self.bodies.len()
    }
    fn vel(&self, y: &[f64], b: usize) -> Vector3<f64> {
        pos(y, self.nb() + b)
    }
    fn spin(&self, y: &[f64], b: usize) -> Vector3<f64> {
        pos(y, 2 * self.nb() + b)
    }

    /// Compression delta (m) and closing rate delta' (m/s) of contact `c`.
    fn compression(&self, y: &[f64], c: &Active) -> (f64, f64) {
        let d = c.ri + c.rj - c.n.dot(&(pos(y, c.j) - pos(y, c.i))) + c.preload;
        (d, c.n.dot(&(self.vel(y, c.i) - self.vel(y, c.j))))
    }

    /// Tangential slip s_t (m/s) of contact `c`.
    fn slip(&self, y: &[f64], c: &Active) -> Vector3<f64> {
        let s = self.vel(y, c.i) - self.vel(y, c.j)
            + (self.spin(y, c.i) * c.ri + self.spin(y, c.j) * c.rj).cross(&c.n);
        s - c.n * s.dot(&c.n)
    }

    /// Whether a frozen step holds contact `k`'s friction along its seed.
    fn holds(&self, k: usize) -> bool {
        self.frozen && self.held.get(k).copied().unwrap_or(false)
    }

    /// The unit vector contact `k` (`c`, its slip `sr` from its offset) slides along, its
    /// friction -mu f times it: a sliding contact's slip direction, or its seed while held or
    /// below the floor; without the stick rule, after its stop, its seed; zero otherwise.
    fn friction_direction(&self, k: usize, c: &Active, sr: Vector3<f64>) -> Vector3<f64> {
        match c.mode {
            Mode::Sliding => {
                let sn = sr.norm();
                if self.holds(k) || sn <= SLIP_FLOOR * self.v_ref {
                    c.seed
                } else {
                    sr / sn
                }
            }
            Mode::Continued => c.seed,
            _ => Vector3::zeros(),
        }
    }

    /// Every force of state `y`.
    fn forces(&self, y: &[f64]) -> Forces {
        let mut fs = Forces::default();
        self.forces_into(y, &mut fs);
        fs
    }

    /// Every force of state `y`, into `fs` (its vectors reused: a step's inner stages
    /// share one, and their allocations were a fifth of a two-ball run's instructions).
    fn forces_into(&self, y: &[f64], fs: &mut Forces) {
        self.evaluations.set(self.evaluations.get() + 1);
        let Forces {
            acc,
            contact,
            need,
            stuck,
        } = fs;
        acc.clear();
        acc.resize(self.nb(), [Vector3::zeros(); 2]);
        for a in &mut acc[..self.nballs] {
            a[0].z -= self.gravity;
        }
        contact.clear();
        // Filled by the stick solve only (no allocation in a step without one).
        need.clear();
        for (k, c) in self.active.iter().enumerate() {
            let (d, w) = self.compression(y, c);
            let f = c.law.force(d, w);
            let s = self.slip(y, c);
            let sr = s - c.offset;
            let friction = match c.mode {
                Mode::SpringStick | Mode::SpringSlide => {
                    let a = capped(self.spring(y, k), self.spring_mu * f.max(0.0));
                    let a = if c.aligned {
                        against_slip(a, in_basis(c, &s))
                    } else {
                        a
                    };
                    c.t[0] * a[0] + c.t[1] * a[1]
                }
                Mode::Sliding | Mode::Continued if f > 0.0 && c.mu > 0.0 => {
                    let dir = self.friction_direction(k, c, sr);
                    // A slip above the floor (a direction read off the slip, not the seed)
                    // against the step's direction has gone through zero: its friction
                    // flipped inside the step.
                    if dir != c.seed && sr.dot(&c.seed) <= 0.0 {
                        if let Some(flip) = self.flips.get(k) {
                            flip.set(true);
                        }
                    }
                    -dir * (c.mu * f)
                }
                _ => Vector3::zeros(),
            };
            self.push(acc, c, -c.n * f + friction);
            contact.push((f, friction, s, w, d));
        }
        if self.active.iter().any(|c| c.mode == Mode::Stuck) {
            self.stuck(acc, contact, need, stuck);
        }
    }

    /// The spring S (N) of contact `k` in its tangent basis.
    fn spring(&self, y: &[f64], k: usize) -> [f64; 2] {
        let o = spring_index(self.nb(), self.pc, k);
        [y[o], y[o + 1]]
    }

    /// Of spring contact `k` at state `y` whose accelerations are `acc`: its spring S (N),
    /// the cap mu f (N), the spring's stick rate (N/s) and the cap's rate (N/s).
    fn spring_rates(
        &self,
        y: &[f64],
        acc: &[[Vector3<f64>; 2]],
        k: usize,
    ) -> ([f64; 2], f64, [f64; 2], f64) {
        let c = &self.active[k];
        let (d, w) = self.compression(y, c);
        let f = c.law.force(d, w);
        let u = in_basis(c, &self.slip(y, c));
        // An aligned spring acts along -u (`Run::align`): its rates, and the events and
        // modes read from them, are those of that spring.
        let sv = if c.aligned {
            against_slip(self.spring(y, k), u)
        } else {
            self.spring(y, k)
        };
        let stick = spring_stick_rate(mindlin_stiffness(c.k_t0, d), u, sv, d, w);
        // The cap's rate, as the pair kernel's: (mu f)' along the motion, delta'' the
        // contact's own, n . (a_i - a_j) (for two balls -f / m*, the law's `force_rate`).
        let cap_rate = if d <= 0.0 {
            0.0
        } else if c.law.damping() == Damping::None {
            self.spring_mu * 1.5 * c.law.stiffness() * d.sqrt() * w
        } else if f > 0.0 {
            let accel = c.n.dot(&(acc[c.i][0] - acc[c.j][0]));
            // `force_rate` takes delta'' as -f / m: the mass that gives this one.
            self.spring_mu * c.law.force_rate(d, w, -f / accel)
        } else {
            0.0
        };
        (sv, self.spring_mu * f.max(0.0), stick, cap_rate)
    }

    /// Adds the force `f` (N) on ball i at the contact point r_i n of `c` (and -f on ball j
    /// at -r_j n) to the accelerations.
    fn push(&self, acc: &mut [[Vector3<f64>; 2]], c: &Active, f: Vector3<f64>) {
        let (bi, bj) = (&self.bodies[c.i], &self.bodies[c.j]);
        let torque = c.n.cross(&f);
        acc[c.i][0] += f / bi.m;
        acc[c.j][0] -= f / bj.m;
        acc[c.i][1] += torque * (c.ri / bi.inertia);
        acc[c.j][1] += torque * (c.rj / bj.inertia);
    }

    /// The friction of the stuck contacts: the tangential forces F_d (2 unknowns each, in the
    /// tangent basis) for which every stuck slip has zero rate, s_t' = 0, given the other
    /// forces; coupled through the balls the contacts share (docs/cluster.md#the-stick-solve).
    /// A stuck contact without normal force carries no friction (Coulomb's bound mu f is
    /// 0): the touching balls of a rack at rest start stuck, and before this they passed
    /// the friction of sticking through a contact that did not yet press.
    ///
    /// A contact that needs more than mu f gets mu f along what it needs (`need` keeps the
    /// whole): the events see the release at a step's ends, and a step whose inner stages
    /// alone ask for more (a force that jumps inside the step) cannot pass Coulomb's bound.
    /// Passed through whole, a Kuwabara-Kono contact (gamma = 0.05 s) whose damped force
    /// rose from 2e-6 N to 4e5 N inside one step took 6e-6 N s of friction on 1.6e-9 N s of
    /// normal impulse and ended 1.3e-3 of mu P past the bound at E = 1.2e21 Pa; steel
    /// balls (E = 1e11 Pa) under the same damping, 23 % of mu P on a contact of 9e-10 N s.
    fn stuck(
        &self,
        acc: &mut [[Vector3<f64>; 2]],
        contact: &mut [ContactForce],
        need: &mut Vec<Vector3<f64>>,
        stuck: &mut Vec<usize>,
    ) {
        stuck.clear();
        stuck.extend(
            (0..self.active.len())
                .filter(|&k| self.active[k].mode == Mode::Stuck && contact[k].0 > self.f_floor),
        );
        let stuck = &stuck[..];
        if stuck.is_empty() {
            return;
        }
        // One stuck contact (two balls, or a ball on the cloth) solves its 2 x 2 system on
        // the stack (the same LU, no allocation: 8 % of the two-ball run's time went to
        // the dynamic matrix).
        let (x1, xn);
        let x: &[f64] = if stuck.len() == 1 {
            let (mut a, mut b) = (Matrix2::zeros(), Vector2::zeros());
            self.stick_system(stuck, acc, &mut a, &mut b);
            let Some(x) = a.lu().solve(&b) else {
                return;
            };
            x1 = x;
            x1.as_slice()
        } else {
            let mut b = DVector::<f64>::zeros(2 * stuck.len());
            self.stick_rhs(stuck, acc, &mut b);
            if !self.stick_solve(stuck, &mut b) {
                return;
            }
            xn = b;
            xn.as_slice()
        };
        for (p, &ci) in stuck.iter().enumerate() {
            let c = &self.active[ci];
            let f = c.t[0] * x[2 * p] + c.t[1] * x[2 * p + 1];
            let (cap, n) = (c.mu * contact[ci].0, f.norm());
            let over = n > cap * (1.0 + RELEASE_SLACK);
            // The needs are kept apart only once one is held (no allocation otherwise: the
            // contacts before it carry what they need).
            if over && need.is_empty() {
                *need = contact.iter().map(|c| c.1).collect();
            }
            if !need.is_empty() {
                need[ci] = f;
            }
            let held = if over { f * (cap / n) } else { f };
            self.push(acc, c, held);
            contact[ci].1 = held;
        }
    }

    /// The stick solve's linear system: `a` x = `b`, x the tangential forces of the
    /// contacts `stuck` (two per contact, in its tangent basis), `b` minus their slips'
    /// rates under the accelerations `acc` of the other forces.
    fn stick_system<A, B>(&self, stuck: &[usize], acc: &[[Vector3<f64>; 2]], a: &mut A, b: &mut B)
    where
        A: std::ops::IndexMut<(usize, usize), Output = f64>,
        B: std::ops::IndexMut<usize, Output = f64>,
    {
        self.stick_rhs(stuck, acc, b);
        self.stick_matrix(stuck, a);
    }

    /// Solves the stick solve's system for the contacts `stuck` in place: `b`
    /// its right-hand side ([`System::stick_rhs`]) becomes the tangential forces. The LU of
    /// the matrix is kept for the next solve of the same contacts ([`StickLu`]). False if
    /// the matrix is singular.
    fn stick_solve(&self, stuck: &[usize], b: &mut DVector<f64>) -> bool {
        let mut cache = self.stick_lu.borrow_mut();
        let same = cache.ids.len() == stuck.len()
            && cache.lu.is_some()
            && cache
                .ids
                .iter()
                .zip(stuck)
                .all(|(&id, &k)| id == self.active[k].id);
        if !same {
            let m = 2 * stuck.len();
            let mut a = DMatrix::<f64>::zeros(m, m);
            self.stick_matrix(stuck, &mut a);
            cache.ids.clear();
            cache.ids.extend(stuck.iter().map(|&k| self.active[k].id));
            cache.lu = Some(a.lu());
        }
        cache.lu.as_ref().is_some_and(|lu| lu.solve_mut(b))
    }

    /// `b` of the stick solve ([`System::stick_system`]): minus the slips' rates of the
    /// contacts `stuck` under the accelerations `acc`, in their tangent bases.
    fn stick_rhs<B>(&self, stuck: &[usize], acc: &[[Vector3<f64>; 2]], b: &mut B)
    where
        B: std::ops::IndexMut<usize, Output = f64>,
    {
        for (p, &ci) in stuck.iter().enumerate() {
            let c = &self.active[ci];
            let rate =
                acc[c.i][0] - acc[c.j][0] + (acc[c.i][1] * c.ri + acc[c.j][1] * c.rj).cross(&c.n);
            for u in 0..2 {
                b[2 * p + u] = -c.t[u].dot(&rate);
            }
        }
    }

    /// `a` of the stick solve ([`System::stick_system`]): the stuck slips' rates under unit
    /// tangential forces at the contacts `stuck`, added to `a`.
    fn stick_matrix<A>(&self, stuck: &[usize], a: &mut A)
    where
        A: std::ops::IndexMut<(usize, usize), Output = f64>,
    {
        // Role of a ball in a contact: the sign of its velocity in the slip and its lever.
        let role = |c: &Active, ball: usize| -> Option<(f64, f64)> {
            if ball == c.i {
                Some((1.0, c.ri))
            } else if ball == c.j {
                Some((-1.0, c.rj))
            } else {
                None
            }
        };
        for (p, &ci) in stuck.iter().enumerate() {
            let c = &self.active[ci];
            for (q, &di) in stuck.iter().enumerate() {
                let d = &self.active[di];
                for ball in [d.i, d.j] {
                    let (Some((sc, rc)), Some((sd, rd))) = (role(c, ball), role(d, ball)) else {
                        continue;
                    };
                    let body = &self.bodies[ball];
                    for v in 0..2 {
                        let f = d.t[v];
                        // s_t' of c from F_d on this ball: sc sd F / m + rc rd ((n_d x F) / I) x n_c.
                        let ds = f * (sc * sd / body.m)
                            + d.n.cross(&f).cross(&c.n) * (rc * rd / body.inertia);
                        for u in 0..2 {
                            a[(2 * p + u, 2 * q + v)] += c.t[u].dot(&ds);
                        }
                    }
                }
            }
        }
    }

    /// dy/dt at `y`, and the forces it came from.
    fn derivative(&self, y: &[f64], dy: &mut [f64]) -> Forces {
        let mut fs = Forces::default();
        self.derivative_into(y, dy, &mut fs);
        fs
    }

    /// dy/dt at `y`, the forces it came from into `fs` ([`System::forces_into`]).
    fn derivative_into(&self, y: &[f64], dy: &mut [f64], fs: &mut Forces) {
        let nb = self.nb();
        self.forces_into(y, fs);
        let fs = &*fs;
        dy[..3 * nb].copy_from_slice(&y[3 * nb..6 * nb]);
        for (b, a) in fs.acc.iter().enumerate() {
            for k in 0..3 {
                dy[3 * nb + 3 * b + k] = a[0][k];
                dy[6 * nb + 3 * b + k] = a[1][k];
            }
        }
        for (c, (f, fr, s, w, d)) in fs.contact.iter().enumerate() {
            let o = PER_BALL * nb + self.pc * c;
            dy[o] = *f;
            dy[o + 1] = fr.x;
            dy[o + 2] = fr.y;
            dy[o + 3] = fr.z;
            // Heat: the work of friction on the slip and, under a damped law, of the normal
            // force on the compression (its elastic part returned as the pair opens). The
            // whole normal work shares the stages that move the velocities, so that the
            // energy balance closes to the step's error: the damping's part alone, f -
            // f(delta, 0), left the breaks' balances 2 to 5 times looser. An elastic law's
            // normal work is zero over any contact that opens (the force depends on the
            // compression alone): integrated, it was the quadrature's error of a zero, of
            // either sign (-2.5 nJ in the 5-ball cradle), so such a pair's heat is
            // friction's, and what it holds if it opens compressed is added then (`open`).
            // A ball may end the run still pressing the cloth: the elastic part of its
            // normal work is stored energy, not heat, so a cloth contact's heat is
            // friction's and the damping's (the force less its elastic part, at the same
            // compression).
            let law = &self.active[c].law;
            dy[o + 4] = if law.damping() == Damping::None {
                -fr.dot(s)
            } else if self.active[c].j != self.nballs {
                f * w - fr.dot(s)
            } else {
                (f - law.force(*d, 0.0)) * w - fr.dot(s)
            };
            let mode = self.active[c].mode;
            if mode.spring() {
                let rate = if self.spring_mu > 0.0 {
                    let (sv, _, stick, cap_rate) = self.spring_rates(y, &fs.acc, c);
                    if mode == Mode::SpringSlide && (sv[0] != 0.0 || sv[1] != 0.0) {
                        spring_slide_rate(stick, sv, cap_rate, self.active[c].aligned)
                    } else {
                        stick
                    }
                } else {
                    [0.0, 0.0]
                };
                dy[o + PER_CONTACT] = rate[0];
                dy[o + PER_CONTACT + 1] = rate[1];
            }
        }
    }

    /// The stiff columns of the Jacobian for a step of `h` (s) from `y` (the derivative `k0`
    /// there) when the step may be ROS34PW2's: each sliding contact whose direction is stiff
    /// (h lambda at least [`STIFF_SLIP`], [`direction_stiffness`]; the column's variable the
    /// slip across it, along p = n x s / |n x s|) and each contact whose damped normal force
    /// is ([`damping_stiffness`]).
    fn stiff_columns(&self, y: &[f64], k0: &[f64], h: f64) -> Vec<StiffColumn> {
        if !self.implicit {
            return Vec::new();
        }
        let floor = SLIP_FLOOR * self.v_ref;
        // Per contact of the set: compression, closing rate, normal force.
        let normal: Vec<(f64, f64, f64)> = self
            .active
            .iter()
            .map(|c| {
                let (d, w) = self.compression(y, c);
                (d, w, c.law.force(d, w))
            })
            .collect();
        // Each column's contact, axis, and the force (N per unit of the axis's variable) it
        // puts on ball i: (normal force, friction).
        let mut wanted: Vec<(usize, StiffAxis, f64, Vector3<f64>)> = Vec::new();
        let mut closing = Vec::new();
        for (k, (c, &(d, _, f))) in self.active.iter().zip(&normal).enumerate() {
            let sr = self.slip(y, c) - c.offset;
            if c.mode == Mode::Sliding && !self.holds(k) {
                let rate = self.slip(k0, c);
                let stiff = direction_stiffness(self.bodies, c, f, sr, rate, h, floor);
                let across = c.n.cross(&sr);
                let an = across.norm();
                if stiff.is_some_and(|lambda| h * lambda >= STIFF_SLIP) && an > 0.0 {
                    let p = across / an;
                    wanted.push((k, StiffAxis::Across(p), 0.0, -p * (c.mu * f / sr.norm())));
                }
            }
            if let Some((rate, lambda)) = damping_stiffness(self.bodies, c, d, f) {
                if h * lambda >= STIFF_SLIP {
                    // Coulomb's friction scales with the normal force along its direction.
                    let along = if c.mu > 0.0 {
                        self.friction_direction(k, c, sr)
                    } else {
                        Vector3::zeros()
                    };
                    closing.push((k, StiffAxis::Closing, rate, -along * (c.mu * rate)));
                }
            }
        }
        wanted.append(&mut closing);
        if wanted.is_empty() {
            return Vec::new();
        }
        // The stuck contacts answer a change of force as the stick solve does: one
        // factorization for every column.
        let stuck: Vec<usize> = (0..self.active.len())
            .filter(|&k| self.active[k].mode == Mode::Stuck && normal[k].2 > self.f_floor)
            .collect();
        let nb = self.nb();
        wanted
            .into_iter()
            .map(|(k, axis, dn, friction)| {
                let c = &self.active[k];
                let mut acc = vec![[Vector3::zeros(); 2]; nb];
                self.push(&mut acc, c, friction - c.n * dn);
                // The heat's rate, f delta' - F . s (the damping's part of f on the cloth),
                // moves with the normal force and the closing rate, and with the friction.
                let heat = |ci: usize, dn: f64, fr: Vector3<f64>| {
                    let sc = &self.active[ci];
                    let mut q = -fr.dot(&self.slip(y, sc));
                    if let StiffAxis::Closing = axis {
                        if ci == k {
                            let (d, w, f) = normal[ci];
                            let damped = if sc.j == self.nballs {
                                f - sc.law.force(d, 0.0)
                            } else {
                                f
                            };
                            q += damped + w * dn;
                        }
                    }
                    q
                };
                let mut impulses = vec![(k, dn, friction, heat(k, dn, friction))];
                if !stuck.is_empty() {
                    let mut x = DVector::<f64>::zeros(2 * stuck.len());
                    self.stick_rhs(&stuck, &acc, &mut x);
                    if self.stick_solve(&stuck, &mut x) {
                        for (q, &ci) in stuck.iter().enumerate() {
                            let sc = &self.active[ci];
                            let fr = sc.t[0] * x[2 * q] + sc.t[1] * x[2 * q + 1];
                            self.push(&mut acc, sc, fr);
                            impulses.push((ci, 0.0, fr, heat(ci, 0.0, fr)));
                        }
                    }
                }
                StiffColumn {
                    k,
                    axis,
                    u: acc,
                    impulses,
                }
            })
            .collect()
    }

    /// A stiff column's variable of the velocities and spins in `x` (a state, or a stage's
    /// increment): the slip across its contact's direction, p . s_t, or its closing rate
    /// delta' = n . (v_i - v_j). (p . s_t written out with p . n = 0: read through
    /// [`System::slip`], the projection's rounding moves the rolling break's evaluations
    /// from 5,401 to 5,409.)
    fn read(&self, x: &[f64], s: &StiffColumn) -> f64 {
        let c = &self.active[s.k];
        match s.axis {
            StiffAxis::Across(p) => {
                p.dot(&(self.vel(x, c.i) - self.vel(x, c.j)))
                    + c.n
                        .cross(&p)
                        .dot(&(self.spin(x, c.i) * c.ri + self.spin(x, c.j) * c.rj))
            }
            StiffAxis::Closing => c.n.dot(&(self.vel(x, c.i) - self.vel(x, c.j))),
        }
    }

    /// A stiff column's variable's rate under the accelerations `acc`.
    fn read_rate(&self, acc: &[[Vector3<f64>; 2]], s: &StiffColumn) -> f64 {
        let c = &self.active[s.k];
        match s.axis {
            StiffAxis::Across(p) => p.dot(&slip_rate(acc, c)),
            StiffAxis::Closing => c.n.dot(&(acc[c.i][0] - acc[c.j][0])),
        }
    }

    /// One step of size `h` from `y` (derivative `k0` there): the new state and its error
    /// norm, the root mean square of the local error over rtol (scale_i + |y_i|), positions
    /// on their scale alone. Dormand-Prince 5(4), or ROS34PW2 (order 3, linearly implicit in
    /// the stiff slips' directions and damped closing rates) when a sliding contact's
    /// direction or a damped normal force is stiff for `h` ([`System::stiff_columns`];
    /// docs/cluster.md, "Stiff slips").
    fn step(&self, y: &[f64], k0: &[f64], h: f64, scale: &[f64], rtol: f64) -> StepOut {
        let columns = self.stiff_columns(y, k0, h);
        if !columns.is_empty() {
            return self.stiff_step(y, k0, h, scale, rtol, columns);
        }
        self.dopri5_step(y, k0, h, scale, rtol)
    }

    /// One Dormand-Prince 5(4) step ([`System::step`]).
    fn dopri5_step(&self, y: &[f64], k0: &[f64], h: f64, scale: &[f64], rtol: f64) -> StepOut {
        let n = y.len();
        let mut k = vec![vec![0.0; n]; 7];
        k[0].copy_from_slice(k0);
        let mut ys = vec![0.0; n];
        // One set of forces for the stages: the last stage's is the step's end.
        let mut end = Forces::default();
        for s in 1..7 {
            ys.copy_from_slice(y);
            for (kj, &aj) in k[..s].iter().zip(&DOPRI5_A[s - 1][..s]) {
                if aj != 0.0 {
                    let ha = h * aj;
                    for (yi, ki) in ys.iter_mut().zip(kj) {
                        *yi += ha * ki;
                    }
                }
            }
            self.derivative_into(&ys, &mut k[s], &mut end);
        }
        // Row 7 of a is the 5th-order solution: the last stage was evaluated at it.
        // The local error, h sum_s e_s k_s, summed stage by stage.
        let mut e = vec![0.0; n];
        for (ks, es) in k.iter().zip(DOPRI5_E) {
            for (ei, ki) in e.iter_mut().zip(ks) {
                *ei += es * ki;
            }
        }
        for ei in &mut e {
            *ei *= h;
        }
        let err = self.error_norm(y, &ys, &e, scale, rtol);
        StepOut {
            y: ys,
            err,
            k,
            end,
            stiff: false,
        }
    }

    /// The error norm of a step from `y0` to `y1` whose local error in component i is
    /// `e[i]`: the root mean square of e_i / (rtol (scale_i + max(|y0_i|, |y1_i|))),
    /// positions on their scale alone.
    fn error_norm(&self, y0: &[f64], y1: &[f64], e: &[f64], scale: &[f64], rtol: f64) -> f64 {
        let npos = 3 * self.nb();
        let mut sum = 0.0;
        let parts = y0.iter().zip(y1).zip(e).zip(scale);
        for (i, (((a, b), ei), si)) in parts.enumerate() {
            let mag = if i < npos { 0.0 } else { a.abs().max(b.abs()) };
            let q = ei / (rtol * (si + mag));
            sum += q * q;
        }
        (sum / y0.len() as f64).sqrt()
    }

    /// One ROS34PW2 step ([`System::step`]) with J the stiff columns' part of the Jacobian
    /// ([`System::stiff_columns`]), each a rank-one term u v^T (v^T y the column's variable,
    /// [`System::read`]), so that I - h gamma J is solved through the small matrix I - h
    /// gamma V^T U (Woodbury).
    fn stiff_step(
        &self,
        y: &[f64],
        k0: &[f64],
        h: f64,
        scale: &[f64],
        rtol: f64,
        columns: Vec<StiffColumn>,
    ) -> StepOut {
        let m = columns.len();
        // V^T U: column c's variable's rate under column d's accelerations.
        let mut small = DMatrix::<f64>::identity(m, m);
        for (c, sc) in columns.iter().enumerate() {
            for (d, sd) in columns.iter().enumerate() {
                small[(c, d)] -= h * rosenbrock::GAMMA * self.read_rate(&sd.u, sc);
            }
        }
        let mut lin = StiffLinear {
            sys: self,
            columns,
            lu: small.lu(),
            h,
            scratch: Forces::default(),
        };
        let (y1, e) = rosenbrock::step(&mut lin, y, k0, h);
        let mut k1 = vec![0.0; y.len()];
        let end = self.derivative(&y1, &mut k1);
        let err = self.error_norm(y, &y1, &e, scale, rtol);
        StepOut {
            y: y1,
            err,
            k: vec![k0.to_vec(), k1],
            end,
            stiff: true,
        }
    }
}

/// What a stiff column's variable is ([`System::read`]).
#[derive(Debug, Clone, Copy)]
enum StiffAxis {
    /// The slip across a sliding contact's direction, along this unit vector of its tangent
    /// plane: its friction -mu f s / |s| turns with it at -mu f / |s| per m/s.
    Across(Vector3<f64>),
    /// The closing rate of a contact whose damped normal force is stiff.
    Closing,
}

/// A stiff column of the Jacobian over one step ([`System::stiff_columns`]).
struct StiffColumn {
    /// The contact (index in the set).
    k: usize,
    axis: StiffAxis,
    /// The column per body: the accelerations (m/s^2, rad/s^2) of the contact's forces'
    /// change per unit of the axis's variable, the stuck contacts answering.
    u: Vec<[Vector3<f64>; 2]>,
    /// The same column's rows of the contacts' impulses: per contact, the change (per unit
    /// of the variable) of its normal force (N) and friction (N), at this contact and at
    /// each stuck contact that answers it. Without them the step would move the velocities
    /// without the impulses that moved them, and a ball on the cloth would gain momentum no
    /// impulse accounts for.
    impulses: Vec<(usize, f64, Vector3<f64>, f64)>,
}

/// The stiff columns' linearisation over one ROS34PW2 step.
struct StiffLinear<'s, 'a> {
    sys: &'s System<'a>,
    columns: Vec<StiffColumn>,
    /// LU of I - h gamma V^T U.
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    h: f64,
    /// The stages' forces (not kept).
    scratch: Forces,
}

impl StiffLinear<'_, '_> {
    /// out += scale U z, z per stiff column.
    fn add_columns(&self, z: &[f64], scale: f64, out: &mut [f64]) {
        let nb = self.sys.nb();
        for (s, &zs) in self.columns.iter().zip(z) {
            if zs == 0.0 {
                continue;
            }
            for (b, a) in s.u.iter().enumerate() {
                for k in 0..3 {
                    out[3 * nb + 3 * b + k] += scale * zs * a[0][k];
                    out[6 * nb + 3 * b + k] += scale * zs * a[1][k];
                }
            }
            for &(c, normal, fr, heat) in &s.impulses {
                let o = PER_BALL * nb + self.sys.pc * c;
                out[o] += scale * zs * normal;
                out[o + 4] += scale * zs * heat;
                for k in 0..3 {
                    out[o + 1 + k] += scale * zs * fr[k];
                }
            }
        }
    }
}

impl rosenbrock::Linearised for StiffLinear<'_, '_> {
    fn rhs(&mut self, y: &[f64], out: &mut [f64]) {
        self.sys.derivative_into(y, out, &mut self.scratch);
    }
    fn add_jacobian_times(&self, x: &[f64], scale: f64, out: &mut [f64]) {
        let z: Vec<f64> = self.columns.iter().map(|s| self.sys.read(x, s)).collect();
        self.add_columns(&z, scale, out);
    }
    fn solve(&self, x: &mut [f64]) {
        // x + h gamma U (I - h gamma V^T U)^(-1) V^T x.
        let z = DVector::from_iterator(
            self.columns.len(),
            self.columns.iter().map(|s| self.sys.read(x, s)),
        );
        match self.lu.solve(&z) {
            Some(w) => self.add_columns(w.as_slice(), self.h * rosenbrock::GAMMA, x),
            // Singular: the step's error is not finite, and it is rejected.
            None => x.fill(f64::NAN),
        }
    }
}

/// One step: the new state, its error norm, the stage derivatives (Dormand-Prince's seven,
/// the last one at the new state; a ROS34PW2 step's, `stiff`, the two at its ends) and the
/// forces at the new state (those of the last stage: the events, the loading check and the
/// check after the step read them instead of evaluating them again).
struct StepOut {
    y: Vec<f64>,
    err: f64,
    k: Vec<Vec<f64>>,
    end: Forces,
    /// A ROS34PW2 step: `k` holds the derivatives at its two ends only, its continuous
    /// extension is the cubic Hermite interpolant (order 3, as the step), and its step
    /// control [`STIFF_CONTROL`].
    stiff: bool,
}

/// Coefficients of the continuous extension of Dormand-Prince 5(4) (order 4), on stages
/// 1, 3, 4, 5, 6, 7: E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential
/// Equations I, 2nd ed., Springer (1993), section II.6 (the code DOPRI5's CONTD5).
const DOPRI5_DENSE: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// The continuous extension of one step from `y0` (size `h`): per component, the
/// coefficients of y(theta) = y0 + theta (dy + theta1 (bspl + theta (r4 + theta1 r5))),
/// theta = x / h, theta1 = 1 - theta. With r5 = 0 it is the cubic Hermite interpolant of
/// the step's ends and their derivatives (a ROS34PW2 step's).
struct Dense {
    h: f64,
    c: Vec<[f64; 5]>,
}

impl Dense {
    fn new(y0: &[f64], s: &StepOut, h: f64) -> Dense {
        let c = (0..y0.len())
            .map(|i| {
                let dy = s.y[i] - y0[i];
                let bspl = h * s.k[0][i] - dy;
                let r4 = dy - h * s.k[s.k.len() - 1][i] - bspl;
                if s.stiff {
                    return [y0[i], dy, bspl, r4, 0.0];
                }
                let r5: f64 = h * s
                    .k
                    .iter()
                    .zip(DOPRI5_DENSE)
                    .map(|(k, d)| d * k[i])
                    .sum::<f64>();
                [y0[i], dy, bspl, r4, r5]
            })
            .collect();
        Dense { h, c }
    }

    /// Components `range` of the state at `x` (s from the step's start) into `out`.
    fn fill(&self, x: f64, range: std::ops::Range<usize>, out: &mut [f64]) {
        let th = x / self.h;
        let th1 = 1.0 - th;
        for i in range {
            let [y0, dy, bspl, r4, r5] = self.c[i];
            out[i] = y0 + th * (dy + th1 * (bspl + th * (r4 + th1 * r5)));
        }
    }
}

/// A crossing found at the end of a step: what happened, and its event function (positive
/// before, <= 0 once it happened).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    /// Contact (index in the set) stops sliding.
    Stop(usize),
    /// Contact (index) opens: the law's separation function reaches 0.
    Open(usize),
    /// Stuck contact (index) slips: the friction it needs to stick reaches mu f; event
    /// function mu f - |F|.
    Release(usize),
    /// Pair (i, j) not in the set closes.
    Close(usize, usize),
    /// Sticking spring (index) reaches Coulomb's cap: event function mu f - |S|.
    SpringSlide(usize),
    /// Sliding spring (index) would leave the cap by sticking: event function
    /// S'_stick . e - (mu f)'.
    SpringStick(usize),
}

/// Resolves `cluster` with `settings`.
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::*;
/// // Two identical balls head on, elastic Hertz, no friction: they exchange velocities.
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let at = |x: f64, v: f64| ClusterBall {
///     ball,
///     position: Vector3::new(x, 0.0, 0.0),
///     velocity: Vector3::new(v, 0.0, 0.0),
///     spin: Vector3::zeros(),
/// };
/// let balls = vec![at(-0.028575, 1.0), at(0.028575, 0.0)];
/// let cluster = Cluster::new(balls, ClusterLaw::Same(ContactLaw::elastic(4.5e8)?), 0.0)?;
/// let out = resolve_cluster(&cluster, &ClusterSettings::default())?;
/// assert!(out.balls[0].velocity.norm() < 1e-7);
/// assert!((out.balls[1].velocity.x - 1.0).abs() < 1e-7);
/// assert_eq!(out.contacts.len(), 1);
/// # Ok::<(), billiard_contact::Error>(())
/// ```
pub fn resolve_cluster(
    cluster: &Cluster,
    settings: &ClusterSettings,
) -> Result<ClusterOutcome, Error> {
    run_cluster(cluster, settings, None)
}

/// [`resolve_cluster`] reporting its state to `trace` as it goes
/// (docs/formats.md#the-cluster-trace): the outcome is the same as without a trace, the
/// rows' forces being evaluated apart from the run's (they are not counted in its
/// evaluations).
///
/// ```
/// use billiard_contact::nalgebra::Vector3;
/// use billiard_contact::*;
/// let ball = Ball::new(0.17, 0.028575, 0.4)?;
/// let at = |x: f64, v: f64| ClusterBall {
///     ball,
///     position: Vector3::new(x, 0.0, 0.0),
///     velocity: Vector3::new(v, 0.0, 0.0),
///     spin: Vector3::zeros(),
/// };
/// let balls = vec![at(-0.028575, 1.0), at(0.028575, 0.0)];
/// let cluster = Cluster::new(balls, ClusterLaw::Same(ContactLaw::elastic(4.5e8)?), 0.0)?;
/// let mut peak: f64 = 0.0;
/// let mut sink = |row: &ClusterTraceRow<'_>| {
///     for c in row.contacts {
///         peak = peak.max(c.normal_force);
///     }
/// };
/// let trace = ClusterTrace { sampling: ClusterSampling::Steps, sink: &mut sink };
/// let out = resolve_cluster_traced(&cluster, &ClusterSettings::default(), trace)?;
/// assert_eq!(out, resolve_cluster(&cluster, &ClusterSettings::default())?);
/// assert!(peak > 100.0); // N: two pool balls at 1 m/s press with about 1.1 kN
/// # Ok::<(), billiard_contact::Error>(())
/// ```
pub fn resolve_cluster_traced(
    cluster: &Cluster,
    settings: &ClusterSettings,
    trace: ClusterTrace<'_>,
) -> Result<ClusterOutcome, Error> {
    run_cluster(cluster, settings, Some(trace))
}

/// The run of [`resolve_cluster`], with a trace or without.
fn run_cluster(
    cluster: &Cluster,
    settings: &ClusterSettings,
    trace: Option<ClusterTrace<'_>>,
) -> Result<ClusterOutcome, Error> {
    let rtol = settings.rtol;
    if !(rtol.is_finite() && (1e-14..=1e-2).contains(&rtol)) {
        return Err(Error::invalid(
            "cluster.rtol",
            rtol,
            "in [1e-14, 1e-2] (relative tolerance of the step control)",
        ));
    }
    let nballs = cluster.balls.len();
    // The cloth is the last body: immovable (infinite mass and inertia), of radius 0, its
    // centre on its surface.
    let mut bodies: Vec<Body> = cluster
        .balls
        .iter()
        .map(|b| Body {
            m: b.ball.mass(),
            r: b.ball.radius(),
            inertia: b.ball.inertia(),
        })
        .collect();
    if cluster.cloth.is_some() {
        bodies.push(Body {
            m: f64::INFINITY,
            r: 0.0,
            inertia: f64::INFINITY,
        });
    }
    let nb = bodies.len();
    // Positions from the balls' centroid, so that compressions keep their digits.
    let centre = cluster
        .balls
        .iter()
        .fold(Vector3::zeros(), |s, b| s + b.position)
        / nballs as f64;
    let mut y = vec![0.0; PER_BALL * nb];
    if let Some(cloth) = cluster.cloth {
        y[3 * nballs + 2] = cloth.height - centre.z;
    }
    for (b, ball) in cluster.balls.iter().enumerate() {
        for k in 0..3 {
            y[3 * b + k] = ball.position[k] - centre[k];
            y[3 * nb + 3 * b + k] = ball.velocity[k];
            y[6 * nb + 3 * b + k] = ball.spin[k];
        }
    }
    // Natural scales: the largest relative speed; the contact time of the softest, heaviest
    // pair at it, and the elastic compression of the stiffest, lightest (the positions'
    // error is judged on it: on the softest pair's, a rubber ball's 40 times a steel pair's,
    // eight balls of rubber, resin and steel at rtol 1e-4 ended 1.1e-1 of their energy off
    // its balance; found by fuzzing).
    let mut v_ref: f64 = 0.0;
    for i in 0..nballs {
        for j in i + 1..nballs {
            let (a, b) = (&cluster.balls[i], &cluster.balls[j]);
            v_ref = v_ref.max((a.velocity - b.velocity).norm());
            v_ref = v_ref.max(a.spin.norm() * bodies[i].r + b.spin.norm() * bodies[j].r);
        }
    }
    let (mut delta0, mut tau0) = (f64::INFINITY, 0.0f64);
    for i in 0..nballs {
        for j in i + 1..nballs {
            let m = bodies[i].m * bodies[j].m / (bodies[i].m + bodies[j].m);
            let k = cluster.laws[pair_index(nballs, i, j)].stiffness();
            let (d, t) = elastic_impact(k, m, v_ref);
            delta0 = delta0.min(d);
            tau0 = tau0.max(t);
        }
    }
    // A ball's impact on the cloth at that speed (its time only: the cloth's compression
    // is mostly the weight's preload, on the scale of the balls' pairs).
    for (law, body) in cluster.cloth_laws.iter().zip(&bodies) {
        tau0 = tau0.max(elastic_impact(law.stiffness(), body.m, v_ref).1);
    }
    let balls_only = &bodies[..nballs];
    let m_min = balls_only.iter().map(|b| b.m).fold(f64::INFINITY, f64::min);
    let r_min = balls_only.iter().map(|b| b.r).fold(f64::INFINITY, f64::min);
    let x_max = (0..nballs)
        .map(|b| pos(&y, b).norm() + bodies[b].r)
        .fold(0.0, f64::max);
    let k_max = cluster
        .laws
        .iter()
        .chain(&cluster.cloth_laws)
        .map(|l| l.stiffness())
        .fold(0.0, f64::max);
    let round_delta = ROUNDING_ULPS * f64::EPSILON * x_max;
    let round_force = k_max * round_delta.powf(1.5);
    let v_max = (0..nballs)
        .map(|b| pos(&y, nb + b).norm())
        .fold(0.0, f64::max);
    let round_speed = ROUNDING_ULPS * f64::EPSILON * (v_max + v_ref);
    let mut run = Run {
        cluster,
        bodies: &bodies,
        settings: *settings,
        v_ref,
        delta0,
        tau0,
        m_min,
        r_min,
        round_force,
        round_delta,
        round_speed,
        t: 0.0,
        y,
        active: Vec::new(),
        paired: vec![false; nb * nb],
        records: Vec::new(),
        cloth_records: Vec::new(),
        first_touch: None,
        stats: ClusterStats::default(),
        changes: 0,
        centre,
        held: Vec::new(),
        flips: Vec::new(),
        implicit: false,
        stick_lu: RefCell::new(StickLu::default()),
        closings: 0,
        stiff_next: None,
        trace: trace.map(|t| Tracer {
            sampling: t.sampling,
            sink: t.sink,
            next: 0,
            last: None,
            opened: Vec::new(),
        }),
    };
    let stop = run.go()?;
    // The contacts still in the set are recorded as they stand: on the cloth its contacts
    // at any end, and in a run that stopped (work bound, step too small) every contact, so
    // that the outcome's impulses account for the balls' momentum up to the stop (on the
    // cloth they are the momentum from outside; left out at a stop they broke its balance
    // by 0.41 N s: four rubber balls at the work bound, found by fuzzing).
    let pressing: Vec<usize> = run
        .active
        .iter()
        .filter(|c| c.j == nballs)
        .map(|c| c.i)
        .collect();
    for k in (0..run.active.len()).rev() {
        run.open(k);
    }
    run.below_the_bed(&pressing);
    let y = &run.y;
    let balls = (0..nballs)
        .map(|b| BallOut {
            position: pos(y, b) + centre,
            velocity: pos(y, nb + b),
            spin: pos(y, 2 * nb + b),
        })
        .collect();
    Ok(ClusterOutcome {
        balls,
        contacts: run.records,
        cloth: run.cloth_records,
        stop,
        time: run.t,
        first_touch: run.first_touch.unwrap_or(run.t),
        stats: run.stats,
    })
}

/// The state of a run.
struct Run<'a> {
    cluster: &'a Cluster,
    bodies: &'a [Body],
    settings: ClusterSettings,
    v_ref: f64,
    delta0: f64,
    tau0: f64,
    m_min: f64,
    r_min: f64,
    /// The force (N) of a compression lost in the positions' rounding ([`ROUNDING_ULPS`]).
    round_force: f64,
    /// That compression (m).
    round_delta: f64,
    /// The velocities' rounding (m/s, [`ROUNDING_ULPS`] of the largest speed).
    round_speed: f64,
    t: f64,
    /// Balls (9 per ball), then the open contacts' accumulators (5 each).
    y: Vec<f64>,
    active: Vec<Active>,
    /// Whether pair (i, j) is in `active`, at i * bodies + j (the per-step scans of every
    /// pair read it: a search of the set per pair was a tenth of a 16-ball break's time).
    paired: Vec<bool>,
    records: Vec<ContactRecord>,
    /// The cloth's contacts that carried force (pair (ball, number of balls)).
    cloth_records: Vec<ContactRecord>,
    /// Time (s) two balls first touched while approaching, once they have.
    first_touch: Option<f64>,
    stats: ClusterStats,
    /// Changes of the contact set or of a contact's mode so far: a derivative kept from a
    /// step is reused only at the same count.
    changes: u64,
    /// The balls' centroid at the start (m): the state's positions are measured from it.
    centre: Vector3<f64>,
    /// Per contact of the set, whether a frozen step holds its friction along its seed: the
    /// contacts whose slips reversed inside the step (`flips`).
    held: Vec<bool>,
    /// Per contact of the set, whether a stage of the step saw its slip reversed.
    flips: Vec<Cell<bool>>,
    /// Whether the step may be ROS34PW2's (`System::step`).
    implicit: bool,
    /// The stick solve's last factorization ([`StickLu`]).
    stick_lu: RefCell<StickLu>,
    /// Closings so far: the next contact's [`Active::id`].
    closings: u64,
    /// ROS34PW2's proposal (s) after its last step, and the explicit steps taken since
    /// because it was short ([`STIFF_SLIP`], [`STIFF_RETRY`]).
    stiff_next: Option<(usize, f64)>,
    /// Where the trace rows go, if anywhere.
    trace: Option<Tracer<'a>>,
}

/// A trace in progress.
struct Tracer<'a> {
    sampling: ClusterSampling<'a>,
    sink: &'a mut dyn FnMut(&ClusterTraceRow<'_>),
    /// Index of the next sample time ([`ClusterSampling::Times`]).
    next: usize,
    /// Time (s) of the last row ([`ClusterSampling::Steps`]).
    last: Option<f64>,
    /// The contacts opened since the last row.
    opened: Vec<ContactRecord>,
}

impl Run<'_> {
    /// The bodies: the balls, then the cloth if there is one.
    fn nb(&self) -> usize {
        self.bodies.len()
    }

    /// The balls; also the cloth's body index.
    fn nballs(&self) -> usize {
        self.cluster.balls.len()
    }

    /// Whether the contacts carry Mindlin's spring.
    fn mindlin(&self) -> bool {
        self.cluster.tangential == ClusterTangential::Mindlin
    }

    /// Components of the state per contact.
    fn pc(&self) -> usize {
        if self.mindlin() {
            PER_SPRING_CONTACT
        } else {
            PER_CONTACT
        }
    }

    fn system(&self, frozen: bool) -> System<'_> {
        let mu = self.cluster.mu;
        System {
            bodies: self.bodies,
            active: &self.active,
            nballs: self.nballs(),
            gravity: self.cluster.cloth.map_or(0.0, |c| c.gravity),
            spring_mu: if mu < NEGLIGIBLE_MU { 0.0 } else { mu },
            pc: self.pc(),
            v_ref: self.v_ref,
            f_floor: self.f_floor(),
            frozen,
            held: &self.held,
            flips: &self.flips,
            implicit: self.implicit,
            stick_lu: &self.stick_lu,
            evaluations: Cell::new(0),
        }
    }

    /// Unmarks every contact's reversal (`flips`), one mark per contact of the set.
    fn clear_flips(&mut self) {
        self.flips.resize(self.active.len(), Cell::new(false));
        for f in &self.flips {
            f.set(false);
        }
    }

    /// The normal force (N) under which a contact does not press for the stick rule:
    /// [`PRESS_FLOOR`] of the impact's force scale, or the force of the positions' rounding.
    fn f_floor(&self) -> f64 {
        (PRESS_FLOOR * self.m_min * self.v_ref / self.tau0).max(self.round_force)
    }

    /// The normal speed (m/s) a spent contact can still give at most ([`Run::spent`]), and
    /// the closing speed below which a free run's flight ends ([`Run::fly`]): rtol of the
    /// reference speed over the number of balls.
    fn spent_speed(&self) -> f64 {
        self.settings.rtol * self.v_ref / self.nballs() as f64
    }

    /// The error scale (N) of a spring's force: it is at most mu f, so mu times the impact's
    /// force scale (the force scale itself without friction, where the spring stays 0).
    fn spring_scale(&self) -> f64 {
        let force = self.m_min * self.v_ref / self.tau0;
        if self.cluster.mu > 0.0 {
            force * self.cluster.mu.min(1.0)
        } else {
            force
        }
    }

    /// The error scale of every component.
    fn scale(&self) -> Vec<f64> {
        let nb = self.nb();
        let mut s = vec![self.delta0; 3 * nb];
        for b in 0..self.cluster.cloth_preloads.len() {
            s[3 * b + 2] = self.height_scale(b);
        }
        s.extend(std::iter::repeat_n(self.v_ref, 3 * nb));
        s.extend(std::iter::repeat_n(self.v_ref / self.r_min, 3 * nb));
        let mindlin = self.mindlin();
        let spring = self.spring_scale();
        for _ in &self.active {
            let p = self.m_min * self.v_ref;
            s.extend([p, p, p, p, p * self.v_ref]);
            if mindlin {
                s.extend([spring, spring]);
            }
        }
        s
    }

    /// Opens a contact between balls i < j (j the cloth's index: ball i on the cloth) at the
    /// current state. A cloth contact's compression counts the ball's static compression
    /// (`cloth_preloads`) at every closing, not only the first: the cloth is where a resting
    /// ball sits at its input height. Measured from the bare geometry after a ball's first
    /// hop, the cloth sank by that compression under a landing ball, which fell the extra
    /// 0.17 um: six balls on a steel cloth gained 1.1e-6 J that way (found by fuzzing).
    fn close(&mut self, i: usize, j: usize) {
        self.changes += 1;
        let (xi, xj) = (pos(&self.y, i), pos(&self.y, j));
        let on_cloth = j == self.nballs();
        let preload = if on_cloth {
            self.cluster.cloth_preloads[i]
        } else {
            0.0
        };
        if !on_cloth && self.first_touch.is_none() {
            let nb = self.nb();
            let closing = (pos(&self.y, nb + i) - pos(&self.y, nb + j)).dot(&(xj - xi));
            if closing > 0.0 {
                self.first_touch = Some(self.t);
            }
        }
        let n = if on_cloth {
            -Vector3::z()
        } else {
            (xj - xi).normalize()
        };
        // A mu below NEGLIGIBLE_MU is stepped as 0, as the pair kernel does: its friction, at
        // most mu P, is below the velocities' rounding, and a contact stuck at mu = 5e-324
        // carried 3e-5 N s of friction before its release (found by fuzzing).
        let mu = match self.cluster.cloth {
            Some(c) if on_cloth => c.mu,
            _ => self.cluster.mu,
        };
        let mu = if mu < NEGLIGIBLE_MU { 0.0 } else { mu };
        let a = if n.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let t0 = n.cross(&a).normalize();
        let t1 = n.cross(&t0);
        let c = Active {
            i,
            j,
            ri: self.bodies[i].r,
            rj: self.bodies[j].r,
            n,
            t: [t0, t1],
            law: if on_cloth {
                self.cluster.cloth_laws[i]
            } else {
                self.cluster.law(i, j)
            },
            mu,
            preload,
            k_t0: if self.mindlin() {
                self.cluster.shear[pair_index(self.nb(), i, j)]
            } else {
                0.0
            },
            mode: if self.mindlin() {
                Mode::SpringStick
            } else {
                Mode::Sliding
            },
            aligned: false,
            seed: t0,
            offset: Vector3::zeros(),
            loaded: false,
            start: self.t,
            stick_time: None,
            id: self.closings,
        };
        self.closings += 1;
        let nb = self.nb();
        self.paired[c.i * nb + c.j] = true;
        self.active.push(c);
        self.y.extend(std::iter::repeat_n(0.0, self.pc()));
        let k = self.active.len() - 1;
        if on_cloth && self.t > 0.0 && self.active[k].law.damping() != Damping::None {
            // A damped cloth contact that let go while the bed was compressed (`let_go`) can
            // close again while the ball is still below the bed's surface: the bed's spring
            // starts compressed, its (2/5) k delta^(5/2) out of nothing; booked against the
            // contact's heat, so that K_in = K_out + heat + held stays closed.
            let (d, _) = self.system(false).compression(&self.y, &self.active[k]);
            let stored = self.active[k].law.elastic_energy(d);
            let o = PER_BALL * self.nb() + self.pc() * k + 4;
            self.y[o] = -stored;
        }
        if self.mindlin() {
            return;
        }
        let sys = self.system(false);
        let s = sys.slip(&self.y, &self.active[k]);
        let sn = s.norm();
        // The cloth's contacts keep the stick rule whatever `stick` says of the balls'.
        let stick = self.settings.stick || on_cloth;
        let stuck = self.active[k].mu > 0.0 && stick && sn <= SLIP_FLOOR * self.v_ref;
        let c = &mut self.active[k];
        if sn > 0.0 {
            c.seed = s / sn;
        }
        if stuck {
            c.mode = Mode::Stuck;
            c.stick_time = Some(0.0);
        }
    }

    /// Removes contact `k`, writing its record if it carried force. An elastic ball pair's
    /// energy at its compression now, (2/5) k delta^(5/2), is not given back to the balls:
    /// it is added to the pair's heat, whose rate is friction's alone (`derivative`; a run
    /// that stopped records its pairs as they stand, and a pair opens within the
    /// tolerance of zero compression).
    fn open(&mut self, k: usize) {
        self.changes += 1;
        let c = &self.active[k];
        if c.j != self.nballs() && c.law.damping() == Damping::None {
            let (d, _) = self.system(false).compression(&self.y, &self.active[k]);
            let left = self.active[k].law.elastic_energy(d);
            let o = PER_BALL * self.nb() + self.pc() * k + 4;
            self.y[o] += left;
        }
        let c = self.active.remove(k);
        let nb = self.nb();
        self.paired[c.i * nb + c.j] = false;
        let o = PER_BALL * nb + self.pc() * k;
        let acc: Vec<f64> = self.y.drain(o..o + self.pc()).collect();
        let record = ContactRecord {
            pair: (c.i, c.j),
            normal: c.n,
            normal_impulse: acc[0],
            friction_impulse: Vector3::new(acc[1], acc[2], acc[3]),
            start: c.start,
            duration: self.t - c.start,
            heat: acc[4],
            stick_time: c.stick_time,
        };
        if let Some(tracer) = self.trace.as_mut() {
            tracer.opened.push(record);
        }
        if acc[0] > RECORD_FLOOR * self.m_min * self.v_ref {
            if c.j == self.nballs() {
                self.cloth_records.push(record);
            } else {
                self.records.push(record);
            }
        }
    }

    /// At the end, each ball off the cloth (not among `pressing`) whose centre is still
    /// below the bed's undeformed surface: a damped cloth contact let go there ([`Run::let_go`],
    /// the bed's elastic energy counted as heat), but what the cloth holds is read off the
    /// geometry ([`ClusterOutcome::cloth_held`]), which counts (2/5) k delta^(5/2) at that
    /// depth again: taken off that ball's last cloth contact's heat, as a closing there
    /// takes it (`close`). (Found on balls pressed in by their neighbours' friction: a
    /// Kuwabara-Kono bed, gamma 1e-4 s, hopping balls 7.1e-4 J past the balance.)
    fn below_the_bed(&mut self, pressing: &[usize]) {
        let cloth = self.nballs();
        for i in 0..cloth {
            let law = match self.cluster.cloth_laws.get(i) {
                Some(l) if l.damping() != Damping::None && !pressing.contains(&i) => *l,
                _ => continue,
            };
            let d = self.bodies[i].r - (pos(&self.y, i).z - pos(&self.y, cloth).z)
                + self.cluster.cloth_preloads[i];
            if d <= 0.0 {
                continue;
            }
            if let Some(r) = self.cloth_records.iter_mut().rev().find(|r| r.pair.0 == i) {
                r.heat -= law.elastic_energy(d);
            }
        }
    }

    /// Contact `k` opens at its separation function's zero: a damped cloth contact
    /// (Kuwabara-Kono) lets go while the bed is still compressed, and its elastic energy
    /// then, (2/5) k delta^(5/2), is not returned to the ball: it counts as the contact's
    /// heat (a ball pair's heat, the whole normal work, holds it already; an elastic
    /// pair's is added as it opens: `open`).
    fn let_go(&mut self, k: usize) {
        let c = &self.active[k];
        if c.j == self.nballs() && c.law.damping() != Damping::None {
            let (d, _) = self.system(false).compression(&self.y, c);
            let left = c.law.elastic_energy(d);
            let o = PER_BALL * self.nb() + self.pc() * k + 4;
            self.y[o] += left;
        }
    }

    /// The error scale (m) of contact `c`'s separation function: the law's separation
    /// function of the error scales of its compression (its balls' positions', the
    /// height's on the cloth: [`Run::scale`]) and of the compression's rate (the reference
    /// speed): delta0 + gamma v_ref under Kuwabara-Kono, delta0 otherwise.
    fn open_scale(&self, c: &Active) -> f64 {
        let d = if c.j == self.nballs() {
            self.height_scale(c.i)
        } else {
            self.delta0
        };
        c.law.separation(d, self.v_ref)
    }

    /// Stops each hovering contact (its slip steady within a factor 2 over the step `h`,
    /// [`keeps_its_size`], and pressed) whose slip is within rtol of the reference speed: it
    /// sticks (without the stick rule, its friction goes on along its direction), that
    /// slip its offset. Left sliding, such a slip can sit just above the
    /// floor without crossing zero, its direction relaxing at 4e15 /s: the 16-ball break
    /// with the cue ball 1e-12 m/s off the plane held a contact at 9.1e-13 m/s under 1,559 N,
    /// its steps at 4.7e-15 s, to the work bound at rtol 1e-11 and 1e-12 (it now separates
    /// in 11,225 and 38,086 steps). A contact that needs more than mu f is released again
    /// as any stuck contact is. Returns whether any contact stopped.
    fn stop_hovering(&mut self, f0: &Forces, h: f64) -> bool {
        let tol = self.settings.rtol * self.v_ref;
        let f_floor = self.f_floor();
        let mut stopped = Vec::new();
        for (k, (c, &(f, _, s, _, _))) in self.active.iter().zip(&f0.contact).enumerate() {
            if c.mode != Mode::Sliding || f <= f_floor || c.mu <= 0.0 {
                continue;
            }
            let sr = s - c.offset;
            if sr.norm() <= tol && keeps_its_size(sr, slip_rate(&f0.acc, c), h) {
                stopped.push((k, s));
            }
        }
        let (t, cloth, stick) = (self.t, self.nballs(), self.settings.stick);
        for &(k, s) in &stopped {
            self.changes += 1;
            let c = &mut self.active[k];
            // As a located stop: without the stick rule friction goes on along the
            // direction it slid in (the cloth's contacts keep the rule).
            c.mode = if stick || c.j == cloth {
                Mode::Stuck
            } else {
                Mode::Continued
            };
            c.offset = s;
            c.stick_time = Some(t - c.start);
        }
        !stopped.is_empty()
    }

    /// Steps as Coulomb's friction each sliding spring whose direction relaxes within half
    /// a step of `h` (s), as the pair kernel turns it (docs/tangential.md#stepping): |rate|
    /// h > [`ALIGN_TURNS`] |S| (forces `f0` at the step's start), the stick rate pointing
    /// outwards. On the cap the spring's direction relaxes towards -u (the slip's
    /// opposite, where its stick rate -k_t u + S delta' / (2 delta) lies along S) at
    /// |rate| / |S|, about k_t |u| / (mu f): on a tiny cap far faster than the contacts
    /// move, and the explicit step cannot follow it (four Mindlin balls at 8.7 mm/s, mu
    /// 0.0017, caps of 1e-5 N turning at 4e9 /s took steps near 1.3e-9 s against a contact
    /// time of 1e-2 s, to the work bound; found by fuzzing). Such a spring is put on -u
    /// with its length and, through the step, its force is |S| along -u at every stage
    /// (`Active::aligned`), its length following the cap: the relaxed direction, which the
    /// step's error control sees through the slip. (The pair kernel keeps the direction of
    /// the step's start instead, an error the control does not see: kept so here, the four
    /// balls' outgoing spins were 1.3e-6 and 5.4e-7 rad/s off at rtol 1e-8 and 1e-10, first
    /// order in the step; followed, 7.5e-10 rad/s at 1e-8.) Returns whether the state or
    /// any contact's flag changed (the derivative at the step's start is then stale).
    fn align(&mut self, f0: &Forces, h: f64) -> bool {
        if !self
            .active
            .iter()
            .any(|c| c.mode == Mode::SpringSlide || c.aligned)
        {
            return false;
        }
        let sys = self.system(false);
        let mut turned = Vec::new();
        let mut flags = Vec::with_capacity(self.active.len());
        for (k, c) in self.active.iter().enumerate() {
            let mut aligned = false;
            if c.mode == Mode::SpringSlide && sys.spring_mu > 0.0 {
                let (sv, _, r, _) = sys.spring_rates(&self.y, &f0.acc, k);
                let s = sv[0].hypot(sv[1]);
                let rn = r[0].hypot(r[1]);
                if s > 0.0
                    && r[0] * sv[0] + r[1] * sv[1] > 0.0
                    && rn * h > ALIGN_TURNS * s
                    && rn.is_finite()
                {
                    let u = in_basis(c, &sys.slip(&self.y, c));
                    if u[0] != 0.0 || u[1] != 0.0 {
                        turned.push((spring_index(self.nb(), sys.pc, k), against_slip(sv, u)));
                        aligned = true;
                    }
                }
            }
            flags.push(aligned);
        }
        let mut changed = false;
        for (c, a) in self.active.iter_mut().zip(flags) {
            changed |= c.aligned != a;
            c.aligned = a;
        }
        for (o, v) in turned {
            changed |= self.y[o] != v[0] || self.y[o + 1] != v[1];
            self.y[o] = v[0];
            self.y[o + 1] = v[1];
        }
        changed
    }

    /// Puts each aligned spring on -u at the current state, its force there
    /// ([`Run::align`]): the step's last stage applied it so, and the next step or mode
    /// decision reads the spring.
    fn settle_aligned(&mut self) {
        let (nb, pc) = (self.nb(), self.pc());
        let sys = self.system(false);
        let turned: Vec<(usize, [f64; 2])> = self
            .active
            .iter()
            .enumerate()
            .filter(|(_, c)| c.aligned && c.mode.spring())
            .map(|(k, c)| {
                let o = spring_index(nb, pc, k);
                let u = in_basis(c, &sys.slip(&self.y, c));
                (o, against_slip([self.y[o], self.y[o + 1]], u))
            })
            .collect();
        for (o, v) in turned {
            self.y[o] = v[0];
            self.y[o + 1] = v[1];
        }
    }

    /// The error scale (m) of ball `b`'s height on the cloth: the compression scale, or its
    /// static compression of the cloth when that is the smaller. The cloth's spring holds
    /// its weight there, and stepped on the balls' compression (often far larger) a
    /// landing's error in the cloth's store made three balls at rtol 1e-4 end 0.5 of their
    /// energy off its balance (found by fuzzing).
    fn height_scale(&self, b: usize) -> f64 {
        match self.cluster.cloth_preloads.get(b) {
            Some(&ds) if ds > 0.0 => self.delta0.min(ds),
            _ => self.delta0,
        }
    }

    /// Whether pair (i, j) is in the contact set.
    fn in_set(&self, i: usize, j: usize) -> bool {
        self.paired[i * self.nb() + j]
    }

    /// Closes the pairs not in the set that press (separation function >= 0 from the
    /// centres' distance) and approach. A contact opened at its located zero can sit a
    /// rounding past it (its frozen normal is not the line of centres): its closing event,
    /// which starts from separation < 0, would never see the crossing, and in a 16-ball
    /// break at rtol 1e-10 two balls of the rack passed through each other that way.
    fn close_pressing(&mut self) {
        let nb = self.nb();
        for i in 0..nb {
            for j in i + 1..nb {
                if self.in_set(i, j) || self.gap_function(&self.y, i, j) < 0.0 {
                    continue;
                }
                // Approaching faster than the grazing speed, as everywhere else: a pair that
                // touched exactly (delta = 0) and closed at 1.3e-245 m/s was dropped as quiet
                // and closed again here at every step, the steps growing to 1.5e11 s, an
                // 8-ball run to the work bound (found by fuzzing).
                if self.closing_speed(&self.y, i, j) > self.grazing() {
                    self.close(i, j);
                }
            }
        }
    }

    /// The speed (m/s) at which bodies `i` and `j` (a ball and the cloth when `j` is the
    /// number of balls) approach each other along their line of centres at state `y`.
    fn closing_speed(&self, y: &[f64], i: usize, j: usize) -> f64 {
        let nb = self.nb();
        if j == self.nballs() {
            return -pos(y, nb + i).z;
        }
        let p = pos(y, j) - pos(y, i);
        -p.dot(&(pos(y, nb + j) - pos(y, nb + i))) / p.norm()
    }

    /// The law's separation function of a pair not in the set, from its centres' distance,
    /// and never above the compression itself: a pair presses only when it overlaps. Under
    /// Kuwabara-Kono, delta + gamma delta' alone turns positive while an approaching pair is
    /// still apart (by gamma times its closing speed); the pair closed there, was dropped as
    /// apart by more than the touch tolerance and closed again at once: six balls without the
    /// stick rule did that a million times 5.6e-15 s apart.
    fn gap_function(&self, y: &[f64], i: usize, j: usize) -> f64 {
        let nb = self.nb();
        if j == self.nballs() {
            // Ball i over the cloth: its height above the cloth's level, the static
            // compression counted as in every cloth contact (`close`).
            let delta =
                self.bodies[i].r - (pos(y, i).z - pos(y, j).z) + self.cluster.cloth_preloads[i];
            let rate = -pos(y, nb + i).z;
            return self.cluster.cloth_laws[i]
                .separation(delta, rate)
                .min(delta);
        }
        let p = pos(y, j) - pos(y, i);
        let d = p.norm();
        let delta = self.bodies[i].r + self.bodies[j].r - d;
        let rate = -p.dot(&(pos(y, nb + j) - pos(y, nb + i))) / d;
        self.cluster.law(i, j).separation(delta, rate).min(delta)
    }

    /// The event function of `e` at state `y` (positive before the event).
    fn event_value(&self, sys: &System<'_>, y: &[f64], e: Event) -> f64 {
        match e {
            Event::Stop(k) => {
                let c = &self.active[k];
                (sys.slip(y, c) - c.offset).dot(&c.seed)
            }
            Event::Open(k) => {
                let c = &self.active[k];
                let (d, w) = sys.compression(y, c);
                c.law.separation(d, w)
            }
            Event::Close(i, j) => -self.gap_function(y, i, j),
            Event::Release(k) => {
                let fs = sys.forces(y);
                self.active[k].mu * fs.contact[k].0 - fs.need(k).norm()
            }
            Event::SpringSlide(k) => {
                let c = &self.active[k];
                let (d, w) = sys.compression(y, c);
                let s = sys.spring(y, k);
                sys.spring_mu * c.law.force(d, w) - (s[0] * s[0] + s[1] * s[1]).sqrt()
            }
            Event::SpringStick(k) => self.spring_turn(sys, y, &sys.forces(y), k).0,
        }
    }

    /// Of the sliding spring `k` at state `y` with forces `fs`: its turn
    /// ([`spring_turn_of`]).
    fn spring_turn(&self, sys: &System<'_>, y: &[f64], fs: &Forces, k: usize) -> (f64, f64) {
        let (s, _, stick, cap_rate) = sys.spring_rates(y, &fs.acc, k);
        spring_turn_of(s, stick, cap_rate)
    }

    /// The events crossed between `y0` and `y1`, whose forces (under `sys`) are `f0` and
    /// `f1`.
    fn crossings(
        &self,
        sys: &System<'_>,
        (y0, f0): (&[f64], &Forces),
        (y1, f1): (&[f64], &Forces),
    ) -> Vec<Event> {
        let mut out = Vec::new();
        if self.active.iter().any(|c| c.mode == Mode::Stuck) {
            // The friction each stuck contact needs against its bound, at both ends.
            for (k, c) in self.active.iter().enumerate() {
                let g = |x: &Forces| c.mu * x.contact[k].0 - x.need(k).norm();
                let (a, b) = (f0.contact[k].0, f1.contact[k].0);
                if c.mode == Mode::Stuck
                    && a > sys.f_floor
                    && b > sys.f_floor
                    && g(f0) > 0.0
                    && g(f1) <= 0.0
                {
                    out.push(Event::Release(k));
                }
            }
        }
        for (k, c) in self.active.iter().enumerate() {
            if c.mode.spring() && sys.spring_mu > 0.0 {
                let e = match c.mode {
                    Mode::SpringStick => Event::SpringSlide(k),
                    _ => Event::SpringStick(k),
                };
                let (d1, w1) = sys.compression(y1, c);
                // A sticking spring already on its cap (within the band) at the start was
                // kept sticking because its rate does not carry it past there; if it passes
                // the cap within the step, that is the rate's turn, not a crossing to locate
                // (it would be located at the start, to no end): the step stands and the
                // spring is put back on the cap after it. Located, three resin balls' first
                // touch (a cap of 1.7e-13 N) was crossed at 1e-17 of the step, again and
                // again, to the work bound.
                // Likewise a sliding spring whose stick rate turns back inside is located
                // only when it starts clear of that turn (within the band of its rates): a
                // four-ball Mindlin cluster at rtol 1e-7 located one at 5e-21 s of the step
                // start, again and again, to the work bound (found by fuzzing).
                // The turn read off the forces at both ends, as a release is.
                // A sticking spring that reaches its cap within the step while it stays
                // within the tolerance of its scale of the cap at both ends is not located
                // either: sticking past the cap by no more than that, it is put back on it
                // after the step. At a contact's onset a cap that grows about as fast as the
                // stick rate (4.2e-12 N, 3.84e-6 N/s against 4.30e-6 N/s) was crossed 1e-10
                // s into each step and left again after it: four Mindlin balls at rtol 1e-3
                // took 22,510 steps (22 now; found by fuzzing).
                let (g0, inside, g1) = match e {
                    Event::SpringSlide(_) => {
                        let (d0, w0) = sys.compression(y0, c);
                        let cap0 = sys.spring_mu * c.law.force(d0, w0).max(0.0);
                        let (g0, g1) = (self.event_value(sys, y0, e), self.event_value(sys, y1, e));
                        let tol = self.settings.rtol * self.spring_scale();
                        let within = g0 <= tol && -g1 <= tol;
                        (
                            g0,
                            if within {
                                f64::INFINITY
                            } else {
                                cap0 * SPRING_CAP_BAND
                            },
                            g1,
                        )
                    }
                    _ => {
                        let (g0, scale0) = self.spring_turn(sys, y0, f0, k);
                        (
                            g0,
                            scale0 * SPRING_CAP_BAND,
                            self.spring_turn(sys, y1, f1, k).0,
                        )
                    }
                };
                if c.law.force(d1, w1) > 0.0 && g0 > inside && g1 <= 0.0 {
                    out.push(e);
                }
            }
            if c.mode == Mode::Sliding && c.mu > 0.0 {
                // Not a contact pressed only by the positions' rounding (at most the force
                // floor), whose friction is rounding: an 8-ball run at rtol 1e-4 stopped such
                // a slip 9e-18 s into each step and released it after, to the work bound
                // (found by fuzzing).
                let e = Event::Stop(k);
                let loaded = c
                    .law
                    .force(sys.compression(y1, c).0, sys.compression(y1, c).1)
                    > sys.f_floor;
                if loaded
                    && self.event_value(sys, y0, e) > 0.0
                    && self.event_value(sys, y1, e) <= 0.0
                {
                    out.push(e);
                }
            }
            let e = Event::Open(k);
            let was = c.loaded
                || c.law
                    .force(sys.compression(y0, c).0, sys.compression(y0, c).1)
                    > 0.0;
            if was && self.event_value(sys, y0, e) > 0.0 && self.event_value(sys, y1, e) <= 0.0 {
                out.push(e);
            }
        }
        let nb = self.nb();
        for i in 0..nb {
            for j in i + 1..nb {
                if self.in_set(i, j) {
                    continue;
                }
                // The end first: most pairs are apart there. A pair that ends the step
                // overlapping by no more than the positions' rounding closes only if it
                // approaches there (faster than a grazing touch; if it does, and the step
                // ends first, `close_pressing` closes it at the next one's start): eight
                // slow balls at rtol 1e-3 had a pair touching to the rounding, separating at
                // 1.5e-17 m/s, closed at the start of a step of 0.42 s whose end put it 1
                // ulp into overlap; dropped as quiet, closed again, a million times at the
                // same instant (found by fuzzing).
                let e = Event::Close(i, j);
                let g1 = self.event_value(sys, y1, e);
                if g1 < 0.0
                    && self.event_value(sys, y0, e) >= 0.0
                    && (g1 < -self.round_delta || self.closing_speed(y1, i, j) > self.grazing())
                {
                    out.push(e);
                }
            }
        }
        out
    }

    /// The stuck contacts without normal force at the current state that press at the step's
    /// end (forces `fs` there) with a friction past mu f there, with that friction (N).
    fn loading_slips(&self, sys: &System<'_>, fs: &Forces) -> Vec<(usize, Vector3<f64>)> {
        let idle: Vec<usize> = (0..self.active.len())
            .filter(|&k| {
                let c = &self.active[k];
                let (d, w) = sys.compression(&self.y, c);
                c.mode == Mode::Stuck && c.law.force(d, w) <= sys.f_floor
            })
            .collect();
        if idle.iter().all(|&k| self.active[k].mu == 0.0) {
            return Vec::new();
        }
        idle.into_iter()
            .filter_map(|k| {
                let (f, fr) = (fs.contact[k].0, fs.need(k));
                let mu = self.active[k].mu;
                (mu > 0.0 && f > sys.f_floor && fr.norm() > mu * f * (1.0 + RELEASE_SLACK))
                    .then_some((k, fr))
            })
            .collect()
    }

    /// The time inside the step of the continuous extension `dense` from the current state
    /// (its end state `y1`) at which `e` happens, by regula falsi (Illinois) on the extension
    /// (order 4: its error is that of the step). Only the components the event reads are
    /// interpolated: the two balls' for a stop, an opening or a closing, all for a release.
    fn locate(&self, sys: &System<'_>, dense: &Dense, y1: &[f64], e: Event) -> f64 {
        let nb = self.nb();
        let balls = match e {
            Event::Stop(k) | Event::Open(k) => vec![self.active[k].i, self.active[k].j],
            Event::Close(i, j) => vec![i, j],
            Event::Release(_) | Event::SpringSlide(_) | Event::SpringStick(_) => (0..nb).collect(),
        };
        // A spring's event reads the springs too.
        let contacts = matches!(e, Event::SpringSlide(_) | Event::SpringStick(_));
        let mut lo = Bound {
            q: 0.0,
            g: self.event_value(sys, &self.y, e),
        };
        let mut hi = Bound {
            q: dense.h,
            g: self.event_value(sys, y1, e),
        };
        let mut side = Side::None;
        let mut yx = self.y.clone();
        for _ in 0..EVENT_TRIALS {
            if hi.q - lo.q <= EVENT_X_TOL * self.tau0 || hi.g == 0.0 {
                break;
            }
            let x = (lo.q + (hi.q - lo.q) * (lo.g / (lo.g - hi.g))).clamp(lo.q, hi.q);
            for &b in &balls {
                for part in 0..3 {
                    let o = part * 3 * nb + 3 * b;
                    dense.fill(x, o..o + 3, &mut yx);
                }
            }
            if contacts {
                dense.fill(x, PER_BALL * nb..yx.len(), &mut yx);
            }
            let g = self.event_value(sys, &yx, e);
            side = illinois_update(&mut lo, &mut hi, side, x, g);
        }
        hi.q
    }

    /// Sends the row of state `y` at time `t` (the contacts of the set with their forces,
    /// friction along the seeds when `frozen`) to the trace's sink.
    fn send_row(&mut self, t: f64, y: &[f64], frozen: bool) {
        let Some(mut tracer) = self.trace.take() else {
            return;
        };
        let nb = self.nb();
        let balls: Vec<BallOut> = (0..self.nballs())
            .map(|b| BallOut {
                position: pos(y, b) + self.centre,
                velocity: pos(y, nb + b),
                spin: pos(y, 2 * nb + b),
            })
            .collect();
        let contacts: Vec<ContactTrace> = if self.active.is_empty() {
            Vec::new()
        } else {
            // A system of its own: its evaluations are not the run's.
            let fs = self.system(frozen).forces(y);
            self.active
                .iter()
                .zip(&fs.contact)
                .enumerate()
                .map(|(k, (c, &(f, fr, sl, _, d)))| {
                    let o = PER_BALL * nb + self.pc() * k;
                    ContactTrace {
                        pair: (c.i, c.j),
                        start: c.start,
                        compression: d,
                        normal_force: f,
                        normal_impulse: y[o],
                        friction_force: fr,
                        friction_impulse: Vector3::new(y[o + 1], y[o + 2], y[o + 3]),
                        slip: sl,
                        stuck: matches!(c.mode, Mode::Stuck | Mode::SpringStick),
                        heat: y[o + 4],
                    }
                })
                .collect()
        };
        (tracer.sink)(&ClusterTraceRow {
            t,
            balls: &balls,
            contacts: &contacts,
            opened: &tracer.opened,
        });
        tracer.opened.clear();
        self.trace = Some(tracer);
    }

    /// The next sample time not yet written, if the trace takes samples.
    fn next_sample(&self) -> Option<f64> {
        match self.trace.as_ref()? {
            Tracer {
                sampling: ClusterSampling::Times(times),
                next,
                ..
            } => times.get(*next).copied(),
            _ => None,
        }
    }

    /// Marks the next sample time written.
    fn sample_done(&mut self) {
        if let Some(tracer) = self.trace.as_mut() {
            tracer.next += 1;
        }
    }

    /// Before a step from the current state: with [`ClusterSampling::Steps`], its row when
    /// it starts a segment (no row at this time yet); with samples, those due by now.
    fn trace_start(&mut self) {
        let Some(tracer) = self.trace.as_ref() else {
            return;
        };
        if tracer.sampling == ClusterSampling::Steps {
            if tracer.last.is_none_or(|l| l < self.t) {
                self.trace_step_row();
            }
            return;
        }
        while self.next_sample().is_some_and(|ts| ts <= self.t) {
            let y = std::mem::take(&mut self.y);
            self.send_row(self.t, &y, false);
            self.y = y;
            self.sample_done();
        }
    }

    /// The row of the current state, with [`ClusterSampling::Steps`].
    fn trace_step_row(&mut self) {
        let y = std::mem::take(&mut self.y);
        self.send_row(self.t, &y, false);
        self.y = y;
        if let Some(tracer) = self.trace.as_mut() {
            tracer.last = Some(self.t);
        }
    }

    /// After an accepted step from time `t0` to the current time (its continuous extension
    /// `dense`, when samples fall inside it; friction along the seeds when `frozen`), before
    /// the contacts that open at its end leave the set: its row, or the samples it covers.
    fn trace_step(&mut self, t0: f64, dense: Option<&Dense>, frozen: bool) {
        let Some(tracer) = self.trace.as_ref() else {
            return;
        };
        if tracer.sampling == ClusterSampling::Steps {
            self.trace_step_row();
            return;
        }
        let mut yx = Vec::new();
        while let Some(ts) = self.next_sample().filter(|&ts| ts <= self.t) {
            match dense {
                Some(dense) if ts < self.t => {
                    yx.resize(self.y.len(), 0.0);
                    dense.fill((ts - t0).max(0.0), 0..yx.len(), &mut yx);
                    self.send_row(ts, &yx, frozen);
                }
                _ => {
                    let y = std::mem::take(&mut self.y);
                    self.send_row(ts, &y, frozen);
                    self.y = y;
                }
            }
            self.sample_done();
        }
    }

    /// Whether a sample falls before the current time plus `h` (s): the step then needs its
    /// continuous extension.
    fn samples_within(&self, h: f64) -> bool {
        self.next_sample().is_some_and(|ts| ts < self.t + h)
    }

    /// The samples of a free flight from the current state to time `until` (s): the balls
    /// move at their velocities, no contact is in the set.
    fn trace_flight(&mut self, until: f64) {
        let nb = self.nb();
        let mut yx = Vec::new();
        while let Some(ts) = self.next_sample().filter(|&ts| ts <= until) {
            yx.clone_from(&self.y);
            let dt = ts - self.t;
            for k in 0..3 * nb {
                yx[k] += dt * yx[3 * nb + k];
            }
            self.send_row(ts, &yx, false);
            self.sample_done();
        }
    }

    /// The run: free flight to the next touch while no contact is in the set, steps with
    /// events while one is.
    fn go(&mut self) -> Result<StopReason, Error> {
        let nb = self.nballs();
        for i in 0..nb {
            for j in i + 1..nb {
                let p = pos(&self.y, j) - pos(&self.y, i);
                let d = self.bodies[i].r + self.bodies[j].r;
                if p.norm() - d <= CLUSTER_TOUCH_TOLERANCE * d {
                    self.close(i, j);
                }
            }
        }
        // Every ball rests on the cloth, pressing it with its weight.
        if self.cluster.cloth.is_some() {
            for i in 0..nb {
                self.close(i, nb);
            }
        }
        let mut h = FIRST_STEP * self.tau0;
        // The derivative at the current state and its forces, kept while the contacts' modes
        // stand (`changes`).
        let mut k0: Option<(u64, Vec<f64>, Forces)> = None;
        // Flights count as steps towards the bound: after a bounce (`bounce_spent`) a
        // flight closes the neighbour it set closing, in no time, without a step.
        let mut flights = 0;
        loop {
            if self.stats.steps + self.stats.rejected + flights >= CLUSTER_MAX_STEPS {
                return Ok(StopReason::WorkBound);
            }
            self.drop_quiet();
            self.close_pressing();
            if self.cluster.cloth.is_some() {
                // On the cloth the balls do not fly freely: the run steps on while a pair
                // presses or will touch (within the horizon once a pair has pressed), or a
                // ball pressed into the cloth (or lifted) will still leave it, and ends
                // otherwise, its cloth contacts recorded as they stand.
                let cloth = self.nballs();
                let horizon = if self.records.is_empty() {
                    f64::INFINITY
                } else {
                    CLOTH_HORIZON * self.tau0
                };
                if !self
                    .active
                    .iter()
                    .any(|c| c.j != cloth && !self.rounding_only(c))
                    && !self.touches_within(horizon)
                    && self.active.iter().all(|c| self.settled_on_cloth(c))
                {
                    // The cloth's contacts are recorded by `run_cluster`, as at any end.
                    self.trace_flight(f64::INFINITY);
                    return Ok(StopReason::Separated);
                }
            } else if self.active.is_empty() {
                flights += 1;
                if !self.fly() {
                    // Samples after the end: the balls fly apart.
                    self.trace_flight(f64::INFINITY);
                    return Ok(StopReason::Separated);
                }
                h = FIRST_STEP * self.tau0;
                k0 = None;
                continue;
            }
            if h < MIN_STEP * self.tau0 {
                return Ok(StopReason::StepTooSmall);
            }
            h = h.min(self.touch_bound());
            h = h.min(self.oscillation_bound());
            // The derivative at the current state and its forces, kept while the contacts'
            // modes stand (`changes`).
            let (mut d0, mut f0) = match k0.take() {
                Some((n, k, f)) if n == self.changes => (k, f),
                _ => {
                    let mut d = vec![0.0; self.y.len()];
                    let f = self.system(false).derivative(&self.y, &mut d);
                    self.stats.evaluations += 1;
                    (d, f)
                }
            };
            if self.stop_hovering(&f0, h) {
                f0 = self.system(false).derivative(&self.y, &mut d0);
                self.stats.evaluations += 1;
            }
            if self.align(&f0, h) {
                f0 = self.system(false).derivative(&self.y, &mut d0);
                self.stats.evaluations += 1;
            }
            let floor = SLIP_FLOOR * self.v_ref;
            let stiffest = self
                .active
                .iter()
                .zip(&f0.contact)
                .flat_map(|(c, &(f, _, s, _, d))| {
                    let normal = damping_stiffness(self.bodies, c, d, f).map(|x| x.1);
                    let slip = (c.mode == Mode::Sliding)
                        .then(|| {
                            let rate = slip_rate(&f0.acc, c);
                            direction_stiffness(self.bodies, c, f, s - c.offset, rate, h, floor)
                        })
                        .flatten();
                    normal.into_iter().chain(slip)
                })
                .reduce(f64::max);
            // The stiffest sliding direction or damped normal force over this step, and the
            // method it takes ([`STIFF_SLIP`]).
            self.implicit = false;
            if let Some(lambda) = stiffest {
                let h_s = STIFF_SLIP / lambda;
                if h > h_s {
                    match self.stiff_next {
                        Some((n, hw)) if n < STIFF_RETRY && hw < h_s => {
                            self.stiff_next = Some((n + 1, hw));
                        }
                        _ => self.implicit = true,
                    }
                }
            }
            self.trace_start();
            // Each sliding contact's direction at the start of the step.
            {
                let sys = self.system(false);
                let seeds: Vec<Option<Vector3<f64>>> = self
                    .active
                    .iter()
                    .map(|c| {
                        let s = sys.slip(&self.y, c) - c.offset;
                        (s.norm() > SLIP_FLOOR * self.v_ref).then(|| s.normalize())
                    })
                    .collect();
                for (c, s) in self.active.iter_mut().zip(seeds) {
                    if let (Mode::Sliding, Some(s)) = (c.mode, s) {
                        c.seed = s;
                    }
                }
            }
            let scale = self.scale();
            self.clear_flips();
            let sys = self.system(false);
            let mut out = sys.step(&self.y, &d0, h, &scale, self.settings.rtol);
            let mut frozen = false;
            let mut evals = sys.evaluations.get();
            let reversed = self.flips.iter().any(Cell::get);
            let mut events = Vec::new();
            if reversed && out.err.is_finite() {
                // A slip reversed inside the step: redo it with the friction of each contact
                // whose slip reversed held along its direction at the step's start (as two
                // balls do), so that its stop is a clean crossing; a contact that reverses in
                // the redone step is held too, and the step redone again. Taken when it
                // crosses a stop or another event within the tolerance, or when the free step
                // fails the tolerance and each held contact ends the step along its held
                // direction or within the stop's residue of rest (`held_fits`): a contact
                // released at its bound whose slip first ran back, 4e-9 m/s against its
                // direction, before its growing need carried it forward; stepped free, the
                // flip was chased down to steps of 1e-8 s and one was taken whose error
                // estimate (of first order there) let a kick of 3.8e-5 m/s through, the
                // 16-ball break 1.3e-6 of the cue speed off at rtol 1e-8 instead of 9e-8.
                // Otherwise the reversal was one a stage saw but the step does not end in (or
                // a slip at the floor's rounding whose friction is nothing), and the step is
                // judged as it came. The other sliding contacts follow their slips: held as well, a slip
                // that turns inside a long located step was held off its direction (the
                // rolling break at rtol 1e-7: 1.3e-5 s through a stop elsewhere turned
                // contact (4, 7)'s slip by 60 degrees, 3.9e-3 m/s off).
                self.held.clear();
                self.held.extend(self.flips.iter().map(Cell::get));
                let mut df = vec![0.0; self.y.len()];
                for _ in 0..=self.active.len() {
                    self.clear_flips();
                    let fsys = self.system(true);
                    let ff = fsys.derivative(&self.y, &mut df);
                    let fout = fsys.step(&self.y, &df, h, &scale, self.settings.rtol);
                    evals += fsys.evaluations.get();
                    let more = self
                        .flips
                        .iter()
                        .zip(&self.held)
                        .any(|(f, &h)| f.get() && !h);
                    if more && fout.err.is_finite() {
                        for (h, f) in self.held.iter_mut().zip(&self.flips) {
                            *h |= f.get();
                        }
                        continue;
                    }
                    if fout.err <= 1.0 {
                        let ev = self.crossings(&fsys, (&self.y, &ff), (&fout.y, &fout.end));
                        if !ev.is_empty() {
                            (out, frozen, events) = (fout, true, ev);
                        } else if (out.err > 1.0 || !out.err.is_finite())
                            && self.held_fits(&fsys, &fout.y, h)
                        {
                            (out, frozen) = (fout, true);
                        }
                    } else if out.err <= 1.0 {
                        // The frozen step fails the tolerance where the free one passed: too
                        // long for a located stop, shorter.
                        out.err = fout.err;
                    }
                    break;
                }
            }
            self.stats.evaluations += evals;
            let err = out.err;
            // The method's next step, accepted or not (a step whose error is not finite
            // counts as one far past the tolerance).
            let proposal = control(out.stiff).next(h, if err.is_finite() { err } else { 1e10 });
            if out.stiff {
                self.stiff_next = Some((0, proposal));
            }
            if err > 1.0 || !err.is_finite() {
                self.stats.rejected += 1;
                h = proposal;
                k0 = Some((self.changes, d0, f0));
                continue;
            }
            let sys = self.system(frozen);
            let loading = self.loading_slips(&sys, &out.end);
            if !loading.is_empty() {
                // A stuck contact without force at the start presses by the end and needs
                // more friction than mu f: it slides from the start, along the friction it
                // would need there (-F / |F|); the step is redone. Not along its slip's rate
                // at the start (`release_directions`): carrying no force there, its friction
                // takes no part in that rate, which says nothing of the direction it will
                // slide in once it presses. Read from there, two such contacts of an 8-ball
                // rack struck at 1 mm/s (mu 0.003) each stopped 1e-15 s after its release,
                // in turn, for 1e6 steps (found by fuzzing).
                let sl: Vec<Vector3<f64>> = loading
                    .iter()
                    .map(|&(k, _)| sys.slip(&self.y, &self.active[k]))
                    .collect();
                for (&(k, fr), sl) in loading.iter().zip(sl) {
                    self.release(k, fr, sl);
                }
                self.stats.rejected += 1;
                k0 = None;
                continue;
            }
            if !frozen {
                events = self.crossings(&sys, (&self.y, &f0), (&out.y, &out.end));
            }
            if events.is_empty() {
                let dense = self.samples_within(h).then(|| Dense::new(&self.y, &out, h));
                let t0 = self.t;
                self.stats.steps += 1;
                self.t += h;
                let hn = proposal;
                let last = out.k.pop().expect("the derivative at the step's end");
                self.y = out.y;
                self.settle_aligned();
                self.trace_step(t0, dense.as_ref(), frozen);
                h = hn;
                // The last stage is the derivative at the new state (first same as last),
                // the next step's first, unless the contacts' modes changed; its forces are
                // those the check after the step reads (not under a frozen step's friction).
                if !self.after_step(Vec::new(), (!frozen).then_some(&out.end)) && !frozen {
                    k0 = Some((self.changes, last, out.end));
                }
                continue;
            }
            // Each event's time on the step's continuous extension; the step then ends at
            // the first.
            let dense = Dense::new(&self.y, &out, h);
            let times: Vec<f64> = events
                .iter()
                .map(|&e| self.locate(&sys, &dense, &out.y, e))
                .collect();
            let at = times.iter().copied().fold(f64::INFINITY, f64::min);
            let sa = sys.step(&self.y, &out.k[0], at, &scale, self.settings.rtol);
            if sa.err > 1.0 || !sa.err.is_finite() {
                // The step to the event fails the tolerance where the whole step passed it:
                // through a contact stiff beyond the explicit step's stability the error
                // estimate of the longer step can pass by chance (five balls of E = 1.2e21
                // Pa under Kuwabara-Kono gamma = 0.05 s: the step to a closing 1.6e-10 s in
                // took the balls from 38 J to 4.2e7 J; found by fuzzing). Rejected, shorter.
                self.stats.evaluations += sys.evaluations.get();
                self.stats.rejected += 1;
                h = control(sa.stiff).next(at, if sa.err.is_finite() { sa.err } else { 1e10 });
                k0 = Some((self.changes, d0, f0));
                continue;
            }
            let ya = sa.y;
            let g: Vec<f64> = events
                .iter()
                .map(|&e| self.event_value(&sys, &ya, e))
                .collect();
            // A stop must stop the whole slip: crossing zero along the step's direction with
            // more than STOP_RESIDUE rtol v_ref left across it, the slip turned, and the
            // step is halved ([`STOP_RESIDUE`]).
            let turned = events.iter().zip(&times).zip(&g).any(|((e, time), g)| {
                let Event::Stop(k) = *e else {
                    return false;
                };
                let c = &self.active[k];
                let r = sys.slip(&ya, c) - c.offset;
                (*time <= at || *g <= 0.0)
                    && (r - c.seed * r.dot(&c.seed)).norm()
                        > STOP_RESIDUE * self.settings.rtol * self.v_ref
            });
            // A frozen step holds the friction of each contact whose slip reversed along its
            // direction at the step's start: a slip that turns inside the step as well leaves
            // about mu f h |e_end - e_start| / 2 of friction impulse along the wrong
            // direction. More than FROZEN_TURN rtol v_ref of velocity (over the lightest
            // ball's mass), and the step is halved as for a turned stop (the draw break at
            // rtol 1e-10 and 1e-11 was 1.5e-6 and 7e-7 m/s off the 1e-12 one; 2.5e-7 and
            // 2.3e-8 now).
            let astray = frozen && self.held_astray(&sys, &ya, at);
            let evals = sys.evaluations.get();
            self.stats.evaluations += evals;
            if (turned || astray) && at > TURN_MIN_STEP * self.tau0 {
                self.stats.rejected += 1;
                h = 0.5 * at;
                k0 = Some((self.changes, d0, f0));
                continue;
            }
            self.stats.steps += 1;
            let t0 = self.t;
            self.y = ya;
            self.settle_aligned();
            self.t += at;
            self.trace_step(t0, Some(&dense), frozen);
            // Every event located at that time (or crossed by it), contacts removed last.
            let mut opened = Vec::new();
            let mut released = Vec::new();
            // A spring's event located here that the state does not show (its event function
            // still positive) was a crossing of the continuous extension only: its mode is
            // decided from the state (`after_step`), so nothing happens, and the next step,
            // as long as this one, would locate it at the same place again. That step is
            // held to twice the secant's time to the crossing, read off the states at this
            // end and at the whole step's, but not below this step nor [`TURN_MIN_STEP`]
            // elastic contact times (a secant of 3e-26 s after a step of 2e-19 s stopped a
            // run as too small). (Eight Mindlin balls at 1 mm/s under
            // Kuwabara-Kono at rtol 1e-10: a cap of 2e-12 N near its contact's let-go,
            // whose force on the extension of a 3.8e-5 s step fell through the spring
            // 2.45e-15 s in, 335,700 times at t = 40.106 s; 3.3 s and 343,125 steps, now
            // 73 ms and 8,119 steps. Found by fuzzing.)
            let mut spurious = f64::INFINITY;
            for ((e, time), g) in events.iter().zip(&times).zip(&g) {
                if matches!(e, Event::SpringSlide(_) | Event::SpringStick(_))
                    && *time <= at
                    && *g > 0.0
                {
                    let sy = self.system(frozen);
                    let g_full = self.event_value(&sy, &out.y, *e);
                    let evals = sy.evaluations.get();
                    self.stats.evaluations += evals;
                    if g_full < 0.0 {
                        let secant = *g * (h - at) / (*g - g_full);
                        let floor = TURN_MIN_STEP * self.tau0;
                        spurious = spurious.min((2.0 * secant.max(at)).max(floor));
                    }
                    continue;
                }
                let happens = match *e {
                    // An opening only where the contact has let go within the tolerance: the
                    // time is read off the step's continuous extension, which on a coarse
                    // step through a stiff, damped contact can be far from the step's own
                    // state there (eight balls at rtol 1e-3: located where a pair still
                    // pressed 9.6 um deep with 25 N, the contact dropped with its stored
                    // energy, closed again 67 um deep, 62 J off the balance; found by
                    // fuzzing). Otherwise the step ends there without it, and the next one
                    // locates it again, from closer. Within the tolerance, or within the
                    // positions' rounding where the tolerance is finer: four balls at 1 mm/s
                    // and rtol 1e-10 held a Kuwabara-Kono pair at its let-go for 1e6 steps,
                    // the tolerance 1.1e-17 m, the compression's rounding 1e-16 m (found by
                    // fuzzing).
                    Event::Open(k) => {
                        let tol = self.settings.rtol * self.open_scale(&self.active[k]);
                        (*time <= at || *g <= 0.0) && *g <= tol.max(self.round_delta)
                    }
                    Event::Close(..) => *time <= at || *g < 0.0,
                    _ => *time <= at || *g <= 0.0,
                };
                if !happens {
                    continue;
                }
                self.stats.events += 1;
                match *e {
                    Event::Stop(k) => {
                        let sl = self.system(false).slip(&self.y, &self.active[k]);
                        self.changes += 1;
                        let cloth = self.nballs();
                        let c = &mut self.active[k];
                        c.stick_time = Some(self.t - c.start);
                        c.offset = sl;
                        // The cloth's contacts keep the stick rule (a ball rolling on the
                        // cloth is not pushed on by the friction it slid under).
                        c.mode = if self.settings.stick || c.j == cloth {
                            Mode::Stuck
                        } else {
                            Mode::Continued
                        };
                    }
                    Event::Open(k) => opened.push(k),
                    Event::Release(k) => released.push(k),
                    Event::Close(i, j) => self.close(i, j),
                    // The spring's mode is decided from the state after the step
                    // (`after_step`).
                    Event::SpringSlide(_) | Event::SpringStick(_) => {}
                }
            }
            if !released.is_empty() {
                let fs = self.system(false).forces(&self.y);
                self.stats.evaluations += 1;
                for &k in &released {
                    self.release(k, fs.need(k), fs.contact[k].2);
                }
            }
            // Released contacts slide from here: their directions before any index moves.
            self.after_step(released, None);
            opened.sort_unstable();
            for k in opened.into_iter().rev() {
                self.let_go(k);
                self.open(k);
            }
            h = h.max(FIRST_STEP * self.tau0).min(spurious);
        }
    }

    /// Whether a frozen step of `h` (s) to `y1` held a contact's friction astray: a held
    /// contact whose slip turned within the step leaves about mu f h |e_end - e_start| / 2
    /// of friction impulse along the wrong direction; more than [`FROZEN_TURN`] rtol v_ref
    /// of velocity (over the lightest ball's mass) is astray.
    fn held_astray(&self, sys: &System<'_>, y1: &[f64], h: f64) -> bool {
        self.active.iter().zip(&self.held).any(|(c, &held)| {
            if !held || c.mode != Mode::Sliding || c.mu == 0.0 {
                return false;
            }
            let r = sys.slip(y1, c) - c.offset;
            let rn = r.norm();
            if rn <= SLIP_FLOOR * self.v_ref || r.dot(&c.seed) <= 0.0 {
                return false;
            }
            let (d, w) = sys.compression(y1, c);
            let f = c.law.force(d, w).max(0.0);
            let off = c.mu * f * h * (r / rn - c.seed).norm() / (2.0 * self.m_min);
            off > FROZEN_TURN * self.settings.rtol * self.v_ref
        })
    }

    /// Whether every contact a frozen step held ends it sliding along the direction it was
    /// held in, or within [`STOP_RESIDUE`] rtol v_ref of rest: the held friction was the
    /// contact's own to the tolerance, and the step needs no event to be taken.
    fn held_fits(&self, sys: &System<'_>, y1: &[f64], h: f64) -> bool {
        let tol = STOP_RESIDUE * self.settings.rtol * self.v_ref;
        self.active.iter().zip(&self.held).all(|(c, &held)| {
            if !held || c.mode != Mode::Sliding {
                return true;
            }
            let r = sys.slip(y1, c) - c.offset;
            r.dot(&c.seed) >= -tol
        }) && !self.held_astray(sys, y1, h)
    }

    /// After a step: marks the loaded contacts and releases the stuck ones whose friction
    /// exceeds mu f, one at a time, the one in excess by the largest fraction first, the
    /// stick solve redone without it (a release changes the friction the others need: in a
    /// tight rack two contacts of one ball were released together and the second's slip
    /// then ran against the direction it was released along). The released contacts then
    /// slide along directions consistent with their slips' rates (`release_directions`).
    /// `released`: contacts already released by a located event; `at`: the forces at the
    /// current state when the caller has them (evaluated otherwise).
    /// Returns whether any contact was released (the right-hand side changed).
    fn after_step(&mut self, mut released: Vec<usize>, at: Option<&Forces>) -> bool {
        let springs = self.mindlin() && self.spring_modes();
        let mut at = at.filter(|_| !springs);
        loop {
            let sys = self.system(false);
            let owned;
            let fs = match at.take() {
                Some(f) => f,
                None => {
                    owned = sys.forces(&self.y);
                    self.stats.evaluations += 1;
                    &owned
                }
            };
            let mut worst: Option<(usize, f64)> = None;
            for (k, c) in self.active.iter_mut().enumerate() {
                let (f, fr) = (fs.contact[k].0, fs.need(k));
                if f > 0.0 {
                    c.loaded = true;
                }
                if c.mode == Mode::Stuck {
                    let cap = c.mu * f;
                    let need = fr.norm();
                    if need > cap * (1.0 + RELEASE_SLACK) && need > 0.0 {
                        let excess = (need - cap) / need;
                        if worst.is_none_or(|w| excess > w.1) {
                            worst = Some((k, excess));
                        }
                    }
                }
            }
            let Some((k, _)) = worst else { break };
            let (fr, sl) = (fs.need(k), fs.contact[k].2);
            self.release(k, fr, sl);
            released.push(k);
        }
        if !released.is_empty() {
            self.release_directions(&released);
        }
        springs || !released.is_empty()
    }

    /// After a step under Mindlin's spring: each spring's mode from the state, as the pair
    /// kernel decides it (docs/tangential.md#the-equations): a sliding spring, or one past
    /// its cap, is first put back on the cap (the step's error lets a sliding spring drift
    /// off it by the tolerance on the spring's scale, mu times the largest force, which for a
    /// tiny cap is far outside [`SPRING_CAP_BAND`]); then a spring slides when it is on its
    /// cap (within that band) and sticking would carry it past. Returns whether the state or
    /// a mode changed (the next step's first derivative is then new).
    fn spring_modes(&mut self) -> bool {
        if self.system(false).spring_mu == 0.0 {
            return false;
        }
        let nb = self.nb();
        let pc = self.pc();
        let mut changed = false;
        // Onto the cap: judged there, as the pair kernel judges a sliding spring. Read off
        // the drifted state, a sliding spring 1e-8 inside a cap of 1e-6 N was a sticking
        // one, and crossed the cap again at the next step's start: five resin balls at 1
        // mm/s (mu 0.0056) had an event in nearly every step to the work bound (found by
        // fuzzing).
        for k in 0..self.active.len() {
            let sys = self.system(false);
            let c = &self.active[k];
            if !c.mode.spring() {
                continue;
            }
            let (d, w) = sys.compression(&self.y, c);
            let cap = sys.spring_mu * c.law.force(d, w).max(0.0);
            let s = sys.spring(&self.y, k);
            let n = (s[0] * s[0] + s[1] * s[1]).sqrt();
            if n > 0.0 && (n > cap || c.mode == Mode::SpringSlide) {
                let q = cap / n;
                if q != 1.0 {
                    let o = spring_index(nb, pc, k);
                    self.y[o] *= q;
                    self.y[o + 1] *= q;
                    changed = true;
                }
            }
        }
        let sys = self.system(false);
        let fs = sys.forces(&self.y);
        // Each spring's mode, and for one that starts to slide within the band its factor
        // onto the cap.
        let modes: Vec<Option<(bool, f64)>> = (0..self.active.len())
            .map(|k| {
                self.active[k].mode.spring().then(|| {
                    let (s, cap, stick, cap_rate) = sys.spring_rates(&self.y, &fs.acc, k);
                    let n = (s[0] * s[0] + s[1] * s[1]).sqrt();
                    // Clear of its turn (as `crossings` locates it): a spring at the turn,
                    // where a located stop of its sliding leaves it, sticks. Judged there by
                    // the rounding's sign, one slid on through the next step, whose start in
                    // the band does not locate the turn (four Mindlin balls at 8.2 m/s, rtol
                    // 1e-10: 3.2e-6 s of sliding that stuck, 2e-4 m/s off).
                    let (turn, scale) = spring_turn_of(s, stick, cap_rate);
                    let slides = cap > 0.0
                        && n > 0.0
                        && n >= cap * (1.0 - SPRING_CAP_BAND)
                        && turn > scale * SPRING_CAP_BAND;
                    (slides, if slides { cap / n } else { 1.0 })
                })
            })
            .collect();
        self.stats.evaluations += 1;
        for (k, m) in modes.into_iter().enumerate() {
            let Some((slides, q)) = m else { continue };
            if q != 1.0 {
                let o = spring_index(nb, pc, k);
                self.y[o] *= q;
                self.y[o + 1] *= q;
                changed = true;
            }
            let mode = if slides {
                Mode::SpringSlide
            } else {
                Mode::SpringStick
            };
            if self.active[k].mode != mode {
                self.active[k].mode = mode;
                self.changes += 1;
                changed = true;
            }
        }
        changed
    }

    /// Contact `k` slides from now, first against the friction `fr` (N) it needed to stick,
    /// its slip measured from `sl` (m/s), the slip it had stuck.
    fn release(&mut self, k: usize, fr: Vector3<f64>, sl: Vector3<f64>) {
        self.changes += 1;
        let c = &mut self.active[k];
        c.mode = Mode::Sliding;
        let n = fr.norm();
        if n > 0.0 {
            c.seed = -fr / n;
        }
        c.offset = sl;
    }

    /// The sliding directions of contacts just released from sticking: each slides along its
    /// slip's rate, s_t' = lambda e with lambda >= 0, the friction -mu f e of every released
    /// contact included (docs/cluster.md#releases). The released slips' rates are affine in
    /// their directions (the stuck contacts answer through the stick solve, which is
    /// linear): s_k' = a_k + sum_j B_kj e_j in the tangent bases, read off 2m + 1 force
    /// evaluations for m contacts. Each contact's direction given the others' is the root
    /// of a secular equation ([`slide_direction`]), swept over the contacts until they
    /// stand; if they do not, each keeps -F / |F|, F the friction it needed to stick. For
    /// one contact whose balls are free otherwise, -F / |F| is already this direction;
    /// coupled through shared balls, it need not be. (A fixed-point iteration e <- s_t' /
    /// |s_t'| diverged at a located release, where lambda = 0: the rate of a contact
    /// released at its bound is zero under -F / |F| and flips under -e, and after 30
    /// iterations the rolling break's contact (2, 4) slid along (0.25, 0.43, -0.87) instead
    /// of (0.5, 0.87, 0): 1.7e-3 m/s off at rtol 1e-8.)
    fn release_directions(&mut self, released: &[usize]) {
        let m = released.len();
        let seeds: Vec<Vector3<f64>> = released.iter().map(|&k| self.active[k].seed).collect();
        for &k in released {
            self.active[k].seed = Vector3::zeros();
        }
        let a = self.released_rates(released);
        // b[k][j]: the response of s_k' to e_j, column v for e_j = t_v of contact j.
        let mut b = vec![vec![Matrix2::zeros(); m]; m];
        for (j, &kj) in released.iter().enumerate() {
            for v in 0..2 {
                self.active[kj].seed = self.active[kj].t[v];
                let r = self.released_rates(released);
                for k in 0..m {
                    b[k][j].set_column(v, &(r[k] - a[k]));
                }
                self.active[kj].seed = Vector3::zeros();
            }
        }
        let mut e: Vec<Vector2<f64>> = released
            .iter()
            .zip(&seeds)
            .map(|(&k, s)| {
                let x = Vector2::from(in_basis(&self.active[k], s));
                x / x.norm().max(f64::MIN_POSITIVE)
            })
            .collect();
        let mut settled = false;
        for _ in 0..RELEASE_SWEEPS {
            let mut moved: f64 = 0.0;
            for k in 0..m {
                let mut rest = a[k];
                for (j, ej) in e.iter().enumerate() {
                    if j != k {
                        rest += b[k][j] * ej;
                    }
                }
                let Some(x) = slide_direction(-b[k][k], rest) else {
                    continue;
                };
                moved = moved.max((x - e[k]).norm());
                e[k] = x;
            }
            if moved <= RELEASE_DIRECTION_TOL {
                settled = true;
                break;
            }
        }
        for ((&k, s), x) in released.iter().zip(seeds).zip(e) {
            let c = &mut self.active[k];
            c.seed = if settled {
                c.t[0] * x[0] + c.t[1] * x[1]
            } else {
                s
            };
        }
    }

    /// The slip rates (m/s^2, in each contact's tangent basis) of the contacts `released`
    /// at the current state, their friction along their seeds.
    fn released_rates(&mut self, released: &[usize]) -> Vec<Vector2<f64>> {
        let fs = self.system(false).forces(&self.y);
        self.stats.evaluations += 1;
        released
            .iter()
            .map(|&k| {
                let c = &self.active[k];
                Vector2::from(in_basis(c, &slip_rate(&fs.acc, c)))
            })
            .collect()
    }

    /// Drops the contacts that carry no force and do not close (or, unloaded, have moved
    /// apart by more than the touch tolerance).
    fn drop_quiet(&mut self) {
        let sys = self.system(false);
        // Per contact: (no force and not closing, unloaded and apart by the tolerance). A
        // closing slower than [`CLUSTER_GRAZING`] of the reference speed is none, as for a
        // pair outside the set (`first_touch`): two balls apart by 1.4e-17 m closing at
        // 7.7e-184 m/s kept an 8-ball run stepping to the work bound, its steps growing to
        // 6e10 s (found by fuzzing).
        let grazing = self.grazing();
        let state: Vec<(bool, bool)> = self
            .active
            .iter()
            .map(|c| {
                let (d, w) = sys.compression(&self.y, c);
                let tol = CLUSTER_TOUCH_TOLERANCE * (c.ri + c.rj);
                (
                    c.law.force(d, w) <= 0.0 && w <= grazing,
                    !c.loaded && d < -tol,
                )
            })
            .collect();
        // The cloth's contacts stay: balls rest on it before and after. On the cloth a pair
        // closed at this instant is not quiet yet: its closing was located because the
        // cloth's friction drives the balls together within the step (free balls in a
        // quiet set move apart or along), and dropping it at once closed it again at the
        // same instant a million times (three spinning balls, found by fuzzing).
        let cloth = self.nballs();
        let on_cloth = self.cluster.cloth.is_some();
        let now = self.t;
        let mut all_quiet = self.active.iter().zip(&state).all(|(c, q)| {
            (q.0 && !(on_cloth && c.start == now))
                || c.j == cloth
                || (!on_cloth && self.spent(&sys, c))
        });
        if all_quiet && !on_cloth && !self.active.is_empty() {
            all_quiet = self.bounce_spent();
        }
        for k in (0..self.active.len()).rev() {
            if (all_quiet && self.active[k].j != cloth) || state[k].1 {
                self.open(k);
            }
        }
    }

    /// Whether contact `c` is spent: between two free balls that have touched (the run's
    /// first touch is past), the normal speed it can still give, sqrt(w+^2 + 2 V(delta) /
    /// m*) from its closing rate w (its approach only) and the elastic energy V it holds (m*
    /// the pair's reduced mass), is at most rtol of the reference speed over the number of
    /// balls (a train of n balls can add up the speeds of its n - 1 contacts). Once every
    /// contact of a free cluster is spent or quiet, the contacts end ([`Run::drop_quiet`],
    /// those still closing bounced off first: [`Run::bounce_spent`]), as the pair kernel
    /// ends a damped contact whose separating balls hold within rtol^2 of the approach's
    /// energy. Stepped on, a train of balls left pressed only by the positions' rounding
    /// (compressions of 1e-16 m closing at 1e-13 m/s, forces of 1e-15 N) crept on for
    /// seconds of simulated time: eight balls under Kuwabara-Kono at rtol 1e-3 took 625,719
    /// steps, each ended at an opening the coarse step's extension put 1.4e-5 s in, the
    /// pair closed again at once (found by fuzzing). Held in the set instead, such contacts
    /// are stepped far past their stability (the tolerance is on the reference speed, their
    /// motion 1e-10 of it) and grew until the tolerance saw them: at rtol 1e-4 the train's
    /// velocities ended 5e-5 m/s (5 % of the cue's speed) from the run at 1e-8.
    fn spent(&self, sys: &System<'_>, c: &Active) -> bool {
        if self.first_touch.is_none() || c.j == self.nballs() {
            return false;
        }
        let (d, w) = sys.compression(&self.y, c);
        let spent = self.spent_speed();
        if w > spent {
            return false;
        }
        let w = w.max(0.0);
        let left = w * w + 2.0 * c.law.elastic_energy(d) / self.reduced_mass(c.i, c.j);
        left <= spent * spent
    }

    /// Whether ball pair `c` presses only by the positions' rounding: a force no larger
    /// than [`Run::round_force`]'s and no approach faster than the grazing speed. On the
    /// cloth such a pair does not keep the run going (`go`): two resting balls of a line,
    /// touching to the rounding (2e-17 m, 1.5e-18 N), kept eight soft balls struck at 1 mm/s
    /// stepping through their oscillations on the cloth for 38.6 s, 232,297 steps, while
    /// another ball drifted to its neighbour (found by fuzzing).
    fn rounding_only(&self, c: &Active) -> bool {
        let (d, w) = self.system(false).compression(&self.y, c);
        c.law.force(d, w) <= self.round_force && w <= self.grazing()
    }

    /// The reduced mass (kg) of balls `i` and `j`, m_i m_j / (m_i + m_j).
    fn reduced_mass(&self, i: usize, j: usize) -> f64 {
        let (mi, mj) = (self.bodies[i].m, self.bodies[j].m);
        mi * mj / (mi + mj)
    }

    /// Before spent contacts end, each still closing (at most the spent speed,
    /// [`Run::spent`]) bounces off as its law would at that vanishing speed (every law's
    /// restitution tends to 1 there: Hertz's is 1, Hunt-Crossley's 1 - O(v), Kuwabara-Kono's
    /// 1 - O(v^(1/5))): an impulse of 2 m* w along its normal, added to its record, the
    /// kinetic energy unchanged. A bounce can set a neighbour closing, so the contacts are
    /// swept in turn until none closes (pairwise, as the sequential engines do; at these
    /// speeds the order moves no velocity by more than rtol). Left closing, such a pair was
    /// flown past: dropped, closed at once by the next flight, dropped again. Returns false,
    /// nothing changed, if some contact still closes after [`BOUNCE_SWEEPS`] sweeps per
    /// ball; the contacts are then stepped on.
    fn bounce_spent(&mut self) -> bool {
        let nb = self.nb();
        let (base, pc) = (PER_BALL * nb, self.pc());
        let mut y = self.y.clone();
        for sweep in 0..BOUNCE_SWEEPS * self.nballs() {
            let mut bounced = false;
            for (k, c) in self.active.iter().enumerate() {
                let (i, j, n) = (c.i, c.j, c.n);
                let w = n.dot(&(pos(&y, nb + i) - pos(&y, nb + j)));
                if w <= self.round_speed {
                    continue;
                }
                let (mi, mj) = (self.bodies[i].m, self.bodies[j].m);
                let p = 2.0 * w * self.reduced_mass(i, j);
                for a in 0..3 {
                    y[3 * (nb + i) + a] -= p / mi * n[a];
                    y[3 * (nb + j) + a] += p / mj * n[a];
                }
                y[base + pc * k] += p;
                bounced = true;
            }
            if !bounced {
                if sweep > 0 {
                    self.y = y;
                    self.changes += 1;
                }
                return true;
            }
        }
        false
    }

    /// The slowest approach (m/s) the run counts: [`CLUSTER_GRAZING`] of the reference
    /// speed, for a contact in the set as for a pair outside it (`first_touch`).
    fn grazing(&self) -> f64 {
        CLUSTER_GRAZING * self.v_ref
    }

    /// Whether the ball of cloth contact `c` stays on the cloth: its vertical energy about
    /// its rest, m w^2 / 2 + V(delta) with V = (2/5) k delta^(5/2) - m g delta (the cloth's
    /// elastic energy and the weight's; V(0) = 0 where the ball leaves the cloth, its
    /// minimum at the static compression), is below V(0). Once no pair presses nothing
    /// else acts along z, the motion keeps that energy, and a ball below it oscillates about
    /// its rest with a speed below sqrt(1.2 g delta_s) (about 2 mm/s for a pool ball on
    /// slate), which the outcome reports as it stands; a ball above it leaves the cloth
    /// within half an oscillation, which the run steps to. Contacts between balls are
    /// "settled" here.
    fn settled_on_cloth(&self, c: &Active) -> bool {
        let Some(cloth) = self.cluster.cloth else {
            return true;
        };
        if c.j != self.nballs() {
            return true;
        }
        let sys = self.system(false);
        let (d, w) = sys.compression(&self.y, c);
        let m = self.bodies[c.i].m;
        let v = c.law.elastic_energy(d) - m * cloth.gravity * d;
        // Without gravity a resting ball sits at V's minimum, 0, with no hold to spare: it
        // stays as long as it neither presses nor closes.
        0.5 * m * w * w + v < 0.0 || (d <= 0.0 && w <= 0.0)
    }

    /// The longest step (s) after which every pair outside the contact set that would touch,
    /// if the balls flew freely from now, is still overlapping: the earliest closest
    /// approach of such a pair, or [`FIRST_STEP`] elastic contact times if that comes sooner. A closing is an event seen at a step's ends (the
    /// pair apart, then overlapping); a step that carries a pair through the other ball
    /// sees it apart at both. While a few contacts creep apart under heavy Kuwabara-Kono
    /// damping the steps grow tenfold at each (to 34 s with gamma = 0.05 s), and balls
    /// passed through each other: closed 4 cm deep they gave 69 mJ out of 8.5 µJ (found
    /// by fuzzing).
    fn touch_bound(&self) -> f64 {
        let nb = self.nb();
        let n = self.nballs();
        let mut bound = f64::INFINITY;
        for i in 0..n {
            for j in i + 1..n {
                if self.in_set(i, j) {
                    continue;
                }
                let p = pos(&self.y, j) - pos(&self.y, i);
                let u = pos(&self.y, nb + j) - pos(&self.y, nb + i);
                if let Some(t) =
                    first_touch(p, u, self.bodies[i].r + self.bodies[j].r, self.grazing())
                {
                    // Halfway from their first touch to their closest approach: a step
                    // that ends there sees them overlapping and still approaching. Not at
                    // the closest approach itself: the cloth's friction moves balls off
                    // their free flight, a step ended just past it, where the pair
                    // overlapped but receded, and under Kuwabara-Kono (gamma = 0.05 s) its
                    // separation function delta + gamma delta' was negative there: no
                    // closing was seen and a ball passed through another (found by
                    // fuzzing the Python package).
                    bound = bound.min(0.5 * (t - p.dot(&u) / u.norm_squared()));
                }
            }
        }
        bound.max(FIRST_STEP * self.tau0)
    }

    /// The longest step (s) through the pressing ball pairs: [`OSCILLATION_STEP`] radians of
    /// the stiffest one's oscillation, omega = sqrt(f'(delta) / m*) with f' = (3/2) k
    /// sqrt(delta) Hertz's stiffness at its compression (m* the pair's reduced mass; the
    /// damping left out). Unbounded while none presses. The cloth's contacts are left out:
    /// a ball rests on the cloth for as long as the run lasts, and stepping its bed's
    /// oscillation would hold every run on the cloth to it.
    fn oscillation_bound(&self) -> f64 {
        let sys = self.system(false);
        let cloth = self.nballs();
        let mut rate: f64 = 0.0;
        for c in self.active.iter().filter(|c| c.j != cloth) {
            let (d, _) = sys.compression(&self.y, c);
            if d > 0.0 {
                rate = rate.max(1.5 * c.law.stiffness() * d.sqrt() / self.reduced_mass(c.i, c.j));
            }
        }
        OSCILLATION_STEP / rate.sqrt()
    }

    /// Whether two balls flying freely from now touch within `horizon` (s).
    fn touches_within(&self, horizon: f64) -> bool {
        let nb = self.nb();
        let n = self.nballs();
        (0..n).any(|i| {
            (i + 1..n).any(|j| {
                let p = pos(&self.y, j) - pos(&self.y, i);
                let u = pos(&self.y, nb + j) - pos(&self.y, nb + i);
                first_touch(p, u, self.bodies[i].r + self.bodies[j].r, self.grazing())
                    .is_some_and(|t| t <= horizon)
            })
        })
    }

    /// Free flight to the next touch; false when no pair will touch. Once balls have
    /// touched, an approach within the velocities' rounding is none: a pair bounced off at
    /// the end of its spent contact ([`Run::bounce_spent`]) can be left closing at that
    /// rounding. Nor is there a next touch, once balls have touched, when every pair that
    /// would still touch closes slower than a spent contact can give ([`Run::spent`]: rtol
    /// of the reference speed over the number of balls): the velocities are not known
    /// closer than that. Flown to, such a touch lies ages away: five balls in a line with
    /// gaps, the first at 1 cm/s, left two of them closing at 2.3e-14 m/s 4 mm apart, and
    /// the run flew 1.7e11 s to close them; with the balls drifting at 1.7 m/s their
    /// positions lost their digits on the way, and the run stepped to the work bound at t =
    /// 1.1e10 s (found by fuzzing the Python package). The flight still stops at the first
    /// touch, slow or not, while a faster pair will touch: flown past, a slow pair closed
    /// again deep in overlap.
    fn fly(&mut self) -> bool {
        let nb = self.nb();
        let (floor, slow) = if self.first_touch.is_some() {
            (self.grazing().max(self.round_speed), self.spent_speed())
        } else {
            (self.grazing(), 0.0)
        };
        let mut next: Option<f64> = None;
        let mut fast = false;
        for i in 0..nb {
            for j in i + 1..nb {
                let p = pos(&self.y, j) - pos(&self.y, i);
                let u = pos(&self.y, nb + j) - pos(&self.y, nb + i);
                if let Some(t) = first_touch(p, u, self.bodies[i].r + self.bodies[j].r, floor) {
                    next = Some(next.map_or(t, |x: f64| x.min(t)));
                    fast |= -p.dot(&u) > slow * p.norm();
                }
            }
        }
        let Some(t) = next.filter(|_| fast) else {
            return false;
        };
        self.trace_flight(self.t + t);
        for b in 0..nb {
            for k in 0..3 {
                self.y[3 * b + k] += t * self.y[3 * nb + 3 * b + k];
            }
        }
        self.t += t;
        for i in 0..nb {
            for j in i + 1..nb {
                let p = pos(&self.y, j) - pos(&self.y, i);
                let u = pos(&self.y, nb + j) - pos(&self.y, nb + i);
                let d = self.bodies[i].r + self.bodies[j].r;
                if first_touch(p, u, d, floor) == Some(0.0) {
                    self.close(i, j);
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Q = q I: the slip's rate a - q e is along e only for e = a / |a|, and then lambda =
    /// |a| - q, which is >= 0 when |a| >= q (the need |a| / q in units of mu f at or past
    /// 1); below, the excess's direction a / |a| all the same.
    #[test]
    fn an_isotropic_contact_slides_along_its_excess() {
        let a = Vector2::new(3.0, -4.0);
        for q in [0.5, 5.0, 20.0] {
            let e = slide_direction(Matrix2::identity() * q, a).unwrap();
            assert!((e - a / 5.0).norm() < 1e-14, "{q}: {e}");
        }
    }

    /// The sliding direction against a scan of the unit circle (independent of the secular
    /// equation): e(phi) = (cos phi, sin phi) is a solution where the rate a - Q e is
    /// parallel to e, cross(e, a - Q e) = 0, with a - Q e . e >= 0; the scan brackets the
    /// sign changes of the cross product on 20,000 angles and bisects each. Q positive
    /// definite and anisotropic (a contact whose balls are held by other stuck contacts
    /// answers its own friction more in one direction), a past the bound: one root.
    #[test]
    fn a_coupled_contact_slides_where_its_rate_is_along_its_direction() {
        let q = Matrix2::new(4.0, 1.5, 1.5, 1.0);
        for a in [
            Vector2::new(6.0, 1.0),
            Vector2::new(-2.0, 7.0),
            Vector2::new(0.3, -9.0),
        ] {
            assert!(q.lu().solve(&a).unwrap().norm() > 1.0);
            let cross = |phi: f64| {
                let e = Vector2::new(phi.cos(), phi.sin());
                let r = a - q * e;
                (e.x * r.y - e.y * r.x, r.dot(&e))
            };
            let n = 20_000;
            let mut roots = Vec::new();
            for i in 0..n {
                let (mut lo, mut hi) = (
                    i as f64 * std::f64::consts::TAU / n as f64,
                    (i + 1) as f64 * std::f64::consts::TAU / n as f64,
                );
                if cross(lo).0.signum() == cross(hi).0.signum() {
                    continue;
                }
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if cross(mid).0.signum() == cross(lo).0.signum() {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                if cross(lo).1 >= 0.0 {
                    roots.push(Vector2::new(lo.cos(), lo.sin()));
                }
            }
            assert_eq!(roots.len(), 1, "{a}: {roots:?}");
            let e = slide_direction(q, a).unwrap();
            assert!((e - roots[0]).norm() < 1e-9, "{a}: {e} vs {}", roots[0]);
            let lambda = (a - q * e).dot(&e);
            assert!(lambda > 0.0 && (a - q * e - e * lambda).norm() < 1e-9 * a.norm());
        }
    }

    /// Exactly at the bound (a = Q e0 for a unit e0: the need is mu f along -e0) the rate
    /// under e0 is zero, lambda = 0, and the contact slides along e0 (where e <- rate / |rate|
    /// has no direction to follow); just short of it, along the excess's direction Q^(-1) a.
    #[test]
    fn a_contact_released_at_its_bound_slides_along_its_need() {
        let q = Matrix2::new(4.0, 1.5, 1.5, 1.0);
        let e0 = Vector2::new(0.6, 0.8);
        for scale in [1.0, 1.0 - 1e-9, 0.5] {
            let e = slide_direction(q, q * e0 * scale).unwrap();
            assert!((e - e0).norm() < 1e-12, "{scale}: {e}");
        }
        assert!(slide_direction(q, Vector2::zeros()).is_none());
        assert!(slide_direction(Matrix2::zeros(), e0).is_none());
    }
}
