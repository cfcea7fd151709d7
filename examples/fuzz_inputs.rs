//! Fuzz harness: arbitrary and near-valid scene text and profile CSV through the
//! library's parsers, and every input that parses through a run and the JSON report.
//!
//! ```sh
//! cargo run --release --example fuzz_inputs -- --inputs 1000000 --seed 1
//! ```
//!
//! Stable Rust has no cargo-fuzz, so this is a deterministic generator (xorshift, `--seed`):
//! half the inputs are mutated scenes (numbers replaced by edge values such as 0, -0.0,
//! 1e-300, 1e308, nan, inf; lines deleted, duplicated, swapped; keys and names misspelt;
//! bytes flipped, inserted, truncated), a tenth arbitrary bytes, the rest mutated profile
//! tables. Each input must:
//! - not panic (caught and counted),
//! - not hang: the work per input is bounded (rk4 steps capped at 20,000, rtol at >= 1e-12,
//!   the adaptive methods stop after 100,000 steps a segment) and its time is measured,
//! - give finite output: every scene that parses is run with the closed form and with its own
//!   method, and `Report::to_json` must succeed (it refuses non-finite numbers);
//!   every table that parses must give a profile with finite, monotone Phi and a run.
//!
//! Findings are written to `fuzz/artifacts/` (panics, non-finite output, failed runs, inputs
//! slower than a second) and summarised at the end. `tests/fuzz_smoke.rs` runs the same
//! harness on a few thousand inputs in `cargo test`.

use billiard_contact::profile::{parse_table, ForceProfile, Profile, Tabulated};
use billiard_contact::run_scene;
use billiard_contact::Error;
use billiard_contact::Report;
use billiard_contact::Scene;
use billiard_contact::{Method, SolverSettings};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Seed scenes: the committed ones and one of every profile, method and incoming form.
const SEEDS: &[&str] = &[
    include_str!("../data/scenes/default.toml"),
    include_str!("../data/scenes/draw_side_spin.toml"),
    include_str!("../data/scenes/head_on_stun.toml"),
    include_str!("../data/scenes/paper_special_case.toml"),
    include_str!("../data/scenes/separating.toml"),
    include_str!("../data/scenes/stun_cut_slides.toml"),
    include_str!("../data/scenes/stun_cut_sticks.toml"),
    r#"name = "every option"
[balls]
mass = 0.17
radius = 0.028575
alpha = 0.4
[contact]
mu = { model = "speed-dependent", a = 9.951e-3, b = 0.108, c = 1.088 }
impulse = 0.3
[contact.profile]
shape = "sine-power"
exponent = 1.5
duration = 2.5e-4
[incoming.cm]
u = [1.0, 0.3, -0.2]
omega_a = [10.0, -20.0, 30.0]
omega_b = [-5.0, 0.0, 1.0]
[solver]
method = "dopri5"
rtol = 1e-9
atol = 1e-9
steps = 500
[effects]
friction = true
stick = false
table = false
"#,
    r#"[balls]
mass = 0.17
radius = 0.028575
[contact]
mu = 0.2
restitution = 0.5
[contact.profile]
shape = "tabulated"
file = "table.csv"
duration = 3e-4
[incoming.cm]
u = [1.0, 0.01, 0.0]
[solver]
method = "rk4"
steps = 300
"#,
    r#"[balls]
mass = 1e-3
radius = 1e-4
alpha = 0.6666666666666666
[contact]
mu = 10
[contact.profile]
shape = "rectangle"
duration = 1e-9
[incoming.cm]
u = [1e4, 0.0, 1e-300]
omega_b = [0.0, 1e6, 0.0]
[solver]
method = "closed-form"
"#,
    r#"[balls]
mass = 2.0
radius = 10.0
alpha = 1e-3
[contact]
mu = 1e-12
restitution = 0
[contact.profile]
shape = "hertz"
duration = 1.0
[incoming.lab]
a = { position = [0.0, 0.0, 10.0], velocity = [0.0, 1e-8, 0.0], spin = [1.0, 0.0, 0.0] }
b = { position = [0.0, 20.0, 10.0], velocity = [0.0, 0.0, 0.0] }
up = [0.0, 0.0, 1.0]
"#,
];

/// Seed tables.
const TABLES: &[&str] = &[
    include_str!("../data/profiles/measured_pulse.csv"),
    "time,force\n0,0\n0.2,1\n0.3,1\n0.35,0\n0.5,0\n0.5005,50\n0.501,0\n0.7,0\n0.8,2\n1,0\n",
    "time,force\n0,3\n1e-3,4\n0.25,0.5\n0.6,6\n0.61,1\n1,2\n",
    "Time , Force\n0,0\n1,1\n",
];

const EDGE_NUMBERS: &[&str] = &[
    "0",
    "0.0",
    "-0.0",
    "-1",
    "1",
    "2",
    "0.5",
    "1e-300",
    "5e-324",
    "1e-15",
    "1e300",
    "1e308",
    "1.7976931348623157e308",
    "-1e308",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "1e400",
    "0.6666666666666666",
    "0.6666666666666667",
    "0.66666666666666674",
    "4294967295",
    "4294967296",
    "-4294967296",
    "9223372036854775807",
    "1000000000",
    "1e9",
    "3",
    "0x10",
    "1_000",
    "1e",
    ".",
    "--1",
    "\"1\"",
    "[1, 2, 3]",
    "{}",
    "true",
];

const NAMES: &[&str] = &[
    "half-sine",
    "hertz",
    "sine-power",
    "rectangle",
    "tabulated",
    "closed-form",
    "rk4",
    "dopri5",
    "dop853",
    "speed-dependent",
    "halfsine",
    "Hertz",
    "",
    "table.csv",
    "missing.csv",
    "..",
    "/",
];

const KEYS: &[&str] = &[
    "mass",
    "radius",
    "alpha",
    "mu",
    "restitution",
    "impulse",
    "shape",
    "duration",
    "exponent",
    "file",
    "u",
    "omega_a",
    "omega_b",
    "a",
    "b",
    "c",
    "up",
    "position",
    "velocity",
    "spin",
    "method",
    "rtol",
    "atol",
    "steps",
    "friction",
    "stick",
    "table",
    "name",
    "model",
    "mas",
    "restitutoin",
];

/// xorshift64*.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, v: &'a [T]) -> &'a T {
        &v[self.below(v.len())]
    }
    fn float(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Spans of number-like tokens in `text`.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let starts = c.is_ascii_digit()
            || ((c == b'-' || c == b'+' || c == b'.')
                && i + 1 < b.len()
                && b[i + 1].is_ascii_digit());
        if starts && (i == 0 || !b[i - 1].is_ascii_alphanumeric() && b[i - 1] != b'_') {
            let s = i;
            i += 1;
            while i < b.len()
                && (b[i].is_ascii_digit()
                    || matches!(b[i], b'.' | b'e' | b'E' | b'-' | b'+' | b'_'))
            {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

fn random_number(rng: &mut Rng) -> String {
    match rng.below(4) {
        0 => rng.pick(EDGE_NUMBERS).to_string(),
        1 => format!(
            "{:e}",
            10f64.powf(rng.float() * 40.0 - 20.0) * if rng.below(4) == 0 { -1.0 } else { 1.0 }
        ),
        2 => format!("{}", rng.float() * 2.0 - 0.5),
        _ => format!("{}", rng.below(2000) as i64 - 500),
    }
}

/// One to four mutations of `text`.
fn mutate(rng: &mut Rng, text: &str) -> String {
    let mut s = text.to_string();
    for _ in 0..1 + rng.below(4) {
        match rng.below(10) {
            0..=2 => {
                let spans = number_spans(&s);
                if !spans.is_empty() {
                    let (a, b) = *rng.pick(&spans);
                    let n = random_number(rng);
                    s.replace_range(a..b, &n);
                }
            }
            3 => {
                let mut lines: Vec<&str> = s.lines().collect();
                if !lines.is_empty() {
                    let i = rng.below(lines.len());
                    lines.remove(i);
                }
                s = lines.join("\n");
            }
            4 => {
                let lines: Vec<String> = s.lines().map(String::from).collect();
                if lines.len() > 1 {
                    let (i, j) = (rng.below(lines.len()), rng.below(lines.len()));
                    let mut l = lines.clone();
                    if rng.below(2) == 0 {
                        l.swap(i, j);
                    } else {
                        l.insert(j, lines[i].clone());
                    }
                    s = l.join("\n");
                }
            }
            5 => {
                // A key renamed (misspelt or another valid key).
                let k = *rng.pick(KEYS);
                if let Some(pos) = s.find(&format!("{k} =")) {
                    let new = match rng.below(3) {
                        0 => rng.pick(KEYS).to_string(),
                        1 => format!("{k}{k}"),
                        _ => k.chars().rev().collect(),
                    };
                    s.replace_range(pos..pos + k.len(), &new);
                }
            }
            6 => {
                // A quoted name replaced.
                let quotes: Vec<usize> = s.match_indices('"').map(|(i, _)| i).collect();
                if quotes.len() >= 2 {
                    let q = rng.below(quotes.len() / 2) * 2;
                    let (a, b) = (quotes[q], quotes[q + 1]);
                    let n = rng.pick(NAMES).to_string();
                    s.replace_range(a + 1..b, &n);
                }
            }
            7 => {
                // Bytes inserted (random ASCII, structure characters, or unicode).
                let pos = char_boundary(&s, rng.below(s.len() + 1));
                let pieces = [
                    "[",
                    "]",
                    "{",
                    "}",
                    "=",
                    ",",
                    "\"",
                    "\n",
                    "#",
                    "\u{feff}",
                    "é",
                    "\0",
                    "[[x]]",
                    "[balls]\n",
                ];
                let p = rng.pick(&pieces).to_string();
                s.insert_str(pos, &p);
            }
            8 => {
                // A range deleted or the text truncated.
                if !s.is_empty() {
                    let a = char_boundary(&s, rng.below(s.len()));
                    let b = char_boundary(&s, (a + 1 + rng.below(40)).min(s.len()));
                    if rng.below(3) == 0 {
                        s.truncate(a);
                    } else {
                        s.replace_range(a..b, "");
                    }
                }
            }
            _ => {
                // A section or key added.
                let extra = [
                    "\n[solver]\nmethod = \"rk4\"\nsteps = 1000000000\n",
                    "\n[solver]\nrtol = 1e-15\natol = 1e-300\n",
                    "\n[effects]\nstick = false\n",
                    "\n[effects]\nfriction = false\n",
                    "\nimpulse = 0.2\n",
                    "\n[incoming.lab]\n",
                    "\nexponent = 64\n",
                    "\nexponent = 0.01\n",
                ];
                let e = extra[rng.below(extra.len())];
                s.push_str(e);
            }
        }
    }
    s
}

fn char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn random_bytes(rng: &mut Rng) -> Vec<u8> {
    let n = rng.below(300);
    (0..n)
        .map(|_| {
            if rng.below(3) == 0 {
                (rng.next() & 0xff) as u8
            } else {
                *rng.pick(b"[]{}=,.\"#\n abcdefmnorstu0123456789-+e")
            }
        })
        .collect()
}

/// What the harness found, by kind.
#[derive(Debug, Default, Clone)]
pub struct Summary {
    pub inputs: u64,
    pub scenes_parsed: u64,
    pub scenes_refused: u64,
    pub tables_parsed: u64,
    pub tables_refused: u64,
    pub runs: u64,
    pub failed_runs: u64,
    pub panics: u64,
    pub non_finite: u64,
    pub slow: u64,
    pub slowest: Duration,
    pub findings: Vec<String>,
}

/// Findings written so far (names the artifact files).
static FOUND: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// A finding: kind and the input (its text), written under `artifacts` when given.
fn found(sum: &mut Summary, artifacts: Option<&Path>, kind: &str, input: &str, detail: &str) {
    let n = FOUND.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    if n < 1000 {
        sum.findings.push(format!("{kind}: {detail}"));
        if let Some(dir) = artifacts {
            let _ = std::fs::create_dir_all(dir);
            let _ = std::fs::write(
                dir.join(format!("{kind}-{n}.txt")),
                format!("# {detail}\n{input}"),
            );
        }
    }
}

/// Caps the work of a parsed scene: rk4 steps and the adaptive tolerance.
fn bounded(s: &SolverSettings) -> SolverSettings {
    // Each bound moves a valid value towards the middle of its range: the setters accept it.
    s.with_steps(s.steps().min(20_000))
        .and_then(|b| b.with_rtol(s.rtol().max(1e-12)))
        .and_then(|b| b.with_atol(s.atol().max(1e-12)))
        .unwrap_or(*s)
}

/// Runs a parsed scene with the closed form and with its own (bounded) method; both reports
/// must serialise (finite numbers).
fn run_parsed(scene: &Scene, sum: &mut Summary, artifacts: Option<&Path>, input: &str) {
    let own = bounded(&scene.solver);
    let closed = own.with_method(Method::ClosedForm);
    for settings in [closed, own] {
        sum.runs += 1;
        match run_scene(scene, &settings, None) {
            Ok(out) => {
                if let Err(e) = Report::new(scene, &out).to_json() {
                    sum.non_finite += 1;
                    found(
                        sum,
                        artifacts,
                        "non-finite",
                        input,
                        &format!("{}: {e}", settings.method()),
                    );
                }
            }
            Err(e) if e.is_bad_input() => {}
            Err(e) => {
                sum.failed_runs += 1;
                found(
                    sum,
                    artifacts,
                    "failed-run",
                    input,
                    &format!("{}: {e}", settings.method()),
                );
            }
        }
    }
}

/// A parsed table as a profile: Phi finite, monotone, 0 and 1 at the ends; its inverse in
/// [0, 1]; then a collision run with it.
fn check_table(
    t: Tabulated,
    rng: &mut Rng,
    sum: &mut Summary,
    artifacts: Option<&Path>,
    input: &str,
) {
    let p = Profile::Tabulated(t);
    let mut last = 0.0;
    for i in 0..=32 {
        let s = i as f64 / 32.0;
        let (phi, cum) = (p.shape(s), p.cumulative(s));
        if !(phi.is_finite() && phi >= 0.0 && cum.is_finite() && cum >= last - 1e-15 && cum <= 1.0)
        {
            sum.non_finite += 1;
            found(
                sum,
                artifacts,
                "bad-profile",
                input,
                &format!("s = {s}: phi {phi}, Phi {cum}"),
            );
            return;
        }
        last = cum;
        let q = rng.float();
        let back = p.time_at_cumulative(q);
        if !(0.0..=1.0).contains(&back) {
            found(
                sum,
                artifacts,
                "bad-inverse",
                input,
                &format!("q = {q}: s = {back}"),
            );
        }
    }
    let scene_text = SEEDS[8];
    let mut scene = Scene::parse(scene_text, Path::new("."), None).unwrap_or_else(|_| {
        // The seed needs table.csv only through the file key; build the scene by hand.
        let text = scene_text.replace(
            "shape = \"tabulated\"\nfile = \"table.csv\"\nduration = 3e-4",
            "shape = \"rectangle\"\nduration = 3e-4",
        );
        Scene::parse(&text, Path::new("."), None).expect("seed scene")
    });
    scene.profile = p;
    scene.solver =
        scene
            .solver
            .with_method(*rng.pick(&[Method::Rk4, Method::Dopri5, Method::Dop853]));
    run_parsed(&scene, sum, artifacts, input);
}

impl Summary {
    /// Adds the counts of one input.
    fn add(&mut self, o: Summary) {
        self.scenes_parsed += o.scenes_parsed;
        self.scenes_refused += o.scenes_refused;
        self.tables_parsed += o.tables_parsed;
        self.tables_refused += o.tables_refused;
        self.runs += o.runs;
        self.failed_runs += o.failed_runs;
        self.non_finite += o.non_finite;
        self.findings.extend(o.findings);
    }
}

/// Processes one scene text.
fn scene_input(text: &str, base: &Path, artifacts: Option<&Path>) -> Summary {
    let mut local = Summary::default();
    match Scene::parse(text, base, None) {
        Ok(scene) => {
            local.scenes_parsed += 1;
            run_parsed(&scene, &mut local, artifacts, text);
        }
        Err(e) => {
            local.scenes_refused += 1;
            if !e.is_bad_input() {
                found(&mut local, artifacts, "not-bad-input", text, &e.to_string());
            }
            // A refusal is one line.
            if e.to_string().contains('\n') {
                found(
                    &mut local,
                    artifacts,
                    "multi-line-error",
                    text,
                    &e.to_string(),
                );
            }
        }
    }
    local
}

/// Processes one table text.
fn table_input(text: &str, rng: &mut Rng, artifacts: Option<&Path>) -> Summary {
    let mut local = Summary::default();
    let path = Path::new("fuzz.csv");
    let duration = (rng.below(2) == 0).then(|| 10f64.powf(rng.float() * 10.0 - 9.0));
    let parsed = parse_table(text, path).and_then(|pts| Tabulated::new(&pts, duration, path));
    match parsed {
        Ok(t) => {
            local.tables_parsed += 1;
            check_table(t, rng, &mut local, artifacts, text);
        }
        Err(e) => {
            local.tables_refused += 1;
            if !matches!(e, Error::ProfileTable { .. }) || e.to_string().contains('\n') {
                found(&mut local, artifacts, "table-error", text, &e.to_string());
            }
        }
    }
    local
}

/// One input: generated from `rng`, processed (panics caught), counted.
fn one(rng: &mut Rng, base: &Path, sum: &mut Summary, artifacts: Option<&Path>) {
    sum.inputs += 1;
    let kind = rng.below(10);
    let input = match kind {
        0 | 6 => String::from_utf8_lossy(&random_bytes(rng)).into_owned(),
        1..=5 => {
            let seed = *rng.pick(SEEDS);
            mutate(rng, seed)
        }
        _ => {
            let seed = *rng.pick(TABLES);
            mutate(rng, seed)
        }
    };
    let mut r2 = Rng(rng.next() | 1);
    let start = Instant::now();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        if kind < 6 {
            scene_input(&input, base, artifacts)
        } else {
            table_input(&input, &mut r2, artifacts)
        }
    }));
    let took = start.elapsed();
    match result {
        Ok(local) => sum.add(local),
        Err(p) => {
            sum.panics += 1;
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            found(sum, artifacts, "panic", &input, &msg);
        }
    }
    if took > sum.slowest {
        sum.slowest = took;
    }
    if took > Duration::from_secs(1) {
        sum.slow += 1;
        found(sum, artifacts, "slow", &input, &format!("{took:?}"));
    }
}

/// Runs `n` inputs from `seed`; `base` holds `table.csv` for scenes that name it.
pub fn run(n: u64, seed: u64, artifacts: Option<&Path>, progress: bool) -> Summary {
    let base: PathBuf = std::env::temp_dir().join(format!("billiard-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&base).expect("temp dir");
    std::fs::write(base.join("table.csv"), TABLES[0]).expect("table");
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut sum = Summary::default();
    // Panics are caught and counted; keep their messages off the terminal.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let start = Instant::now();
    for i in 0..n {
        one(&mut rng, &base, &mut sum, artifacts);
        if progress && (i + 1) % 100_000 == 0 {
            eprintln!(
                "{} inputs, {:.0} s, {} panics, {} non-finite, {} failed runs, slowest {:?}",
                i + 1,
                start.elapsed().as_secs_f64(),
                sum.panics,
                sum.non_finite,
                sum.failed_runs,
                sum.slowest
            );
        }
    }
    std::panic::set_hook(hook);
    let _ = std::fs::remove_dir_all(&base);
    sum
}

#[allow(dead_code)]
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let get = |name: &str, default: u64| -> u64 {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let n = get("--inputs", 1_000_000);
    let seed = get("--seed", 1);
    let artifacts = PathBuf::from("fuzz/artifacts");
    let start = Instant::now();
    let sum = run(n, seed, Some(&artifacts), true);
    let secs = start.elapsed().as_secs_f64();
    println!(
        "{} inputs (seed {seed}) in {secs:.1} s: {} scenes parsed, {} refused; {} tables parsed, {} refused; \
         {} runs, {} failed runs; {} panics, {} non-finite outputs, {} inputs over 1 s (slowest {:?})",
        sum.inputs,
        sum.scenes_parsed,
        sum.scenes_refused,
        sum.tables_parsed,
        sum.tables_refused,
        sum.runs,
        sum.failed_runs,
        sum.panics,
        sum.non_finite,
        sum.slow,
        sum.slowest
    );
    for f in sum.findings.iter().take(20) {
        println!("  {f}");
    }
    if !sum.findings.is_empty() {
        println!("inputs of the findings: {}", artifacts.display());
        std::process::exit(1);
    }
}
