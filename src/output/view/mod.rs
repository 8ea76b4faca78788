//! The route in 3-D: `route.html` (a page that plays it, `html.rs`) and `route.glb` (the same
//! scene as binary glTF with the route as an animation, `glb.rs`), both from one [`View3d`].
//!
//! The block is a node placed at each recorded pose: its origin the row's point (`route.csv`'s
//! `x_m`, `y_m`, `z_m`: the centre of mass on the three-point frame, the point under it on a
//! base), its axes (x′, y′, z′) those `pose_of_row` rebuilds from the row's yaw θ and tilts α, β
//! (`src/route/body/report.rs`), so the contacts land where the plan view puts them (tested
//! below). Its mesh stands on the node's plane y′ = 0: a monolith's section extruded over its
//! width, a slab over its base, or a slab over the frame's triangle. The foundation is drawn
//! in world axes over the route's extent: each plane where it is the highest (the paper's
//! three, a general site's or a ground of faces), or a surface's triangles, shaded by dip.

mod glb;
mod html;
pub(crate) mod many;

use super::half_plane::{HalfPlane, clip};
use super::{OutputError, OutputFolder, Written};
use crate::model::Base;
use crate::route::models::pose_of_row;
use crate::{Route, Row, Scene};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

/// The most poses a view keeps of a route (its rows thinned evenly, the last kept).
pub const MAX_POSES: usize = 4000;

/// The most foundation triangles a view draws (a surface's nearest the route).
pub const MAX_GROUND_TRIANGLES: usize = 40_000;

/// A contact or corner's state at a pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Touch {
    /// Not on the ground.
    Off,
    /// On the ground and not moving over it (held by friction).
    Sticking,
    /// On the ground and sliding over it.
    Slipping,
    /// On the ground, carrying the block (a base's corner: the rows do not say how it moves).
    Carrying,
}

impl Touch {
    /// Its code in the page's data: 0 off, 1 sticking, 2 slipping, 3 carrying.
    pub fn code(self) -> u8 {
        match self {
            Touch::Off => 0,
            Touch::Sticking => 1,
            Touch::Slipping => 2,
            Touch::Carrying => 3,
        }
    }
}

/// A triangle mesh: corners (m) and, for each triangle, its three corners' numbers; a colour
/// (linear RGB, 0–1) a corner where it has them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<[f64; 3]>,
    pub colors: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// Adds triangle a, b, c (with colour `color` where the mesh is coloured), wound so that its
    /// normal points along `outward`.
    fn push(
        &mut self,
        [a, b, c]: [Vector3<f64>; 3],
        outward: Vector3<f64>,
        color: Option<[f64; 3]>,
    ) {
        let n = (b - a).cross(&(c - a));
        let corners = if n.dot(&outward) < 0.0 {
            [a, c, b]
        } else {
            [a, b, c]
        };
        let first = self.positions.len() as u32;
        for p in corners {
            self.positions.push([p.x, p.y, p.z]);
            if let Some(c) = color {
                self.colors.push(c);
            }
        }
        self.triangles.push([first, first + 1, first + 2]);
    }

    /// The corners' smallest and largest coordinates; none for an empty mesh.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| {
            (
                [0, 1, 2].map(|k| lo[k].min(p[k])),
                [0, 1, 2].map(|k| hi[k].max(p[k])),
            )
        }))
    }
}

/// What the block is drawn as.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BlockShape {
    /// The monolith's section extruded over its width.
    Monolith,
    /// A slab over its base's outline.
    Base,
    /// A slab over the contact frame's triangle.
    Frame,
}

/// The block at one recorded pose.
#[derive(Debug, Clone, PartialEq)]
pub struct PoseAt {
    /// Time (s).
    pub t_s: f64,
    /// The node's origin: the row's point (m).
    pub at: [f64; 3],
    /// The node's rotation, body to world, as a unit quaternion (x, y, z, w).
    pub rotation: [f64; 4],
    /// The centre of mass (m).
    pub cm: [f64; 3],
    /// The CM path's length from the start (m).
    pub travel_m: f64,
    /// The yaw θ (degrees).
    pub theta_deg: f64,
    /// The tilts α and β (degrees).
    pub alpha_deg: f64,
    pub beta_deg: f64,
    /// Each of [`View3d::points`]'s state.
    pub touch: Vec<Touch>,
}

/// The water's push at the start, on its line of action.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceArrow {
    /// Its tail and its head (m), the head on the block's upstream side.
    pub tail: [f64; 3],
    pub head: [f64; 3],
    /// Its size (N) and its line's offset c from the CM (m).
    pub size_n: f64,
    pub eccentricity_m: f64,
}

/// Everything the 3-D outputs show of a route.
#[derive(Debug, Clone, PartialEq)]
pub struct View3d {
    /// The scene's name and the dynamics.
    pub name: String,
    pub dynamics: String,
    /// The frame's side L (m): the scale of the view.
    pub l_m: f64,
    /// The foundation, in world axes, coloured by dip.
    pub ground: Mesh,
    /// The plan extent the foundation covers, X from–to and Z from–to (m).
    pub extent: [f64; 4],
    /// The block, in its node's axes (its base on y′ = 0).
    pub block: Mesh,
    pub shape: BlockShape,
    /// The contacts (or a base's corners) in the node's axes.
    pub points: Vec<[f64; 3]>,
    /// Whether `points` are a base's corners (else the frame's three contacts).
    pub corners: bool,
    /// The poses, at most [`MAX_POSES`], the first and last rows among them.
    pub poses: Vec<PoseAt>,
    pub force: Option<ForceArrow>,
    /// How the route ended: its reason (as in summary.json), time, travel and detail.
    pub reason: String,
    pub end_t_s: f64,
    pub travel_m: f64,
    pub detail: String,
}

/// Why a route has no view.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ViewError {
    /// The route recorded no row.
    #[error("the route has no rows to show")]
    NoRows,
    /// A number that is not finite where the view needs one.
    #[error("the route's rows hold a number that is not finite")]
    NotFinite,
}

/// The body-to-world rotation at `row`: yaw θ, then the pitch and roll that give the frame's
/// sides 0→1 and 0→2 their elevations α and β (`pose_of_row`).
pub fn rotation_of_row(row: &Row, contacts: &[[f64; 2]; 3]) -> Option<Matrix3<f64>> {
    pose_of_row(row, contacts, 0.0).map(|p| p.rotation)
}

/// The view of `route` on `scene`.
pub fn view_of(scene: &Scene, route: &Route) -> Result<View3d, ViewError> {
    usable(route)?;
    let site = scene.site();
    let contacts = *site.contacts();
    let l = site.l();
    let body = BlockView::of(scene, route, &contacts, l);
    let placed = placed(&route.rows, &contacts);
    let travel = travels(&placed, body.cm_above, route.travel_m);
    let poses = kept_poses(&placed, &travel, &body, l);
    let force = force_arrow(scene, &placed[0], &body.block, l);
    let extent = plan_extent(
        placed.iter().map(|(row, _)| [row.x_m, row.z_m]),
        reach_of(&body.block),
        l,
    );
    let ground = ground_mesh(scene, extent);
    Ok(View3d {
        name: route.scene.clone(),
        dynamics: route.dynamics.to_string(),
        l_m: l,
        ground,
        extent,
        block: body.block,
        shape: body.shape,
        points: body.points,
        corners: body.on_base,
        poses,
        force,
        reason: serde_json::to_value(route.termination.reason)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default(),
        end_t_s: route.termination.t_s,
        travel_m: route.travel_m,
        detail: route.termination.detail.clone(),
    })
}

/// Whether `route` has rows to show, each with finite numbers where the view reads them.
fn usable(route: &Route) -> Result<(), ViewError> {
    if route.rows.is_empty() {
        return Err(ViewError::NoRows);
    }
    if route.rows.iter().any(|r| {
        ![
            r.t_s,
            r.x_m,
            r.y_m,
            r.z_m,
            r.theta_deg,
            r.alpha_deg,
            r.beta_deg,
        ]
        .iter()
        .all(|v| v.is_finite())
    }) {
        return Err(ViewError::NotFinite);
    }
    Ok(())
}

/// The block as the view draws it: its mesh and shape, the points whose state it shows (a
/// base's corners or the frame's contacts) in the node's axes, and how far above the node's
/// origin its centre of mass stands.
struct BlockView {
    block: Mesh,
    shape: BlockShape,
    points: Vec<[f64; 3]>,
    on_base: bool,
    cm_above: f64,
}

impl BlockView {
    /// The block of `scene` as `route` carried it (on its base where the rows say so).
    fn of(scene: &Scene, route: &Route, contacts: &[[f64; 2]; 3], l: f64) -> BlockView {
        let on_base = route.rows[0].corners_carrying.is_some();
        let sim = scene.simulation().ok();
        let base: Option<Base> = if on_base {
            sim.as_ref().and_then(|s| s.first_body().base()).cloned()
        } else {
            scene.base().cloned()
        };
        let (block, shape) = block_mesh(scene, base.as_ref(), contacts, l);
        let points: Vec<[f64; 3]> = match (&base, on_base) {
            (Some(b), true) => b.outline().iter().map(|&[x, z]| [x, 0.0, z]).collect(),
            _ => contacts.iter().map(|&[x, z]| [x, 0.0, z]).collect(),
        };
        let cm_above = match (&base, on_base) {
            (Some(b), true) => b.depth(),
            _ => 0.0,
        };
        BlockView {
            block,
            shape,
            points,
            on_base,
            cm_above,
        }
    }
}

/// Every row with its body-to-world rotation: a row whose tilts fit no rotation keeps the one
/// before it (at the start: its yaw).
fn placed(rows: &[Row], contacts: &[[f64; 2]; 3]) -> Vec<(Row, Matrix3<f64>)> {
    let mut last: Option<Matrix3<f64>> = None;
    let mut placed: Vec<(Row, Matrix3<f64>)> = Vec::with_capacity(rows.len());
    for row in rows {
        let r = rotation_of_row(row, contacts).or(last).unwrap_or_else(|| {
            Rotation3::from_axis_angle(&Vector3::y_axis(), -row.theta_deg.to_radians()).into_inner()
        });
        placed.push((*row, r));
        last = Some(r);
    }
    placed
}

/// The row's point (m).
fn at(row: &Row) -> Vector3<f64> {
    Vector3::new(row.x_m, row.y_m, row.z_m)
}

/// The centre of mass at a placed row, `cm_above` the row's point along y′.
fn cm_of((row, r): &(Row, Matrix3<f64>), cm_above: f64) -> Vector3<f64> {
    at(row) + r.column(1) * cm_above
}

/// The CM path's length to each row, summed over all of them; the chords between recorded rows
/// fall a little short of the route's own path, so they are scaled to end at `travel_m`.
fn travels(placed: &[(Row, Matrix3<f64>)], cm_above: f64, travel_m: f64) -> Vec<f64> {
    let mut travel = Vec::with_capacity(placed.len());
    let mut sum = 0.0;
    for k in 0..placed.len() {
        if k > 0 {
            sum += (cm_of(&placed[k], cm_above) - cm_of(&placed[k - 1], cm_above)).norm();
        }
        travel.push(sum);
    }
    let scale = if sum > 0.0 && travel_m.is_finite() {
        travel_m / sum
    } else {
        1.0
    };
    travel.into_iter().map(|t| t * scale).collect()
}

/// The poses kept of the placed rows, at most [`MAX_POSES`] evenly, the last among them, each
/// with its points' state.
fn kept_poses(
    placed: &[(Row, Matrix3<f64>)],
    travel: &[f64],
    body: &BlockView,
    l: f64,
) -> Vec<PoseAt> {
    let every = placed.len().div_ceil(MAX_POSES - 1).max(1);
    let kept: Vec<usize> = (0..placed.len())
        .filter(|k| k % every == 0 || k + 1 == placed.len())
        .collect();
    kept.iter()
        .enumerate()
        .map(|(i, &k)| {
            let (row, r) = &placed[k];
            let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix(r));
            let cm = cm_of(&placed[k], body.cm_above);
            // A contact sticks where it does not move between this kept pose and its
            // neighbour (the next one for the first).
            let other = if i + 1 < kept.len() && i == 0 {
                Some(kept[i + 1])
            } else if i > 0 {
                Some(kept[i - 1])
            } else {
                None
            };
            PoseAt {
                t_s: row.t_s,
                at: [row.x_m, row.y_m, row.z_m],
                rotation: [q.i, q.j, q.k, q.w],
                cm: [cm.x, cm.y, cm.z],
                travel_m: travel[k],
                theta_deg: row.theta_deg,
                alpha_deg: row.alpha_deg,
                beta_deg: row.beta_deg,
                touch: touches(placed, k, other, body, 1e-7 * l),
            }
        })
        .collect()
}

/// The state of each of the body's points at placed row `k`: a base's corner carrying or off
/// as the row says; a contact off where its normal reaction is none, else slipping where it
/// moved more than `still` (m) since the `other` kept pose, else sticking.
fn touches(
    placed: &[(Row, Matrix3<f64>)],
    k: usize,
    other: Option<usize>,
    body: &BlockView,
    still: f64,
) -> Vec<Touch> {
    let world = |k: usize, p: &[f64; 3]| {
        let (row, r) = &placed[k];
        at(row) + r * Vector3::new(p[0], p[1], p[2])
    };
    let row = &placed[k].0;
    (0..body.points.len())
        .map(|c| {
            if body.on_base {
                let carrying = row.corners_carrying.unwrap_or(0);
                return if c < 32 && carrying & (1 << c) != 0 {
                    Touch::Carrying
                } else {
                    Touch::Off
                };
            }
            if row.n_n.is_some_and(|n| n.get(c).is_some_and(|n| *n <= 0.0)) {
                return Touch::Off;
            }
            match other {
                Some(o)
                    if (world(k, &body.points[c]) - world(o, &body.points[c])).norm() > still =>
                {
                    Touch::Slipping
                }
                _ => Touch::Sticking,
            }
        })
        .collect()
}

/// The block's mesh in its node's axes (base on y′ = 0): the monolith's section over its
/// width, a slab over `base`, or a slab over the frame's triangle.
fn block_mesh(
    scene: &Scene,
    base: Option<&Base>,
    contacts: &[[f64; 2]; 3],
    l: f64,
) -> (Mesh, BlockShape) {
    let mut mesh = Mesh::default();
    let v = Vector3::new;
    if let Some(m) = scene.monolith() {
        let s = m.section;
        let x0 = -m.props.cm_from_heel;
        // The section (x′, y′), counter-clockwise: heel, toe, crest's downstream and upstream
        // edges (`src/model/monolith.rs`).
        let section = [
            [x0, 0.0],
            [x0 + s.base_length, 0.0],
            [x0 + s.crest_length, s.height],
            [x0, s.height],
        ];
        let w = s.width / 2.0;
        for (z, out) in [(w, 1.0), (-w, -1.0)] {
            for k in 1..section.len() - 1 {
                let p = [section[0], section[k], section[k + 1]].map(|[x, y]| v(x, y, z));
                mesh.push(p, v(0.0, 0.0, out), None);
            }
        }
        for k in 0..section.len() {
            let ([x0, y0], [x1, y1]) = (section[k], section[(k + 1) % section.len()]);
            let out = v(y1 - y0, x0 - x1, 0.0);
            mesh.push([v(x0, y0, -w), v(x1, y1, -w), v(x1, y1, w)], out, None);
            mesh.push([v(x0, y0, -w), v(x1, y1, w), v(x0, y0, w)], out, None);
        }
        return (mesh, BlockShape::Monolith);
    }
    let (outline, thickness, shape): (Vec<[f64; 2]>, f64, BlockShape) = match base {
        Some(b) => (
            b.outline().to_vec(),
            if b.depth() > 0.0 {
                2.0 * b.depth()
            } else {
                0.08 * l
            },
            BlockShape::Base,
        ),
        None => (contacts.to_vec(), 0.08 * l, BlockShape::Frame),
    };
    let area: f64 = (0..outline.len())
        .map(|k| {
            let (p, q) = (outline[k], outline[(k + 1) % outline.len()]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum();
    let sign = if area < 0.0 { -1.0 } else { 1.0 };
    let caps: Vec<[[f64; 2]; 3]> = match base {
        Some(b) => b.triangles(),
        None => vec![[contacts[0], contacts[1], contacts[2]]],
    };
    for t in caps {
        for (y, out) in [(0.0, -1.0), (thickness, 1.0)] {
            mesh.push(t.map(|[x, z]| v(x, y, z)), v(0.0, out, 0.0), None);
        }
    }
    for k in 0..outline.len() {
        let ([x0, z0], [x1, z1]) = (outline[k], outline[(k + 1) % outline.len()]);
        let out = sign * v(z1 - z0, 0.0, x0 - x1);
        mesh.push(
            [v(x0, 0.0, z0), v(x1, 0.0, z1), v(x1, thickness, z1)],
            out,
            None,
        );
        mesh.push(
            [v(x0, 0.0, z0), v(x1, thickness, z1), v(x0, thickness, z0)],
            out,
            None,
        );
    }
    (mesh, shape)
}

/// The water's push at the start: along x′ on its line, c off the CM along −z′ at the height
/// of its pushes' resultant above the base (the paper's force lies in the base plane: drawn a
/// hundredth of L above it, to be seen), its head on the block's upstream side.
fn force_arrow(
    scene: &Scene,
    (row, r): &(Row, Matrix3<f64>),
    block: &Mesh,
    l: f64,
) -> Option<ForceArrow> {
    let loads = scene.loads()?;
    let f = loads.hydraulic_force;
    if !(f.is_finite() && f.abs() > 0.0) {
        return None;
    }
    let (lo, hi) = block.bounds()?;
    let height = (-loads.hydraulic_pitch / f).clamp(0.0, hi[1]).max(0.01 * l);
    let c = loads.eccentricity;
    let at = Vector3::new(row.x_m, row.y_m, row.z_m);
    let head = at + r * Vector3::new(lo[0], height, -c);
    let length = 0.5 * l.max(hi[0] - lo[0]);
    let dir = r.column(0).into_owned() * f.signum();
    let tail = head - dir * length;
    Some(ForceArrow {
        tail: [tail.x, tail.y, tail.z],
        head: [head.x, head.y, head.z],
        size_n: f.abs(),
        eccentricity_m: c,
    })
}

/// A face's colour by its dip: sand where level, darker brown towards 60° and steeper.
fn dip_color(dip: f64) -> [f64; 3] {
    let steep = (dip / 60f64.to_radians()).clamp(0.0, 1.0);
    let shade = |light: f64, dark: f64| (light + steep * (dark - light)) / 255.0;
    [shade(235.0, 110.0), shade(225.0, 80.0), shade(205.0, 50.0)]
}

/// How far the block reaches from its node's origin (m): its mesh's farthest coordinate.
pub fn reach_of(block: &Mesh) -> f64 {
    let (lo, hi) = block.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    (0..3)
        .map(|k| lo[k].abs().max(hi[k].abs()))
        .fold(0.0, f64::max)
}

/// The plan extent, X from–to and Z from–to, of `points` (X, Z), `reach` round each and L
/// beyond; round the origin where there are none.
pub fn plan_extent(points: impl IntoIterator<Item = [f64; 2]>, reach: f64, l: f64) -> [f64; 4] {
    let (mut x0, mut x1, mut z0, mut z1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for [x, z] in points {
        if !(x.is_finite() && z.is_finite()) {
            continue;
        }
        x0 = x0.min(x - reach);
        x1 = x1.max(x + reach);
        z0 = z0.min(z - reach);
        z1 = z1.max(z + reach);
    }
    if x0 > x1 {
        (x0, x1, z0, z1) = (-reach, reach, -reach, reach);
    }
    [x0 - l, x1 + l, z0 - l, z1 + l]
}

/// The union of two plan extents.
pub fn union_extent(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].max(b[1]),
        a[2].min(b[2]),
        a[3].max(b[3]),
    ]
}

/// The ground's height at (X, Z): the highest plane, or the surface's (none off it).
pub fn ground_height(scene: &Scene, x: f64, z: f64) -> Option<f64> {
    let site = scene.site();
    match site.ground() {
        Some((g, _)) => g.top(x, z).map(|(_, h)| h),
        None => site
            .planes()
            .iter()
            .map(|q| q.height(x, z))
            .reduce(f64::max),
    }
    .filter(|h| h.is_finite())
}

/// The foundation over `extent` (X from–to, Z from–to): each plane where it is the highest,
/// or a surface's triangles there (the nearest its middle, at most [`MAX_GROUND_TRIANGLES`]).
pub fn ground_mesh(scene: &Scene, [x0, x1, z0, z1]: [f64; 4]) -> Mesh {
    let mut mesh = Mesh::default();
    let up = Vector3::y();
    let site = scene.site();
    if let Some((ground, _)) = site.ground().filter(|(g, _)| g.is_surface()) {
        let (cx, cz) = ((x0 + x1) / 2.0, (z0 + z1) / 2.0);
        let mut faces: Vec<(usize, f64)> = ground
            .faces_in((x0, x1, z0, z1))
            .into_iter()
            .filter_map(|k| {
                let t = ground.triangle(k)?;
                let (mx, mz) = (
                    (t[0][0] + t[1][0] + t[2][0]) / 3.0,
                    (t[0][1] + t[1][1] + t[2][1]) / 3.0,
                );
                Some((k, (mx - cx).hypot(mz - cz)))
            })
            .collect();
        faces.sort_by(|a, b| a.1.total_cmp(&b.1));
        faces.truncate(MAX_GROUND_TRIANGLES);
        faces.sort_by_key(|f| f.0);
        for (k, _) in faces {
            let (Some(t), Some(plane)) = (ground.triangle(k), ground.faces().get(k)) else {
                continue;
            };
            let p = t.map(|[x, z]| Vector3::new(x, plane.height(x, z), z));
            mesh.push(p, up, Some(dip_color(plane.dip())));
        }
        return mesh;
    }
    let planes: Vec<crate::Plane> = match site.ground() {
        Some((ground, _)) => ground.faces().to_vec(),
        None => site.planes().to_vec(),
    };
    let rect = vec![(x0, z0), (x1, z0), (x1, z1), (x0, z1)];
    for (k, plane) in planes.iter().enumerate() {
        // Where plane k stands at least as high as every other.
        let poly = planes.iter().enumerate().filter(|(j, _)| *j != k).fold(
            rect.clone(),
            |poly, (_, q)| {
                if poly.len() < 3 {
                    return poly;
                }
                clip(&poly, HalfPlane::above(plane, q))
            },
        );
        if poly.len() < 3 {
            continue;
        }
        let lift = |(x, z): (f64, f64)| Vector3::new(x, plane.height(x, z), z);
        for j in 1..poly.len() - 1 {
            mesh.push(
                [lift(poly[0]), lift(poly[j]), lift(poly[j + 1])],
                up,
                Some(dip_color(plane.dip())),
            );
        }
    }
    mesh
}

/// Writes `route.html` and `route.glb` of `route` into `folder`. A route with nothing to show
/// (no rows, a number that is not finite) gets neither, with a warning: the route's own files
/// stand without them. The error (a file that could not be written) names the file.
pub(crate) fn write_route_view(
    folder: &mut OutputFolder,
    scene: &Scene,
    route: &Route,
) -> Result<Written, OutputError> {
    let made = view_of(scene, route)
        .map_err(|e| e.to_string())
        .and_then(|view| {
            let page = html::page(&view).map_err(|e| format!("route.html: {e}"))?;
            let glb = glb::glb(&view).map_err(|e| format!("route.glb: {e}"))?;
            Ok((page, glb))
        });
    let mut written = Written::default();
    match made {
        Ok((page, glb)) => {
            written
                .files
                .push(folder.write_bytes("route.html", page.as_bytes())?);
            written.files.push(folder.write_bytes("route.glb", &glb)?);
        }
        Err(e) => written
            .warnings
            .push(format!("no route.html or route.glb: {e}")),
    }
    Ok(written)
}

/// Writes `page` as `name` into `folder`; a page that cannot be made is left out with a
/// warning (the command's own files stand without it).
pub(crate) fn write_page(
    folder: &mut OutputFolder,
    name: &str,
    page: &many::Page3d,
) -> Result<Written, OutputError> {
    let mut written = Written::default();
    match html::page_of(page) {
        Ok(html) => written
            .files
            .push(folder.write_bytes(name, html.as_bytes())?),
        Err(e) => written.warnings.push(format!("no {name}: {e}")),
    }
    Ok(written)
}

/// Writes `compare.html` of both routes into `folder` (none, with a warning, where a route
/// has nothing to show).
pub(crate) fn write_compare_view(
    folder: &mut OutputFolder,
    scene: &Scene,
    paper: &Route,
    rigid: &Route,
) -> Result<Written, OutputError> {
    match many::compare_page(scene, paper, rigid) {
        Ok(page) => write_page(folder, "compare.html", &page),
        Err(e) => Ok(Written {
            files: Vec::new(),
            warnings: vec![format!("no compare.html: {e}")],
        }),
    }
}

#[cfg(test)]
mod tests;
