//! The cloth under a collision: the plane at `height` along the unit vertical n = `up`,
//! checked against the balls' positions at contact, and the kinematics of a ball's contact
//! point with it.
//!
//! The contact point with the cloth is x - r n; its velocity is v + w x (-r n), whose
//! horizontal part is the slip
//!
//! ```text
//! u = v_h - r (w x n)          (v_h = v - (v.n) n)
//! ```

use super::params::TableParams;
use crate::base::error::Error;
use crate::model::params::Ball;
use nalgebra::Vector3;

/// Relative tolerance (of 2r) on the line of centres being horizontal and on the ball
/// centres' height r above the cloth.
pub const LEVEL_TOLERANCE: f64 = 1e-9;

/// The cloth under a collision: parameters, `up` and the plane's height, validated
/// against the balls' positions at contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Table {
    /// Parameters.
    pub params: TableParams,
    /// Unit vector away from the cloth (dimensionless).
    pub up: Vector3<f64>,
    /// Height of the cloth along `up` (m).
    pub height: f64,
}

impl Table {
    /// The cloth under balls of radii `radii` = [r_A, r_B] (m) touching at
    /// `positions` = [p_A, p_B] (m, lab): both must rest on one plane, so the centres'
    /// heights differ by r_B - r_A ((p_B - p_A).up = r_B - r_A; a horizontal line of centres
    /// for identical balls) and, when the parameters give a height, each centre is its own
    /// radius above it.
    pub fn new(
        params: TableParams,
        up: Vector3<f64>,
        positions: [Vector3<f64>; 2],
        radii: [f64; 2],
    ) -> Result<Self, Error> {
        let [pos_a, pos_b] = positions;
        let [radius, radius_b] = radii;
        let norm = up.norm();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(Error::invalid(
                "incoming.lab.up",
                format!("[{}, {}, {}]", up.x, up.y, up.z),
                "a non-zero direction",
            ));
        }
        let n = up / norm;
        let tol = LEVEL_TOLERANCE * (radius + radius_b);
        let rise = (pos_b - pos_a).dot(&n);
        if (rise - (radius_b - radius)).abs() > tol {
            return Err(Error::invalid(
                "incoming.lab.b.position",
                format!(
                    "[{}, {}, {}] ((p_B - p_A).up = {rise:e} m)",
                    pos_b.x, pos_b.y, pos_b.z
                ),
                "both balls on the cloth for the table effect: (p_B - p_A).up = r_B - r_A \
                 (0, a horizontal line of centres, for balls of one radius)",
            ));
        }
        let height = match params.height() {
            None => pos_a.dot(&n) - radius,
            Some(h) => {
                both_centres_r_above(h, &n, positions, radii, tol)?;
                h
            }
        };
        Ok(Table {
            params,
            up: n,
            height,
        })
    }

    /// Gravitational potential energy (J) of a ball centred at `position` (m, lab), zero on
    /// the cloth: m g (x.n - height - r).
    pub fn potential_energy(&self, ball: &Ball, position: &Vector3<f64>) -> f64 {
        ball.mass() * self.params.g() * (position.dot(&self.up) - self.height - ball.radius())
    }
}

/// Checks that the centres `[pos_a, pos_b]` (m, lab) lie their radii `[r_A, r_B]` (m)
/// above the cloth at height `h` (m along the unit `n`), within `tol` (m).
fn both_centres_r_above(
    h: f64,
    n: &Vector3<f64>,
    positions: [Vector3<f64>; 2],
    radii: [f64; 2],
    tol: f64,
) -> Result<(), Error> {
    for ((field, p), radius) in ["incoming.lab.a.position", "incoming.lab.b.position"]
        .into_iter()
        .zip(positions)
        .zip(radii)
    {
        let above = p.dot(n) - h;
        if (above - radius).abs() > tol {
            return Err(Error::invalid(
                field,
                format!(
                    "[{}, {}, {}] (centre {above} m above the cloth)",
                    p.x, p.y, p.z
                ),
                format!(
                    "the centre r = {radius} m above the cloth (table.height = {h} m along up) \
                     for the table effect"
                ),
            ));
        }
    }
    Ok(())
}

pub(crate) use crate::model::frame::horizontal;

/// The horizontal slip u = v_h - r (w x n) (m/s) of the contact point with the cloth, for
/// a ball with `velocity` (m/s) and `spin` (rad/s), `up` the unit vertical n.
pub fn cloth_slip(
    ball: &Ball,
    up: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> Vector3<f64> {
    horizontal(velocity, up) - ball.radius() * spin.cross(up)
}

/// The spin (rad/s) that rolls with `velocity` (m/s): horizontal part n x v_h / r, vertical
/// part that of `spin`.
pub(super) fn roll_spin(
    ball: &Ball,
    up: &Vector3<f64>,
    velocity: &Vector3<f64>,
    spin: &Vector3<f64>,
) -> Vector3<f64> {
    up.cross(&horizontal(velocity, up)) / ball.radius() + up * spin.dot(up)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Potential energy m g (x.n - height - r): zero for a ball resting on the cloth, m g h
    /// for its centre h higher. Balls of 0.17 kg and 28.575 mm touching on a cloth whose
    /// height follows from them (0.1 m below A's centre along up = +z, g from the defaults).
    #[test]
    fn potential_energy_is_zero_on_the_cloth() {
        let r = 0.028575;
        let ball = Ball::new(0.17, r, 0.4).unwrap();
        let (a, b) = (
            Vector3::new(0.0, 0.0, 0.1 + r),
            Vector3::new(2.0 * r, 0.0, 0.1 + r),
        );
        let params = TableParams::default();
        let g = params.g();
        let table = Table::new(params, Vector3::z(), [a, b], [r, r]).unwrap();
        assert!(table.potential_energy(&ball, &a).abs() < 1e-15);
        let h = 0.05;
        let up = a + Vector3::new(0.3, -0.2, h);
        let want = 0.17 * g * h;
        assert!((table.potential_energy(&ball, &up) - want).abs() < 1e-15 * want.max(1.0));
    }
}
