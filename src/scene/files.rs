//! The files a scene names (a surface, a ground-motion record) and what was read from them:
//! a scene edited by key (`Scene::with`) keeps them rather than reading them again.

use super::Scene;
use super::record::Record;
use crate::geometry::Ground;
use std::sync::Arc;

/// The files a scene named and what was read from them, by the name the scene gave.
#[derive(Default)]
pub(super) struct Files {
    pub surface: Option<(String, Arc<Ground>)>,
    pub record: Option<(String, Arc<Record>)>,
}

impl Files {
    /// What `scene` read.
    pub fn of(scene: &Scene) -> Files {
        let named = |section: &str, key: &str| {
            scene
                .source
                .get(section)
                .and_then(|s| s.get(key))
                .and_then(|v| v.as_str())
                .map(str::to_string)
        };
        Files {
            surface: named("foundation", "surface").zip(scene.site.shared_ground().cloned()),
            record: named("seismic", "record").zip(scene.record.clone()),
        }
    }
}
