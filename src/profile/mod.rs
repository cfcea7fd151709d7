//! Prescribed normal-force profiles f(t) over the contact (0, tau).
//!
//! Every profile is stored normalised: with s = t / tau,
//!
//! ```text
//! f(t) = (P / tau) phi(s),      p(t) = integral_0^t f = P Phi(s),      Phi(1) = 1,
//! ```
//!
//! so a profile delivers exactly the impulse P whatever its shape, and the integrator
//! works in the scaled time s. `Phi` is exact (analytic, or tabulated to round-off): it is
//! what the exact time-resolved solution needs (while sliding, the state at time t is the
//! closed form at impulse p(t): docs/model.md#the-exact-state-during-the-contact).
//!
//! | shape | phi(s) | Phi(s) |
//! |---|---|---|
//! | `half-sine` | (pi/2) sin(pi s) | sin^2(pi s / 2) |
//! | `sine-power` (exponent n) | sin^n(pi s) pi / B((n+1)/2, 1/2) | I_{sin^2(pi s)}((n+1)/2, 1/2) / 2 for s <= 1/2 |
//! | `hertz` | elastic Hertz impact, f ~ delta^(3/2) | (1 - delta'(t)/delta'(0)) / 2 |
//! | `rectangle` | 1 | s |
//! | `tabulated` | linear between (time, force) points | exact trapezoids |

pub(crate) mod force;
pub(crate) mod half_sine;
pub(crate) mod hertz;
pub(crate) mod rectangle;
pub(crate) mod sine_power;
pub(crate) mod spec;
pub(crate) mod tabulated;

pub use force::{invert_cumulative, ForceProfile};
pub use half_sine::HalfSine;
pub use hertz::Hertz;
pub use rectangle::Rectangle;
pub use sine_power::SinePower;
pub use spec::{Profile, ProfileKind, ProfileSpec, DEFAULT_SINE_POWER_EXPONENT};
pub use tabulated::{parse_table, Tabulated};
