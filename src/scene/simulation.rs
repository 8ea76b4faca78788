//! A scene that can be run: its [`Simulation`] of one body, every section it needs present and
//! their combination one the dynamics can run.

use super::error::SceneErrorKind;
use super::{Scene, SceneError};
use crate::model::{Body, Foundation, ModelError, Simulation};

impl Scene {
    /// The scene's simulation, or an error naming the first missing section or the setting that
    /// cannot be run as written.
    pub fn simulation(&self) -> Result<Simulation, SceneError> {
        let missing = |section: &str| {
            SceneError::of(
                SceneErrorKind::MissingSection,
                &self.origin,
                section,
                format!("missing section [{section}] (needed to simulate)"),
            )
        };
        // The values were validated when the scene was read: a scene is built no other way, and
        // building checks them once more only as cheap comparisons.
        let block = self.block.ok_or_else(|| missing("block"))?;
        let loads = self.loads.ok_or_else(|| missing("loads"))?;
        let strengths = self.strengths.clone().ok_or_else(|| missing("friction"))?;
        let settings = self.settings.ok_or_else(|| missing("solver"))?;
        let model = |e: ModelError| SceneError::new(&self.origin, e.key, e.reason);
        let mut body = Body::builder(self.site.clone())
            .name("block")
            .block(block)
            .loads(loads)
            .initial(self.initial)
            .shares_m2(self.shares_m2);
        if let Some(base) = &self.base {
            body = body.base(base.clone());
        }
        if let (Some(m), false) = (&self.monolith, self.anchors.is_empty()) {
            body = body.anchors(m, &self.anchors);
        }
        let mut foundation = Foundation::under(&self.site);
        if let Some(record) = &self.record {
            foundation = foundation.shaken(record.clone());
            if self.both_polarities {
                foundation = foundation.reversed_too();
            }
        }
        Simulation::builder()
            .name(self.name.clone())
            .body(body.build().map_err(model)?)
            .foundation(foundation)
            .strengths(strengths)
            .settings(settings)
            .build()
            .map_err(model)
    }
}
