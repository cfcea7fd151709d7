//! Which physical effects a scene simulates (`[effects]` in scene files).

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
