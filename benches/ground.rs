//! Foundations of faces: `cargo bench --bench ground`.
//!
//! * the face under a point of a triangulated surface of 10⁴ triangles, through the R*-tree,
//!   against a scan of every triangle (the tree's cost grows as log n, the scan's as n);
//! * building the ground of a surface of 10⁵ triangles (checks, planes, the tree's bulk load),
//!   from triangles each with its own corners and from a grid of shared corners;
//! * loading a scene on a surface of 10⁶ triangles from its OBJ file, end to end (the file
//!   written once into a temporary folder);
//! * one tracker step on the paper's site (the paper's system) and on the same contacts and
//!   planes as a general site (the generated general system).

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use slideroute::internals::{model::Mode, scene::Scene};
use slideroute::poses::Tracker;
use slideroute::{Displacement, Ground, Site};
use std::hint::black_box;
use std::io::Write;

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

/// Building the ground of a surface of 10⁵ triangles: the checks, the planes and the tree's
/// bulk load (the per-triangle figure of docs/performance.md), from triangles each with its own
/// corners, and from a grid of shared corners as a file gives them.
fn surface_load(c: &mut Criterion) {
    let (tris, _) = surface(224);
    c.bench_function(
        &format!("build the ground of {} triangles", tris.len()),
        |b| b.iter(|| Ground::surface(black_box(&tris)).expect("a valid surface")),
    );
    let (vertices, triangles) = grid(225, |_, _| 0.0);
    c.bench_function(
        &format!(
            "build the ground of {} triangles on shared corners",
            triangles.len()
        ),
        |b| {
            b.iter_batched(
                || (vertices.clone(), triangles.clone()),
                |(v, t)| Ground::mesh(v, t).expect("a valid surface"),
                BatchSize::LargeInput,
            )
        },
    );
}

/// A grid of n × n corners 2 m apart from (−20, −700), two triangles a cell, the height of
/// corner (i, j) `height(x, z)`.
fn grid(n: usize, height: impl Fn(f64, f64) -> f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut vertices = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let (x, z) = (-20.0 + 2.0 * i as f64, -700.0 + 2.0 * j as f64);
            vertices.push([x, height(x, z), z]);
        }
    }
    let at = |i: usize, j: usize| (i * n + j) as u32;
    let mut triangles = Vec::with_capacity(2 * (n - 1) * (n - 1));
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    (vertices, triangles)
}

/// Loading `scenes/valley.toml`'s block on a valley of 999 698 triangles (708 × 708 corners)
/// from its OBJ file: reading, the checks, the planes, the tree, the scene's own checks.
fn obj_load(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("slideroute-bench-ground-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    // Level where the block starts, rising at 20° beyond X = 4 m, rough from X = 8 m on.
    let (vertices, triangles) = grid(708, |x, z| {
        let rise = 20f64.to_radians().tan() * (x - 4.0).max(0.0);
        let rough = if x >= 8.0 {
            0.1 * (0.7 * x + 1.3 * z).sin()
        } else {
            0.0
        };
        rise + rough
    });
    let mut obj = std::io::BufWriter::new(
        std::fs::File::create(dir.join("big.obj")).expect("the surface file"),
    );
    for [x, y, z] in &vertices {
        writeln!(obj, "v {x:.6} {y:.6} {z:.6}").expect("written");
    }
    for [a, b, c] in &triangles {
        writeln!(obj, "f {} {} {}", a + 1, b + 1, c + 1).expect("written");
    }
    obj.flush().expect("written");
    let valley =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/valley.toml"))
            .expect("scenes/valley.toml");
    let path = dir.join("big.toml");
    std::fs::write(&path, valley.replace("valley.obj", "big.obj")).expect("the scene file");
    let mut group = c.benchmark_group("surface file");
    group.sample_size(10);
    group.bench_function(
        format!("load a scene on {} triangles from OBJ", triangles.len()),
        |b| b.iter(|| Scene::from_file(black_box(&path)).expect("a valid scene")),
    );
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, face_lookup, tracker_step, surface_load, obj_load);
criterion_main!(benches);
