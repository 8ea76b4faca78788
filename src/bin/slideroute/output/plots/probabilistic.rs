//! The pictures of `slideroute probabilistic`: the route fan (every sampled CM
//! path in plan over the foundation, beside the route of the scene as written), the histogram
//! of the factor of safety, and the sensitivity tornado (each input's rank correlation with the
//! factor of safety and with the travel).

use super::plan::{self, Fan, Track};
use super::sheet::{self, Area, Entry, Mark, Res, Sheet, err};
use super::thinned;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use slideroute::Outcome;
use slideroute::Route;
use slideroute::Scene;
use slideroute::internals::numeric::fixed;
use slideroute::probabilistic::{Distribution, Sample, Summary};
use std::path::Path;

/// The most sampled paths a route fan draws (the first in sample order, a random subset of a
/// Monte Carlo design): past this the picture would only grow, not tell more.
pub const MAX_FAN_PATHS: usize = 1000;

const BELOW: RGBColor = RGBColor(200, 30, 30);
const ABOVE: RGBColor = RGBColor(30, 90, 200);
const TRAVEL: RGBColor = RGBColor(230, 140, 0);

/// The route fan: the sampled CM paths under the route of the scene as written (`nominal`).
pub fn route_fan(
    path: &Path,
    scene: &Scene,
    nominal: Option<&Route>,
    samples: &[Sample],
    summary: &Summary,
) -> Res<()> {
    let paths: Vec<Vec<[f64; 2]>> = samples
        .iter()
        .filter_map(|s| match &s.outcome {
            Outcome::Route(r) => Some(r.cm_path_m.clone()),
            _ => None,
        })
        .take(MAX_FAN_PATHS)
        .collect();
    let drawn = if paths.len() < summary.routes {
        format!(", the first {} drawn", paths.len())
    } else {
        String::new()
    };
    let fan = Fan {
        paths: &paths,
        name: format!("CM paths of the {} sampled routes{drawn}", summary.routes),
    };
    let rows = nominal.map_or(vec![], |r| thinned(&r.rows));
    let mut notes = vec![Entry::new(
        Mark::None,
        format!(
            "{} samples ({}), seed {}",
            summary.samples,
            match summary.sampling {
                slideroute::probabilistic::Sampling::MonteCarlo => "Monte Carlo",
                slideroute::probabilistic::Sampling::LatinHypercube => "Latin hypercube",
            },
            summary.seed
        ),
    )];
    notes.extend(summary.distributions.iter().map(|g| {
        let words = g
            .distribution
            .parse::<Distribution>()
            .map_or(g.distribution.clone(), |d| d.words());
        Entry::new(Mark::None, format!("{}: {words}", g.key))
    }));
    notes.push(Entry::new(
        Mark::None,
        "the foundation and the force are drawn as the scene writes them",
    ));
    if summary.invalid_samples > 0 {
        notes.push(Entry::new(
            Mark::None,
            format!(
                "{} samples made no valid scene, not drawn: their rows in samples.csv say why",
                summary.invalid_samples
            ),
        ));
    }
    notes.push(Entry::new(Mark::None, sliding(summary)));
    if let Some(t) = summary.travel_m {
        notes.push(Entry::new(
            Mark::None,
            format!(
                "travel (m): 5 % {}, median {}, 95 % {}",
                fixed(t.p5, 3),
                fixed(t.p50, 3),
                fixed(t.p95, 3)
            ),
        ));
    }
    let tracks: Vec<Track> = nominal
        .map(|r| Track {
            name: format!(
                "CM path of the scene as written (travel {} m)",
                fixed(r.travel_m, 3)
            ),
            rows: &rows,
            color: RGBColor(0, 0, 0),
            base: r.base.as_ref(),
        })
        .into_iter()
        .collect();
    plan::plan_view(
        path,
        scene,
        &plan::PlanView {
            title: &format!("{}: route fan, plan view from above", scene.name()),
            tracks: &tracks,
            fan: Some(&fan),
            notes: &notes,
        },
    )
}

/// The histogram of the factor of safety: bars below 1 red, at or above blue; infinite values
/// (no multiple of the loads starts the block, or the weight alone does) counted in the panel.
pub fn factor_of_safety(path: &Path, samples: &[Sample], summary: &Summary) -> Res<()> {
    let fs = factors_of_safety(samples);
    let finite: Vec<f64> = fs
        .iter()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    let title = format!("{}: factor of safety of the samples", summary.scene);
    if finite.is_empty() {
        return sheet::message(
            path,
            (900, 300),
            &title,
            &[format!(
                "No sample has a finite factor of safety ({} routes): nothing to plot.",
                summary.routes
            )],
        );
    }
    let histogram = Histogram::of(&finite);
    let sheet = Sheet::new(path, (1200, 600), &title)?;
    histogram.draw(path, &sheet.chart)?;
    let mut entries = histogram.entries(summary);
    entries.extend(not_drawn(&fs));
    let y = sheet::heading(path, &sheet.panel, "Legend", 0)?;
    sheet::legend(path, &sheet.panel, &entries, y)?;
    sheet.root.present().map_err(err(path))
}

/// The factor of safety of each sample whose route ran: a number, ±∞, or none where the cone
/// program failed.
fn factors_of_safety(samples: &[Sample]) -> Vec<Option<f64>> {
    samples
        .iter()
        .filter_map(|s| match &s.outcome {
            Outcome::Route(r) => Some(r.factor_of_safety_value()),
            _ => None,
        })
        .collect()
}

/// The bars of the factor of safety's histogram: the axis from `lo` to `hi` (half a bar wider
/// than the values and 1 each side), the bars' width and counts from `lo` plus half a bar, and
/// the top of the count axis.
struct Histogram {
    lo: f64,
    hi: f64,
    width: f64,
    counts: Vec<usize>,
    top: f64,
}

impl Histogram {
    /// The histogram of the `finite` factors of safety (not empty): about √n bars, from 10 to
    /// 60, over the values and 1.
    fn of(finite: &[f64]) -> Histogram {
        let (lo, hi) = sheet::ranges(finite.iter().copied().chain([1.0]));
        let bins = (finite.len() as f64).sqrt().clamp(10.0, 60.0) as usize;
        let width = (hi - lo) / bins as f64;
        let mut counts = vec![0usize; bins];
        for v in finite {
            counts[(((v - lo) / width) as usize).min(bins - 1)] += 1;
        }
        let top = counts.iter().copied().max().unwrap_or(1) as f64 * 1.08;
        Histogram {
            lo: lo - 0.5 * width,
            hi: hi + 0.5 * width,
            width,
            counts,
            top,
        }
    }

    /// Its axes on `area`, its bars (below 1 red, at or above blue) and a dashed line at 1.
    fn draw(&self, path: &Path, area: &Area) -> Res<()> {
        let (lo, hi, width, top) = (self.lo, self.hi, self.width, self.top);
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(lo..hi, 0.0..top)
            .map_err(err(path))?;
        let fx = sheet::ticks(lo, hi);
        chart
            .configure_mesh()
            .max_light_lines(1)
            .x_desc("factor of safety at the start")
            .y_desc("samples")
            .x_label_formatter(&fx)
            .y_label_formatter(&|v| format!("{v:.0}"))
            .light_line_style(BLACK.mix(0.05))
            .draw()
            .map_err(err(path))?;
        let start = lo + 0.5 * width;
        chart
            .draw_series(
                self.counts
                    .iter()
                    .enumerate()
                    .filter(|(_, c)| **c > 0)
                    .map(|(k, c)| {
                        let x0 = start + k as f64 * width;
                        let color = if x0 + 0.5 * width < 1.0 { BELOW } else { ABOVE };
                        Rectangle::new(
                            [(x0, 0.0), (x0 + width, *c as f64)],
                            color.mix(0.6).filled(),
                        )
                    }),
            )
            .map_err(err(path))?;
        chart
            .draw_series(DashedLineSeries::new(
                [(1.0, 0.0), (1.0, top)],
                6,
                4,
                BLACK.stroke_width(2),
            ))
            .map_err(err(path))?;
        Ok(())
    }

    /// The legend's entries: the bars' colours, the line at 1, the probability of sliding, the
    /// number of routes and bars, and the percentiles of the factor of safety.
    fn entries(&self, summary: &Summary) -> Vec<Entry> {
        let mut entries = vec![
            // Under a record the static factor of safety does not decide whether it slides.
            Entry::new(
                Mark::Swatch(BELOW),
                if summary.shaken {
                    "factor of safety below 1"
                } else {
                    "factor of safety below 1: slides"
                },
            ),
            Entry::new(
                Mark::Swatch(ABOVE),
                if summary.shaken {
                    "1 or more (held without the record)"
                } else {
                    "1 or more: held"
                },
            ),
            Entry::new(Mark::Dashed(BLACK), "factor of safety 1"),
            Entry::new(Mark::None, sliding(summary)),
            Entry::new(
                Mark::None,
                format!(
                    "{} routes, {} bars of {}",
                    summary.routes,
                    self.counts.len(),
                    fixed(self.width, 4)
                ),
            ),
        ];
        if let Some(p) = summary.factor_of_safety {
            entries.push(Entry::new(
                Mark::None,
                format!(
                    "5 % {}, median {}, 95 % {}",
                    fixed(p.p5, 3),
                    fixed(p.p50, 3),
                    fixed(p.p95, 3)
                ),
            ));
        }
        entries
    }
}

/// The legend's notes of the factors of safety `fs` the histogram does not draw: how many are
/// +∞, −∞ or none, and what each means (no note for none of a kind).
fn not_drawn(fs: &[Option<f64>]) -> Vec<Entry> {
    let count = |f: &dyn Fn(&Option<f64>) -> bool| fs.iter().filter(|v| f(v)).count();
    [
        (
            count(&|v| *v == Some(f64::INFINITY)),
            "no multiple of the driving loads starts the block (factor of safety +∞)",
        ),
        (
            count(&|v| *v == Some(f64::NEG_INFINITY)),
            "the weight alone starts the block (−∞)",
        ),
        (count(&|v| v.is_none()), "the cone program failed (none)"),
    ]
    .into_iter()
    .filter(|(n, _)| *n > 0)
    .map(|(n, words)| Entry::new(Mark::None, format!("not drawn: {n} where {words}")))
    .collect()
}

/// The sensitivity tornado: for each uncertain value, Spearman's ρ with the factor of safety
/// and with the travel, the values ordered by their largest |ρ|.
pub fn tornado(path: &Path, summary: &Summary) -> Res<()> {
    let mut rows: Vec<_> = summary.rank_correlations.iter().collect();
    let size = |s: &&slideroute::probabilistic::Sensitivity| {
        s.with_factor_of_safety
            .unwrap_or(0.0)
            .abs()
            .max(s.with_travel.unwrap_or(0.0).abs())
    };
    rows.sort_by(|a, b| size(b).total_cmp(&size(a)));
    let n = rows.len().max(1);
    let title = format!(
        "{}: sensitivity, rank correlation of each uncertain value",
        summary.scene
    );
    let height = (160 + 90 * n as u32).clamp(320, 1400);
    let sheet = Sheet::new(path, (1200, height), &title)?;
    let mut chart = ChartBuilder::on(&sheet.chart)
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(10)
        .build_cartesian_2d(-1.0..1.0, n as f64..0.0)
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .disable_y_mesh()
        .disable_y_axis()
        .max_light_lines(1)
        .x_labels(11)
        .x_desc("Spearman's rank correlation ρ")
        .x_label_formatter(&|v| format!("{v:.1}"))
        .light_line_style(BLACK.mix(0.05))
        .draw()
        .map_err(err(path))?;
    chart
        .draw_series(LineSeries::new(
            [(0.0, 0.0), (0.0, n as f64)],
            BLACK.stroke_width(1),
        ))
        .map_err(err(path))?;
    for (k, s) in rows.iter().enumerate() {
        let y = k as f64;
        let name = ("sans-serif", 16)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Center));
        chart
            .draw_series(std::iter::once(Text::new(
                s.key.clone(),
                (0.0, y + 0.18),
                name,
            )))
            .map_err(err(path))?;
        for (rho, color, (y0, y1)) in [
            (s.with_factor_of_safety, ABOVE, (y + 0.33, y + 0.6)),
            (s.with_travel, TRAVEL, (y + 0.63, y + 0.9)),
        ] {
            let Some(rho) = rho else {
                let style = ("sans-serif", 13)
                    .into_font()
                    .color(&color)
                    .pos(Pos::new(HPos::Left, VPos::Center));
                chart
                    .draw_series(std::iter::once(Text::new(
                        "none (too few routes, or constant)",
                        (0.02, 0.5 * (y0 + y1)),
                        style,
                    )))
                    .map_err(err(path))?;
                continue;
            };
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(0.0, y0), (rho, y1)],
                    color.mix(0.7).filled(),
                )))
                .map_err(err(path))?;
            // Beyond the bar's end, or inside it (in white) where the end is near the edge.
            let inside = rho.abs() > 0.8;
            let (anchor, at) = match (rho >= 0.0, inside) {
                (true, false) => (HPos::Left, rho + 0.02),
                (true, true) => (HPos::Right, rho - 0.02),
                (false, false) => (HPos::Right, rho - 0.02),
                (false, true) => (HPos::Left, rho + 0.02),
            };
            let style = ("sans-serif", 13)
                .into_font()
                .color(if inside { &WHITE } else { &BLACK })
                .pos(Pos::new(anchor, VPos::Center));
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{rho:+.2}").replace('-', "−"),
                    (at, 0.5 * (y0 + y1)),
                    style,
                )))
                .map_err(err(path))?;
        }
    }
    let entries = [
        Entry::new(Mark::Swatch(ABOVE), "with the factor of safety"),
        Entry::new(Mark::Swatch(TRAVEL), "with the travel"),
        Entry::new(
            Mark::None,
            format!(
                "over the {} samples whose route ran; ranks, so any monotone effect counts fully; \
                 ordered by the larger |ρ|",
                summary.routes
            ),
        ),
    ];
    let y = sheet::heading(path, &sheet.panel, "Legend", 0)?;
    sheet::legend(path, &sheet.panel, &entries, y)?;
    sheet.root.present().map_err(err(path))
}

/// `route-fan.svg`, `factor-of-safety.svg` and `sensitivity.svg` in `dir`; `nominal` is the
/// route of the scene as written, drawn in black on the fan (none if it failed).
pub fn write_probabilistic_plots(
    dir: &Path,
    scene: &Scene,
    nominal: Option<&Route>,
    samples: &[Sample],
    summary: &Summary,
) -> Res<Vec<std::path::PathBuf>> {
    let fan = dir.join("route-fan.svg");
    route_fan(&fan, scene, nominal, samples, summary)?;
    let fs = dir.join("factor-of-safety.svg");
    factor_of_safety(&fs, samples, summary)?;
    let t = dir.join("sensitivity.svg");
    tornado(&t, summary)?;
    Ok(vec![fan, fs, t])
}

/// The probability of sliding as the legend says it: under a ground-motion record, that the
/// record displaces the block (its static factor of safety does not decide it).
fn sliding(summary: &Summary) -> String {
    if summary.shaken {
        format!(
            "probability the record displaces the block {}",
            summary.probability_of_sliding
        )
    } else {
        format!("probability of sliding {}", summary.probability_of_sliding)
    }
}
