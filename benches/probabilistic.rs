//! Probabilistic throughput: `cargo bench --bench probabilistic`.
//!
//! * samples per second on one core, the default scene with μ, the eccentricity and the dip of
//!   plane 2 uncertain, under each dynamics (the time of one sample is the figure; samples/s
//!   per core is its inverse);
//! * the analysis's overhead over bare routes: the same scenes' routes run directly, against
//!   [`Design::run`] with its sampling, scene edits, results and summary — on one thread, so
//!   that the figure is the overhead and not the parallel speed-up;
//! * the default scene with μ and the eccentricity uncertain, 256 samples, the whole analysis on
//!   one thread and on two (`docs/performance.md`: samples per CPU-second).

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use slideroute::internals::analysis::probabilistic::{
    Design, Limits, Sampling, Uncertain, sample_scene, summarise,
};
use slideroute::internals::{model::DynamicsModel, scene::Scene};
use std::hint::black_box;

/// Samples in one measured batch.
const BATCH: usize = 16;

fn uncertain() -> Vec<Uncertain> {
    [
        "friction.mu_k=normal:0.40:0.05",
        "loads.eccentricity_m=truncnormal:1.0:0.5:0:2",
        "foundation.zeta_deg=uniform:22:28",
    ]
    .iter()
    .map(|s| s.parse().unwrap())
    .collect()
}

fn throughput(c: &mut Criterion) {
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let u = uncertain();
    let mut g = c.benchmark_group("probabilistic");
    g.sample_size(10);
    g.throughput(Throughput::Elements(BATCH as u64));
    for model in [DynamicsModel::RigidBody, DynamicsModel::Paper] {
        let scene = Scene::default_scene().with_dynamics(model).unwrap();
        let design = Design {
            scene: &scene,
            uncertain: &u,
            samples: BATCH,
            // A seed whose batch has no sample of a stiff route (see docs/performance.md).
            seed: 2,
            sampling: Sampling::LatinHypercube,
        };
        // The scenes of the samples, made before timing: the bare routes' input.
        let scenes: Vec<Scene> = design
            .values()
            .iter()
            .map(|v| sample_scene(&scene, &u, v).unwrap())
            .collect();
        g.bench_function(BenchmarkId::new("bare routes", model.as_str()), |b| {
            b.iter(|| {
                for s in &scenes {
                    black_box(slideroute::run(s).unwrap());
                }
            })
        });
        g.bench_function(BenchmarkId::new("analysis", model.as_str()), |b| {
            b.iter(|| {
                one_thread.install(|| {
                    let rows = design.run(|| {}, || false);
                    black_box(summarise(&design, Limits::default(), &rows))
                })
            })
        });
    }
    g.finish();
}

/// The default scene with μ and the eccentricity uncertain: the whole analysis of 256 samples
/// on one thread and on two.
fn mu_and_eccentricity(c: &mut Criterion) {
    const SAMPLES: usize = 256;
    let u: Vec<Uncertain> = [
        "friction.mu_k=normal:0.4:0.04",
        "loads.eccentricity_m=uniform:0.5:1.5",
    ]
    .iter()
    .map(|s| s.parse().unwrap())
    .collect();
    let scene = Scene::default_scene();
    let design = Design {
        scene: &scene,
        uncertain: &u,
        samples: SAMPLES,
        seed: 1,
        sampling: Sampling::LatinHypercube,
    };
    let mut g = c.benchmark_group("probabilistic, mu and eccentricity");
    g.sample_size(10);
    g.throughput(Throughput::Elements(SAMPLES as u64));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        g.bench_function(BenchmarkId::new("threads", threads), |b| {
            b.iter(|| {
                pool.install(|| {
                    let rows = design.run(|| {}, || false);
                    black_box(summarise(&design, Limits::default(), &rows))
                })
            })
        });
    }
    g.finish();
}

criterion_group!(benches, throughput, mu_and_eccentricity);
criterion_main!(benches);
