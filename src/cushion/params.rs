//! The cushion: its contact height, the two friction coefficients and the restitution rule,
//! validated on construction.

use crate::base::error::Error;
use crate::base::validate::finite;
use crate::model::params::MU_MAX;
use serde::Serialize;

/// How the impact's restitution phase ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CushionRestitution {
    /// Stronge's energetic rule (the default): the work of the cushion's normal force
    /// during restitution is e^2 times its work during compression.
    #[default]
    Stronge,
    /// Newton's kinematic rule: the impact ends where the normal velocity at the contact
    /// is -e times its value at the start.
    Newton,
}

impl CushionRestitution {
    /// The name used in scene files and on the command line (`stronge`, `newton`).
    pub fn name(&self) -> &'static str {
        match self {
            CushionRestitution::Stronge => "stronge",
            CushionRestitution::Newton => "newton",
        }
    }
}

/// A cushion: the height of its contact above the table, the friction of the ball on the
/// cushion and on the cloth, and the restitution. Validated on construction
/// ([`Cushion::new`]); the height is checked against the ball's radius when an impact is
/// resolved.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Cushion {
    height: f64,
    mu_cushion: f64,
    mu_table: f64,
    restitution: f64,
    rule: CushionRestitution,
}

impl Cushion {
    /// A validated cushion.
    ///
    /// `height` (m, of the contact above the cloth) must be finite and positive (an impact
    /// also needs r < height < 2r, [`crate::resolve_cushion`]); `mu_cushion` and `mu_table`
    /// in [0, 1e6]; `restitution` in [0, 1]. Errors are [`Error::InvalidParameter`] naming
    /// `cushion.height`, `cushion.mu_cushion`, `cushion.mu_table` or `cushion.restitution`.
    ///
    /// ```
    /// use billiard_contact::{Cushion, CushionRestitution};
    /// let c = Cushion::new(0.04, 0.2, 0.2, 0.85, CushionRestitution::Stronge)?;
    /// assert_eq!((c.height(), c.restitution()), (0.04, 0.85));
    /// assert!(Cushion::new(0.04, 0.2, 0.2, 1.5, CushionRestitution::Newton).is_err());
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(
        height: f64,
        mu_cushion: f64,
        mu_table: f64,
        restitution: f64,
        rule: CushionRestitution,
    ) -> Result<Cushion, Error> {
        finite("cushion.height", height)?;
        if height <= 0.0 {
            return Err(Error::invalid(
                "cushion.height",
                height,
                "> 0 m (and between r and 2r of the ball, in metres)",
            ));
        }
        for (field, mu) in [
            ("cushion.mu_cushion", mu_cushion),
            ("cushion.mu_table", mu_table),
        ] {
            finite(field, mu)?;
            if !(0.0..=MU_MAX).contains(&mu) {
                return Err(Error::invalid(field, mu, format!("in [0, {MU_MAX:e}]")));
            }
        }
        finite("cushion.restitution", restitution)?;
        if !(0.0..=1.0).contains(&restitution) {
            return Err(Error::invalid(
                "cushion.restitution",
                restitution,
                "in [0, 1]",
            ));
        }
        Ok(Cushion {
            height,
            mu_cushion,
            mu_table,
            restitution,
            rule,
        })
    }

    /// Height of the contact above the cloth (m).
    pub fn height(&self) -> f64 {
        self.height
    }

    /// Coefficient of friction of the ball on the cushion.
    pub fn mu_cushion(&self) -> f64 {
        self.mu_cushion
    }

    /// Coefficient of friction of the ball on the cloth.
    pub fn mu_table(&self) -> f64 {
        self.mu_table
    }

    /// Coefficient of restitution, in [0, 1].
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The restitution rule.
    pub fn rule(&self) -> CushionRestitution {
        self.rule
    }
}
