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
//! (4/5) B(2/5, 1/2) delta_max / v0 = 2.9432752... delta_max / v0 (docs/model.md#force-profiles). The curve's
//! shape is universal: c and v0 only set the duration and the impulse, both given.

use crate::base::beta::{beta, inc_beta};
use crate::base::error::Error;
use crate::profile::force::valid_duration;
use crate::profile::force::ForceProfile;

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

/// The compression at a point of the rising half: u = (delta/delta_max)^(5/2) and
/// w = delta'/v0 = sqrt(1 - u), both to full relative accuracy.
#[derive(Debug, Clone, Copy)]
struct Compression {
    u: f64,
    w: f64,
}

impl Hertz {
    /// A Hertz pulse of `duration` tau (s), finite and > 0 (else
    /// [`Error::InvalidParameter`] naming `contact.profile.duration`).
    ///
    /// ```
    /// use billiard_contact::profile::{ForceProfile, Hertz};
    /// let p = Hertz::new(1.0)?;
    /// // peak of phi: B(2/5, 1/2) / 2, B(2/5, 1/2) = Gamma(2/5) Gamma(1/2) / Gamma(9/10)
    /// let b = 3.679093980405881;
    /// assert!((p.shape(0.5) - b / 2.0).abs() < 1e-12);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(duration: f64) -> Result<Self, Error> {
        Ok(Hertz {
            duration: valid_duration(duration)?,
            beta_ab: beta(A, B_),
        })
    }

    /// The compression at scaled time s in [0, 1/2], from the interpolants of [`Fits`] (a few
    /// dozen flops and two square roots, instead of a Newton iteration on the incomplete
    /// Beta function per call).
    #[inline]
    fn compression(&self, s: f64) -> Compression {
        fits().compression(s)
    }
}

/// The compression at scaled time s in [0, 1/2] by Newton's method on I_u(2/5, 1/2) = 2 s:
/// exact to a few ulp, about 2 microseconds. The reference the interpolants are built from.
fn compression_newton(s: f64, bb: f64) -> Compression {
    {
        let t2 = (2.0 * s).clamp(0.0, 1.0);
        if t2 == 0.0 {
            return Compression { u: 0.0, w: 1.0 };
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
            Compression {
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
            Compression { u: 1.0 - w * w, w }
        }
    }
}

/// Terms of the Chebyshev interpolants. The functions are analytic on their intervals with
/// the nearest singularity far away: the coefficients fall below 1e-16 after 8 (early) and
/// 11 (late) terms; more would only add the reference's round-off (the test
/// `interpolants_match_newton` checks against [`compression_newton`]).
const TERMS: usize = 12;
/// Chebyshev nodes sampled to compute the coefficients (more than TERMS: no aliasing).
const SAMPLES: usize = 28;

/// Chebyshev interpolants of the rising half, built once per process.
///
/// Early (2s <= 1/2): with sigma = a B 2s, the solution z = u^a of I_u(a, 1/2) = 2s is
/// z = sigma G(sigma^(5/2)), G analytic (I_u = z/(aB) (1 + O(u)), u = z^(5/2)).
/// Late (2s >= 1/2): with t = 1 - 2s, w = sqrt(1 - u) solves I_{w^2}(1/2, a) = t and
/// w = (B/2) t H(t^2), H analytic (I_y(1/2, a) = 2 sqrt(y) / B (1 + O(y))).
struct Fits {
    early: [f64; TERMS],
    late: [f64; TERMS],
    /// Upper end of the early interval in v = sigma^(5/2).
    v_max: f64,
    /// B(2/5, 1/2).
    bb: f64,
}

static FITS: std::sync::OnceLock<Fits> = std::sync::OnceLock::new();

fn fits() -> &'static Fits {
    FITS.get_or_init(Fits::build)
}

/// The first TERMS Chebyshev coefficients of f on [lo, hi], from its values at SAMPLES
/// Chebyshev nodes.
fn chebyshev(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> [f64; TERMS] {
    use std::f64::consts::PI;
    let n = SAMPLES as f64;
    let values: Vec<f64> = (0..SAMPLES)
        .map(|k| {
            let x = (PI * (k as f64 + 0.5) / n).cos();
            f(lo + 0.5 * (hi - lo) * (x + 1.0))
        })
        .collect();
    let mut c = [0.0; TERMS];
    for (j, cj) in c.iter_mut().enumerate() {
        let sum: f64 = values
            .iter()
            .enumerate()
            .map(|(k, v)| v * (PI * j as f64 * (k as f64 + 0.5) / n).cos())
            .sum();
        *cj = 2.0 * sum / n;
    }
    c[0] *= 0.5;
    c
}

/// Clenshaw's recurrence for sum c_j T_j(x), x in [-1, 1].
#[inline]
fn clenshaw(c: &[f64; TERMS], x: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    let x2 = 2.0 * x;
    for &cj in c[1..].iter().rev() {
        let b0 = cj + x2 * b1 - b2;
        b2 = b1;
        b1 = b0;
    }
    c[0] + x * b1 - b2
}

impl Fits {
    fn build() -> Self {
        let bb = beta(A, B_);
        let sigma_max = A * bb * 0.5;
        let v_max = sigma_max.powf(2.5);
        let early = chebyshev(
            |v| {
                let sigma = v.powf(0.4);
                let ph = compression_newton(sigma / (A * bb) / 2.0, bb);
                ph.u.powf(A) / sigma
            },
            0.0,
            v_max,
        );
        let late = chebyshev(
            |x| {
                let t = x.sqrt();
                let ph = compression_newton((1.0 - t) / 2.0, bb);
                ph.w / (0.5 * bb * t)
            },
            0.0,
            0.25,
        );
        Fits {
            early,
            late,
            v_max,
            bb,
        }
    }

    #[inline]
    fn compression(&self, s: f64) -> Compression {
        let t2 = (2.0 * s).clamp(0.0, 1.0);
        if t2 == 0.0 {
            return Compression { u: 0.0, w: 1.0 };
        }
        if t2 <= 0.5 {
            let sigma = A * self.bb * t2;
            let v = sigma * sigma * sigma.sqrt();
            let z = sigma * clenshaw(&self.early, 2.0 * v / self.v_max - 1.0);
            let u = (z * z * z.sqrt()).min(1.0);
            Compression {
                u,
                w: (1.0 - u).sqrt(),
            }
        } else {
            let t = 1.0 - t2;
            let w = (0.5 * self.bb * t * clenshaw(&self.late, 8.0 * t * t - 1.0)).clamp(0.0, 1.0);
            Compression {
                u: (1.0 - w) * (1.0 + w),
                w,
            }
        }
    }

    /// u^(3/5) at scaled time s in [0, 1/2] (the force over its peak): z^(3/2) on the
    /// early interval, without a power function.
    #[inline]
    fn u_three_fifths(&self, s: f64) -> f64 {
        let t2 = (2.0 * s).clamp(0.0, 1.0);
        if t2 <= 0.5 {
            let sigma = A * self.bb * t2;
            let v = sigma * sigma * sigma.sqrt();
            let z = (sigma * clenshaw(&self.early, 2.0 * v / self.v_max - 1.0)).min(1.0);
            z * z.sqrt()
        } else {
            self.compression(s).u.powf(1.0 - A)
        }
    }
}

impl ForceProfile for Hertz {
    fn duration(&self) -> f64 {
        self.duration
    }

    /// The force grows like t^1.5 from both ends (f ~ delta^(3/2), delta ~ v0 t).
    fn end_power(&self) -> Option<f64> {
        Some(1.5)
    }

    fn shape(&self, s: f64) -> f64 {
        if !(0.0..=1.0).contains(&s) {
            return 0.0;
        }
        0.5 * self.beta_ab * fits().u_three_fifths(s.min(1.0 - s))
    }

    fn cumulative(&self, s: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        if s >= 1.0 {
            return 1.0;
        }
        let half = |s: f64| {
            let ph = self.compression(s);
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
        crate::profile::force::tests::check_profile(&Hertz::new(1.0).unwrap(), 1e-9);
    }

    /// The interpolants against the Newton solution they replace, densely over the rising
    /// half and near both ends of each interval: u and w to 4e-15 relative (and the force,
    /// u^(3/5), with them).
    #[test]
    fn interpolants_match_newton() {
        let bb = beta(A, B_);
        let mut worst: f64 = 0.0;
        let n = 20_000;
        let mut points: Vec<f64> = (1..=n).map(|i| 0.5 * i as f64 / n as f64).collect();
        points.extend([
            1e-12,
            1e-8,
            1e-5,
            0.25 - 1e-12,
            0.25,
            0.25 + 1e-12,
            0.5 - 1e-9,
        ]);
        for s in points {
            let fast = fits().compression(s);
            let exact = compression_newton(s, bb);
            let du = (fast.u - exact.u).abs() / exact.u;
            let dw = (fast.w - exact.w).abs() / exact.w.max(1e-300);
            let force = fits().u_three_fifths(s);
            let dphi = (force - exact.u.powf(0.6)).abs() / exact.u.powf(0.6);
            worst = worst
                .max(du)
                .max(dphi)
                .max(if exact.w > 1e-3 { dw } else { 0.0 });
            assert!(
                du < 1.5e-14 && dphi < 1e-14,
                "s = {s}: u {} vs {}",
                fast.u,
                exact.u
            );
            assert!(
                (fast.w - exact.w).abs() < 4e-15,
                "s = {s}: w {} vs {}",
                fast.w,
                exact.w
            );
        }
        eprintln!("largest relative difference {worst:e}");
        assert!(worst > 0.0, "the comparison compared something");
    }

    /// Independent check: integrate delta'' = -delta^(3/2) (c = 1, v0 = 1) with classical
    /// RK4 at a small step, and compare the force-time curve and the contact time
    /// (4/5) B(2/5, 1/2) delta_max / v0 with delta_max = (5/4)^(2/5): energy conservation
    /// with c = v0 = 1 gives (2/5) delta_max^(5/2) = 1/2.
    #[test]
    fn matches_the_hertz_ode() {
        let delta_max = 1.25_f64.powf(0.4);
        let tau = 0.8 * beta(0.4, 0.5) * delta_max;
        assert!((0.8 * beta(0.4, 0.5) - 2.943_275_2).abs() < 1e-7);
        let p = Hertz::new(tau).unwrap();
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
