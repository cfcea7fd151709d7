//! Which physical effects a scene simulates (`[effects]` in scene files).
//!
//! Each effect is a unit of its own: its equations live in one place, its parameters in
//! one scene section, its outputs under its own JSON keys, its trace columns in its own
//! file, and turning it off removes its work. [`CATALOGUE`] lists them.
//!
//! | effect | equations (code) | parameters | outputs | trace |
//! |---|---|---|---|---|
//! | `normal-impulse` (always) | eq 14, [`crate::integrator::rhs::NormalRhs`] | `[contact]` restitution / impulse, profile | `impulse`, `cm_out.u` | `U`, `f`, `p` |
//! | `friction` | eqs 15-23, 47-49, [`crate::integrator::rhs::SlidingRhs`], [`crate::closed_form::sliding`] | `contact.mu` | `s0`, `theta`, `s_out`, `tangential_impulse`, `heat_sliding`, `check.theta_drift` | `V`, `W`, spins, `S`, `theta`, `H_sfr` |
//! | `stick` | the stop of sliding, [`crate::integrator`] event, [`crate::closed_form::sliding::SlidingLaw`] | none | `sticks`, `stick_time`, `stick_impulse`; off: eq 57 `warnings` | the stop row |
//! | `table` | [`crate::table_phase`] | `[table]` | `table` | `--path` CSV, `--plot` |

use serde::{Deserialize, Serialize};

/// The effects a run simulates. Each one adds its equations, parameters and outputs; an
/// effect that is off costs nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Effects {
    /// Coulomb sliding friction between the balls (eqs 15-19). Off: eq 14 alone, the
    /// impulse is purely normal.
    pub friction: bool,
    /// Static friction once sliding stops (S reaches 0): the rest of the impulse is
    /// purely normal. Off: the paper's formulas literally (friction keeps acting along
    /// the initial sliding direction), and every run where eq 57 fails is flagged.
    pub stick: bool,
    /// After separation, the cloth: flight, impact with the table and the slide until
    /// rolling.
    pub table: bool,
}

impl Default for Effects {
    /// friction = true, stick = true, table = false.
    fn default() -> Self {
        Effects {
            friction: true,
            stick: true,
            table: false,
        }
    }
}

impl Effects {
    /// Names of the effects that are on, in a fixed order (the contact itself is always
    /// simulated and listed as `normal-impulse`).
    pub fn names(&self) -> Vec<&'static str> {
        let mut v = vec!["normal-impulse"];
        if self.friction {
            v.push("friction");
            if self.stick {
                v.push("stick");
            }
        }
        if self.table {
            v.push("table");
        }
        v
    }
}

impl Effects {
    /// The effects a run with ball-ball friction `friction` actually simulates: as
    /// [`Effects::names`], without `friction` and `stick` when mu is zero at every speed
    /// (then only eq 14 is integrated).
    pub fn simulated(&self, friction: &crate::model::params::Friction) -> Vec<&'static str> {
        let mut names = self.names();
        if friction.is_zero() {
            names.retain(|n| *n != "friction" && *n != "stick");
        }
        names
    }
}

/// What one effect adds to a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EffectInfo {
    /// Name in `effects` (JSON) and the summary.
    pub name: &'static str,
    /// The physics it adds.
    pub adds: &'static str,
    /// Its parameters (scene keys).
    pub parameters: &'static str,
    /// Its outputs (JSON keys).
    pub outputs: &'static str,
}

/// Every effect, in the order of [`Effects::names`].
pub const CATALOGUE: [EffectInfo; 4] = [
    EffectInfo {
        name: "normal-impulse",
        adds: "eq 14: the normal force changes U only (always on)",
        parameters: "contact.restitution or contact.impulse, contact.profile",
        outputs: "impulse, cm_out.u, lab_out",
    },
    EffectInfo {
        name: "friction",
        adds:
            "eqs 15-23: Coulomb sliding friction between the balls (theta constant, S falls with p)",
        parameters: "contact.mu (constant or speed-dependent)",
        outputs:
            "s0, theta, s_out, tangential_impulse, heat_sliding, throw_angle_deg, check.theta_drift",
    },
    EffectInfo {
        name: "stick",
        adds: "static friction once S reaches 0: the rest of the impulse is purely normal",
        parameters: "none (off: the paper's formulas literally, eq 57 flagged in warnings)",
        outputs: "sticks, stick_time, stick_impulse",
    },
    EffectInfo {
        name: "table",
        adds: "after separation: hop, impact with the cloth, sliding until rolling",
        parameters: "[table] mu, restitution, g, rolling_resistance, spin_decay, height",
        outputs: "table {a, b}, --path CSV, --plot SVG",
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::Friction;

    #[test]
    fn every_name_is_catalogued_and_zero_friction_is_not_simulated() {
        let all = Effects {
            friction: true,
            stick: true,
            table: true,
        };
        let names = all.names();
        assert_eq!(names, vec!["normal-impulse", "friction", "stick", "table"]);
        let catalogued: Vec<&str> = CATALOGUE.iter().map(|e| e.name).collect();
        assert_eq!(names, catalogued);
        assert_eq!(
            all.simulated(&Friction::constant(0.0).unwrap()),
            vec!["normal-impulse", "table"]
        );
        assert_eq!(all.simulated(&Friction::constant(0.06).unwrap()), names);
    }
}
