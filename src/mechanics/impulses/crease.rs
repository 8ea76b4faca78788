//! The normals of a corner in a crease: two or three faces at one point of the body, solved
//! together and exactly in a sweep (`derivations/13-base-contact.md` §4).

use super::{Body, Solved};
use crate::contact::ContactRow;
use nalgebra::{Matrix3, Vector3};

/// The rows next to row `i` at the same point of the same bodies.
pub(super) fn point_group(rows: &[ContactRow], i: usize) -> std::ops::Range<usize> {
    let same = |j: usize| rows[j].same_point(&rows[i]);
    let mut start = i;
    while start > 0 && same(start - 1) {
        start -= 1;
    }
    let mut end = i + 1;
    while end < rows.len() && same(end) {
        end += 1;
    }
    start..end
}

/// The normal impulses of the first three rows of `group` at one point of the bodies (a
/// fourth and more, which no ground of faces gives a corner but at a point where four planes
/// meet, go alone), the others held: the small linear complementarity problem W p + q ≥ 0,
/// p ≥ 0, p ⟂ (W p + q), solved exactly by trying each set of rows that push (W the group's
/// normal effective inverse mass, q their closing velocities without their own impulses).
/// Where no set fits (a singular W: faces whose normals are not independent), each row alone.
pub(super) fn normal_at_point(
    out: &mut Solved,
    rows: &[ContactRow],
    group: std::ops::Range<usize>,
    bodies: &[Body],
) {
    let g = group.len().min(3);
    let idx: Vec<usize> = group.clone().take(g).collect();
    let first = &rows[idx[0]];
    let (a, b) = (&first.a, first.b.as_ref());
    let u = out.velocity(a, b);
    let (body_a, other) = (&bodies[a.body], b.map(|b| (&bodies[b.body], &b.arm)));
    let k = |x: &Vector3<f64>, y: &Vector3<f64>| {
        let ka = body_a.k(&a.arm, x, y);
        match other {
            None => ka,
            Some((body_b, arm_b)) => ka + body_b.k(arm_b, x, y),
        }
    };
    let mut w = Matrix3::zeros();
    let mut q = Vector3::zeros();
    for (i, &ia) in idx.iter().enumerate() {
        for (j, &ib) in idx.iter().enumerate() {
            w[(i, j)] = k(&rows[ia].normal, &rows[ib].normal);
        }
    }
    for (i, &ia) in idx.iter().enumerate() {
        let held: f64 = (0..g).map(|j| w[(i, j)] * out.normal[idx[j]]).sum();
        q[i] = rows[ia].normal.dot(&u) + rows[ia].closing - held;
    }
    let Some(p) = pushing_set(&w, &q, g) else {
        for &i in &idx {
            let c = &rows[i];
            let u = out.velocity(&c.a, c.b.as_ref());
            let pn_old = out.normal[i];
            let pn = (pn_old - (c.normal.dot(&u) + c.closing) / k(&c.normal, &c.normal)).max(0.0);
            out.apply(bodies, &c.a, c.b.as_ref(), c.normal * (pn - pn_old));
            out.normal[i] = pn;
        }
        return;
    };
    for (i, &r) in idx.iter().enumerate() {
        let c = &rows[r];
        out.apply(
            bodies,
            &c.a,
            c.b.as_ref(),
            c.normal * (p[i] - out.normal[r]),
        );
        out.normal[r] = p[i];
    }
}

/// The solution of the complementarity problem of the first `g` rows of W p + q by its active
/// sets, the first set that fits; None where none does.
fn pushing_set(w: &Matrix3<f64>, q: &Vector3<f64>, g: usize) -> Option<Vector3<f64>> {
    for set in 0u32..(1 << g) {
        let pushes = |a: usize| set & (1 << a) != 0;
        let mut p = Vector3::zeros();
        if set != 0 {
            // W and q of the rows that push, the others' rows and columns the identity's
            // (their p stays zero): one 3 × 3 solve, on the stack.
            let ws = Matrix3::from_fn(|a, b| {
                if pushes(a) && pushes(b) {
                    w[(a, b)]
                } else if a == b {
                    1.0
                } else {
                    0.0
                }
            });
            let qs = Vector3::from_fn(|a, _| if pushes(a) { -q[a] } else { 0.0 });
            let Some(x) = ws.lu().solve(&qs) else {
                continue;
            };
            p = x;
        }
        let scale = q.abs().max() + 1e-300;
        let fits = (0..g).all(|a| {
            let gap_rate = (0..g).map(|b| w[(a, b)] * p[b]).sum::<f64>() + q[a];
            if pushes(a) {
                p[a] >= 0.0
            } else {
                gap_rate >= -1e-12 * scale
            }
        });
        if fits {
            return Some(p);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::super::*;
    use crate::contact::Shear;

    #[test]
    fn a_corner_in_a_v_groove_is_held_by_both_faces_as_the_statics_of_the_groove_say() {
        // A point mass (no arm) dropped into a symmetric groove of faces at ±φ: both faces push,
        // each P = m g h / (2 cos φ), and it stops; with the groove tipped, the statics of two
        // forces along the normals carry the weight: P1 n1 + P2 n2 = m g h Y.
        let (m, g, h) = (1000.0, 9.81, 1e-3);
        let body = Body {
            inv_mass: 1.0 / m,
            inv_inertia: Matrix3::identity(),
        };
        for (a, b) in [(30f64, 30f64), (20.0, 50.0)] {
            let (a, b) = (a.to_radians(), b.to_radians());
            let n1 = Vector3::new(-a.sin(), a.cos(), 0.0);
            let n2 = Vector3::new(b.sin(), b.cos(), 0.0);
            let row = |n: Vector3<f64>| ContactRow {
                a: Side {
                    body: 0,
                    arm: Vector3::zeros(),
                },
                b: None,
                normal: n,
                shear: Shear::none(),
                closing: 0.0,
                guess: Vector3::zeros(),
            };
            let free = Motion {
                v: Vector3::new(0.0, -g * h, 0.0),
                w: Vector3::zeros(),
            };
            let until = Until {
                tol: 1e-14,
                max_sweeps: 50,
            };
            let s = solve(&[body], &[free], &[row(n1), row(n2)], &[], until);
            assert!(s.motion[0].v.norm() < 1e-14, "{}", s.motion[0].v);
            // The two normals' statics by Cramer's rule in (X, Y).
            let det = n1.x * n2.y - n2.x * n1.y;
            let w = m * g * h;
            let p1 = (0.0 * n2.y - n2.x * w) / det;
            let p2 = (n1.x * w - 0.0 * n1.y) / det;
            assert!((s.normal[0] - p1).abs() < 1e-12 * w, "{} {p1}", s.normal[0]);
            assert!((s.normal[1] - p2).abs() < 1e-12 * w, "{} {p2}", s.normal[1]);
            // Solved together at the point in the first sweep; the second only finds nothing moves.
            assert_eq!(s.sweeps, 2);
        }
    }
}
