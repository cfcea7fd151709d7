//! Names a user typed (a scene key, a batch column, a subcommand) against the names
//! accepted: the closest accepted name, for a "did you mean" in the error.

/// The candidate within edit distance 2 (or a third of the length) of `word`, the nearest
/// first; `None` when no candidate is that close.
pub(crate) fn closest<'a>(word: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let limit = (word.len() / 3).max(2);
    candidates
        .iter()
        .map(|c| (edit_distance(word, c), *c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// ` (did you mean `name`?)` for the [`closest`] candidate, or nothing.
pub(crate) fn did_you_mean(word: &str, candidates: &[&str]) -> String {
    closest(word, candidates)
        .map(|best| format!(" (did you mean `{best}`?)"))
        .unwrap_or_default()
}

/// Levenshtein distance: the fewest insertions, deletions and substitutions of characters
/// that turn `a` into `b`.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = if ca == *cb {
                prev
            } else {
                1 + prev.min(cur).min(row[j])
            };
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distances counted by hand: one insertion, one substitution, a swap of two letters
    /// (two substitutions), and the whole word.
    #[test]
    fn edit_distances_by_hand() {
        assert_eq!(edit_distance("mas", "mass"), 1);
        assert_eq!(edit_distance("rk5", "rk4"), 1);
        assert_eq!(edit_distance("rnu", "run"), 2);
        assert_eq!(edit_distance("", "run"), 3);
        assert_eq!(edit_distance("run", "run"), 0);
    }

    #[test]
    fn suggestion_only_when_close() {
        assert_eq!(
            did_you_mean("runn", &["run", "batch"]),
            " (did you mean `run`?)"
        );
        assert_eq!(did_you_mean("plot", &["run", "batch"]), "");
    }

    /// The examples of the documentation of `closest`.
    #[test]
    fn closest_examples() {
        assert_eq!(
            closest("omega_a_xx", &["omega_a_x", "omega_b_x", "u_x"]),
            Some("omega_a_x")
        );
        assert_eq!(closest("speed", &["mass", "radius"]), None);
    }
}
