//! Eigenvalues of a small upper Hessenberg matrix: balancing, then the Francis double-shift QR
//! iteration (the EISPACK `balanc` and `hqr` algorithms, as given in Numerical Recipes §11.5–11.6).
//!
//! Written with explicit 1-based indices so that it can be checked line by line against the
//! published algorithm (hence `needless_range_loop` is allowed here).
//!
//! Used on the companion matrix of the degree-≤ 8 resultant, which is already Hessenberg, so
//! no reduction is needed. Fixed-size storage, no allocation.

#![allow(clippy::needless_range_loop)]

/// Largest order handled.
pub const N: usize = 8;

/// Sweeps per eigenvalue before the iteration is given up.
pub(crate) const MAX_SWEEPS: usize = 30;

/// Reading and writing entry (i, j) of a matrix: the steps of the iteration take their storage
/// through it (one implementation, the fixed 1-based array).
pub(crate) trait Entries {
    /// Entry (i, j), 1-based.
    fn at(&self, i: usize, j: usize) -> f64;
    /// Sets entry (i, j).
    fn set(&mut self, i: usize, j: usize, v: f64);
}

impl<const M: usize> Entries for [[f64; M]; M] {
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        self[i][j]
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, v: f64) {
        self[i][j] = v;
    }
}

/// A Hessenberg matrix of order `n ≤ N`, 1-based storage (row and column 0 unused) so that the
/// classic algorithm reads as published.
pub struct Hessenberg {
    a: [[f64; N + 1]; N + 1],
    n: usize,
}

/// The base of the balancing scale factors.
pub(crate) const RADIX: f64 = 2.0;

impl Hessenberg {
    /// The companion matrix of the monic polynomial x^n + c\[n−1\] x^(n−1) + … + c\[0\]:
    /// first row −c\[n−1\], …, −c\[0\]; ones on the subdiagonal.
    pub fn companion(c: &[f64]) -> Self {
        let n = c.len();
        assert!(n <= N, "order {n} > {N}");
        let mut a = [[0.0; N + 1]; N + 1];
        for k in 1..=n {
            a[1][k] = -c[n - k];
        }
        for j in 2..=n {
            a[j][j - 1] = 1.0;
        }
        Hessenberg { a, n }
    }

    /// Diagonal similarity by powers of 2 that makes row and column norms comparable.
    pub fn balance(&mut self) {
        let (a, n) = (&mut self.a, self.n);
        let sqrdx = RADIX * RADIX;
        let mut done = false;
        while !done {
            done = true;
            for i in 1..=n {
                let (mut r, mut c) = (0.0, 0.0);
                for j in 1..=n {
                    if j != i {
                        c += a[j][i].abs();
                        r += a[i][j].abs();
                    }
                }
                if c != 0.0 && r != 0.0 {
                    let mut g = r / RADIX;
                    let mut f = 1.0;
                    let s = c + r;
                    while c < g {
                        f *= RADIX;
                        c *= sqrdx;
                    }
                    g = r * RADIX;
                    while c > g {
                        f /= RADIX;
                        c /= sqrdx;
                    }
                    if (c + r) / f < 0.95 * s {
                        done = false;
                        let g = 1.0 / f;
                        for j in 1..=n {
                            a[i][j] *= g;
                        }
                        for row in a.iter_mut().take(n + 1).skip(1) {
                            row[i] *= f;
                        }
                    }
                }
            }
        }
    }

    /// All eigenvalues as (re, im); `None` if the iteration does not converge (30 sweeps per
    /// eigenvalue), which for these matrices signals a defect upstream. The shifted QR
    /// algorithm of an upper Hessenberg matrix (Numerical Recipes' `hqr`): deflate at a
    /// negligible subdiagonal, take a trailing 1×1 or 2×2 block's eigenvalues, else one double
    /// shift (Francis) sweep.
    pub fn eigenvalues(self, wr: &mut [f64; N], wi: &mut [f64; N]) -> Option<usize> {
        self.eigenvalues_within(wr, wi, MAX_SWEEPS)
    }

    /// [`Hessenberg::eigenvalues`], giving up after `max_sweeps` sweeps without a deflation.
    pub(crate) fn eigenvalues_within(
        mut self,
        wr: &mut [f64; N],
        wi: &mut [f64; N],
        max_sweeps: usize,
    ) -> Option<usize> {
        let n = self.n;
        let mut progress = Progress::new(&self.a, n, max_sweeps);
        loop {
            match progress.step(&mut self.a, wr, wi) {
                Step::Sweep(rows, first) => francis_sweep(&mut self.a, rows, first),
                Step::Done => return Some(n),
                Step::Failed => return None,
            }
        }
    }
}

/// Σ|a_ij| over the Hessenberg part of the leading n×n block: the scale a negligible
/// subdiagonal is judged by.
fn norm<A: Entries>(a: &A, n: usize) -> f64 {
    let mut anorm = 0.0;
    for i in 1..=n {
        for j in (i.max(2) - 1)..=n {
            anorm += a.at(i, j).abs();
        }
    }
    anorm
}

/// Where one matrix's iteration stands: rows 1..=`nn` not yet deflated, the sweeps since the
/// last deflation, the exceptional shifts taken so far (added back to every eigenvalue).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Progress {
    pub(crate) nn: usize,
    its: usize,
    t: f64,
    anorm: f64,
    max_sweeps: usize,
}

/// What a matrix needs next: a sweep of these rows from this first Householder vector, nothing
/// (every eigenvalue found), or to be given up.
pub(crate) enum Step {
    Sweep(Rows, [f64; 3]),
    Done,
    Failed,
}

impl Progress {
    /// The start on the balanced matrix `a` of order `n`, giving up after `max_sweeps` sweeps
    /// without a deflation.
    pub(crate) fn new<A: Entries>(a: &A, n: usize, max_sweeps: usize) -> Self {
        Progress {
            nn: n,
            its: 0,
            t: 0.0,
            anorm: norm(a, n),
            max_sweeps,
        }
    }

    /// Deflates at a negligible subdiagonal, taking a trailing 1×1 or 2×2 block's eigenvalues
    /// into `wr`, `wi`, as long as it can; then says what comes next (for a sweep, with the
    /// shift chosen: the exceptional one after 10 and 20 sweeps).
    pub(crate) fn step<A: Entries>(
        &mut self,
        a: &mut A,
        wr: &mut [f64; N],
        wi: &mut [f64; N],
    ) -> Step {
        loop {
            let nn = self.nn;
            if nn == 0 {
                return Step::Done;
            }
            let l = small_subdiagonal(a, nn, self.anorm);
            let x = a.at(nn, nn);
            if l == nn {
                // A 1×1 block: one eigenvalue.
                wr[nn - 1] = x + self.t;
                wi[nn - 1] = 0.0;
                self.nn -= 1;
                self.its = 0;
                continue;
            }
            let y = a.at(nn - 1, nn - 1);
            let w = a.at(nn, nn - 1) * a.at(nn - 1, nn);
            if l == nn - 1 {
                let (re, im) = two_by_two(Shift { x, y, w }, self.t);
                (wr[nn - 2], wr[nn - 1]) = (re[0], re[1]);
                (wi[nn - 2], wi[nn - 1]) = (im[0], im[1]);
                self.nn -= 2;
                self.its = 0;
                continue;
            }
            if self.its == self.max_sweeps {
                return Step::Failed;
            }
            let shift = if self.its == 10 || self.its == 20 {
                exceptional_shift(a, nn, &mut self.t, x)
            } else {
                Shift { x, y, w }
            };
            self.its += 1;
            let (m, first) = sweep_start(a, l, nn, &shift);
            return Step::Sweep(Rows { l, m, nn }, first);
        }
    }
}

/// The double shift of a sweep: the trailing 2×2 block's x = a_nn, y = a_(n−1)(n−1) and
/// w = a_n(n−1) a_(n−1)n (or the exceptional shift's).
struct Shift {
    x: f64,
    y: f64,
    w: f64,
}

/// The row l of the lowest negligible subdiagonal element at or above row `nn` (set to zero),
/// or 1: where the active block starts.
fn small_subdiagonal<A: Entries>(a: &mut A, nn: usize, anorm: f64) -> usize {
    let mut l = nn;
    while l >= 2 {
        let mut s = a.at(l - 1, l - 1).abs() + a.at(l, l).abs();
        if s == 0.0 {
            s = anorm;
        }
        if a.at(l, l - 1).abs() + s == s {
            a.set(l, l - 1, 0.0);
            break;
        }
        l -= 1;
    }
    l
}

/// The eigenvalues (re, im) of a trailing 2×2 block (x = a_22, y = a_11, w = a_21 a_12), the
/// exceptional shifts `t` added back: a real pair, or a complex conjugate pair.
fn two_by_two(block: Shift, t: f64) -> ([f64; 2], [f64; 2]) {
    let Shift { x, y, w } = block;
    let p = 0.5 * (y - x);
    let q = p * p + w;
    let z = q.abs().sqrt();
    let x = x + t;
    if q >= 0.0 {
        let z = p + z.copysign(p);
        let low = if z != 0.0 { x - w / z } else { x + z };
        ([x + z, low], [0.0, 0.0])
    } else {
        ([x + p, x + p], [-z, z])
    }
}

/// The exceptional shift after 10 and 20 sweeps without a deflation: the diagonal shifted by
/// a_nn (added to `t`), and an ad hoc shift from the last subdiagonal elements.
fn exceptional_shift<A: Entries>(a: &mut A, nn: usize, t: &mut f64, x: f64) -> Shift {
    *t += x;
    for i in 1..=nn {
        a.set(i, i, a.at(i, i) - x);
    }
    let s = a.at(nn, nn - 1).abs() + a.at(nn - 1, nn - 2).abs();
    Shift {
        x: 0.75 * s,
        y: 0.75 * s,
        w: -0.4375 * s * s,
    }
}

/// Where the double-shift sweep starts: the row m ≥ l below which two consecutive subdiagonal
/// elements are small enough, and the first Householder vector (p, q, r) there.
fn sweep_start<A: Entries>(a: &A, l: usize, nn: usize, shift: &Shift) -> (usize, [f64; 3]) {
    let Shift { x, y, w } = *shift;
    let mut m = nn - 2;
    loop {
        let z = a.at(m, m);
        let r = x - z;
        let s = y - z;
        let p = (r * s - w) / a.at(m + 1, m) + a.at(m, m + 1);
        let q = a.at(m + 1, m + 1) - z - r - s;
        let r = a.at(m + 2, m + 1);
        let s = p.abs() + q.abs() + r.abs();
        let (p, q, r) = (p / s, q / s, r / s);
        if m == l {
            return (m, [p, q, r]);
        }
        let u = a.at(m, m - 1).abs() * (q.abs() + r.abs());
        let v = p.abs() * (a.at(m - 1, m - 1).abs() + z.abs() + a.at(m + 1, m + 1).abs());
        if u + v == v {
            return (m, [p, q, r]);
        }
        m -= 1;
    }
}

/// The rows a sweep works on: the active block l..=nn, the sweep starting at row m.
pub(crate) struct Rows {
    pub(crate) l: usize,
    pub(crate) m: usize,
    pub(crate) nn: usize,
}

/// One Francis double-shift QR sweep of the active block from row m, its first Householder
/// vector `first`: the bulge chased down the subdiagonal.
fn francis_sweep<const M: usize>(a: &mut [[f64; M]; M], rows: Rows, first: [f64; 3]) {
    let Rows { l, m, nn } = rows;
    for i in (m + 2)..=nn {
        a[i][i - 2] = 0.0;
        if i != m + 2 {
            a[i][i - 3] = 0.0;
        }
    }
    let [mut p, mut q, mut r] = first;
    let mut x = 0.0;
    let mut k = m;
    while k < nn {
        if k != m {
            p = a[k][k - 1];
            q = a[k + 1][k - 1];
            r = 0.0;
            if k != nn - 1 {
                r = a[k + 2][k - 1];
            }
            x = p.abs() + q.abs() + r.abs();
            if x != 0.0 {
                p /= x;
                q /= x;
                r /= x;
            }
        }
        let s = (p * p + q * q + r * r).sqrt().copysign(p);
        if s != 0.0 {
            if k == m {
                if l != m {
                    a[k][k - 1] = -a[k][k - 1];
                }
            } else {
                a[k][k - 1] = -s * x;
            }
            p += s;
            let (x, y, z) = (p / s, q / s, r / s);
            q /= p;
            r /= p;
            for j in k..=nn {
                p = a[k][j] + q * a[k + 1][j];
                if k != nn - 1 {
                    p += r * a[k + 2][j];
                    a[k + 2][j] -= p * z;
                }
                a[k + 1][j] -= p * y;
                a[k][j] -= p * x;
            }
            let mmin = if nn < k + 3 { nn } else { k + 3 };
            for i in l..=mmin {
                p = x * a[i][k] + y * a[i][k + 1];
                if k != nn - 1 {
                    p += z * a[i][k + 2];
                    a[i][k + 2] -= p * r;
                }
                a[i][k + 1] -= p * q;
                a[i][k] -= p;
            }
        }
        k += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn roots_of(c: &[f64]) -> Vec<(f64, f64)> {
        let mut h = Hessenberg::companion(c);
        h.balance();
        let (mut wr, mut wi) = ([0.0; N], [0.0; N]);
        let n = h.eigenvalues(&mut wr, &mut wi).expect("converges");
        let mut v: Vec<(f64, f64)> = (0..n).map(|k| (wr[k], wi[k])).collect();
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v
    }

    #[test]
    fn real_roots_of_a_product() {
        // (x−1)(x−2)(x−3)(x+4) = x⁴ − 2x³ − 13x² + 38x − 24
        let r = roots_of(&[-24.0, 38.0, -13.0, -2.0]);
        let want = [-4.0, 1.0, 2.0, 3.0];
        for (g, w) in r.iter().zip(want) {
            assert!((g.0 - w).abs() < 1e-12 && g.1 == 0.0, "{r:?}");
        }
    }

    #[test]
    fn complex_pairs_and_degree_eight() {
        // (x² + 1)(x² + 2x + 5)(x − 0.5)(x + 7)(x − 10)(x − 1e-3), expanded by multiplication.
        let factors: [&[f64]; 6] = [
            &[1.0, 0.0, 1.0],
            &[5.0, 2.0, 1.0],
            &[-0.5, 1.0],
            &[7.0, 1.0],
            &[-10.0, 1.0],
            &[-1e-3, 1.0],
        ];
        let mut poly = vec![1.0];
        for f in factors {
            let mut out = vec![0.0; poly.len() + f.len() - 1];
            for (i, a) in poly.iter().enumerate() {
                for (j, b) in f.iter().enumerate() {
                    out[i + j] += a * b;
                }
            }
            poly = out;
        }
        let monic: Vec<f64> = poly[..8].to_vec();
        let r = roots_of(&monic);
        let want = [
            (-7.0, 0.0),
            (-1.0, -2.0),
            (-1.0, 2.0),
            (0.0, -1.0),
            (0.0, 1.0),
            (1e-3, 0.0),
            (0.5, 0.0),
            (10.0, 0.0),
        ];
        for (g, w) in r.iter().zip(want) {
            assert!(
                (g.0 - w.0).abs() < 1e-9 && (g.1 - w.1).abs() < 1e-9,
                "{r:?}"
            );
        }
    }
}
