//! Cushion impacts for a grid of states (scripts/compare_mathavan.py): reads CSV rows on
//! stdin, `m,r,h,mu_cushion,mu_table,e,vx,vy,wx,wy,wz` (SI units, the cushion's frame,
//! v_z = 0; a header line is skipped), and prints for each
//! `vx,vy,vz,wx,wy,wz,impulse_cushion,lifts_off,events` with dop853 at rtol = atol = 1e-12
//! and Stronge's rule (events as contact:kind separated by spaces; an impact that fails
//! prints `error` and the message). `cargo run --release --example cushion_grid < grid.csv`.

use billiard_contact::nalgebra::Vector3;
use billiard_contact::{resolve_cushion, Ball, Cushion, CushionRestitution, SolverSettings};
use std::io::BufRead;

fn main() {
    let settings = SolverSettings::default()
        .with_rtol(1e-12)
        .and_then(|s| s.with_atol(1e-12))
        .expect("valid tolerances");
    println!("vx,vy,vz,wx,wy,wz,impulse_cushion,lifts_off,events");
    for line in std::io::stdin().lock().lines() {
        let line = line.expect("stdin");
        let x: Result<Vec<f64>, _> = line.split(',').map(|f| f.trim().parse::<f64>()).collect();
        let Ok(x) = x else { continue }; // the header
        if x.len() != 11 {
            println!("error,expected 11 columns");
            continue;
        }
        let run = || {
            let ball = Ball::new(x[0], x[1], 0.4)?;
            let cushion = Cushion::new(x[2], x[3], x[4], x[5], CushionRestitution::Stronge)?;
            let v = Vector3::new(x[6], x[7], 0.0);
            let w = Vector3::new(x[8], x[9], x[10]);
            resolve_cushion(&ball, &cushion, v, w, &settings, None)
        };
        match run() {
            Ok(o) => {
                let events: Vec<String> = o
                    .events
                    .iter()
                    .map(|e| format!("{:?}:{:?}", e.contact, e.kind))
                    .collect();
                println!(
                    "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{}",
                    o.v.x,
                    o.v.y,
                    o.v.z,
                    o.w.x,
                    o.w.y,
                    o.w.z,
                    o.impulse_cushion,
                    o.lifts_off,
                    events.join(" ")
                );
            }
            Err(e) => println!("error,{}", e.to_string().replace(',', ";")),
        }
    }
}
