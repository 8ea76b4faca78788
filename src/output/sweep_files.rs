//! The files of a sweep, as `slideroute sweep` writes them: `sweep.csv` (a row per combination,
//! written as they come), `sweep.svg` (the travel and the factor of safety against the first
//! key) and `sweep.html` (every combination's CM path over the ground, in 3-D).

use super::sweep_csv::SweepCsv;
use super::sweep_row::SweepRow;
use super::{MAX_FAN_PATHS, OutputError, OutputFolder, Written};
use crate::sweep::Sweep;
use crate::{Outcome, Scene};
use std::collections::BTreeMap;

/// A sweep's routes and its files, whole or absent: what `slideroute sweep` writes. The sweep
/// runs here, on every core, each combination written to `sweep.csv` as it comes, so that a
/// sweep of any size is written in bounded memory.
///
/// ```
/// use slideroute::output::{OutputFolder, SweepFiles};
/// use slideroute::sweep::{Sweep, Vary};
/// let base = slideroute::Scene::default_scene().with("solver.t_end_s", 0.1)?;
/// let sweep = Sweep::new(&base, vec!["friction.mu_k=0.3:0.5:3".parse::<Vary>()?])?;
/// let dir = std::env::temp_dir().join(format!("slideroute-doc-sweep-{}", std::process::id()));
/// let (written, ends) = SweepFiles::new(&base, &sweep)
///     .pictures(false)
///     .view(false)
///     .write(OutputFolder::open(&dir, "sweep")?, || (), || false)?;
/// assert!(written.files[0].ends_with("sweep.csv"));
/// assert_eq!(ends.values().sum::<usize>(), 3);
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct SweepFiles<'a> {
    base: &'a Scene,
    sweep: &'a Sweep<'a>,
    pictures: bool,
    view: bool,
}

/// What a sweep kept of its combinations as they came, for the pictures.
struct Kept {
    /// How many combinations ended each way, by the reason's words.
    counts: BTreeMap<String, usize>,
    /// How many ran a route.
    routes: usize,
    /// The first routes, for the fan page.
    fan: Vec<Outcome>,
    #[cfg(feature = "plots")]
    drawn: super::plots::Drawn,
}

impl<'a> SweepFiles<'a> {
    /// The files of `sweep`, made from the scene `base`.
    pub fn new(base: &'a Scene, sweep: &'a Sweep<'a>) -> SweepFiles<'a> {
        SweepFiles {
            base,
            sweep,
            pictures: true,
            view: true,
        }
    }

    /// With `sweep.svg` or without it.
    pub fn pictures(self, on: bool) -> SweepFiles<'a> {
        SweepFiles {
            pictures: on,
            ..self
        }
    }

    /// With `sweep.html` or without it.
    pub fn view(self, on: bool) -> SweepFiles<'a> {
        SweepFiles { view: on, ..self }
    }

    /// Runs every combination, `tick` called as each route ends, writing `sweep.csv` as they
    /// come; then the pictures (not after `stop` answered true: the combinations not started
    /// are rows "not run (interrupted)"), and finishes `folder`. Gives the files written and
    /// how many combinations ended each way (by the reason's words, as `sweep.csv` has them).
    pub fn write(
        &self,
        mut folder: OutputFolder,
        tick: impl Fn() + Sync,
        stop: impl Fn() -> bool + Sync,
    ) -> Result<(Written, BTreeMap<String, usize>), OutputError> {
        let mut kept = Kept {
            counts: BTreeMap::new(),
            routes: 0,
            fan: Vec::new(),
            #[cfg(feature = "plots")]
            drawn: super::plots::Drawn::new(self.sweep.varies(), Some(folder.staging()?)),
        };
        let csv = folder.write_with("sweep.csv", |tmp| self.rows(tmp, &mut kept, tick, &stop))?;
        #[allow(unused_mut)]
        let mut written = Written {
            files: vec![csv],
            warnings: Vec::new(),
        };
        #[cfg(feature = "view")]
        if self.view && !stop() {
            written.extend(self.fan_page(&mut folder, &kept)?);
        }
        #[cfg(feature = "plots")]
        if self.pictures {
            let varies = self.sweep.varies();
            written.files.push(folder.write_with("sweep.svg", |tmp| {
                super::plots::sweep_drawn(tmp, varies, &kept.drawn)
            })?);
        }
        #[cfg(not(all(feature = "view", feature = "plots")))]
        let _ = (self.base, self.pictures, self.view, kept.routes, &kept.fan);
        folder.finish()?;
        Ok((written, kept.counts))
    }

    /// Every combination, as it comes, written to `sweep.csv` at `tmp`, counted, and what the
    /// picture shows of it kept if it lies on a line the picture draws (in a temporary file in
    /// the staging folder past a few MB); the first routes kept for the fan.
    fn rows(
        &self,
        tmp: &std::path::Path,
        kept: &mut Kept,
        tick: impl Fn() + Sync,
        stop: impl Fn() -> bool + Sync,
    ) -> Result<(), OutputError> {
        let file = std::fs::File::create(tmp)
            .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
        let mut csv = SweepCsv::new(std::io::BufWriter::new(file), self.sweep.varies())
            .map_err(|e| format!("sweep.csv: {e}"))?;
        self.sweep.run_each(tick, stop, |ran| {
            let row = SweepRow::from(&ran);
            csv.push(&row).map_err(|e| format!("sweep.csv: {e}"))?;
            *kept.counts.entry(row.reason.clone()).or_default() += 1;
            kept.routes += usize::from(row.travel_m.is_some());
            #[cfg(feature = "plots")]
            if self.pictures {
                kept.drawn
                    .add(&row)
                    .map_err(|e| format!("sweep picture: {e}"))?;
            }
            if kept.fan.len() < MAX_FAN_PATHS && ran.outcome.route().is_some() {
                kept.fan.push(ran.outcome);
            }
            Ok::<(), String>(())
        })?;
        csv.finish().map_err(|e| format!("sweep.csv: {e}"))?;
        Ok(())
    }

    /// `sweep.html`: every combination's CM path over the base scene's foundation.
    #[cfg(feature = "view")]
    fn fan_page(&self, folder: &mut OutputFolder, kept: &Kept) -> Result<Written, OutputError> {
        use super::view::many;
        let (paths, _) = many::cm_paths(&kept.fan);
        let mut notes: Vec<String> = self
            .sweep
            .varies()
            .iter()
            .map(|v| {
                let n = v.values.len();
                format!("{}: {n} value{}", v.key, if n == 1 { "" } else { "s" })
            })
            .collect();
        notes.push("the foundation is drawn as the base scene writes it".into());
        let page = many::fan_page(self.base, None, &paths, kept.routes, "combinations", notes);
        super::view::write_page(folder, "sweep.html", &page)
    }
}
