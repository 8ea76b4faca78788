//! A scene that can be run: its [`Simulation`], every section it needs present and their
//! combination one the dynamics can run.

use super::error::SceneErrorKind;
use super::{Scene, SceneError};
use crate::model::Simulation;

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
        let friction = self.friction.ok_or_else(|| missing("friction"))?;
        let settings = self.settings.ok_or_else(|| missing("solver"))?;
        let mut builder = Simulation::builder(self.site.clone())
            .name(self.name.clone())
            .block(block)
            .loads(loads)
            .friction(friction)
            .strengths(self.strengths.clone())
            .settings(settings)
            .initial(self.initial);
        if let Some(record) = &self.record {
            builder = builder.record(record.clone());
            if self.both_polarities {
                builder = builder.both_polarities();
            }
        }
        if let Some(base) = &self.base {
            builder = builder.base(base.clone());
        }
        if let (Some(m), false) = (&self.monolith, self.anchors.is_empty()) {
            builder = builder.anchors(m, &self.anchors);
        }
        builder
            .build()
            .map_err(|e| SceneError::new(&self.origin, e.key, e.reason))
    }
}
