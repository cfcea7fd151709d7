//! The closed choices of the options (`--method`, `--profiles`) as clap value enums over the
//! library's own lists ([`Method::ALL`], [`StudyForce::ALL`]) and names, so that each name
//! is defined once and clap lists the accepted values in the help and in its errors; and
//! the parsers of numeric options, whose errors say what is accepted.

use crate::apps::work_precision::StudyForce;
use crate::base::method::Method;
use clap::builder::{EnumValueParser, PossibleValue, TypedValueParser};
use clap::ValueEnum;
use std::ffi::OsStr;
use std::marker::PhantomData;

/// A clap value enum over a library enum with `ALL` and `name()`.
macro_rules! choice {
    ($(#[$doc:meta])* $choice:ident($inner:ty)) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        pub(crate) struct $choice(pub(crate) $inner);

        impl ValueEnum for $choice {
            fn value_variants<'a>() -> &'a [Self] {
                const ALL: [$choice; <$inner>::ALL.len()] = {
                    let mut all = [$choice(<$inner>::ALL[0]); <$inner>::ALL.len()];
                    let mut i = 1;
                    while i < all.len() {
                        all[i] = $choice(<$inner>::ALL[i]);
                        i += 1;
                    }
                    all
                };
                &ALL
            }

            fn to_possible_value(&self) -> Option<PossibleValue> {
                Some(PossibleValue::new(self.0.name()))
            }
        }
    };
}

choice!(
    /// A `--method` value.
    MethodChoice(Method)
);

choice!(
    /// A `--profiles` value: a profile or a contact law.
    ProfileChoice(StudyForce)
);

/// clap's parser of a value enum applied to the value with surrounding white space removed,
/// so that a list reads the same with or without spaces after its commas.
#[derive(Debug)]
pub(super) struct Trimmed<E>(PhantomData<E>);

impl<E> Trimmed<E> {
    /// The parser.
    pub(super) fn new() -> Self {
        Trimmed(PhantomData)
    }
}

impl<E> Default for Trimmed<E> {
    fn default() -> Self {
        Trimmed::new()
    }
}

impl<E> Clone for Trimmed<E> {
    fn clone(&self) -> Self {
        Trimmed::new()
    }
}

impl<E: ValueEnum + Clone + Send + Sync + 'static> TypedValueParser for Trimmed<E> {
    type Value = E;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<E, clap::Error> {
        let trimmed = value.to_str().map_or(value, |s| OsStr::new(s.trim()));
        EnumValueParser::<E>::new().parse_ref(cmd, arg, trimmed)
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(
            E::value_variants()
                .iter()
                .filter_map(ValueEnum::to_possible_value),
        ))
    }
}

/// A whole-number option (`--samples`, `--steps`, `--threads`, ...), white space around it
/// ignored; the error says what is accepted.
pub(super) fn whole<T: std::str::FromStr>(value: &str) -> Result<T, String> {
    value
        .trim()
        .parse()
        .map_err(|_| "a whole number (0, 1, 2, ...)".to_string())
}

/// A real-number option (`--rtol`, `--atol`), white space around it ignored; the error
/// says what is accepted. NaN and infinities parse: the settings refuse them, naming the
/// field.
pub(super) fn number(value: &str) -> Result<f64, String> {
    value
        .trim()
        .parse()
        .map_err(|_| "a number such as 1e-10".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::contact_law::Damping;
    use crate::profile::spec::ProfileKind;

    #[test]
    fn every_method_and_profile_is_a_choice_under_its_name() {
        let methods: Vec<Method> = MethodChoice::value_variants().iter().map(|c| c.0).collect();
        assert_eq!(methods, Method::ALL);
        assert_eq!(
            MethodChoice::from_str("dopri5", false),
            Ok(MethodChoice(Method::Dopri5))
        );
        let profiles: Vec<StudyForce> = ProfileChoice::value_variants()
            .iter()
            .map(|c| c.0)
            .collect();
        assert_eq!(profiles, StudyForce::ALL);
        assert_eq!(
            ProfileChoice::from_str("sine-power", false),
            Ok(ProfileChoice(StudyForce::Profile(ProfileKind::SinePower)))
        );
        assert_eq!(
            ProfileChoice::from_str("hertz-law", false),
            Ok(ProfileChoice(StudyForce::Law(Damping::None)))
        );
        assert_eq!(
            ProfileChoice::from_str("kuwabara-kono", false),
            Ok(ProfileChoice(StudyForce::Law(Damping::KuwabaraKono)))
        );
        assert!(ProfileChoice::from_str("sine", false).is_err());
    }

    #[test]
    fn numbers_parse_or_say_what_is_accepted() {
        assert_eq!(whole::<u64>(" 12 "), Ok(12));
        assert_eq!(
            whole::<u64>("-5"),
            Err("a whole number (0, 1, 2, ...)".into())
        );
        assert_eq!(number("-1e-6"), Ok(-1e-6));
        assert_eq!(number("abc"), Err("a number such as 1e-10".into()));
    }
}
