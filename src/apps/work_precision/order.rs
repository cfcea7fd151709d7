//! The study's lines (one per profile, method and variant), their observed order of
//! convergence, and the cost tables (text summary and Markdown).

use crate::apps::work_precision::csv::is_peer_method;
use crate::apps::work_precision::plan::StudyRow;

/// How far (factor) a run may lie from the fitted line on the straight part of a line.
pub(crate) const STRAIGHT: f64 = 3.0;

/// The highest order of the methods studied (LSODA's Adams formulas go to 12; dop853 is 8):
/// a steeper fit is not an order.
pub(crate) const MAX_ORDER: f64 = 12.0;

/// Why a line has no observed order ([`Series::order_fit`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NoOrder {
    /// Fewer than two runs with error in [1e-13, 1e-2].
    TooFewRuns,
    /// Runs with the same evaluations and errors more than a factor 2 apart: the
    /// tolerance, not the work, sets the error.
    NotSetByWork,
    /// No three runs within a factor [`STRAIGHT`] of a line over a factor 1.5 in work.
    NoStraightPart,
    /// A slope steeper than [`MAX_ORDER`]: the error falls faster than any method's order
    /// allows (equal steps on the smoothed pulse, whose errors cancel as for a periodic
    /// integrand, or an error the tolerance sets).
    FasterThanAnyOrder,
}

impl NoOrder {
    /// A few words for legends and tables.
    pub(crate) fn text(&self) -> &'static str {
        match self {
            NoOrder::TooFewRuns => "too few runs",
            NoOrder::NotSetByWork => "error not set by work",
            NoOrder::NoStraightPart => "no straight part",
            NoOrder::FasterThanAnyOrder => "steeper than any order",
        }
    }
}

/// The least-squares line through `pts`: its slope and the largest distance (in y) of a
/// point from it; `None` when the x are all equal.
fn line_fit(pts: &[(f64, f64)]) -> Option<(f64, f64)> {
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| {
        let b = sxy / sxx;
        let worst = pts
            .iter()
            .map(|p| (p.1 - my - b * (p.0 - mx)).abs())
            .fold(0.0, f64::max);
        (b, worst)
    })
}

/// A line of the figure: the rows of one scene, profile, method and breakpoint setting.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Series<'a> {
    /// Scene name.
    pub scene: &'a str,
    /// Profile name.
    pub profile: &'a str,
    /// Method name.
    pub method: &'a str,
    /// Breakpoints on.
    pub breakpoints: bool,
    /// Time transform on.
    pub time_transform: bool,
    /// The rows, in the order of the ladder (cheapest first).
    pub rows: Vec<&'a StudyRow>,
}

impl Series<'_> {
    /// Whether the line runs with the defaults (breakpoints and time transform on).
    pub(crate) fn is_default(&self) -> bool {
        self.breakpoints && self.time_transform
    }

    /// The label of the line: the method, with "no transform" and "no breakpoints" when
    /// they were off.
    pub(crate) fn label(&self) -> String {
        match (self.time_transform, self.breakpoints) {
            (true, true) => self.method.to_string(),
            (true, false) => format!("{} (no breakpoints)", self.method),
            (false, true) => format!("{} (no transform)", self.method),
            (false, false) => format!("{} (no transform, no breakpoints)", self.method),
        }
    }

    /// Whether the line is a peer's ([`is_peer_method`]).
    pub(crate) fn is_peer(&self) -> bool {
        is_peer_method(self.method)
    }

    /// The observed order: minus the least-squares slope of log(error) against
    /// log(rhs evaluations) on the straight part of the line ([`Series::order_fit`]);
    /// `None` where there is none.
    #[cfg(test)]
    pub(crate) fn observed_order(&self) -> Option<f64> {
        self.order_fit().ok()
    }

    /// The observed order p (error ~ evaluations^-p), or why there is none. The runs are
    /// those with error in [1e-13, 1e-2] (below, round-off dominates; above, the
    /// asymptotic regime has not started) up to the ladder's most accurate run (past it,
    /// more work only accumulates round-off: hertz with rk4 ends at 1e-13 to 3e-13 after
    /// 4096 steps). Two such runs give the secant's slope (a ladder that reaches round-off
    /// within a rung or two). With more, the straight part: runs are dropped from either
    /// end, the one that leaves the better fit first, until every run lies within a factor
    /// [`STRAIGHT`] of the least-squares line, keeping at least three; the fit counts when
    /// those runs span a factor 1.5 in evaluations, no two of them with the same
    /// evaluations differ in error by more than a factor 2 (then the tolerance, not the
    /// work, sets the error; runs at either end with their neighbour's work are left out
    /// first), and the order is at most [`MAX_ORDER`] (LSODA on the tabulated pulse: 42
    /// evaluations from rtol 1e-3 to 1e-6, then 1e-10 in 54 more: "p = 23.4").
    pub(crate) fn order_fit(&self) -> Result<f64, NoOrder> {
        let best = self
            .rows
            .iter()
            .enumerate()
            .filter_map(|(i, r)| r.error.map(|e| (i, e)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0, |(i, _)| i);
        let pts: Vec<(f64, f64)> = self.rows[..=best.min(self.rows.len().saturating_sub(1))]
            .iter()
            .filter_map(|r| {
                let e = r.error?;
                let n = r.stats.rhs_evaluations;
                ((1e-13..=1e-2).contains(&e) && n > 0).then(|| ((n as f64).ln(), e.ln()))
            })
            .collect();
        if pts.len() < 2 {
            return Err(NoOrder::TooFewRuns);
        }
        let mut w: &[(f64, f64)] = &pts;
        // Runs at the ladder's ends with the work of their neighbour (the fewest steps a
        // method takes, or the most) measure the tolerance, not the work.
        while w.len() > 2 && w[0].0 == w[1].0 {
            w = &w[1..];
        }
        while w.len() > 2 && w[w.len() - 1].0 == w[w.len() - 2].0 {
            w = &w[..w.len() - 1];
        }
        let mut fit = line_fit(w);
        while fit.is_none_or(|f| f.1 > STRAIGHT.ln()) && w.len() > 3 {
            let (head, tail) = (line_fit(&w[1..]), line_fit(&w[..w.len() - 1]));
            let worst = |f: Option<(f64, f64)>| f.map_or(f64::INFINITY, |f| f.1);
            w = if worst(head) <= worst(tail) {
                &w[1..]
            } else {
                &w[..w.len() - 1]
            };
            fit = line_fit(w);
        }
        let same_work = w.iter().enumerate().any(|(i, a)| {
            w[i + 1..]
                .iter()
                .any(|b| a.0 == b.0 && (a.1 - b.1).abs() > 2f64.ln())
        });
        if same_work {
            return Err(NoOrder::NotSetByWork);
        }
        let spans = w.len() == 2 || w[w.len() - 1].0 - w[0].0 >= 1.5f64.ln();
        match fit {
            Some((slope, worst)) if worst <= STRAIGHT.ln() && spans => {
                if -slope > MAX_ORDER {
                    Err(NoOrder::FasterThanAnyOrder)
                } else {
                    Ok(-slope)
                }
            }
            _ => Err(NoOrder::NoStraightPart),
        }
    }

    /// The fewest right-hand-side evaluations of a run with error <= `target`, if any.
    pub(crate) fn fewest_evaluations_within(&self, target: f64) -> Option<u64> {
        self.rows
            .iter()
            .filter(|r| r.error.is_some_and(|e| e <= target))
            .map(|r| r.stats.rhs_evaluations)
            .min()
    }

    /// The cheapest run (seconds per contact) with error <= `target`, if any.
    pub(crate) fn cheapest_within(&self, target: f64) -> Option<&StudyRow> {
        self.rows
            .iter()
            .copied()
            .filter(|r| r.error.is_some_and(|e| e <= target) && r.seconds_per_contact.is_finite())
            .min_by(|a, b| a.seconds_per_contact.total_cmp(&b.seconds_per_contact))
    }
}

/// Groups rows into lines, in order of first appearance; within a line the rows are
/// ordered from the loosest setting to the tightest (rk4 by steps, others by decreasing
/// rtol, then by evaluations).
pub(crate) fn series(rows: &[StudyRow]) -> Vec<Series<'_>> {
    let mut out: Vec<Series<'_>> = Vec::new();
    for r in rows {
        let found = out.iter_mut().find(|s| {
            s.scene == r.scene
                && s.profile == r.profile
                && s.method == r.method
                && s.breakpoints == r.breakpoints
                && s.time_transform == r.time_transform
        });
        match found {
            Some(s) => s.rows.push(r),
            None => out.push(Series {
                scene: &r.scene,
                profile: &r.profile,
                method: &r.method,
                breakpoints: r.breakpoints,
                time_transform: r.time_transform,
                rows: vec![r],
            }),
        }
    }
    for s in &mut out {
        s.rows.sort_by(|a, b| {
            let ka = (a.steps.unwrap_or(0), -a.rtol.unwrap_or(0.0));
            let kb = (b.steps.unwrap_or(0), -b.rtol.unwrap_or(0.0));
            ka.0.cmp(&kb.0)
                .then(ka.1.total_cmp(&kb.1))
                .then(a.stats.rhs_evaluations.cmp(&b.stats.rhs_evaluations))
        });
    }
    out
}

/// The error levels the summaries give the cost of.
pub(crate) const TARGETS: [f64; 4] = [1e-6, 1e-8, 1e-10, 1e-12];

/// The cost of reaching `target` on a line: time per contact and evaluations of its
/// cheapest run, or "not reached".
fn cost_cell(line: &Series<'_>, target: f64) -> String {
    match line.cheapest_within(target) {
        Some(r) => format!(
            "{} / {}",
            human_seconds(r.seconds_per_contact),
            r.stats.rhs_evaluations
        ),
        None => "not reached".into(),
    }
}

/// A line's observed order, one decimal, or "-" and why not.
fn order_cell(line: &Series<'_>) -> String {
    match line.order_fit() {
        Ok(o) => format!("{o:.1}"),
        Err(NoOrder::TooFewRuns) => "-".into(),
        Err(why) => format!("- ({})", why.text()),
    }
}

/// A plain-text summary: per scene and profile, each method's observed order and the
/// cheapest cost (time per contact / evaluations) of reaching the errors 1e-6, 1e-8, 1e-10 and 1e-12.
pub fn summary(rows: &[StudyRow]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let mut scene = "";
    for line in series(rows) {
        if line.scene != scene {
            scene = line.scene;
            let _ = writeln!(s, "\nscene: {scene}");
            let _ = write!(s, "{:<11} {:<34} {:>24}", "profile", "method", "order");
            for t in TARGETS {
                let _ = write!(s, "  {:>18}", format!("error<={t:e}"));
            }
            s.push('\n');
        }
        let _ = write!(
            s,
            "{:<11} {:<34} {:>24}",
            line.profile,
            line.label(),
            order_cell(&line)
        );
        for target in TARGETS {
            let _ = write!(s, "  {:>18}", cost_cell(&line, target));
        }
        s.push('\n');
    }
    s
}

/// The cost tables in Markdown (the study writes them to `work_precision.md` beside the
/// CSV): per scene, every line's observed order, best error and cheapest cost of each
/// error of 1e-6, 1e-8, 1e-10 and 1e-12; then, per profile, what the adaptive methods pay against the
/// half-sine for the same error.
pub fn markdown(rows: &[StudyRow]) -> String {
    use std::fmt::Write as _;
    let mut s = String::from(
        "# What accuracy costs\n\n\
         Generated by `billiard-contact work-precision` (or `--replot`) from `work_precision.csv` \
         in the same directory: do not edit by hand. Each cell is the time per contact \
         (median wall time of one solve) / the right-hand-side evaluations of the cheapest run \
         of the line's ladder that reaches the error; p is the observed order (error ~ \
         evaluations^-p), fitted on the straight part of the runs with error in [1e-13, 1e-2] \
         up to the ladder's most accurate one (every run within a factor 3 of the line); \
         \"-\" says why there is none: no straight part, the error not set by the work \
         (runs with the same evaluations and errors a factor 2 or more apart), or a slope \
         steeper than 12, the highest order of the methods; best is the smallest error of the ladder. \"no transform\": hertz and sine-power stepped through graded \
         breakpoints instead of the smoothing time transform; \"no breakpoints\": a table's \
         knots not stepped to.\n",
    );
    let lines = series(rows);
    let mut scenes: Vec<&str> = Vec::new();
    for l in &lines {
        if !scenes.contains(&l.scene) {
            scenes.push(l.scene);
        }
    }
    for scene in scenes {
        let _ = write!(s, "\n## {scene}\n\n| profile | method | p | best error |");
        for t in TARGETS {
            let _ = write!(s, " error <= {t:e} |");
        }
        s.push_str("\n|---|---|---|---|");
        s.push_str(&"---|".repeat(TARGETS.len()));
        s.push('\n');
        for line in lines.iter().filter(|l| l.scene == scene) {
            let best = line
                .rows
                .iter()
                .filter_map(|r| r.error)
                .min_by(f64::total_cmp)
                .map_or("-".to_string(), |e| match e {
                    0.0 => "0".to_string(),
                    e => format!("{e:.1e}"),
                });
            let _ = write!(
                s,
                "| {} | {} | {} | {best} |",
                line.profile,
                line.label(),
                order_cell(line)
            );
            for t in TARGETS {
                let _ = write!(s, " {} |", cost_cell(line, t));
            }
            s.push('\n');
        }
        s.push_str(&against_half_sine(&lines, scene));
    }
    s
}

/// Per profile other than the half-sine, for dopri5 and dop853 with the default settings:
/// evaluations (fewest of a run reaching the error) and time per contact (cheapest run)
/// over the half-sine's, at the errors of [`TARGETS`] but the last.
fn against_half_sine(lines: &[Series<'_>], scene: &str) -> String {
    use std::fmt::Write as _;
    let targets = &TARGETS[..TARGETS.len() - 1];
    let mut s = String::from(
        "\nAgainst the half-sine at the same error (evaluations, time per contact; \
         default settings):\n\n| profile | method |",
    );
    for t in targets {
        let _ = write!(s, " error <= {t:e} |");
    }
    s.push_str("\n|---|---|");
    s.push_str(&"---|".repeat(targets.len()));
    s.push('\n');
    let default = |profile: &str, method: &str| {
        lines.iter().find(|l| {
            l.scene == scene && l.profile == profile && l.method == method && l.is_default()
        })
    };
    for line in lines.iter().filter(|l| l.scene == scene && l.is_default()) {
        if line.profile == "half-sine" || !matches!(line.method, "dopri5" | "dop853") {
            continue;
        }
        let Some(base) = default("half-sine", line.method) else {
            continue;
        };
        let _ = write!(s, "| {} | {} |", line.profile, line.method);
        for &t in targets {
            let evals = line.fewest_evaluations_within(t);
            let base_evals = base.fewest_evaluations_within(t);
            let time = line.cheapest_within(t).map(|r| r.seconds_per_contact);
            let base_time = base.cheapest_within(t).map(|r| r.seconds_per_contact);
            let cell = match (evals, base_evals, time, base_time) {
                (Some(n), Some(b), Some(x), Some(y)) if b > 0 && y > 0.0 => {
                    format!("{:.2}x, {:.2}x", n as f64 / b as f64, x / y)
                }
                _ => "-".into(),
            };
            let _ = write!(s, " {cell} |");
        }
        s.push('\n');
    }
    s
}

/// Seconds in ns, us or ms.
pub(crate) fn human_seconds(t: f64) -> String {
    if t < 1e-6 {
        format!("{:.0} ns", t * 1e9)
    } else if t < 1e-3 {
        format!("{:.2} us", t * 1e6)
    } else {
        format!("{:.2} ms", t * 1e3)
    }
}
