//! What the subcommands share: reading the scene, the solver options a run ignores,
//! progress bars, warnings, and clap's errors in one line.

use crate::base::error::Error;
use crate::base::number::readable_numbers;
use crate::base::settings::SolverSettings;
use crate::scene::overrides::SolverOverrides;
use crate::scene::types::Scene;
use std::path::Path;

/// The scene file, or the built-in default scene when none is given; a warning on stderr
/// for each value far outside the range of any ball game (a likely unit slip).
pub(super) fn load_scene(path: Option<&Path>) -> Result<Scene, Error> {
    let scene = match path {
        Some(p) => Scene::load(p)?,
        None => Scene::default_scene(),
    };
    for w in scene.warnings() {
        warn(w);
    }
    Ok(scene)
}

/// The warnings for the solver options of `overrides` that a run with `settings` does not
/// use ([`SolverOverrides::unused`]: tolerances with rk4 and a profile's closed form, the
/// time transform with the closed form or under a contact law, `law`), named as options.
pub(super) fn solver_options_unused(
    overrides: &SolverOverrides,
    settings: &SolverSettings,
    law: bool,
) -> Vec<String> {
    overrides
        .unused(settings, law)
        .into_iter()
        .map(|(field, why)| format!("--{} has no effect with {why}", field.replace('_', "-")))
        .collect()
}

/// A bad command line in one line, for stderr (bad options are bad input: exit code 2):
/// for a value outside a closed choice, the option, the value and the accepted values; for
/// a value that does not parse, the option, the value and what is accepted; otherwise
/// clap's whole message (the missing argument's name, its tip, the usage) joined into one
/// line.
pub(super) fn one_line(e: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    let text = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.as_str()),
        _ => None,
    };
    if let (Some(arg), Some(value)) = (
        text(ContextKind::InvalidArg),
        text(ContextKind::InvalidValue),
    ) {
        // "--method <M>": the option without its value name.
        let option = arg.split_whitespace().next().unwrap_or(arg);
        let accepted = match e.get(ContextKind::ValidValue) {
            Some(ContextValue::Strings(names)) if !names.is_empty() => {
                Some(format!("one of {}", names.join(", ")))
            }
            _ if e.kind() == ErrorKind::ValueValidation => {
                std::error::Error::source(e).map(|cause| cause.to_string())
            }
            _ => None,
        };
        if let Some(accepted) = accepted {
            let hint = text(ContextKind::SuggestedValue)
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            return if value.is_empty() {
                format!("error: {option} needs a value: {accepted} (see --help)")
            } else {
                format!("error: {option} = \"{value}\": {accepted}{hint} (see --help)")
            };
        }
    }
    let text = e.to_string();
    let mut line = String::new();
    // Inside a list (indented lines after a line ending in ':'): items joined by ", ".
    let mut in_list = false;
    for raw in text.lines().filter(|l| !l.trim().is_empty()) {
        let part = raw.trim();
        if part.starts_with("For more information") {
            continue;
        }
        let item = raw.starts_with(' ') && (in_list || line.ends_with(':'));
        let part = match part.strip_prefix("tip: a similar argument exists: ") {
            Some(name) => format!("did you mean {name}?"),
            None => part.replacen("Usage:", "usage:", 1),
        };
        if !line.is_empty() {
            line.push_str(match (item, in_list) {
                (true, true) => ", ",
                _ if line.ends_with(':') => " ",
                _ => "; ",
            });
        }
        in_list = item;
        line.push_str(&part);
    }
    if line.is_empty() {
        line.push_str("error: invalid arguments");
    }
    format!("{line} (see --help)")
}

/// A warning on stderr: one line starting `warning: `; the run goes on.
pub(super) fn warn(message: impl std::fmt::Display) {
    eprintln!("warning: {}", readable_numbers(&message.to_string()));
}

/// A progress bar on stderr with `template` (indicatif's syntax).
pub(super) fn progress_bar(len: u64, template: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(len),
        indicatif::ProgressDrawTarget::stderr(),
    );
    let style = indicatif::ProgressStyle::with_template(template)
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::choice::MethodChoice;
    use clap::builder::EnumValueParser;

    fn error_of(args: &[&str]) -> clap::Error {
        clap::Command::new("t")
            .arg(
                clap::Arg::new("method")
                    .long("method")
                    .value_name("M")
                    .value_parser(EnumValueParser::<MethodChoice>::new()),
            )
            .arg(
                clap::Arg::new("rtol")
                    .long("rtol")
                    .value_parser(clap::value_parser!(f64)),
            )
            .try_get_matches_from(args)
            .unwrap_err()
    }

    #[test]
    fn a_bad_choice_names_the_option_the_value_and_the_choices() {
        assert_eq!(
            one_line(&error_of(&["t", "--method", "euler"])),
            "error: --method = \"euler\": one of closed-form, rk4, dopri5, dop853 (see --help)"
        );
        let near = one_line(&error_of(&["t", "--method", "dop85"]));
        assert!(
            near.ends_with("(did you mean `dop853`?) (see --help)"),
            "{near}"
        );
        assert_eq!(
            one_line(&error_of(&["t", "--method"])),
            "error: --method needs a value: one of closed-form, rk4, dopri5, dop853 (see --help)"
        );
        // A value that does not parse: the option, the value and the parser's words.
        let other = one_line(&error_of(&["t", "--rtol", "abc"]));
        assert_eq!(
            other,
            "error: --rtol = \"abc\": invalid float literal (see --help)"
        );
        // Other errors: clap's whole message in one line, the usage included.
        let other = one_line(&error_of(&["t", "extra"]));
        assert!(
            other.starts_with("error: unexpected argument 'extra' found; usage: t "),
            "{other}"
        );
        assert!(!other.contains('\n'), "{other}");
    }
}
