//! Root finding and tracking: `cargo bench --bench roots`.
//!
//! * all roots, small-angle and exact: coefficients + eigenvalue solve + refinement
//!   (`eigen`), and the whole `solve_all` (plus classification and selection by continuation
//!   from the start of sliding);
//! * one tracker step in exact mode: a 1 mm / 0.01° increment along a slide (coefficients,
//!   predictor, Newton corrector, admissibility check).

use criterion::{Criterion, criterion_group, criterion_main};
use slideroute::Displacement;
use slideroute::internals::roots::{self, Tracker, eigen, system};
use slideroute::internals::{model::Mode, scene::Scene};
use std::hint::black_box;

fn all_roots(c: &mut Criterion) {
    let scene = Scene::default_scene();
    let d = Displacement::new(0.5, 0.1, 0.03);
    for (name, mode) in [("small-angle", Mode::SmallAngle), ("exact", Mode::Exact)] {
        c.bench_function(&format!("all roots {name}: coefficients + eigen"), |b| {
            b.iter(|| {
                let (p, q) = system::biquadratic(black_box(scene.site()), black_box(d), mode);
                eigen::solve(&p, &q)
            })
        });
        c.bench_function(&format!("all roots {name}: reference 8x8 pencil"), |b| {
            let (p, q) = system::biquadratic(scene.site(), d, mode);
            b.iter(|| eigen::solve_pencil(black_box(&p), black_box(&q)))
        });
        c.bench_function(
            &format!("all roots {name}: solve_all (classify + select)"),
            |b| b.iter(|| roots::solve_all(black_box(scene.site()), black_box(d), mode)),
        );
    }
}

fn tracker_step(c: &mut Criterion) {
    let scene = Scene::default_scene();
    for (name, mode) in [("exact", Mode::Exact), ("small-angle", Mode::SmallAngle)] {
        c.bench_function(&format!("tracker step {name} (1 mm)"), |b| {
            let path = |k: usize| {
                let t = k as f64;
                Displacement::new(1e-3 * t, 2e-4 * t, (1e-2 * t).to_radians())
            };
            let mut tracker = Tracker::new(scene.site(), mode);
            let mut k = 0usize;
            b.iter(|| {
                k += 1;
                if k > 2000 {
                    tracker = Tracker::new(scene.site(), mode);
                    k = 1;
                }
                tracker.advance(black_box(path(k))).expect("on the branch")
            })
        });
    }
}

criterion_group!(benches, all_roots, tracker_step);
criterion_main!(benches);
