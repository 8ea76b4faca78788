//! The pages of more than one route: `compare.html` (both dynamics' routes over one
//! foundation, each its own colour, one time moving both) and `route-fan.html` / `sweep.html`
//! (every sample's or combination's CM path over the ground, with the scene as written where
//! there is one). One [`Page3d`] describes any page, a single route's too; `html.rs` writes it
//! and `route.js` draws it by its [`Mode`].

use super::{Mesh, View3d, ViewError, ground_height, ground_mesh, plan_extent, union_extent};
use crate::output::MAX_FAN_PATHS;
use crate::{Outcome, Route, Scene};

/// The most points a fan path keeps (where it turns most, the first and last kept: [`simplified`]):
/// with points to the centimetre, a thousand paths and three.js keep a fan page under 2 MB.
pub const MAX_FAN_POINTS: usize = 32;

/// At most `n` of the points of `path`, the first and last kept and each other chosen where the
/// path turns most: point after point, the one farthest from the chord between the points kept
/// either side of it (Douglas–Peucker's order, stopped at `n` points or when every point left
/// lies within a millimetre of its chord, far below the centimetre the page writes). Evenly
/// spread points cut the corner of a sharply turning route; these keep it.
pub fn simplified(path: &[[f64; 2]], n: usize) -> Vec<[f64; 2]> {
    if path.len() <= n || n < 2 {
        return path.to_vec();
    }
    let off = |q: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        crate::geometry::ground::segment_distance_2(a, b, q).sqrt()
    };
    let mut keep = vec![false; path.len()];
    keep[0] = true;
    keep[path.len() - 1] = true;
    for _ in 2..n {
        let (mut farthest, mut at) = (1e-3, None);
        let mut a = 0;
        for b in 1..path.len() {
            if keep[b] {
                for i in a + 1..b {
                    let d = off(path[i], path[a], path[b]);
                    if d > farthest {
                        (farthest, at) = (d, Some(i));
                    }
                }
                a = b;
            }
        }
        match at {
            Some(i) => keep[i] = true,
            None => break,
        }
    }
    path.iter()
        .zip(&keep)
        .filter(|(_, k)| **k)
        .map(|(q, _)| *q)
        .collect()
}

/// What a page shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// One route (`route.html`).
    Route,
    /// Both dynamics' routes (`compare.html`).
    Compare,
    /// Many routes' CM paths (`route-fan.html`, `sweep.html`).
    Fan,
}

/// A route on a page, with its name in the legend and its colour (0xRRGGBB).
#[derive(Debug, Clone, PartialEq)]
pub struct Shown {
    pub label: String,
    pub color: u32,
    pub view: View3d,
}

/// Many routes' CM paths, each on the ground.
#[derive(Debug, Clone, PartialEq)]
pub struct Fan3d {
    /// What they are, for the legend.
    pub label: String,
    /// Each path's points (m), at most [`MAX_FAN_PATHS`] of at most [`MAX_FAN_POINTS`].
    pub paths: Vec<Vec<[f64; 3]>>,
    /// How many routes there were (drawn or not).
    pub routes: usize,
}

/// One page: its foundation, its routes and its fan.
#[derive(Debug, Clone, PartialEq)]
pub struct Page3d {
    pub mode: Mode,
    pub name: String,
    pub title: String,
    /// The frame's side L (m): the scale of the view.
    pub l_m: f64,
    pub ground: Mesh,
    pub routes: Vec<Shown>,
    pub fan: Option<Fan3d>,
    /// Notes for the panel (what was varied, what the foundation is).
    pub notes: Vec<String>,
}

/// The colour of the one route of `route.html`'s CM path.
pub const ROUTE_RED: u32 = 0xd0021b;
/// The paper's dynamics on `compare.html`.
pub const PAPER_PURPLE: u32 = 0x7b1fa2;
/// The rigid body's on `compare.html`.
pub const RIGID_TEAL: u32 = 0x00897b;
/// The fan's paths.
pub const FAN_ORANGE: u32 = 0xe65100;
/// The scene as written, on a fan (black, as on `route-fan.svg`).
pub const NOMINAL_BLACK: u32 = 0x111111;

impl Page3d {
    /// `route.html`'s page: the one route.
    pub fn single(view: View3d) -> Page3d {
        Page3d {
            mode: Mode::Route,
            name: view.name.clone(),
            title: format!(
                "{}: the route in 3-D ({} dynamics)",
                view.name, view.dynamics
            ),
            l_m: view.l_m,
            ground: view.ground.clone(),
            routes: vec![Shown {
                label: "CM path".into(),
                color: ROUTE_RED,
                view,
            }],
            fan: None,
            notes: Vec::new(),
        }
    }
}

/// `compare.html`'s page: the paper's route and the rigid body's over one foundation.
pub fn compare_page(scene: &Scene, paper: &Route, rigid: &Route) -> Result<Page3d, ViewError> {
    let a = super::view_of(scene, paper)?;
    let b = super::view_of(scene, rigid)?;
    let ground = ground_mesh(scene, union_extent(a.extent, b.extent));
    let label = |v: &View3d| format!("{} dynamics", v.dynamics);
    Ok(Page3d {
        mode: Mode::Compare,
        name: a.name.clone(),
        title: format!("{}: both dynamics in 3-D", a.name),
        l_m: a.l_m,
        ground,
        routes: vec![
            Shown {
                label: label(&a),
                color: PAPER_PURPLE,
                view: a,
            },
            Shown {
                label: label(&b),
                color: RIGID_TEAL,
                view: b,
            },
        ],
        fan: None,
        notes: Vec::new(),
    })
}

/// The CM paths of the outcomes that ran, the first [`MAX_FAN_PATHS`] in order (as
/// `route-fan.svg` draws them), and how many ran.
pub fn cm_paths<'a>(
    outcomes: impl IntoIterator<Item = &'a Outcome>,
) -> (Vec<&'a [[f64; 2]]>, usize) {
    let mut paths = Vec::new();
    let mut routes = 0;
    for o in outcomes {
        if let Outcome::Route(r) = o {
            routes += 1;
            if paths.len() < MAX_FAN_PATHS {
                paths.push(r.cm_path_m.as_slice());
            }
        }
    }
    (paths, routes)
}

/// A fan page (`route-fan.html`, `sweep.html`): the foundation of `scene` under `paths` (X,
/// Z; each [`simplified`] to [`MAX_FAN_POINTS`], at most [`MAX_FAN_PATHS`] drawn), each point
/// on the ground (a point off a surface left out), of `routes` routes in all, with `nominal`
/// (the scene as written) where there is one. `what` names the routes ("sampled routes").
pub fn fan_page(
    scene: &Scene,
    nominal: Option<&Route>,
    paths: &[&[[f64; 2]]],
    routes: usize,
    what: &str,
    notes: Vec<String>,
) -> Page3d {
    let nominal = nominal.and_then(|r| super::view_of(scene, r).ok());
    let l = scene.site().l();
    let lifted: Vec<Vec<[f64; 3]>> = paths
        .iter()
        .take(MAX_FAN_PATHS)
        .map(|p| {
            simplified(p, MAX_FAN_POINTS)
                .into_iter()
                .filter_map(|[x, z]| ground_height(scene, x, z).map(|y| [x, y, z]))
                .collect::<Vec<_>>()
        })
        .filter(|p| !p.is_empty())
        .collect();
    let mut extent = plan_extent(lifted.iter().flatten().map(|p| [p[0], p[2]]), 0.0, l);
    if let Some(v) = &nominal {
        extent = if lifted.is_empty() {
            v.extent
        } else {
            union_extent(extent, v.extent)
        };
    }
    let ground = ground_mesh(scene, extent);
    let drawn = if lifted.len() < routes {
        format!(", {} drawn", lifted.len())
    } else {
        String::new()
    };
    let name = scene.name().to_string();
    Page3d {
        mode: Mode::Fan,
        title: format!("{name}: CM paths of {routes} {what} in 3-D"),
        name,
        l_m: l,
        ground,
        routes: nominal
            .into_iter()
            .map(|v| Shown {
                label: "the scene as written".into(),
                color: NOMINAL_BLACK,
                view: v,
            })
            .collect(),
        fan: Some(Fan3d {
            label: format!("CM paths of the {routes} {what}{drawn}"),
            paths: lifted,
            routes,
        }),
        notes,
    }
}
