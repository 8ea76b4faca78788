//! Where words and arrows go on the plan view: the clearest spot of a region, away from the
//! data, and the shapes of arrows.

use super::{P, View};

/// The distance from `p` to the segment a–b.
fn segment_distance(p: P, a: P, b: P) -> f64 {
    let (dx, dz) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dz * dz;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dz) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dz)
}

/// The point of convex `poly` farthest from every obstacle point and from its own edges, with
/// that distance, on a 41 × 31 grid over the view; labels go there so that they stay off the
/// data.
pub(super) fn free_spot(poly: &[P], obstacles: &[P], view: View) -> Option<(P, f64)> {
    let View { x0, x1, z0, z1 } = view;
    let n = poly.len();
    if n < 3 {
        return None;
    }
    // Inside a convex polygon: on the same side of every edge as its centroid.
    let c = poly.iter().fold((0.0, 0.0), |s, q| {
        (s.0 + q.0 / n as f64, s.1 + q.1 / n as f64)
    });
    let mut best: Option<(P, f64)> = None;
    for i in 0..=40 {
        for j in 0..=30 {
            let p = (
                x0 + (x1 - x0) * f64::from(i) / 40.0,
                z0 + (z1 - z0) * f64::from(j) / 30.0,
            );
            let edge = (0..n)
                .map(|k| segment_distance(p, poly[k], poly[(k + 1) % n]))
                .fold(f64::INFINITY, f64::min);
            let inside = (0..n).all(|k| {
                let (a, b) = (poly[k], poly[(k + 1) % n]);
                let side = |q: P| (b.0 - a.0) * (q.1 - a.1) - (b.1 - a.1) * (q.0 - a.0);
                side(p) * side(c) >= 0.0
            });
            if !inside {
                continue;
            }
            let clear = obstacles
                .iter()
                .map(|q| (p.0 - q.0).hypot(p.1 - q.1))
                .fold(edge, f64::min);
            if best.is_none_or(|b| clear > b.1) {
                best = Some((p, clear));
            }
        }
    }
    best
}

/// An arrow from `from` along unit `dir` of length `len` (data units): the shaft and its head.
pub(super) fn arrow(from: P, dir: P, len: f64) -> [Vec<P>; 2] {
    let tip = (from.0 + len * dir.0, from.1 + len * dir.1);
    let h = 0.25 * len;
    let (c, s) = (0.42f64.cos(), 0.42f64.sin());
    let back = |sgn: f64| {
        let d = (
            -(dir.0 * c - sgn * dir.1 * s),
            -(sgn * dir.0 * s + dir.1 * c),
        );
        (tip.0 + h * d.0, tip.1 + h * d.1)
    };
    [vec![from, tip], vec![back(1.0), tip, back(-1.0)]]
}

/// Points along the segment a–b, for the label placer's obstacles.
pub(super) fn along(a: P, b: P, n: usize) -> impl Iterator<Item = P> {
    (0..=n).map(move |k| {
        let t = k as f64 / n as f64;
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_go_where_the_data_is_not() {
        let poly = vec![(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
        let obstacles: Vec<P> = (0..=10).map(|k| (f64::from(k), 2.0)).collect();
        let view = View {
            x0: 0.0,
            x1: 10.0,
            z0: 0.0,
            z1: 10.0,
        };
        let (p, clear) = free_spot(&poly, &obstacles, view).unwrap();
        // The clearest point lies between the line Z = 2 and the far edge Z = 10.
        assert!((p.1 - 6.0).abs() < 0.5 && clear > 3.5, "{p:?} {clear}");
    }

    #[test]
    fn an_arrow_ends_at_its_length_with_a_symmetric_head() {
        let [shaft, head] = arrow((1.0, 2.0), (0.0, 1.0), 4.0);
        assert_eq!(shaft, vec![(1.0, 2.0), (1.0, 6.0)]);
        assert_eq!(head[1], (1.0, 6.0));
        // The barbs mirror each other across the shaft, behind the tip.
        assert!((head[0].0 - 1.0 + (head[2].0 - 1.0)).abs() < 1e-12);
        assert!((head[0].1 - head[2].1).abs() < 1e-12 && head[0].1 < 6.0);
    }
}
