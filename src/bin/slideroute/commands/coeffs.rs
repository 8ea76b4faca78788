//! `slideroute coeffs`: the coefficients of the paper's small-angle system (15) and of the
//! exact form at one displacement.

use super::{displacement, load, print_json};
use crate::cli::CoeffsArgs;
use crate::exit::{CliError, bad_input, out};
use slideroute::output::{CoeffReport, number};

/// Runs `slideroute coeffs`.
pub fn coeffs(args: &CoeffsArgs) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    let report =
        CoeffReport::new(&scene, displacement(&(&args.pose).into())?).ok_or_else(|| {
            bad_input(format!(
                "{}: coeffs prints the paper's f1–f12 and exact (13), (14), which need the paper's \
             frame (l1x … l2z) and planes (xi_deg, zeta_deg, kappa_deg); this scene's pose comes \
             from the general system (derivations/09-general-pose.md)",
                scene.origin()
            ))
        })?;
    if let Some(name) = report.not_finite() {
        return Err(bad_input(format!(
            "--x {} --z {} --theta-deg {}: {name} is not a finite number there (the \
             displacement is too large for the system to be evaluated)",
            number(report.x_m),
            number(report.z_m),
            number(report.theta_deg)
        )));
    }
    if args.json {
        print_json(&report)
    } else {
        out!("{report}");
        Ok(())
    }
}
