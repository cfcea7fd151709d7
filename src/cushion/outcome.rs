//! What an impact on the cushion reports: the outgoing state, the impulses and works, the
//! slip events, and the trace rows.

use crate::base::settings::Stats;
use nalgebra::Vector3;
use serde::Serialize;

/// The two contacts of a ball at the cushion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CushionContact {
    /// The contact with the cushion, at height h.
    Cushion,
    /// The contact with the cloth, under the ball.
    Table,
}

/// A change of a contact's slip state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SlipChange {
    /// The slip reached zero and static friction holds it there.
    Sticks,
    /// The slip reached zero, static friction cannot hold it, and it goes on in a new
    /// direction.
    Reverses,
    /// A stuck contact needed more friction than mu N and slides again.
    Restarts,
    /// The table's normal force would have to pull: the ball leaves the cloth.
    LiftsOff,
    /// The ball's vertical velocity came back to zero: it is on the cloth again.
    TouchesDown,
}

/// One event of an impact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SlipEvent {
    /// The contact whose state changed.
    pub contact: CushionContact,
    /// What changed.
    pub kind: SlipChange,
    /// The cushion's normal impulse P_I at the event (N s).
    pub impulse: f64,
}

/// The phase of the impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CushionPhase {
    /// The normal velocity at the cushion is positive: the cushion is compressed.
    Compression,
    /// After the compression, until the restitution rule ends the impact.
    Restitution,
}

/// A row of an impact's trace: at the start, after each accepted step, at each event and at
/// the end.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CushionTraceRow {
    /// The cushion's normal impulse so far (N s), the independent variable.
    pub p_i: f64,
    /// The table's normal impulse so far (N s).
    pub p_c: f64,
    /// The ball's velocity (m/s), cushion frame (x along the cushion, y towards it, z up).
    pub v: Vector3<f64>,
    /// The ball's spin (rad/s), same axes.
    pub w: Vector3<f64>,
    /// Slip of the ball at the cushion contact (m/s): along x, and along
    /// (0, -sin theta, cos theta), the cushion's tangent plane's direction perpendicular
    /// to x (upwards on the cushion's face).
    pub slip_cushion: [f64; 2],
    /// Slip of the ball at the cloth (m/s): along x and y.
    pub slip_table: [f64; 2],
    /// Normal velocity at the cushion, v . (0, cos theta, sin theta) (m/s; > 0 approaching).
    pub normal_velocity: f64,
    /// W, the integral of the normal velocity over the cushion's normal impulse (J): the
    /// work the ball does on the cushion's normal force so far.
    pub work: f64,
    /// The phase.
    pub phase: CushionPhase,
}

/// The result of an impact on the cushion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CushionOutcome {
    /// Outgoing velocity (m/s), cushion frame.
    pub v: Vector3<f64>,
    /// Outgoing spin (rad/s).
    pub w: Vector3<f64>,
    /// Total normal impulse of the cushion, P_I (N s).
    pub impulse_cushion: f64,
    /// P_I at the end of compression (N s).
    pub impulse_compression: f64,
    /// Total normal impulse of the cloth, P_C (N s).
    pub impulse_table: f64,
    /// Work of the ball on the cushion's normal force during compression, >= 0 (J).
    pub work_compression: f64,
    /// Work the cushion's normal force gives back during restitution, >= 0 (J).
    pub work_restitution: f64,
    /// Kinetic energy in minus out, translation and spin (J).
    pub energy_lost: f64,
    /// The slip events, in order.
    pub events: Vec<SlipEvent>,
    /// Whether the ball left the cloth at some time during the impact.
    pub lifts_off: bool,
    /// Work of the integration.
    pub stats: Stats,
}
