//! The block's base: the flat footprint it stands on (`[base]` in a scene file;
//! `derivations/13-base-contact.md`).
//!
//! The paper idealises the contact as three points. A monolith touches its rock over its whole
//! base: the footprint is the section's base rectangle, an outline the engineer gives, or, for
//! a block without a section, the bounding rectangle of its three frame contacts. It lies in
//! the block's plane y′ = −ȳ (ȳ the centre of mass's height above the base).

use super::error::ModelError;
use crate::geometry::signed_area;
use nalgebra::Vector3;

/// A flat base: a simple polygon in the block's own axes (x′, z′) about the centre of mass,
/// its corners in the order whose shoelace area over (x′, z′) is positive, at the depth ȳ below
/// the centre of mass.
#[derive(Debug, Clone, PartialEq)]
pub struct Base {
    outline: Vec<[f64; 2]>,
    depth: f64,
    cast: bool,
}

/// Points and weights of a triangle (corners `t`, its area `area` in m²): cut into `split`²
/// alike triangles, three points in each at 2/3, 1/6, 1/6 of its corners, each weighing a third
/// of it. Exact for quadratics; a flat base's ears and a cast base's relief's faces alike
/// (`derivations/13-base-contact.md` §9).
pub fn triangle_quadrature(
    t: [Vector3<f64>; 3],
    area: f64,
    split: usize,
) -> Vec<(Vector3<f64>, f64)> {
    let split = split.max(1);
    let [a, b, c] = t;
    let n = split as f64;
    let at = |i: f64, j: f64| {
        let (s, t) = (i / n, j / n);
        Vector3::new(
            a.x + s * (b.x - a.x) + t * (c.x - a.x),
            a.y + s * (b.y - a.y) + t * (c.y - a.y),
            a.z + s * (b.z - a.z) + t * (c.z - a.z),
        )
    };
    let weight = area / (split * split) as f64 / 3.0;
    let mut out = Vec::with_capacity(3 * split * split);
    for i in 0..split {
        for j in 0..split - i {
            let (fi, fj) = (i as f64, j as f64);
            let mut small = vec![[at(fi, fj), at(fi + 1.0, fj), at(fi, fj + 1.0)]];
            if i + j + 1 < split {
                small.push([at(fi + 1.0, fj), at(fi + 1.0, fj + 1.0), at(fi, fj + 1.0)]);
            }
            for [p, q, r] in small {
                for (u, v, w) in [(4.0, 1.0, 1.0), (1.0, 4.0, 1.0), (1.0, 1.0, 4.0)] {
                    let point = Vector3::new(
                        (u * p.x + v * q.x + w * r.x) / 6.0,
                        (u * p.y + v * q.y + w * r.y) / 6.0,
                        (u * p.z + v * q.z + w * r.z) / 6.0,
                    );
                    out.push((point, weight));
                }
            }
        }
    }
    out
}

impl Base {
    /// The polygon `outline` (x′, z′ about the centre of mass, m; either winding) at `depth`
    /// (m) below the centre of mass. At least three corners, finite, an area, and no edge
    /// crossing another: the errors name `base.outline_m`.
    pub fn polygon(outline: Vec<[f64; 2]>, depth: f64) -> Result<Base, ModelError> {
        let key = "base.outline_m";
        if outline.len() < 3 {
            return Err(ModelError::new(
                key,
                format!("a base needs at least three corners, got {}", outline.len()),
            ));
        }
        if let Some(k) = outline
            .iter()
            .position(|p| !p[0].is_finite() || !p[1].is_finite())
        {
            return Err(ModelError::new(
                key,
                format!("corner {k} is not a pair of finite numbers"),
            ));
        }
        if !depth.is_finite() || depth < 0.0 {
            return Err(ModelError::new(
                "monolith.height_m (the centre of mass's height)",
                format!("must be zero or more, got {}", crate::numeric::given(depth)),
            ));
        }
        if let Some((a, b)) = crossing_edges(&outline) {
            return Err(ModelError::new(
                key,
                format!("edge {a} crosses edge {b}: the outline must be a simple polygon"),
            ));
        }
        let mut outline = outline;
        let area = signed_area(&outline);
        let size = diameter(&outline);
        if area.abs() <= 1e-9 * size * size {
            return Err(ModelError::new(
                key,
                "the outline has no area (its corners are on one line)",
            ));
        }
        if area < 0.0 {
            outline.reverse();
        }
        Ok(Base {
            outline,
            depth,
            cast: false,
        })
    }

    /// The rectangle x′ in `x`, z′ in `z` (m, about the centre of mass) at `depth` (m).
    pub fn rectangle(x: [f64; 2], z: [f64; 2], depth: f64) -> Result<Base, ModelError> {
        Base::polygon(
            vec![[x[0], z[0]], [x[1], z[0]], [x[1], z[1]], [x[0], z[1]]],
            depth,
        )
    }

    /// The bounding rectangle of three frame contacts (x′, z′ about the centre of mass) at
    /// `depth`: a block given only by its frame.
    pub fn around(contacts: &[[f64; 2]; 3], depth: f64) -> Result<Base, ModelError> {
        let [x0, x1, z0, z1] = crate::geometry::plan_box(contacts.iter().copied());
        Base::rectangle([x0, x1], [z0, z1], depth)
    }

    /// The same footprint cast onto its rock (`[base] cast = true`): its underside is the
    /// foundation's own surface under it where it rests, not a plane
    /// (`derivations/13-base-contact.md` §10).
    pub fn with_cast(mut self, cast: bool) -> Base {
        self.cast = cast;
        self
    }

    /// Whether the base is cast onto its rock.
    pub fn is_cast(&self) -> bool {
        self.cast
    }

    /// The outline cut into triangles by its ears (x′, z′, each counter-clockwise).
    pub fn triangles(&self) -> Vec<[[f64; 2]; 3]> {
        ears(&self.outline)
    }

    /// The corners (x′, z′), in the order of a positive shoelace area.
    pub fn outline(&self) -> &[[f64; 2]] {
        &self.outline
    }

    /// ȳ: the centre of mass's height above the base (m).
    pub fn depth(&self) -> f64 {
        self.depth
    }

    /// The largest distance between two corners (m): the base's size.
    pub fn size(&self) -> f64 {
        diameter(&self.outline)
    }

    /// The area (m²).
    pub fn area(&self) -> f64 {
        signed_area(&self.outline)
    }

    /// Whether (x′, z′) is on the base (its boundary included).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        crate::geometry::in_outline(&self.outline, p)
    }

    /// Points and weights (m²) of a quadrature over the base's area
    /// (`derivations/13-base-contact.md` §9): the outline cut into triangles by its ears, each
    /// triangle into `split`² alike, and in each the three-point rule exact for quadratics
    /// (points at ⅔, ⅙, ⅙ of its corners, a third of its area each). The weights add up to the
    /// area; the rule is exact for any quadratic over the base.
    pub fn quadrature(&self, split: usize) -> Vec<([f64; 2], f64)> {
        let lift = |[x, z]: [f64; 2]| Vector3::new(x, 0.0, z);
        ears(&self.outline)
            .into_iter()
            .flat_map(|[a, b, c]| {
                let area = signed_area(&[a, b, c]);
                triangle_quadrature([lift(a), lift(b), lift(c)], area, split)
            })
            .map(|(p, w)| ([p.x, p.z], w))
            .collect()
    }

    /// Points and weights (m) of the five-point Gauss–Legendre rule along edge `k` (corner k to
    /// k + 1): where an edge lies on a face, its pressure and friction act there
    /// (`derivations/13-base-contact.md` §9). Exact for polynomials of degree nine along it.
    pub fn edge_quadrature(&self, k: usize) -> Vec<([f64; 2], f64)> {
        const NODES: [(f64, f64); 5] = [
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let n = self.outline.len();
        let (a, b) = (self.outline[k % n], self.outline[(k + 1) % n]);
        let half = 0.5 * (b[0] - a[0]).hypot(b[1] - a[1]);
        NODES
            .iter()
            .map(|&(x, w)| {
                let t = 0.5 * (1.0 + x);
                (
                    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])],
                    w * half,
                )
            })
            .collect()
    }
}

/// The triangles of a simple polygon of positive winding, by ear clipping: a corner whose
/// triangle with its neighbours turns left and holds no other corner is cut off, until three
/// are left.
fn ears(outline: &[[f64; 2]]) -> Vec<[[f64; 2]; 3]> {
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let mut left: Vec<[f64; 2]> = outline.to_vec();
    let mut out = Vec::with_capacity(outline.len().saturating_sub(2));
    while left.len() > 3 {
        let n = left.len();
        let ear = (0..n).find(|&k| {
            let (a, b, c) = (left[(k + n - 1) % n], left[k], left[(k + 1) % n]);
            orient(a, b, c) > 0.0
                && left.iter().all(|&p| {
                    p == a
                        || p == b
                        || p == c
                        || orient(a, b, p) < 0.0
                        || orient(b, c, p) < 0.0
                        || orient(c, a, p) < 0.0
                })
        });
        // A simple polygon always has an ear; round-off on nearly collinear corners may hide
        // it, and then the corner of least turn goes.
        let k = ear.unwrap_or_else(|| {
            (0..n)
                .max_by(|&i, &j| {
                    let o = |k: usize| orient(left[(k + n - 1) % n], left[k], left[(k + 1) % n]);
                    o(i).total_cmp(&o(j))
                })
                .unwrap_or(0)
        });
        let (a, b, c) = (left[(k + n - 1) % n], left[k], left[(k + 1) % n]);
        if orient(a, b, c) > 0.0 {
            out.push([a, b, c]);
        }
        left.remove(k);
    }
    if left.len() == 3 && orient(left[0], left[1], left[2]) > 0.0 {
        out.push([left[0], left[1], left[2]]);
    }
    out
}

fn diameter(p: &[[f64; 2]]) -> f64 {
    let mut d: f64 = 0.0;
    for a in p {
        for b in p {
            d = d.max((a[0] - b[0]).hypot(a[1] - b[1]));
        }
    }
    d
}

/// The first two edges of `p` that cross (not neighbours), if any.
fn crossing_edges(p: &[[f64; 2]]) -> Option<(usize, usize)> {
    let n = p.len();
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    for i in 0..n {
        for j in i + 1..n {
            let neighbours = j == i + 1 || (i == 0 && j == n - 1);
            if neighbours {
                continue;
            }
            let (a, b, c, d) = (p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]);
            let (o1, o2) = (orient(a, b, c), orient(a, b, d));
            let (o3, o4) = (orient(c, d, a), orient(c, d, b));
            if o1 * o2 <= 0.0 && o3 * o4 <= 0.0 {
                return Some((i, j));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {

    #[test]
    fn the_triangle_rule_on_a_tilted_triangle_integrates_quadratics_exactly() {
        // The triangle (0,0,0), (2,1,0), (0,1,3): area |(2,1,0) × (0,1,3)|/2 = |(3,−6,2)|/2 =
        // 7/2. Over it ∫ x dA = A x̄ = 2A/3, and for linear f, g:
        // ∫ f g dA = A (Σ fᵢ gᵢ + Σ fᵢ Σ gᵢ)/12.
        let t = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(2.0, 1.0, 0.0),
            Vector3::new(0.0, 1.0, 3.0),
        ];
        let area: f64 = 0.5 * (t[1] - t[0]).cross(&(t[2] - t[0])).norm();
        assert!((area - 3.5).abs() < 1e-15);
        for split in [1, 2, 3] {
            let pts = triangle_quadrature(t, area, split);
            let int =
                |f: &dyn Fn(&Vector3<f64>) -> f64| pts.iter().map(|(p, w)| f(p) * w).sum::<f64>();
            assert!((int(&|_| 1.0) - area).abs() < 1e-12);
            assert!((int(&|p| p.x) - area * 2.0 / 3.0).abs() < 1e-12);
            // x at the corners 0, 2, 0 and z 0, 0, 3: Σ xᵢ zᵢ = 0, Σ xᵢ Σ zᵢ = 6.
            let xz = area * (0.0 + 2.0 * 3.0) / 12.0;
            assert!((int(&|p| p.x * p.z) - xz).abs() < 1e-12, "{split}");
        }
    }

    use super::*;

    #[test]
    fn a_frame_block_stands_on_the_bounding_rectangle_of_its_contacts() {
        let b = Base::around(&[[-2.0, 1.0], [3.0, 1.0], [3.0, -4.0]], 0.0).unwrap();
        assert_eq!(b.area(), 25.0);
        assert!(b.contains([0.0, 0.0]) && b.contains([3.0, -4.0]));
        assert!(!b.contains([3.1, 0.0]));
    }

    #[test]
    fn an_outline_given_in_either_winding_is_kept_in_one() {
        let cw = vec![[0.0, 0.0], [0.0, 1.0], [2.0, 1.0], [2.0, 0.0]];
        let b = Base::polygon(cw, 1.0).unwrap();
        assert!((b.area() - 2.0).abs() < 1e-15);
        assert_eq!(b.size(), 5f64.sqrt());
    }

    #[test]
    fn an_outline_that_is_not_a_simple_polygon_is_refused_naming_the_key() {
        let bow_tie = vec![[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
        let e = Base::polygon(bow_tie, 0.0).unwrap_err();
        assert_eq!(e.key, "base.outline_m");
        assert!(e.reason.contains("crosses"), "{}", e.reason);
        let line = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert!(Base::polygon(line, 0.0).is_err());
        assert!(Base::polygon(vec![[0.0, 0.0], [1.0, 0.0]], 0.0).is_err());
        let nan = vec![[0.0, 0.0], [1.0, f64::NAN], [1.0, 1.0]];
        assert_eq!(Base::polygon(nan, 0.0).unwrap_err().key, "base.outline_m");
    }

    #[test]
    fn a_point_in_the_notch_of_an_l_shaped_base_is_off_it() {
        let l = vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ];
        let b = Base::polygon(l, 0.0).unwrap();
        assert!(b.contains([0.5, 1.5]) && b.contains([1.5, 0.5]));
        assert!(!b.contains([1.5, 1.5]));
        assert!((b.area() - 3.0).abs() < 1e-15);
    }

    #[test]
    fn the_quadrature_of_an_l_shaped_base_integrates_quadratics_exactly() {
        let l = vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ];
        let b = Base::polygon(l, 0.0).unwrap();
        for split in [1, 3] {
            let q = b.quadrature(split);
            assert_eq!(q.len(), 4 * 3 * split * split);
            let integral =
                |f: &dyn Fn(f64, f64) -> f64| q.iter().map(|(p, w)| w * f(p[0], p[1])).sum::<f64>();
            // By hand, over [0,2]×[0,1] and [0,1]×[1,2]: ∫1 = 2 + 1, ∫x = 2·1 + 1·½,
            // ∫z = 2·½ + 1·1½, ∫x² = 8/3 + 1/3, ∫xz = 2·½ + ½·1½.
            assert!((integral(&|_, _| 1.0) - 3.0).abs() < 1e-14);
            assert!((integral(&|x, _| x) - 2.5).abs() < 1e-14);
            assert!((integral(&|_, z| z) - 2.5).abs() < 1e-14);
            assert!((integral(&|x, _| x * x) - 3.0).abs() < 1e-13);
            assert!((integral(&|x, z| x * z) - 1.75).abs() < 1e-13);
            assert!(q.iter().all(|(p, _)| b.contains(*p)));
        }
    }

    #[test]
    fn the_quadrature_along_an_edge_integrates_its_length_and_moments() {
        let b = Base::rectangle([-3.0, 3.0], [-1.0, 1.0], 0.0).unwrap();
        // Edge 0 runs from (−3, −1) to (3, −1): ∫1 = 6, ∫x = 0, ∫x⁴ = 2·3⁵/5.
        let q = b.edge_quadrature(0);
        let integral = |f: &dyn Fn(f64) -> f64| q.iter().map(|(p, w)| w * f(p[0])).sum::<f64>();
        assert!((integral(&|_| 1.0) - 6.0).abs() < 1e-13);
        assert!(integral(&|x| x).abs() < 1e-13);
        assert!((integral(&|x| x.powi(4)) - 2.0 * 243.0 / 5.0).abs() < 1e-11);
        assert!(q.iter().all(|(p, _)| (p[1] + 1.0).abs() < 1e-15));
    }
}
