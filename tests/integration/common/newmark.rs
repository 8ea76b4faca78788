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
