//! `slideroute check`: each load case's factor of safety at the start against the
//! factor its guideline requires, and the route of each case, so that a case that fails shows
//! where the monolith would go (`derivations/11-dam-loads.md` §5).

use crate::mechanics::static_friction::FactorOfSafety;
use crate::model::{Category, LoadCase};
use crate::route::{Computed, Runner};
use crate::scene::{LoadsUsed, Scene, SceneError};

/// One load case checked.
#[derive(Debug, Clone, serde::Serialize)]
pub struct CaseResult {
    /// The load case.
    pub case: LoadCase,
    /// The guideline factor of safety at the start (`None` where the start has no pose).
    pub factor_of_safety: Option<FactorOfSafety>,
    /// Whether it is at least the case's requirement.
    pub passes: bool,
    /// The loads the case used.
    pub loads: Option<LoadsUsed>,
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
/// each with its factor of safety, verdict and route. `each` is called after each case (for
/// progress). A case whose levels or coefficients make no valid scene is an error naming it.
pub fn check_cases(
    scene: &Scene,
    mut each: impl FnMut(&CaseResult),
) -> Result<Vec<CaseResult>, SceneError> {
    let as_written;
    let cases = if scene.cases().is_empty() {
        as_written = [LoadCase {
            name: "as written".to_string(),
            category: Category::Usual,
            required_fs: scene.guideline().required(Category::Usual),
            keys: Vec::new(),
        }];
        &as_written[..]
    } else {
        scene.cases()
    };
    let mut out = Vec::with_capacity(cases.len());
    for case in cases {
        let s = scene.for_case(case)?;
        let run = Runner::new(&s.simulation()?).run();
        let fs = run.route.factor_of_safety;
        let result = CaseResult {
            case: case.clone(),
            factor_of_safety: fs,
            passes: meets(fs, case.required_fs),
            loads: s.loads_used(),
            run,
        };
        each(&result);
        out.push(result);
    }
    Ok(out)
}
