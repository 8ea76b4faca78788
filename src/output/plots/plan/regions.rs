//! The foundation on the plan view: the paper's three regions (each plane where it is real),
//! a ground's faces (each where it is the highest) or a general site's planes, as convex
//! polygons clipped to the view, with their names, colours and down-dip directions.

use super::{HORIZONTAL, P, PLANE_1, PLANE_2, View};
use crate::Scene;
use crate::geometry::PaperSite;
use crate::geometry::paper_planes::r as strike_2_distance;
use crate::output::half_plane::{HalfPlane, clip};
use crate::output::plots::sheet;
use plotters::prelude::*;

/// Which of the paper's regions: where the horizontal plane, plane 1 or plane 2 carries its
/// contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PaperRegion {
    Horizontal,
    One,
    Two,
}

/// A part of the foundation on the plan view: where it is drawn, where its name may go, its
/// name, colour and down-dip direction (in plan, unit; none for a level plane).
pub(super) struct Region {
    pub poly: Vec<P>,
    pub label_poly: Vec<P>,
    pub name: String,
    pub color: RGBColor,
    pub down: Option<P>,
}

/// Colours of a general site's planes or faces, in order.
const FACE_COLORS: [RGBColor; 8] = [
    HORIZONTAL,
    PLANE_1,
    PLANE_2,
    RGBColor(200, 120, 0),
    RGBColor(140, 60, 170),
    RGBColor(0, 150, 160),
    RGBColor(190, 50, 80),
    RGBColor(90, 110, 30),
];

/// The area of a polygon (shoelace).
pub(super) fn area_of(poly: &[P]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % n]);
            p.0 * q.1 - q.0 * p.1
        })
        .sum::<f64>()
        .abs()
}

/// The half-planes where planes 1 and 2 are real (their regions).
pub(super) fn region_half_planes(paper: &PaperSite) -> [HalfPlane; 2] {
    let (sk, ck) = paper.foundation.kappa.sin_cos();
    [
        HalfPlane {
            a: 1.0,
            b: 0.0,
            c: paper.frame.l2x,
        },
        HalfPlane {
            a: ck,
            b: -sk,
            c: strike_2_distance(paper),
        },
    ]
}

/// The region of each plane inside the view, as convex polygons (the horizontal one where
/// neither inclined plane is; planes 1 and 2 overlap beyond both strikes, where each contact
/// still uses only its own plane).
pub(super) fn regions(paper: &PaperSite, view: View) -> [(PaperRegion, Vec<P>); 3] {
    let rect = view.corners();
    let [h1, h2] = region_half_planes(paper);
    [
        (
            PaperRegion::Horizontal,
            clip(&clip(&rect, h1.opposite()), h2.opposite()),
        ),
        (PaperRegion::One, clip(&rect, h1)),
        (PaperRegion::Two, clip(&rect, h2)),
    ]
}

/// The down-dip direction of a plane in plan (unit), none for a level one.
fn down_dip(plane: &crate::Plane) -> Option<P> {
    let dip = plane.dip();
    (dip > 1e-9).then(|| {
        let a = plane.dip_direction();
        (a.cos(), a.sin())
    })
}

/// The regions of the scene's foundation inside `view`: the paper's three (named as the paper
/// names them), a ground surface's triangles, a ground's faces (each where it is the highest),
/// or a general site's three planes (the paper's regions on them: plane 0 where it is above
/// both others, planes 1 and 2 where they are above plane 0).
pub(super) fn foundation_regions(scene: &Scene, view: View) -> Vec<Region> {
    let site = scene.site();
    if let Some(paper) = site.as_paper() {
        return paper_regions(paper, view);
    }
    if let Some((ground, _)) = site.ground().filter(|(g, _)| g.is_surface()) {
        return surface_regions(ground, view);
    }
    face_regions(scene, view)
}

/// The paper's three regions, each named where its plane is the only inclined one.
fn paper_regions(paper: &PaperSite, view: View) -> Vec<Region> {
    let g = paper.foundation;
    let (sk, ck) = g.kappa.sin_cos();
    let [h1, h2] = region_half_planes(paper);
    regions(paper, view)
        .into_iter()
        .map(|(plane, poly)| {
            let label_poly = match plane {
                PaperRegion::Horizontal => poly.clone(),
                PaperRegion::One => clip(&poly, h2.opposite()),
                PaperRegion::Two => clip(&poly, h1.opposite()),
            };
            let (name, color, down) = match plane {
                PaperRegion::Horizontal => ("horizontal".to_string(), HORIZONTAL, None),
                PaperRegion::One => (
                    format!("plane 1, dip {}°", sheet::short(g.xi.to_degrees())),
                    PLANE_1,
                    Some((-1.0, 0.0)),
                ),
                PaperRegion::Two => (
                    format!("plane 2, dip {}°", sheet::short(g.zeta.to_degrees())),
                    PLANE_2,
                    Some((-ck, sk)),
                ),
            };
            Region {
                poly,
                label_poly,
                name,
                color,
                down,
            }
        })
        .collect()
}

/// A surface: each triangle in the view, shaded by its dip (darker: steeper); too many to name.
fn surface_regions(ground: &crate::Ground, view: View) -> Vec<Region> {
    let View { x0, x1, z0, z1 } = view;
    let borders = [
        HalfPlane {
            a: 1.0,
            b: 0.0,
            c: x0,
        },
        HalfPlane {
            a: -1.0,
            b: 0.0,
            c: -x1,
        },
        HalfPlane {
            a: 0.0,
            b: 1.0,
            c: z0,
        },
        HalfPlane {
            a: 0.0,
            b: -1.0,
            c: -z1,
        },
    ];
    ground
        .faces_in((x0, x1, z0, z1))
        .into_iter()
        .filter_map(|k| {
            let corners = ground.triangle(k)?;
            let mut poly = corners.map(|c| (c[0], c[1])).to_vec();
            for edge in borders {
                poly = clip(&poly, edge);
            }
            let steep = (ground.faces()[k].dip() / 60f64.to_radians()).min(1.0);
            let shade = |light: u8, dark: u8| {
                (f64::from(light) + steep * (f64::from(dark) - f64::from(light))) as u8
            };
            Some(Region {
                label_poly: Vec::new(),
                poly,
                name: String::new(),
                color: RGBColor(shade(235, 110), shade(225, 80), shade(205, 50)),
                down: None,
            })
        })
        .collect()
}

/// A ground's faces (each where it is above every other) or a general site's planes.
fn face_regions(scene: &Scene, view: View) -> Vec<Region> {
    let site = scene.site();
    let rect = view.corners();
    let (planes, word): (Vec<_>, &str) = match site.ground() {
        Some((ground, _)) => (ground.faces().to_vec(), "face"),
        None => (site.planes().to_vec(), "plane"),
    };
    (0..planes.len())
        .map(|k| {
            let over: Vec<usize> = match (site.ground(), k) {
                (Some(_), _) => (0..planes.len()).filter(|&j| j != k).collect(),
                (None, 0) => vec![1, 2],
                (None, _) => vec![0],
            };
            let poly = over.iter().fold(rect.clone(), |poly, &j| {
                if poly.len() < 3 {
                    poly
                } else {
                    clip(&poly, HalfPlane::above(&planes[k], &planes[j]))
                }
            });
            let plane = &planes[k];
            Region {
                label_poly: poly.clone(),
                poly,
                name: format!(
                    "{word} {k}, dip {}°",
                    sheet::short(plane.dip().to_degrees())
                ),
                color: FACE_COLORS[k % FACE_COLORS.len()],
                down: down_dip(plane),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_tile_the_view_with_the_inclined_ones_overlapping_beyond_both_strikes() {
        let scene = Scene::default_scene();
        let paper = scene.site().as_paper().unwrap();
        let view = View {
            x0: -20.0,
            x1: 30.0,
            z0: -15.0,
            z1: 25.0,
        };
        let [h, one, two] = regions(paper, view);
        let whole = 50.0 * 40.0;
        // Inclusion–exclusion: horizontal + plane 1 + plane 2 − overlap = the view.
        let [h1, h2] = region_half_planes(paper);
        let rect = vec![(-20.0, -15.0), (30.0, -15.0), (30.0, 25.0), (-20.0, 25.0)];
        let both = clip(&clip(&rect, h1), h2);
        let sum = area_of(&h.1) + area_of(&one.1) + area_of(&two.1) - area_of(&both);
        assert!((sum - whole).abs() < 1e-9 * whole, "{sum} vs {whole}");
        // Plane 1 is X ≥ L2X: its area is known in closed form.
        let l2x = paper.frame.l2x;
        assert!((area_of(&one.1) - (30.0 - l2x) * 40.0).abs() < 1e-9);
        // Every vertex of the horizontal region is in it (to round-off).
        for &(x, z) in &h.1 {
            assert!(x <= l2x + 1e-9);
            let (sk, ck) = paper.foundation.kappa.sin_cos();
            assert!(x * ck - z * sk <= strike_2_distance(paper) + 1e-9);
        }
    }

    #[test]
    fn a_face_is_drawn_where_it_is_above_the_other() {
        // Two planes crossing on X = 0: level, and rising with X. The rising one is above
        // where X > 0.
        let origin = nalgebra::Vector3::zeros();
        let level = crate::Plane::through(nalgebra::Vector3::y(), origin);
        let rising =
            crate::Plane::through(nalgebra::Vector3::new(-1.0, 1.0, 0.0).normalize(), origin);
        let h = HalfPlane::above(&rising, &level);
        let square = vec![(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let part = clip(&square, h);
        assert!((area_of(&part) - 2.0).abs() < 1e-12);
        assert!(part.iter().all(|p| p.0 >= -1e-12), "{part:?}");
    }
}
