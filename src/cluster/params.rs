//! The inputs of a cluster of touching balls (docs/cluster.md): the balls with their lab
//! state, the contact law of each pair, the friction, validated together.

use crate::base::error::Error;
use crate::integrator::law::damping_within_bound;
use crate::model::contact_law::{ContactLaw, Damping};
use crate::model::material::{elastic_impact, hertz_stiffness, sphere_plane_stiffness, Material};
use crate::model::params::Ball;
use crate::tangential::impact::shear_compliance;
use nalgebra::Vector3;

/// Most balls in one cluster: a full rack and its cue ball with room to spare; the stick
/// solve is dense in the stuck contacts, so its cost grows with their cube.
pub const MAX_CLUSTER_BALLS: usize = 22;

/// Largest overlap or gap (relative to r_i + r_j) at which two balls count as touching: the
/// same relative tolerance as two touching lab balls (`TOUCH_TOLERANCE`), 1e-9, a few
/// hundred times the rounding of positions of a metre-sized table.
pub const CLUSTER_TOUCH_TOLERANCE: f64 = crate::model::frame::TOUCH_TOLERANCE;

/// Smallest Hertz compression at the cluster's fastest speed, relative to r_i + r_j, of a
/// pair the kernel resolves: the positions (about 0.1 m) carry 1e-17 m of rounding, so a
/// compression of 1e-8 of 57 mm keeps about 1e-8 of its own value.
pub(crate) const MIN_COMPRESSION: f64 = 1e-8;

/// Largest coordinate of a ball's centre (m): a table is a few metres; at 1e4 m a position
/// carries 2e-12 m of rounding, below 1e-8 of a ball's radius. Centres 1.8e308 m apart
/// overflowed their distance and the run never ended (found by fuzzing).
pub const CLUSTER_MAX_POSITION: f64 = 1e4;

/// One ball of a cluster in the lab frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterBall {
    /// Mass, radius, alpha.
    pub ball: Ball,
    /// Centre (m).
    pub position: Vector3<f64>,
    /// Velocity of the centre (m/s).
    pub velocity: Vector3<f64>,
    /// Spin (rad/s).
    pub spin: Vector3<f64>,
}

/// The damping of the pairs' laws when the stiffness comes from the materials.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PairDamping {
    /// Elastic Hertz.
    None,
    /// A given coefficient (beta in s/m or gamma in s) for every pair.
    Coefficient(Damping, f64),
    /// Each pair's coefficient calibrated so that its head-on impact at `at_speed` (m/s)
    /// has restitution `restitution` (`ContactLaw::calibrated`, docs/contact-law.md).
    Restitution {
        /// The damping law.
        damping: Damping,
        /// Restitution in (0, 1].
        restitution: f64,
        /// Relative approach speed of the calibration (m/s).
        at_speed: f64,
    },
}

impl PairDamping {
    /// The damping law (none, Hunt-Crossley or Kuwabara-Kono).
    pub fn damping(&self) -> Damping {
        match *self {
            PairDamping::None => Damping::None,
            PairDamping::Coefficient(d, _) => d,
            PairDamping::Restitution { damping, .. } => damping,
        }
    }

    /// The law of a pair of stiffness `k` (N/m^1.5) and reduced mass `reduced_mass` (kg):
    /// a calibrated damping runs its head-on calibration on that mass.
    pub fn law(&self, k: f64, reduced_mass: f64) -> Result<ContactLaw, Error> {
        match *self {
            PairDamping::None => ContactLaw::elastic(k),
            PairDamping::Coefficient(d, c) => ContactLaw::new(k, d, c),
            PairDamping::Restitution {
                damping,
                restitution,
                at_speed,
            } => ContactLaw::calibrated(k, damping, restitution, at_speed, reduced_mass),
        }
    }
}

/// The normal law of every pair.
#[derive(Debug, Clone, PartialEq)]
pub enum ClusterLaw {
    /// The same law for every pair (identical balls).
    Same(ContactLaw),
    /// Hertz's stiffness k = (4/3) E* sqrt(R) from the two balls' materials (one per ball,
    /// in order), with a damping.
    Materials(Vec<Material>, PairDamping),
}

/// A validated cluster: balls, laws of every pair, friction coefficient.
#[derive(Debug, Clone, PartialEq)]
pub struct Cluster {
    pub(crate) balls: Vec<ClusterBall>,
    /// The law of pair (i, j), i < j, at index `pair_index(i, j)`.
    pub(crate) laws: Vec<ContactLaw>,
    /// Coulomb's mu (dimensionless), the same at every contact.
    pub(crate) mu: f64,
    /// Each ball's material, when the laws came from them ([`ClusterLaw::Materials`]).
    pub(crate) materials: Option<Vec<Material>>,
    /// The tangential law of every contact.
    pub(crate) tangential: ClusterTangential,
    /// Mindlin's 8 G* sqrt(R*) of pair (i, j) at `pair_index(i, j)` (N/m^1.5: the spring's
    /// stiffness is this times sqrt(delta)); empty under [`ClusterTangential::Rigid`].
    pub(crate) shear: Vec<f64>,
    /// The cloth under the balls, if they rest on one ([`Cluster::with_cloth`]).
    pub(crate) cloth: Option<ClusterCloth>,
    /// Each ball's Hertz law on the cloth, elastic unless [`Cluster::with_cloth_damping`]
    /// (empty without a cloth).
    pub(crate) cloth_laws: Vec<ContactLaw>,
    /// The damping of every ball's contact with the cloth ([`PairDamping::None`] unless
    /// [`Cluster::with_cloth_damping`]).
    pub(crate) cloth_damping: PairDamping,
    /// Each ball's static compression of the cloth under its weight (m; empty without one).
    pub(crate) cloth_preloads: Vec<f64>,
}

/// Default Coulomb friction between ball and cloth in scenes and Python: a typical sliding
/// friction of a phenolic ball on a worsted cloth (pooltool's default sliding friction is
/// the same 0.2).
pub const CLOTH_DEFAULT_MU: f64 = 0.2;

/// Default gravity (m/s^2) in scenes and Python.
pub const CLOTH_DEFAULT_GRAVITY: f64 = 9.81;

/// The field naming a cluster's cloth.
pub const CLUSTER_CLOTH_FIELD: &str = "cluster.cloth";

/// The cloth the balls of a cluster rest on (docs/cluster.md#the-cloth): the plane
/// z = `height` of the lab frame, up along +z, with gravity along -z. Each ball presses it
/// with an elastic Hertz contact of stiffness (4/3) E* sqrt(r), 1/E* the sum of the ball's
/// and the cloth's (1 - nu^2) / E (the cloth's alone when the balls' materials are not
/// given: the ball then counts as rigid against it), preloaded by the ball's weight, and
/// Coulomb's friction `mu` with the stick rule acts at the ball's lowest point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterCloth {
    /// Height (m) of the cloth's surface: every ball's centre starts at height + r.
    pub height: f64,
    /// The cloth bed's material.
    pub material: Material,
    /// Coulomb's mu between ball and cloth.
    pub mu: f64,
    /// Gravity (m/s^2), along -z.
    pub gravity: f64,
}

/// The field naming a cluster's tangential law.
pub const CLUSTER_TANGENTIAL_FIELD: &str = "cluster.tangential";

/// How every contact of a cluster carries friction (docs/cluster.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ClusterTangential {
    /// Coulomb's friction with the rigid stick rule: a stuck contact's slip is held at zero
    /// by whatever friction the coupled stick solve gives (docs/cluster.md#the-stick-solve).
    #[default]
    Rigid,
    /// Mindlin's no-slip tangential spring under Coulomb's cap at every contact, as the
    /// two-sphere compliant kernel (docs/tangential.md#two-spheres): stiffness
    /// k_t = 8 G* sqrt(R* delta) from the two balls' materials.
    Mindlin,
}

/// Index of pair (i, j), i < j, among the n (n - 1) / 2 pairs.
pub(crate) fn pair_index(n: usize, i: usize, j: usize) -> usize {
    i * n - i * (i + 1) / 2 + (j - i - 1)
}

impl Cluster {
    /// A validated cluster: 2 to [`MAX_CLUSTER_BALLS`] balls with finite states, no two
    /// overlapping by more than [`CLUSTER_TOUCH_TOLERANCE`] of r_i + r_j, at least one pair
    /// approaching (touching and closing, or on course to touch); `mu` finite in [0, 1e6].
    pub fn new(balls: Vec<ClusterBall>, law: ClusterLaw, mu: f64) -> Result<Self, Error> {
        let n = balls.len();
        if !(2..=MAX_CLUSTER_BALLS).contains(&n) {
            return Err(Error::invalid(
                "cluster.balls",
                format!("{n} balls"),
                format!("2 to {MAX_CLUSTER_BALLS} balls"),
            ));
        }
        if !(mu.is_finite() && (0.0..=crate::model::params::MU_MAX).contains(&mu)) {
            return Err(Error::invalid(
                "cluster.mu",
                mu,
                "finite, in [0, 1e6] (Coulomb's friction coefficient)",
            ));
        }
        for (i, b) in balls.iter().enumerate() {
            if b.position.amax() > CLUSTER_MAX_POSITION {
                return Err(Error::invalid(
                    format!("cluster.balls[{i}].position"),
                    format!("{:?}", b.position.as_slice()),
                    format!(
                        "coordinates within {CLUSTER_MAX_POSITION:e} m (a table's size; the \
                         contacts' compressions drown in the rounding of larger ones)"
                    ),
                ));
            }
            let all = [b.position, b.velocity, b.spin];
            if !all.iter().all(|v| v.iter().all(|x| x.is_finite())) {
                return Err(Error::invalid(
                    format!("cluster.balls[{i}]"),
                    format!(
                        "position {:?}, velocity {:?}, spin {:?}",
                        b.position.as_slice(),
                        b.velocity.as_slice(),
                        b.spin.as_slice()
                    ),
                    "finite components (m, m/s, rad/s)",
                ));
            }
        }
        let mut approaching = false;
        for i in 0..n {
            for j in i + 1..n {
                let (a, b) = (&balls[i], &balls[j]);
                let d = a.ball.radius() + b.ball.radius();
                let p = b.position - a.position;
                let gap = p.norm() - d;
                if gap < -CLUSTER_TOUCH_TOLERANCE * d {
                    return Err(Error::invalid(
                        format!("cluster.balls[{i}], cluster.balls[{j}]"),
                        format!("an overlap of {:e} m", -gap),
                        format!(
                            "at most {CLUSTER_TOUCH_TOLERANCE:e} of r_i + r_j = {d} m (balls \
                             that do not overlap)"
                        ),
                    ));
                }
                approaching |= first_touch(p, b.velocity - a.velocity, d, 0.0).is_some();
            }
        }
        if !approaching {
            return Err(Error::invalid(
                "cluster.balls",
                "no pair of balls touching and closing or on course to touch",
                "at least one pair that approaches",
            ));
        }
        let materials = match &law {
            ClusterLaw::Materials(m, _) => Some(m.clone()),
            ClusterLaw::Same(_) => None,
        };
        let laws = pair_laws(&balls, law)?;
        // Every pair's Hertz compression at the fastest speed in the cluster (the speed plus
        // r |w| of its fastest ball) must keep its digits beside the positions' rounding: a stiffness of 1e30 (E ~ 1e30 Pa) gives
        // 1e-12 m at 1 m/s and answers off by 2.5e-6, 1e60 ran to the work bound.
        let speed = fastest_speed(&balls);
        for i in 0..n {
            for j in i + 1..n {
                let (a, b) = (&balls[i].ball, &balls[j].ball);
                let k = laws[pair_index(n, i, j)].stiffness();
                let m = a.mass() * b.mass() / (a.mass() + b.mass());
                let (delta, tau0) = elastic_impact(k, m, speed);
                let d = a.radius() + b.radius();
                let refused = |expected: String| {
                    Error::invalid(
                        format!("cluster.balls[{i}], cluster.balls[{j}]"),
                        format!(
                            "a Hertz compression of {delta:e} m at {speed:e} m/s (stiffness \
                             {k:e} N/m^1.5)"
                        ),
                        expected,
                    )
                };
                if delta.is_nan() || delta < MIN_COMPRESSION * d {
                    return Err(refused(format!(
                        "at least {MIN_COMPRESSION:e} of r_i + r_j = {d} m: a stiffer \
                             material or slower balls leave the compression in the rounding \
                             of the positions"
                    )));
                }
                // And stay a Hertz contact: a compression past the pair's effective radius
                // (a contact radius sqrt(R delta) past R) is none. A ball at 1.5e308 m/s
                // gave an infinite compression and ran 5 s to the work bound (fuzzing).
                let effective = a.radius() * b.radius() / d;
                if delta > effective {
                    return Err(refused(format!(
                        "at most the pair's effective radius r_i r_j / (r_i + r_j) = \
                             {effective} m: a stiffer material or slower balls (Hertz's \
                             contact is small against the balls)"
                    )));
                }
                // The two-ball law's bounds on the damping (docs/contact-law.md) at the
                // pair's elastic contact time at this speed, (4/5) B(2/5, 1/2) delta / v: a
                // Kuwabara-Kono coefficient of 3.5e306 s ran past a minute (found by fuzzing).
                damping_within_bound(&laws[pair_index(n, i, j)], speed, tau0)?;
            }
        }
        Ok(Cluster {
            balls,
            laws,
            mu,
            materials,
            tangential: ClusterTangential::Rigid,
            shear: Vec::new(),
            cloth: None,
            cloth_laws: Vec::new(),
            cloth_damping: PairDamping::None,
            cloth_preloads: Vec::new(),
        })
    }

    /// The cluster resting on `cloth`: every ball's centre at the cloth's height plus its
    /// radius (within [`CLUSTER_TOUCH_TOLERANCE`] of its radius), `mu` finite in [0, 1e6],
    /// gravity finite in [0, 1e3] m/s^2, the weight's static compression below the ball's
    /// radius. Under Mindlin's spring the cloth is refused (its contacts are rigid-stick
    /// only), naming `cluster.cloth`.
    pub fn with_cloth(mut self, cloth: ClusterCloth) -> Result<Self, Error> {
        if self.tangential != ClusterTangential::Rigid {
            return Err(Error::invalid(
                CLUSTER_CLOTH_FIELD,
                "a cloth with tangential = \"mindlin\"",
                "tangential = \"rigid\" with a cloth (the cloth's contacts carry Coulomb's \
                 friction with the stick rule, not Mindlin's spring)",
            ));
        }
        if !cloth.height.is_finite() {
            return Err(Error::invalid(
                "cluster.cloth.height",
                cloth.height,
                "finite (m, the z of the cloth's surface)",
            ));
        }
        if !(cloth.mu.is_finite() && (0.0..=crate::model::params::MU_MAX).contains(&cloth.mu)) {
            return Err(Error::invalid(
                "cluster.cloth.mu",
                cloth.mu,
                "finite, in [0, 1e6] (Coulomb's friction between ball and cloth)",
            ));
        }
        if !(cloth.gravity.is_finite() && (0.0..=1e3).contains(&cloth.gravity)) {
            return Err(Error::invalid(
                "cluster.cloth.gravity",
                cloth.gravity,
                "finite, in [0, 1e3] m/s^2 (9.81 on Earth)",
            ));
        }
        let mut laws = Vec::with_capacity(self.balls.len());
        let mut preloads = Vec::with_capacity(self.balls.len());
        for (i, b) in self.balls.iter().enumerate() {
            let r = b.ball.radius();
            let gap = b.position.z - r - cloth.height;
            if gap.abs() > CLUSTER_TOUCH_TOLERANCE * r {
                return Err(Error::invalid(
                    format!("cluster.balls[{i}]"),
                    format!(
                        "a centre at z = {} m, {gap:e} m from resting on the cloth at height {} m",
                        b.position.z, cloth.height
                    ),
                    format!(
                        "z = height + r = {} m within {CLUSTER_TOUCH_TOLERANCE:e} of r (every \
                         ball resting on the cloth)",
                        cloth.height + r
                    ),
                ));
            }
            let k = match &self.materials {
                Some(m) => sphere_plane_stiffness(&b.ball, &m[i], Some(&cloth.material)).2,
                None => sphere_plane_stiffness(&b.ball, &cloth.material, None).2,
            };
            // A stiffness lost to underflow (a bed of E = 5e-324 Pa; found by fuzzing) is
            // the cloth's material's fault: named by it.
            let law = ContactLaw::elastic(k).map_err(|_| {
                Error::invalid(
                    "cluster.cloth.youngs_modulus",
                    cloth.material.youngs_modulus(),
                    format!(
                        "a modulus that gives balls[{i}] a Hertz stiffness on the cloth ({k:e} \
                         N/m^1.5 here)"
                    ),
                )
            })?;
            // The weight's static compression: k delta^1.5 = m g.
            let preload = (b.ball.mass() * cloth.gravity / k).powf(2.0 / 3.0);
            if preload.is_nan() || preload >= r {
                return Err(Error::invalid(
                    format!("cluster.balls[{i}]"),
                    format!("a static compression of {preload:e} m on the cloth"),
                    format!("below the radius {r} m (a stiffer cloth or less gravity)"),
                ));
            }
            laws.push(law);
            preloads.push(preload);
        }
        self.cloth = Some(cloth);
        self.cloth_laws = laws;
        self.cloth_preloads = preloads;
        Ok(self)
    }

    /// The cloth the balls rest on, if any.
    pub fn cloth(&self) -> Option<&ClusterCloth> {
        self.cloth.as_ref()
    }

    /// The cluster with every ball's contact with the cloth damped by `damping` (a real
    /// cloth returns about half of a drop's speed; the default is elastic). A coefficient
    /// is taken as given; a restitution is calibrated for each ball on its own mass, the bed
    /// immovable, on the contact alone (no gravity, no preload: docs/cluster.md#the-cloth).
    /// The weight's static compression is the elastic law's (the damping force vanishes
    /// at rest), and the damping's work is each cloth contact's heat besides friction's.
    /// Refused naming `cluster.cloth` without a cloth ([`Cluster::with_cloth`] first).
    ///
    /// ```
    /// use billiard_contact::nalgebra::Vector3;
    /// use billiard_contact::*;
    /// // A ball dropped onto a steel bed at 1 m/s beside another that it nudges at 1 mm/s,
    /// // its contact with the bed calibrated to return half of that speed.
    /// let resin = Material::new(5.4e9, 0.34).unwrap();
    /// let r = 0.028575;
    /// let ball = |x: f64, v: Vector3<f64>| ClusterBall {
    ///     ball: Ball::new(0.17, r, 0.4).unwrap(),
    ///     position: Vector3::new(x, 0.0, r),
    ///     velocity: v,
    ///     spin: Vector3::zeros(),
    /// };
    /// let cluster = Cluster::new(
    ///     vec![ball(0.0, Vector3::new(1e-3, 0.0, -1.0)), ball(2.0 * r, Vector3::zeros())],
    ///     ClusterLaw::Materials(vec![resin; 2], PairDamping::None),
    ///     0.0,
    /// )
    /// .unwrap()
    /// .with_cloth(ClusterCloth {
    ///     height: 0.0,
    ///     material: Material::new(2.0e11, 0.3).unwrap(),
    ///     mu: 0.2,
    ///     gravity: 0.0,
    /// })
    /// .unwrap()
    /// .with_cloth_damping(PairDamping::Restitution {
    ///     damping: Damping::HuntCrossley,
    ///     restitution: 0.5,
    ///     at_speed: 1.0,
    /// })
    /// .unwrap();
    /// let out = resolve_cluster(&cluster, &ClusterSettings::default()).unwrap();
    /// assert!((out.balls[0].velocity.z - 0.5).abs() < 1e-6);
    /// ```
    pub fn with_cloth_damping(mut self, damping: PairDamping) -> Result<Self, Error> {
        if self.cloth.is_none() {
            return Err(Error::invalid(
                CLUSTER_CLOTH_FIELD,
                "a cloth damping without a cloth",
                "a cloth first (with_cloth), then its damping",
            ));
        }
        // One calibration per kind of ball (stiffness on the bed and mass).
        let mut done: Vec<(f64, f64, ContactLaw)> = Vec::new();
        let laws = self
            .cloth_laws
            .iter()
            .zip(&self.balls)
            .map(|(law, b)| {
                let (k, m) = (law.stiffness(), b.ball.mass());
                if let Some(&(_, _, l)) = done.iter().find(|d| d.0 == k && d.1 == m) {
                    return Ok(l);
                }
                let l = damping.law(k, m)?;
                done.push((k, m, l));
                Ok(l)
            })
            .collect::<Result<Vec<_>, Error>>()
            .map_err(|e| e.moved("contact.law.", "cluster.cloth."))?;
        // The two-ball law's bounds on the damping, as for the pairs ([`Cluster::new`]), at
        // each ball's impact on the bed at the cluster's fastest speed: a Kuwabara-Kono
        // coefficient of 6.7e20 s on the bed ran five balls to the work bound (found by
        // fuzzing the Python package).
        let speed = fastest_speed(&self.balls);
        for (law, b) in laws.iter().zip(&self.balls) {
            let tau0 = elastic_impact(law.stiffness(), b.ball.mass(), speed).1;
            damping_within_bound(law, speed, tau0)
                .map_err(|e| e.moved("contact.law.", "cluster.cloth."))?;
        }
        self.cloth_laws = laws;
        self.cloth_damping = damping;
        Ok(self)
    }

    /// The damping of the balls' contacts with the cloth ([`Cluster::with_cloth_damping`]).
    pub fn cloth_damping(&self) -> PairDamping {
        self.cloth_damping
    }

    /// Ball `i`'s law on the cloth (its Hertz stiffness from the two materials, its damping
    /// coefficient calibrated on its mass), if the balls rest on one.
    pub fn cloth_law(&self, i: usize) -> Option<ContactLaw> {
        self.cloth_laws.get(i).copied()
    }

    /// The cluster with the tangential law `tangential` at every contact. Mindlin's spring
    /// needs the balls' materials (its stiffness 8 G* sqrt(R* delta), 1/G* = (2 - nu_i)/G_i +
    /// (2 - nu_j)/G_j): a cluster whose laws were not built from them
    /// ([`ClusterLaw::Materials`]) is refused naming `cluster.tangential`.
    pub fn with_tangential(mut self, tangential: ClusterTangential) -> Result<Self, Error> {
        if self.cloth.is_some() && tangential != ClusterTangential::Rigid {
            return Err(Error::invalid(
                CLUSTER_TANGENTIAL_FIELD,
                "\"mindlin\" on a cloth",
                "\"rigid\" when the balls rest on a cloth (its contacts carry Coulomb's \
                 friction with the stick rule)",
            ));
        }
        self.shear = match tangential {
            ClusterTangential::Rigid => Vec::new(),
            ClusterTangential::Mindlin => {
                let Some(materials) = &self.materials else {
                    return Err(Error::invalid(
                        CLUSTER_TANGENTIAL_FIELD,
                        "\"mindlin\" without the balls' materials",
                        "\"mindlin\" with every ball's youngs_modulus and poisson_ratio (the \
                         cluster's laws from its materials), or \"rigid\"",
                    ));
                };
                let n = self.balls.len();
                let mut shear = Vec::with_capacity(n * (n - 1) / 2);
                for i in 0..n {
                    for j in i + 1..n {
                        let (a, b) = (&self.balls[i].ball, &self.balls[j].ball);
                        let radius = hertz_stiffness((a, &materials[i]), (b, &materials[j])).1;
                        let g_star = 1.0
                            / (shear_compliance(&materials[i]) + shear_compliance(&materials[j]));
                        shear.push(8.0 * g_star * radius.sqrt());
                    }
                }
                shear
            }
        };
        self.tangential = tangential;
        Ok(self)
    }

    /// The tangential law of every contact.
    pub fn tangential(&self) -> ClusterTangential {
        self.tangential
    }

    /// Each ball's material, when the laws came from them.
    pub fn materials(&self) -> Option<&[Material]> {
        self.materials.as_deref()
    }

    /// The balls.
    pub fn balls(&self) -> &[ClusterBall] {
        &self.balls
    }

    /// The law of pair (i, j).
    pub fn law(&self, i: usize, j: usize) -> ContactLaw {
        let (i, j) = (i.min(j), i.max(j));
        self.laws[pair_index(self.balls.len(), i, j)]
    }

    /// Coulomb's mu.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The time (s from the start) at which the first pair touches while approaching, the
    /// balls flying freely until then: 0 when a pair touches and closes at the start. No
    /// contact presses before it (a force needs a compression, and a compression an
    /// approach), so a trace's action starts there (docs/formats.md#the-cluster-trace).
    pub fn first_touch_time(&self) -> f64 {
        let b = &self.balls;
        let mut first = f64::INFINITY;
        for i in 0..b.len() {
            for j in i + 1..b.len() {
                let d = b[i].ball.radius() + b[j].ball.radius();
                let p = b[j].position - b[i].position;
                if let Some(t) = first_touch(p, b[j].velocity - b[i].velocity, d, 0.0) {
                    first = first.min(t);
                }
            }
        }
        // Cluster::new refuses a cluster without an approaching pair.
        if first.is_finite() {
            first
        } else {
            0.0
        }
    }
}

/// An approach along the line of centres (m/s) slower than this fraction of the pair's
/// relative speed is none, as the compliant kernel's grazing bound: an impulse of that
/// fraction of the momentum changes no velocity to double precision. Two touching balls
/// closing at 7e-310 m/s while sliding past each other at 2 mm/s held a cluster's steps at
/// their smallest for 1e6 steps (found by fuzzing): the pair counted as about to close
/// at every step and never did.
pub(crate) const CLUSTER_GRAZING: f64 = 1e-40;

/// The time (s) from now at which two balls in free flight, centre of the second at `p` (m)
/// from the first's, relative velocity `u` (m/s), come to the distance `d` (m) while
/// approaching: 0 when they touch (within the tolerance) and close; `None` when they never do
/// (an approach slower than [`CLUSTER_GRAZING`] of their relative speed, or than `floor`
/// (m/s), is none).
pub(crate) fn first_touch(p: Vector3<f64>, u: Vector3<f64>, d: f64, floor: f64) -> Option<f64> {
    let b = p.dot(&u);
    // Separating pairs (most, at every step) first, without the bound's square roots.
    if b >= 0.0 || b >= -p.norm() * (CLUSTER_GRAZING * u.norm()).max(floor) {
        return None;
    }
    let c = p.norm_squared() - d * d;
    if c <= 2.0 * CLUSTER_TOUCH_TOLERANCE * d * d {
        return Some(0.0);
    }
    let a = u.norm_squared();
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    // The smaller root, written without cancellation: c / (-b + sqrt(disc)).
    Some(c / (-b + disc.sqrt()))
}

/// The fastest speed in the cluster: the largest over its balls of the speed plus r |w|, at
/// which every pair's compression and every ball's impact on the bed are judged.
fn fastest_speed(balls: &[ClusterBall]) -> f64 {
    balls
        .iter()
        .map(|b| b.velocity.norm() + b.ball.radius() * b.spin.norm())
        .fold(0.0, f64::max)
}

/// The law of every pair.
fn pair_laws(balls: &[ClusterBall], law: ClusterLaw) -> Result<Vec<ContactLaw>, Error> {
    let n = balls.len();
    match law {
        ClusterLaw::Same(l) => Ok(vec![l; n * (n - 1) / 2]),
        ClusterLaw::Materials(materials, damping) => {
            if materials.len() != n {
                return Err(Error::invalid(
                    "cluster.materials",
                    format!("{} materials", materials.len()),
                    format!("one material per ball ({n})"),
                ));
            }
            // Calibrations cost a head-on run each: identical pairs share one.
            let mut done: Vec<(f64, f64, ContactLaw)> = Vec::new();
            let mut laws = Vec::with_capacity(n * (n - 1) / 2);
            for i in 0..n {
                for j in i + 1..n {
                    let (a, b) = (&balls[i].ball, &balls[j].ball);
                    let k = hertz_stiffness((a, &materials[i]), (b, &materials[j])).2;
                    let m = a.mass() * b.mass() / (a.mass() + b.mass());
                    let l = match done.iter().find(|x| x.0 == k && x.1 == m) {
                        Some(x) => x.2,
                        None => {
                            let l = damping.law(k, m)?;
                            done.push((k, m, l));
                            l
                        }
                    };
                    laws.push(l);
                }
            }
            Ok(laws)
        }
    }
}

impl ClusterLaw {
    /// One law for every pair, of the given stiffness `k` (N/m^1.5) and `damping`; a
    /// calibrated damping needs identical balls (it is calibrated on their pair's reduced
    /// mass m m / (m + m)), else an error naming `contact.law.stiffness` and the first ball
    /// unlike the others.
    pub fn same_stiffness(k: f64, damping: PairDamping, balls: &[Ball]) -> Result<Self, Error> {
        if let PairDamping::Restitution { .. } = damping {
            if let Some(i) = balls.iter().position(|b| *b != balls[0]) {
                return Err(Error::invalid(
                    crate::model::contact_law::STIFFNESS_FIELD,
                    format!("{k} with balls[{i}] unlike balls[0] and a calibrated damping"),
                    "identical balls (one law calibrated on their reduced mass), or every \
                         ball's material (each pair calibrated on its own)",
                ));
            }
        }
        let m = balls.first().map_or(0.0, |b| b.mass());
        let law = damping.law(k, m * m / (m + m))?;
        Ok(ClusterLaw::Same(law))
    }
}
