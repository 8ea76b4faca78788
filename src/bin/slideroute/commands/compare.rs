//! `slideroute run --compare-dynamics`: the paper's route beside the rigid body's, each in its
//! own folder, where they part, both CM paths on one plan view and both routes in 3-D
//! (`compare.html`): `slideroute::output::ComparisonFiles`.

use super::{load, warn_all};
use crate::cli::RunArgs;
use crate::exit::{CliError, interrupted, interrupted_after, out, output_error};
use slideroute::output::{ComparisonFiles, OutputFolder};

/// Runs `slideroute run --compare-dynamics`.
pub fn compare(args: &RunArgs) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    let folder = OutputFolder::open(&args.out_dir(), "run").map_err(output_error)?;
    let (c, written) = ComparisonFiles::new(&scene)
        .pictures(!args.no_plots)
        .view(!args.no_3d)
        .write(folder, interrupted)
        .map_err(output_error)?;
    warn_all(&written.warnings);
    if interrupted() {
        return Err(interrupted_after(
            "interrupted: the routes stopped at their next increment",
            &written.files,
        ));
    }
    if !args.quiet {
        out!("{}", c.summary(&written.files));
    }
    Ok(())
}
