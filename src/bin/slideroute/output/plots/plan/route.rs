//! What a route puts on the plan view besides its CM path: the contact frame's outline at its
//! poses (a block on its base: its base's outline, and the corners that carried it), where a
//! contact changed face or rode a crease, and the hydraulic force's line of action at the
//! start.

use super::P;
use crate::output::plots::sheet;
use nalgebra::Vector3;
use slideroute::internals::geometry::direct;
use slideroute::internals::model::Base;
use slideroute::internals::route::pose_of_row;
use slideroute::{Displacement, Pose, Row, Scene};

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

/// Outlines every 1/8 of a route's rows (and at its end): the frame's triangle, or, for a
/// block on its base, its base's polygon; and, for a block on its base, the corners that
/// carried it at those rows.
pub(super) fn outlines_of(scene: &Scene, rows: &[Row]) -> (Vec<Vec<P>>, Vec<P>) {
    let every = (rows.len() / 8).max(1);
    let drawn = rows
        .iter()
        .enumerate()
        .filter(|(k, _)| k % every == 0 || *k + 1 == rows.len())
        .map(|(_, r)| r);
    let on_base = rows.first().is_some_and(|r| r.corners_carrying.is_some());
    let sim = scene.simulation().ok().filter(|_| on_base);
    match sim.as_ref().and_then(|s| s.base()) {
        Some(base) => {
            let (mut outlines, mut touches) = (Vec::new(), Vec::new());
            for (corners, touching) in drawn.filter_map(|r| base_corners(scene, base, r)) {
                outlines.push(corners);
                touches.extend(touching);
            }
            (outlines, touches)
        }
        None => (
            drawn
                .filter_map(|r| vertices(scene, r))
                .map(|v| v.to_vec())
                .collect(),
            Vec::new(),
        ),
    }
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
    fn the_frame_at_the_start_has_the_scenes_contacts() {
        let scene = Scene::default_scene();
        let v = vertices(&scene, &Row::default()).unwrap();
        let frame = scene.site().as_paper().unwrap().frame.vertices();
        for k in 0..3 {
            assert!((v[k].0 - frame[k][0]).abs() < 1e-12 && (v[k].1 - frame[k][1]).abs() < 1e-12);
        }
    }
}
