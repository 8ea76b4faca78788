//! A block on its base: `cargo bench --bench base`.
//!
//! * the default scene's first 3 s on its base against on its three-point frame (the same
//!   scene, `contacts = "base"` and `"frame"`);
//! * 1 s of a block sliding down a rough surveyed-style surface of 2 m cells, the survey 10³
//!   and 10⁵ triangles large: the same terrain under the block, so the same route; what the
//!   survey's size costs.

use criterion::{Criterion, criterion_group, criterion_main};
use slideroute::internals::scene::Scene;
use std::hint::black_box;
use std::path::{Path, PathBuf};

/// A surface of 2·n² triangles in 2 m cells from (−n, −n) m, falling 8° along +X with a seeded
/// relief of ±0.1 m: the same heights wherever two sizes overlap.
fn terrain(dir: &Path, n: usize) -> PathBuf {
    let height = |i: i64, j: i64| {
        let x = 2.0 * i as f64;
        let relief = (((i * 7919 + j * 104_729).rem_euclid(97)) as f64 / 97.0 - 0.5) * 0.2;
        -x * 8f64.to_radians().tan() + relief
    };
    let half = (n / 2) as i64;
    let mut obj = String::new();
    for i in -half..=half {
        for j in -half..=half {
            obj.push_str(&format!("v {} {} {}\n", 2 * i, height(i, j), 2 * j));
        }
    }
    let side = (2 * half + 1) as usize;
    let at = |i: usize, j: usize| i * side + j + 1;
    for i in 0..side - 1 {
        for j in 0..side - 1 {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            obj.push_str(&format!("f {a} {b} {c}\nf {a} {c} {d}\n"));
        }
    }
    let path = dir.join(format!("terrain-{n}.obj"));
    std::fs::write(&path, obj).unwrap();
    path
}

fn scene_on(dir: &Path, obj: &Path) -> Scene {
    let text = format!(
        r#"name = "terrain"
[frame]
contacts_m = [[-5.0, 4.0], [5.0, 4.0], [5.0, -4.0]]
[foundation]
surface = "{}"
[block]
mass_kg = 2.0e6
inertia_kg_m2 = 3.0e7
[loads]
hydraulic_force_n = 4.0e6
eccentricity_m = 1.0
gravity_m_s2 = 9.81
[friction]
model = "coulomb"
mu_k = 0.3
[solver]
mode = "exact"
dt_s = 1.0e-3
t_end_s = 1.0
"#,
        obj.file_name().unwrap().to_string_lossy()
    );
    let path = dir.join(format!(
        "{}.toml",
        obj.file_stem().unwrap().to_string_lossy()
    ));
    std::fs::write(&path, text).unwrap();
    Scene::from_file(&path).unwrap()
}

fn base_against_frame(c: &mut Criterion) {
    let scene = Scene::default_scene().with("solver.t_end_s", 3.0).unwrap();
    for contacts in ["frame", "base"] {
        let s = scene.with("solver.contacts", contacts).unwrap();
        c.bench_function(&format!("default scene 3 s, contacts = {contacts}"), |b| {
            b.iter(|| slideroute::run(black_box(&s)).unwrap())
        });
    }
}

fn survey_size(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("slideroute-bench-base-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // 2·22² = 968 and 2·224² = 100 352 triangles.
    for n in [22usize, 224] {
        let scene = scene_on(&dir, &terrain(&dir, n));
        let triangles = scene.site().ground().map_or(0, |(g, _)| g.faces().len());
        c.bench_function(&format!("1 s on a surface of {triangles} triangles"), |b| {
            b.iter(|| slideroute::run(black_box(&scene)).unwrap())
        });
    }
    std::fs::remove_dir_all(&dir).ok();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = base_against_frame, survey_size
}
criterion_main!(benches);
