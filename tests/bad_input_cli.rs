//! Bad input through the command line: every case gives exactly one line on
//! stderr, starting `error: `, naming the field (or file and line), the value and what is
//! accepted; exit code 2; nothing on stdout; no panic; and the file system as it was: an
//! existing trace file keeps its bytes and modification time, no new trace file and no
//! temporary file appears.
//!
//! Exit codes (docs/formats.md): 0 success, 1 a run that failed (integrator gave up, non-finite
//! result), 2 bad input (scene, profile table, options, unreadable or unwritable files).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, SystemTime};

const BIN: &str = env!("CARGO_BIN_EXE_billiard-contact");

/// A centre-of-mass scene (the paper's special case).
const CM: &str = r#"name = "cm"
[balls]
mass = 0.17
radius = 0.028575
alpha = 0.4
[contact]
mu = 0.06
restitution = 1.0
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.cm]
u = [0.5, 0.25, 0.0]
omega_a = [-17.5, 35.0, 0.0]
omega_b = [0.0, 0.0, 0.0]
[solver]
method = "dop853"
rtol = 1e-10
[effects]
friction = true
"#;

/// A lab scene (a stun cut at 10 degrees).
const LAB: &str = r#"name = "lab"
[balls]
mass = 0.17
radius = 0.028575
[contact]
mu = 0.06
[contact.profile]
shape = "tabulated"
file = "prof.csv"
duration = 3e-4
[incoming.lab]
a = { position = [-0.028575, 0.0, 0.028575], velocity = [1.9696, 0.3473, 0.0], spin = [0.0, 0.0, 0.0] }
b = { position = [0.028575, 0.0, 0.028575], velocity = [0.0, 0.0, 0.0], spin = [0.0, 0.0, 0.0] }
up = [0.0, 0.0, 1.0]
"#;

const TABLE: &str = "time,force\n0,0\n1e-4,900\n2e-4,1000\n3e-4,0\n";

/// A fresh directory with `scene.toml`, `prof.csv` and an old `existing.csv`.
struct Sandbox {
    dir: PathBuf,
}

const OLD_TRACE: &[u8] = b"t (s)\n0.0\n";

impl Sandbox {
    fn new(name: &str, scene: &str, table: &str) -> Self {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join("bad_input")
            .join(name.replace(|c: char| !c.is_ascii_alphanumeric(), "_"));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("scene.toml"), scene).unwrap();
        std::fs::write(dir.join("prof.csv"), table).unwrap();
        let trace = dir.join("existing.csv");
        std::fs::write(&trace, OLD_TRACE).unwrap();
        let old = SystemTime::UNIX_EPOCH + Duration::from_secs(1_600_000_000);
        std::fs::File::options()
            .write(true)
            .open(&trace)
            .unwrap()
            .set_modified(old)
            .unwrap();
        Sandbox { dir }
    }

    /// Every file: bytes and modification time.
    fn snapshot(&self) -> BTreeMap<String, (Vec<u8>, SystemTime)> {
        let mut m = BTreeMap::new();
        for e in std::fs::read_dir(&self.dir).unwrap() {
            let e = e.unwrap();
            let meta = e.metadata().unwrap();
            let bytes = if meta.is_file() {
                std::fs::read(e.path()).unwrap()
            } else {
                Vec::new()
            };
            m.insert(
                e.file_name().to_string_lossy().into_owned(),
                (bytes, meta.modified().unwrap()),
            );
        }
        m
    }

    fn path(&self, name: &str) -> String {
        self.dir.join(name).to_string_lossy().into_owned()
    }
}

/// Runs `args` (with `{dir}` replaced by the sandbox) twice, once writing the existing trace
/// and once a new one, and checks the one-line error, exit code 2 and the untouched files.
fn refuse(name: &str, scene: &str, table: &str, args: &[&str], want: &[&str]) {
    let sb = Sandbox::new(name, scene, table);
    for trace in ["existing.csv", "new.csv"] {
        let before = sb.snapshot();
        let mut argv: Vec<String> = args
            .iter()
            .map(|a| a.replace("{dir}", &sb.path("")))
            .collect();
        if !args.contains(&"--trace") {
            argv.extend(["--trace".into(), sb.path(trace), "--json".into()]);
        }
        let out = Command::new(BIN).args(&argv).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{name}: exit {:?}, stderr {stderr}",
            out.status
        );
        assert!(stdout.is_empty(), "{name}: stdout {stdout}");
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
        let lines: Vec<&str> = stderr.lines().collect();
        assert_eq!(lines.len(), 1, "{name}: not one line:\n{stderr}");
        assert!(lines[0].starts_with("error: "), "{name}: {stderr}");
        for w in want {
            assert!(
                lines[0].contains(w),
                "{name}: `{w}` missing in: {}",
                lines[0]
            );
        }
        assert_eq!(sb.snapshot(), before, "{name}: files changed ({trace})");
    }
}

/// `scene` with `from` replaced by `to` (which must occur).
fn edit(scene: &str, from: &str, to: &str) -> String {
    assert!(scene.contains(from), "{from}");
    scene.replacen(from, to, 1)
}

fn cm(from: &str, to: &str, want: &[&str]) {
    let name = format!("cm {from} -> {to}");
    refuse(
        &name,
        &edit(CM, from, to),
        TABLE,
        &["run", "{dir}scene.toml"],
        want,
    );
}

fn lab(from: &str, to: &str, want: &[&str]) {
    let name = format!("lab {from} -> {to}");
    refuse(
        &name,
        &edit(LAB, from, to),
        TABLE,
        &["run", "{dir}scene.toml"],
        want,
    );
}

fn table(text: &str, want: &[&str]) {
    refuse(
        &format!("table {text}"),
        LAB,
        text,
        &["run", "{dir}scene.toml"],
        want,
    );
}

#[test]
fn a_valid_scene_writes_its_trace() {
    // The control: the same sandbox and command succeed and replace the trace.
    for scene in [CM, LAB] {
        let sb = Sandbox::new(&format!("valid {}", &scene[..10]), scene, TABLE);
        let out = Command::new(BIN)
            .args([
                "run",
                &sb.path("scene.toml"),
                "--json",
                "--trace",
                &sb.path("existing.csv"),
            ])
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = std::fs::read_to_string(sb.path("existing.csv")).unwrap();
        assert!(text.starts_with("t (s),f (N)"));
        let names: Vec<String> = sb.snapshot().into_keys().collect();
        assert_eq!(names, ["existing.csv", "prof.csv", "scene.toml"]);
    }
}

#[test]
fn non_finite_numbers_anywhere() {
    cm(
        "mass = 0.17",
        "mass = nan",
        &["balls.mass", "NaN", "finite"],
    );
    cm(
        "radius = 0.028575",
        "radius = inf",
        &["balls.radius", "inf", "finite"],
    );
    cm(
        "alpha = 0.4",
        "alpha = nan",
        &["balls.alpha", "NaN", "finite"],
    );
    cm("mu = 0.06", "mu = -inf", &["contact.mu", "-inf", "finite"]);
    cm(
        "mu = 0.06",
        "mu = { model = \"speed-dependent\", a = 0.01, b = nan, c = 1.0 }",
        &["contact.mu.b", "NaN", "finite"],
    );
    cm(
        "restitution = 1.0",
        "restitution = nan",
        &["contact.restitution", "NaN", "finite"],
    );
    cm(
        "restitution = 1.0",
        "impulse = inf",
        &["contact.impulse", "inf", "finite"],
    );
    cm(
        "duration = 2.5e-4",
        "duration = nan",
        &["contact.profile.duration", "NaN", "finite"],
    );
    cm(
        "shape = \"half-sine\"",
        "shape = \"sine-power\"\nexponent = nan",
        &["contact.profile.exponent", "NaN", "finite"],
    );
    cm(
        "u = [0.5, 0.25, 0.0]",
        "u = [0.5, nan, 0.0]",
        &["incoming.cm.u[1]", "NaN", "finite"],
    );
    cm(
        "omega_a = [-17.5, 35.0, 0.0]",
        "omega_a = [-17.5, 35.0, inf]",
        &["incoming.cm.omega_a[2]", "inf"],
    );
    cm(
        "omega_b = [0.0, 0.0, 0.0]",
        "omega_b = [-inf, 0.0, 0.0]",
        &["incoming.cm.omega_b[0]", "-inf"],
    );
    cm(
        "rtol = 1e-10",
        "rtol = nan",
        &["solver.rtol", "NaN", "1e-15"],
    );
    cm(
        "rtol = 1e-10",
        "rtol = 1e-10\natol = inf",
        &["solver.atol", "inf"],
    );
    lab(
        "position = [-0.028575",
        "position = [nan",
        &["incoming.lab.a.position[0]", "NaN", "finite"],
    );
    lab(
        "velocity = [0.0, 0.0, 0.0]",
        "velocity = [0.0, inf, 0.0]",
        &["incoming.lab.b.velocity[1]", "inf"],
    );
    lab(
        "spin = [0.0, 0.0, 0.0] }\nb",
        "spin = [0.0, 0.0, nan] }\nb",
        &["incoming.lab.a.spin[2]", "NaN"],
    );
    lab(
        "up = [0.0, 0.0, 1.0]",
        "up = [0.0, nan, 1.0]",
        &["incoming.lab.up[1]", "NaN"],
    );
    // Finite but so large that the energy m v^2 overflows. The message names the balls and
    // the largest speed they allow, sqrt(f64::MAX / m) with the pair mass m: 0.17 kg gives
    // 1.3408e154 / 0.41231 = 3.2519e154 m/s; unequal balls of 0.17 and 0.16 kg, whose pair
    // mass is 2 (0.17 0.16 / 0.33) = 0.16485 kg, 3.3023e154 m/s.
    cm(
        "u = [0.5, 0.25, 0.0]",
        "u = [1e160, 0.25, 0.0]",
        &[
            "incoming",
            "1e160",
            "finite",
            "(m = 0.17 kg, r = 0.028575 m)",
            "to 3.3e154 m/s",
        ],
    );
    // So small that m v^2 underflows to zero: 1e-170 m/s squared is 1e-340, below the
    // smallest double, and the ball must not pass for one at rest. The lower end is where
    // m v^2 is the smallest normal double: sqrt(2.2251e-308 / 0.17) = 3.6178e-154 m/s.
    cm(
        "u = [0.5, 0.25, 0.0]\nomega_a = [-17.5, 35.0, 0.0]",
        "u = [1e-170, 0.0, 0.0]\nomega_a = [0.0, 0.0, 0.0]",
        &["incoming", "1e-170", "from 3.6e-154 to 3.3e154 m/s"],
    );
    let unequal = edit(
        CM,
        "[balls]\nmass = 0.17\nradius = 0.028575\nalpha = 0.4",
        "[balls.a]\nmass = 0.17\nradius = 0.028575\nalpha = 0.4\n\
         [balls.b]\nmass = 0.16\nradius = 0.028\nalpha = 0.4",
    );
    refuse(
        "unequal balls, u = 1e160",
        &edit(&unequal, "u = [0.5, 0.25, 0.0]", "u = [1e160, 0.25, 0.0]"),
        TABLE,
        &["run", "{dir}scene.toml"],
        &[
            "incoming",
            "1e160",
            "(m_A = 0.17 kg, r_A = 0.028575 m, m_B = 0.16 kg, r_B = 0.028 m)",
            "to 3.3e154 m/s",
        ],
    );
}

#[test]
fn parameters_out_of_range() {
    cm("mass = 0.17", "mass = 0.0", &["balls.mass = 0", "> 0 kg"]);
    cm(
        "mass = 0.17",
        "mass = -0.17",
        &["balls.mass = -0.17", "> 0 kg"],
    );
    cm(
        "radius = 0.028575",
        "radius = 0.0",
        &["balls.radius = 0", "> 0 m"],
    );
    cm(
        "radius = 0.028575",
        "radius = -1e-3",
        &["balls.radius = -0.001", "> 0 m"],
    );
    cm(
        "duration = 2.5e-4",
        "duration = 0.0",
        &["contact.profile.duration = 0", "> 0 s"],
    );
    cm(
        "duration = 2.5e-4",
        "duration = -2.5e-4",
        &["contact.profile.duration = -0.00025", "> 0 s"],
    );
    lab(
        "duration = 3e-4",
        "duration = -1.0",
        &["contact.profile.duration = -1", "> 0 s"],
    );
    for a in ["0.0", "-0.4", "0.7", "1.0"] {
        cm(
            "alpha = 0.4",
            &format!("alpha = {a}"),
            &["balls.alpha", "(0, 2/3]", "sphere cannot exceed"],
        );
    }
    cm(
        "mu = 0.06",
        "mu = -0.06",
        &["contact.mu = -0.06", "mu >= 0"],
    );
    cm(
        "mu = 0.06",
        "mu = { model = \"speed-dependent\", a = -0.01, b = 0.1, c = 1.0 }",
        &["contact.mu.a = -0.01", ">= 0"],
    );
    for e in ["-0.1", "1.5"] {
        cm(
            "restitution = 1.0",
            &format!("restitution = {e}"),
            &["contact.restitution", e, "[0, 1]"],
        );
    }
    cm(
        "restitution = 1.0",
        "restitution = 1.0\nimpulse = 0.1",
        &["contact.restitution", "contact.impulse = 0.1", "not both"],
    );
    // m U(0) = 0.085 N s, 2 m U(0) = 0.17 N s.
    for p in ["0.08", "0.2"] {
        cm(
            "restitution = 1.0",
            &format!("impulse = {p}"),
            &[
                "contact.impulse",
                p,
                "m U(0) = 0.085",
                "2 m U(0) = 0.17",
                "eq 56",
            ],
        );
    }
    cm(
        "restitution = 1.0",
        "impulse = 0.0",
        &["contact.impulse = 0", "> 0"],
    );
    // An explicit impulse for balls that separate.
    refuse(
        "impulse, separating",
        &edit(
            &edit(CM, "restitution = 1.0", "impulse = 0.1"),
            "u = [0.5",
            "u = [-0.5",
        ),
        TABLE,
        &["run", "{dir}scene.toml"],
        &["contact.impulse", "do not approach"],
    );
    lab(
        "position = [0.028575",
        "position = [0.03",
        &["incoming.lab.b.position", "must touch", "2r = 0.05715"],
    );
    lab(
        "up = [0.0, 0.0, 1.0]",
        "up = [0.0, 0.0, 0.0]",
        &["incoming.lab.up", "non-zero"],
    );
    cm(
        "shape = \"half-sine\"",
        "shape = \"sine-power\"\nexponent = -1.0",
        &["contact.profile.exponent", "(0, 64]"],
    );
    cm(
        "rtol = 1e-10",
        "rtol = 0.5",
        &["solver.rtol = 0.5", "[1e-15, 0.1]"],
    );
    cm(
        "rtol = 1e-10",
        "rtol = 1e-10\nsteps = 0",
        &["solver.steps = 0", "[1, 1e7]"],
    );
}

#[test]
fn unknown_keys_with_suggestions() {
    let cases = [
        ("name = \"cm\"", "nmae = \"cm\"", "nmae", "name"),
        ("mass = 0.17", "mas = 0.17", "balls.mas", "mass"),
        (
            "restitution = 1.0",
            "restitutoin = 1.0",
            "contact.restitutoin",
            "restitution",
        ),
        (
            "duration = 2.5e-4",
            "duraton = 2.5e-4",
            "contact.profile.duraton",
            "duration",
        ),
        ("omega_a =", "omega_aa =", "incoming.cm.omega_aa", "omega_a"),
        (
            "method = \"dop853\"",
            "mehtod = \"dop853\"",
            "solver.mehtod",
            "method",
        ),
        (
            "friction = true",
            "frction = true",
            "effects.frction",
            "friction",
        ),
        ("[solver]", "[solvr]", "solvr", "solver"),
        (
            "shape = \"half-sine\"",
            "shape = \"half-sin\"",
            "half-sin",
            "half-sine",
        ),
        (
            "mu = 0.06",
            "mu = { model = \"speed-dependent\", a = 0.01, bb = 0.1, c = 1.0 }",
            "contact.mu.bb",
            "b",
        ),
    ];
    for (from, to, field, hint) in cases {
        cm(from, to, &[field, &format!("did you mean `{hint}`")]);
    }
    lab(
        "velocity = [1.9696",
        "velocty = [1.9696",
        &["incoming.lab.a.velocty", "did you mean `velocity`"],
    );
    lab(
        "up = [",
        "upp = [",
        &["incoming.lab.upp", "did you mean `up`"],
    );
    lab(
        "file = \"prof.csv\"",
        "fiel = \"prof.csv\"",
        &["contact.profile.fiel", "did you mean `file`"],
    );
    // No close match: the accepted keys are listed.
    cm(
        "mass = 0.17",
        "mass = 0.17\ncolour = \"red\"",
        &[
            "balls.colour",
            "unknown key",
            "`mass`",
            "`radius`",
            "`alpha`",
        ],
    );
    cm(
        "method = \"dop853\"",
        "method = \"euler\"",
        &[
            "solver.method",
            "\"euler\"",
            "closed-form, rk4, dopri5, dop853",
        ],
    );
}

#[test]
fn wrong_types_and_missing_sections() {
    cm(
        "mass = 0.17",
        "mass = \"heavy\"",
        // `mass = "heavy"` on line 3: the value starts at its 8th character.
        &[
            "line 3, column 8",
            "balls.mass",
            "\"heavy\"",
            "expected a number",
        ],
    );
    cm(
        "u = [0.5, 0.25, 0.0]",
        "u = \"fast\"",
        &["incoming.cm.u", "\"fast\""],
    );
    cm(
        "u = [0.5, 0.25, 0.0]",
        "u = [0.5, 0.25]",
        &["incoming.cm.u", "length 2", "length 3"],
    );
    cm(
        "rtol = 1e-10",
        "rtol = 1e-10\nsteps = 1.5",
        &["solver.steps", "1.5"],
    );
    cm(
        "friction = true",
        "friction = \"yes\"",
        &["effects.friction", "\"yes\""],
    );
    cm("method = \"dop853\"", "method = 3", &["solver.method", "3"]);
    cm(
        "mu = 0.06",
        "mu = \"high\"",
        &["contact.mu", "\"high\"", "a number >= 0"],
    );
    cm("mu = 0.06", "mu = [0.06]", &["contact.mu", "a number >= 0"]);
    cm("name = \"cm\"", "name = 3", &["name", "3"]);
    cm("mass = 0.17", "mass = ", &["line 3"]);
    // Missing sections and fields.
    let without = |section: &str| -> String {
        let mut out = String::new();
        let mut skip = false;
        for line in CM.lines() {
            if line.starts_with('[') {
                skip = line == section;
            }
            if !skip {
                out.push_str(line);
                out.push('\n');
            }
        }
        out
    };
    for (section, want) in [
        ("[balls]", "missing section [balls]"),
        ("[contact]", "contact.mu"),
        (
            "[contact.profile]",
            "contact.profile = missing: a section [contact.profile]",
        ),
        ("[incoming.cm]", "[incoming.cm]"),
    ] {
        refuse(
            section,
            &without(section),
            TABLE,
            &["run", "{dir}scene.toml"],
            &[want],
        );
    }
    let no_incoming = without("[incoming.cm]").replace("[solver]", "[incoming]\n[solver]");
    refuse(
        "empty incoming",
        &no_incoming,
        TABLE,
        &["run", "{dir}scene.toml"],
        &["incoming", "[incoming.cm]", "[incoming.lab]"],
    );
    cm("mass = 0.17\n", "", &["balls.mass", "missing"]);
    cm("u = [0.5, 0.25, 0.0]\n", "", &["incoming.cm.u", "missing"]);
    cm("shape = \"half-sine\"\n", "", &["contact.profile", "shape"]);
    lab(
        "up = [0.0, 0.0, 1.0]",
        "[incoming.cm]\nu = [1.0, 0.0, 0.0]",
        &["incoming", "both", "exactly one"],
    );
}

#[test]
fn bad_profile_tables_name_the_line() {
    table(
        "time,force\n0,0\n1e-4,900\n1e-4,1000\n3e-4,0\n",
        &[
            "prof.csv:4:",
            "0.0001 s after 0.0001 s",
            "strictly increasing",
        ],
    );
    table(
        "time,force\n0,0\n2e-4,900\n1e-4,1000\n",
        &["prof.csv:4:", "strictly increasing"],
    );
    table(
        "time,force\n0,0\n1e-4,-900\n3e-4,0\n",
        &["prof.csv:3:", "-900", "negative", ">= 0"],
    );
    table(
        "time,force\n0,0\n1e-4,nan\n3e-4,0\n",
        &["prof.csv:3:", "NaN", "not finite"],
    );
    table(
        "time,force\n0,0\ninf,1\n",
        &["prof.csv:3:", "inf", "not finite"],
    );
    table("time,force\n0,5\n", &["prof.csv", "at least two"]);
    table("time,force\n", &["prof.csv", "at least two"]);
    table("", &["prof.csv", "empty", "time,force"]);
    table(
        "time,force\n0,0\n1e-4,9o0\n3e-4,0\n",
        &["prof.csv:3:", "9o0", "not a number"],
    );
    table(
        "time,force\n0,0\n1e-4;900\n3e-4,0\n",
        &["prof.csv:3:", "two cells"],
    );
    table(
        "time,force\n0,0\n1e-4,900,1\n",
        &["prof.csv:3:", "two cells"],
    );
    table("t,f\n0,0\n1,1\n", &["prof.csv:1:", "header", "time,force"]);
    table(
        "time,force\n1e-5,0\n1e-4,900\n",
        &["prof.csv:2:", "start at time 0"],
    );
    table(
        "time,force\n0,0\n1e-4,0\n",
        &["prof.csv", "positive impulse"],
    );
    // A table file that cannot be read.
    lab(
        "file = \"prof.csv\"",
        "file = \"missing.csv\"",
        &["missing.csv", "cannot read the profile table"],
    );
}

#[test]
fn unreadable_scenes_and_unwritable_outputs() {
    let sb = Sandbox::new("files", CM, TABLE);
    std::fs::write(sb.path("latin1.toml"), b"name = \"caf\xe9\"\n").unwrap();
    std::fs::create_dir(sb.path("subdir")).unwrap();
    let cases: Vec<(Vec<String>, Vec<&str>)> = vec![
        (
            vec![sb.path("nope.toml")],
            vec!["nope.toml", "cannot read the scene file", "No such file"],
        ),
        (
            vec![sb.path("subdir")],
            vec!["subdir", "cannot read the scene file"],
        ),
        (vec![sb.path("latin1.toml")], vec!["latin1.toml", "UTF-8"]),
        (
            vec![
                sb.path("scene.toml"),
                "--trace".into(),
                sb.path("no/such/dir/t.csv"),
            ],
            vec!["t.csv", "cannot write an output file here", "No such file"],
        ),
        (
            vec![sb.path("scene.toml"), "--trace".into(), sb.path("subdir")],
            vec!["subdir", "is a directory", "file name"],
        ),
        (
            vec![
                sb.path("scene.toml"),
                "--trace".into(),
                sb.path("scene.toml/t.csv"),
            ],
            vec!["scene.toml/t.csv", "cannot write an output file here"],
        ),
        (
            vec![sb.path("scene.toml"), "--method".into(), "euler".into()],
            vec!["\"euler\"", "closed-form, rk4, dopri5, dop853"],
        ),
        (
            vec![sb.path("scene.toml"), "--rtol".into(), "abc".into()],
            vec!["--rtol", "abc"],
        ),
        (
            vec![sb.path("scene.toml"), "--rtol".into(), "NaN".into()],
            vec!["solver.rtol", "NaN"],
        ),
        (
            vec![sb.path("scene.toml"), "--samples".into(), "0".into()],
            vec!["--samples", "at least 1"],
        ),
        (
            vec![sb.path("scene.toml"), "--samples".into(), "-5".into()],
            vec!["--samples"],
        ),
        (
            vec![sb.path("scene.toml"), "--tarce".into(), "x.csv".into()],
            vec!["--tarce"],
        ),
    ];
    for (args, want) in cases {
        let before = sb.snapshot();
        let mut argv = vec!["run".to_string()];
        argv.extend(args.iter().cloned());
        let out = Command::new(BIN)
            .args(&argv)
            .current_dir(&sb.dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{argv:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{argv:?}");
        let lines: Vec<&str> = stderr.lines().collect();
        assert_eq!(lines.len(), 1, "{argv:?}: not one line:\n{stderr}");
        assert!(lines[0].starts_with("error: "), "{stderr}");
        for w in want {
            assert!(
                lines[0].contains(w),
                "{argv:?}: `{w}` missing in {}",
                lines[0]
            );
        }
        assert_eq!(sb.snapshot(), before, "{argv:?}: files changed");
    }
}
