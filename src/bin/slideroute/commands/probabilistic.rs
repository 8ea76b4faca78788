//! `slideroute probabilistic`: uncertain scene keys sampled from their distributions, every
//! sample's route in parallel (the library's `slideroute::probabilistic`), `samples.csv`,
//! `probabilistic.json` and the pictures.

use super::{load_with, progress_bar};
use crate::cli::ProbabilisticArgs;
use crate::exit::{
    CliError, bad_input, failed, interrupted, interrupted_after, many_interrupted_after, outln,
};
use crate::output::folder::Folder;
use crate::output::route_files::{Manifest, write_json_with_manifest};
use crate::output::samples_files::SamplesCsv;
use crate::output::view::many::MAX_FAN_PATHS;
use slideroute::Scene;
use slideroute::probabilistic::{
    Design, Limits, MAX_SAMPLES, Sample, Sampling, Summary, Tally, Uncertain, check_uncertain,
    merged,
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
    let mut folder = Folder::open(&args.out, "probabilistic").map_err(failed)?;
    let bar = progress_bar(args.quiet, args.samples as u64, "probabilistic", "samples");
    let design = Design {
        scene: &base,
        uncertain: &uncertain,
        samples: args.samples,
        seed: args.seed,
        sampling: args.sampling,
    };
    // Each sample, as it comes, written to samples.csv and tallied (its values kept in a
    // temporary file in the staging folder past a few MB); the first routes kept for the fans.
    let mut tally = Tally::new(&design, limits, Some(folder.staging().map_err(failed)?));
    let mut kept: Vec<Sample> = Vec::new();
    let csv_path = folder
        .write_with("samples.csv", |tmp| {
            let file = std::fs::File::create(tmp)
                .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
            let mut csv = SamplesCsv::new(std::io::BufWriter::new(file), &uncertain)
                .map_err(|e| format!("samples.csv: {e}"))?;
            design.run_each(
                || bar.inc(1),
                interrupted,
                |s| {
                    csv.push(&s).map_err(|e| format!("samples.csv: {e}"))?;
                    tally
                        .add(&s)
                        .map_err(|e| format!("the samples' temporary file: {e}"))?;
                    if kept.len() < MAX_FAN_PATHS && s.outcome.route().is_some() {
                        kept.push(s);
                    }
                    Ok::<(), String>(())
                },
            )?;
            csv.finish().map_err(|e| format!("samples.csv: {e}"))
        })
        .map_err(failed)?;
    bar.finish_and_clear();
    // Summed up whole after an interrupted run (its samples not run counted); a Ctrl-C while
    // millions of routes are summed up stops it.
    if !interrupted() {
        tally.stop_when(interrupted);
    }
    let summary = tally.finish().map_err(|e| {
        if e.kind() == std::io::ErrorKind::Interrupted {
            interrupted_after(
                "interrupted while the samples were summed up (probabilistic.json not written)",
                std::slice::from_ref(&csv_path),
            )
        } else {
            failed(format!("the samples' temporary file: {e}"))
        }
    })?;
    let mut written = vec![csv_path];
    // The scene as written, drawn in black on the fan (route-fan.svg and route-fan.html).
    let drawn_plots = cfg!(feature = "plots") && !args.no_plots;
    let nominal = if (drawn_plots || !args.no_3d) && !interrupted() {
        slideroute::run(&base).ok()
    } else {
        None
    };
    #[cfg(feature = "plots")]
    if drawn_plots && !interrupted() {
        let staging = folder.staging().map_err(failed)?;
        let fs = |each: &mut dyn FnMut(Option<f64>)| {
            tally
                .factors_of_safety(|v| each(Some(v).filter(|v| !v.is_nan())))
                .map_err(|e| format!("the samples' temporary file: {e}"))
        };
        let staged = crate::output::plots::write_probabilistic_plots(
            &staging,
            &base,
            nominal.as_ref(),
            &kept,
            &fs,
            &summary,
        )
        .map_err(failed)?;
        written.extend(folder.adopt_all(staged).map_err(failed)?);
    }
    if !args.no_3d && !interrupted() {
        let (paths, _) = crate::output::view::many::cm_paths(kept.iter().map(|s| &s.outcome));
        let routes = summary.routes;
        let mut notes = vec![format!(
            "{} samples, seed {}; the foundation is drawn as the scene writes it",
            summary.samples, summary.seed
        )];
        notes.extend(
            summary
                .distributions
                .iter()
                .map(|g| format!("{}: {}", g.key, g.distribution)),
        );
        let page = crate::output::view::many::fan_page(
            &base,
            nominal.as_ref(),
            &paths,
            routes,
            "sampled routes",
            notes,
        );
        written.extend(
            crate::output::view::many::write_page(&mut folder, "route-fan.html", &page)
                .map_err(failed)?,
        );
    }
    let manifest = Manifest::new(&base, &folder);
    let json = write_json_with_manifest(&mut folder, "probabilistic.json", &summary, &manifest)
        .map_err(failed)?;
    folder.finish().map_err(failed)?;
    written.push(json);
    if interrupted() {
        return Err(many_interrupted_after("samples", &written));
    }
    if !args.quiet {
        print_summary(&summary, args.sampling, &written)?;
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
