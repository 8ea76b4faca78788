//! The files of a probabilistic analysis, as `slideroute probabilistic` writes them:
//! `samples.csv` (a row per sample, written as they come), the pictures (`route-fan.svg`,
//! `factor-of-safety.svg`, `sensitivity.svg`), every sample's CM path in 3-D
//! (`route-fan.html`) and `probabilistic.json` (what the samples come to, with the manifest,
//! last).

use super::manifest::{Manifest, write_json_with_manifest};
use super::samples_csv::SamplesCsv;
use super::{MAX_FAN_PATHS, OutputError, OutputFolder, Written};
use crate::probabilistic::{Design, Limits, Sample, Summary, Tally};
use std::path::Path;

/// A probabilistic analysis's routes and its files, whole or absent: what `slideroute
/// probabilistic` writes. The samples run here, on every core, each written to `samples.csv`
/// and tallied as it comes (the values past a few MB in a temporary file in the folder's staging
/// folder), so that any number of samples is written in bounded memory.
///
/// ```
/// use slideroute::output::{OutputFolder, ProbabilisticFiles};
/// use slideroute::probabilistic::{Design, Limits, Sampling, Uncertain};
/// let scene = slideroute::Scene::default_scene().with("solver.t_end_s", 0.1)?;
/// let uncertain: Vec<Uncertain> = vec!["friction.mu_k=uniform:0.3:0.5".parse()?];
/// let design = Design { scene: &scene, uncertain: &uncertain, samples: 4, seed: 1, sampling: Sampling::LatinHypercube };
/// let dir = std::env::temp_dir().join(format!("slideroute-doc-samples-{}", std::process::id()));
/// fn never() -> bool { false }
/// let (summary, written) = ProbabilisticFiles::new(&design, Limits::default())
///     .pictures(false)
///     .view(false)
///     .write(OutputFolder::open(&dir, "probabilistic")?, || (), never)?;
/// assert_eq!(summary.samples, 4);
/// assert!(written.files.last().unwrap().ends_with("probabilistic.json"));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct ProbabilisticFiles<'a> {
    design: &'a Design<'a>,
    limits: Limits,
    pictures: bool,
    view: bool,
}

/// What the analysis kept of its samples as they came: the tally, and the first routes for the
/// fans.
struct Kept {
    tally: Tally,
    fan: Vec<Sample>,
}

impl<'a> ProbabilisticFiles<'a> {
    /// The files of `design`'s samples, with the probabilities of exceeding `limits`.
    pub fn new(design: &'a Design<'a>, limits: Limits) -> ProbabilisticFiles<'a> {
        ProbabilisticFiles {
            design,
            limits,
            pictures: true,
            view: true,
        }
    }

    /// With the pictures or without them.
    pub fn pictures(self, on: bool) -> ProbabilisticFiles<'a> {
        ProbabilisticFiles {
            pictures: on,
            ..self
        }
    }

    /// With `route-fan.html` or without it.
    pub fn view(self, on: bool) -> ProbabilisticFiles<'a> {
        ProbabilisticFiles { view: on, ..self }
    }

    /// Runs every sample, `tick` called as each route ends, writing `samples.csv` as they come;
    /// sums them up; then the pictures and the fan page (not after `stop` answered true: the
    /// samples not started are rows "not run (interrupted)"), `probabilistic.json`, and
    /// finishes `folder`. Gives what the samples come to and the files written. A summing up
    /// that `stop` ends is [`OutputError::Interrupted`], `probabilistic.json` not written.
    pub fn write(
        &self,
        mut folder: OutputFolder,
        tick: impl Fn() + Sync,
        stop: fn() -> bool,
    ) -> Result<(Summary, Written), OutputError> {
        let tally = Tally::new(self.design, self.limits, Some(folder.staging()?));
        let mut kept = Kept {
            tally,
            fan: Vec::new(),
        };
        let csv = folder.write_with("samples.csv", |tmp| self.rows(tmp, &mut kept, tick, stop))?;
        let summary = summed_up(&mut kept.tally, stop, &csv)?;
        let mut written = Written {
            files: vec![csv],
            warnings: Vec::new(),
        };
        if !stop() {
            written.extend(self.pictured(&mut folder, &kept, &summary)?);
        }
        let manifest = Manifest::new(self.design.scene, &folder);
        let json =
            write_json_with_manifest(&mut folder, "probabilistic.json", &summary, &manifest)?;
        folder.finish()?;
        written.files.push(json);
        Ok((summary, written))
    }

    /// Every sample, as it comes, written to `samples.csv` at `tmp` and tallied; the first
    /// routes kept for the fans.
    fn rows(
        &self,
        tmp: &Path,
        kept: &mut Kept,
        tick: impl Fn() + Sync,
        stop: fn() -> bool,
    ) -> Result<(), OutputError> {
        let file = std::fs::File::create(tmp)
            .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
        let mut csv = SamplesCsv::new(std::io::BufWriter::new(file), self.design.uncertain)
            .map_err(|e| format!("samples.csv: {e}"))?;
        self.design.run_each(tick, stop, |s| {
            csv.push(&s).map_err(|e| format!("samples.csv: {e}"))?;
            kept.tally
                .add(&s)
                .map_err(|e| format!("the samples' temporary file: {e}"))?;
            if kept.fan.len() < MAX_FAN_PATHS && s.outcome.route().is_some() {
                kept.fan.push(s);
            }
            Ok::<(), String>(())
        })?;
        csv.finish().map_err(|e| format!("samples.csv: {e}"))?;
        Ok(())
    }

    /// The pictures and the fan page, as asked and built, with the scene as written drawn in
    /// black on the fans.
    fn pictured(
        &self,
        folder: &mut OutputFolder,
        kept: &Kept,
        summary: &Summary,
    ) -> Result<Written, OutputError> {
        let pictures = cfg!(feature = "plots") && self.pictures;
        let view = cfg!(feature = "view") && self.view;
        let nominal = if pictures || view {
            crate::run(self.design.scene).ok()
        } else {
            None
        };
        #[allow(unused_mut)]
        let mut written = Written::default();
        #[cfg(feature = "plots")]
        if pictures {
            written
                .files
                .extend(self.plots(folder, kept, nominal.as_ref(), summary)?);
        }
        #[cfg(feature = "view")]
        if view {
            written.extend(self.fan_page(folder, kept, nominal.as_ref(), summary)?);
        }
        #[cfg(not(all(feature = "view", feature = "plots")))]
        let _ = (folder, kept, nominal, summary);
        Ok(written)
    }

    /// `route-fan.svg`, `factor-of-safety.svg` and `sensitivity.svg`.
    #[cfg(feature = "plots")]
    fn plots(
        &self,
        folder: &mut OutputFolder,
        kept: &Kept,
        nominal: Option<&crate::Route>,
        summary: &Summary,
    ) -> Result<Vec<std::path::PathBuf>, OutputError> {
        let staging = folder.staging()?;
        let fs = |each: &mut dyn FnMut(Option<f64>)| {
            kept.tally
                .factors_of_safety(|v| each(Some(v).filter(|v| !v.is_nan())))
                .map_err(|e| format!("the samples' temporary file: {e}"))
        };
        let staged = super::plots::write_probabilistic_plots(
            &staging,
            self.design.scene,
            nominal,
            &kept.fan,
            &fs,
            summary,
        )?;
        folder.adopt_all(staged)
    }

    /// `route-fan.html`: every sample's CM path over the scene's foundation.
    #[cfg(feature = "view")]
    fn fan_page(
        &self,
        folder: &mut OutputFolder,
        kept: &Kept,
        nominal: Option<&crate::Route>,
        summary: &Summary,
    ) -> Result<Written, OutputError> {
        use super::view::many;
        let (paths, _) = many::cm_paths(kept.fan.iter().map(|s| &s.outcome));
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
        let page = many::fan_page(
            self.design.scene,
            nominal,
            &paths,
            summary.routes,
            "sampled routes",
            notes,
        );
        super::view::write_page(folder, "route-fan.html", &page)
    }
}

/// What the samples tallied come to: summed up whole after an interrupted run (its samples not
/// run counted); `stop` ends the summing up of millions of routes.
fn summed_up(tally: &mut Tally, stop: fn() -> bool, csv: &Path) -> Result<Summary, OutputError> {
    if !stop() {
        tally.stop_when(stop);
    }
    tally.finish().map_err(|e| {
        if e.kind() == std::io::ErrorKind::Interrupted {
            OutputError::Interrupted {
                what: "interrupted while the samples were summed up (probabilistic.json not \
                       written)"
                    .into(),
                written: vec![csv.to_path_buf()],
            }
        } else {
            OutputError::Write(format!("the samples' temporary file: {e}"))
        }
    })
}
