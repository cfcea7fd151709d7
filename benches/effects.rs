//! What each effect costs: the contact (`solve` on a prepared collision) with effects
//! switched on one at a time, with rk4 (1000 fixed steps: the cost per right-hand-side
//! evaluation), dop853 (the default, rtol 1e-10: step count included) and the closed form;
//! then the table phase alone and a whole `run_scene` with the table off and on.
//!
//! Scenes: `default.toml` (rolling cue ball, 30 degree cut: slides throughout) and
//! `stun_cut_sticks.toml` (10 degree stun cut: sliding stops during contact, so `stick`
//! adds the event location). `cargo bench --bench effects`; docs/effects.md quotes the numbers.

use billiard_contact::run_scene;
use billiard_contact::table_phase::TableOutcome;
use billiard_contact::Effects;
use billiard_contact::Scene;
use billiard_contact::{solve, Friction};
use billiard_contact::{Method, SolverSettings};
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::path::Path;
use std::time::Duration;

fn scene(file: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenes")
        .join(file);
    Scene::load(&path).expect("committed scene")
}

/// The variants: (label, effects, speed-dependent friction).
fn variants() -> Vec<(&'static str, Effects, bool)> {
    let e = |friction, stick, table| Effects {
        friction,
        stick,
        table,
    };
    vec![
        ("normal-impulse", e(false, false, false), false),
        ("+friction (stick off)", e(true, false, false), false),
        ("+friction+stick", e(true, true, false), false),
        ("+friction(mu(S))+stick", e(true, true, false), true),
        ("+friction+stick+table", e(true, true, true), false),
    ]
}

fn bench(c: &mut Criterion) {
    for (file, tag) in [
        ("default.toml", "rolling 30deg cut"),
        ("stun_cut_sticks.toml", "stun 10deg cut, sticks"),
    ] {
        let base = scene(file);
        for (method, steps) in [
            (Method::Rk4, 1000),
            (Method::Dop853, 1000),
            (Method::ClosedForm, 1000),
        ] {
            let settings = SolverSettings::default()
                .with_method(method)
                .with_steps(steps)
                .unwrap();
            let mut group = c.benchmark_group(format!("{tag} / {method}"));
            group
                .warm_up_time(Duration::from_millis(500))
                .measurement_time(Duration::from_secs(2))
                .sample_size(30);
            for (label, effects, speed_dependent) in variants() {
                if effects.table {
                    continue;
                }
                let mut s = base.clone();
                s.effects = effects;
                if speed_dependent {
                    s.contact.friction = Friction::speed_dependent(9.951e-3, 0.108, 1.088).unwrap();
                }
                let (collision, _) = s.collision().unwrap();
                let profile = s.profile.clone();
                group.bench_function(label, |b| {
                    b.iter(|| {
                        solve(black_box(&collision), &profile, black_box(&settings), None).unwrap()
                    })
                });
            }
            group.finish();
        }
        // The table effect alone: both balls from separation until they roll.
        let mut s = base.clone();
        s.effects.table = true;
        let so = run_scene(&s, &SolverSettings::default(), None).unwrap();
        let t = so.table.expect("table on");
        let (balls, table) = (s.balls, t.table);
        let (a, b) = (t.a.start, t.b.start);
        let (incoming, scale) = (t.incoming, 1.0);
        let mut group = c.benchmark_group(format!("{tag} / table"));
        group
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2))
            .sample_size(30);
        group.bench_function("table phase (both balls, with checks)", |bch| {
            bch.iter(|| {
                TableOutcome::new(&balls, table, black_box(&a), black_box(&b), incoming, scale)
                    .unwrap()
            })
        });
        group.bench_function("run_scene, table off", |bch| {
            let mut off = s.clone();
            off.effects.table = false;
            bch.iter(|| run_scene(black_box(&off), &SolverSettings::default(), None).unwrap())
        });
        group.bench_function("run_scene, table on", |bch| {
            bch.iter(|| run_scene(black_box(&s), &SolverSettings::default(), None).unwrap())
        });
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
