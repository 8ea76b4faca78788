//! The one runner of many routes: each from its own scene, on every core (with the `parallel`
//! feature), in order, every item a row whatever its fate — a route, values that make no valid
//! scene, or not run because the caller stopped. Sweeps (`sweep.rs`) and probabilistic analyses
//! (`probabilistic/`) run through it, from the command line and from Python alike.

use super::run::run_observed;
use crate::mechanics::static_friction::FactorOfSafety;
use crate::route::{Reason, Route};
use crate::scene::{Scene, SceneError};
use std::ops::ControlFlow;

/// The reason written for an item a stopped run did not start.
pub const NOT_RUN: &str = "not run (interrupted)";

/// What one route came to, as a row of many has it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RouteResult {
    /// The factor of safety at the start (absent only where its cone program failed).
    pub factor_of_safety: Option<FactorOfSafety>,
    /// How the route ended.
    pub reason: Reason,
    /// When (s).
    pub t_s: f64,
    /// What exactly happened, for people.
    pub detail: String,
    /// Travel (m).
    pub travel_m: f64,
    /// The final position of the CM, X and Z (m).
    pub x_m: f64,
    /// Z (m).
    pub z_m: f64,
    /// The final yaw (degrees).
    pub yaw_deg: f64,
    /// The largest tilt α along the route (degrees).
    pub max_alpha_deg: f64,
    /// The largest tilt β along the route (degrees).
    pub max_beta_deg: f64,
    /// Under a ground-motion record, the permanent displacement relative to the foundation, X
    /// and Z (m; `Route::permanent_displacement_xz_m`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permanent_xz_m: Option<[f64; 2]>,
    /// The CM path in plan, (X, Z) in m, thinned evenly to at most [`RouteResult::PATH_POINTS`]
    /// points (the
    /// first and last kept).
    #[serde(skip)]
    pub cm_path_m: Vec<[f64; 2]>,
}

impl RouteResult {
    /// The most points of a route's CM path a row keeps ([`RouteResult::cm_path_m`]): enough to
    /// draw it in a route fan, little enough that ten thousand rows keep ten megabytes.
    pub const PATH_POINTS: usize = 64;

    /// What `route` came to.
    pub fn of(route: &Route) -> RouteResult {
        let last = route.rows.last();
        let max = |f: fn(&crate::route::Row) -> f64| {
            route.rows.iter().map(f).fold(f64::NEG_INFINITY, f64::max)
        };
        RouteResult {
            factor_of_safety: route.factor_of_safety,
            reason: route.termination.reason,
            t_s: route.termination.t_s,
            detail: route.termination.detail.clone(),
            travel_m: route.travel_m,
            x_m: last.map_or(0.0, |l| l.x_m),
            z_m: last.map_or(0.0, |l| l.z_m),
            yaw_deg: last.map_or(0.0, |l| l.theta_deg),
            max_alpha_deg: max(|r| r.alpha_deg),
            max_beta_deg: max(|r| r.beta_deg),
            permanent_xz_m: route.permanent_displacement_xz_m,
            cm_path_m: thin(
                &route
                    .rows
                    .iter()
                    .map(|r| [r.x_m, r.z_m])
                    .collect::<Vec<_>>(),
                RouteResult::PATH_POINTS,
            ),
        }
    }

    /// The permanent displacement's length (m), under a ground-motion record.
    pub fn permanent_m(&self) -> Option<f64> {
        self.permanent_xz_m.map(|d| d[0].hypot(d[1]))
    }

    /// The factor of safety as a number: +∞ where no multiple of the driving loads starts the
    /// block, −∞ where the weight alone does.
    pub fn factor_of_safety_value(&self) -> Option<f64> {
        self.factor_of_safety.map(|f| match f {
            FactorOfSafety::Finite { value } => value,
            FactorOfSafety::Unbounded => f64::INFINITY,
            FactorOfSafety::NotHoldable => f64::NEG_INFINITY,
        })
    }
}

/// What one item of many came to: its route, or why it has none.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "outcome", rename_all = "kebab-case")]
pub enum Outcome {
    /// Its route ran.
    Route(RouteResult),
    /// Its values make no valid scene (the reason names the key).
    Invalid {
        /// Why, naming the key.
        reason: String,
    },
    /// Not run: the caller stopped the run first.
    NotRun,
}

impl Outcome {
    /// The route's result, where a route ran.
    pub fn route(&self) -> Option<&RouteResult> {
        match self {
            Outcome::Route(r) => Some(r),
            _ => None,
        }
    }

    /// How it ended, as a table writes it: the route's reason, `invalid scene` or [`NOT_RUN`].
    pub fn reason(&self) -> &'static str {
        match self {
            Outcome::Route(r) => r.reason.as_str(),
            Outcome::Invalid { .. } => "invalid scene",
            Outcome::NotRun => NOT_RUN,
        }
    }
}

/// The route of each item of `items`, its scene `scene_of(item)`, in the items' order: on every
/// core where the `parallel` feature is on. `tick` is called after each item; `stop` is asked
/// before each (those it stops are [`Outcome::NotRun`]) and by routes under way, which end at
/// their next increment as interrupted. Only the first [`PATHS_KEPT`] routes keep their CM
/// path.
pub fn run_many<T: Sync>(
    items: &[T],
    scene_of: impl Fn(&T) -> Result<Scene, SceneError> + Sync,
    tick: impl Fn() + Sync,
    stop: impl Fn() -> bool + Sync,
) -> Vec<Outcome> {
    let one = |item: &T| {
        let outcome = if stop() {
            Outcome::NotRun
        } else {
            let observe = |_: f64| {
                if stop() {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            };
            match scene_of(item)
                .and_then(|scene| with_rows_for_results(&scene))
                .and_then(|scene| run_observed(&scene, observe))
            {
                Ok(route) => Outcome::Route(RouteResult::of(&route)),
                Err(e) => Outcome::Invalid {
                    reason: e.to_string(),
                },
            }
        };
        tick();
        outcome
    };
    // Beyond the first PATHS_KEPT items a route keeps no CM path: a thousand samples' paths
    // are all a fan draws, and a path is most of what a row of many holds.
    let numbered = |(k, item): (usize, &T)| {
        let mut outcome = one(item);
        if k >= PATHS_KEPT
            && let Outcome::Route(r) = &mut outcome
        {
            r.cm_path_m = Vec::new();
        }
        outcome
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items.par_iter().enumerate().map(numbered).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        items.iter().enumerate().map(numbered).collect()
    }
}

/// The items of a [`run_many`] whose routes keep their CM path ([`RouteResult::cm_path_m`]):
/// the first 2000 (the route fans draw the first thousand routes that ran); the others keep
/// none (1 kB a row saved: 10⁷ samples held 14 GB).
pub const PATHS_KEPT: usize = 2000;

/// The most routes the streaming runs (`Design::run_each`, `Sweep::run_each`) run at once on
/// every core: enough that the cores seldom wait for a chunk's slowest route, few enough that
/// their results take a few MB.
pub const CHUNK: usize = 4096;

/// The items of `items` run [`CHUNK`] at a time by `run(first, chunk)` (`first`: the number of
/// the chunk's first item), each result handed in order to `each` as soon as its chunk has run:
/// memory holds one chunk, whatever the number of items. The first error of `each` ends it.
pub fn run_chunked<T, R, E>(
    mut items: impl Iterator<Item = T>,
    mut run: impl FnMut(usize, Vec<T>) -> Vec<R>,
    mut each: impl FnMut(R) -> Result<(), E>,
) -> Result<(), E> {
    let mut first = 0;
    loop {
        let chunk: Vec<T> = items.by_ref().take(CHUNK).collect();
        if chunk.is_empty() {
            return Ok(());
        }
        let n = chunk.len();
        for r in run(first, chunk) {
            each(r)?;
        }
        first += n;
    }
}

/// The most rows a route of many keeps (every stride-th increment, the stride chosen so): what
/// a [`RouteResult`] takes from them — the last row, the largest tilts, a CM path of
/// [`RouteResult::PATH_POINTS`] — needs no more, and each row of a rigid-body route is the model
/// evaluated where its steps pass (`route::rigid`), the most of a sample's cost at a fine dt.
pub const ROWS_OF_MANY: usize = 4 * RouteResult::PATH_POINTS;

/// `scene`, recording at most about [`ROWS_OF_MANY`] rows (its own stride where that records
/// fewer); the route is the same, its steps its own (the rigid body's) or dt (the paper's).
fn with_rows_for_results(scene: &Scene) -> Result<Scene, SceneError> {
    let Some(s) = scene.settings() else {
        return Ok(scene.clone());
    };
    let increments = (s.t_end / s.dt).ceil();
    let stride = (increments / ROWS_OF_MANY as f64).ceil().max(1.0);
    if stride <= s.stride as f64 || stride >= i64::MAX as f64 {
        return Ok(scene.clone());
    }
    scene.with("solver.stride", stride as i64)
}

/// At most `n` of the items, evenly spread, the first and last kept (a route's CM path for
/// [`RouteResult::cm_path_m`]; the command line's fan pages too).
pub fn thin<T: Copy>(items: &[T], n: usize) -> Vec<T> {
    if items.len() <= n || n < 2 {
        return items.to_vec();
    }
    (0..n)
        .map(|i| items[(i * (items.len() - 1)).div_ceil(n - 1).min(items.len() - 1)])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunked_runs_hand_every_result_on_in_order_with_its_number_and_stop_at_an_error() {
        let n = 2 * CHUNK + 3;
        let mut firsts = Vec::new();
        let mut got = Vec::new();
        let done: Result<(), ()> = run_chunked(
            0..n,
            |first, chunk| {
                firsts.push((first, chunk.len()));
                chunk.into_iter().map(|k| (first, k)).collect()
            },
            |r| {
                got.push(r);
                Ok(())
            },
        );
        assert_eq!(done, Ok(()));
        assert_eq!(firsts, [(0, CHUNK), (CHUNK, CHUNK), (2 * CHUNK, 3)]);
        assert!(
            got.iter()
                .enumerate()
                .all(|(i, &(first, k))| k == i && first == i / CHUNK * CHUNK)
        );
        // The first error ends it: no chunk after the one it came in runs.
        let mut runs = 0;
        let e = run_chunked(
            0..n,
            |_, c| {
                runs += 1;
                c
            },
            |k| if k == 5 { Err(k) } else { Ok(()) },
        );
        assert_eq!((e, runs), (Err(5), 1));
    }

    #[test]
    fn a_thinned_path_keeps_its_ends_and_at_most_its_count() {
        let v: Vec<usize> = (0..1000).collect();
        let t = thin(&v, RouteResult::PATH_POINTS);
        assert_eq!(t.len(), RouteResult::PATH_POINTS);
        assert_eq!((t[0], *t.last().unwrap()), (0, 999));
        assert!(t.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(thin(&v[..10], RouteResult::PATH_POINTS), v[..10].to_vec());
    }

    #[test]
    fn only_the_first_paths_kept_routes_of_many_hold_their_path() {
        // A path is 1 kB of a row of many: 10⁷ samples held 14 GB.
        let base = Scene::default_scene()
            .with("solver.t_end_s", 0.002)
            .unwrap();
        let items: Vec<usize> = (0..PATHS_KEPT + 3).collect();
        let rows = run_many(&items, |_| Ok(base.clone()), || (), || false);
        let paths: Vec<usize> = rows
            .iter()
            .map(|o| match o {
                Outcome::Route(r) => r.cm_path_m.len(),
                other => panic!("{other:?}"),
            })
            .collect();
        assert!(
            paths[..PATHS_KEPT].iter().all(|&n| n >= 2),
            "{:?}",
            &paths[..4]
        );
        assert_eq!(paths[PATHS_KEPT..], [0, 0, 0]);
    }

    #[test]
    fn every_item_has_its_row_in_order_whatever_its_fate() {
        let base = Scene::default_scene().with("solver.t_end_s", 0.05).unwrap();
        let items = [0.3, -1.0, 0.5];
        let rows = run_many(
            &items,
            |mu| base.with("friction.mu_k", *mu),
            || (),
            || false,
        );
        assert_eq!(rows.len(), 3);
        let route = |mu: f64| {
            RouteResult::of(&crate::run(&base.with("friction.mu_k", mu).unwrap()).unwrap())
        };
        assert_eq!(rows[0], Outcome::Route(route(0.3)));
        assert_eq!(rows[2], Outcome::Route(route(0.5)));
        assert!(
            matches!(&rows[1], Outcome::Invalid { reason } if reason.contains("friction.mu_k"))
        );
        let stopped = run_many(&items, |mu| base.with("friction.mu_k", *mu), || (), || true);
        assert!(stopped.iter().all(|o| *o == Outcome::NotRun));
    }

    #[test]
    fn a_route_of_many_keeps_fewer_rows_and_comes_to_the_same_result() {
        // The default scene's route records 4365 rows; run among many it records at most
        // ROWS_OF_MANY, its steps the same: the same end, travel and path ends, its largest tilts
        // from fewer rows within a hundredth of a degree.
        let scene = Scene::default_scene();
        let alone = crate::run(&scene).unwrap();
        assert!(alone.rows.len() > 4 * ROWS_OF_MANY);
        let many = run_many(&[()], |_| Ok(scene.clone()), || (), || false);
        let Outcome::Route(r) = &many[0] else {
            panic!("{:?}", many[0]);
        };
        let want = RouteResult::of(&alone);
        assert_eq!(
            (r.reason, r.t_s, r.travel_m, r.x_m, r.z_m, r.yaw_deg),
            (
                want.reason,
                want.t_s,
                want.travel_m,
                want.x_m,
                want.z_m,
                want.yaw_deg
            )
        );
        assert_eq!(r.cm_path_m.first(), want.cm_path_m.first());
        assert_eq!(r.cm_path_m.last(), want.cm_path_m.last());
        assert!((r.max_alpha_deg - want.max_alpha_deg).abs() < 1e-2);
        assert!((r.max_beta_deg - want.max_beta_deg).abs() < 1e-2);
    }
}
