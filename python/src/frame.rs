//! Lab frame <-> the paper's centre-of-mass frame, for one row of `resolve_lab`.
//!
//! The library builds this frame for lab scenes and lab batch rows (e_x along the line of
//! centres from A to B, e_z = `up` without its e_x part, e_y = e_z x e_x; the frame moves
//! with the centre of mass and does not rotate). The bindings reach the library through its
//! centre-of-mass entry points (`Incoming::Cm`), so the change of frame is written out
//! here, with the same formulas, tolerances and error messages as the library's lab rows;
//! the tests compare every output and message with the command line's lab-frame batch.

use billiard_contact::nalgebra::Vector3;
use billiard_contact::{CmState, Error, LabMotion};

/// Relative tolerance on |p_B - p_A| = r_A + r_B (the library's, for lab scenes and rows).
pub const TOUCH_TOLERANCE: f64 = 1e-9;

/// One row of lab-frame input.
#[derive(Debug, Clone, Copy)]
pub struct LabRow {
    pub pa: Vector3<f64>,
    pub va: Vector3<f64>,
    pub wa: Vector3<f64>,
    pub pb: Vector3<f64>,
    pub vb: Vector3<f64>,
    pub wb: Vector3<f64>,
    pub up: Vector3<f64>,
}

/// The centre-of-mass frame of one row.
#[derive(Debug, Clone)]
pub struct Frame {
    /// The basis e_x, e_y, e_z in lab coordinates (kept as three vectors: dot products
    /// and sums of scaled vectors, not 3x3 matrix products, cost fewer instructions here).
    ex: Vector3<f64>,
    ey: Vector3<f64>,
    ez: Vector3<f64>,
    /// Velocity of the centre of mass (m/s).
    v_cm: Vector3<f64>,
    /// 2 m_B / (m_A + m_B) and 2 m_A / (m_A + m_B): A moves with the first times u
    /// relative to the centre of mass, B with minus the second (both 1 for identical
    /// balls).
    shares: [f64; 2],
    /// Unit `up`.
    up: Vector3<f64>,
}

impl Frame {
    /// The frame of a row whose balls, of radii `radii` = [r_A, r_B] (m), touch
    /// (|p_B - p_A| = r_A + r_B within [`TOUCH_TOLERANCE`]); the centre of mass moves with
    /// the mass weights `weights` = [m_A, m_B] / (m_A + m_B).
    #[inline(always)]
    pub fn new(row: &LabRow, radii: [f64; 2], weights: [f64; 2]) -> Result<Self, Error> {
        let d = row.pb - row.pa;
        let dist = d.norm();
        // r + r = 2r exactly for identical balls.
        let contact = radii[0] + radii[1];
        let touching = (dist - contact).abs() <= TOUCH_TOLERANCE * contact;
        if !touching {
            return Err(not_touching(row, dist, radii));
        }
        let up_norm = row.up.norm();
        if !(up_norm > 0.0 && up_norm.is_finite()) {
            return Err(zero_up(row));
        }
        let up = row.up / up_norm;
        let ex = d / dist;
        let mut ez = up - ex * up.dot(&ex);
        let mut ez_norm = ez.norm();
        if ez_norm < 1e-12 {
            // `up` along the line of centres: any perpendicular gives the same result; the
            // lab axis least aligned with e_x, as the library takes.
            let i = ex.iamin();
            let mut axis = Vector3::zeros();
            axis[i] = 1.0;
            ez = axis - ex * axis.dot(&ex);
            ez_norm = ez.norm();
        }
        let ez = ez / ez_norm;
        let ey = ez.cross(&ex);
        Ok(Frame {
            ex,
            ey,
            ez,
            v_cm: weights[0] * row.va + weights[1] * row.vb,
            shares: [2.0 * weights[1], 2.0 * weights[0]],
            up,
        })
    }

    /// The centre-of-mass state of the row.
    #[inline(always)]
    pub fn to_cm(&self, row: &LabRow) -> CmState {
        let into =
            |v: Vector3<f64>| Vector3::new(self.ex.dot(&v), self.ey.dot(&v), self.ez.dot(&v));
        CmState::new(into(0.5 * (row.va - row.vb)), into(row.wa), into(row.wb))
    }

    /// Lab motions of A and B for a centre-of-mass state.
    #[inline(always)]
    pub fn to_lab(&self, cm: &CmState) -> (LabMotion, LabMotion) {
        let out = |v: &Vector3<f64>| self.ex * v.x + self.ey * v.y + self.ez * v.z;
        let u = out(&cm.u_cm);
        (
            LabMotion {
                velocity: self.v_cm + u * self.shares[0],
                spin: out(&cm.omega_a),
            },
            LabMotion {
                velocity: self.v_cm - u * self.shares[1],
                spin: out(&cm.omega_b),
            },
        )
    }

    /// Throw angle (degrees), counter-clockwise about `up`, from the horizontal line of
    /// centres to the horizontal part of B's velocity change; `None` when the line of
    /// centres is vertical or the horizontal change vanishes (below 1e-12 of the change).
    /// The library's tests on lengths, compared squared (no square roots).
    #[inline(always)]
    pub fn throw_angle_deg(&self, delta_v_b: &Vector3<f64>) -> Option<f64> {
        let line = self.ex - self.up * self.ex.dot(&self.up);
        let dv = delta_v_b - self.up * delta_v_b.dot(&self.up);
        let dv2 = dv.norm_squared();
        if line.norm_squared() < 1e-24 || dv2 <= 1e-24 * delta_v_b.norm_squared() || dv2 == 0.0 {
            return None;
        }
        let sin = line.cross(&dv).dot(&self.up);
        let cos = line.dot(&dv);
        Some(sin.atan2(cos).to_degrees())
    }
}

#[cold]
#[inline(never)]
fn zero_up(row: &LabRow) -> Error {
    Error::invalid(
        "up",
        format!("[{}, {}, {}]", row.up.x, row.up.y, row.up.z),
        "a non-zero direction",
    )
}

#[cold]
#[inline(never)]
fn not_touching(row: &LabRow, dist: f64, radii: [f64; 2]) -> Error {
    let term = if radii[0] == radii[1] {
        "2r"
    } else {
        "r_A + r_B"
    };
    Error::invalid(
        "pb",
        format!(
            "[{}, {}, {}] (|pb - pa| = {dist} m)",
            row.pb.x, row.pb.y, row.pb.z
        ),
        format!(
            "the balls must touch: |pb - pa| = {term} = {} m within a relative \
             {TOUCH_TOLERANCE:e}",
            radii[0] + radii[1]
        ),
    )
}
