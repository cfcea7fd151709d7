//! The JSON contract of the command's report (docs/formats.md), walked and checked without
//! the crate's report code: the keys, their types, where null may appear, finite numbers.

use nalgebra::Vector3;
use serde_json::Value;

/// A JSON array of three numbers.
pub fn vector3(v: &Value) -> Vector3<f64> {
    let a = v.as_array().expect("array");
    assert_eq!(a.len(), 3);
    Vector3::new(
        a[0].as_f64().unwrap(),
        a[1].as_f64().unwrap(),
        a[2].as_f64().unwrap(),
    )
}

/// The number `v[key]` (a panic naming the key otherwise).
pub fn number(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number: {v}"))
}

/// Fields that may be null (docs/formats.md): nothing else.
pub const NULLABLE: [&str; 4] = ["theta", "stick_time", "stick_impulse", "throw_angle_deg"];

/// Walks the report: no null outside the nullable fields, every number finite.
fn walk(v: &Value, path: &str, nulls: &mut Vec<String>) {
    match v {
        Value::Null => nulls.push(path.to_string()),
        Value::Number(n) => {
            if let Some(x) = n.as_f64() {
                assert!(x.is_finite(), "{path} = {x}");
            }
        }
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, x)| walk(x, &format!("{path}[{i}]"), nulls)),
        Value::Object(o) => o.iter().for_each(|(k, x)| {
            let p = if path.is_empty() {
                k.clone()
            } else {
                format!("{path}.{k}")
            };
            walk(x, &p, nulls)
        }),
        _ => {}
    }
}

/// The `run --json` report's contract (docs/formats.md): every key there, the state arrays
/// (and `lab_out` for a lab scene), the checks >= 0, the solver's method and step counts,
/// booleans and strings where promised, no null outside [`NULLABLE`], every number finite.
pub fn check_contract(j: &Value, lab: bool, method: &str, what: &str) {
    for key in [
        "collision",
        "impulse",
        "s0",
        "theta",
        "s_out",
        "sticks",
        "stick_time",
        "stick_impulse",
        "tangential_impulse",
        "heat",
        "heat_sliding",
        "cm_out",
        "throw_angle_deg",
        "check",
        "solver",
        "effects",
        "warnings",
    ] {
        assert!(j.get(key).is_some(), "{what}: key {key} missing");
    }
    for key in ["u", "omega_a", "omega_b"] {
        vector3(&j["cm_out"][key]);
    }
    if lab {
        for ball in ["a", "b"] {
            for key in ["velocity", "spin"] {
                vector3(&j["lab_out"][ball][key]);
            }
        }
    }
    for key in [
        "theta_drift",
        "closed_form_error",
        "momentum_error",
        "angular_momentum_error",
        "energy_balance_error",
    ] {
        let x = number(&j["check"], key);
        assert!(x >= 0.0, "{what}: check.{key} = {x}");
    }
    assert_eq!(j["solver"]["method"], method, "{what}");
    for key in ["rhs_evaluations", "accepted_steps", "rejected_steps"] {
        assert!(j["solver"][key].is_u64(), "{what}: solver.{key}");
    }
    // Every step tried, accepted or rejected, evaluates the equations at least once.
    let count = |key: &str| u128::from(j["solver"][key].as_u64().unwrap());
    assert!(
        count("accepted_steps") + count("rejected_steps") <= count("rhs_evaluations"),
        "{what}: {}",
        j["solver"]
    );
    assert!(j["collision"].is_boolean() && j["sticks"].is_boolean());
    assert!(j["effects"]
        .as_array()
        .unwrap()
        .iter()
        .all(Value::is_string));
    assert!(j["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .all(Value::is_string));
    let mut nulls = Vec::new();
    walk(j, "", &mut nulls);
    for n in nulls {
        assert!(NULLABLE.contains(&n.as_str()), "{what}: {n} is null");
    }
}
