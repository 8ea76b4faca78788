//! The pictures of `slideroute probabilistic`: the route fan (every sampled CM
//! path in plan over the foundation, beside the route of the scene as written), the histogram
//! of the factor of safety, and the sensitivity tornado (each input's rank correlation with the
//! factor of safety and with the travel).

use super::plan::{self, Fan, Track};
use super::sheet::{self, Area, Entry, Mark, Res, Sheet, err};
use super::thinned;
use crate::FactorOfSafety;
use crate::Outcome;
use crate::Route;
use crate::Scene;
use crate::numeric::fixed;
use crate::output::MAX_FAN_PATHS;
use crate::probabilistic::{Distribution, Sample, Summary};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

const BELOW: RGBColor = RGBColor(200, 30, 30);
const ABOVE: RGBColor = RGBColor(30, 90, 200);
const TRAVEL: RGBColor = RGBColor(230, 140, 0);

/// The route fan: the sampled CM paths under the route of the scene as written (`nominal`).
pub(super) fn route_fan(
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
                crate::probabilistic::Sampling::MonteCarlo => "Monte Carlo",
                crate::probabilistic::Sampling::LatinHypercube => "Latin hypercube",
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
            who: "the scene as written".into(),
            rows: &rows,
            color: RGBColor(0, 0, 0),
            base: r.base(),
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

/// The factors of safety of the samples whose route ran, each handed in order to the function
/// given (`None` where the cone program failed): held in no list, so that a picture of any
/// number of samples takes no memory for them.
pub type FactorsOfSafety<'a> = &'a dyn Fn(&mut dyn FnMut(Option<f64>)) -> Res<()>;

/// The finite factors of safety, each handed in order to the function given.
type Finite<'a> = &'a dyn Fn(&mut dyn FnMut(f64)) -> Res<()>;

/// The histogram of the factor of safety: bars below 1 red, at or above blue; infinite values
/// (no multiple of the loads starts the block, or the weight alone does) counted in the panel.
/// Two passes over the factors: their range and what is not drawn, then the bars.
pub fn factor_of_safety(path: &Path, fs: FactorsOfSafety, summary: &Summary) -> Res<()> {
    let mut not = NotDrawn::default();
    let (mut finite, mut lo, mut hi) = (0usize, f64::INFINITY, f64::NEG_INFINITY);
    fs(&mut |v| match v {
        Some(v) if v.is_finite() => {
            finite += 1;
            (lo, hi) = (lo.min(v), hi.max(v));
        }
        v => not.count(v),
    })?;
    let title = format!("{}: factor of safety of the samples", summary.scene);
    if finite == 0 {
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
    let histogram = Histogram::over(finite, (lo, hi), &|each| {
        fs(&mut |v| {
            if let Some(v) = v.filter(|v| v.is_finite()) {
                each(v)
            }
        })
    })?;
    let sheet = Sheet::new(path, (1200, 600), &title)?;
    histogram.draw(path, &sheet.chart)?;
    let mut entries = histogram.entries(summary);
    entries.extend(not.entries());
    let y = sheet::heading(path, &sheet.panel, "Legend", 0)?;
    sheet::legend(path, &sheet.panel, &entries, y)?;
    sheet.root.present().map_err(err(path))
}

/// The factor of safety of each sample whose route ran, handed to `each`: a number, ±∞, or
/// none where the cone program failed.
#[cfg(test)]
pub(super) fn factors_of_safety(samples: &[Sample], each: &mut dyn FnMut(Option<f64>)) {
    for s in samples {
        if let Outcome::Route(r) = &s.outcome {
            each(r.factor_of_safety_value());
        }
    }
}

/// The bars of the factor of safety's histogram: their edges placed so that 1 is always one of
/// them, so that every bar holds only samples below 1 (red: they slide) or only samples at 1 or
/// more (blue: held), and is coloured by them. The axis runs from `lo` to `hi`, half a bar
/// wider than the bars each side; the top of the count axis is `top`.
struct Histogram {
    lo: f64,
    hi: f64,
    width: f64,
    /// The left edge of the first bar.
    first: f64,
    counts: Vec<usize>,
    /// How many bars lie below 1 (the first ones).
    below: usize,
    top: f64,
}

/// One bar as drawn: its edges, its count and its colour.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Bar {
    x0: f64,
    x1: f64,
    count: usize,
    color: RGBColor,
}

impl Histogram {
    /// The histogram of the `finite` factors of safety (not empty).
    #[cfg(test)]
    fn of(finite: &[f64]) -> Histogram {
        let lo = finite.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let all = |each: &mut dyn FnMut(f64)| -> Res<()> {
            finite.iter().for_each(|&v| each(v));
            Ok(())
        };
        Histogram::over(finite.len(), (lo, hi), &all).expect("values in memory")
    }

    /// The histogram of `n` finite factors of safety, `n` at least one, the least and largest
    /// `(lo, hi)`, which `scan` hands over one by one: about √n bars, from 10 to 60, of one
    /// width over the values and 1, an edge at 1.
    fn over(n: usize, (lo, hi): (f64, f64), scan: Finite) -> Res<Histogram> {
        let (lo, hi) = sheet::ranges([lo, hi, 1.0].into_iter());
        let bins = (n as f64).sqrt().clamp(10.0, 60.0);
        let width = (hi - lo) / bins;
        // Whole bars from 1 down past `lo` and up past `hi`: 1 is an edge.
        let below = ((1.0 - lo) / width).ceil().max(0.0) as usize;
        let above = ((hi - 1.0) / width).ceil().max(1.0) as usize;
        let first = 1.0 - below as f64 * width;
        let mut counts = vec![0usize; below + above];
        scan(&mut |v| {
            // Counted from 1, so that a value of exactly 1 starts the first bar held.
            let k = below as f64 + ((v - 1.0) / width).floor();
            counts[(k.max(0.0) as usize).min(below + above - 1)] += 1;
        })?;
        let top = counts.iter().copied().max().unwrap_or(1) as f64 * 1.08;
        Ok(Histogram {
            lo: first - 0.5 * width,
            hi: first + (below + above) as f64 * width + 0.5 * width,
            width,
            first,
            counts,
            below,
            top,
        })
    }

    /// The bars that hold samples, each coloured by the side of 1 its samples are on.
    fn bars(&self) -> Vec<Bar> {
        self.counts
            .iter()
            .enumerate()
            .filter(|(_, c)| **c > 0)
            .map(|(k, &count)| Bar {
                x0: self.edge(k),
                x1: self.edge(k + 1),
                count,
                color: if k < self.below { BELOW } else { ABOVE },
            })
            .collect()
    }

    /// The left edge of bar `k` (1 exactly for the first bar held).
    fn edge(&self, k: usize) -> f64 {
        if k == self.below {
            1.0
        } else {
            self.first + k as f64 * self.width
        }
    }

    /// Its axes on `area`, its bars (below 1 red, at or above blue) and a dashed line at 1.
    fn draw(&self, path: &Path, area: &Area) -> Res<()> {
        let (lo, hi, top) = (self.lo, self.hi, self.top);
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(lo..hi, 0.0..top)
            .map_err(err(path))?;
        let fx = sheet::ticks(lo, hi);
        chart
            .configure_mesh()
            .label_style(sheet::label_font())
            .axis_desc_style(sheet::label_font())
            .max_light_lines(1)
            .x_desc("factor of safety at the start")
            .y_desc("samples")
            .x_label_formatter(&fx)
            // Counts are whole: no label at a tick between two (`2` twice, at 2 and 2.5).
            .y_label_formatter(&|v| {
                if (v - v.round()).abs() < 1e-9 {
                    format!("{v:.0}")
                } else {
                    String::new()
                }
            })
            .light_line_style(BLACK.mix(0.05))
            .draw()
            .map_err(err(path))?;
        chart
            .draw_series(self.bars().into_iter().map(|b| {
                Rectangle::new(
                    [(b.x0, 0.0), (b.x1, b.count as f64)],
                    b.color.mix(0.6).filled(),
                )
            }))
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
                    "≥ 1: held without the record"
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
                    fs_percentile(p.p5),
                    fs_percentile(p.p50),
                    fs_percentile(p.p95)
                ),
            ));
        }
        entries
    }
}

/// A percentile of the factor of safety for the legend: the number, or where more than 5 % of
/// the samples are unbounded or cannot be held (their value as a number is ±∞), the word
/// `samples.csv` and `sweep.csv` write for them; never `inf`.
fn fs_percentile(v: f64) -> String {
    if v == f64::INFINITY {
        FactorOfSafety::Unbounded.cell()
    } else if v == f64::NEG_INFINITY {
        FactorOfSafety::NotHoldable.cell()
    } else if v.is_finite() {
        fixed(v, 3).to_string()
    } else {
        "—".into()
    }
}

/// How many of the factors of safety the histogram does not draw are +∞, −∞ or none, and the
/// legend's notes of them, each saying what it means (no note for none of a kind).
#[derive(Debug, Default)]
struct NotDrawn {
    unbounded: usize,
    not_holdable: usize,
    none: usize,
}

impl NotDrawn {
    /// Counts a factor of safety that is not drawn (not a finite number).
    fn count(&mut self, v: Option<f64>) {
        match v {
            Some(f64::INFINITY) => self.unbounded += 1,
            Some(f64::NEG_INFINITY) => self.not_holdable += 1,
            None => self.none += 1,
            Some(_) => {}
        }
    }

    fn entries(&self) -> Vec<Entry> {
        [
            (
                self.unbounded,
                "no multiple of the driving loads starts the block (factor of safety +∞)",
            ),
            (self.not_holdable, "the weight alone starts the block (−∞)"),
            (self.none, "the cone program failed (none)"),
        ]
        .into_iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, words)| Entry::new(Mark::None, format!("not drawn: {n} where {words}")))
        .collect()
    }
}

/// The sensitivity tornado: for each uncertain value, Spearman's ρ with the factor of safety
/// and with the travel, the values ordered by their largest |ρ|.
pub fn tornado(path: &Path, summary: &Summary) -> Res<()> {
    let mut rows: Vec<_> = summary.rank_correlations.iter().collect();
    let size = |s: &&crate::probabilistic::Sensitivity| {
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
        .x_label_area_size(50)
        .y_label_area_size(10)
        .build_cartesian_2d(-1.0..1.0, n as f64..0.0)
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .label_style(sheet::label_font())
        .axis_desc_style(sheet::label_font())
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
        let name = ("sans-serif", 20)
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
        for (rho, color, ys) in [
            (s.with_factor_of_safety, ABOVE, (y + 0.33, y + 0.6)),
            (s.with_travel, TRAVEL, (y + 0.63, y + 0.9)),
        ] {
            tornado_bar(&mut chart, path, rho, color, ys)?;
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

/// One bar of the tornado: a correlation `rho` drawn from zero between `y0` and `y1` in
/// `color`, with its value; one that is not a number says so in words.
fn tornado_bar(
    chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    path: &Path,
    rho: Option<f64>,
    color: RGBColor,
    (y0, y1): (f64, f64),
) -> Res<()> {
    // A correlation that is not a number (none is expected) is drawn as none.
    let rho = rho.filter(|r| r.is_finite());
    let Some(rho) = rho else {
        let style = ("sans-serif", sheet::FONT)
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
        return Ok(());
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
    let style = ("sans-serif", sheet::FONT)
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
    Ok(())
}

/// `route-fan.svg`, `factor-of-safety.svg` and `sensitivity.svg` in `dir`; `nominal` is the
/// route of the scene as written, drawn in black on the fan (none if it failed); `kept` the
/// samples whose paths the fan draws (the first [`MAX_FAN_PATHS`] routes will do), `fs` every
/// route's factor of safety.
pub fn write_probabilistic_plots(
    dir: &Path,
    scene: &Scene,
    nominal: Option<&Route>,
    kept: &[Sample],
    fs: FactorsOfSafety,
    summary: &Summary,
) -> Res<Vec<std::path::PathBuf>> {
    let fan = dir.join("route-fan.svg");
    route_fan(&fan, scene, nominal, kept, summary)?;
    let path = dir.join("factor-of-safety.svg");
    factor_of_safety(&path, fs, summary)?;
    let t = dir.join("sensitivity.svg");
    tornado(&t, summary)?;
    Ok(vec![fan, path, t])
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Factors of safety spread from 0.5 to 1.15 and packed about 1 (0.988 to 1.017, as the
    /// paper-like uncertain scene's were), from a fixed sequence.
    fn factors() -> Vec<f64> {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut v: Vec<f64> = (0..189).map(|_| 0.5 + 0.65 * next()).collect();
        v.extend([
            0.988, 0.99, 0.992, 0.995, 0.997, 0.998, 0.999, 1.0, 1.004, 1.01, 1.017,
        ]);
        v
    }

    /// The value of attribute `name` of an SVG tag.
    fn attr(tag: &str, name: &str) -> Option<f64> {
        let key = format!(" {name}=\"");
        let start = tag.find(&key)? + key.len();
        tag[start..].split('"').next()?.parse().ok()
    }

    #[test]
    fn percentiles_of_the_factor_of_safety_past_the_finite_are_words_not_infinities() {
        // Over 5 % of the samples unbounded: the 95th percentile is +∞ as a number, and the
        // legend wrote `95 % inf`.
        assert_eq!(fs_percentile(f64::INFINITY), "unbounded");
        assert_eq!(fs_percentile(f64::NEG_INFINITY), "not-holdable");
        assert_eq!(fs_percentile(1.23456), "1.235");
        assert_eq!(fs_percentile(f64::NAN), "—");
    }

    #[test]
    fn histogram_bars_are_coloured_by_the_samples_they_hold() {
        for values in [
            factors(),
            vec![0.988, 0.99, 0.999, 1.0, 1.01, 1.017, 0.7, 1.3],
        ] {
            let h = Histogram::of(&values);
            let bars = h.bars();
            // Every sample in one bar, and every bar's samples on its colour's side of 1.
            let mut counted = 0;
            for b in &bars {
                let inside: Vec<f64> = values
                    .iter()
                    .copied()
                    .filter(|&v| v >= b.x0 && v < b.x1)
                    .collect();
                assert_eq!(inside.len(), b.count, "{b:?}: {inside:?}");
                let below = b.color == BELOW;
                assert!(
                    inside.iter().all(|&v| (v < 1.0) == below),
                    "{b:?}: {inside:?}"
                );
                counted += b.count;
            }
            assert_eq!(counted, values.len());
            // Drawn: every red bar ends at or left of the dashed line at 1, every blue bar
            // starts at or right of it.
            let path = std::env::temp_dir().join(format!(
                "slideroute-fs-bars-{}-{}.svg",
                values.len(),
                std::process::id()
            ));
            let sheet = Sheet::new(&path, (1200, 600), "factor of safety").unwrap();
            h.draw(&path, &sheet.chart).unwrap();
            sheet.root.present().unwrap();
            drop(sheet);
            let svg = std::fs::read_to_string(&path).unwrap();
            let _ = std::fs::remove_file(&path);
            let line = svg
                .split("<polyline")
                .skip(1)
                .filter(|p| p.contains("stroke-width=\"2\"") && p.contains("#000000"))
                .find_map(|p| {
                    let pts = p.split("points=\"").nth(1)?.split('"').next()?;
                    let xs: Vec<f64> = pts
                        .split_whitespace()
                        .filter_map(|q| q.split(',').next()?.parse().ok())
                        .collect();
                    (xs.len() >= 2 && xs.iter().all(|x| (x - xs[0]).abs() < 0.5)).then(|| xs[0])
                })
                .expect("no dashed line at 1");
            let hex = |c: RGBColor| format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
            let (red, blue) = (hex(BELOW), hex(ABOVE));
            let mut drawn = 0;
            for rect in svg.split("<rect").skip(1) {
                let tag = rect.split("/>").next().unwrap_or("");
                let (Some(x), Some(w)) = (attr(tag, "x"), attr(tag, "width")) else {
                    continue;
                };
                if tag.contains(&red) {
                    assert!(
                        x + w <= line + 1.0,
                        "a red bar {x}…{} past 1 at {line}",
                        x + w
                    );
                    drawn += 1;
                } else if tag.contains(&blue) {
                    assert!(
                        x >= line - 1.0,
                        "a blue bar {x}…{} before 1 at {line}",
                        x + w
                    );
                    drawn += 1;
                }
            }
            assert_eq!(drawn, bars.len());
        }
    }
}
