//! A scene that can be run: every section present, and their combination one the dynamics
//! can run.

use super::error::SceneErrorKind;
use super::{Block, DynamicsModel, Friction, Loads, Mode, Scene, SceneError, Solver};

/// A scene that can be run (issue #14): its physical model — the frame and foundation, the
/// block, the loads, the friction — and its run settings (`[solver]`), every section present and
/// their combination valid, settled once when it is built ([`Simulation::new`]). Its fields are
/// private: a `Simulation` exists only as validated, and running one checks nothing again.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    scene: Scene,
    block: Block,
    loads: Loads,
    friction: Friction,
    settings: Solver,
    /// The upward unit normals of the planes under vertices 0, 1, 2 (horizontal, plane 1,
    /// plane 2), computed once.
    normals: [nalgebra::Vector3<f64>; 3],
}

impl Simulation {
    /// The scene's simulation, or an error naming the first missing section or the setting that
    /// cannot be run as written.
    pub fn new(scene: &Scene) -> Result<Simulation, SceneError> {
        let missing = |section: &str| {
            SceneError::of(
                SceneErrorKind::MissingSection,
                &scene.origin,
                section,
                format!("missing section [{section}] (needed to simulate)"),
            )
        };
        // The values were validated when the scene was read: a scene is built no other way.
        let block = scene.block.ok_or_else(|| missing("block"))?;
        let loads = scene.loads.ok_or_else(|| missing("loads"))?;
        let friction = scene.friction.ok_or_else(|| missing("friction"))?;
        let settings = scene.solver.ok_or_else(|| missing("solver"))?;
        if settings.dynamics == DynamicsModel::RigidBody && settings.mode == Mode::SmallAngle {
            return Err(SceneError::new(
                &scene.origin,
                "solver.mode",
                "the rigid-body dynamics needs mode = \"exact\": small-angle poses (the paper's \
                 approximation (15)) leave the contacts off their planes (about 1 % in α at \
                 20–25° dips), which the rigid body's contact constraints cannot follow (the \
                 tracker then takes about a thousand steps an increment); use \"exact\", or \
                 dynamics = \"paper\" (--dynamics paper) for the small-angle system",
            ));
        }
        Ok(Simulation {
            scene: scene.clone(),
            block,
            loads,
            friction,
            settings,
            normals: scene.site.normals(),
        })
    }

    /// The scene it was built from (name, frame, foundation, initial motion).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn block(&self) -> &Block {
        &self.block
    }

    pub fn loads(&self) -> &Loads {
        &self.loads
    }

    /// `[friction]`'s criterion (of every face without its own).
    pub fn friction(&self) -> &Friction {
        &self.friction
    }

    /// What the contacts on `faces` carry (each face's criterion; the cohesion when `bonded`:
    /// at rest, never yet slid).
    pub fn strength(&self, faces: [u32; 3], bonded: bool) -> super::Strength {
        self.scene.strengths.at(&self.friction, faces, bonded)
    }

    /// The run settings: mode, dynamics, integrator, dt, t_end, stride.
    pub fn solver(&self) -> &Solver {
        &self.settings
    }

    /// The upward unit normals of the planes under vertices 0, 1, 2.
    pub fn normals(&self) -> &[nalgebra::Vector3<f64>; 3] {
        &self.normals
    }
}
