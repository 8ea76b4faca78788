//! What a route puts on the plan view besides its CM path: the contact frame's outline at its
//! poses (a block on its base: its base's outline, and the corners that carried it; a frame
//! under a block with a footprint of its own, a monolith or a `[base]` outline: that
//! footprint), where a contact changed face or rode a crease, and the hydraulic force's line of
//! action at the start.

use super::P;
use crate::geometry::direct;
use crate::model::Base;
use crate::output::plots::sheet;
use crate::route::models::pose_of_row;
use crate::{BaseReport, Displacement, Pose, Row, Scene};
use nalgebra::Vector3;

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

/// A block on its base at a row: its base's corners in plan, rebuilt from the row alone
/// (`pose_of_row`), and those that carry it.
fn base_corners(scene: &Scene, base: &Base, row: &Row) -> Option<(Vec<P>, Vec<P>)> {
    let pose = pose_of_row(row, scene.site().contacts(), base.depth())?;
    let corners: Vec<P> = base
        .outline()
        .iter()
        .map(|&[x, z]| {
            let p = pose.point(&Vector3::new(x, -base.depth(), z));
            (p.x, p.z)
        })
        .collect();
    let carrying = row.corners_carrying.unwrap_or(0);
    let touching = corners
        .iter()
        .enumerate()
        .filter(|(k, _)| *k < 32 && carrying & (1 << k) != 0)
        .map(|(_, p)| *p)
        .collect();
    Some((corners, touching))
}

/// The footprint of a block that has one of its own, its base's outline (x′, z′ about the
/// centre of mass, m): a monolith's base rectangle or `[base] outline_m`, as the scene reads
/// them ([`Scene::base`]); none for a block given only by its frame.
pub(super) fn footprint(scene: &Scene) -> Option<Vec<[f64; 2]>> {
    scene.base().map(|b| b.outline().to_vec())
}

/// The footprint `outline` (x′, z′ about the centre of mass) in plan where the frame's contacts
/// (x′, z′ in `contacts`) stand at `at`: the plan's affine image of the contacts' plane, which
/// is the base's.
fn placed(outline: &[[f64; 2]], contacts: &[[f64; 2]; 3], at: &[P; 3]) -> Option<Vec<P>> {
    let (c0, c1, c2) = (contacts[0], contacts[1], contacts[2]);
    let (a, b) = (
        [c1[0] - c0[0], c1[1] - c0[1]],
        [c2[0] - c0[0], c2[1] - c0[1]],
    );
    let det = a[0] * b[1] - a[1] * b[0];
    if det.abs() <= 1e-12 * (a[0].hypot(a[1]) * b[0].hypot(b[1])).max(f64::MIN_POSITIVE) {
        return None;
    }
    let (u, v) = (
        (at[1].0 - at[0].0, at[1].1 - at[0].1),
        (at[2].0 - at[0].0, at[2].1 - at[0].1),
    );
    Some(
        outline
            .iter()
            .map(|p| {
                let d = [p[0] - c0[0], p[1] - c0[1]];
                // (s, t): d = s·a + t·b.
                let s = (d[0] * b[1] - d[1] * b[0]) / det;
                let t = (a[0] * d[1] - a[1] * d[0]) / det;
                (at[0].0 + s * u.0 + t * v.0, at[0].1 + s * u.1 + t * v.1)
            })
            .collect(),
    )
}

/// What a route puts on the plan at its drawn rows (every 1/8 of them, and the last).
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Outlines {
    /// The outline drawn at each drawn row: the frame's triangle, or the block's footprint
    /// where it has one (a block on its base: its base's polygon).
    pub shapes: Vec<Vec<P>>,
    /// The points numbered at each drawn row: the frame's contacts (a block on its base: its
    /// base's corners).
    pub points: Vec<Vec<P>>,
    /// Whether the route is a block on its base (its shapes are its base's).
    pub on_base: bool,
    /// Whether a frame route's shapes are the block's footprint, not the frame's triangle.
    pub footprint: bool,
    /// A block on its base: the corners that carried it at those rows.
    pub touches: Vec<P>,
    /// A block on its base: what else carried it at rest before any load (a ground vertex
    /// under its base, a ground edge across a base edge), each point once; its carrying
    /// corners are among `touches` at the first row.
    pub resting: Vec<P>,
}

/// A route's [`Outlines`]: the frame's triangle every 1/8 of its rows (and at its end), or,
/// for a block on its base (its rows say which corners carry, or it has a `base` report), its
/// base's polygon there, the corners that carried it, and what else carried it at rest. A base
/// that cannot be placed draws nothing rather than a frame the route did not ride on.
pub(super) fn outlines_of(scene: &Scene, rows: &[Row], report: Option<&BaseReport>) -> Outlines {
    let every = (rows.len() / 8).max(1);
    let drawn = rows
        .iter()
        .enumerate()
        .filter(|(k, _)| k % every == 0 || *k + 1 == rows.len())
        .map(|(_, r)| r);
    let on_base = report.is_some() || rows.first().is_some_and(|r| r.corners_carrying.is_some());
    if !on_base {
        let frames: Vec<[P; 3]> = drawn.filter_map(|r| vertices(scene, r)).collect();
        let points: Vec<Vec<P>> = frames.iter().map(|v| v.to_vec()).collect();
        let contacts = scene.site().contacts();
        let feet: Option<Vec<Vec<P>>> = footprint(scene).and_then(|outline| {
            frames
                .iter()
                .map(|v| placed(&outline, contacts, v))
                .collect()
        });
        return Outlines {
            footprint: feet.is_some(),
            shapes: feet.unwrap_or_else(|| points.clone()),
            points,
            ..Outlines::default()
        };
    }
    let mut out = Outlines {
        on_base,
        resting: report.map_or(vec![], resting_points),
        ..Outlines::default()
    };
    let sim = scene.simulation().ok();
    if let Some(base) = sim.as_ref().and_then(|s| s.first_body().base()) {
        for (corners, touching) in drawn.filter_map(|r| base_corners(scene, base, r)) {
            out.shapes.push(corners);
            out.touches.extend(touching);
        }
    }
    out.points = out.shapes.clone();
    out
}

/// What carried a block at rest besides its corners (a ground vertex under its base, a ground
/// edge across a base edge), in plan, each point once.
fn resting_points(report: &BaseReport) -> Vec<P> {
    let mut out: Vec<P> = Vec::new();
    for c in &report.resting.carrying {
        if c.feature.starts_with("corner") {
            continue;
        }
        let p = (c.x_m, c.z_m);
        if !out
            .iter()
            .any(|q| (p.0 - q.0).hypot(p.1 - q.1) < 1e-6 * (1.0 + p.0.hypot(p.1)))
        {
            out.push(p);
        }
    }
    out
}

/// Where a contact changed face, rode into a crease or left one, along `rows`: its plan
/// position then and what happened, e.g. "contact 2 into the crease with face 1 at 0.003 s".
pub(super) fn face_changes(scene: &Scene, rows: &[Row]) -> Vec<(P, String)> {
    let mut out = Vec::new();
    // A block on its base has no three contacts to follow from face to face.
    if rows.first().is_some_and(|r| r.corners_carrying.is_some()) {
        return out;
    }
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

/// The hydraulic force at the start, in plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Force {
    /// The point of its line of action nearest the CM.
    pub at: P,
    /// Its direction (unit).
    pub dir: P,
    /// Its size (N).
    pub size: f64,
    /// The eccentricity c of its line (m).
    pub eccentricity: f64,
}

/// The hydraulic force at the start: x' at the start, on the line offset by −c along z'. F·i'
/// with the couple −c·F·j' (eqs. 40, 41) is F acting along x' on that line
/// (`docs/conventions.md`: c > 0 turns θ up).
pub(super) fn line_of_action(scene: &Scene, start: &Row) -> Option<Force> {
    let loads = scene.loads()?;
    let (s, c) = start.theta_deg.to_radians().sin_cos();
    let x_dir = (c, s);
    let z_dir = (-s, c);
    let e = loads.eccentricity;
    Some(Force {
        at: (start.x_m - e * z_dir.0, start.z_m - e * z_dir.1),
        dir: x_dir,
        size: loads.hydraulic_force,
        eccentricity: e,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_force_acts_on_the_side_that_turns_theta_up() {
        // c > 0 must turn θ up (docs/conventions.md): F along +X on the line Z = −c.
        let scene = Scene::default_scene();
        let start = Row::default();
        let Force {
            at: q,
            dir: d,
            size: f,
            eccentricity: e,
        } = line_of_action(&scene, &start).unwrap();
        assert!(e > 0.0 && f > 0.0);
        assert_eq!(d, (1.0, 0.0));
        assert!((q.0).abs() < 1e-12 && (q.1 + e).abs() < 1e-12, "{q:?}");
        // Moment about +Y of F·X̂ applied at (0, 0, q_z): r × F has Y part z·F_x.
        let moment_y = q.1 * f;
        // A negative moment about +Y raises θ (θ is measured from +X towards +Z).
        assert!(moment_y < 0.0);
    }

    #[test]
    fn a_block_on_its_base_is_outlined_by_its_base_where_its_rows_put_it() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/ramp-faces.toml");
        let scene = Scene::from_file(&path)
            .unwrap()
            .with("solver.t_end_s", 0.5)
            .unwrap();
        let route = crate::analysis::run(&scene).unwrap();
        let report = route.base().unwrap();
        let drawn = outlines_of(&scene, &route.rows, Some(report));
        assert!(drawn.on_base);
        assert!(drawn.shapes.len() >= 2);
        // At the start the block rests level, unturned, its CM over the origin: its corners
        // are its outline's.
        let first = &drawn.shapes[0];
        assert_eq!(first.len(), report.outline_m.len());
        for (p, q) in first.iter().zip(&report.outline_m) {
            assert!(
                (p.0 - q[0]).abs() < 1e-6 && (p.1 - q[1]).abs() < 1e-6,
                "{p:?} {q:?}"
            );
        }
        // Every corner that carries it at a drawn row is marked, and only those.
        let every = (route.rows.len() / 8).max(1);
        let carrying: u32 = route
            .rows
            .iter()
            .enumerate()
            .filter(|(k, _)| k % every == 0 || *k + 1 == route.rows.len())
            .map(|(_, r)| r.corners_carrying.unwrap().count_ones())
            .sum();
        assert_eq!(drawn.touches.len(), carrying as usize);
        // A flat floor carries it at its corners alone.
        assert!(drawn.resting.is_empty(), "{:?}", drawn.resting);
        // The same rows as a frame route: the frame's triangles, nothing touching.
        let frame_rows: Vec<Row> = route
            .rows
            .iter()
            .map(|r| Row {
                corners_carrying: None,
                points_carrying: None,
                ..*r
            })
            .collect();
        let framed = outlines_of(&scene, &frame_rows, None);
        assert!(!framed.on_base && framed.touches.is_empty());
        assert!(framed.shapes.iter().all(|s| s.len() == 3));
    }

    #[test]
    fn a_monoliths_frame_is_drawn_as_the_base_it_stands_on() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/monolith.toml");
        let scene = Scene::from_file(&path).unwrap();
        // The footprint is the base the block stands on when it runs on its base.
        let sim = scene.simulation().unwrap();
        let base = sim.first_body().base().unwrap().outline();
        let foot = footprint(&scene).unwrap();
        assert_eq!(foot.len(), base.len());
        for (p, q) in foot.iter().zip(base) {
            assert!((p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12);
        }
        // On its three contacts (the paper's dynamics), at rest where it starts: that
        // footprint, 20 m by 10 m, drawn about them; the contacts numbered.
        let frame = scene.with_dynamics(crate::DynamicsModel::Paper).unwrap();
        let drawn = outlines_of(&frame, &[Row::default()], None);
        assert!(drawn.footprint && !drawn.on_base);
        assert_eq!(drawn.points[0].len(), 3);
        for (p, q) in drawn.shapes[0].iter().zip(base) {
            assert!(
                (p.0 - q[0]).abs() < 1e-9 && (p.1 - q[1]).abs() < 1e-9,
                "{p:?} {q:?}"
            );
        }
        // Turned by 90°, the footprint turns with the contacts.
        let turned = Row {
            theta_deg: 90.0,
            ..Row::default()
        };
        let drawn = outlines_of(&frame, &[turned], None);
        let xs: Vec<f64> = drawn.shapes[0].iter().map(|p| p.0).collect();
        let width = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - xs.iter().copied().fold(f64::INFINITY, f64::min);
        assert!((width - 10.0).abs() < 1e-6, "{width}");
        // A block given only by its frame has none: its triangle is drawn.
        assert!(footprint(&Scene::default_scene()).is_none());
    }

    #[test]
    fn the_frame_at_the_start_has_the_scenes_contacts() {
        let scene = Scene::default_scene();
        let v = vertices(&scene, &Row::default()).unwrap();
        let frame = scene.site().as_paper().unwrap().frame.vertices();
        for k in 0..3 {
            assert!((v[k].0 - frame[k][0]).abs() < 1e-12 && (v[k].1 - frame[k][1]).abs() < 1e-12);
        }
    }
}
