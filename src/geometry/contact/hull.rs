//! The plane across a normal: two tangents completing it, and the corners of a set of points'
//! convex hull seen along it (what a flush patch and the static check's supports keep).

use nalgebra::Vector3;

/// Two unit tangents completing `n`.
pub fn tangents(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::z()
    };
    let t1 = n.cross(&helper).normalize();
    (t1, n.cross(&t1))
}

/// The indices of the corners of the convex hull of `points` seen along `n` (their coordinates
/// on the plane across it), as [`hull_corners`] gives them.
pub fn hull_across(n: &Vector3<f64>, points: impl Iterator<Item = Vector3<f64>>) -> Vec<usize> {
    let axes = tangents(n);
    let plan: Vec<[f64; 2]> = points.map(|r| [r.dot(&axes.0), r.dot(&axes.1)]).collect();
    hull_corners(&plan)
}

/// The indices of the corners of the convex hull of `p` (Andrew's monotone chain; points on a
/// hull edge or repeated are left out).
pub fn hull_corners(p: &[[f64; 2]]) -> Vec<usize> {
    if p.len() <= 2 {
        return (0..p.len()).collect();
    }
    let mut idx: Vec<usize> = (0..p.len()).collect();
    idx.sort_by(|&a, &b| {
        p[a][0]
            .total_cmp(&p[b][0])
            .then(p[a][1].total_cmp(&p[b][1]))
    });
    let cross = |o: usize, a: usize, b: usize| {
        (p[a][0] - p[o][0]) * (p[b][1] - p[o][1]) - (p[a][1] - p[o][1]) * (p[b][0] - p[o][0])
    };
    let mut hull: Vec<usize> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let order: Vec<usize> = if pass == 0 {
            idx.clone()
        } else {
            idx.iter().rev().copied().collect()
        };
        for i in order {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], i) <= 0.0
            {
                hull.pop();
            }
            hull.push(i);
        }
        hull.pop();
    }
    if hull.is_empty() {
        hull.push(idx[0]);
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hull_keeps_its_corners_only() {
        // A 3 × 2 rectangle's corners among points inside it, on its edges and repeated: the
        // four corners, each once; then a triangle, two points and one.
        let mut p = vec![[0.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 2.0]];
        let mut s = 7u64;
        for _ in 0..200 {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let (u, v) = (
                (s >> 11) as f64 / 2f64.powi(53),
                (s >> 20) as f64 / 2f64.powi(44),
            );
            p.push([3.0 * u, 2.0 * v]);
        }
        p.extend([[1.5, 0.0], [3.0, 1.0], [0.0, 0.5], [3.0, 2.0], [0.0, 0.0]]);
        let mut hull = hull_corners(&p);
        hull.sort_unstable();
        let corners: Vec<[f64; 2]> = hull.iter().map(|&k| p[k]).collect();
        assert_eq!(corners.len(), 4, "{corners:?}");
        for c in [[0.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 2.0]] {
            assert!(corners.contains(&c), "{c:?} in {corners:?}");
        }
        let mut t = hull_corners(&[[0.0, 0.0], [1.0, 0.2], [2.0, 0.0], [1.0, 1.0]]);
        t.sort_unstable();
        assert_eq!(t, [0, 2, 3]);
        assert_eq!(hull_corners(&[[0.0, 0.0], [1.0, 0.0]]).len(), 2);
        assert_eq!(hull_corners(&[[1.0, 1.0]]), [0]);
        assert!(hull_corners(&[]).is_empty());
        // Points on one line: its two ends.
        let mut line = hull_corners(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]]);
        line.sort_unstable();
        assert_eq!(line, [0, 3]);
    }

    #[test]
    fn the_tangents_complete_a_normal_to_a_right_handed_frame() {
        for n in [
            Vector3::y(),
            Vector3::x(),
            Vector3::new(0.6, 0.0, 0.8),
            Vector3::new(-0.95, 0.1, 0.3).normalize(),
        ] {
            let (t1, t2) = tangents(&n);
            assert!((t1.norm() - 1.0).abs() < 1e-15 && (t2.norm() - 1.0).abs() < 1e-15);
            assert!(t1.dot(&n).abs() < 1e-15 && t2.dot(&n).abs() < 1e-15);
            assert!((t1.cross(&t2) - n).norm() < 1e-15, "{n}");
        }
    }
}
