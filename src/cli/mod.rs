//! The subcommands of the `billiard-contact` command, one module each, and what they share:
//! reading the scene, the closed choices of the options, progress bars, and clap's errors
//! in one line.

pub mod batch;
pub mod choice;
pub mod run;
pub mod work_precision;

use billiard_contact::{Error, Scene};
use std::path::Path;

/// The scene file, or the built-in default scene when none is given.
pub fn load_scene(path: Option<&Path>) -> Result<Scene, Error> {
    match path {
        Some(p) => Scene::load(p),
        None => Ok(Scene::default_scene()),
    }
}

/// A bad command line in one line, for stderr (bad options are bad input: exit code 2):
/// for a value outside a closed choice, the option, the value and the accepted values;
/// otherwise clap's first line.
pub fn one_line(e: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue};
    let text = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.as_str()),
        _ => None,
    };
    if let (Some(arg), Some(value), Some(ContextValue::Strings(accepted))) = (
        text(ContextKind::InvalidArg),
        text(ContextKind::InvalidValue),
        e.get(ContextKind::ValidValue),
    ) {
        // "--method <M>": the option without its value name.
        let option = arg.split_whitespace().next().unwrap_or(arg);
        let hint = text(ContextKind::SuggestedValue)
            .map(|s| format!(" (did you mean `{s}`?)"))
            .unwrap_or_default();
        let accepted = accepted.join(", ");
        return if value.is_empty() {
            format!("error: {option} needs a value: one of {accepted} (see --help)")
        } else {
            format!("error: {option} = \"{value}\": one of {accepted}{hint} (see --help)")
        };
    }
    let text = e.to_string();
    let first = text.lines().next().unwrap_or("error: invalid arguments");
    format!("{} (see --help)", first.trim_end())
}

/// A progress bar on stderr with `template` (indicatif's syntax).
pub fn progress_bar(len: u64, template: &str) -> indicatif::ProgressBar {
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
    use super::choice::MethodChoice;
    use super::*;
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
        // Other errors: clap's first line.
        let other = one_line(&error_of(&["t", "--rtol", "abc"]));
        assert!(
            other.starts_with("error: invalid value 'abc' for '--rtol"),
            "{other}"
        );
        assert!(!other.contains('\n'), "{other}");
    }
}
