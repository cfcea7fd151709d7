//! The table phase of one ball written out from its physics (docs/model.md#the-table-phase),
//! not calling the library: a flight under gravity, impacts with the cloth (Newton's law of
//! restitution along `up`, Coulomb friction bounded by the impulse that stops the slip),
//! bounces until the vertical speed after an impact is below 1e-3 m/s, a slide with constant
//! friction -mu_t m g u/|u| (the slip keeps its direction), then rolling, with rolling
//! resistance and the decay of the spin about `up` on the cloth.

use super::Balls;
use nalgebra::Vector3;

/// The cloth: friction, restitution, gravity, rolling resistance, spin decay, the unit `up`.
#[derive(Debug, Clone, Copy)]
pub struct Cloth {
    pub mu: f64,
    pub restitution: f64,
    pub g: f64,
    pub rolling_resistance: f64,
    pub spin_decay: f64,
    pub up: Vector3<f64>,
}

/// One impact with the cloth: the state after it and its impulses.
#[derive(Debug, Clone, Copy)]
pub struct Impact {
    pub time: f64,
    pub velocity: Vector3<f64>,
    pub spin: Vector3<f64>,
    pub normal_impulse: f64,
    pub tangential_impulse: f64,
    pub sticks: bool,
}

/// A ball's roll-out, the quantities of the JSON `table.a` / `table.b` objects.
#[derive(Debug, Clone)]
pub struct RollOut {
    /// Times of the impacts with a normal impulse, in order.
    pub impacts: Vec<f64>,
    pub hop_time: f64,
    pub hop_height: f64,
    pub impact: Impact,
    pub bounces: u64,
    pub settle_time: f64,
    pub slide_time: f64,
    pub slide_displacement: Vector3<f64>,
    pub roll_time: f64,
    pub rolling_velocity: Vector3<f64>,
    pub rolling_spin: Vector3<f64>,
    pub rolling_position: Vector3<f64>,
    /// (time, position) of rest, with rolling resistance.
    pub rest: Option<(f64, Vector3<f64>)>,
    pub table_impulse: Vector3<f64>,
    pub end_time: f64,
}

/// Vertical speed after an impact below which the ball stays on the cloth (m/s).
const SETTLE_SPEED: f64 = 1e-3;

impl Cloth {
    fn horizontal(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.up * v.dot(&self.up)
    }

    /// The velocity of the ball's lowest point, x - r n: v_h - r (w x n) (no normal part).
    fn slip(&self, b: &Balls, v: &Vector3<f64>, w: &Vector3<f64>) -> Vector3<f64> {
        self.horizontal(v) - b.r * w.cross(&self.up)
    }

    /// An impact at `time`: P_n = (1 + e) m |v . n| when moving down; the friction impulse
    /// J against the slip u changes v by -J u^/m and w by J (n x u^) / (alpha m r), so the
    /// slip by -J (1 + 1/alpha) u^/m: at most mu P_n, at most what stops the slip.
    fn impact(&self, b: &Balls, time: f64, v: Vector3<f64>, w: Vector3<f64>) -> Impact {
        let n = self.up;
        let vn = v.dot(&n);
        let normal = if vn < 0.0 {
            (1.0 + self.restitution) * b.m * -vn
        } else {
            0.0
        };
        let u = self.slip(b, &v, &w);
        let su = u.norm();
        let stop = b.m * su / (1.0 + 1.0 / b.alpha);
        let tangential = (self.mu * normal).min(stop);
        let dir = if su > 0.0 { u / su } else { Vector3::zeros() };
        Impact {
            time,
            velocity: v + (normal * n - tangential * dir) / b.m,
            spin: w + tangential * n.cross(&dir) / (b.alpha * b.m * b.r),
            normal_impulse: normal,
            tangential_impulse: tangential,
            sticks: normal > 0.0 && tangential == stop,
        }
    }

    /// The roll-out of a ball leaving the contact at `x0` with velocity `v0` and spin `w0`.
    pub fn roll_out(
        &self,
        b: &Balls,
        x0: Vector3<f64>,
        v0: Vector3<f64>,
        w0: Vector3<f64>,
    ) -> RollOut {
        let (n, g) = (self.up, self.g);
        // Flight: up at v . n, back down after 2 v . n / g at -v . n, same horizontal velocity.
        let flight = |v: Vector3<f64>| -> (f64, Vector3<f64>) {
            let vn = v.dot(&n);
            (2.0 * vn / g, v - 2.0 * vn * n)
        };
        let vn0 = v0.dot(&n);
        let (hop_time, hop_height) = if vn0 > 0.0 {
            (2.0 * vn0 / g, vn0 * vn0 / (2.0 * g))
        } else {
            (0.0, 0.0)
        };
        let (mut t, mut x, mut v, w) = (0.0, x0, v0, w0);
        if vn0 > 0.0 {
            let (dt, landing) = flight(v);
            x += self.horizontal(&v) * dt;
            (t, v) = (dt, landing);
        }
        let first = self.impact(b, t, v, w);
        let (mut imp, mut bounces) = (first, 0);
        let mut impacts: Vec<f64> = (first.normal_impulse > 0.0)
            .then_some(t)
            .into_iter()
            .collect();
        while imp.velocity.dot(&n) >= SETTLE_SPEED {
            bounces += 1;
            let (dt, landing) = flight(imp.velocity);
            x += self.horizontal(&imp.velocity) * dt;
            t += dt;
            imp = self.impact(b, t, landing, imp.spin);
            impacts.push(t);
        }
        let settle_time = t;
        // The cloth absorbs what is left of the vertical speed.
        let (v, w) = (self.horizontal(&imp.velocity), imp.spin);
        // Slide: du/dt = -mu g (1 + 1/alpha) u^ until u = 0.
        let u = self.slip(b, &v, &w);
        let su = u.norm();
        let dir = if su > 0.0 { u / su } else { Vector3::zeros() };
        let a = self.mu * g;
        let slide_time = su / (a * (1.0 + 1.0 / b.alpha));
        let slide_displacement = v * slide_time - 0.5 * a * dir * slide_time * slide_time;
        let rolling_velocity = v - a * dir * slide_time;
        let mut rolling_spin = w + a * n.cross(&dir) * slide_time / (b.alpha * b.r);
        // Spin decay: on the cloth |w . n| falls at mu_sp g / (alpha r), to 0 at most; the
        // ball is on the cloth for the whole slide (impacts take no time).
        let wn = rolling_spin.dot(&n);
        let decayed =
            (wn.abs() - self.spin_decay * g / (b.alpha * b.r) * slide_time).max(0.0) * wn.signum();
        rolling_spin += (decayed - wn) * n;
        let roll_time = settle_time + slide_time;
        let rolling_position = x + slide_displacement;
        let speed = rolling_velocity.norm();
        let rest = (self.rolling_resistance > 0.0).then(|| {
            let dec = self.rolling_resistance * g;
            (
                roll_time + speed / dec,
                rolling_position + rolling_velocity * speed / (2.0 * dec),
            )
        });
        let (end_time, v_end) = match rest {
            Some((time, _)) => (time, Vector3::zeros()),
            None => (roll_time, rolling_velocity),
        };
        // Newton for the whole phase: the cloth's impulse is the momentum change plus what
        // carried the weight, m (v_end - v0) + m g n t_end.
        let table_impulse = b.m * (v_end - v0) + b.m * g * end_time * n;
        RollOut {
            impacts,
            hop_time,
            hop_height,
            impact: first,
            bounces,
            settle_time,
            slide_time,
            slide_displacement,
            roll_time,
            rolling_velocity,
            rolling_spin,
            rolling_position,
            rest,
            table_impulse,
            end_time,
        }
    }

    /// The angle (degrees, counter-clockwise about up) from `from` to `to` on the cloth.
    pub fn angle_deg(&self, from: &Vector3<f64>, to: &Vector3<f64>) -> f64 {
        let (f, t) = (self.horizontal(from), self.horizontal(to));
        f.cross(&t).dot(&self.up).atan2(f.dot(&t)).to_degrees()
    }
}
