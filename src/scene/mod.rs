//! A scene: the balls, contact, profile or law, solver settings, effects and incoming state
//! of one collision; built in code ([`builder`]) or read from a scene file (TOML, [`file`],
//! which fills a builder), and run.

pub(crate) mod builder;
pub(crate) mod cluster;
pub(crate) mod compliant;
pub(crate) mod cushion;
pub(crate) mod file;
pub(crate) mod overrides;
pub(crate) mod run;
pub(crate) mod types;
pub(crate) mod warnings;
