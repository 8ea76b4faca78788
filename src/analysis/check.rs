//! `slideroute check`: each load case by its guideline — on a monolith with its water, the
//! gravity method's sliding factor of safety, resultant and base pressures (with a cracked
//! base); on any block, the load multiple friction holds at the start — and the route of each
//! case, so that a case that fails shows where the monolith would go
//! (`derivations/11-dam-loads.md` §5, §9).

use super::gravity_method::{BaseFace, GravityCase, GravityVerdict, gravity_method};
use crate::mechanics::static_friction::{FactorOfSafety, Limit};
use crate::model::Mode;
use crate::model::Strengths;
use crate::model::{Category, Guideline, LoadCase};
use crate::route::PoseMethod;
use crate::route::pose_finder::PoseFinder;
use crate::route::three_point::faces_of;
use crate::route::{Computed, Route, Runner};
use crate::scene::{LoadsUsed, Scene, SceneError};
use nalgebra::Vector3;
use std::ops::ControlFlow;

/// One load case checked.
#[derive(Debug, Clone, serde::Serialize)]
pub struct CaseResult {
    /// The load case.
    pub case: LoadCase,
    /// The load multiple at the start: the largest multiple of the driving loads the three
    /// contacts' friction cones hold (`None` where the start has no pose). The three-dimensional
    /// measure of how far the loads are from starting any motion, sliding or tipping; the
    /// verdict where the scene has no monolith with its water.
    pub factor_of_safety: Option<FactorOfSafety>,
    /// What limits the load multiple: the loads' multiple slides the block, or tips it.
    pub load_multiple_limit: Option<Limit>,
    /// The sliding factor the case's guideline requires (the case's own, repeated flat for a
    /// program reading `check.json`).
    pub required_fs: f64,
    /// The gravity method's verdicts, on a monolith with `[water]` (flattened into the case in
    /// `check.json`).
    #[serde(flatten)]
    pub gravity: Option<GravityVerdict>,
    /// Whether the case meets its guideline: on a monolith with its water, the sliding factor
    /// at least the requirement, the resultant within its limit and the base pressures within
    /// the allowable bearing stress (where one is given); otherwise the load multiple at least
    /// the requirement.
    pub passes: bool,
    /// The loads the case used.
    pub loads: Option<LoadsUsed>,
    /// The anchors as the case has them (a case may change their keys).
    #[serde(skip)]
    pub anchors: Vec<crate::model::RockAnchor>,
    /// Its route and how it was computed (a block held at the start has a route of no
    /// increments).
    #[serde(skip)]
    pub run: Computed,
}

/// Whether a factor of safety meets `required`: a number at least it, or unbounded (no
/// multiple of the driving loads starts the block).
pub fn meets(fs: Option<FactorOfSafety>, required: f64) -> bool {
    match fs {
        Some(FactorOfSafety::Finite { value }) => value >= required,
        Some(FactorOfSafety::Unbounded) => true,
        Some(FactorOfSafety::NotHoldable) | None => false,
    }
}

/// The load cases of `scene` (`[[case]]`; a scene without any is one usual case, as written),
/// each with its factor of safety, verdict and route (at most
/// [`KEPT_ROWS`](crate::route::KEPT_ROWS) of its rows kept). `each` is called after each case (for
/// progress). A case whose levels or coefficients make no valid scene is an error naming it.
pub fn check_cases(
    scene: &Scene,
    each: impl FnMut(&CaseResult),
) -> Result<Vec<CaseResult>, SceneError> {
    check_cases_until(scene, each, || false)
}

/// [`check_cases`], asking `stop` before each case and at each increment of a case's route:
/// once it answers true the route under way ends there (termination "interrupted") and the
/// cases done so far are returned, that one last; a caller that stopped the check knows it
/// holds fewer results than cases.
pub fn check_cases_until(
    scene: &Scene,
    mut each: impl FnMut(&CaseResult),
    stop: impl Fn() -> bool,
) -> Result<Vec<CaseResult>, SceneError> {
    let cases = cases_of(scene);
    let mut out = Vec::with_capacity(cases.len());
    for case in cases.iter() {
        if stop() {
            break;
        }
        let s = scene.for_case(case)?;
        let observe = |_: f64| {
            if stop() {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        };
        // A few rows kept (its summary, its path): a case of any length in bounded memory.
        let run = Runner::new(&s.simulation()?)
            .progress(observe)
            .keep_at_most(crate::route::KEPT_ROWS)
            .run();
        let fs = run.route.factor_of_safety;
        let gravity = gravity_case(&s, case.category, &run.route).map(|c| gravity_method(&c));
        let passes = match &gravity {
            Some(g) => verdict(g, case.required_fs, scene.guideline()),
            None => meets(fs, case.required_fs),
        };
        let result = CaseResult {
            case: case.clone(),
            factor_of_safety: fs,
            load_multiple_limit: run.route.factor_of_safety_limit,
            required_fs: case.required_fs,
            gravity,
            passes,
            loads: s.loads_used(),
            anchors: s.anchors().to_vec(),
            run,
        };
        each(&result);
        out.push(result);
    }
    Ok(out)
}

/// The load cases of `scene`: its `[[case]]`s, or one usual case, the scene as written.
pub(super) fn cases_of(scene: &Scene) -> std::borrow::Cow<'_, [LoadCase]> {
    if scene.cases().is_empty() {
        std::borrow::Cow::Owned(vec![LoadCase {
            name: "as written".to_string(),
            category: Category::Usual,
            required_fs: scene.guideline().required(Category::Usual),
            keys: Vec::new(),
        }])
    } else {
        std::borrow::Cow::Borrowed(scene.cases())
    }
}

/// The gravity method's case of the scene `s` (a case's), on a monolith with its water and a
/// friction criterion: in the axes of its base where it starts — where `route` set it down on
/// its base (`contacts = "base"`), else the three-point frame's start — on the faces under it.
pub(super) fn gravity_case(s: &Scene, category: Category, route: &Route) -> Option<GravityCase> {
    let (m, loads, strengths) = (s.monolith()?, s.loads()?, s.strengths()?);
    let water = loads.water?;
    let (axes, under) = match route.base() {
        Some(b) => {
            let r = b.resting.rotation;
            let col = |k: usize| Vector3::new(r[0][k], r[1][k], r[2][k]);
            // The faces carrying it, the most loaded first (the method takes three).
            let mut share: Vec<(u32, f64)> = Vec::new();
            for c in &b.resting.carrying {
                match share.iter_mut().find(|(f, _)| *f == c.face) {
                    Some((_, s)) => *s += c.share,
                    None => share.push((c.face, c.share)),
                }
            }
            share.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
            let faces: Vec<u32> = share.iter().map(|(f, _)| *f).collect();
            ([col(0), col(1), col(2)], faces)
        }
        None => (start_axes(s), faces_of(s.site()).to_vec()),
    };
    Some(GravityCase {
        section: m.section,
        levels: water.levels,
        gravity: loads.gravity,
        kh: loads.kh,
        kv: loads.kv,
        friction: strengths.friction,
        cohesion_pa: strengths.cohesion_pa,
        category,
        anchors: s.anchors().to_vec(),
        faces: faces_under(s, strengths, &axes, &under),
        up: axes.map(|e| e.y),
        downstream: axes.map(|e| e.x),
    })
}

/// The base's axes i′, j′, k′ at the start (the scene's axes, where the start has no pose).
fn start_axes(s: &Scene) -> [Vector3<f64>; 3] {
    match PoseFinder::new(s.site(), Mode::Exact, PoseMethod::Continuation).pose() {
        Some(p) => [p.frame.i, p.frame.j, p.frame.k],
        None => [Vector3::x(), Vector3::y(), Vector3::z()],
    }
}

/// The faces `under` the monolith, each once, with its normal in the base's axes `axes` at
/// the start and its criterion and cohesion under `strengths`.
fn faces_under(
    s: &Scene,
    strengths: &Strengths,
    axes: &[Vector3<f64>; 3],
    under: &[u32],
) -> Vec<BaseFace> {
    let site = s.site();
    let mut faces: Vec<BaseFace> = Vec::new();
    for &face in under.iter().take(3) {
        if faces.iter().any(|f| f.face == face) {
            continue;
        }
        let normal = match site.ground() {
            Some((g, _)) => g.faces().get(face as usize).map(|p| p.normal()),
            None => site.planes().get(face as usize).map(|p| p.normal()),
        };
        let Some(normal) = normal else {
            continue;
        };
        let own = strengths.face(face);
        faces.push(BaseFace {
            face,
            normal: axes.map(|e| e.dot(&normal)),
            friction: own.criterion,
            cohesion_pa: own.cohesion_pa,
        });
    }
    faces
}

/// Whether the gravity method's verdicts meet the case's requirement `required` and the
/// guideline's allowable bearing stress.
pub(super) fn verdict(g: &GravityVerdict, required: f64, guideline: &Guideline) -> bool {
    let sliding = g.sliding_fs.is_none_or(|fs| fs >= required);
    let bearing = guideline
        .allowable_bearing_pa
        .is_none_or(|q| g.heel_pressure_pa.max(g.toe_pressure_pa) <= q);
    sliding && g.resultant_passes && bearing
}
