//! A long record with a few slips: `cargo bench --bench records`.
//!
//! 10⁵ samples at 5 ms (500 s): weak shaking throughout and three strong bursts, on a block
//! pushed to 0.9 of its friction (μ = 1, k_y = 0.1 g) on a level face, the route's increment the
//! record's interval. Against it, the exact one-dimensional solution of the same continuous
//! problem (`tests/integration/common/newmark.rs`), the figure the route is asked to be
//! within ten times of: the block is held for all but a few seconds, and a held block is
//! checked against the friction cones sample by sample by a few multiplications
//! (`src/route/rigid/held_region.rs`).

#[path = "../tests/integration/common/newmark.rs"]
#[allow(dead_code)]
mod newmark;

use criterion::{Criterion, criterion_group, criterion_main};
use slideroute::Scene;
use std::hint::black_box;

const SAMPLES: usize = 100_000;
const DT: f64 = 0.005;

/// The record (g along X).
fn long_record() -> Vec<f64> {
    let mut a: Vec<f64> = (0..SAMPLES)
        .map(|k| {
            let t = k as f64 * DT;
            let tau = std::f64::consts::TAU;
            let weak = 0.03 * (tau * 1.3 * t).sin() * (tau * 0.01 * t).sin();
            let bursts: f64 = [100.0, 250.0, 400.0]
                .iter()
                .map(|c| -0.5 * (-((t - c) / 0.3).powi(2)).exp() * (tau * 2.0 * (t - c)).cos())
                .sum();
            weak + bursts
        })
        .collect();
    a[0] = 0.0;
    a
}

fn scene(a: &[f64], stride: usize) -> Scene {
    let dir = std::env::temp_dir().join(format!("slideroute-bench-records-{}", std::process::id()));
    let run = newmark::Run {
        contacts: "frame",
        dt_s: DT,
        stride,
    };
    let path = newmark::write_along(&dir, "long-record", (a, DT, "x"), (1.0, 0.9), run);
    let s = Scene::from_file(&path).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    s
}

fn records(c: &mut Criterion) {
    let a = long_record();
    let s = scene(&a, 1);
    let mut group = c.benchmark_group("10^5-sample record, three slips");
    group.sample_size(10);
    group.bench_function("route (three-point frame, dt = the record's 5 ms)", |b| {
        b.iter(|| slideroute::run(black_box(&s)).unwrap())
    });
    // A row every 100 samples (0.5 s): what the route itself costs, without 10⁵ rows.
    let strided = scene(&a, 100);
    group.bench_function("route, a row every 100 samples", |b| {
        b.iter(|| slideroute::run(black_box(&strided)).unwrap())
    });
    group.bench_function("exact one-dimensional solution", |b| {
        b.iter(|| newmark::exact(black_box(&a), DT, 1.0, 0.9))
    });
    group.finish();
}

criterion_group!(benches, records);
criterion_main!(benches);
