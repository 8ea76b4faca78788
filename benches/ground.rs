//! Foundations of faces: `cargo bench --bench ground`.
//!
//! * the face under a point of a triangulated surface of 10⁴ triangles, through the R*-tree,
//!   against a scan of every triangle (the tree's cost grows as log n, the scan's as n);
//! * building the ground of a surface of 10⁵ triangles (checks, planes, the tree's bulk load);
//! * one tracker step on the paper's site (the paper's system) and on the same contacts and
//!   planes as a general site (the generated general system).

use criterion::{Criterion, criterion_group, criterion_main};
use slideroute::internals::{model::Mode, scene::Scene};
use slideroute::poses::Tracker;
use slideroute::{Displacement, Ground, Site};
use std::hint::black_box;

/// A rough surface of 2·n² triangles over [0, n]².
fn surface(n: usize) -> (Vec<[[f64; 3]; 3]>, Ground) {
    let height = |i: usize, j: usize| ((i * 7 + j * 13) % 11) as f64 * 0.05;
    let mut tris = Vec::with_capacity(2 * n * n);
    for i in 0..n {
        for j in 0..n {
            let c = |a: usize, b: usize| [a as f64, height(a, b), b as f64];
            tris.push([c(i, j), c(i + 1, j), c(i + 1, j + 1)]);
            tris.push([c(i, j), c(i + 1, j + 1), c(i, j + 1)]);
        }
    }
    let ground = Ground::surface(&tris).expect("a valid surface");
    (tris, ground)
}

/// The highest triangle over (x, z) by looking at every one.
fn scan(tris: &[[[f64; 3]; 3]], ground: &Ground, x: f64, z: f64) -> Option<f64> {
    tris.iter()
        .enumerate()
        .filter(|(_, t)| {
            let cross =
                |p: [f64; 3], q: [f64; 3]| (q[0] - p[0]) * (z - p[2]) - (q[2] - p[2]) * (x - p[0]);
            let d = [cross(t[0], t[1]), cross(t[1], t[2]), cross(t[2], t[0])];
            !(d.iter().any(|v| *v < 0.0) && d.iter().any(|v| *v > 0.0))
        })
        .map(|(k, _)| ground.faces()[k].height(x, z))
        .reduce(f64::max)
}

fn face_lookup(c: &mut Criterion) {
    for n in [10usize, 71] {
        let (tris, ground) = surface(n);
        let count = tris.len();
        let points: Vec<(f64, f64)> = (0..64)
            .map(|k| {
                let t = k as f64 / 64.0;
                (t * n as f64, (0.37 + 0.61 * t) % 1.0 * n as f64)
            })
            .collect();
        c.bench_function(
            &format!("face under a point, {count} triangles: R*-tree"),
            |b| {
                let mut k = 0;
                b.iter(|| {
                    k = (k + 1) % points.len();
                    let (x, z) = points[k];
                    ground.top(black_box(x), black_box(z))
                })
            },
        );
        c.bench_function(
            &format!("face under a point, {count} triangles: scan"),
            |b| {
                let mut k = 0;
                b.iter(|| {
                    k = (k + 1) % points.len();
                    let (x, z) = points[k];
                    scan(&tris, &ground, black_box(x), black_box(z))
                })
            },
        );
    }
}

fn tracker_step(c: &mut Criterion) {
    let scene = Scene::default_scene();
    let paper = scene.site().clone();
    let general = Site::general(*paper.contacts(), *paper.planes());
    for (name, site) in [("paper's system", &paper), ("general system", &general)] {
        c.bench_function(&format!("tracker step exact (1 mm), {name}"), |b| {
            let path = |k: usize| {
                let t = k as f64;
                Displacement::new(1e-3 * t, 2e-4 * t, (1e-2 * t).to_radians())
            };
            let mut tracker = Tracker::new(site, Mode::Exact);
            let mut k = 0usize;
            b.iter(|| {
                k += 1;
                if k > 2000 {
                    tracker = Tracker::new(site, Mode::Exact);
                    k = 1;
                }
                tracker.advance(black_box(path(k))).expect("on the branch")
            })
        });
    }
}

/// Building the ground of a surface of 10⁵ triangles from its corners: the checks, the planes and
/// the R*-tree's bulk load (the per-triangle figure of docs/performance.md).
fn surface_load(c: &mut Criterion) {
    let (tris, _) = surface(224);
    c.bench_function(
        &format!("build the ground of {} triangles", tris.len()),
        |b| b.iter(|| Ground::surface(black_box(&tris)).expect("a valid surface")),
    );
}

criterion_group!(benches, face_lookup, tracker_step, surface_load);
criterion_main!(benches);
