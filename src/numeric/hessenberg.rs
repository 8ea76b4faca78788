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

/// A Hessenberg matrix of order `n ≤ N`, 1-based storage (row and column 0 unused) so that the
/// classic algorithm reads as published.
pub struct Hessenberg {
    a: [[f64; N + 1]; N + 1],
    n: usize,
}

const RADIX: f64 = 2.0;

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
    /// eigenvalue), which for these matrices signals a defect upstream.
    #[allow(clippy::many_single_char_names)]
    pub fn eigenvalues(mut self, wr: &mut [f64; N], wi: &mut [f64; N]) -> Option<usize> {
        let n = self.n;
        let a = &mut self.a;
        let mut anorm = 0.0;
        for i in 1..=n {
            for j in (i.max(2) - 1)..=n {
                anorm += a[i][j].abs();
            }
        }
        let mut nn = n;
        let mut t = 0.0;
        let (mut p, mut q, mut r): (f64, f64, f64);
        let (mut x, mut y, mut z);
        let mut w;
        while nn >= 1 {
            let mut its = 0;
            let mut l;
            loop {
                l = nn;
                while l >= 2 {
                    let mut s = a[l - 1][l - 1].abs() + a[l][l].abs();
                    if s == 0.0 {
                        s = anorm;
                    }
                    if a[l][l - 1].abs() + s == s {
                        a[l][l - 1] = 0.0;
                        break;
                    }
                    l -= 1;
                }
                x = a[nn][nn];
                if l == nn {
                    wr[nn - 1] = x + t;
                    wi[nn - 1] = 0.0;
                    nn -= 1;
                } else {
                    y = a[nn - 1][nn - 1];
                    w = a[nn][nn - 1] * a[nn - 1][nn];
                    if l == nn - 1 {
                        p = 0.5 * (y - x);
                        q = p * p + w;
                        z = q.abs().sqrt();
                        x += t;
                        if q >= 0.0 {
                            z = p + z.copysign(p);
                            wr[nn - 2] = x + z;
                            wr[nn - 1] = x + z;
                            if z != 0.0 {
                                wr[nn - 1] = x - w / z;
                            }
                            wi[nn - 2] = 0.0;
                            wi[nn - 1] = 0.0;
                        } else {
                            wr[nn - 2] = x + p;
                            wr[nn - 1] = x + p;
                            wi[nn - 2] = -z;
                            wi[nn - 1] = z;
                        }
                        nn -= 2;
                    } else {
                        if its == 30 {
                            return None;
                        }
                        if its == 10 || its == 20 {
                            // Exceptional shift.
                            t += x;
                            for i in 1..=nn {
                                a[i][i] -= x;
                            }
                            let s = a[nn][nn - 1].abs() + a[nn - 1][nn - 2].abs();
                            x = 0.75 * s;
                            y = x;
                            w = -0.4375 * s * s;
                        }
                        its += 1;
                        let mut m = nn - 2;
                        loop {
                            z = a[m][m];
                            r = x - z;
                            let s = y - z;
                            p = (r * s - w) / a[m + 1][m] + a[m][m + 1];
                            q = a[m + 1][m + 1] - z - r - s;
                            r = a[m + 2][m + 1];
                            let s = p.abs() + q.abs() + r.abs();
                            p /= s;
                            q /= s;
                            r /= s;
                            if m == l {
                                break;
                            }
                            let u = a[m][m - 1].abs() * (q.abs() + r.abs());
                            let v =
                                p.abs() * (a[m - 1][m - 1].abs() + z.abs() + a[m + 1][m + 1].abs());
                            if u + v == v {
                                break;
                            }
                            m -= 1;
                        }
                        for i in (m + 2)..=nn {
                            a[i][i - 2] = 0.0;
                            if i != m + 2 {
                                a[i][i - 3] = 0.0;
                            }
                        }
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
                                x = p / s;
                                y = q / s;
                                z = r / s;
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
                }
                if l + 1 >= nn {
                    break;
                }
            }
        }
        Some(n)
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
