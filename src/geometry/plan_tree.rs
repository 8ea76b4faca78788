//! A packed R-tree of plan boxes (X, Z): the spatial index of a triangulated surface
//! (`ground.rs`), loaded once and never changed.
//!
//! The items' boxes are sorted along a Hilbert curve through their centres, then grouped
//! [`NODE`] at a time into the level above, and so on up to one root. A node is a box in single
//! precision, rounded outwards so that it holds its items' exact extents, and a number (an
//! item's, or its first child's position): 20 bytes, in two flat arrays, about 1.07 nodes an
//! item. Loading takes one sort of one 8-byte key an item and writes each node once; a search
//! walks down from the root with its stack in place, allocating nothing. Which items a search
//! gives is decided by the boxes alone; the caller tests its items exactly.

/// Children per node.
pub const NODE: usize = 16;

/// The most items a tree holds: its nodes' positions, about 16/15 of its items, are `u32`.
pub const MAX_ITEMS: usize = 4_000_000_000;

/// The most inner nodes a search holds at once: at most `NODE` a level, and no more than 8
/// levels over the leaves for [`MAX_ITEMS`].
const STACK: usize = NODE * 8;

/// A plan box [X low, Z low, X high, Z high] in single precision.
pub type PlanBox = [f32; 4];

/// The plan box in single precision that holds the box from `lo` to `hi` (X, Z).
pub fn outward(lo: [f64; 2], hi: [f64; 2]) -> PlanBox {
    let down = |v: f64| {
        let f = v as f32;
        if f as f64 > v { f.next_down() } else { f }
    };
    let up = |v: f64| {
        let f = v as f32;
        if (f as f64) < v { f.next_up() } else { f }
    };
    [down(lo[0]), down(lo[1]), up(hi[0]), up(hi[1])]
}

fn meets(a: &PlanBox, b: &PlanBox) -> bool {
    a[0] <= b[2] && a[2] >= b[0] && a[1] <= b[3] && a[3] >= b[1]
}

/// A packed R-tree of the plan boxes of items numbered from 0.
#[derive(Clone)]
pub struct PlanTree {
    /// Every node's box: the leaves (one an item, along the curve), then each level above,
    /// the root last.
    boxes: Vec<PlanBox>,
    /// A leaf's item; an inner node's first child's position in `boxes`.
    ids: Vec<u32>,
    /// Where each level ends in `boxes`, the leaves' first.
    level_ends: Vec<usize>,
}

impl std::fmt::Debug for PlanTree {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "PlanTree({} items, {} nodes)",
            self.items(),
            self.boxes.len()
        )
    }
}

impl PlanTree {
    /// The tree of `n` items (at least one, at most [`MAX_ITEMS`]), item `k`'s box
    /// `extent(k)` (finite) and `point(k)` a point of it that places it along the curve: each
    /// asked for in the items' order, the boxes once more along the curve.
    pub fn new(
        n: usize,
        point: impl Fn(usize) -> [f64; 2],
        extent: impl Fn(usize) -> PlanBox,
    ) -> PlanTree {
        assert!(
            (1..=MAX_ITEMS).contains(&n),
            "a tree holds from one to {MAX_ITEMS} items"
        );
        // The curve spans the points' extent, 2¹⁶ steps a side.
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for k in 0..n {
            let c = point(k);
            for a in 0..2 {
                lo[a] = lo[a].min(c[a]);
                hi[a] = hi[a].max(c[a]);
            }
        }
        let scale = |a: usize| {
            let w = hi[a] - lo[a];
            if w > 0.0 { 65535.0 / w } else { 0.0 }
        };
        let (sx, sz) = (scale(0), scale(1));
        let mut keys: Vec<u64> = (0..n)
            .map(|k| {
                let c = point(k);
                let x = ((c[0] - lo[0]) * sx) as u32;
                let z = ((c[1] - lo[1]) * sz) as u32;
                (u64::from(hilbert(x, z)) << 32) | k as u64
            })
            .collect();
        keys.sort_unstable();

        // Every level's size, then each node written once in place: the leaves along the
        // curve, then each level above.
        let mut level_ends = vec![n];
        let mut size = n;
        while size > 1 {
            size = size.div_ceil(NODE);
            level_ends.push(level_ends.last().unwrap() + size);
        }
        let total = *level_ends.last().unwrap();
        // The items along the curve, their keys dropped before their boxes are made.
        let mut ids = Vec::with_capacity(total);
        ids.extend(keys.iter().map(|&key| key as u32));
        drop(keys);
        let mut boxes = Vec::with_capacity(total);
        boxes.extend(ids.iter().map(|&k| extent(k as usize)));
        let mut start = 0;
        for &end in &level_ends[..level_ends.len() - 1] {
            for first in (start..end).step_by(NODE) {
                let children = &boxes[first..(first + NODE).min(end)];
                let union = children.iter().fold(children[0], |u, b| {
                    [
                        u[0].min(b[0]),
                        u[1].min(b[1]),
                        u[2].max(b[2]),
                        u[3].max(b[3]),
                    ]
                });
                boxes.push(union);
                ids.push(first as u32);
            }
            start = end;
        }
        debug_assert_eq!(boxes.len(), total);
        PlanTree {
            boxes,
            ids,
            level_ends,
        }
    }

    /// How many items the tree holds.
    pub fn items(&self) -> usize {
        self.level_ends[0]
    }

    /// The bytes the tree holds (its nodes' arrays).
    #[cfg(test)]
    pub(crate) fn bytes(&self) -> usize {
        self.boxes.capacity() * std::mem::size_of::<PlanBox>()
            + self.ids.capacity() * std::mem::size_of::<u32>()
    }

    /// The items whose box meets `query` (edges included), in the tree's order.
    pub fn search(&self, query: PlanBox) -> Search<'_> {
        let root = self.boxes.len() - 1;
        Search {
            tree: self,
            query,
            stack: [0; STACK],
            depth: 0,
            next: root,
            end: root + 1,
        }
    }

    /// Where the level holding node `pos` ends.
    fn level_end(&self, pos: usize) -> usize {
        *self
            .level_ends
            .iter()
            .find(|&&end| end > pos)
            .expect("a node is on a level")
    }
}

/// A search's walk down the tree: the nodes `next..end` of one parent still to test, and the
/// inner nodes met to open after them.
pub struct Search<'a> {
    tree: &'a PlanTree,
    query: PlanBox,
    stack: [u32; STACK],
    depth: usize,
    next: usize,
    end: usize,
}

impl Iterator for Search<'_> {
    type Item = usize;

    fn next(&mut self) -> Option<usize> {
        let tree = self.tree;
        let leaves = tree.items();
        loop {
            while self.next < self.end {
                let pos = self.next;
                self.next += 1;
                if meets(&tree.boxes[pos], &self.query) {
                    if pos < leaves {
                        return Some(tree.ids[pos] as usize);
                    }
                    self.stack[self.depth] = pos as u32;
                    self.depth += 1;
                }
            }
            if self.depth == 0 {
                return None;
            }
            self.depth -= 1;
            let first = tree.ids[self.stack[self.depth] as usize] as usize;
            self.next = first;
            self.end = (first + NODE).min(tree.level_end(first));
        }
    }
}

/// The position of (x, z), each in [0, 2¹⁶), along a Hilbert curve through the 2¹⁶ × 2¹⁶ grid
/// (the branch-free form of "Fast Hilbert curve generation", by rawrunprotected, as the
/// `flatbush` library writes it).
fn hilbert(x: u32, z: u32) -> u32 {
    let mut a = x ^ z;
    let mut b = 0xFFFF ^ a;
    let mut c = 0xFFFF ^ (x | z);
    let mut d = x & (z ^ 0xFFFF);

    let mut aa = a | (b >> 1);
    let mut bb = (a >> 1) ^ a;
    let mut cc = ((c >> 1) ^ (b & (d >> 1))) ^ c;
    let mut dd = ((a & (c >> 1)) ^ (d >> 1)) ^ d;

    (a, b, c, d) = (aa, bb, cc, dd);
    aa = (a & (a >> 2)) ^ (b & (b >> 2));
    bb = (a & (b >> 2)) ^ (b & ((a ^ b) >> 2));
    cc ^= (a & (c >> 2)) ^ (b & (d >> 2));
    dd ^= (b & (c >> 2)) ^ ((a ^ b) & (d >> 2));

    (a, b, c, d) = (aa, bb, cc, dd);
    aa = (a & (a >> 4)) ^ (b & (b >> 4));
    bb = (a & (b >> 4)) ^ (b & ((a ^ b) >> 4));
    cc ^= (a & (c >> 4)) ^ (b & (d >> 4));
    dd ^= (b & (c >> 4)) ^ ((a ^ b) & (d >> 4));

    (a, b, c, d) = (aa, bb, cc, dd);
    cc ^= (a & (c >> 8)) ^ (b & (d >> 8));
    dd ^= (b & (c >> 8)) ^ ((a ^ b) & (d >> 8));

    a = cc ^ (cc >> 1);
    b = dd ^ (dd >> 1);

    let spread = |mut v: u32| {
        v = (v | (v << 8)) & 0x00FF_00FF;
        v = (v | (v << 4)) & 0x0F0F_0F0F;
        v = (v | (v << 2)) & 0x3333_3333;
        (v | (v << 1)) & 0x5555_5555
    };
    let i0 = x ^ z;
    let i1 = b | (0xFFFF ^ (i0 | a));
    (spread(i1) << 1) | spread(i0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curve_visits_each_point_of_a_corner_square_once_each_step_to_a_neighbour() {
        // Its first 4⁶ positions fill the 64 × 64 square at the origin.
        let mut along = vec![None; 64 * 64];
        for x in 0..64u32 {
            for z in 0..64u32 {
                let h = hilbert(x, z) as usize;
                assert!(h < along.len(), "({x}, {z}) at {h}");
                assert!(along[h].is_none(), "({x}, {z}) at {h} twice");
                along[h] = Some((x as i64, z as i64));
            }
        }
        for w in along.windows(2) {
            let ((x0, z0), (x1, z1)) = (w[0].unwrap(), w[1].unwrap());
            assert_eq!((x1 - x0).abs() + (z1 - z0).abs(), 1, "{w:?}");
        }
    }

    #[test]
    fn a_search_gives_every_item_whose_box_meets_the_query_once_as_a_scan_does() {
        // Boxes of all sizes, far from the origin, some equal and some degenerate (points).
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let items: Vec<PlanBox> = (0..5000)
            .map(|k| {
                let (x, z) = (1.0e4 + 300.0 * next(), -2.0e4 + 200.0 * next());
                let (w, h) = match k % 5 {
                    0 => (0.0, 0.0),
                    1 => (50.0 * next(), 40.0 * next()),
                    _ => (2.0 * next(), 3.0 * next()),
                };
                outward([x, z], [x + w, z + h])
            })
            .collect();
        for n in [1, 2, NODE, NODE + 1, 300, items.len()] {
            let tree = PlanTree::new(
                n,
                |k| [items[k][0] as f64, items[k][1] as f64],
                |k| items[k],
            );
            assert_eq!(tree.items(), n);
            for _ in 0..200 {
                let (x, z) = (
                    1.0e4 - 10.0 + 320.0 * next(),
                    -2.0e4 - 10.0 + 220.0 * next(),
                );
                let (w, h) = (5.0 * next() * next(), 5.0 * next() * next());
                let q = outward([x, z], [x + w, z + h]);
                let mut found: Vec<usize> = tree.search(q).collect();
                found.sort_unstable();
                let scan: Vec<usize> = (0..n).filter(|&k| meets(&items[k], &q)).collect();
                assert_eq!(found, scan, "{n} items, query {q:?}");
            }
            // A box that meets everything gives everything.
            let all = [f32::MIN, f32::MIN, f32::MAX, f32::MAX];
            assert_eq!(tree.search(all).count(), n);
        }
    }

    #[test]
    fn a_tree_is_about_one_and_a_fifteenth_nodes_an_item_of_twenty_bytes_each() {
        // The memory a surface's index costs (docs/performance.md, "Foundations of faces").
        assert_eq!(
            std::mem::size_of::<PlanBox>() + std::mem::size_of::<u32>(),
            20
        );
        let n = 100_000;
        let at = |k: usize| [(k % 400) as f64, (k / 400) as f64];
        let tree = PlanTree::new(n, at, |k| {
            let [x, z] = at(k);
            outward([x, z], [x + 1.0, z + 1.0])
        });
        let nodes = tree.boxes.len();
        assert!(nodes <= n + n / (NODE - 1) + 8, "{nodes}");
        assert_eq!(tree.boxes.capacity(), nodes);
        assert_eq!(tree.ids.capacity(), nodes);
    }

    #[test]
    fn a_box_rounded_outwards_holds_the_exact_box() {
        let (lo, hi) = ([0.1, -1.0e5 - 0.3], [0.7, 1.0e5 / 3.0]);
        let b = outward(lo, hi);
        assert!((b[0] as f64) <= lo[0] && (b[1] as f64) <= lo[1]);
        assert!((b[2] as f64) >= hi[0] && (b[3] as f64) >= hi[1]);
        // Exact in single precision, kept.
        assert_eq!(outward([0.5, 2.0], [4.0, 8.0]), [0.5, 2.0, 4.0, 8.0]);
    }
}
