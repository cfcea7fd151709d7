//! The table phase (effect `table`): what each ball does on the cloth after the balls
//! separate, the paper's last section ("Complications associated with the table") worked
//! out (docs/model.md#the-table-phase).
//!
//! Lab frame, n = unit `up`, ball of mass m, radius r, inertia alpha m r^2, centre x,
//! velocity v, spin w. The contact point with the cloth slips at
//! u = v_h - r (w x n), v_h = v - (v.n) n ([`cloth_slip`]).
//!
//! The ball-ball contact takes O(tau); the cloth's impulse during it is O(tau) too and is
//! neglected (docs/model.md#notes-on-the-paper-text), so the phase starts from the
//! outgoing lab motions. [`roll_out`] follows each ball from t = 0 at the separation point
//! through the stages, one file each:
//!
//! | stage | what | file |
//! |---|---|---|
//! | parameters | `[table]`: mu_t, e_t, g, mu_r, mu_sp, height ([`TableParams`]) | `params.rs` |
//! | the cloth | the plane under the balls, the slip u ([`Table`]) | `cloth.rs` |
//! | 1. flight | hop under gravity, then bounces until settled | `flight.rs` |
//! | 2. impact | ball-cloth impact with the stick rule ([`cloth_impact`]) | `impact.rs` |
//! | 3. sliding | slip falls at mu_t g (1 + 1/alpha) until rolling | `rolling.rs` |
//! | 4. rolling | at [`rolling_velocity`]; with mu_r, to rest | `rolling.rs` |
//! | the motion | constant-acceleration pieces ([`Segment`], [`BallMotion`]) | `segment.rs` |
//! | the driver | the stages in order ([`roll_out`], [`RollOut`]) | `roll_out.rs` |
//! | both balls | directions, deflections, checks ([`TableOutcome`]) | `outcome.rs` |
//!
//! Energy E = m |v|^2 / 2 + alpha m r^2 |w|^2 / 2 + m g (x.n - h_table - r) never increases;
//! the balls' later paths are independent (a second collision between them is not
//! modelled).

pub(crate) mod cloth;
pub(crate) mod flight;
pub(crate) mod impact;
pub(crate) mod outcome;
pub(crate) mod params;
pub(crate) mod path;
pub(crate) mod roll_out;
pub(crate) mod rolling;
pub(crate) mod segment;
mod track;

pub use cloth::{cloth_slip, Table, LEVEL_TOLERANCE};
pub use flight::{MAX_BOUNCES, SETTLE_SPEED};
pub use impact::{cloth_impact, ClothImpact};
pub use outcome::{TableChecks, TableOutcome};
pub use params::{TableParams, TableSettings, TableSize};
pub use path::{ball_path_rows, BallPathRow};
pub use roll_out::{roll_out, RollOut};
pub use rolling::rolling_velocity;
pub use segment::{BallMotion, Segment};
