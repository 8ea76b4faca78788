//! The values the summary needs of every route of a probabilistic analysis — rows of a few
//! numbers, one a route — kept in memory up to a bound and beyond it in an unnamed temporary
//! file, so that the percentiles and Spearman's rank correlations come out exactly as if every
//! value were held (`summary.rs`, `sensitivity.rs`) for any number of samples, in a few tens
//! of MB: percentiles by a radix selection in passes over the rows, ranks by counting, block by
//! block, where each of a block's values falls among all the others. The sweep's picture keeps
//! what it shows of each combination in the same store.

use super::Percentiles;
use super::sensitivity::spearman as spearman_held;
use super::summary::percentiles as percentiles_held;
use std::cell::RefCell;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Seek, SeekFrom, Write};
use std::path::PathBuf;

/// Rows of `width` numbers appended in order: the first `in_memory_rows` held in memory, every
/// later one written to an unnamed temporary file (made when first needed, in the folder given,
/// else the system's temporary folder; gone when the store is dropped).
pub struct Columns {
    width: usize,
    in_memory_rows: usize,
    held: Vec<f64>,
    spilled: usize,
    spill_in: Option<PathBuf>,
    file: RefCell<Option<BufWriter<File>>>,
    stop: Option<fn() -> bool>,
}

/// How many rows a pass reads between two askings of [`Columns::stop_when`]'s function.
const ASK_EVERY: usize = 1 << 16;

/// Puts the spill file's offset back at its end when dropped: after a pass over the file, also
/// one its callback panicked out of, so that the rows pushed later are written after the others.
struct AtEnd<'a>(&'a mut BufWriter<File>);

impl AtEnd<'_> {
    /// The offset at the end now, or why it could not be put there.
    fn finish(self) -> std::io::Result<u64> {
        self.0.get_mut().seek(SeekFrom::End(0))
    }
}

impl Drop for AtEnd<'_> {
    fn drop(&mut self) {
        let _ = self.0.get_mut().seek(SeekFrom::End(0));
    }
}

impl Columns {
    /// The rows held in memory unless said otherwise: 2¹⁸ (a few MB for a few columns).
    pub const DEFAULT_IN_MEMORY_ROWS: usize = 1 << 18;

    /// An empty store of rows of `width` numbers; a temporary file, if one is needed, made in
    /// `spill_in`.
    pub fn new(width: usize, spill_in: Option<PathBuf>) -> Columns {
        Columns {
            width,
            in_memory_rows: Columns::DEFAULT_IN_MEMORY_ROWS,
            held: Vec::new(),
            spilled: 0,
            spill_in,
            file: RefCell::new(None),
            stop: None,
        }
    }

    /// Passes over the rows asking `stop` every 65 536 rows, and ending with an error of kind
    /// `Interrupted` when it says so: a summary of millions of rows stops within a second.
    pub fn stop_when(&mut self, stop: fn() -> bool) {
        self.stop = Some(stop);
    }

    /// An `Interrupted` error if the stop function says so.
    fn asked_to_stop(&self) -> std::io::Result<()> {
        match self.stop {
            Some(stop) if stop() => Err(std::io::Error::new(
                std::io::ErrorKind::Interrupted,
                "interrupted",
            )),
            _ => Ok(()),
        }
    }

    /// The same store holding at most `rows` rows in memory (at least one).
    pub fn with_in_memory_rows(self, rows: usize) -> Columns {
        Columns {
            in_memory_rows: rows.max(1),
            ..self
        }
    }

    /// The numbers in a row.
    pub fn width(&self) -> usize {
        self.width
    }

    /// The rows stored.
    pub fn rows(&self) -> usize {
        self.held.len() / self.width.max(1) + self.spilled
    }

    /// Appends a row (its first `width` numbers; missing ones are NaN).
    pub fn push(&mut self, row: &[f64]) -> std::io::Result<()> {
        let values = (0..self.width).map(|c| row.get(c).copied().unwrap_or(f64::NAN));
        if self.spilled == 0 && self.held.len() < self.in_memory_rows * self.width {
            self.held.extend(values);
            return Ok(());
        }
        let mut file = self.file.borrow_mut();
        if file.is_none() {
            let f = match &self.spill_in {
                Some(dir) => tempfile::tempfile_in(dir)?,
                None => tempfile::tempfile()?,
            };
            *file = Some(BufWriter::with_capacity(1 << 20, f));
        }
        if let Some(w) = file.as_mut() {
            for v in values {
                w.write_all(&v.to_le_bytes())?;
            }
        }
        self.spilled += 1;
        Ok(())
    }

    /// Every row, in order: those in memory, then the file's read back.
    pub fn scan(&self, mut each: impl FnMut(&[f64])) -> std::io::Result<()> {
        let w = self.width.max(1);
        if self.width == 0 {
            for _ in 0..self.rows() {
                each(&[]);
            }
            return Ok(());
        }
        for (k, row) in self.held.chunks_exact(w).enumerate() {
            if k % ASK_EVERY == 0 {
                self.asked_to_stop()?;
            }
            each(row);
        }
        // A pass begun from within another's callback (the file is being read): an error, not a
        // panic.
        let Ok(mut file) = self.file.try_borrow_mut() else {
            return Err(std::io::Error::other(
                "the store's rows are already being read by an enclosing pass",
            ));
        };
        let Some(writer) = file.as_mut() else {
            return Ok(());
        };
        writer.flush()?;
        let f = writer.get_ref().try_clone()?;
        let mut read = || -> std::io::Result<()> {
            let mut r = BufReader::with_capacity(1 << 20, &f);
            r.seek(SeekFrom::Start(0))?;
            let (mut bytes, mut row) = (vec![0u8; 8 * w], vec![0.0; w]);
            for k in 0..self.spilled {
                if k % ASK_EVERY == 0 {
                    self.asked_to_stop()?;
                }
                r.read_exact(&mut bytes)?;
                for (v, b) in row.iter_mut().zip(bytes.chunks_exact(8)) {
                    *v = f64::from_le_bytes(b.try_into().unwrap_or([0; 8]));
                }
                each(&row);
            }
            Ok(())
        };
        // The next write goes at the end, wherever the reading left the offset the clone
        // shares, whether it ended, was stopped, or `each` panicked (the guard's drop).
        let at_end = AtEnd(writer);
        let read = read();
        at_end.finish()?;
        read
    }

    /// Whether every row is in memory.
    fn all_held(&self) -> bool {
        self.spilled == 0
    }

    /// The numbers of column `c`, in order (all rows in memory).
    fn held_column(&self, c: usize) -> Vec<f64> {
        self.held
            .chunks_exact(self.width.max(1))
            .map(|r| r[c])
            .collect()
    }

    /// Percentiles 5, 50 and 95 of column `c`, as `summary::percentiles` gives them of the
    /// column held whole (NaN left out; `None` if nothing is left).
    pub fn percentiles(&self, c: usize) -> std::io::Result<Option<Percentiles>> {
        if c >= self.width {
            return Ok(None);
        }
        if self.all_held() {
            return Ok(percentiles_held(self.held_column(c)));
        }
        // The first pass counts the values as it takes the first 16 bits of their order keys.
        let first = self.histogram(c, 48, &[0])?;
        let n: usize = first[0].iter().sum();
        if n == 0 {
            return Ok(None);
        }
        // The order statistics the interpolation reads: i and i + 1 at each percentile, each
        // found once.
        let mut wanted: Vec<usize> = Vec::with_capacity(6);
        for q in [0.05, 0.5, 0.95] {
            let i = (q * (n - 1) as f64).floor() as usize;
            wanted.extend([i, (i + 1).min(n - 1)]);
        }
        let mut ks = wanted.clone();
        ks.sort_unstable();
        ks.dedup();
        let found = self.select(c, &ks, &first[0])?;
        let value = |k: usize| ks.binary_search(&k).map_or(f64::NAN, |i| found[i]);
        let at = |j: usize, q: f64| {
            let pos = q * (n - 1) as f64;
            let f = pos.fract();
            let (vi, vj) = (value(wanted[2 * j]), value(wanted[2 * j + 1]));
            if f == 0.0 || vi == vj {
                vi
            } else if vi.is_infinite() || vj.is_infinite() {
                if f < 0.5 { vi } else { vj }
            } else {
                vi + f * (vj - vi)
            }
        };
        Ok(Some(Percentiles {
            p5: at(0, 0.05),
            p50: at(1, 0.5),
            p95: at(2, 0.95),
        }))
    }

    /// The `ks`-th smallest (from 0) of column `c` in the order of `f64::total_cmp`, NaN left
    /// out: a radix selection on the order's 64-bit keys, 16 bits a pass, all of `ks` in the
    /// same three passes over the rows after the first, whose histogram of the first 16 bits
    /// is `first` (65 536 counters a value sought).
    fn select(&self, c: usize, ks: &[usize], first: &[usize]) -> std::io::Result<Vec<f64>> {
        // Each value sought: the bits of its key found so far, and its rank among the keys
        // that begin with them.
        let mut sought: Vec<(u64, usize)> = ks
            .iter()
            .map(|&k| {
                let mut rank = k;
                (digit_at(first, &mut rank) << 48, rank)
            })
            .collect();
        for shift in [32, 16, 0] {
            let prefixes: Vec<u64> = sought.iter().map(|&(p, _)| p).collect();
            let counts = self.histogram(c, shift, &prefixes)?;
            for ((prefix, rank), counts) in sought.iter_mut().zip(&counts) {
                *prefix |= digit_at(counts, rank) << shift;
            }
        }
        Ok(sought.iter().map(|&(p, _)| from_order_key(p)).collect())
    }

    /// For each of `prefixes`, how many of column `c`'s numbers (NaN left out) have an order
    /// key that begins as it does (the bits above `shift + 16`), by their 16 bits from `shift`
    /// up: one pass.
    fn histogram(
        &self,
        c: usize,
        shift: u32,
        prefixes: &[u64],
    ) -> std::io::Result<Vec<Vec<usize>>> {
        let mask = u64::MAX.checked_shl(shift + 16).unwrap_or(0);
        let mut counts = vec![vec![0usize; 1 << 16]; prefixes.len()];
        self.scan(|r| {
            let v = r[c];
            if !v.is_nan() {
                let key = order_key(v);
                let digit = ((key >> shift) & 0xffff) as usize;
                for (&prefix, counts) in prefixes.iter().zip(&mut counts) {
                    if key & mask == prefix {
                        counts[digit] += 1;
                    }
                }
            }
        })?;
        Ok(counts)
    }

    /// Spearman's ρ of columns `a` and `b`, as `sensitivity::spearman` gives it of the pairs
    /// `(row[a], row[b])` held whole (a pair with a NaN left out; `None` with fewer than three
    /// pairs or a constant side).
    pub fn spearman(&self, a: usize, b: usize) -> std::io::Result<Option<f64>> {
        if a >= self.width || b >= self.width {
            return Ok(None);
        }
        if self.all_held() {
            let pairs: Vec<(f64, f64)> = self
                .held
                .chunks_exact(self.width.max(1))
                .map(|r| (r[a], r[b]))
                .collect();
            return Ok(spearman_held(&pairs));
        }
        let kept = |r: &[f64]| !r[a].is_nan() && !r[b].is_nan();
        let mut n = 0usize;
        self.scan(|r| n += usize::from(kept(r)))?;
        if n < 3 {
            return Ok(None);
        }
        // The ranks' mean is (n + 1)/2 whatever the ties; Pearson's sums of the deviations
        // block by block: each block's kept pairs ranked among all kept pairs.
        let mean = 0.5 * (n as f64 + 1.0);
        let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
        let block = self.in_memory_rows;
        let mut start = 0usize;
        while start < n {
            let end = start.saturating_add(block).min(n);
            // The block's pairs: the kept pairs numbered start..end.
            let (mut va, mut vb) = (Vec::new(), Vec::new());
            let mut index = 0usize;
            self.scan(|r| {
                if kept(r) {
                    if (start..end).contains(&index) {
                        va.push(r[a]);
                        vb.push(r[b]);
                    }
                    index += 1;
                }
            })?;
            let (mut ra, mut rb) = (Ranks::of(va), Ranks::of(vb));
            self.scan(|r| {
                if kept(r) {
                    ra.count(r[a]);
                    rb.count(r[b]);
                }
            })?;
            for (x, y) in ra.ranks().zip(rb.ranks()) {
                let (dx, dy) = (x - mean, y - mean);
                sab += dx * dy;
                saa += dx * dx;
                sbb += dy * dy;
            }
            start = end;
        }
        Ok((saa > 0.0 && sbb > 0.0).then(|| (sab / (saa * sbb).sqrt()).clamp(-1.0, 1.0)))
    }
}

/// The next 16 bits of the key ranked `rank` among those a histogram counts (`counts`, by
/// those bits); `rank` becomes its rank among the keys with those bits.
fn digit_at(counts: &[usize], rank: &mut usize) -> u64 {
    let mut digit = 0usize;
    while digit + 1 < counts.len() && *rank >= counts[digit] {
        *rank -= counts[digit];
        digit += 1;
    }
    digit as u64
}

/// The ranks of a block's numbers among all the numbers counted ([`Ranks::count`]), ties
/// given their mean rank as `sensitivity::ranks` gives them: how many are less plus half of
/// one more than how many are equal. The numbers counted are taken a batch at a time, sorted
/// and merged with the block's (a pass over both), which reads memory in order where a search
/// of the block for each would wait on it.
struct Ranks {
    /// The block's distinct numbers as [`tie_key`]s, increasing.
    keys: Vec<u64>,
    /// Each of the block's numbers in its order: the index of its key.
    of: Vec<usize>,
    /// `between[j]`: the numbers counted above `keys[j - 1]` and below `keys[j]` (the last
    /// one above every key).
    between: Vec<u64>,
    /// `equal[j]`: the numbers counted equal to `keys[j]`.
    equal: Vec<u64>,
    /// The batch of numbers counted but not yet merged, as [`tie_key`]s.
    batch: Vec<u64>,
}

impl Ranks {
    /// A batch at least this long (or as long as the block): a short block's merges cost
    /// little more than their batch.
    const BATCH: usize = 1 << 12;

    fn of(values: Vec<f64>) -> Ranks {
        let mut keys: Vec<u64> = values.iter().map(|&v| tie_key(v)).collect();
        keys.sort_unstable();
        keys.dedup();
        let of = values
            .into_iter()
            .map(|v| keys.partition_point(|&k| k < tie_key(v)))
            .collect();
        let between = vec![0; keys.len() + 1];
        let equal = vec![0; keys.len()];
        let batch = Vec::with_capacity(keys.len().max(Ranks::BATCH));
        Ranks {
            keys,
            of,
            between,
            equal,
            batch,
        }
    }

    /// Counts one more number (not NaN).
    fn count(&mut self, v: f64) {
        self.batch.push(tie_key(v));
        if self.batch.len() >= self.keys.len().max(Ranks::BATCH) {
            self.merge();
        }
    }

    /// Counts the batch: sorted, then walked beside the block's keys.
    fn merge(&mut self) {
        self.batch.sort_unstable();
        let mut j = 0;
        for &x in &self.batch {
            while j < self.keys.len() && self.keys[j] < x {
                j += 1;
            }
            match self.equal.get_mut(j) {
                Some(e) if self.keys[j] == x => *e += 1,
                _ => self.between[j] += 1,
            }
        }
        self.batch.clear();
    }

    /// The rank of each of the block's numbers, in its order.
    fn ranks(&mut self) -> impl Iterator<Item = f64> + '_ {
        self.merge();
        let mut less = 0u64;
        let rank_of: Vec<f64> = self
            .equal
            .iter()
            .zip(&self.between)
            .map(|(&e, &b)| {
                less += b;
                let r = less as f64 + 0.5 * (e as f64 + 1.0);
                less += e;
                r
            })
            .collect();
        self.of.iter().map(move |&j| rank_of[j])
    }
}

/// [`order_key`] with −0 taken as +0: equal keys for numbers equal as `==` has them (NaN
/// aside), in the order of `f64::total_cmp` otherwise.
fn tie_key(v: f64) -> u64 {
    order_key(if v == 0.0 { 0.0 } else { v })
}

/// The 64-bit key that orders numbers as `f64::total_cmp` does (sign flipped for the
/// positives, every bit for the negatives).
fn order_key(v: f64) -> u64 {
    let bits = v.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | (1 << 63)
    }
}

/// The number whose [`order_key`] is `key`.
fn from_order_key(key: u64) -> f64 {
    f64::from_bits(if key >> 63 == 1 {
        key & !(1 << 63)
    } else {
        !key
    })
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// Uniforms in [0, 1) from a fixed xorshift sequence seeded with `seed` (not zero).
    pub(in crate::analysis::probabilistic) fn uniforms(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// `n` rows of three columns from a fixed sequence: a column of ties on a coarse grid
    /// with −0 and +0, one with ±∞ and NaN now and then, and a constant one.
    fn rows(n: usize) -> Vec<[f64; 3]> {
        let mut next = uniforms(0x9e37_79b9_7f4a_7c15);
        (0..n)
            .map(|k| {
                let (u, w) = (next(), next());
                let tie = ((u * 8.0).floor() - 4.0) / 4.0;
                let tie = if k % 5 == 0 && tie == 0.0 { -0.0 } else { tie };
                let wild = match k % 13 {
                    1 => f64::INFINITY,
                    4 => f64::NEG_INFINITY,
                    7 => f64::NAN,
                    _ => w * 3.0 - u,
                };
                [tie, wild, 2.5]
            })
            .collect()
    }

    fn stored(data: &[[f64; 3]], in_memory: usize) -> Columns {
        let mut c = Columns::new(3, None).with_in_memory_rows(in_memory);
        for r in data {
            c.push(r).unwrap();
        }
        c
    }

    fn bits(p: Option<Percentiles>) -> Option<[u64; 3]> {
        p.map(|p| [p.p5.to_bits(), p.p50.to_bits(), p.p95.to_bits()])
    }

    /// `n` rows of −0, +0 and 1 in a fixed order, NaN now and then: order statistics that fall
    /// on −0 or +0 (equal as numbers, not as bits) and the interpolation between them.
    fn zeros(n: usize) -> Vec<[f64; 3]> {
        let mut next = uniforms(0x5851_f42d_4c95_7f2d);
        (0..n)
            .map(|_| {
                let u = next();
                let z = if u < 0.4 { -0.0 } else { 0.0 };
                [
                    z,
                    if u > 0.9 { 1.0 } else { z },
                    if u < 0.1 { f64::NAN } else { -z },
                ]
            })
            .collect()
    }

    #[test]
    fn a_store_past_its_memory_gives_the_percentiles_of_every_value_held_bit_for_bit() {
        let sets = [0, 1, 2, 3, 10, 1000, 5000]
            .into_iter()
            .map(rows)
            .chain([3, 21, 400].map(zeros));
        for data in sets {
            let n = data.len();
            for in_memory in [1, 7, 64, n.max(1)] {
                let s = stored(&data, in_memory);
                assert_eq!(s.spilled, n.saturating_sub(in_memory), "{n} {in_memory}");
                for c in 0..3 {
                    let want = percentiles_held(data.iter().map(|r| r[c]).collect());
                    assert_eq!(
                        bits(s.percentiles(c).unwrap()),
                        bits(want),
                        "n {n}, {in_memory} held, column {c}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_store_past_its_memory_gives_the_rank_correlations_of_every_pair_held() {
        let sets = [0, 1, 2, 3, 4, 10, 1000, 5000]
            .into_iter()
            .map(|n| {
                let mut data = rows(n);
                // A column related to the first by a monotone function with its ties.
                for r in &mut data {
                    r[2] = if r[0].is_nan() { 0.0 } else { r[0].powi(3) };
                }
                data
            })
            .chain([3, 21, 400].map(zeros));
        for data in sets {
            let n = data.len();
            // A block of one row at a time only where it is quick.
            let smallest = if n > 1000 { 7 } else { 1 };
            for in_memory in [smallest, 7, 64, n.max(1)] {
                let s = stored(&data, in_memory);
                assert_eq!(s.spilled, n.saturating_sub(in_memory), "{n} {in_memory}");
                for (a, b) in [(0, 1), (1, 0), (0, 2), (1, 2), (1, 1)] {
                    let pairs: Vec<(f64, f64)> = data.iter().map(|r| (r[a], r[b])).collect();
                    let want = spearman_held(&pairs);
                    let got = s.spearman(a, b).unwrap();
                    match (got, want) {
                        (Some(g), Some(w)) => {
                            assert!(
                                (g - w).abs() < 1e-12,
                                "n {n} {in_memory} ({a},{b}): {g} {w}"
                            )
                        }
                        (g, w) => assert!(
                            g.is_none() && w.is_none(),
                            "n {n} {in_memory} ({a},{b}): {g:?} {w:?}"
                        ),
                    }
                }
            }
        }
        // A constant side has none.
        let s = stored(
            &rows(100)
                .iter()
                .map(|r| [r[0], 1.0, 1.0])
                .collect::<Vec<_>>(),
            8,
        );
        assert_eq!(s.spearman(0, 1).unwrap(), None);
    }

    #[test]
    fn a_store_gives_back_every_row_in_order_bit_for_bit_and_takes_more_after() {
        let data = rows(500);
        let mut s = stored(&data, 16);
        assert_eq!(s.rows(), 500);
        let mut back = Vec::new();
        s.scan(|r| back.push([r[0].to_bits(), r[1].to_bits(), r[2].to_bits()]))
            .unwrap();
        let want: Vec<[u64; 3]> = data.iter().map(|r| r.map(f64::to_bits)).collect();
        assert_eq!(back, want);
        // Read back, then written on: the new rows go at the end.
        s.push(&[1.0, 2.0, 3.0]).unwrap();
        let mut last = None;
        let mut count = 0;
        s.scan(|r| {
            count += 1;
            last = Some([r[0], r[1], r[2]]);
        })
        .unwrap();
        assert_eq!((count, last), (501, Some([1.0, 2.0, 3.0])));
    }

    #[test]
    fn a_store_holds_no_more_rows_in_memory_than_it_was_given_and_the_rest_in_its_file() {
        let data = rows(1000);
        let s = stored(&data, 64);
        assert_eq!((s.held.len(), s.spilled, s.rows()), (3 * 64, 936, 1000));
        assert!(s.file.borrow().is_some());
        // Within its bound, no file.
        let s = stored(&data, 1000);
        assert_eq!((s.held.len(), s.spilled, s.rows()), (3 * 1000, 0, 1000));
        assert!(s.file.borrow().is_none());
        // Nothing stored: nothing to give, and no panic.
        let s = stored(&[], 4);
        assert_eq!(s.rows(), 0);
        assert_eq!(s.percentiles(0).unwrap(), None);
        assert_eq!(s.spearman(0, 1).unwrap(), None);
        assert_eq!(s.percentiles(3).unwrap(), None);
    }

    static STOP: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

    #[test]
    fn a_pass_over_the_rows_ends_as_interrupted_when_the_stop_function_says_so() {
        let mut s = stored(&rows(300_000), 1000);
        s.stop_when(|| STOP.load(std::sync::atomic::Ordering::Relaxed));
        assert!(s.percentiles(1).unwrap().is_some());
        STOP.store(true, std::sync::atomic::Ordering::Relaxed);
        let mut seen = 0usize;
        let e = s.scan(|_| seen += 1).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::Interrupted);
        assert!(seen < ASK_EVERY, "{seen}");
        assert_eq!(
            s.spearman(0, 1).unwrap_err().kind(),
            std::io::ErrorKind::Interrupted
        );
    }

    #[test]
    fn the_order_key_orders_as_total_cmp_and_comes_back_to_its_number() {
        let v = [
            f64::NEG_INFINITY,
            -1e300,
            -1.0,
            -5e-324,
            -0.0,
            0.0,
            5e-324,
            1.0,
            f64::INFINITY,
        ];
        for w in v.windows(2) {
            assert!(order_key(w[0]) < order_key(w[1]), "{} {}", w[0], w[1]);
        }
        for x in v {
            assert_eq!(from_order_key(order_key(x)).to_bits(), x.to_bits());
        }
    }

    #[test]
    fn rows_pushed_after_a_stopped_pass_go_at_the_end_and_every_row_reads_back() {
        // A pass stopped halfway left the file's offset in the middle, where the next row was
        // written over the others (found by a reviewing helper).
        let data = rows(300_000);
        let mut s = stored(&data, 1000);
        STOP2.store(false, std::sync::atomic::Ordering::Relaxed);
        s.stop_when(|| STOP2.load(std::sync::atomic::Ordering::Relaxed));
        let mut seen = 0usize;
        let _ = s.scan(|_| {
            seen += 1;
            if seen == 200_000 {
                STOP2.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        });
        STOP2.store(false, std::sync::atomic::Ordering::Relaxed);
        s.push(&[1.0, 2.0, 3.0]).unwrap();
        let mut back = Vec::new();
        s.scan(|r| back.push([r[0].to_bits(), r[1].to_bits(), r[2].to_bits()]))
            .unwrap();
        let mut want: Vec<[u64; 3]> = data.iter().map(|r| r.map(f64::to_bits)).collect();
        want.push([1.0f64.to_bits(), 2.0f64.to_bits(), 3.0f64.to_bits()]);
        assert_eq!(back.len(), want.len());
        assert!(
            back == want,
            "rows differ after a push following an interrupted scan"
        );
    }
    static STOP2: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

    #[test]
    fn a_pass_left_by_a_panic_or_begun_within_another_leaves_every_row_whole() {
        // A callback that panics halfway through the file left its offset there (the next row
        // went over the others), and a pass begun inside another's callback panicked on the
        // file already borrowed.
        // The file's rows are more than its reader's buffer holds (1 MiB, 43 690 rows of
        // three), so the panic leaves the offset within the file.
        let data = rows(100_000);
        let mut s = stored(&data, 1000);
        let mut seen = 0usize;
        let panicked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let _ = s.scan(|_| {
                seen += 1;
                assert!(seen < 3000, "a callback that panics");
            });
        }));
        assert!(panicked.is_err());
        s.push(&[1.0, 2.0, 3.0]).unwrap();
        let mut inner = None;
        let mut back = Vec::new();
        s.scan(|r| {
            if back.len() == 2000 {
                inner = Some(s.scan(|_| ()));
            }
            back.push([r[0].to_bits(), r[1].to_bits(), r[2].to_bits()]);
        })
        .unwrap();
        assert!(inner.is_some_and(|r| r.is_err()));
        let mut want: Vec<[u64; 3]> = data.iter().map(|r| r.map(f64::to_bits)).collect();
        want.push([1.0f64.to_bits(), 2.0f64.to_bits(), 3.0f64.to_bits()]);
        assert!(back == want, "rows differ after a panicked pass");
    }
}
