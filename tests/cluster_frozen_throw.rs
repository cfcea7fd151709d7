//! The frozen-combination throw (docs/cluster.md, "The frozen-combination throw"): the cue
//! ball drives the first object ball at a cut angle into a second ball frozen to it along +x;
//! friction at the frozen contact throws the second ball off the combination's line towards
//! the side the first ball is driven to (B. Jewett, "Combinations and Throw", Billiards
//! Digest, 2001; D. G. Alciatore, "Small-Gap Combos", Billiards Digest, August 2018), by at
//! most "about 1 inch per foot" of travel (Alciatore 2018), atan(1/12) = 4.76 degrees.
//! Published numbers and their provenance: data/frozen_throw/README.md.
//!
//! The closed form the test checks, derived here (not from the kernel). Frame: first object
//! ball O1 at the origin, O2 frozen to it at (2r, 0, 0), the cue ball along +x hitting O1
//! with the line of centres n1 = (cos phi, sin phi, 0) at the cut angle phi. All forces lie
//! in the table's plane, so every spin is about z and the slip at the frozen contact (normal
//! +x) is along y only:
//!
//! ```text
//!   s2 = v1y - v2y + r (w1z + w2z)
//! ```
//!
//! While it slides (s2 > 0), Coulomb's friction on O2 is +mu f2 y (f2 the normal force at the
//! frozen contact), so O2's momentum is m v2 = P2 (1, mu, 0), P2 its normal impulse: the
//! throw is atan(Phi / P2) = atan(mu) exactly, whatever the time course of the forces. A
//! stuck phase (stick rule) carries |F| < mu f2, so in general throw <= atan(mu), with
//! equality iff the frozen contact slides throughout. It does whenever the slip, which starts
//! at 0, grows from the start and never returns to 0. Its rate, with the cue ball's contact
//! sliding (friction mu f1 t1 on O1, t1 = (sin phi, -cos phi, 0), at lever -r n1; on O1 from
//! O2 -f2 x - mu f2 y at lever +r x; I = alpha m r^2):
//!
//! ```text
//!   m v1y'  = f1 (sin phi - mu cos phi) - mu f2        m v2y' = mu f2
//!   I w1z'  = r mu (f1 - f2)                            I w2z' = -r mu f2
//!   m s2'   = f1 (sin phi - mu cos phi + mu / alpha) - f2 mu (2 + 2 / alpha)
//! ```
//!
//! so s2 = [p1 (sin phi - mu cos phi + mu / alpha) - p2 mu (2 + 2 / alpha)] / m, with p1, p2
//! the impulses so far: the slip stays positive while p2 / p1 < K = (sin phi - mu cos phi +
//! mu / alpha) / (2 mu (1 + 1 / alpha)). O2 gets only what O1 passes on along x: p2 <= p1
//! (cos phi + mu sin phi) - m v1x, and v1x >= 0 until O1 rebounds; the ratio stays below
//! cos phi + mu sin phi + (O1's rebound, a few percent of m v for a Hertz pair). For mu = 0.06,
//! alpha = 2/5: K = 1.42 at 30 degrees, 1.94 at 45, 2.35 at 60, 0.84 at 15, against
//! cos phi + mu sin phi = 0.90, 0.75, 0.55, 0.98: the frozen contact slides throughout from
//! 30 degrees up, and the throw is atan(mu). (The cue ball's contact itself slides at these
//! cuts: its slip v sin phi would need 2 mu (1 + 1/alpha) p1 / m = 0.42 p1 / m to stop, and
//! p1 / m is about v cos phi, below v sin phi / 0.42 from 30 degrees up; its slip stays
//! horizontal, along t1, as no force has a torque about a horizontal axis. The
//! derivation needs that.) At 15 degrees K < 0.98: the margin is gone and atan(mu) is only a
//! bound.
use billiard_contact::nalgebra::Vector3;
use billiard_contact::*;

const M: f64 = 0.17;
const R: f64 = 0.028575;
/// The cue ball's speed (m/s), as data/scenes/cluster_frozen_combination_30.toml.
const SPEED: f64 = 2.0;
/// How far the kernel's throw may be from atan(mu) where the closed form holds exactly
/// (degrees): the cluster kernel at rtol 1e-10 gives the friction impulse to about 1e-9 of
/// itself (docs/cluster.md: two balls agree with the two-ball law to 2e-11 of |U|), far below
/// this; a contact that stuck for even 1e-4 of the impulse would move the throw by ~3e-4
/// degrees and fail.
const CLOSED_FORM_TOL_DEG: f64 = 1e-6;
/// The published largest throw: "about 1 inch per foot of travel" (Alciatore 2018),
/// atan(1/12) in degrees. "About": the tests use it only as an upper bound.
fn published_max_throw_deg() -> f64 {
    (1.0f64 / 12.0).atan().to_degrees()
}

/// Hertz stiffness of two phenolic resin pool balls (E = 5.4 GPa, nu = 0.34):
/// k = (4/3) E* sqrt(R_eff), E* = E / (2 (1 - nu^2)), R_eff = r / 2.
fn pool_k() -> f64 {
    let e_star = 5.4e9 / (2.0 * (1.0 - 0.34 * 0.34));
    4.0 / 3.0 * e_star * (R / 2.0).sqrt()
}

fn at(p: Vector3<f64>, v: Vector3<f64>) -> ClusterBall {
    ClusterBall {
        ball: Ball::new(M, R, 0.4).unwrap(),
        position: p,
        velocity: v,
        spin: Vector3::zeros(),
    }
}

/// The frozen combination at cut `phi_deg`: the cue ball 1 mm before it touches O1 with the
/// line of centres at phi (from below, so O1 is driven towards +y), O2 frozen to O1 along +x.
/// Returns O2's throw (degrees, counter-clockwise from +x) and the run's outcome.
fn frozen_throw(phi_deg: f64, mu: f64) -> (f64, ClusterOutcome) {
    let phi = phi_deg.to_radians();
    let n1 = Vector3::new(phi.cos(), phi.sin(), 0.0);
    let cue = -2.0 * R * n1 - Vector3::new(1e-3, 0.0, 0.0);
    let balls = vec![
        at(cue, Vector3::new(SPEED, 0.0, 0.0)),
        at(Vector3::zeros(), Vector3::zeros()),
        at(Vector3::new(2.0 * R, 0.0, 0.0), Vector3::zeros()),
    ];
    let law = ContactLaw::calibrated(pool_k(), Damping::HuntCrossley, 0.93, 1.0, M / 2.0).unwrap();
    let cl = Cluster::new(balls, ClusterLaw::Same(law), mu).unwrap();
    let settings = ClusterSettings {
        rtol: 1e-10,
        stick: true,
    };
    let out = resolve_cluster(&cl, &settings).unwrap();
    assert_eq!(out.stop, StopReason::Separated);
    let v2 = out.balls[2].velocity;
    (v2.y.atan2(v2.x).to_degrees(), out)
}

/// From 30 degrees up the frozen contact slides throughout (derivation above) and the second
/// ball leaves at atan(mu) off the combination's line, towards the side the first ball is
/// driven to (Jewett's "let the friction drag the second ball"), below the published largest
/// throw.
#[test]
fn frozen_combination_throw_is_the_gross_sliding_closed_form() {
    let mu: f64 = 0.06;
    let expected = mu.atan().to_degrees();
    for phi in [30.0, 45.0, 60.0] {
        let (throw, out) = frozen_throw(phi, mu);
        eprintln!("cut {phi}: throw {throw:.9} deg, atan(mu) {expected:.9} deg");
        assert!(
            (throw - expected).abs() < CLOSED_FORM_TOL_DEG,
            "cut {phi}: throw {throw} deg, atan(mu) = {expected} deg"
        );
        assert!(throw > 0.0 && throw < published_max_throw_deg());
        // The frozen contact carried force (the run is the combination, not a miss).
        assert!(out
            .contacts
            .iter()
            .any(|c| c.pair == (1, 2) && c.normal_impulse > 0.0));
    }
}

/// At 15 degrees the derivation's margin is gone: Coulomb's bound throw <= atan(mu) still
/// holds (a stuck phase carries less than mu f), and the throw keeps its side.
#[test]
fn frozen_combination_throw_never_exceeds_coulombs_bound() {
    let mu: f64 = 0.06;
    for phi in [5.0, 10.0, 15.0, 20.0] {
        let (throw, _) = frozen_throw(phi, mu);
        eprintln!("cut {phi}: throw {throw:.6} deg");
        assert!(
            throw > 0.0,
            "cut {phi}: throw {throw} deg on the wrong side"
        );
        assert!(
            throw <= mu.atan().to_degrees() + CLOSED_FORM_TOL_DEG,
            "cut {phi}: throw {throw} deg above atan(mu)"
        );
    }
}

/// The published largest throw, about 1 inch per foot (4.76 degrees), is the gross-sliding
/// throw of mu = 1/12 = 0.083, inside the range of D. G. Alciatore's friction fit of TP A-14
/// (mu from 0.118 at zero slip down to 0.01 at large slip): the kernel reaches it at a
/// half-ball cut with that mu, and scales with mu as atan(mu) between.
#[test]
fn frozen_combination_throw_follows_mu() {
    for mu in [0.02f64, 0.04, 1.0 / 12.0] {
        let (throw, _) = frozen_throw(30.0, mu);
        let expected = mu.atan().to_degrees();
        eprintln!("mu {mu}: throw {throw:.9} deg, atan(mu) {expected:.9}");
        assert!((throw - expected).abs() < CLOSED_FORM_TOL_DEG);
    }
    let (throw, _) = frozen_throw(30.0, 1.0 / 12.0);
    assert!((throw - published_max_throw_deg()).abs() < CLOSED_FORM_TOL_DEG);
}
