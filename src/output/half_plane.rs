//! Half-planes of the plan (X, Z) and the convex polygons they cut: the plan view's regions
//! and faces (`plots/plan/regions.rs`) and the 3-D view's ground (`view/mod.rs`) are the view's
//! rectangle cut to where a plane of the foundation stands above the others.

use crate::Plane;

/// A half-plane of the plan, a·X + b·Z ≥ c.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct HalfPlane {
    pub a: f64,
    pub b: f64,
    pub c: f64,
}

impl HalfPlane {
    /// Where plane `p` stands at least as high as plane `q`.
    pub fn above(p: &Plane, q: &Plane) -> HalfPlane {
        // height = (e − m_x X − m_z Z) / m_y
        let (mp, mq) = (p.normal(), q.normal());
        HalfPlane {
            a: -mp.x / mp.y + mq.x / mq.y,
            b: -mp.z / mp.y + mq.z / mq.y,
            c: q.offset() / mq.y - p.offset() / mp.y,
        }
    }

    /// The other side (its edge included).
    #[cfg_attr(not(feature = "plots"), allow(dead_code))]
    pub fn opposite(self) -> HalfPlane {
        HalfPlane {
            a: -self.a,
            b: -self.b,
            c: -self.c,
        }
    }
}

/// The part of convex `poly` (X, Z) in the half-plane `h` (one pass of Sutherland–Hodgman).
pub(super) fn clip(poly: &[(f64, f64)], h: HalfPlane) -> Vec<(f64, f64)> {
    let HalfPlane { a, b, c } = h;
    let inside = |p: (f64, f64)| a * p.0 + b * p.1 >= c;
    let mut out = Vec::new();
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        if inside(p) {
            out.push(p);
        }
        if inside(p) != inside(q) {
            let (fp, fq) = (a * p.0 + b * p.1 - c, a * q.0 + b * q.1 - c);
            let t = fp / (fp - fq);
            out.push((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)));
        }
    }
    out
}
