//! The force-time curve of an elastic Hertz impact.
//!
//! The compression delta obeys delta'' = -c delta^(3/2), delta(0) = 0, delta'(0) = v0, and
//! the force is proportional to delta^(3/2). Energy conservation,
//! delta'^2 / 2 + (2/5) c delta^(5/2) = v0^2 / 2, gives with u = (delta / delta_max)^(5/2)
//! and w = delta' / v0 = sqrt(1 - u):
//!
//! ```text
//! s(u)   = I_u(2/5, 1/2) / 2                         (time, s = t / tau, rising half)
//! phi(s) = (B(2/5, 1/2) / 2) u^(3/5)                 (force, normalised)
//! Phi(s) = (1 - w) / 2 = u / (2 (1 + w))             (impulse = momentum change)
//! ```
//!
//! and the pulse is symmetric about s = 1/2. The contact time is
//! (4/5) B(2/5, 1/2) delta_max / v0 (ERRATA.md; 2.9432752... delta_max / v0). The curve's
//! shape is universal: c and v0 only set the duration and the impulse, both given.

use super::beta::{beta, inc_beta};
use super::ForceProfile;

/// a = 2/5 in I_u(a, b).
const A: f64 = 0.4;
/// b = 1/2 in I_u(a, b).
const B_: f64 = 0.5;

/// The elastic Hertz pulse (not the sin^1.5 approximation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    duration: f64,
    /// B(2/5, 1/2).
    beta_ab: f64,
}

/// A point of the rising half: u = (delta/delta_max)^(5/2) and w = sqrt(1 - u), both to
/// full relative accuracy.
#[derive(Debug, Clone, Copy)]
struct Phase {
    u: f64,
    w: f64,
}

impl Hertz {
    /// A Hertz pulse of `duration` tau (s), validated by the caller.
    ///
    /// ```
    /// use billiard_contact::profile::{ForceProfile, Hertz};
    /// let p = Hertz::new(1.0);
    /// // peak of phi: B(2/5, 1/2) / 2
    /// let b = billiard_contact::profile::beta::beta(0.4, 0.5);
    /// assert!((p.shape(0.5) - b / 2.0).abs() < 1e-12);
    /// ```
    pub fn new(duration: f64) -> Self {
        Hertz {
            duration,
            beta_ab: beta(A, B_),
        }
    }

    /// The phase at scaled time s in [0, 1/2]: solves I_u(2/5, 1/2) = 2 s.
    fn phase(&self, s: f64) -> Phase {
        let t2 = (2.0 * s).clamp(0.0, 1.0);
        let bb = self.beta_ab;
        if t2 == 0.0 {
            return Phase { u: 0.0, w: 1.0 };
        }
        if t2 <= 0.5 {
            // Newton in z = u^a: I = z / (a B) (1 + O(u)), dI/dz = 1 / (a B w).
            let mut z = (A * bb * t2).min(1.0);
            for _ in 0..40 {
                let u = z.powf(1.0 / A);
                let w = (1.0 - u).sqrt();
                let i = inc_beta(A, B_, u, 1.0 - u, bb);
                let dz = (i - t2) * A * bb * w;
                let z_new = (z - dz).clamp(0.0, 1.0);
                let done = (z_new - z).abs() <= 2.0 * f64::EPSILON * z;
                z = z_new;
                if done {
                    break;
                }
            }
            let u = z.powf(1.0 / A);
            Phase {
                u,
                w: (1.0 - u).sqrt(),
            }
        } else {
            // Newton in w: J(w) = I_{w^2}(1/2, 2/5) = 1 - 2 s, dJ/dw = 2 u^(a-1) / B.
            let t3 = 1.0 - t2;
            let mut w = (0.5 * bb * t3).min(1.0);
            for _ in 0..40 {
                let y = w * w;
                let u = 1.0 - y;
                let j = inc_beta(B_, A, y, u, bb);
                let dw = (j - t3) * bb * u.powf(1.0 - A) / 2.0;
                let w_new = (w - dw).clamp(0.0, 1.0);
                let done = (w_new - w).abs() <= 2.0 * f64::EPSILON * w.max(1e-300);
                w = w_new;
                if done {
                    break;
                }
            }
            Phase { u: 1.0 - w * w, w }
        }
    }
}

impl ForceProfile for Hertz {
    fn duration(&self) -> f64 {
        self.duration
    }

    /// The force grows like t^1.5 from both ends: steps graded toward them.
    fn breakpoints(&self) -> &[f64] {
        &super::GRADED_ENDS
    }

    fn shape(&self, s: f64) -> f64 {
        if !(0.0..=1.0).contains(&s) {
            return 0.0;
        }
        let ph = self.phase(s.min(1.0 - s));
        0.5 * self.beta_ab * ph.u.powf(1.0 - A)
    }

    fn cumulative(&self, s: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        if s >= 1.0 {
            return 1.0;
        }
        let half = |s: f64| {
            let ph = self.phase(s);
            ph.u / (2.0 * (1.0 + ph.w))
        };
        if s <= 0.5 {
            half(s)
        } else {
            1.0 - half(1.0 - s)
        }
    }

    /// Exact inverse: Phi = q <= 1/2 means w = 1 - 2q, u = 4 q (1 - q), s = I_u(2/5, 1/2) / 2.
    fn time_at_cumulative(&self, q: f64) -> f64 {
        if q <= 0.0 {
            return 0.0;
        }
        if q >= 1.0 {
            return 1.0;
        }
        let half = |q: f64| {
            let u = 4.0 * q * (1.0 - q);
            let w = 1.0 - 2.0 * q;
            0.5 * inc_beta(A, B_, u, w * w, self.beta_ab)
        };
        if q <= 0.5 {
            half(q)
        } else {
            1.0 - half(1.0 - q)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contract() {
        crate::profile::tests::check_profile(&Hertz::new(1.0), 1e-9);
    }

    /// Independent check: integrate delta'' = -delta^(3/2) (c = 1, v0 = 1) with classical
    /// RK4 at a small step, and compare the force-time curve and the contact time
    /// (4/5) B(2/5, 1/2) delta_max / v0 with delta_max = (5/4)^(2/5) (ERRATA.md).
    #[test]
    fn matches_the_hertz_ode() {
        let delta_max = 1.25_f64.powf(0.4);
        let tau = 0.8 * beta(0.4, 0.5) * delta_max;
        assert!((0.8 * beta(0.4, 0.5) - 2.943_275_2).abs() < 1e-7);
        let p = Hertz::new(tau);
        // Impulse P = 2 m v0 with m = 1: f = delta^(3/2).
        let rhs = |y: [f64; 2]| [y[1], -y[0].max(0.0).powf(1.5)];
        let n = 200_000;
        let h = tau / n as f64;
        let mut y = [0.0, 1.0];
        let mut worst: f64 = 0.0;
        for i in 0..n {
            let k1 = rhs(y);
            let k2 = rhs([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
            let k3 = rhs([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
            let k4 = rhs([y[0] + h * k3[0], y[1] + h * k3[1]]);
            for j in 0..2 {
                y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
            }
            let t = (i + 1) as f64 * h;
            if (i + 1) % 1000 == 0 {
                let f_ode = y[0].max(0.0).powf(1.5);
                let f_profile = p.force(t, 2.0);
                worst = worst.max((f_ode - f_profile).abs());
                // p(t) = v0 - delta'(t)
                assert!(
                    (p.impulse_until(t, 2.0) - (1.0 - y[1])).abs() < 1e-9,
                    "t = {t}"
                );
            }
        }
        assert!(worst < 1e-9, "largest force difference {worst}");
        // After tau the balls separate with the reversed speed.
        assert!((y[1] + 1.0).abs() < 1e-9, "final delta' = {}", y[1]);
        assert!(y[0].abs() < 1e-9, "final delta = {}", y[0]);
    }
}
