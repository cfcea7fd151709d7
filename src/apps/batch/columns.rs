//! The batch CSV's columns: the input header read into column positions (either frame,
//! the overrides, did-you-mean for the rest), and one output row formatted.

use crate::apps::batch::engine::{BatchInput, BatchOutput, Overrides};
use crate::base::method::Method;
use crate::base::names::did_you_mean;
use crate::base::number::Shortest;
use crate::base::validate::finite_output;
use crate::model::frame::LabScene;
use crate::model::state::{CmState, LabBall};
use crate::scene::types::Incoming;
use nalgebra::Vector3;

/// Positions of the input columns.
#[derive(Debug, Clone)]
pub(super) struct Columns {
    pub(super) id: Option<usize>,
    state: StateColumns,
    overrides: [Option<usize>; 7],
}

/// The incoming state's columns: one frame or the other.
#[derive(Debug, Clone)]
pub(super) enum StateColumns {
    Cm(CmColumns),
    Lab(Box<LabColumns>),
}

#[derive(Debug, Clone)]
pub(super) struct CmColumns {
    u: [usize; 3],
    omega_a: [Option<usize>; 3],
    omega_b: [Option<usize>; 3],
}

#[derive(Debug, Clone)]
pub(super) struct LabColumns {
    a: [[Option<usize>; 3]; 3],
    b: [[Option<usize>; 3]; 3],
    up: [Option<usize>; 3],
}

const OVERRIDES: [&str; 7] = [
    "mass",
    "radius",
    "alpha",
    "mu",
    "restitution",
    "impulse",
    "duration",
];

/// The header cell without a trailing `(unit)`.
pub(super) fn bare(cell: &str) -> &str {
    let c = cell.trim().trim_start_matches('\u{feff}');
    match c.find('(') {
        Some(i) if c.ends_with(')') => c[..i].trim_end(),
        _ => c,
    }
}

/// `text` (a header or cell of the input) as an error shows it: control characters (a
/// newline inside a quoted cell) escaped, so the message stays one line.
fn shown(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Prefixes of the x, y, z columns of the centre-of-mass frame's state.
const CM_PREFIXES: [&str; 3] = ["u_", "omega_a_", "omega_b_"];

/// Prefixes of the x, y, z columns of the lab frame's state.
const LAB_PREFIXES: [&str; 7] = ["a_p", "a_v", "a_w", "b_p", "b_v", "b_w", "up_"];

/// The input columns accepted with the state columns of `prefixes`: `id`, the state's x, y
/// and z columns, the overrides.
pub(super) fn accepted_columns(prefixes: &[&str]) -> Vec<String> {
    let mut names = vec!["id".to_string()];
    for p in prefixes {
        names.extend(["x", "y", "z"].map(|axis| format!("{p}{axis}")));
    }
    names.extend(OVERRIDES.map(String::from));
    names
}

/// Every header cell names an input column (`id`, a state column of either frame, an
/// override), once: an unknown column is refused with the accepted names and the closest
/// one, as a scene file's unknown key is.
pub(super) fn check_names(names: &[&str]) -> Result<(), String> {
    let all = accepted_columns(&[&CM_PREFIXES[..], &LAB_PREFIXES[..]].concat());
    let all: Vec<&str> = all.iter().map(String::as_str).collect();
    let mut seen = std::collections::HashSet::new();
    for (k, n) in names.iter().enumerate() {
        if n.is_empty() {
            return Err(format!(
                "column {} has no name: every column needs one (see docs/formats.md#input-columns)",
                k + 1
            ));
        }
        if !all.contains(n) {
            return Err(format!(
                "column `{}`: unknown column, expected one of {}{}",
                shown(n),
                all.iter()
                    .map(|a| format!("`{a}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                did_you_mean(n, &all)
            ));
        }
        if !seen.insert(*n) {
            return Err(format!("column `{}` appears twice", shown(n)));
        }
    }
    Ok(())
}

/// Every state column belongs to the input's frame (`prefixes`, named `frame`): a column of
/// the other frame would be ignored.
pub(super) fn check_frame(names: &[&str], prefixes: &[&str], frame: &str) -> Result<(), String> {
    let own = accepted_columns(prefixes);
    match names.iter().find(|n| !own.iter().any(|o| o == *n)) {
        Some(n) => Err(format!(
            "column `{}` belongs to the other frame; this input is in the {frame} frame: give \
             the columns of one frame",
            shown(n)
        )),
        None => Ok(()),
    }
}

impl Columns {
    pub(super) fn from_header(header: &csv::StringRecord) -> Result<Self, String> {
        let names: Vec<&str> = header.iter().map(bare).collect();
        check_names(&names)?;
        let find = |n: &str| names.iter().position(|h| *h == n);
        let xyz = |prefix: &str| {
            [
                find(&format!("{prefix}x")),
                find(&format!("{prefix}y")),
                find(&format!("{prefix}z")),
            ]
        };
        let u = xyz("u_");
        let any_cm = u.iter().any(Option::is_some);
        let lab_names = ["a_p", "a_v", "b_p", "b_v"];
        let any_lab = lab_names.iter().any(|p| xyz(p).iter().any(Option::is_some));
        let state = match (any_cm, any_lab) {
            (true, true) => {
                return Err("both centre-of-mass (u_x, ...) and lab (a_px, ...) columns: give one frame".into())
            }
            (false, false) => {
                return Err("no state columns: give u_x, u_y, u_z (centre-of-mass frame) or a_px .. b_vz (lab frame)".into())
            }
            (true, false) => {
                check_frame(&names, &CM_PREFIXES, "centre-of-mass")?;
                let mut req = [0; 3];
                for (k, c) in u.iter().enumerate() {
                    req[k] = c.ok_or_else(|| format!("missing column `u_{}`", ["x", "y", "z"][k]))?;
                }
                StateColumns::Cm(CmColumns {
                    u: req,
                    omega_a: xyz("omega_a_"),
                    omega_b: xyz("omega_b_"),
                })
            }
            (false, true) => {
                check_frame(&names, &LAB_PREFIXES, "lab")?;
                for p in lab_names {
                    for (k, c) in xyz(p).iter().enumerate() {
                        if c.is_none() {
                            return Err(format!("missing column `{p}{}`", ["x", "y", "z"][k]));
                        }
                    }
                }
                StateColumns::Lab(Box::new(LabColumns {
                    a: [xyz("a_p"), xyz("a_v"), xyz("a_w")],
                    b: [xyz("b_p"), xyz("b_v"), xyz("b_w")],
                    up: xyz("up_"),
                }))
            }
        };
        let mut overrides = [None; 7];
        for (slot, n) in overrides.iter_mut().zip(OVERRIDES) {
            *slot = find(n);
        }
        Ok(Columns {
            id: find("id"),
            state,
            overrides,
        })
    }

    pub(super) fn parse(&self, rec: &csv::StringRecord) -> Result<BatchInput, String> {
        let num = |i: Option<usize>, name: &dyn Fn() -> String| -> Result<Option<f64>, String> {
            let Some(i) = i else { return Ok(None) };
            let cell = rec.get(i).unwrap_or("").trim();
            if cell.is_empty() {
                return Ok(None);
            }
            let v: f64 = cell
                .parse()
                .map_err(|_| format!("{} = `{}` is not a number", name(), shown(cell)))?;
            if !v.is_finite() {
                return Err(format!("{} = {cell}: expected a finite number", name()));
            }
            Ok(Some(v))
        };
        let vec3 = |cols: [Option<usize>; 3],
                    prefix: &str,
                    default: Option<[f64; 3]>|
         -> Result<Vector3<f64>, String> {
            let mut v = [0.0; 3];
            for k in 0..3 {
                let axis = ["x", "y", "z"][k];
                v[k] = match (num(cols[k], &|| format!("{prefix}{axis}"))?, default) {
                    (Some(x), _) => x,
                    (None, Some(d)) => d[k],
                    (None, None) => return Err(format!("{prefix}{axis} is empty")),
                };
            }
            Ok(Vector3::from(v))
        };
        let incoming = match &self.state {
            StateColumns::Cm(cm) => Incoming::Cm(CmState::new(
                vec3(cm.u.map(Some), "u_", None)?,
                vec3(cm.omega_a, "omega_a_", Some([0.0; 3]))?,
                vec3(cm.omega_b, "omega_b_", Some([0.0; 3]))?,
            )),
            StateColumns::Lab(lab) => {
                let ball = |c: &[[Option<usize>; 3]; 3], n: &str| -> Result<LabBall, String> {
                    Ok(LabBall {
                        position: vec3(c[0], &format!("{n}_p"), None)?,
                        velocity: vec3(c[1], &format!("{n}_v"), None)?,
                        spin: vec3(c[2], &format!("{n}_w"), Some([0.0; 3]))?,
                    })
                };
                Incoming::Lab(LabScene {
                    a: ball(&lab.a, "a")?,
                    b: ball(&lab.b, "b")?,
                    up: vec3(lab.up, "up_", Some([0.0, 0.0, 1.0]))?,
                })
            }
        };
        let mut o = [None; 7];
        for (k, slot) in o.iter_mut().enumerate() {
            *slot = num(self.overrides[k], &|| OVERRIDES[k].to_string())?;
        }
        Ok(BatchInput {
            incoming,
            overrides: Overrides {
                mass: o[0],
                radius: o[1],
                alpha: o[2],
                mu: o[3],
                restitution: o[4],
                impulse: o[5],
                duration: o[6],
            },
        })
    }

    /// The output header for this input and method.
    pub(super) fn output_header(&self, method: Method) -> Vec<&'static str> {
        let mut h = vec!["line"];
        if self.id.is_some() {
            h.push("id");
        }
        h.extend(OUTPUT_COLUMNS);
        if matches!(self.state, StateColumns::Lab(_)) {
            h.extend(LAB_OUTPUT_COLUMNS);
        }
        if method != Method::ClosedForm {
            h.extend(["closed_form_error", "rhs_evaluations"]);
        }
        h
    }
}

/// Output columns after `line` and `id`, for every input.
pub const OUTPUT_COLUMNS: [&str; 20] = [
    "collision",
    "impulse",
    "s0",
    "theta",
    "sticks",
    "stick_time",
    "stick_impulse",
    "tangential_impulse",
    "s_out",
    "heat",
    "heat_sliding",
    "u_x",
    "u_y",
    "u_z",
    "omega_a_x",
    "omega_a_y",
    "omega_a_z",
    "omega_b_x",
    "omega_b_y",
    "omega_b_z",
];

/// Output columns for lab-frame input.
pub const LAB_OUTPUT_COLUMNS: [&str; 13] = [
    "a_vx",
    "a_vy",
    "a_vz",
    "a_wx",
    "a_wy",
    "a_wz",
    "b_vx",
    "b_vy",
    "b_vz",
    "b_wx",
    "b_wy",
    "b_wz",
    "throw_angle_deg",
];

/// Formats one output row (with its newline) into `line_out`; every float must be finite.
/// Rows are formatted by the workers, so the single writer only copies bytes.
pub(super) fn format_row(
    line: u64,
    id: Option<&str>,
    o: &BatchOutput,
    method: Method,
    line_out: &mut String,
) -> Result<(), String> {
    use std::fmt::Write as _;
    fn num(s: &mut String, name: &str, v: f64) -> Result<(), String> {
        let v = finite_output(v, || name.to_string()).map_err(|e| e.to_string())?;
        let _ = write!(s, ",{}", Shortest(v));
        Ok(())
    }
    fn opt(s: &mut String, name: &str, v: Option<f64>) -> Result<(), String> {
        match v {
            Some(x) => num(s, name, x),
            None => {
                s.push(',');
                Ok(())
            }
        }
    }
    let s = line_out;
    s.clear();
    let _ = write!(s, "{line}");
    if let Some(id) = id {
        s.push(',');
        if id.contains([',', '"', '\n', '\r']) {
            s.push('"');
            s.push_str(&id.replace('"', "\"\""));
            s.push('"');
        } else {
            s.push_str(id);
        }
    }
    let r = &o.result;
    let _ = write!(s, ",{}", r.collided());
    num(s, "impulse", r.impulse)?;
    num(s, "s0", r.s0)?;
    opt(s, "theta", r.theta)?;
    let _ = write!(s, ",{}", r.sticks);
    opt(s, "stick_time", o.stick_time)?;
    opt(s, "stick_impulse", r.stick_impulse)?;
    let st = &r.out;
    let scalars = [
        r.tangential_impulse,
        r.s_out,
        r.heat,
        r.heat_sliding,
        st.u_cm.x,
        st.u_cm.y,
        st.u_cm.z,
        st.omega_a.x,
        st.omega_a.y,
        st.omega_a.z,
        st.omega_b.x,
        st.omega_b.y,
        st.omega_b.z,
    ];
    for (name, v) in OUTPUT_COLUMNS[7..].iter().zip(scalars) {
        num(s, name, v)?;
    }
    if let Some((a, b, throw)) = &o.lab {
        let v = [a.velocity, a.spin, b.velocity, b.spin];
        for (name, x) in LAB_OUTPUT_COLUMNS
            .iter()
            .zip(v.iter().flat_map(|v| v.iter()))
        {
            num(s, name, *x)?;
        }
        opt(s, "throw_angle_deg", *throw)?;
    }
    if method != Method::ClosedForm {
        num(s, "closed_form_error", o.closed_form_error)?;
        let _ = write!(s, ",{}", o.rhs_evaluations);
    }
    s.push('\n');
    Ok(())
}
