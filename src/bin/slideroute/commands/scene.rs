//! `slideroute scene`: the embedded default scene or a template to start from, or a scene file
//! checked.

use crate::cli::{SceneFileArgs, Template};
use crate::exit::{CliError, bad_input, out, outln, scene_faults};
use slideroute::{Scene, SceneErrorKind};

/// Runs `slideroute scene`.
pub fn scene(args: &SceneFileArgs) -> Result<(), CliError> {
    if let Some(t) = args.template {
        out!(
            "{}",
            match t {
                Template::Paper => Scene::DEFAULT_TOML,
                Template::Dam => Scene::DAM_TOML,
            }
        );
        return Ok(());
    }
    match (args.print_default, &args.check) {
        (true, _) => {
            out!("{}", slideroute::Scene::DEFAULT_TOML);
            Ok(())
        }
        (false, Some(p)) => {
            let s = Scene::from_file(p).map_err(scene_faults)?;
            let sections = match s.simulation() {
                Ok(_) => "all sections",
                Err(e) if e.kind == SceneErrorKind::MissingSection => {
                    "geometry only (frame, foundation)"
                }
                // Present but not runnable as written (e.g. small-angle with the rigid body).
                Err(e) => return Err(bad_input(e)),
            };
            outln!("{}: ok ({sections})", p.display());
            Ok(())
        }
        (false, None) => Err(bad_input(
            "scene: say --print-default, --template paper|dam or --check FILE",
        )),
    }
}
