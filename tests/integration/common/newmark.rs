//! Newmark's one-dimensional sliding block with a constant push, in closed form, and the
//! synthetic records it is tried on: shared by `newmark_exact.rs` and `benches/records.rs`
//! (which includes this file). Independent of the library: nothing here calls it.

/// g (m/s²), as the scenes give it.
pub const G: f64 = 9.81;

/// A synthetic strong-motion record along X (g) at `dt` for `length` s, the same for a seed
/// every time: white noise through a Kanai–Tajimi-like filter (2.5 Hz, 60 % damping), under an
/// envelope rising over 2 s and decaying after 40 % of the length, scaled to `pga` g.
pub fn record(seed: u64, length: f64, dt: f64, pga: f64) -> Vec<f64> {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let n = (length / dt).round() as usize + 1;
    let omega = 2.0 * std::f64::consts::PI * 2.5;
    let zeta = 0.6;
    let (mut x, mut v) = (0.0, 0.0);
    let mut a: Vec<f64> = (0..n)
        .map(|i| {
            let w = (-2.0 * uniform().ln()).sqrt() * (2.0 * std::f64::consts::PI * uniform()).cos();
            let acc = -2.0 * zeta * omega * v - omega * omega * x + w / dt.sqrt();
            v += acc * dt;
            x += v * dt;
            let t = i as f64 * dt;
            let envelope =
                (t / 2.0).min(1.0) * (-(t - 0.4 * length).max(0.0) / (0.15 * length)).exp();
            -(2.0 * zeta * omega * v + omega * omega * x) * envelope
        })
        .collect();
    a[0] = 0.0;
    let peak = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter_mut().for_each(|v| *v *= pga / peak);
    a
}

/// The exact permanent displacement (m, along +X) of a block pushed by `push` of its weight
/// along +X on a level plane of friction `mu`, the ground's acceleration `a` (g, along X)
/// linear between samples `dt` apart and zero after the last; from rest.
pub fn exact(a: &[f64], dt: f64, mu: f64, push: f64) -> f64 {
    // s: the sliding direction (0 held). While sliding u'' = g (push − s μ − a(t)).
    let (mut u, mut v, mut s) = (0.0f64, 0.0f64, 0.0f64);
    let band = |acc: f64| -> f64 {
        if acc < push - mu {
            1.0
        } else if acc > push + mu {
            -1.0
        } else {
            0.0
        }
    };
    for k in 0..a.len() - 1 {
        let (a0, a1) = (a[k], a[k + 1]);
        let slope = (a1 - a0) / dt;
        let mut tau = 0.0;
        while tau < dt {
            let at = a0 + slope * tau;
            if s == 0.0 {
                s = band(at);
                if s != 0.0 {
                    continue;
                }
                // Held: the first moment the linear acceleration leaves the band.
                let leaves = [push - mu, push + mu]
                    .iter()
                    .filter(|&&edge| (a1 - edge) * (at - edge) < 0.0)
                    .map(|&edge| (edge - a0) / slope)
                    .fold(f64::INFINITY, f64::min);
                if leaves >= dt {
                    break;
                }
                tau = leaves.max(tau);
                s = if slope < 0.0 { 1.0 } else { -1.0 };
                continue;
            }
            // v(r) = v + c0 r + c1 r²/2: its first zero in the interval stops the block.
            let (c0, c1) = (G * (push - s * mu - at), -G * slope);
            let rem = dt - tau;
            let roots = quadratic(0.5 * c1, c0, v);
            match roots
                .into_iter()
                .filter(|&r| r > 1e-15 && r <= rem)
                .reduce(f64::min)
            {
                Some(r) => {
                    u += v * r + 0.5 * c0 * r * r + c1 * r.powi(3) / 6.0;
                    v = 0.0;
                    tau += r;
                    s = band(a0 + slope * tau);
                }
                None => {
                    u += v * rem + 0.5 * c0 * rem * rem + c1 * rem.powi(3) / 6.0;
                    v += c0 * rem + 0.5 * c1 * rem * rem;
                    tau = dt;
                }
            }
        }
    }
    // After the record the ground rests: the block slides to its stop if it can.
    if s != 0.0 && v != 0.0 {
        let decel = G * (push - s * mu);
        if s * decel < 0.0 {
            let r = -v / decel;
            u += v * r + 0.5 * decel * r * r;
        }
    }
    u
}

/// The permanent displacement (m; X, Z) of a block on a level plane of friction `mu`, from
/// rest, the ground accelerating by `ax` and `az` (g, along X and Z) linear between samples `dt`
/// apart and zero after the last: Newmark's block in two directions, a point mass whose
/// friction μ g opposes its slip u relative to the ground, u′ = −A(t) − μ g u/|u|, held while
/// |A| ≤ μ g. (The frame's block is that point: its load passes through its centre of mass in
/// the base plane, so its friction has no moment and it does not turn.) Not closed form: RK4
/// in `per_sample` steps a sample, each onset located within its step by bisection on
/// |A| = μ g, a slow slip (within ten steps' friction of zero, where its direction turns fast)
/// in 256 substeps, each stop taken where the slip is under what friction stops in one substep
/// and A within the cone; converged in the step, which the test checks by halving it.
pub fn two_way(ax: &[f64], az: &[f64], dt: f64, mu: f64, per_sample: usize) -> [f64; 2] {
    let h = dt / per_sample as f64;
    let n = ax.len().min(az.len());
    // The ground's acceleration (m/s²) at time t.
    let ground = |t: f64| -> [f64; 2] {
        let k = (t / dt).floor();
        if k < 0.0 || k as usize + 1 >= n {
            return [0.0, 0.0];
        }
        let (k, r) = (k as usize, t / dt - k);
        [
            G * (ax[k] + r * (ax[k + 1] - ax[k])),
            G * (az[k] + r * (az[k + 1] - az[k])),
        ]
    };
    let norm = |v: [f64; 2]| v[0].hypot(v[1]);
    let cone = mu * G;
    let slip_rate = |t: f64, u: [f64; 2]| -> [f64; 2] {
        let a = ground(t);
        let s = norm(u);
        [-a[0] - cone * u[0] / s, -a[1] - cone * u[1] / s]
    };
    let (mut d, mut u, mut sliding) = ([0.0f64; 2], [0.0f64; 2], false);
    // Step k spans [k h, (k + 1) h]: the samples fall on step ends, so that RK4 never steps
    // over a kink of the record. Past the record, until the block stops.
    let last = (n - 1) * per_sample;
    let mut k = 0usize;
    while k < last || sliding {
        let (t, t1) = (k as f64 * h, (k + 1) as f64 * h);
        k += 1;
        if !sliding {
            if norm(ground(t1)) <= cone {
                continue;
            }
            // The onset: where |A| first exceeds μ g within the step.
            let (mut lo, mut hi) = (t, t1);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if norm(ground(mid)) > cone {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            // From rest the slip starts against the ground's acceleration.
            let a = ground(hi);
            let e = 1e-300_f64.max(1e-14 * h * (norm(a) - cone));
            let (next, moved) = rk4_slip(
                &slip_rate,
                hi,
                [-e * a[0] / norm(a), -e * a[1] / norm(a)],
                t1 - hi,
            );
            d = [d[0] + moved[0], d[1] + moved[1]];
            u = next;
            sliding = true;
            continue;
        }
        // A slow slip turns fast (at μ g / |u|): within ten steps' friction of zero the step
        // is taken in SLOW substeps. Slower than friction stops in a substep, where the cone
        // holds: the stop, the rest of the step held.
        let parts = if norm(u) < 10.0 * cone * h { SLOW } else { 1 };
        let hs = h / parts as f64;
        for p in 0..parts {
            let ts = t + p as f64 * hs;
            if norm(u) <= cone * hs && norm(ground(ts)) <= cone {
                u = [0.0, 0.0];
                sliding = false;
                break;
            }
            let (next, moved) = rk4_slip(&slip_rate, ts, u, hs);
            d = [d[0] + moved[0], d[1] + moved[1]];
            u = next;
        }
    }
    d
}

/// The substeps of a step of [`two_way`] whose slip is slow.
const SLOW: usize = 256;

/// One RK4 step of length `h` of the slip u′ = `f`(t, u) from (t, u): the slip after it and the
/// displacement over it (∫ u, by the same stages).
fn rk4_slip(
    f: &dyn Fn(f64, [f64; 2]) -> [f64; 2],
    t: f64,
    u: [f64; 2],
    h: f64,
) -> ([f64; 2], [f64; 2]) {
    let add = |a: [f64; 2], b: [f64; 2], s: f64| [a[0] + s * b[0], a[1] + s * b[1]];
    let k1 = f(t, u);
    let u2 = add(u, k1, 0.5 * h);
    let k2 = f(t + 0.5 * h, u2);
    let u3 = add(u, k2, 0.5 * h);
    let k3 = f(t + 0.5 * h, u3);
    let u4 = add(u, k3, h);
    let k4 = f(t + h, u4);
    let next = [
        u[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
        u[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
    ];
    let moved = [
        h / 6.0 * (u[0] + 2.0 * u2[0] + 2.0 * u3[0] + u4[0]),
        h / 6.0 * (u[1] + 2.0 * u2[1] + 2.0 * u3[1] + u4[1]),
    ];
    (next, moved)
}

/// The real roots of A x² + B x + C (one for A = 0).
fn quadratic(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a == 0.0 {
        return if b == 0.0 { vec![] } else { vec![-c / b] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    if q == 0.0 {
        vec![0.0]
    } else {
        vec![q / a, c / q]
    }
}

/// How a pushed block on a level face is run: its contacts (`frame` or `base`), the route's
/// increment (s) and its row stride.
pub struct Run<'a> {
    pub contacts: &'a str,
    pub dt_s: f64,
    pub stride: usize,
}

/// Writes into `dir` the scene of a block on one level face, three points of the paper's frame
/// (or its base), pushed along X by `push` of its weight through its centre of mass, friction
/// `mu`, shaken along `axis` ("x" or "z") by the record `a` (g) at `record_dt` (a one-column
/// file, every digit kept, so that the exact solution of `a` is the route's), its time limit
/// 10 s past the record; the scene file's path.
pub fn write_along(
    dir: &std::path::Path,
    name: &str,
    (a, record_dt, axis): (&[f64], f64, &str),
    (mu, push): (f64, f64),
    run: Run<'_>,
) -> std::path::PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let column: String = a.iter().map(|v| format!("{v:?}\n")).collect();
    std::fs::write(dir.join("record.txt"), column).unwrap();
    let seismic = format!("record_{axis} = \"record.txt\"\ndt_s = {record_dt}\n");
    let t_end = (a.len() - 1) as f64 * record_dt + 10.0;
    write_shaken(dir, name, &seismic, t_end, (mu, push), run)
}

/// Writes into `dir` the scene of [`write_along`] with `seismic` as its `[seismic]` table
/// (the record's files already in `dir`) and the time limit `t_end` (s); the scene file's path.
pub fn write_shaken(
    dir: &std::path::Path,
    name: &str,
    seismic: &str,
    t_end: f64,
    (mu, push): (f64, f64),
    run: Run<'_>,
) -> std::path::PathBuf {
    let text = format!(
        r#"name = "{name}"
[frame]
l1x = 6.0
l2x = 4.0
l1z = 5.0
l2z = 5.0
[foundation]
[[foundation.plane]]
dip_deg = 0.0
dip_direction_deg = 0.0
point_m = [0.0, 0.0, 0.0]
[block]
mass_kg = 1.0e6
inertia_kg_m2 = 1.1e7
[loads]
hydraulic_force_n = {force}
eccentricity_m = 0.0
gravity_m_s2 = {G}
[friction]
model = "coulomb"
mu_k = {mu}
[solver]
mode = "exact"
contacts = "{contacts}"
dt_s = {dt}
t_end_s = {t_end}
stride = {stride}
[seismic]
{seismic}"#,
        force = push * 1.0e6 * G,
        contacts = run.contacts,
        dt = run.dt_s,
        stride = run.stride,
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}
