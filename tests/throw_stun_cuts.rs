//! Throw of the object ball in stun cut shots, through the scene runner (lab frame).
//!
//! Ball B at rest, ball A without spin moving at speed v with cut angle c to the horizontal
//! line of centres. In the centre-of-mass frame U(0) = v cos(c)/2, the slip is 2V = v sin(c)
//! along the side direction (theta = 0), P = (1 + e) m U(0), and B's velocity change is
//! (P, J)/m along (line of centres, side). So tan(throw) = J / P:
//! - sliding throughout, J = mu P: throw = atan(mu);
//! - sliding stops (tan c < mu (1 + e)(1 + 1/alpha)), J = m S(0) / (2 (1 + 1/alpha)):
//!   tan(throw) = tan(c) / ((1 + e)(1 + 1/alpha)), tan(c)/7 for alpha = 2/5, e = 1 (docs/model.md).
//!
//! Sign (docs/formats.md): counter-clockwise about `up`. A moving towards +y drags B's surface
//! towards +y, so with up = +z the throw is positive; mirrored shots and an upside-down
//! `up` flip it; rotating the whole shot about `up` does not change it.

use billiard_contact::Scene;
use billiard_contact::{run_scene, SceneOutcome};
use billiard_contact::{Method, SolverSettings};
use std::path::Path;

const M: f64 = 0.17;
const R: f64 = 0.028575;
const SPEED: f64 = 1.6;
/// Throw angle accuracy (radians): closed form to round-off; adaptive time stepping at
/// rtol 1e-12 (state within ~1e-11 scaled); RK4 with 1000 steps (O(h^4) ~ 1e-12).
const CLOSED_FORM_TOL: f64 = 1e-12;
const STEPPING_TOL: f64 = 1e-11;

struct Shot {
    cut_deg: f64,
    mu: f64,
    e: f64,
    alpha: f64,
    /// Direction of the line of centres in the table plane (degrees from +x).
    heading_deg: f64,
    up: [f64; 3],
}

impl Shot {
    fn new(cut_deg: f64, mu: f64, e: f64, alpha: f64) -> Self {
        Shot {
            cut_deg,
            mu,
            e,
            alpha,
            heading_deg: 0.0,
            up: [0.0, 0.0, 1.0],
        }
    }

    /// The scene as a user would write it: balls on the table plane z = r, B at rest.
    fn scene(&self) -> Scene {
        let h = self.heading_deg.to_radians();
        let (hc, hs) = (h.cos(), h.sin());
        let c = self.cut_deg.to_radians();
        // Velocity at angle c to the line of centres, rotated by the heading about z.
        let (vx, vy) = (SPEED * c.cos(), SPEED * c.sin());
        let v = [vx * hc - vy * hs, vx * hs + vy * hc];
        let text = format!(
            "name = \"stun cut\"\n\
             [balls]\nmass = {M:?}\nradius = {R:?}\nalpha = {:?}\n\
             [contact]\nmu = {:?}\nrestitution = {:?}\n\
             [contact.profile]\nshape = \"half-sine\"\nduration = 2.5e-4\n\
             [incoming.lab]\n\
             a = {{ position = [{:?}, {:?}, {R:?}], velocity = [{:?}, {:?}, 0.0] }}\n\
             b = {{ position = [{:?}, {:?}, {R:?}], velocity = [0.0, 0.0, 0.0] }}\n\
             up = [{:?}, {:?}, {:?}]\n",
            self.alpha,
            self.mu,
            self.e,
            0.3 - R * hc,
            0.5 - R * hs,
            v[0],
            v[1],
            0.3 + R * hc,
            0.5 + R * hs,
            self.up[0],
            self.up[1],
            self.up[2],
        );
        Scene::parse(&text, Path::new("."), None).unwrap()
    }

    /// Whether sliding stops: tan c < mu (1 + e)(1 + 1/alpha).
    fn sticks(&self) -> bool {
        self.cut_deg.abs().to_radians().tan() < self.mu * (1.0 + self.e) * (1.0 + 1.0 / self.alpha)
    }

    /// The expected throw (radians, counter-clockwise about +z for a positive cut).
    fn expected(&self) -> f64 {
        let c = self.cut_deg.to_radians();
        let magnitude = if self.sticks() {
            (c.abs().tan() / ((1.0 + self.e) * (1.0 + 1.0 / self.alpha))).atan()
        } else {
            self.mu.atan()
        };
        magnitude * c.signum()
    }

    fn run(&self, method: Method) -> SceneOutcome {
        let settings = SolverSettings::new(method, 1e-12, 1e-12, 1000).unwrap();
        run_scene(&self.scene(), &settings, None).unwrap()
    }
}

fn throw_rad(so: &SceneOutcome) -> f64 {
    so.throw_angle_deg.expect("a throw angle").to_radians()
}

fn check(shot: &Shot, sign: f64) -> (f64, f64) {
    let want = sign * shot.expected();
    let mut errs = (0.0_f64, 0.0_f64);
    for (method, tol) in [
        (Method::ClosedForm, CLOSED_FORM_TOL),
        (Method::Dop853, STEPPING_TOL),
        (Method::Dopri5, STEPPING_TOL),
        (Method::Rk4, STEPPING_TOL),
    ] {
        let so = shot.run(method);
        assert_eq!(
            so.outcome.result.sticks,
            shot.sticks(),
            "cut {}",
            shot.cut_deg
        );
        let got = throw_rad(&so);
        let err = (got - want).abs();
        assert!(
            err <= tol,
            "cut {} deg, mu {}, e {}, alpha {}, heading {}, up {:?}, {method}: throw {} deg, \
             expected {} deg",
            shot.cut_deg,
            shot.mu,
            shot.e,
            shot.alpha,
            shot.heading_deg,
            shot.up,
            got.to_degrees(),
            want.to_degrees()
        );
        if method == Method::ClosedForm {
            errs.0 = err;
        } else {
            errs.1 = errs.1.max(err);
        }
    }
    errs
}

#[test]
fn sliding_stun_cuts_throw_by_atan_mu() {
    let (mut w0, mut w1) = (0.0_f64, 0.0_f64);
    // mu (1 + e)(1 + 1/alpha) = 0.42 for the first ones: cuts above 22.8 degrees slide.
    for (cut, mu, e, alpha) in [
        (25.0, 0.06, 1.0, 0.4),
        (40.0, 0.06, 1.0, 0.4),
        (60.0, 0.06, 1.0, 0.4),
        (85.0, 0.06, 1.0, 0.4),
        (30.0, 0.06, 0.5, 0.4),
        (45.0, 0.1, 0.8, 2.0 / 3.0),
        (70.0, 0.2, 1.0, 0.4),
    ] {
        let shot = Shot::new(cut, mu, e, alpha);
        assert!(!shot.sticks());
        let (a, b) = check(&shot, 1.0);
        w0 = w0.max(a);
        w1 = w1.max(b);
    }
    eprintln!("sliding: throw errors closed form {w0:.2e} rad, time stepping {w1:.2e} rad");
}

#[test]
fn sticking_stun_cuts_throw_by_atan_tan_cut_over_7() {
    let (mut w0, mut w1) = (0.0_f64, 0.0_f64);
    for (cut, mu, e, alpha) in [
        (1.0, 0.06, 1.0, 0.4),
        (10.0, 0.06, 1.0, 0.4),
        (15.0, 0.06, 1.0, 0.4),
        (22.0, 0.06, 1.0, 0.4),
        (10.0, 0.06, 0.5, 0.4),
        (20.0, 0.1, 0.8, 2.0 / 3.0),
        (50.0, 0.5, 1.0, 0.4),
    ] {
        let shot = Shot::new(cut, mu, e, alpha);
        assert!(shot.sticks());
        if e == 1.0 && alpha == 0.4 {
            // The literature's limit: tan(throw) = tan(cut) / 7.
            let t = (cut.to_radians().tan() / 7.0).atan();
            assert!((shot.expected() - t).abs() <= 1e-15);
        }
        let (a, b) = check(&shot, 1.0);
        w0 = w0.max(a);
        w1 = w1.max(b);
    }
    eprintln!("sticking: throw errors closed form {w0:.2e} rad, time stepping {w1:.2e} rad");
}

/// At tan(c) = mu (1 + e)(1 + 1/alpha) the two laws meet: the throw is continuous.
#[test]
fn throw_is_continuous_where_sliding_stops_at_separation() {
    let mu = 0.06;
    let c_star = (mu * 2.0 * 3.5_f64).atan().to_degrees();
    let below = Shot::new(c_star - 1e-6, mu, 1.0, 0.4);
    let above = Shot::new(c_star + 1e-6, mu, 1.0, 0.4);
    assert!(below.sticks() && !above.sticks());
    let (tb, ta) = (
        throw_rad(&below.run(Method::ClosedForm)),
        throw_rad(&above.run(Method::ClosedForm)),
    );
    assert!((tb - mu.atan()).abs() <= 1e-8 && (ta - mu.atan()).abs() <= 1e-12);
}

/// Sign convention: mirrored cuts throw the other way; `up` = -z flips the sign; the
/// direction of the line of centres on the table does not matter.
#[test]
fn throw_sign_is_counter_clockwise_about_up() {
    for (cut, mu) in [(10.0, 0.06), (40.0, 0.06)] {
        check(&Shot::new(-cut, mu, 1.0, 0.4), 1.0);
        let mut flipped = Shot::new(cut, mu, 1.0, 0.4);
        flipped.up = [0.0, 0.0, -1.0];
        check(&flipped, -1.0);
        for heading in [30.0, 135.0, -100.0] {
            let mut turned = Shot::new(cut, mu, 1.0, 0.4);
            turned.heading_deg = heading;
            check(&turned, 1.0);
        }
    }
    // A positive cut means A moves towards +y: B is thrown towards +y, a positive angle.
    let so = Shot::new(30.0, 0.06, 1.0, 0.4).run(Method::ClosedForm);
    let (_, b) = so.lab_out.unwrap();
    assert!(b.velocity.y > 0.0 && so.throw_angle_deg.unwrap() > 0.0);
}

/// Full hit: no slip, no friction, B leaves along the line of centres: throw exactly 0.
#[test]
fn full_hit_has_no_throw() {
    for method in [
        Method::ClosedForm,
        Method::Dop853,
        Method::Rk4,
        Method::Dopri5,
    ] {
        let so = Shot::new(0.0, 0.06, 1.0, 0.4).run(method);
        assert_eq!(so.throw_angle_deg, Some(0.0), "{method}");
    }
}

/// The throw is undefined (null) when the line of centres is vertical or B's horizontal
/// velocity does not change (no collision).
#[test]
fn throw_is_undefined_without_a_horizontal_line_or_change() {
    let vertical = format!(
        "[balls]\nmass = {M:?}\nradius = {R:?}\n[contact]\nmu = 0.06\n\
         [contact.profile]\nshape = \"half-sine\"\nduration = 2.5e-4\n\
         [incoming.lab]\n\
         a = {{ position = [0.0, 0.0, {:?}], velocity = [0.1, 0.0, -1.0] }}\n\
         b = {{ position = [0.0, 0.0, {R:?}], velocity = [0.0, 0.0, 0.0] }}\n",
        3.0 * R
    );
    let apart = format!(
        "[balls]\nmass = {M:?}\nradius = {R:?}\n[contact]\nmu = 0.06\n\
         [contact.profile]\nshape = \"half-sine\"\nduration = 2.5e-4\n\
         [incoming.lab]\n\
         a = {{ position = [{:?}, 0.0, {R:?}], velocity = [-1.0, 0.5, 0.0] }}\n\
         b = {{ position = [{R:?}, 0.0, {R:?}], velocity = [0.0, 0.0, 0.0] }}\n",
        -R
    );
    for text in [vertical, apart] {
        let scene = Scene::parse(&text, Path::new("."), None).unwrap();
        for method in [Method::ClosedForm, Method::Dop853] {
            let settings = SolverSettings::default().with_method(method);
            let so = run_scene(&scene, &settings, None).unwrap();
            assert_eq!(so.throw_angle_deg, None, "{text}");
        }
    }
}
