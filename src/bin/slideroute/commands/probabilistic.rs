//! `slideroute probabilistic`: uncertain scene keys sampled from their distributions, every
//! sample's route in parallel (the library's `slideroute::probabilistic`), `samples.csv`,
//! `probabilistic.json` and the pictures (`slideroute::output::ProbabilisticFiles`).

use super::{load_with, progress_bar, warn_all};
use crate::cli::ProbabilisticArgs;
use crate::exit::{CliError, bad_input, interrupted, many_interrupted_after, outln, output_error};
use slideroute::Scene;
use slideroute::output::{OutputFolder, ProbabilisticFiles};
use slideroute::probabilistic::{
    Design, Limits, MAX_SAMPLES, Sampling, Summary, Uncertain, check_uncertain, merged,
};

/// Runs `slideroute probabilistic`.
pub fn probabilistic(args: &ProbabilisticArgs) -> Result<(), CliError> {
    let base = load_with(&args.scene, args.dynamics)?;
    if args.samples == 0 || args.samples > MAX_SAMPLES {
        return Err(bad_input(format!(
            "--samples {}: from 1 to {MAX_SAMPLES}",
            args.samples
        )));
    }
    let limits = Limits::new(args.travel_limit_m, args.rotation_limit_deg)
        .and_then(|l| l.with_displacement(args.displacement_limit_m))
        .map_err(|(name, l)| {
            bad_input(format!(
                "--{} {l}: a finite number, zero or more",
                name.replace('_', "-")
            ))
        })?;
    if args.displacement_limit_m.is_some() && base.record().is_none() {
        return Err(bad_input(format!(
            "--displacement-limit-m: {} has no ground-motion record ([seismic] record) to \
             displace the block",
            base.origin()
        )));
    }
    let uncertain = uncertain(&base, &args.dist)?;
    let folder = OutputFolder::open(&args.out, "probabilistic").map_err(output_error)?;
    let bar = progress_bar(args.quiet, args.samples as u64, "probabilistic", "samples");
    let design = Design {
        scene: &base,
        uncertain: &uncertain,
        samples: args.samples,
        seed: args.seed,
        sampling: args.sampling,
    };
    let written = ProbabilisticFiles::new(&design, limits)
        .pictures(!args.no_plots)
        .view(!args.no_3d)
        .write(folder, || bar.inc(1), interrupted);
    bar.finish_and_clear();
    let (summary, written) = written.map_err(output_error)?;
    warn_all(&written.warnings);
    if interrupted() {
        return Err(many_interrupted_after("samples", &written.files));
    }
    if !args.quiet {
        print_summary(&summary, args.sampling, &written.files)?;
    }
    Ok(())
}

/// The uncertain keys: the scene's `[uncertain]` table, then `--dist` (a key of both takes the
/// command line's), each a number of the scene, given once; the error names each as it was
/// given.
fn uncertain(base: &Scene, dist: &[String]) -> Result<Vec<Uncertain>, CliError> {
    let given = dist
        .iter()
        .map(|d| d.parse::<Uncertain>().map_err(|e| format!("--dist {e}")))
        .collect::<Result<Vec<_>, _>>()
        .map_err(bad_input)?;
    let uncertain = merged(base.uncertain(), given);
    if uncertain.is_empty() {
        return Err(bad_input(format!(
            "{}: nothing is uncertain: give --dist KEY=DISTRIBUTION or an [uncertain] table in \
             the scene",
            base.origin()
        )));
    }
    check_uncertain(base, &uncertain).map_err(|e| {
        let on_command_line = dist.iter().any(|d| d.starts_with(&format!("{}=", e.key)));
        if on_command_line || !base.uncertain().iter().any(|u| u.key == e.key) {
            bad_input(format!("--dist {e}"))
        } else {
            bad_input(format!(
                "{}: uncertain.\"{}\": {}",
                base.origin(),
                e.key,
                e.reason
            ))
        }
    })?;
    Ok(uncertain)
}

/// What the samples came to, and the files written.
fn print_summary(
    summary: &Summary,
    sampling: Sampling,
    written: &[std::path::PathBuf],
) -> Result<(), CliError> {
    let how = match sampling {
        Sampling::MonteCarlo => "Monte Carlo",
        Sampling::LatinHypercube => "Latin hypercube",
    };
    outln!(
        "probabilistic {}: {} samples ({how}), {} routes, {} invalid",
        summary.scene,
        summary.samples,
        summary.routes,
        summary.invalid_samples
    );
    if summary.shaken {
        // Under a record the static factor of safety does not say whether the block slides.
        outln!(
            "  probability the record displaces the block {}",
            summary.probability_of_sliding
        );
        match (
            summary.displacement_limit_m,
            summary.probability_displacement_exceeds_limit,
        ) {
            (Some(l), Some(q)) => {
                outln!("  probability the permanent displacement exceeds {l} m {q}")
            }
            _ => outln!(
                "  (name a permanent displacement limit with --displacement-limit-m for its \
                 probability)"
            ),
        }
        if let Some(p) = summary.permanent_displacement_m {
            outln!(
                "  permanent displacement 5 / 50 / 95 %: {:.4} / {:.4} / {:.4} m",
                p.p5,
                p.p50,
                p.p95
            );
        }
    } else {
        outln!(
            "  probability of sliding (factor of safety below 1) {}",
            summary.probability_of_sliding
        );
    }
    for (what, prob) in [
        (
            "travel over the limit",
            summary.probability_travel_exceeds_limit,
        ),
        (
            "rotation over the limit",
            summary.probability_rotation_exceeds_limit,
        ),
    ] {
        if let Some(q) = prob {
            outln!("  probability of {what} {q}");
        }
    }
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    outln!("  wrote {}", names.join(", "));
    Ok(())
}
