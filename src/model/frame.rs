//! The lab frame and the centre-of-mass frame of the paper.
//!
//! Basis: e_x = (p_B - p_A)/|p_B - p_A| (line of centres), e_z = `up` with its e_x part
//! removed, normalised (any perpendicular when `up` is parallel to e_x), e_y = e_z x e_x.
//! The centre-of-mass frame translates with V_cm = (v_A + v_B)/2 and its axes are the basis;
//! spins are the same in both frames (the frames do not rotate relative to each other).
//! For balls of different mass V_cm = (m_A v_A + m_B v_B) / (m_A + m_B); the state's u is
//! half the relative velocity (v_A - v_B) / 2 in every case, and A moves with
//! 2 m_B / (m_A + m_B) u, B with -2 m_A / (m_A + m_B) u relative to the centre of mass
//! (docs/unequal-balls.md).

use crate::base::error::Error;
use crate::model::params::BallPair;
use crate::model::state::{CmState, LabBall, LabMotion};
use nalgebra::{Matrix3, Vector3};

/// Relative tolerance on |p_B - p_A| = 2r (r_A + r_B for balls of different radii).
pub const TOUCH_TOLERANCE: f64 = 1e-9;

/// The horizontal part of `v`: v - up (v . up), its part perpendicular to the unit vector
/// `up` (any unit vector: the part perpendicular to it).
#[inline]
pub(crate) fn horizontal(v: &Vector3<f64>, up: &Vector3<f64>) -> Vector3<f64> {
    v - up * v.dot(up)
}

/// Both balls in the lab frame, with the direction `up` (away from the table).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LabScene {
    /// Ball A (the paper's ball at x = -r).
    pub a: LabBall,
    /// Ball B (at x = +r).
    pub b: LabBall,
    /// Direction away from the table (need not be normalised), default +z.
    pub up: Vector3<f64>,
}

/// The change of frame between a lab scene and the paper's centre-of-mass frame, made by
/// [`Frame::new`] (an orthonormal, right-handed basis) or [`Frame::paper`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    basis: Matrix3<f64>,
    v_cm: Vector3<f64>,
    up: Vector3<f64>,
    /// m_A / (m_A + m_B) and m_B / (m_A + m_B) (both 1/2 for identical balls).
    weights: [f64; 2],
}

impl Frame {
    /// The paper's frame itself: the identity basis, at rest, `up` = +z. Gives the throw
    /// angle of centre-of-mass scenes.
    pub fn paper() -> Self {
        Frame {
            basis: Matrix3::identity(),
            v_cm: Vector3::zeros(),
            up: Vector3::z(),
            weights: [0.5, 0.5],
        }
    }

    /// The frame of a lab scene of two identical balls of radius `radius` (m), see
    /// [`Frame::of_pair`].
    #[inline(always)]
    pub fn new(scene: &LabScene, radius: f64) -> Result<Self, Error> {
        // The weights of identical balls are 1/2 whatever their mass.
        Frame::build(scene, [radius, radius], [0.5, 0.5])
    }

    /// The frame of a lab scene whose balls touch: |p_B - p_A| = r_A + r_B within
    /// [`TOUCH_TOLERANCE`] relative; `up` must be a non-zero finite vector.
    #[inline(always)]
    pub fn of_pair(scene: &LabScene, balls: &BallPair) -> Result<Self, Error> {
        Frame::build(
            scene,
            [balls.a.radius(), balls.b.radius()],
            balls.mass_weights(),
        )
    }

    /// The frame of balls of radii `radii` touching in `scene`, whose centre of mass moves
    /// with the mass weights `weights`.
    #[inline(always)]
    fn build(scene: &LabScene, radii: [f64; 2], weights: [f64; 2]) -> Result<Self, Error> {
        let d = scene.b.position - scene.a.position;
        let dist = d.norm();
        // r + r = 2r exactly: identical balls keep the paper's test bit for bit.
        let contact = radii[0] + radii[1];
        let touching = (dist - contact).abs() <= TOUCH_TOLERANCE * contact;
        if !touching {
            return Err(Error::NotTouching {
                position_b: scene.b.position.into(),
                distance: dist,
                contact_distance: contact,
                contact_term: if radii[0] == radii[1] {
                    "2r"
                } else {
                    "r_A + r_B"
                },
                gap: dist - contact,
                tolerance: TOUCH_TOLERANCE,
            });
        }
        // Fast paths of the batch kernels' hot path, each giving the same numbers as the
        // general one: a unit `up` (such as the default +z) divided by its norm sqrt(1) = 1
        // is itself; so is e_z when, in addition, `up` is perpendicular to the line of
        // centres (balls of one radius on the table), as `up` - e_x 0 = `up`.
        let up_squared = scene.up.norm_squared();
        let up = if up_squared == 1.0 {
            scene.up
        } else {
            let up_norm = up_squared.sqrt();
            if !(up_norm > 0.0 && up_norm.is_finite()) {
                return Err(Error::invalid(
                    "incoming.lab.up",
                    format!("[{}, {}, {}]", scene.up.x, scene.up.y, scene.up.z),
                    "a non-zero direction",
                ));
            }
            scene.up / up_norm
        };
        let ex = d / dist;
        let ez = if up_squared == 1.0 && up.dot(&ex) == 0.0 {
            up
        } else {
            // e_z: `up` without its e_x part.
            let mut ez = horizontal(&up, &ex);
            let mut ez_norm = ez.norm();
            if ez_norm < 1e-12 {
                // `up` along the line of centres: any perpendicular will do (the result
                // does not depend on it); take the lab axis least aligned with e_x.
                let i = ex.iamin();
                let mut axis = Vector3::zeros();
                axis[i] = 1.0;
                ez = horizontal(&axis, &ex);
                ez_norm = ez.norm();
            }
            // `normalize` would take the norm again.
            ez / ez_norm
        };
        let ey = ez.cross(&ex);
        Ok(Frame {
            basis: Matrix3::from_columns(&[ex, ey, ez]),
            v_cm: weights[0] * scene.a.velocity + weights[1] * scene.b.velocity,
            up,
            weights,
        })
    }

    /// Columns e_x, e_y, e_z of the centre-of-mass basis, in lab coordinates.
    pub fn basis(&self) -> &Matrix3<f64> {
        &self.basis
    }

    /// Velocity of the centre of mass (m/s), lab frame.
    pub fn v_cm(&self) -> &Vector3<f64> {
        &self.v_cm
    }

    /// Unit `up` (lab coordinates).
    pub fn up(&self) -> &Vector3<f64> {
        &self.up
    }

    /// The centre-of-mass state of a lab scene.
    #[inline(always)]
    pub fn to_cm(&self, scene: &LabScene) -> CmState {
        let rt = self.basis.transpose();
        CmState {
            u_cm: rt * (0.5 * (scene.a.velocity - scene.b.velocity)),
            omega_a: rt * scene.a.spin,
            omega_b: rt * scene.b.spin,
        }
    }

    /// Lab-frame motions of A and B for a centre-of-mass state.
    #[inline(always)]
    pub fn to_lab(&self, cm: &CmState) -> (LabMotion, LabMotion) {
        let u = self.basis * cm.u_cm;
        let [wa, wb] = self.weights;
        (
            LabMotion {
                velocity: self.v_cm + u * (2.0 * wb),
                spin: self.basis * cm.omega_a,
            },
            LabMotion {
                velocity: self.v_cm - u * (2.0 * wa),
                spin: self.basis * cm.omega_b,
            },
        )
    }

    /// The outgoing lab motions of A and B for the outgoing centre-of-mass state `out` of the
    /// lab scene `lab` (whose frame this is), and the throw angle of B's velocity change
    /// ([`Frame::throw_angle_deg`]).
    #[inline(always)]
    pub fn outgoing(
        &self,
        lab: &LabScene,
        out: &CmState,
        collided: bool,
    ) -> (LabMotion, LabMotion, Option<f64>) {
        let (a, b) = self.to_lab(out);
        let throw = self.throw_of(&(b.velocity - lab.b.velocity), collided);
        (a, b, throw)
    }

    /// The throw angle (degrees) of a collision whose B velocity changed by `delta_v_b`
    /// ([`Frame::throw_angle_deg`]); `None` when the balls did not collide, where the change
    /// is the round-off of the change of frame, not a throw.
    #[inline(always)]
    pub fn throw_of(&self, delta_v_b: &Vector3<f64>, collided: bool) -> Option<f64> {
        if collided {
            self.throw_angle_deg(delta_v_b)
        } else {
            None
        }
    }

    /// The throw angle (degrees): the signed angle, counter-clockwise about `up`, from the
    /// horizontal line of centres to the horizontal part of B's velocity change
    /// `delta_v_b` (lab frame). `None` when the line of centres is vertical or the
    /// horizontal velocity change vanishes.
    #[inline(always)]
    pub fn throw_angle_deg(&self, delta_v_b: &Vector3<f64>) -> Option<f64> {
        let ex = self.basis.column(0).into_owned();
        let line = horizontal(&ex, &self.up);
        let dv = horizontal(delta_v_b, &self.up);
        // |line| < 1e-12, |dv| <= 1e-12 |delta_v_b| or dv = 0, in squares (no square roots
        // on the batch kernels' hot path).
        let dv2 = dv.norm_squared();
        if line.norm_squared() < 1e-24 || dv2 <= 1e-24 * delta_v_b.norm_squared() || dv2 == 0.0 {
            return None;
        }
        let sin = line.cross(&dv).dot(&self.up);
        let cos = line.dot(&dv);
        // libm's atan2 (within an ulp, as the system's) costs two thirds of the system's.
        Some(libm::atan2(sin, cos).to_degrees())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(p: [f64; 3]) -> LabBall {
        LabBall {
            position: Vector3::from(p),
            velocity: Vector3::new(1.0, 0.0, 0.0),
            spin: Vector3::zeros(),
        }
    }

    /// Balls 7 cm apart with r = 3 cm: NotTouching with a 1 cm gap, bad input, and its
    /// message in the form of an InvalidParameter naming the field.
    #[test]
    fn balls_apart_are_not_touching() {
        let scene = LabScene {
            a: at([0.0; 3]),
            b: at([0.07, 0.0, 0.0]),
            up: Vector3::z(),
        };
        let e = Frame::new(&scene, 0.03).unwrap_err();
        let Error::NotTouching {
            gap,
            distance,
            contact_distance,
            ..
        } = e
        else {
            panic!("{e:?}");
        };
        assert!((distance - 0.07).abs() < 1e-15);
        assert_eq!(contact_distance, 0.06);
        assert!((gap - 0.01).abs() < 1e-15);
        let old = Error::invalid(
            "incoming.lab.b.position",
            format!("[0.07, 0, 0] (|p_B - p_A| = {distance} m)"),
            format!(
                "the balls must touch: |p_B - p_A| = 2r = 0.06 m within a relative \
                 {TOUCH_TOLERANCE:e}"
            ),
        );
        assert_eq!(e.to_string(), old.to_string());
        assert!(e.is_bad_input());
    }

    #[test]
    fn horizontal_part_by_hand() {
        // up = (0, 0.6, 0.8) (unit), v = (1, 2, 3): v . up = 1.2 + 2.4 = 3.6, so
        // v - 3.6 up = (1, 2 - 2.16, 3 - 2.88) = (1, -0.16, 0.12), and that is
        // perpendicular to up: -0.16 * 0.6 + 0.12 * 0.8 = 0.
        let up = Vector3::new(0.0, 0.6, 0.8);
        let h = horizontal(&Vector3::new(1.0, 2.0, 3.0), &up);
        assert!((h - Vector3::new(1.0, -0.16, 0.12)).amax() < 1e-15, "{h}");
        assert!(h.dot(&up).abs() < 1e-15);
        // A vertical vector has no horizontal part; a horizontal one is its own.
        assert_eq!(
            horizontal(&(2.5 * Vector3::z()), &Vector3::z()),
            Vector3::zeros()
        );
        let flat = Vector3::new(0.3, -0.7, 0.0);
        assert_eq!(horizontal(&flat, &Vector3::z()), flat);
    }

    fn ball(p: [f64; 3], v: [f64; 3], w: [f64; 3]) -> LabBall {
        LabBall {
            position: Vector3::from(p),
            velocity: Vector3::from(v),
            spin: Vector3::from(w),
        }
    }

    #[test]
    fn round_trip_is_identity() {
        let r = 0.03;
        let scene = LabScene {
            a: ball([0.1, 0.2, 0.03], [1.0, 0.4, -0.1], [3.0, -2.0, 1.0]),
            b: ball(
                [0.1 + 0.036, 0.2 + 0.048, 0.03],
                [0.2, -0.3, 0.0],
                [0.5, 0.0, 7.0],
            ),
            up: Vector3::new(0.0, 0.0, 2.0),
        };
        let f = Frame::new(&scene, r).unwrap();
        // Orthonormal, right-handed.
        let q = f.basis.transpose() * f.basis;
        assert!((q - Matrix3::identity()).norm() < 1e-15);
        assert!((f.basis.determinant() - 1.0).abs() < 1e-15);
        let cm = f.to_cm(&scene);
        let (a, b) = f.to_lab(&cm);
        assert!((a.velocity - scene.a.velocity).norm() < 1e-15);
        assert!((b.velocity - scene.b.velocity).norm() < 1e-15);
        assert!((a.spin - scene.a.spin).norm() < 1e-14);
        assert!((b.spin - scene.b.spin).norm() < 1e-14);
    }

    #[test]
    fn unit_up_and_any_up_give_the_basis_of_balls_on_the_table() {
        // Balls of one radius on the table (the line of centres d horizontal): by hand,
        // e_x = d / |d|, e_z = up = z and e_y = z x e_x = (-e_x.y, e_x.x, 0), exact in floating
        // point. The unit `up` takes the fast path, (0, 0, 4) the general one (4 / 4 = 1): both
        // must give these numbers to the bit, and an inclined `up` a tilted e_z.
        let r = 0.028575;
        for k in 0..64 {
            let phi = 0.1 + k as f64 * 0.41;
            let d = Vector3::new(2.0 * r * phi.cos(), 2.0 * r * phi.sin(), 0.0);
            let pa = [0.3 + 0.01 * k as f64, 0.9, r];
            let pb = [pa[0] + d.x, pa[1] + d.y, r];
            // The positions differ from pa + d by round-off: e_x from their own difference.
            let ex = (Vector3::from(pb) - Vector3::from(pa)).normalize();
            let by_hand =
                Matrix3::from_columns(&[ex, Vector3::new(-ex.y, ex.x, 0.0), Vector3::z()]);
            for up in [Vector3::z(), Vector3::new(0.0, 0.0, 4.0)] {
                let scene = LabScene {
                    a: ball(pa, [1.0, 0.0, 0.0], [0.0; 3]),
                    b: ball(pb, [0.0; 3], [0.0; 3]),
                    up,
                };
                let f = Frame::new(&scene, r).unwrap();
                assert_eq!(f.basis, by_hand, "up {up}");
                assert_eq!(*f.up(), Vector3::z());
            }
            // `up` tilted towards e_y by 0.3 rad: e_z is up itself (still perpendicular to e_x).
            let (sin, cos) = 0.3_f64.sin_cos();
            let tilt = Vector3::new(-ex.y * sin, ex.x * sin, cos);
            let scene = LabScene {
                a: ball(pa, [1.0, 0.0, 0.0], [0.0; 3]),
                b: ball(pb, [0.0; 3], [0.0; 3]),
                up: tilt,
            };
            let f = Frame::new(&scene, r).unwrap();
            assert!((f.basis.column(2) - tilt).amax() < 1e-15);
            assert!((f.basis.column(1).dot(&Vector3::z()) + sin).abs() < 1e-15);
        }
    }

    #[test]
    fn up_along_line_of_centres_still_gives_a_basis() {
        let scene = LabScene {
            a: ball([0.0; 3], [0.0, 0.0, -1.0], [0.0; 3]),
            b: ball([0.0, 0.0, -0.06], [0.0; 3], [0.0; 3]),
            up: Vector3::z(),
        };
        let f = Frame::new(&scene, 0.03).unwrap();
        let q = f.basis.transpose() * f.basis;
        assert!((q - Matrix3::identity()).norm() < 1e-15);
        assert_eq!(f.throw_angle_deg(&Vector3::new(0.0, 0.0, -1.0)), None);
    }

    #[test]
    fn touching_means_within_one_part_in_1e9_of_the_contact_distance() {
        // docs/formats.md: | |p_B - p_A| - (r_A + r_B) | <= 1e-9 (r_A + r_B). Pool balls of
        // radius 0.028575 m (2r = 0.05715 m, so 1e-9 2r = 5.7e-11 m, far above the 7e-18 m
        // of an ulp here), B along x at 2r times 1 + k 1e-9: k = +-0.5 touch, k = +-2 do
        // not; unequal radii (0.03 + 0.02 m) the same.
        for radii in [[0.028575, 0.028575], [0.03, 0.02]] {
            let contact = radii[0] + radii[1];
            for (k, touches) in [(0.5, true), (-0.5, true), (2.0, false), (-2.0, false)] {
                let scene = LabScene {
                    a: ball([0.0; 3], [1.0, 0.0, 0.0], [0.0; 3]),
                    b: ball([contact * (1.0 + k * 1e-9), 0.0, 0.0], [0.0; 3], [0.0; 3]),
                    up: Vector3::z(),
                };
                match Frame::build(&scene, radii, [0.5, 0.5]) {
                    Ok(_) => assert!(touches, "{radii:?}, gap {k:e} contact: accepted"),
                    Err(Error::NotTouching { .. }) => {
                        assert!(!touches, "{radii:?}, gap {k:e} contact: refused")
                    }
                    Err(e) => panic!("{e}"),
                }
            }
        }
    }

    #[test]
    fn throw_angle_sign_is_counter_clockwise_about_up() {
        let scene = LabScene {
            a: ball([-0.03, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0; 3]),
            b: ball([0.03, 0.0, 0.0], [0.0; 3], [0.0; 3]),
            up: Vector3::z(),
        };
        let f = Frame::new(&scene, 0.03).unwrap();
        let a = f.throw_angle_deg(&Vector3::new(1.0, 1.0, -0.3)).unwrap();
        assert!((a - 45.0).abs() < 1e-12);
        let a = f.throw_angle_deg(&Vector3::new(1.0, -1.0, 0.0)).unwrap();
        assert!((a + 45.0).abs() < 1e-12);
        // The angle does not depend on the size of the change: a change of 1e-9 m/s.
        let a = f
            .throw_angle_deg(&Vector3::new(1e-9, 1e-9, -3e-10))
            .unwrap();
        assert!((a - 45.0).abs() < 1e-12, "{a}");
        // A horizontal part at 1e-13 of a vertical change is round-off: no throw.
        assert_eq!(f.throw_angle_deg(&Vector3::new(1e-13, 0.0, 1.0)), None);
    }
}
