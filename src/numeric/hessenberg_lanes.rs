//! Eigenvalues of many small upper Hessenberg matrices at once: the balancing and Francis QR
//! iteration of `hessenberg.rs` run on [`LANES`] matrices in lockstep, each in its own lane of
//! a structure of arrays (entry (i, j) of every lane side by side), so that the compiler
//! vectorises a sweep across matrices with plain arrays.
//!
//! Each lane deflates on its own: the choice of shift, the deflation and the eigenvalues of a
//! trailing block are the one-matrix version's own code run on that lane (`Progress::step`);
//! only the balancing passes and the sweeps run in lockstep. Where a lane is outside its own
//! active rows, or not sweeping at all, its entries are kept by a bitwise select, and where it is
//! inside them it performs the one-matrix operations in the same order (Rust never fuses a
//! multiply and an add), so every lane's eigenvalues are those of the one-matrix version to the
//! last bit. A matrix that does not converge is reported as such, as the one-matrix
//! version reports it.

#![allow(clippy::needless_range_loop)]

use super::hessenberg::{Entries, Hessenberg, N, Progress, RADIX, Rows, Step};

/// Matrices iterated together.
pub const LANES: usize = 4;

/// One entry of every lane.
type V = [f64; LANES];
/// A lane mask: all ones where the lane takes the new value, zero where it keeps the old.
type Mask = [u64; LANES];

/// The lanes' storage, 1-based as in `hessenberg.rs`, with two rows and columns of zeros
/// beyond N that a sweep's third row (`a[k + 2]`) may read but never keeps.
type Block = [[V; N + 3]; N + 3];

/// The eigenvalues of one matrix: `n` of them as (re, im) in `wr`, `wi`, as
/// `Hessenberg::eigenvalues` gives them; `None` where the iteration did not converge.
pub type Eigenvalues = Option<([f64; N], [f64; N], usize)>;

#[inline(always)]
fn select(m: &Mask, new: &V, old: &V) -> V {
    let mut out = [0.0; LANES];
    for k in 0..LANES {
        out[k] = f64::from_bits((new[k].to_bits() & m[k]) | (old[k].to_bits() & !m[k]));
    }
    out
}

#[inline(always)]
fn mask(f: impl Fn(usize) -> bool) -> Mask {
    let mut m = [0; LANES];
    for k in 0..LANES {
        m[k] = if f(k) { u64::MAX } else { 0 };
    }
    m
}

#[inline(always)]
fn and(a: &Mask, b: &Mask) -> Mask {
    let mut m = [0; LANES];
    for k in 0..LANES {
        m[k] = a[k] & b[k];
    }
    m
}

#[inline(always)]
fn map2(a: &V, b: &V, f: impl Fn(f64, f64) -> f64) -> V {
    let mut out = [0.0; LANES];
    for k in 0..LANES {
        out[k] = f(a[k], b[k]);
    }
    out
}

/// One lane of a block, as a matrix of its own for the one-matrix steps.
struct Lane<'a> {
    a: &'a mut Block,
    lane: usize,
}

impl Entries for Lane<'_> {
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        self.a[i][j][self.lane]
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, v: f64) {
        self.a[i][j][self.lane] = v;
    }
}

/// Buffers reused from one batch to the next: the balanced matrices.
#[derive(Default)]
pub struct Scratch {
    balanced: Vec<([[f64; N + 1]; N + 1], usize)>,
}

/// The eigenvalues of each matrix of `matrices` into `out` (cleared first, one item a matrix,
/// in order), exactly as `m.balance()` then `m.eigenvalues(..)` give them one at a time when
/// `max_sweeps` is `hessenberg.rs`'s `MAX_SWEEPS`: a matrix is given up after `max_sweeps`
/// sweeps without a deflation.
pub fn eigenvalues(
    matrices: &[Hessenberg],
    out: &mut Vec<Eigenvalues>,
    scratch: &mut Scratch,
    max_sweeps: usize,
) {
    scratch.balanced.clear();
    for group in matrices.chunks(LANES) {
        balance_group(group, &mut scratch.balanced);
    }
    out.clear();
    out.resize(matrices.len(), None);
    iterate(&scratch.balanced, out, max_sweeps);
}

/// Balances up to [`LANES`] matrices together and appends them, balanced, to `balanced`.
fn balance_group(group: &[Hessenberg], balanced: &mut Vec<([[f64; N + 1]; N + 1], usize)>) {
    let mut a: Block = [[[0.0; LANES]; N + 3]; N + 3];
    let mut n = 0;
    for (lane, m) in group.iter().enumerate() {
        let (entries, order) = m.parts();
        n = n.max(order);
        for i in 1..=order {
            for j in 1..=order {
                a[i][j][lane] = entries[i][j];
            }
        }
    }
    balance(&mut a, n);
    for (lane, m) in group.iter().enumerate() {
        let mut entries = [[0.0; N + 1]; N + 1];
        let order = m.parts().1;
        for i in 1..=order {
            for j in 1..=order {
                entries[i][j] = a[i][j][lane];
            }
        }
        balanced.push((entries, order));
    }
}

/// `Hessenberg::balance` on every lane at once, rows and columns 1..=n (a lane of a smaller
/// order has zeros beyond it, which add nothing to its sums and are never scaled into values).
/// A lane already balanced makes passes that change nothing while the others finish.
fn balance(a: &mut Block, n: usize) {
    let sqrdx = RADIX * RADIX;
    let mut done = false;
    while !done {
        done = true;
        for i in 1..=n {
            let (mut r, mut c) = ([0.0; LANES], [0.0; LANES]);
            for j in 1..=n {
                if j != i {
                    c = map2(&c, &a[j][i], |c, v| c + v.abs());
                    r = map2(&r, &a[i][j], |r, v| r + v.abs());
                }
            }
            let usable = mask(|k| c[k] != 0.0 && r[k] != 0.0);
            if usable == [0; LANES] {
                continue;
            }
            let mut g = r.map(|r| r / RADIX);
            let mut f = [1.0; LANES];
            let s = map2(&c, &r, |c, r| c + r);
            loop {
                let m = and(&usable, &mask(|k| c[k] < g[k]));
                if m == [0; LANES] {
                    break;
                }
                f = select(&m, &f.map(|f| f * RADIX), &f);
                c = select(&m, &c.map(|c| c * sqrdx), &c);
            }
            g = r.map(|r| r * RADIX);
            loop {
                let m = and(&usable, &mask(|k| c[k] > g[k]));
                if m == [0; LANES] {
                    break;
                }
                f = select(&m, &f.map(|f| f / RADIX), &f);
                c = select(&m, &c.map(|c| c / sqrdx), &c);
            }
            let scale = and(&usable, &mask(|k| (c[k] + r[k]) / f[k] < 0.95 * s[k]));
            if scale == [0; LANES] {
                continue;
            }
            done = false;
            let g = f.map(|f| 1.0 / f);
            for j in 1..=n {
                a[i][j] = select(&scale, &map2(&a[i][j], &g, |v, g| v * g), &a[i][j]);
            }
            for row in 1..=n {
                a[row][i] = select(&scale, &map2(&a[row][i], &f, |v, f| v * f), &a[row][i]);
            }
        }
    }
}

/// A lane's matrix: which one of the batch, its progress and its eigenvalues so far.
struct Slot {
    matrix: usize,
    progress: Progress,
    wr: [f64; N],
    wi: [f64; N],
}

/// The QR iteration of every balanced matrix, [`LANES`] at a time: each lane deflates on its
/// own until it needs a sweep, then the lanes that do sweep together, until every lane's matrix
/// is done (or given up); then the next [`LANES`]. (A lane given the next matrix as soon as its
/// own is done would sweep an 8×8 window beside lanes near their end, and the lockstep sweep
/// costs the union of the lanes' windows: slower, measured.)
fn iterate(
    balanced: &[([[f64; N + 1]; N + 1], usize)],
    out: &mut [Eigenvalues],
    max_sweeps: usize,
) {
    let mut a: Block = [[[0.0; LANES]; N + 3]; N + 3];
    let mut slots: [Option<Slot>; LANES] = [const { None }; LANES];
    let mut next = 0;
    loop {
        if slots.iter().all(Option::is_none) {
            // The next group, all lanes starting together.
            if next == balanced.len() {
                return;
            }
            for lane in 0..LANES.min(balanced.len() - next) {
                let mut view = Lane { a: &mut a, lane };
                let (entries, n) = &balanced[next];
                for i in 0..=N {
                    for j in 0..=N {
                        view.set(i, j, entries[i][j]);
                    }
                }
                slots[lane] = Some(Slot {
                    matrix: next,
                    progress: Progress::new(&view, *n, max_sweeps),
                    wr: [0.0; N],
                    wi: [0.0; N],
                });
                next += 1;
            }
        }
        let mut sweeps: [Option<(Rows, [f64; 3])>; LANES] = [const { None }; LANES];
        for lane in 0..LANES {
            let mut view = Lane { a: &mut a, lane };
            while let Some(slot) = &mut slots[lane] {
                match slot.progress.step(&mut view, &mut slot.wr, &mut slot.wi) {
                    Step::Sweep(rows, first) => {
                        sweeps[lane] = Some((rows, first));
                        break;
                    }
                    Step::Done => {
                        out[slot.matrix] = Some((slot.wr, slot.wi, balanced[slot.matrix].1));
                        slots[lane] = None;
                    }
                    Step::Failed => {
                        out[slot.matrix] = None;
                        slots[lane] = None;
                    }
                }
            }
        }
        if sweeps.iter().any(Option::is_some) {
            sweep(&mut a, &sweeps);
        }
    }
}

/// `francis_sweep` of `hessenberg.rs` on every lane that has a sweep to make, each on its own
/// rows: k runs over the union of the lanes' ranges, and a lane outside its own keeps its
/// entries.
fn sweep(a: &mut Block, sweeps: &[Option<(Rows, [f64; 3])>; LANES]) {
    let none = (usize::MAX, usize::MAX, 0);
    let rows: [(usize, usize, usize); LANES] = std::array::from_fn(|k| match &sweeps[k] {
        Some((r, _)) => (r.l, r.m, r.nn),
        None => none,
    });
    let (mut kmin, mut kmax, mut lmin) = (usize::MAX, 0, usize::MAX);
    for (lane, &(l, m, nn)) in rows.iter().enumerate() {
        if sweeps[lane].is_none() {
            continue;
        }
        (kmin, kmax, lmin) = (kmin.min(m), kmax.max(nn), lmin.min(l));
        for i in (m + 2)..=nn {
            a[i][i - 2][lane] = 0.0;
            if i != m + 2 {
                a[i][i - 3][lane] = 0.0;
            }
        }
    }
    let first =
        |i: usize| -> V { std::array::from_fn(|k| sweeps[k].as_ref().map_or(0.0, |(_, f)| f[i])) };
    let (mut p, mut q, mut r) = (first(0), first(1), first(2));
    let mut x = [0.0; LANES];
    for k in kmin..kmax {
        let on = mask(|j| rows[j].1 <= k && k < rows[j].2);
        let at_m = mask(|j| k == rows[j].1);
        let not_last = mask(|j| k + 1 != rows[j].2);
        // Rows k.. of the bulge: its Householder vector (the first one given at k = m).
        let reload = mask(|j| on[j] != 0 && at_m[j] == 0);
        let pk = a[k][k - 1];
        let qk = a[k + 1][k - 1];
        let rk = select(&not_last, &a[k + 2][k - 1], &[0.0; LANES]);
        let xk: V = std::array::from_fn(|j| pk[j].abs() + qk[j].abs() + rk[j].abs());
        let nonzero = mask(|j| xk[j] != 0.0);
        let scaled = |v: &V| select(&nonzero, &map2(v, &xk, |v, x| v / x), v);
        p = select(&reload, &scaled(&pk), &p);
        q = select(&reload, &scaled(&qk), &q);
        r = select(&reload, &scaled(&rk), &r);
        x = select(&reload, &xk, &x);
        let s: V = std::array::from_fn(|j| {
            (p[j] * p[j] + q[j] * q[j] + r[j] * r[j])
                .sqrt()
                .copysign(p[j])
        });
        let act = and(&on, &mask(|j| s[j] != 0.0));
        if act == [0; LANES] {
            continue;
        }
        // The subdiagonal entry the reflection makes.
        let negate = and(&act, &mask(|j| at_m[j] != 0 && rows[j].0 != rows[j].1));
        let bulge = and(&act, &mask(|j| at_m[j] == 0));
        let sub = a[k][k - 1];
        let sub = select(&negate, &sub.map(|v| -v), &sub);
        a[k][k - 1] = select(&bulge, &map2(&s, &x, |s, x| -s * x), &sub);
        p = select(&act, &map2(&p, &s, |p, s| p + s), &p);
        let (hx, hy, hz) = (
            map2(&p, &s, |p, s| p / s),
            map2(&q, &s, |q, s| q / s),
            map2(&r, &s, |r, s| r / s),
        );
        let (q2, r2) = (map2(&q, &p, |q, p| q / p), map2(&r, &p, |r, p| r / p));
        let third = and(&act, &not_last);
        let jmax = (0..LANES)
            .filter(|&j| act[j] != 0)
            .map(|j| rows[j].2)
            .max()
            .unwrap_or(0);
        for j in k..=jmax {
            let row = and(&act, &mask(|lane| j <= rows[lane].2));
            let row3 = and(&row, &third);
            let (a0, a1, a2) = (a[k][j], a[k + 1][j], a[k + 2][j]);
            let two: V = std::array::from_fn(|l| a0[l] + q2[l] * a1[l]);
            let pp = select(
                &third,
                &std::array::from_fn(|l| two[l] + r2[l] * a2[l]),
                &two,
            );
            a[k + 2][j] = select(&row3, &std::array::from_fn(|l| a2[l] - pp[l] * hz[l]), &a2);
            a[k + 1][j] = select(&row, &std::array::from_fn(|l| a1[l] - pp[l] * hy[l]), &a1);
            a[k][j] = select(&row, &std::array::from_fn(|l| a0[l] - pp[l] * hx[l]), &a0);
        }
        let imax = (0..LANES)
            .filter(|&j| act[j] != 0)
            .map(|j| rows[j].2.min(k + 3))
            .max()
            .unwrap_or(0);
        for i in lmin..=imax {
            let col = and(
                &act,
                &mask(|lane| rows[lane].0 <= i && i <= rows[lane].2.min(k + 3)),
            );
            let col3 = and(&col, &third);
            let (a0, a1, a2) = (a[i][k], a[i][k + 1], a[i][k + 2]);
            let two: V = std::array::from_fn(|l| hx[l] * a0[l] + hy[l] * a1[l]);
            let pp = select(
                &third,
                &std::array::from_fn(|l| two[l] + hz[l] * a2[l]),
                &two,
            );
            a[i][k + 2] = select(&col3, &std::array::from_fn(|l| a2[l] - pp[l] * r2[l]), &a2);
            a[i][k + 1] = select(&col, &std::array::from_fn(|l| a1[l] - pp[l] * q2[l]), &a1);
            a[i][k] = select(&col, &std::array::from_fn(|l| a0[l] - pp[l]), &a0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::hessenberg::MAX_SWEEPS;
    use super::*;

    /// A pseudo-random monic polynomial of degree `n` (a fixed linear congruential sequence).
    fn polynomial(seed: u64, n: usize) -> Vec<f64> {
        let mut s = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let u = (s >> 11) as f64 / (1u64 << 53) as f64;
                // Coefficients over several decades, as a resultant's are.
                (2.0 * u - 1.0) * 10f64.powi((s % 7) as i32 - 3)
            })
            .collect()
    }

    fn one_at_a_time(c: &[f64], max_sweeps: usize) -> Eigenvalues {
        let mut h = Hessenberg::companion(c);
        h.balance();
        let (mut wr, mut wi) = ([0.0; N], [0.0; N]);
        h.eigenvalues_within(&mut wr, &mut wi, max_sweeps)
            .map(|n| (wr, wi, n))
    }

    fn bits(e: &Eigenvalues) -> Option<(Vec<u64>, Vec<u64>, usize)> {
        e.map(|(wr, wi, n)| {
            (
                wr[..n].iter().map(|v| v.to_bits()).collect(),
                wi[..n].iter().map(|v| v.to_bits()).collect(),
                n,
            )
        })
    }

    #[test]
    fn lockstep_eigenvalues_equal_one_at_a_time_to_the_last_bit() {
        // Orders 0 to 8 mixed, so that lanes of different orders sweep together and refill.
        let polys: Vec<Vec<f64>> = (0..1000u64)
            .map(|k| polynomial(k, [8, 8, 8, 7, 6, 8, 5, 3, 8, 2, 1, 0, 4][k as usize % 13]))
            .collect();
        let matrices: Vec<Hessenberg> = polys.iter().map(|c| Hessenberg::companion(c)).collect();
        let (mut out, mut scratch) = (Vec::new(), Scratch::default());
        eigenvalues(&matrices, &mut out, &mut scratch, MAX_SWEEPS);
        assert_eq!(out.len(), polys.len());
        for (c, got) in polys.iter().zip(&out) {
            assert!(got.is_some(), "{c:?} did not converge");
            assert_eq!(bits(got), bits(&one_at_a_time(c, MAX_SWEEPS)), "{c:?}");
        }
    }

    #[test]
    fn a_matrix_that_does_not_converge_is_reported_as_one_at_a_time() {
        // Five sweeps without a deflation are too few for some of these.
        let polys: Vec<Vec<f64>> = (0..200u64).map(|k| polynomial(k, 8)).collect();
        let matrices: Vec<Hessenberg> = polys.iter().map(|c| Hessenberg::companion(c)).collect();
        let (mut out, mut scratch) = (Vec::new(), Scratch::default());
        eigenvalues(&matrices, &mut out, &mut scratch, 5);
        let failed = out.iter().filter(|e| e.is_none()).count();
        assert!(
            failed > 0 && failed < polys.len(),
            "{failed} of {} failed",
            polys.len()
        );
        for (c, got) in polys.iter().zip(&out) {
            assert_eq!(bits(got), bits(&one_at_a_time(c, 5)), "{c:?}");
        }
    }
}
