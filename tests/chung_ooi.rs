//! Chung and Ooi's particle-impact benchmark (Granular Matter 13 (2011) 643-656) as data:
//! every row of data/chung_ooi/benchmark.csv is one quantity of one case, with its reference
//! value, its tolerance and the formula the value comes from (data/chung_ooi/README.md):
//! Hertz's impact (tests 1 and 2) and the rigid body's gross sliding, which the compliant
//! contact must reproduce exactly once the spring slides from first touch to the end
//! (tests 4 to 8). The references were computed from those formulas, not by this crate.

use crate::common::compliant::{sphere, tight};
use billiard_contact::nalgebra::Vector3;
use billiard_contact::*;

const CSV: &str = include_str!("../data/chung_ooi/benchmark.csv");

/// What the kernel gives for each quantity the file names, for one case.
type Measured = Box<dyn Fn(&str) -> f64>;

/// One case: what the kernel gives for each quantity the file names.
fn measure(f: &[&str], num: &dyn Fn(usize) -> f64) -> Measured {
    let (mu, v_n, v_t, w1, w2) = (num(11), num(12), num(13), num(14), num(15));
    let ball = sphere(num(5), num(6));
    let mat = Material::new(num(3), num(4)).unwrap();
    if f[2] == "plane" {
        // The plane y = 0; the slip u = v_t + R w1 along +x.
        let v = Vector3::new(v_t, -v_n, 0.0);
        let w = Vector3::new(0.0, 0.0, w1);
        let o = resolve_sphere_plane_compliant(&ball, mat, None, mu, v, w, Vector3::y(), &tight())
            .unwrap();
        Box::new(move |q| match q {
            "max_overlap" => o.max_compression,
            "max_force" => o.max_normal_force,
            "contact_time" => o.contact_time,
            "vn_out" => o.velocity.y,
            "vt_out" => o.velocity.x,
            "w_out" => o.spin.z,
            "tangential_restitution" => o.velocity.x / v_t,
            "rebound_angle_deg" => o.velocity.x.atan2(o.velocity.y).to_degrees(),
            other => panic!("unknown quantity {other}"),
        })
    } else {
        // n = +x from A to B; A at (v_n, v_t, 0), B at (-v_n, 0, 0): the slip of A over B
        // is (v_t + R_A w1 + R_B w2) along +y.
        let b = CompliantSphere {
            ball: sphere(num(9), num(10)),
            material: Material::new(num(7), num(8)).unwrap(),
            velocity: Vector3::new(-v_n, 0.0, 0.0),
            spin: Vector3::new(0.0, 0.0, w2),
        };
        let a = CompliantSphere {
            ball,
            material: mat,
            velocity: Vector3::new(v_n, v_t, 0.0),
            spin: Vector3::new(0.0, 0.0, w1),
        };
        let o = resolve_sphere_sphere_compliant(&a, &b, Vector3::x(), mu, 1.0, &tight()).unwrap();
        Box::new(move |q| match q {
            "max_overlap" => o.ball_a.max_compression,
            "max_force" => o.ball_a.max_normal_force,
            "contact_time" => o.ball_a.contact_time,
            "vn_a_out" => o.ball_a.velocity.x,
            "vt_a_out" => o.ball_a.velocity.y,
            "vt_b_out" => o.velocity_b.y,
            "w_a_out" => o.ball_a.spin.z,
            "w_b_out" => o.spin_b.z,
            other => panic!("unknown quantity {other}"),
        })
    }
}

/// Every row of the benchmark file within its tolerance (1e-6 of the case's speed scale:
/// the kernel runs at rtol = atol = 1e-11, and the gross-sliding and Hertz references are
/// exact, so the margin covers the stepping's error and the events' location). Prints the
/// table (ours, reference, difference) with `--nocapture`.
#[test]
fn chung_ooi_benchmark_rows() {
    let mut lines = CSV.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("test,case,partner"), "{header}");
    let mut seen = std::collections::BTreeSet::new();
    let mut case: Option<(String, Measured)> = None;
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 20, "{line}");
        let num = |i: usize| f[i].parse::<f64>().unwrap_or_else(|_| panic!("{line}"));
        let key = format!("{} {}", f[0], f[1]);
        if case.as_ref().map(|c| &c.0) != Some(&key) {
            case = Some((key.clone(), measure(&f, &num)));
        }
        let ours = (case.as_ref().unwrap().1)(f[16]);
        let (reference, tol) = (num(17), num(18));
        println!(
            "test {} {:20} {:24} ours {:>16.10} ref {:>16.10} diff {:9.2e} tol {:8.1e}",
            f[0],
            f[1],
            f[16],
            ours,
            reference,
            ours - reference,
            tol
        );
        assert!((ours - reference).abs() <= tol, "{line}: ours {ours}");
        seen.insert(f[0].to_string());
    }
    let tests: Vec<&str> = seen.iter().map(|s| s.as_str()).collect();
    // Test 3 (restitution) is chung_ooi_test_3_restitution below.
    assert_eq!(tests, ["1", "2", "4", "5", "6", "7", "8"]);
}

/// Test 3: a sphere's normal impact on a rigid plane at 3.9 m/s with restitution 0.2, 0.4,
/// 0.6, 0.8 and 1.0, for aluminium oxide (E = 380 GPa, nu = 0.23, 4000 kg/m3) and cast iron
/// (100 GPa, 0.25, 7000 kg/m3), R = 2.5 mm, no friction (the parameters of Yade's Test3.py
/// for this benchmark, data/chung_ooi/README.md). The expected rebound is the benchmark's
/// own: -v_n'/v_n = e. The damping (Hunt-Crossley and Kuwabara-Kono) is calibrated by the
/// contact-law module's head-on integration (`ContactLaw::calibrated`), a different
/// integrator from the compliant kernel's, so the two must agree: to 1e-6 of v_n (the
/// calibration's and the kernel's tolerances are 1e-10 and 1e-11). Energy: the kinetic
/// energy after is e^2 that before.
#[test]
fn chung_ooi_test_3_restitution() {
    let v_n = 3.9;
    for (name, e_mod, nu, rho) in [
        ("aluminium oxide", 3.8e11, 0.23, 4000.0),
        ("cast iron", 1.0e11, 0.25, 7000.0),
    ] {
        let ball = sphere(rho, 0.0025);
        let mat = Material::new(e_mod, nu).unwrap();
        let k = HertzContact::sphere_plane(&ball, &mat, None, v_n)
            .unwrap()
            .stiffness;
        for damping in [Damping::HuntCrossley, Damping::KuwabaraKono] {
            for e in [0.2, 0.4, 0.6, 0.8, 1.0] {
                let law = ContactLaw::calibrated(k, damping, e, v_n, ball.mass()).unwrap();
                let o = resolve_sphere_plane_compliant_damped(
                    &ball,
                    mat,
                    None,
                    (law.damping(), law.coefficient()),
                    0.0,
                    Vector3::new(0.0, -v_n, 0.0),
                    Vector3::zeros(),
                    Vector3::y(),
                    &tight(),
                )
                .unwrap();
                let ratio = o.velocity.y / v_n;
                println!("test 3 {name} {damping:?} e = {e}: rebound {ratio:.9}");
                assert!(
                    (ratio - e).abs() < 1e-6,
                    "{name} {damping:?} e = {e}: {ratio}"
                );
                let ke = o.kinetic_energy_out / o.kinetic_energy_in;
                assert!((ke - e * e).abs() < 2e-6, "{name} {damping:?} {e}: {ke}");
            }
        }
    }
}
