//! All roots of a real monic polynomial of degree ≤ 8 from the quadratic factors of a nearby
//! one, by Bairstow's method: each real quadratic factor found by Newton's method on the
//! remainder of a synthetic division, from the nearby polynomial's factor of the same place,
//! and divided out (smallest roots first); then every root certified and polished by one Newton
//! step on the polynomial itself.
//!
//! A quadratic factor x² + u x + v of p spans an invariant subspace of p's companion matrix of
//! dimension two (a 2 × 2 diagonal block of its real Schur form), so this continues the
//! eigenvalues that the Francis QR iteration of `hessenberg.rs` gives the nearby polynomial, in
//! a fraction of QR's arithmetic; but it has neither QR's guarantee of convergence nor its
//! backward stability. It therefore answers only where its roots are certified (every factor's
//! iteration converged; the Weierstrass inclusion disks, each holding exactly one root, pairwise
//! disjoint and small; no two roots within 10⁻⁶ of each other) and otherwise declines, so that a
//! caller solves by QR. Derivation: `derivations/06-roots-and-tracking.md` ("Many poses").

/// Newton iterations allowed for one quadratic factor from its seed.
const MAX_ITERATIONS: usize = 10;

/// Roots closer than this (relative, |re| + |im|) are a cluster: declined (the QR path and
/// the recovery of y treat clusters).
const DISTINCT: f64 = 1e-6;

/// A certified root's inclusion radius may be at most this, relative to 1 + |root|, before its
/// Newton step.
const RADIUS: f64 = 1e-6;

/// The quadratic factors x² + u x + v, as (u, v), in the order they are divided out.
pub type Factors = [(f64, f64); 4];

/// The roots of xⁿ + c₍ₙ₋₁₎ xⁿ⁻¹ + … + c₀ (n = `c.len()` ≤ 8) into `wr`, `wi` (real and
/// imaginary parts), each quadratic factor's Newton iteration started from `seed`'s factor of
/// the same place (the factors of a nearby polynomial of the same degree, e.g. from
/// [`factors_of`]); the factors found into `found` (a seed for the next). How many roots (n),
/// or `None` where the result is not certified (see the module documentation).
pub fn roots(
    c: &[f64],
    seed: &Factors,
    wr: &mut [f64; 8],
    wi: &mut [f64; 8],
    found: &mut Factors,
) -> Option<usize> {
    let n = c.len();
    if n > 8 || !c.iter().all(|v| v.is_finite()) {
        return None;
    }
    // The working polynomial, lowest degree first, monic of degree d.
    let mut w = [0.0; 9];
    w[..n].copy_from_slice(c);
    w[n] = 1.0;
    let mut d = n;
    let (mut k, mut stage) = (0, 0);
    while d >= 3 {
        let (u, v) = newton(&w[..=d], seed[stage])?;
        found[stage] = (u, v);
        stage += 1;
        // Deflate: w ← w / (x² + u x + v), its quotient.
        let mut q = [0.0; 9];
        divide_twice(&w[..=d], u, v, &mut q);
        w = q;
        d -= 2;
        k += quadratic(u, v, &mut wr[k..], &mut wi[k..]);
    }
    match d {
        2 => {
            found[stage] = (w[1], w[0]);
            k += quadratic(w[1], w[0], &mut wr[k..], &mut wi[k..]);
        }
        1 => {
            wr[k] = -w[0];
            wi[k] = 0.0;
            k += 1;
        }
        _ => {}
    }
    debug_assert_eq!(k, n);
    certify(c, &mut wr[..n], &mut wi[..n])?;
    Some(n)
}

/// The real quadratic factors of the polynomial whose roots are `wr`, `wi` (conjugate pairs
/// adjacent, as `hessenberg.rs` gives them): each complex pair one factor, the real roots
/// paired in order of modulus (the largest left alone where their number is odd), the factors
/// in order of their smaller root's modulus — smallest first, so that dividing them out is
/// stable. `false` if the roots are not in conjugate pairs.
pub fn factors_of(wr: &[f64], wi: &[f64], out: &mut Factors) -> bool {
    let n = wr.len();
    // (modulus, u, v) of each factor; real roots first gathered.
    let mut units: [(f64, f64, f64); 8] = [(0.0, 0.0, 0.0); 8];
    let (mut nu, mut reals, mut nr) = (0, [0.0; 8], 0);
    let mut k = 0;
    while k < n {
        if wi[k] == 0.0 {
            reals[nr] = wr[k];
            nr += 1;
            k += 1;
        } else {
            if k + 1 >= n || wr[k + 1] != wr[k] || wi[k + 1] != -wi[k] {
                return false;
            }
            let (a, b) = (wr[k], wi[k]);
            units[nu] = ((a * a + b * b).sqrt(), -2.0 * a, a * a + b * b);
            nu += 1;
            k += 2;
        }
    }
    let reals = &mut reals[..nr];
    reals.sort_unstable_by(|a, b| a.abs().total_cmp(&b.abs()));
    for pair in reals.chunks_exact(2) {
        units[nu] = (pair[0].abs(), -(pair[0] + pair[1]), pair[0] * pair[1]);
        nu += 1;
    }
    let units = &mut units[..nu];
    units.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    for (o, u) in out.iter_mut().zip(units.iter()) {
        *o = (u.1, u.2);
    }
    true
}

/// The quotient q (into `q[..d − 1]`) and remainder r1 x + r0 of the monic `w` (degree d ≥ 3)
/// by D = x² + u x + v (synthetic division), and the remainder h1 x + h0 of q by D: both
/// divisions in one loop (q's coefficients come from the top down, so the second division
/// follows two behind the first and the two recurrences overlap).
#[inline]
fn divide_twice(w: &[f64], u: f64, v: f64, q: &mut [f64; 9]) -> (f64, f64, f64, f64) {
    let d = w.len() - 1;
    let (mut b1, mut b2) = (0.0, 0.0); // q[k + 1], q[k + 2]
    let (mut g1, mut g2) = (0.0, 0.0); // the second quotient's g[k + 1], g[k + 2]
    for k in (0..d - 1).rev() {
        let b = w[k + 2] - u * b1 - v * b2;
        q[k] = b;
        b2 = b1;
        b1 = b;
        if k + 4 <= d {
            let g = q[k + 2] - u * g1 - v * g2;
            g2 = g1;
            g1 = g;
        }
    }
    // q[0] = b1, q[1] = b2; g[0] = g1, g[1] = g2 (zero where q is linear: its own remainder).
    (
        w[1] - u * b1 - v * b2,
        w[0] - v * b1,
        b2 - u * g1 - v * g2,
        b1 - v * g1,
    )
}

/// A quadratic factor x² + u x + v of the monic `w` (degree ≥ 3) by Newton's method on the
/// remainder R(u, v) = r1 x + r0 of the division from `start`: with q the quotient,
/// ∂R/∂v = −(q mod D) and ∂R/∂u = −(x q mod D), D = x² + u x + v (derivations/06). `None` if it
/// does not converge within [`MAX_ITERATIONS`].
fn newton(w: &[f64], (mut u, mut v): (f64, f64)) -> Option<(f64, f64)> {
    if !(u.is_finite() && v.is_finite()) {
        return None;
    }
    let mut last = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let (r1, r0, h1, h0) = divide_twice(w, u, v, &mut [0.0; 9]);
        // J [du, dv]ᵀ = −[r1, r0]ᵀ with J = [[−(h0 − u h1), −h1], [v h1, −h0]].
        let (j11, j12, j21, j22) = (-(h0 - u * h1), -h1, v * h1, -h0);
        let (mut du, mut dv) = solve2(j11, j12, j21, j22, -r1, -r0);
        if !(du.is_finite() && dv.is_finite()) {
            // Each row scaled to entries of at most one: products of two rows' entries leave
            // the doubles' range where the roots are large (entries grow as |root|^(d−2)).
            let (s1, s2) = (j11.abs().max(j12.abs()), j21.abs().max(j22.abs()));
            (du, dv) = solve2(j11 / s1, j12 / s1, j21 / s2, j22 / s2, -r1 / s1, -r0 / s2);
        }
        u += du;
        v += dv;
        // The step relative to the factor's roots: their scale s = max(|u|, √|v|) (u is a sum
        // of two roots, v a product), so du against s and dv against s².
        let scale = u.abs().max(v.abs().sqrt()).max(f64::MIN_POSITIVE);
        let step = (du.abs() / scale).max(dv.abs() / (scale * scale));
        if !step.is_finite() {
            return None;
        }
        // Converged: Newton's error after a step of 10⁻⁶ is of order its square (10⁻¹²), which
        // the certificate's Newton step on p itself takes to round-off; or a step no longer
        // shrinking once small.
        if step <= 1e-6 || (step >= last && step <= 1e-4) {
            return Some((u, v));
        }
        last = step;
    }
    None
}

/// The solution of [[a, b], [c, d]] [x, y]ᵀ = [e, f]ᵀ by Cramer's rule (NaN where singular).
#[inline]
fn solve2(a: f64, b: f64, c: f64, d: f64, e: f64, f: f64) -> (f64, f64) {
    let det = a * d - b * c;
    if det == 0.0 {
        return (f64::NAN, f64::NAN);
    }
    ((e * d - b * f) / det, (a * f - e * c) / det)
}

/// The roots of x² + u x + v into `wr[..2]`, `wi[..2]` without cancellation; 2.
#[inline]
fn quadratic(u: f64, v: f64, wr: &mut [f64], wi: &mut [f64]) -> usize {
    let h = -0.5 * u;
    let disc = h * h - v;
    if disc >= 0.0 {
        let s = disc.sqrt();
        let big = if h >= 0.0 { h + s } else { h - s };
        wr[0] = big;
        wr[1] = if big != 0.0 { v / big } else { 0.0 };
        wi[0] = 0.0;
        wi[1] = 0.0;
    } else {
        let s = (-disc).sqrt();
        wr[0] = h;
        wr[1] = h;
        wi[0] = s;
        wi[1] = -s;
    }
    2
}

/// p(z), p'(z) and Σ|terms| (a bound on p's rounding, in real arithmetic from |z|) of the
/// monic p (coefficients `c`, the leading 1 implied) at z = (re, im).
#[inline]
fn eval(c: &[f64], re: f64, im: f64) -> ((f64, f64), (f64, f64), f64) {
    let az = (re * re + im * im).sqrt();
    let (mut pr, mut pi) = (1.0, 0.0);
    let (mut dr, mut di) = (0.0, 0.0);
    let mut m = 1.0;
    for &a in c.iter().rev() {
        // p' ← p' z + p, p ← p z + a.
        let (ndr, ndi) = (dr * re - di * im + pr, dr * im + di * re + pi);
        dr = ndr;
        di = ndi;
        let (npr, npi) = (pr * re - pi * im + a, pr * im + pi * re);
        pr = npr;
        pi = npi;
        m = m * az + a.abs();
    }
    ((pr, pi), (dr, di), m)
}

/// Certifies the roots `wr`, `wi` of the monic p (`c`) and polishes them by one Newton step on
/// p itself (a deflated factor carries the rounding of the factors divided out before it).
///
/// The certificate is the Weierstrass inclusion: with W_i = p(z_i) / Π_{j≠i} (z_i − z_j), the
/// disks |z − z_i| ≤ n |W_i| contain all roots of p, and where they are pairwise disjoint each
/// holds exactly one (derivations/06). p(z_i) is bounded with its rounding error (4 n ε
/// Σ|terms|); a modulus by |re| + |im| above and by (|re| + |im|)/√2 below. Required besides:
/// every radius within [`RADIUS`] of 1 + |z_i|, every Newton step within its disk, and no two
/// roots within [`DISTINCT`] (a cluster, which the caller treats otherwise).
fn certify(c: &[f64], wr: &mut [f64], wi: &mut [f64]) -> Option<()> {
    let n = wr.len();
    let mut radius = [0.0; 8];
    let mut step = [(0.0, 0.0); 8];
    let rounding = 4.0 * n as f64 * f64::EPSILON;
    for i in 0..n {
        // The second of a conjugate pair mirrors the first (p is real, the roots closed under
        // conjugation).
        if i > 0 && wi[i] != 0.0 && wi[i] == -wi[i - 1] && wr[i] == wr[i - 1] {
            radius[i] = radius[i - 1];
            step[i] = (step[i - 1].0, -step[i - 1].1);
            continue;
        }
        let (p, (sr, si)) = if wi[i] == 0.0 {
            let (v, d, m) = eval_real(c, wr[i]);
            (v.abs() + rounding * m, (v / d, 0.0))
        } else {
            let ((pr, pi), (dr, di), m) = eval(c, wr[i], wi[i]);
            // |p| and p / p' by their squares, or where those leave the doubles' range (the
            // roots large or small), by `hypot` and p' scaled to at most one.
            let (p2, den) = (pr * pr + pi * pi, dr * dr + di * di);
            if p2.is_normal() && den.is_normal() {
                (
                    p2.sqrt() + rounding * m,
                    ((pr * dr + pi * di) / den, (pi * dr - pr * di) / den),
                )
            } else {
                let k = dr.abs().max(di.abs());
                let (dr, di) = (dr / k, di / k);
                let den = dr * dr + di * di;
                (
                    pr.hypot(pi) + rounding * m,
                    ((pr * dr + pi * di) / den / k, (pi * dr - pr * di) / den / k),
                )
            }
        };
        // |Π_{j≠i} (z_i − z_j)|, by its square in real arithmetic; where that leaves the range
        // of doubles (roots beyond 10²² or within 10⁻²² of each other), modulus by modulus.
        let gap = |j: usize| {
            let (ar, ai) = (wr[i] - wr[j], wi[i] - wi[j]);
            ar * ar + ai * ai
        };
        let others = (0..n).filter(|&j| j != i);
        let mut g = others.clone().map(gap).product::<f64>().sqrt();
        if !(g.is_normal()) {
            g = others.map(|j| gap(j).sqrt()).product();
        }
        // A product still out of range bounds nothing: declined.
        if !(g.is_normal()) {
            return None;
        }
        // Inflated by (1 + 8 n ε) for the rounding of this quotient and of g itself.
        radius[i] = n as f64 * p / g * (1.0 + 8.0 * rounding);
        let size = 1.0 + wr[i].abs() + wi[i].abs();
        if !(radius[i] <= RADIUS * size && sr.abs() + si.abs() <= radius[i]) {
            return None;
        }
        step[i] = (sr, si);
    }
    for i in 0..n {
        for j in i + 1..n {
            let gap = (wr[i] - wr[j]).abs() + (wi[i] - wi[j]).abs();
            if gap <= DISTINCT * (1.0 + wr[i].abs() + wi[i].abs())
                || gap * std::f64::consts::FRAC_1_SQRT_2 <= radius[i] + radius[j]
            {
                return None;
            }
        }
    }
    for i in 0..n {
        wr[i] -= step[i].0;
        // A real root stays real (its step is real); a pair's steps are conjugate.
        wi[i] -= step[i].1;
    }
    Some(())
}

/// [`eval`] at a real x, in real arithmetic.
#[inline]
fn eval_real(c: &[f64], x: f64) -> (f64, f64, f64) {
    let (mut p, mut d, mut m) = (1.0, 0.0, 1.0);
    let ax = x.abs();
    for &a in c.iter().rev() {
        d = d * x + p;
        p = p * x + a;
        m = m * ax + a.abs();
    }
    (p, d, m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The monic polynomial with the given roots (conjugate pairs included by the caller).
    fn from_roots(r: &[(f64, f64)]) -> Vec<f64> {
        // Complex coefficients, highest last.
        let mut p = vec![(1.0f64, 0.0f64)];
        for &(a, b) in r {
            let mut next = vec![(0.0, 0.0); p.len() + 1];
            for (k, &(pr, pi)) in p.iter().enumerate() {
                next[k + 1].0 += pr;
                next[k + 1].1 += pi;
                next[k].0 -= pr * a - pi * b;
                next[k].1 -= pr * b + pi * a;
            }
            p = next;
        }
        p[..p.len() - 1].iter().map(|c| c.0).collect()
    }

    fn sorted(wr: &[f64], wi: &[f64]) -> Vec<(f64, f64)> {
        let mut v: Vec<(f64, f64)> = wr.iter().copied().zip(wi.iter().copied()).collect();
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v
    }

    const WANT: [(f64, f64); 8] = [
        (-3.0, 0.0),
        (-0.5, 0.0),
        (0.25, 0.0),
        (2.0, 0.0),
        (1.0, 2.0),
        (1.0, -2.0),
        (-0.3, 0.7),
        (-0.3, -0.7),
    ];

    /// The factors of `WANT`, each (u, v) moved by `by` relative.
    fn seed(by: f64) -> Factors {
        let (wr, wi): (Vec<f64>, Vec<f64>) = WANT.iter().copied().unzip();
        let mut f = [(0.0, 0.0); 4];
        assert!(factors_of(&wr, &wi, &mut f));
        f.map(|(u, v)| (u * (1.0 + by), v * (1.0 - by)))
    }

    #[test]
    fn roots_are_found_from_the_factors_of_a_nearby_polynomial() {
        let c = from_roots(&WANT);
        let (mut wr, mut wi, mut found) = ([0.0; 8], [0.0; 8], [(0.0, 0.0); 4]);
        assert_eq!(
            roots(&c, &seed(0.05), &mut wr, &mut wi, &mut found),
            Some(8)
        );
        let mut w = WANT.to_vec();
        w.sort_by(|a, b| a.partial_cmp(b).unwrap());
        for (g, e) in sorted(&wr, &wi).iter().zip(&w) {
            assert!((g.0 - e.0).abs() + (g.1 - e.1).abs() < 1e-14, "{g:?} {e:?}");
        }
        // The factors found are the exact ones, in the seed's order.
        for (f, s) in found.iter().zip(seed(0.0)) {
            assert!((f.0 - s.0).abs() + (f.1 - s.1).abs() < 1e-13, "{f:?} {s:?}");
        }
    }

    #[test]
    fn factors_pair_conjugates_and_real_roots_by_modulus_smallest_first() {
        let mut f = [(9.0, 9.0); 4];
        // Roots −3, 0.5 ± i, 0.25, 2 (degree 5): {0.25, 2} first (0.25), the pair (|z| ≈ 1.12).
        let (wr, wi) = ([0.25, 0.5, 0.5, 2.0, -3.0], [0.0, 1.0, -1.0, 0.0, 0.0]);
        assert!(factors_of(&wr, &wi, &mut f));
        assert_eq!(&f[..2], &[(-2.25, 0.5), (-1.0, 1.25)]);
        // −3, the largest real root, is left alone.
        assert_eq!(&f[2..], &[(9.0, 9.0); 2]);
        // Not conjugate pairs.
        assert!(!factors_of(&[0.5, 0.6], &[1.0, -1.0], &mut f));
    }

    #[test]
    fn a_double_root_or_a_coefficient_not_finite_is_declined() {
        let (mut wr, mut wi, mut found) = ([0.0; 8], [0.0; 8], [(0.0, 0.0); 4]);
        // (x − 1)² (x − 2)(x + 3): a double root, within 10⁻⁶ of itself.
        let c = from_roots(&[(1.0, 0.0), (1.0, 0.0), (2.0, 0.0), (-3.0, 0.0)]);
        let f = [(-2.0, 1.0), (1.0, -6.0), (0.0, 0.0), (0.0, 0.0)];
        assert_eq!(roots(&c, &f, &mut wr, &mut wi, &mut found), None);
        // Not finite.
        assert_eq!(
            roots(&[f64::NAN, 1.0, 0.0], &f, &mut wr, &mut wi, &mut found),
            None
        );
    }

    #[test]
    fn roots_whose_disks_overlap_are_not_certified() {
        // Roots 1 and 1 + 2.5·10⁻⁶ (apart by more than 10⁻⁶ of 1 + |z|), each approximation
        // 4·10⁻⁷ outside: each disk (radius 1.4·10⁻⁶) is within the bound and each Newton step
        // within its disk, but the two disks overlap, so that neither is known to hold exactly
        // one root.
        let want = [(1.0, 0.0), (1.0 + 2.5e-6, 0.0), (-2.0, 0.0), (4.0, 0.0)];
        let c = from_roots(&want);
        let (mut wr, mut wi): (Vec<f64>, Vec<f64>) = want.iter().copied().unzip();
        assert_eq!(certify(&c, &mut wr.clone(), &mut wi.clone()), Some(()));
        wr[0] -= 4e-7;
        wr[1] += 4e-7;
        assert_eq!(certify(&c, &mut wr, &mut wi), None);
    }

    #[test]
    fn roots_of_odd_degree_leave_the_largest_real_root_to_the_last_division() {
        let want = [(0.5, 0.0), (-1.5, 0.0), (1.0, 1.0), (1.0, -1.0), (4.0, 0.0)];
        let c = from_roots(&want);
        let (wr, wi): (Vec<f64>, Vec<f64>) = want.iter().copied().unzip();
        let mut f = [(0.0, 0.0); 4];
        assert!(factors_of(&wr, &wi, &mut f));
        let f = f.map(|(u, v)| (u * 1.01, v * 0.99));
        let (mut gr, mut gi, mut found) = ([0.0; 8], [0.0; 8], [(0.0, 0.0); 4]);
        assert_eq!(roots(&c, &f, &mut gr, &mut gi, &mut found), Some(5));
        let mut w = want.to_vec();
        w.sort_by(|a, b| a.partial_cmp(b).unwrap());
        for (g, e) in sorted(&gr[..5], &gi[..5]).iter().zip(&w) {
            assert!((g.0 - e.0).abs() + (g.1 - e.1).abs() < 1e-14, "{g:?} {e:?}");
        }
    }

    #[test]
    fn a_root_found_twice_and_one_missed_is_not_certified() {
        let c = from_roots(&WANT);
        let (mut wr, mut wi): (Vec<f64>, Vec<f64>) = WANT.iter().copied().unzip();
        // As found: certified, and unchanged to round-off by the Newton step.
        assert_eq!(certify(&c, &mut wr.clone(), &mut wi.clone()), Some(()));
        // 2 found twice (the second 10⁻³ away), −3 missed: the disks of the two near 2 are
        // large (R is far from zero 10⁻³ from a simple root) and overlap.
        wr[0] = 2.001;
        assert_eq!(certify(&c, &mut wr, &mut wi), None);
    }

    #[test]
    fn roots_certified_from_a_seed_are_the_roots_of_the_polynomial() {
        let mut s = 11u64;
        let mut uniform = |lo: f64, hi: f64| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            lo + (hi - lo) * ((s >> 11) as f64 / (1u64 << 53) as f64)
        };
        let (mut certified, mut tried) = (0, 0);
        while tried < 500 {
            // Four real roots and two complex pairs in [−10, 10], at least 0.1 apart.
            let mut want: Vec<(f64, f64)> = (0..4).map(|_| (uniform(-10.0, 10.0), 0.0)).collect();
            for _ in 0..2 {
                let (a, b) = (uniform(-10.0, 10.0), uniform(0.1, 5.0));
                want.extend([(a, b), (a, -b)]);
            }
            let apart = want.iter().enumerate().all(|(i, a)| {
                want[i + 1..]
                    .iter()
                    .all(|b| (a.0 - b.0).hypot(a.1 - b.1) > 0.1)
            });
            if !apart {
                continue;
            }
            tried += 1;
            let c = from_roots(&want);
            let (wr, wi): (Vec<f64>, Vec<f64>) = want.iter().copied().unzip();
            let mut seed = [(0.0, 0.0); 4];
            assert!(factors_of(&wr, &wi, &mut seed));
            // A nearby polynomial's factors: each moved by up to 1 % of its size.
            let seed = seed.map(|(u, v)| {
                let size = u.abs() + v.abs();
                (
                    u + 0.01 * size * uniform(-1.0, 1.0),
                    v + 0.01 * size * uniform(-1.0, 1.0),
                )
            });
            let (mut gr, mut gi, mut found) = ([0.0; 8], [0.0; 8], [(0.0, 0.0); 4]);
            if roots(&c, &seed, &mut gr, &mut gi, &mut found).is_none() {
                continue;
            }
            certified += 1;
            // Each true root has one of ours within 10⁻⁹ (relative to 1 + |root|; the
            // coefficients carry their own rounding), and no two of ours share one.
            let mut taken = [false; 8];
            for &(a, b) in &want {
                let k = (0..8)
                    .filter(|&k| !taken[k])
                    .min_by(|&i, &j| {
                        let d = |k: usize| (gr[k] - a).hypot(gi[k] - b);
                        d(i).total_cmp(&d(j))
                    })
                    .unwrap();
                taken[k] = true;
                let gap = (gr[k] - a).hypot(gi[k] - b);
                assert!(gap <= 1e-9 * (1.0 + a.hypot(b)), "{want:?}: {gap:e}");
            }
        }
        // Most seeds 1 % off converge and are certified.
        assert!(certified >= 450, "{certified} of {tried} certified");
    }

    #[test]
    fn roots_far_beyond_the_range_of_their_products_square_are_still_certified_soundly() {
        // Roots near 10²⁵: |Π (z_i − z_j)|² is about 10³⁵⁰, beyond the doubles; R's
        // coefficients (up to 10²⁰⁰) and values are not.
        let want: Vec<(f64, f64)> = WANT.iter().map(|&(a, b)| (a * 1e25, b * 1e25)).collect();
        let c = from_roots(&want);
        assert!(c.iter().all(|v| v.is_finite()));
        let (wr, wi): (Vec<f64>, Vec<f64>) = want.iter().copied().unzip();
        let mut seed = [(0.0, 0.0); 4];
        assert!(factors_of(&wr, &wi, &mut seed));
        let (mut gr, mut gi, mut found) = ([0.0; 8], [0.0; 8], [(0.0, 0.0); 4]);
        assert_eq!(roots(&c, &seed, &mut gr, &mut gi, &mut found), Some(8));
        // A root found twice and one missed, at that scale, is refused (its disk is not
        // shrunk to nothing by an overflowing product).
        let (mut wr, mut wi) = (wr, wi);
        wr[0] = 2.001e25;
        assert_eq!(certify(&c, &mut wr, &mut wi), None);
    }
}
