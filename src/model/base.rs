//! The block's base: the flat footprint it stands on (`[base]` in a scene file;
//! `derivations/13-base-contact.md`).
//!
//! The paper idealises the contact as three points. A monolith touches its rock over its whole
//! base: the footprint is the section's base rectangle, an outline the engineer gives, or, for
//! a block without a section, the bounding rectangle of its three frame contacts. It lies in
//! the block's plane y′ = −ȳ (ȳ the centre of mass's height above the base).

use super::error::ModelError;

/// A flat base: a simple polygon in the block's own axes (x′, z′) about the centre of mass,
/// its corners in the order whose shoelace area over (x′, z′) is positive, at the depth ȳ below
/// the centre of mass.
#[derive(Debug, Clone, PartialEq)]
pub struct Base {
    outline: Vec<[f64; 2]>,
    depth: f64,
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
                format!("must be zero or more, got {depth}"),
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
        Ok(Base { outline, depth })
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
}

/// The signed area (m²): the shoelace sum over (x′, z′) taken as a plane's (x, y); a base
/// keeps the winding that makes it positive.
fn signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
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
}
