//! All roots of many poses at once, against NumPy: `cargo bench --bench roots_batch`.
//!
//! The same 4096 random poses of the default scene (X in [0, 0.5] m, Z in [−0.2, 0.2] m,
//! θ in [−3°, 3°], exact mode), their pose systems' coefficients computed once:
//!
//! * criterion: the roots of the 4096 systems batched (`BatchSolver`: the resultant, the
//!   companion matrix's eigenvalues continued from the pose before as quadratic factors and
//!   certified, else by QR; y), and one system at a time (`eigen::solve`, QR);
//! * then, under `cargo bench` only, the CPU time a pose of each on this thread, and the same
//!   solve in vectorised NumPy over all 4096 poses (`benches/numpy_roots.py`: the resultant in y
//!   as a degree-8 polynomial in x, `np.linalg.eigvals` of the stacked companion matrices, y
//!   from both quadratics), on one thread, on the same coefficients, which it checks against
//!   ours; and the ratio. The interpreter is `$SLIDEROUTE_NUMPY_PYTHON`, else
//!   `python/.venv/bin/python` (`python/setup.sh` makes it), else `python3`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use slideroute::Displacement;
use slideroute::internals::roots::eigen::{self, Coeffs};
use slideroute::internals::roots::{BatchSolver, system};
use slideroute::internals::{model::Mode, scene::Scene};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

const POSES: usize = 4096;

/// The systems of `POSES` random poses (a fixed linear congruential sequence).
fn systems() -> Vec<(Coeffs, Coeffs)> {
    let scene = Scene::default_scene();
    let mut s = 2026u64;
    let mut uniform = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..POSES)
        .map(|_| {
            let d = Displacement::new(
                0.5 * uniform(),
                0.4 * uniform() - 0.2,
                (6.0 * uniform() - 3.0f64).to_radians(),
            );
            system::biquadratic(scene.site(), d, Mode::Exact)
        })
        .collect()
}

fn batch(c: &mut Criterion) {
    let systems = systems();
    let mut g = c.benchmark_group("roots of 4096 poses");
    g.throughput(Throughput::Elements(POSES as u64));
    g.bench_function("batched (continued, certified)", |b| {
        let (mut solver, mut out) = (BatchSolver::new(), Vec::new());
        b.iter(|| solver.solve(black_box(&systems), &mut out))
    });
    g.bench_function("one at a time (eigen::solve)", |b| {
        b.iter(|| {
            black_box(&systems)
                .iter()
                .map(|(p, q)| eigen::solve(p, q).roots.len())
                .sum::<usize>()
        })
    });
    g.finish();
    if std::env::args().any(|a| a == "--bench") {
        against_numpy(&systems);
    }
}

/// This thread's CPU time, where Linux tells it (else the wall clock's).
fn cpu_time(wall: Instant) -> Duration {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .map_or_else(|| wall.elapsed(), Duration::from_nanos)
}

/// CPU µs a pose of `solve` over all the systems, the best of five runs of at least 0.4 s.
fn us_per_pose(mut solve: impl FnMut()) -> f64 {
    let origin = Instant::now();
    (0..5)
        .map(|_| {
            let (start, mut runs) = (cpu_time(origin), 0u32);
            while cpu_time(origin) - start < Duration::from_millis(400) {
                solve();
                runs += 1;
            }
            (cpu_time(origin) - start).as_secs_f64() * 1e6 / (runs as f64 * POSES as f64)
        })
        .fold(f64::INFINITY, f64::min)
}

fn python() -> PathBuf {
    if let Some(p) = std::env::var_os("SLIDEROUTE_NUMPY_PYTHON") {
        return p.into();
    }
    let venv = Path::new(env!("CARGO_MANIFEST_DIR")).join("python/.venv/bin/python");
    if venv.exists() {
        venv
    } else {
        "python3".into()
    }
}

fn against_numpy(systems: &[(Coeffs, Coeffs)]) {
    let (mut solver, mut out) = (BatchSolver::new(), Vec::new());
    let batched = us_per_pose(|| solver.solve(black_box(systems), &mut out));
    let (continued, by_qr) = (solver.continued, solver.by_qr);
    let alone = us_per_pose(|| {
        black_box(
            systems
                .iter()
                .map(|(p, q)| eigen::solve(p, q).roots.len())
                .sum::<usize>(),
        );
    });
    // The coefficients (p then q, p[i][j] the coefficient of x^i y^j) and our x-roots (NaN
    // where a pose has fewer), little-endian f64, for the script.
    let dir = std::env::temp_dir().join(format!("slideroute-roots-batch-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let mut coeffs = Vec::with_capacity(POSES * 18 * 8);
    let mut roots = Vec::with_capacity(POSES * 16 * 8);
    for ((p, q), r) in systems.iter().zip(&out) {
        for v in p.iter().chain(q).flatten() {
            coeffs.extend(v.to_le_bytes());
        }
        for k in 0..8 {
            let x = r.roots().get(k).map_or([f64::NAN; 2], |r| [r.x.re, r.x.im]);
            x.iter().for_each(|v| roots.extend(v.to_le_bytes()));
        }
    }
    let (cf, rf) = (dir.join("coeffs.f64"), dir.join("x_roots.f64"));
    std::fs::write(&cf, coeffs).expect("the coefficients written");
    std::fs::write(&rf, roots).expect("the roots written");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/numpy_roots.py");
    let run = std::process::Command::new(python())
        .arg(&script)
        .arg(&cf)
        .arg(&rf)
        .envs(["OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"].map(|k| (k, "1")))
        .output();
    let _ = std::fs::remove_dir_all(&dir);
    println!("\nCPU time a pose, one thread, {POSES} poses of the default scene (exact):");
    println!("  ours, batched (continued):       {batched:.3} µs");
    println!("  ours, one at a time:             {alone:.3} µs");
    println!(
        "  poses continued and certified: {:.2} % ({continued} of {})",
        100.0 * continued as f64 / (continued + by_qr) as f64,
        continued + by_qr
    );
    let text = match run {
        Ok(o) if o.status.success() => String::from_utf8_lossy(&o.stdout).into_owned(),
        Ok(o) => {
            println!(
                "  NumPy: skipped ({})",
                String::from_utf8_lossy(&o.stderr).trim()
            );
            return;
        }
        Err(e) => {
            println!("  NumPy: skipped ({}: {e})", python().display());
            return;
        }
    };
    print!("{text}");
    let value = |key: &str| {
        text.lines().find_map(|l| {
            l.trim()
                .strip_prefix(key)?
                .split_whitespace()
                .next()?
                .parse()
                .ok()
        })
    };
    if let (Some(eig), Some(all)) = (value("eigvals_us"), value("all_us")) {
        let all: f64 = all;
        let eig: f64 = eig;
        println!(
            "  ratio: NumPy resultant + eigvals + y / ours batched = {:.1}× \
             (eigvals without y: {:.1}×; ours one at a time: {:.1}×)",
            all / batched,
            eig / batched,
            all / alone
        );
    }
}

criterion_group!(benches, batch);
criterion_main!(benches);
