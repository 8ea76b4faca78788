//! The plan view from above, like the paper's Figure 12 (issue #13, item 9): the foundation's
//! three regions shaded and named with their dips and down-dip arrows, the strike lines, the
//! hydraulic force on its line of action at the start, the contact frame along the route with
//! the contacts numbered at the start and the end, and the CM path — enlarged in an inset when
//! it is short beside the frame.

use super::sheet::{self, Area, Entry, Mark, Res, Sheet, err};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use slideroute::Row;
use slideroute::Scene;
use slideroute::internals::geometry::paper_planes::{PaperPlane as Plane, r as strike_2_distance};
use slideroute::internals::geometry::{PaperSite, direct};
use slideroute::{Displacement, Pose};
use std::path::Path;

pub(super) const PLANE_1: RGBColor = RGBColor(30, 90, 200);
pub(super) const PLANE_2: RGBColor = RGBColor(0, 140, 60);
pub(super) const HORIZONTAL: RGBColor = RGBColor(150, 130, 100);
const FORCE: RGBColor = RGBColor(150, 30, 150);

/// Sheet size of a plan view (pixels).
pub(super) const SIZE: (u32, u32) = (1200, 760);
const MARGIN: u32 = 10;
const X_LABELS: u32 = 40;
const Y_LABELS: u32 = 55;

/// One route on a plan view: its name in the legend, its rows (thinned) and its colour.
pub(super) struct Track<'r> {
    pub name: String,
    pub rows: &'r [Row],
    pub color: RGBColor,
}

type P = (f64, f64);

/// The frame's vertices in plan at a row's pose: from the row's tilts on the paper's site, by
/// the direct pose solver on any other (a row does not carry the roll ψ).
fn vertices(scene: &Scene, row: &Row) -> Option<[P; 3]> {
    let d = Displacement::new(row.x_m, row.z_m, row.theta_deg.to_radians());
    let v = match scene.site().as_paper() {
        Some(paper) => {
            Pose::from_tilts(
                paper,
                d,
                row.alpha_deg.to_radians(),
                row.beta_deg.to_radians(),
            )
            .ok()?
            .vertices
        }
        None => direct::solve(scene.site(), d).ok()?.vertices,
    };
    Some(v.map(|v| (v.x, v.z)))
}

/// Frame outlines every 1/8 of a route's rows (and at its end).
fn outlines_of(scene: &Scene, rows: &[Row]) -> Vec<[P; 3]> {
    let every = (rows.len() / 8).max(1);
    rows.iter()
        .enumerate()
        .filter(|(k, _)| k % every == 0 || *k + 1 == rows.len())
        .filter_map(|(_, r)| vertices(scene, r))
        .collect()
}

/// The part of convex `poly` where a·x + b·z ≥ c (one pass of Sutherland–Hodgman).
fn clip_half_plane(poly: &[P], (a, b, c): (f64, f64, f64)) -> Vec<P> {
    let inside = |p: P| a * p.0 + b * p.1 >= c;
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

/// The half-planes (a, b, c: a·X + b·Z ≥ c) where planes 1 and 2 are real (their regions).
fn region_half_planes(paper: &PaperSite) -> [(f64, f64, f64); 2] {
    let (sk, ck) = paper.foundation.kappa.sin_cos();
    [
        (1.0, 0.0, paper.frame.l2x),
        (ck, -sk, strike_2_distance(paper)),
    ]
}

/// The region of each plane inside the view `[x0, x1] × [z0, z1]`, as convex polygons (the
/// horizontal one where neither inclined plane is; planes 1 and 2 overlap beyond both strikes,
/// where each contact still uses only its own plane).
fn regions(paper: &PaperSite, (x0, x1, z0, z1): (f64, f64, f64, f64)) -> [(Plane, Vec<P>); 3] {
    let rect = vec![(x0, z0), (x1, z0), (x1, z1), (x0, z1)];
    let [h1, h2] = region_half_planes(paper);
    let neg = |(a, b, c): (f64, f64, f64)| (-a, -b, -c);
    [
        (
            Plane::Horizontal,
            clip_half_plane(&clip_half_plane(&rect, neg(h1)), neg(h2)),
        ),
        (Plane::One, clip_half_plane(&rect, h1)),
        (Plane::Two, clip_half_plane(&rect, h2)),
    ]
}

fn area_of(poly: &[P]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % n]);
            p.0 * q.1 - q.0 * p.1
        })
        .sum::<f64>()
        .abs()
}

/// A part of the foundation on the plan view: where it is drawn, where its name may go, its
/// name, colour and down-dip direction (in plan, unit; none for a level plane).
struct Region {
    poly: Vec<P>,
    label_poly: Vec<P>,
    name: String,
    color: RGBColor,
    down: Option<P>,
}

/// The marks of a contact's change of face.
const FACE_CHANGE: RGBColor = RGBColor(200, 30, 30);

/// Where a contact changed face, rode into a crease or left one, along `rows`: its plan
/// position then and what happened, e.g. "contact 2 into the crease with face 1 at 0.003 s".
fn face_changes(scene: &Scene, rows: &[Row]) -> Vec<(P, String)> {
    let mut out = Vec::new();
    for w in rows.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let mut said = Vec::new();
        for k in 0..3 {
            if a.faces[k] != b.faces[k] {
                said.push((k, format!("contact {k} onto face {}", b.faces[k])));
            }
        }
        for c in 0..3 {
            match (a.crease[c], b.crease[c]) {
                (None, Some(f)) => {
                    said.push((c, format!("contact {c} into the crease with face {f}")));
                }
                // Out of the crease onto its other face is said as the change of face above.
                (Some(f), None) if a.faces[c] == b.faces[c] => {
                    said.push((c, format!("contact {c} out of the crease with face {f}")));
                }
                _ => {}
            }
        }
        for (k, text) in said {
            if let Some(v) = vertices(scene, b) {
                out.push((v[k], format!("{text} at {} s", sheet::short(b.t_s))));
            }
        }
    }
    out
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

/// The down-dip direction of a plane in plan (unit), none for a level one.
fn down_dip(plane: &slideroute::Plane) -> Option<P> {
    let dip = plane.dip();
    (dip > 1e-9).then(|| {
        let a = plane.dip_direction();
        (a.cos(), a.sin())
    })
}

/// a·X + b·Z ≥ c where plane `p` stands at least as high as plane `q`.
fn above(p: &slideroute::Plane, q: &slideroute::Plane) -> (f64, f64, f64) {
    // height = (e − m_x X − m_z Z) / m_y
    let (mp, mq) = (p.normal(), q.normal());
    (
        -mp.x / mp.y + mq.x / mq.y,
        -mp.z / mp.y + mq.z / mq.y,
        q.offset() / mq.y - p.offset() / mp.y,
    )
}

/// The regions of the scene's foundation inside `view`: the paper's three (named as the paper
/// names them), a ground's faces (each where it is the highest), or a general site's three
/// planes (the paper's regions on them: plane 0 where it is above both others, planes 1 and 2
/// where they are above plane 0).
fn foundation_regions(scene: &Scene, view: (f64, f64, f64, f64)) -> Vec<Region> {
    let (x0, x1, z0, z1) = view;
    let rect = vec![(x0, z0), (x1, z0), (x1, z1), (x0, z1)];
    let site = scene.site();
    if let Some(paper) = site.as_paper() {
        let g = paper.foundation;
        let (sk, ck) = g.kappa.sin_cos();
        let [h1, h2] = region_half_planes(paper);
        let neg = |(a, b, c): (f64, f64, f64)| (-a, -b, -c);
        return regions(paper, view)
            .into_iter()
            .map(|(plane, poly)| {
                // Named where the plane is the only inclined one.
                let label_poly = match plane {
                    Plane::Horizontal => poly.clone(),
                    Plane::One => clip_half_plane(&poly, neg(h2)),
                    Plane::Two => clip_half_plane(&poly, neg(h1)),
                };
                let (name, color, down) = match plane {
                    Plane::Horizontal => ("horizontal".to_string(), HORIZONTAL, None),
                    Plane::One => (
                        format!("plane 1, dip {}°", sheet::short(g.xi.to_degrees())),
                        PLANE_1,
                        Some((-1.0, 0.0)),
                    ),
                    Plane::Two => (
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
            .collect();
    }
    if let Some((ground, _)) = site.ground().filter(|(g, _)| g.is_surface()) {
        // A surface: each triangle in the view, shaded by its dip (darker: steeper); too many
        // to name.
        return ground
            .faces_in(view)
            .into_iter()
            .filter_map(|k| {
                let corners = ground.triangle(k)?;
                let mut poly = corners.map(|c| (c[0], c[1])).to_vec();
                for edge in [
                    (1.0, 0.0, x0),
                    (-1.0, 0.0, -x1),
                    (0.0, 1.0, z0),
                    (0.0, -1.0, -z1),
                ] {
                    poly = clip_half_plane(&poly, edge);
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
            .collect();
    }
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
                    clip_half_plane(&poly, above(&planes[k], &planes[j]))
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
/// that distance; labels go there so that they stay off the data.
fn free_spot(poly: &[P], obstacles: &[P], view: (f64, f64, f64, f64)) -> Option<(P, f64)> {
    let (x0, x1, z0, z1) = view;
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
fn arrow(from: P, dir: P, len: f64) -> [Vec<P>; 2] {
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
fn along(a: P, b: P, n: usize) -> impl Iterator<Item = P> {
    (0..=n).map(move |k| {
        let t = k as f64 / n as f64;
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    })
}

/// The hydraulic force at the start, in plan: the point of its line of action nearest the CM
/// and its direction (x' at the start). F·i' with the couple −c·F·j' (eqs. 40, 41) is F acting
/// along x' on the line offset by −c along z' (`docs/conventions.md`: c > 0 turns θ up).
fn line_of_action(scene: &Scene, start: &Row) -> Option<(P, P, f64, f64)> {
    let loads = scene.loads()?;
    let (s, c) = start.theta_deg.to_radians().sin_cos();
    let x_dir = (c, s);
    let z_dir = (-s, c);
    let e = loads.eccentricity;
    let q = (start.x_m - e * z_dir.0, start.z_m - e * z_dir.1);
    Some((q, x_dir, loads.hydraulic_force, e))
}

/// Many CM paths drawn thin under the tracks (a probabilistic analysis's route fan): each a
/// polyline in plan (X, Z in m), with what the legend says of them.
pub(super) struct Fan<'f> {
    pub paths: &'f [Vec<[f64; 2]>],
    pub name: String,
}

/// The colour of a route fan.
const FAN: RGBColor = RGBColor(200, 30, 30);

/// Draws the plan view of `tracks` (the first one's frame in black), and of `fan` if any,
/// with `notes` in the panel.
pub(super) fn plan_view(
    path: &Path,
    scene: &Scene,
    title: &str,
    (tracks, fan): (&[Track], Option<&Fan>),
    notes: &[Entry],
) -> Res<()> {
    let fan_points = || {
        fan.into_iter()
            .flat_map(|f| f.paths.iter().flatten().map(|p| (p[0], p[1])))
    };
    let sheet = Sheet::new(path, SIZE, title)?;
    let outlines: Vec<Vec<[P; 3]>> = tracks.iter().map(|t| outlines_of(scene, t.rows)).collect();
    let l = scene.l();
    let start = tracks.first().and_then(|t| t.rows.first()).copied();
    let force = start.as_ref().and_then(|s| line_of_action(scene, s));
    let arrow_len = 0.3 * l;
    let force_tail = force.map(|(q, d, _, _)| (q.0 - arrow_len * d.0, q.1 - arrow_len * d.1));

    // The view: every path, outline and the force arrow, at equal scales on both axes.
    let pts: Vec<P> = tracks
        .iter()
        .flat_map(|t| t.rows.iter().map(|r| (r.x_m, r.z_m)))
        .chain(outlines.iter().flatten().flatten().copied())
        .chain(force_tail)
        .chain(force.map(|f| f.0))
        .chain(fan_points())
        .collect();
    // Room round the frame for the regions' names.
    let pad = 0.15 * l;
    let (mut x0, mut x1) = sheet::ranges(pts.iter().map(|p| p.0));
    let (mut z0, mut z1) = sheet::ranges(pts.iter().map(|p| p.1));
    (x0, x1, z0, z1) = (x0 - pad, x1 + pad, z0 - pad, z1 + pad);
    let (cw, ch) = sheet.chart.dim_in_pixel();
    let plot_w = f64::from(cw - 2 * MARGIN - Y_LABELS);
    let plot_h = f64::from(ch - 2 * MARGIN - X_LABELS);
    let scale = ((x1 - x0) / plot_w).max((z1 - z0) / plot_h) * 1.04;
    let (cx, cz) = (0.5 * (x0 + x1), 0.5 * (z0 + z1));
    x0 = cx - 0.5 * scale * plot_w;
    x1 = cx + 0.5 * scale * plot_w;
    z0 = cz - 0.5 * scale * plot_h;
    z1 = cz + 0.5 * scale * plot_h;
    let view = (x0, x1, z0, z1);

    let mut chart = ChartBuilder::on(&sheet.chart)
        .margin(MARGIN)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(x0..x1, z1..z0)
        .map_err(err(path))?;
    let (fx, fz) = (sheet::ticks(x0, x1), sheet::ticks(z0, z1));
    chart
        .configure_mesh()
        .max_light_lines(1)
        .x_desc("X (m), forward")
        .y_desc("Z (m), lateral (down the page)")
        .x_label_formatter(&fx)
        .y_label_formatter(&fz)
        .light_line_style(BLACK.mix(0.05))
        .bold_line_style(BLACK.mix(0.12))
        .draw()
        .map_err(err(path))?;

    // The foundation's regions, shaded, and their edges: the paper's strike lines, or the
    // creases between faces.
    let paper = scene.site().as_paper();
    let regions = foundation_regions(scene, view);
    let surface = scene.site().ground().is_some_and(|(g, _)| g.is_surface());
    for r in &regions {
        if r.poly.len() >= 3 {
            let fill = if surface {
                r.color.filled()
            } else {
                r.color.mix(0.10).filled()
            };
            chart
                .draw_series(std::iter::once(Polygon::new(r.poly.clone(), fill)))
                .map_err(err(path))?;
        }
    }
    let on_border = |p: P, q: P| {
        let eps = 1e-9 * (x1 - x0);
        [(p.0, q.0, x0), (p.0, q.0, x1)]
            .iter()
            .any(|&(a, b, c)| (a - c).abs() < eps && (b - c).abs() < eps)
            || [(p.1, q.1, z0), (p.1, q.1, z1)]
                .iter()
                .any(|&(a, b, c)| (a - c).abs() < eps && (b - c).abs() < eps)
    };
    // The paper's strike lines (the inclined regions' edges, in their colours), or the creases
    // between faces (every region's edges inside the view, in grey).
    let (edged, grey) = match paper {
        Some(_) => (&regions[1..], false),
        None => (&regions[..], true),
    };
    let edges: Vec<(Vec<P>, RGBColor)> = edged
        .iter()
        .flat_map(|r| {
            let n = r.poly.len();
            let color = if grey { RGBColor(90, 90, 90) } else { r.color };
            (0..n)
                .map(|k| (r.poly[k], r.poly[(k + 1) % n]))
                .filter(|&(p, q)| !on_border(p, q))
                .map(move |(p, q)| (vec![p, q], color))
                .collect::<Vec<_>>()
        })
        .collect();
    let width = if surface { 1 } else { 2 };
    for (line, color) in edges {
        let color = if surface {
            color.mix(0.35)
        } else {
            color.into()
        };
        chart
            .draw_series(LineSeries::new(line, color.stroke_width(width)))
            .map_err(err(path))?;
    }

    // The fan, thin and pale enough that where many paths run together reads darker.
    if let Some(f) = fan {
        let alpha = (3.0 / (f.paths.len().max(1) as f64).sqrt()).clamp(0.05, 0.6);
        for p in f.paths.iter().filter(|p| p.len() > 1) {
            chart
                .draw_series(LineSeries::new(
                    p.iter().map(|q| (q[0], q[1])),
                    FAN.mix(alpha).stroke_width(1),
                ))
                .map_err(err(path))?;
        }
        chart
            .draw_series(
                f.paths
                    .iter()
                    .filter_map(|p| p.last())
                    .map(|q| Circle::new((q[0], q[1]), 2, FAN.mix(alpha.max(0.25)).filled())),
            )
            .map_err(err(path))?;
    }

    // The frame along each route, the CM paths.
    for (k, (outlines, track)) in outlines.iter().zip(tracks).enumerate() {
        let ink = if k == 0 { BLACK } else { track.color };
        for (j, o) in outlines.iter().enumerate() {
            let mut pts = o.to_vec();
            pts.push(o[0]);
            let style = if j == 0 || j + 1 == outlines.len() {
                ink.stroke_width(2)
            } else {
                ink.mix(0.3).stroke_width(1)
            };
            chart
                .draw_series(std::iter::once(PathElement::new(pts, style)))
                .map_err(err(path))?;
        }
    }
    for track in tracks {
        chart
            .draw_series(LineSeries::new(
                track.rows.iter().map(|r| (r.x_m, r.z_m)),
                track.color.stroke_width(2),
            ))
            .map_err(err(path))?;
        if let (Some(a), Some(b)) = (track.rows.first(), track.rows.last()) {
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((a.x_m, a.z_m)) + Circle::new((0, 0), 4, track.color.filled()),
                ))
                .map_err(err(path))?;
            if a == b {
                continue;
            }
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((b.x_m, b.z_m))
                        + Circle::new((0, 0), 4, WHITE.filled())
                        + Circle::new((0, 0), 4, track.color.stroke_width(2)),
                ))
                .map_err(err(path))?;
        }
    }

    // Where a contact of the first route changed face or went into or out of a crease.
    let changes = face_changes(scene, tracks.first().map_or(&[][..], |t| t.rows));
    for (at, _) in &changes {
        chart
            .draw_series(std::iter::once(
                EmptyElement::at(*at)
                    + Rectangle::new([(-4, -4), (4, 4)], FACE_CHANGE.stroke_width(2)),
            ))
            .map_err(err(path))?;
    }

    // The hydraulic force on its line of action at the start.
    let mut obstacles: Vec<P> = Vec::new();
    if let (Some((q, d, f, e)), Some(tail), Some(s)) = (force, force_tail, start) {
        let far = (q.0 + 0.5 * l * d.0, q.1 + 0.5 * l * d.1);
        chart
            .draw_series(DashedLineSeries::new(
                [tail, far],
                6,
                4,
                FORCE.mix(0.8).stroke_width(1),
            ))
            .map_err(err(path))?;
        for part in arrow(tail, d, arrow_len) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    part,
                    FORCE.stroke_width(3),
                )))
                .map_err(err(path))?;
        }
        if e != 0.0 {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(s.x_m, s.z_m), q],
                    FORCE.stroke_width(1),
                )))
                .map_err(err(path))?;
        }
        let label = ("sans-serif", 14)
            .into_font()
            .color(&FORCE)
            .pos(Pos::new(HPos::Right, VPos::Center));
        chart
            .draw_series(std::iter::once(Text::new(
                format!("F = {}", sheet::force(f)),
                (tail.0 - 0.02 * l * d.0, tail.1 - 0.02 * l * d.1),
                label,
            )))
            .map_err(err(path))?;
        obstacles.extend(along(tail, far, 20));
    }

    // Contacts numbered at the start (dots) and at the end (crosses) of every route.
    let starts: Vec<P> = outlines
        .first()
        .and_then(|o| o.first())
        .map_or(vec![], |o| o.to_vec());
    for (k, (outlines, track)) in outlines.iter().zip(tracks).enumerate() {
        let ink = if k == 0 { BLACK } else { track.color };
        let number = |i: usize| {
            Text::new(
                format!("{i}"),
                (7, -15),
                ("sans-serif", 15).into_font().color(&ink),
            )
        };
        let moved = track.rows.len() > 1 && track.rows.first() != track.rows.last();
        if let Some(first) = outlines.first().filter(|_| k == 0) {
            chart
                .draw_series(first.iter().enumerate().map(|(i, &p)| {
                    EmptyElement::at(p) + Circle::new((0, 0), 5, ink.filled()) + number(i)
                }))
                .map_err(err(path))?;
        }
        if let Some(last) = outlines.last().filter(|_| moved) {
            let first = outlines.first().copied().unwrap_or(*last);
            chart
                .draw_series(
                    last.iter()
                        .map(|&p| EmptyElement::at(p) + Cross::new((0, 0), 6, ink.stroke_width(2))),
                )
                .map_err(err(path))?;
            // Numbered: not where a contact has hardly moved (its start number is there), and
            // below and to the left where a start number stands close by.
            let starts: Vec<P> = starts.iter().chain(first.iter()).copied().collect();
            let near = |p: &P, q: &P, px: f64| (p.0 - q.0).hypot(p.1 - q.1) <= px * scale;
            chart
                .draw_series(
                    last.iter()
                        .enumerate()
                        .filter(|(i, p)| !near(p, &first[*i], 3.0))
                        .map(|(i, &p)| {
                            let crowded = starts.iter().any(|q| near(&p, q, 14.0));
                            let at = if crowded { (-16, 4) } else { (7, -15) };
                            EmptyElement::at(p)
                                + Text::new(
                                    format!("{i}"),
                                    at,
                                    ("sans-serif", 15).into_font().color(&ink),
                                )
                        }),
                )
                .map_err(err(path))?;
        }
    }

    // Names, dips and down-dip arrows of the regions, where they keep off the data.
    for t in tracks {
        let every = (t.rows.len() / 400).max(1);
        obstacles.extend(t.rows.iter().step_by(every).map(|r| (r.x_m, r.z_m)));
    }
    obstacles.extend(fan_points().step_by(7));
    for o in outlines.iter().flatten() {
        for k in 0..3 {
            obstacles.extend(along(o[k], o[(k + 1) % 3], 12));
        }
    }
    let label_room = 45.0 * scale;
    let view_area = (x1 - x0) * (z1 - z0);
    for r in regions.iter().filter(|r| !r.name.is_empty()) {
        // Named where the region is its own (for the paper's, where it is the only inclined
        // plane), if there is room there.
        let poly = if r.label_poly.len() >= 3 && area_of(&r.label_poly) >= 0.02 * view_area {
            &r.label_poly
        } else {
            &r.poly
        };
        if poly.len() < 3 || area_of(poly) < 0.02 * view_area {
            continue;
        }
        let Some((spot, clear)) = free_spot(poly, &obstacles, view) else {
            continue;
        };
        if clear < label_room {
            continue;
        }
        let (text, color, down) = (r.name.clone(), r.color, r.down);
        let style = ("sans-serif", 15)
            .into_font()
            .color(&color)
            .pos(Pos::new(HPos::Center, VPos::Bottom));
        chart
            .draw_series(std::iter::once(Text::new(text, spot, style)))
            .map_err(err(path))?;
        if let Some(d) = down {
            // Centred just under the name (Z grows down the page).
            let len = 36.0 * scale;
            let centre = (spot.0, spot.1 + 22.0 * scale);
            let from = (centre.0 - 0.5 * len * d.0, centre.1 - 0.5 * len * d.1);
            for part in arrow(from, d, len) {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        part,
                        color.stroke_width(2),
                    )))
                    .map_err(err(path))?;
            }
        }
        obstacles.extend(along(
            (spot.0 - label_room, spot.1),
            (spot.0 + label_room, spot.1),
            8,
        ));
    }

    // A short route: its extent boxed here and drawn enlarged in the panel.
    let cm: Vec<P> = tracks
        .iter()
        .flat_map(|t| t.rows.iter().map(|r| (r.x_m, r.z_m)))
        .collect();
    let span = |f: fn(&P) -> f64| {
        cm.iter().map(f).fold(f64::NEG_INFINITY, f64::max)
            - cm.iter().map(f).fold(f64::INFINITY, f64::min)
    };
    let cm_span = span(|p| p.0).max(span(|p| p.1));
    let inset = fan.is_none() && cm_span > 0.0 && cm_span < 0.12 * (x1 - x0).min(z1 - z0);
    if inset {
        let (ix0, ix1) = sheet::ranges(cm.iter().map(|p| p.0));
        let (iz0, iz1) = sheet::ranges(cm.iter().map(|p| p.1));
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(ix0, iz0), (ix1, iz1)],
                BLACK.mix(0.6).stroke_width(1),
            )))
            .map_err(err(path))?;
    }

    // The panel: legend, notes, inset.
    let mut entries = match paper {
        Some(paper) => {
            let g = paper.foundation;
            vec![
                Entry::new(Mark::Swatch(HORIZONTAL), "horizontal plane (contact 0)"),
                Entry::new(
                    Mark::Swatch(PLANE_1),
                    format!(
                        "plane 1 (contact 1), dip ξ = {}°; solid line: its strike",
                        sheet::short(g.xi.to_degrees())
                    ),
                ),
                Entry::new(
                    Mark::Swatch(PLANE_2),
                    format!(
                        "plane 2 (contact 2), dip ζ = {}°; solid line: its strike",
                        sheet::short(g.zeta.to_degrees())
                    ),
                ),
                Entry::new(Mark::None, "arrows on the planes point down-dip"),
            ]
        }
        None if surface => vec![Entry::new(
            Mark::None,
            format!(
                "foundation: a surface of {} triangles, shaded by dip (darker: steeper, \
                     60° and more darkest); grey lines: its edges",
                scene.site().ground().map_or(0, |(g, _)| g.faces().len())
            ),
        )],
        None => {
            let mut e: Vec<Entry> = regions
                .iter()
                .take(8)
                .map(|r| Entry::new(Mark::Swatch(r.color), r.name.clone()))
                .collect();
            if regions.len() > 8 {
                e.push(Entry::new(
                    Mark::None,
                    format!("… {} faces in all", regions.len()),
                ));
            }
            e.push(Entry::new(
                Mark::None,
                match scene.site().ground() {
                    Some(_) => "the ground is the highest face; grey lines: its creases",
                    None => "each contact on its own plane (the paper's model); grey: region edges",
                },
            ));
            e.push(Entry::new(Mark::None, "arrows point down-dip"));
            e
        }
    };
    if let Some((_, _, f, e)) = force {
        entries.push(Entry::new(
            Mark::Line(FORCE),
            format!(
                "hydraulic force F = {} at the start, its line of action {} m from the CM",
                sheet::force(f),
                sheet::short(e.abs())
            ),
        ));
    }
    for t in tracks {
        entries.push(Entry::new(Mark::Line(t.color), t.name.clone()));
    }
    if let Some(f) = fan {
        entries.push(Entry::new(Mark::Line(FAN), f.name.clone()));
        entries.push(Entry::new(Mark::Dot(FAN), "where each sampled route ended"));
    }
    entries.push(Entry::new(
        Mark::Dot(BLACK),
        "contacts 0, 1, 2 at the start; thick frame: start and end, thin: every 1/8 of the route",
    ));
    if tracks
        .iter()
        .any(|t| t.rows.len() > 1 && t.rows.first() != t.rows.last())
    {
        entries.push(Entry::new(Mark::Cross(BLACK), "contacts at the end"));
        if !changes.is_empty() {
            let said: Vec<&str> = changes.iter().map(|(_, s)| s.as_str()).collect();
            entries.push(Entry::new(
                Mark::Square(FACE_CHANGE),
                format!("where a contact changed face: {}", said.join("; ")),
            ));
        }
        entries.push(Entry::new(
            Mark::Ring(BLACK),
            "CM at the end (filled dot: at the start)",
        ));
    }
    let mut y = sheet::heading(path, &sheet.panel, "Legend", 0)?;
    y = sheet::legend(path, &sheet.panel, &entries, y)?;
    if !notes.is_empty() {
        y = sheet::heading(path, &sheet.panel, "Route", y + 6)?;
        y = sheet::legend(path, &sheet.panel, notes, y)?;
    }
    if inset {
        draw_inset(path, &sheet.panel, y + 8, tracks, scale)?;
    }
    sheet.root.present().map_err(err(path))
}

/// `v` to two significant digits (a magnification needs no more).
fn round_2(v: f64) -> f64 {
    if v <= 0.0 || !v.is_finite() {
        return v;
    }
    let e = 10f64.powi(v.log10().floor() as i32 - 1);
    (v / e).round() * e
}

/// The CM paths enlarged, at equal scales, in the lower part of the panel from `y`.
fn draw_inset(path: &Path, panel: &Area, y: i32, tracks: &[Track], main_scale: f64) -> Res<()> {
    let (_, ph) = panel.dim_in_pixel();
    let top = (y.max(0) as u32).min(ph.saturating_sub(200));
    let (_, area) = panel.split_vertically(top);
    let (w, h) = area.dim_in_pixel();
    let cm: Vec<P> = tracks
        .iter()
        .flat_map(|t| t.rows.iter().map(|r| (r.x_m, r.z_m)))
        .collect();
    let (mut x0, mut x1) = sheet::ranges(cm.iter().map(|p| p.0));
    let (mut z0, mut z1) = sheet::ranges(cm.iter().map(|p| p.1));
    let (pw, ph) = (f64::from(w - 60), f64::from(h - 70));
    let scale = ((x1 - x0) / pw).max((z1 - z0) / ph);
    let (cx, cz) = (0.5 * (x0 + x1), 0.5 * (z0 + z1));
    (x0, x1) = (cx - 0.5 * scale * pw, cx + 0.5 * scale * pw);
    (z0, z1) = (cz - 0.5 * scale * ph, cz + 0.5 * scale * ph);
    let zoom = main_scale / scale;
    let mut chart = ChartBuilder::on(&area)
        .caption(
            format!(
                "CM path enlarged {}× (boxed on the plan)",
                sheet::short(round_2(zoom))
            ),
            ("sans-serif", 13),
        )
        .margin(4)
        .x_label_area_size(24)
        .y_label_area_size(40)
        .build_cartesian_2d(x0..x1, z1..z0)
        .map_err(err(path))?;
    let (fx, fz) = (sheet::ticks(x0, x1), sheet::ticks(z0, z1));
    chart
        .configure_mesh()
        .max_light_lines(0)
        .x_labels(4)
        .y_labels(4)
        .x_label_formatter(&fx)
        .y_label_formatter(&fz)
        .label_style(("sans-serif", 11))
        .draw()
        .map_err(err(path))?;
    for t in tracks {
        chart
            .draw_series(LineSeries::new(
                t.rows.iter().map(|r| (r.x_m, r.z_m)),
                t.color.stroke_width(2),
            ))
            .map_err(err(path))?;
        if let (Some(a), Some(b)) = (t.rows.first(), t.rows.last()) {
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((a.x_m, a.z_m)) + Circle::new((0, 0), 4, t.color.filled()),
                ))
                .map_err(err(path))?;
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((b.x_m, b.z_m))
                        + Circle::new((0, 0), 4, WHITE.filled())
                        + Circle::new((0, 0), 4, t.color.stroke_width(2)),
                ))
                .map_err(err(path))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_tile_the_view_with_the_inclined_ones_overlapping_beyond_both_strikes() {
        let scene = Scene::default_scene();
        let view = (-20.0, 30.0, -15.0, 25.0);
        let [h, one, two] = regions(scene.site().as_paper().unwrap(), view);
        let whole = 50.0 * 40.0;
        // Inclusion–exclusion: horizontal + plane 1 + plane 2 − overlap = the view.
        let [h1, h2] = region_half_planes(scene.site().as_paper().unwrap());
        let rect = vec![(-20.0, -15.0), (30.0, -15.0), (30.0, 25.0), (-20.0, 25.0)];
        let both = clip_half_plane(&clip_half_plane(&rect, h1), h2);
        let sum = area_of(&h.1) + area_of(&one.1) + area_of(&two.1) - area_of(&both);
        assert!((sum - whole).abs() < 1e-9 * whole, "{sum} vs {whole}");
        // Plane 1 is X ≥ L2X: its area is known in closed form.
        let l2x = scene.site().as_paper().unwrap().frame.l2x;
        assert!((area_of(&one.1) - (30.0 - l2x) * 40.0).abs() < 1e-9);
        // Every vertex of the horizontal region is in it (to round-off).
        for &(x, z) in &h.1 {
            assert!(x <= l2x + 1e-9);
            let (sk, ck) = scene.site().as_paper().unwrap().foundation.kappa.sin_cos();
            assert!(x * ck - z * sk <= strike_2_distance(scene.site().as_paper().unwrap()) + 1e-9);
        }
    }

    #[test]
    fn the_force_acts_on_the_side_that_turns_theta_up() {
        // c > 0 must turn θ up (docs/conventions.md): F along +X on the line Z = −c.
        let scene = Scene::default_scene();
        let start = Row::default();
        let (q, d, f, e) = line_of_action(&scene, &start).unwrap();
        assert!(e > 0.0 && f > 0.0);
        assert_eq!(d, (1.0, 0.0));
        assert!((q.0).abs() < 1e-12 && (q.1 + e).abs() < 1e-12, "{q:?}");
        // Moment about +Y of F·X̂ applied at (0, 0, q_z): r × F has Y part z·F_x.
        let moment_y = q.1 * f;
        // A negative moment about +Y raises θ (θ is measured from +X towards +Z).
        assert!(moment_y < 0.0);
    }

    #[test]
    fn magnifications_have_two_significant_digits() {
        assert_eq!(sheet::short(round_2(3.043e8)), "3×10⁸");
        assert_eq!(sheet::short(round_2(87.4)), "87");
        assert_eq!(sheet::short(round_2(111.2)), "110");
    }

    #[test]
    fn labels_go_where_the_data_is_not() {
        let poly = vec![(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)];
        let obstacles: Vec<P> = (0..=10).map(|k| (f64::from(k), 2.0)).collect();
        let (p, clear) = free_spot(&poly, &obstacles, (0.0, 10.0, 0.0, 10.0)).unwrap();
        // The clearest point lies between the line Z = 2 and the far edge Z = 10.
        assert!((p.1 - 6.0).abs() < 0.5 && clear > 3.5, "{p:?} {clear}");
    }
}
