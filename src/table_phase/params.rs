//! The cloth's parameters (`[table]` in scene files), validated on construction.
//!
//! [`TableSettings`] holds the six values by name (all public, with their defaults);
//! [`TableParams::new`] checks them and returns the validated, read-only parameters. The
//! `with_*` setters change one value of valid parameters and check it again.

use crate::base::error::Error;
use crate::base::validate::finite;
use serde::Serialize;

/// The `[table]` values by name, not yet validated: pass them to [`TableParams::new`].
///
/// Every field's default is the one a scene gets when it leaves the key out
/// (docs/formats.md#cloth-parameters).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TableSettings {
    /// Ball-cloth sliding friction mu_t (dimensionless), > 0. Default 0.2.
    pub mu: f64,
    /// Ball-cloth restitution e_t (dimensionless), in [0, 1). Default 0: the paper's
    /// idealisation of a soft cloth (no bounce).
    pub restitution: f64,
    /// Gravitational acceleration g (m/s^2), > 0. Default 9.81 m/s^2.
    pub g: f64,
    /// Rolling resistance mu_r (dimensionless), >= 0: a rolling ball decelerates at
    /// mu_r g (m/s^2). Default 0 (off).
    pub rolling_resistance: f64,
    /// Spin decay about the vertical mu_sp (dimensionless), >= 0: on the cloth |w.n| falls
    /// at mu_sp g / (alpha r) (rad/s^2). Default 0 (off).
    pub spin_decay: f64,
    /// Height of the cloth along `up` (m), finite: points p of the cloth have
    /// p.up = height. Default `None`: the plane r below the balls' centres at contact.
    pub height: Option<f64>,
}

impl Default for TableSettings {
    /// mu = 0.2, restitution = 0, g = 9.81 m/s^2, rolling resistance 0 (off), spin decay 0
    /// (off), height `None` (the plane under the balls).
    fn default() -> Self {
        TableSettings {
            mu: 0.2,
            restitution: 0.0,
            g: 9.81,
            rolling_resistance: 0.0,
            spin_decay: 0.0,
            height: None,
        }
    }
}

/// Validated parameters of the cloth: build them with [`TableParams::new`] from
/// [`TableSettings`], or change one value of valid parameters with a `with_*` setter.
///
/// ```
/// use billiard_contact::table_phase::{TableParams, TableSettings};
/// let p = TableParams::new(TableSettings { restitution: 0.5, ..TableSettings::default() })?;
/// assert_eq!(p.restitution(), 0.5);
/// let q = TableParams::default().with_mu(0.25)?.with_rolling_resistance(0.01)?;
/// assert_eq!((q.mu(), q.rolling_resistance(), q.g()), (0.25, 0.01, 9.81));
/// // A negative rolling resistance is refused, naming the scene key.
/// let e = TableParams::default().with_rolling_resistance(-0.01).unwrap_err();
/// assert!(e.to_string().starts_with("table.rolling_resistance = -0.01"));
/// # Ok::<(), billiard_contact::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(transparent)]
pub struct TableParams {
    settings: TableSettings,
}

impl Default for TableParams {
    /// The defaults of [`TableSettings`], which are valid.
    fn default() -> Self {
        TableParams {
            settings: TableSettings::default(),
        }
    }
}

impl TableParams {
    /// Validated parameters: an error names the first field out of range
    /// (`table.mu`, `table.restitution`, `table.g`, `table.rolling_resistance`,
    /// `table.spin_decay`, `table.height`), its value and the accepted range (see the
    /// fields of [`TableSettings`]).
    ///
    /// ```
    /// use billiard_contact::table_phase::{TableParams, TableSettings};
    /// let p = TableParams::new(TableSettings::default()).unwrap();
    /// assert_eq!(p, TableParams::default());
    /// // Restitution 1 would bounce forever.
    /// assert!(TableParams::new(TableSettings { restitution: 1.0, ..TableSettings::default() }).is_err());
    /// ```
    pub fn new(settings: TableSettings) -> Result<Self, Error> {
        let TableSettings {
            mu,
            restitution,
            g,
            rolling_resistance,
            spin_decay,
            height,
        } = settings;
        finite("table.mu", mu)?;
        if mu <= 0.0 {
            return Err(Error::invalid(
                "table.mu",
                mu,
                "> 0 (on a frictionless cloth a sliding ball never starts to roll)",
            ));
        }
        finite("table.restitution", restitution)?;
        if !(0.0..1.0).contains(&restitution) {
            return Err(Error::invalid(
                "table.restitution",
                restitution,
                "in [0, 1) (1 would bounce forever)",
            ));
        }
        finite("table.g", g)?;
        if g <= 0.0 {
            return Err(Error::invalid("table.g", g, "> 0 m/s^2"));
        }
        for (name, v) in [
            ("table.rolling_resistance", rolling_resistance),
            ("table.spin_decay", spin_decay),
        ] {
            finite(name, v)?;
            if v < 0.0 {
                return Err(Error::invalid(name, v, ">= 0 (0: off)"));
            }
        }
        if let Some(h) = height {
            finite("table.height", h)?;
        }
        Ok(TableParams { settings })
    }

    /// The values, by name.
    pub fn settings(&self) -> TableSettings {
        self.settings
    }

    /// Ball-cloth sliding friction mu_t (dimensionless), > 0.
    pub fn mu(&self) -> f64 {
        self.settings.mu
    }

    /// Ball-cloth restitution e_t (dimensionless), in [0, 1).
    pub fn restitution(&self) -> f64 {
        self.settings.restitution
    }

    /// Gravitational acceleration g (m/s^2), > 0.
    pub fn g(&self) -> f64 {
        self.settings.g
    }

    /// Rolling resistance mu_r (dimensionless), >= 0; 0 is off.
    pub fn rolling_resistance(&self) -> f64 {
        self.settings.rolling_resistance
    }

    /// Spin decay about the vertical mu_sp (dimensionless), >= 0; 0 is off.
    pub fn spin_decay(&self) -> f64 {
        self.settings.spin_decay
    }

    /// Height of the cloth along `up` (m); `None`: r below the balls' centres at contact.
    pub fn height(&self) -> Option<f64> {
        self.settings.height
    }

    /// These parameters with mu_t = `mu` (dimensionless), checked as by [`TableParams::new`].
    pub fn with_mu(self, mu: f64) -> Result<Self, Error> {
        Self::new(TableSettings {
            mu,
            ..self.settings
        })
    }

    /// These parameters with e_t = `restitution` (dimensionless), checked.
    pub fn with_restitution(self, restitution: f64) -> Result<Self, Error> {
        Self::new(TableSettings {
            restitution,
            ..self.settings
        })
    }

    /// These parameters with gravity `g` (m/s^2), checked.
    pub fn with_g(self, g: f64) -> Result<Self, Error> {
        Self::new(TableSettings { g, ..self.settings })
    }

    /// These parameters with mu_r = `rolling_resistance` (dimensionless), checked.
    pub fn with_rolling_resistance(self, rolling_resistance: f64) -> Result<Self, Error> {
        Self::new(TableSettings {
            rolling_resistance,
            ..self.settings
        })
    }

    /// These parameters with mu_sp = `spin_decay` (dimensionless), checked.
    pub fn with_spin_decay(self, spin_decay: f64) -> Result<Self, Error> {
        Self::new(TableSettings {
            spin_decay,
            ..self.settings
        })
    }

    /// These parameters with the cloth's height `height` (m along `up`; `None`: under the
    /// balls), checked.
    pub fn with_height(self, height: Option<f64>) -> Result<Self, Error> {
        Self::new(TableSettings {
            height,
            ..self.settings
        })
    }
}

/// The playing area between the cushions (`[table] length, width`): drawn on the top view,
/// not modelled (a ball's path runs on through a cushion). The rectangle is centred on the
/// lab origin projected on the cloth, its length along the figure's first horizontal axis
/// (lab x when up is +z) and its width along the second.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableSize {
    length: f64,
    width: f64,
}

impl TableSize {
    /// The area `length` x `width` (m), both finite and > 0; an error names
    /// `table.length` or `table.width`, the value and the accepted range.
    ///
    /// ```
    /// use billiard_contact::table_phase::TableSize;
    /// let pool = TableSize::new(2.54, 1.27).unwrap(); // a 9-foot pool table
    /// assert_eq!((pool.length(), pool.width()), (2.54, 1.27));
    /// assert!(TableSize::new(2.54, 0.0).is_err());
    /// ```
    pub fn new(length: f64, width: f64) -> Result<Self, Error> {
        for (name, v) in [("table.length", length), ("table.width", width)] {
            finite(name, v)?;
            if v <= 0.0 {
                return Err(Error::invalid(
                    name,
                    v,
                    "> 0 m (the playing area between the cushions)",
                ));
            }
        }
        Ok(TableSize { length, width })
    }

    /// Length (m), along the figure's first horizontal axis.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Width (m), along the figure's second horizontal axis.
    pub fn width(&self) -> f64 {
        self.width
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The field named in an invalid-parameter error.
    fn field(e: Error) -> String {
        match e {
            Error::InvalidParameter { field, .. } => field,
            other => panic!("expected an invalid parameter, got {other}"),
        }
    }

    #[test]
    fn defaults_are_the_documented_values() {
        let p = TableParams::default();
        assert_eq!(p.mu(), 0.2);
        assert_eq!(p.restitution(), 0.0);
        assert_eq!(p.g(), 9.81);
        assert_eq!(p.rolling_resistance(), 0.0);
        assert_eq!(p.spin_decay(), 0.0);
        assert_eq!(p.height(), None);
        assert_eq!(TableParams::new(TableSettings::default()).unwrap(), p);
    }

    #[test]
    fn each_setter_rejects_its_bad_value_naming_the_key() {
        let p = TableParams::default();
        let cases: [(Result<TableParams, Error>, &str); 9] = [
            (p.with_mu(0.0), "table.mu"),
            (p.with_mu(f64::NAN), "table.mu"),
            (p.with_restitution(1.0), "table.restitution"),
            (p.with_restitution(-0.1), "table.restitution"),
            (p.with_g(-9.81), "table.g"),
            (p.with_rolling_resistance(-0.01), "table.rolling_resistance"),
            (p.with_spin_decay(-1e-3), "table.spin_decay"),
            (p.with_spin_decay(f64::INFINITY), "table.spin_decay"),
            (p.with_height(Some(f64::NAN)), "table.height"),
        ];
        for (result, key) in cases {
            assert_eq!(field(result.unwrap_err()), key);
        }
    }

    #[test]
    fn rejection_message_gives_value_and_range() {
        let e = TableParams::default()
            .with_rolling_resistance(-0.01)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "table.rolling_resistance = -0.01: >= 0 (0: off)"
        );
    }

    #[test]
    fn setters_change_only_their_value() {
        let p = TableParams::default()
            .with_mu(0.3)
            .and_then(|p| p.with_restitution(0.5))
            .and_then(|p| p.with_g(9.8))
            .and_then(|p| p.with_rolling_resistance(0.01))
            .and_then(|p| p.with_spin_decay(0.04))
            .and_then(|p| p.with_height(Some(0.75)))
            .unwrap();
        assert_eq!(
            p.settings(),
            TableSettings {
                mu: 0.3,
                restitution: 0.5,
                g: 9.8,
                rolling_resistance: 0.01,
                spin_decay: 0.04,
                height: Some(0.75),
            }
        );
    }

    #[test]
    fn restitution_boundaries() {
        let p = TableParams::default();
        assert!(p.with_restitution(0.0).is_ok());
        assert!(p.with_restitution(0.999).is_ok());
        assert!(p.with_restitution(1.0).is_err());
        assert!(p.with_rolling_resistance(0.0).is_ok());
        assert!(p.with_height(Some(-0.5)).is_ok(), "any finite height");
    }
}
