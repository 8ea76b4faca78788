//! The sweep picture: the CM's travel (under a record, the permanent displacement) and the
//! factor of safety against the first varied key, one line per combination of the other keys
//! (markers alone across a key of words, such as records), the travel's broken where the route
//! ends otherwise from one value to the next; a sweep where nothing moved says so over an axis
//! from 0. Legends are in numeric order
//! with units; past a handful of groups the colour follows the second key on a scale with a
//! colour bar; a block that did not slide, a route that ended at once and one that slid are
//! marked apart. However large the sweep, the picture stays under 2 MB: past [`MAX_LINES`]
//! lines it draws an evenly spaced choice of them, and along each line at most [`MAX_ALONG`]
//! values of the first key (fewer when there are many lines, [`MAX_MARKED`] in all), evenly
//! spaced, the ends kept and, where there is room, both sides of every change of how the route
//! ended; a caption across the picture's foot says what was drawn of how many combinations,
//! and `sweep.csv` keeps every one. The lines drawn are known from the varied keys before any
//! route runs, and the values drawn along them chosen once every combination has come from a
//! few numbers kept of each, past a few MB in a temporary file ([`Drawn`]), so that a sweep of
//! any size keeps only a few MB for its picture.

use super::COLORS;
use super::sheet::{self, Area, Entry, Mark, Res, Sheet, err};
use crate::FactorOfSafety;
use crate::output::sweep_row::SweepRow;
use crate::sweep::Vary;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

const SIZE: (u32, u32) = (1200, 820);
/// The most words of a numbered axis the panel lists.
const LISTED: usize = 20;
/// The width of the charts' x axes (px): the sheet's chart area less the y labels.
const AXIS_WIDTH: u32 = 800;
/// The sweep's reason for a block that did not slide (the route's own word).
const DID_NOT_SLIDE: &str = crate::Reason::DoesNotSlide.as_str();
/// The most lines (combinations of the keys after the first) a picture draws: past this, an
/// evenly spaced choice of them in the keys' order, the first and last kept. Thirty lines
/// already fill the colour scale.
const MAX_LINES: usize = 30;
/// The most values of the first key a line marks, however few the lines: 400 over an axis
/// 800 pixels wide, each marker already touching the next.
const MAX_ALONG: usize = 400;
/// The most combinations a picture marks in all, each on both charts (some 320 bytes a
/// combination at most, its two markers and its pieces of line): 1.2 MB at most (1.17 MB
/// measured with every marker a cross over a triangle), so that the picture stays under 2 MB
/// whatever the sweep's size. Along each line, `MAX_MARKED` over the number of lines.
const MAX_MARKED: usize = 3600;
/// The most tick marks of an axis of words (numbered past the room for their names).
const MAX_WORD_TICKS: usize = 40;

/// How a combination came out, for its marker.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Outcome {
    Slid,
    DidNotSlide,
    EndedAtOnce,
    /// Under a record, a route that ended before the record did and the block came to rest
    /// (a contact left its plane, lifted off, …): its displacement is only what it had moved.
    Cut,
    /// No route (an invalid scene): not drawn, counted.
    NoRoute,
}

/// How row `r` came out; `shaken`: under a ground-motion record.
fn outcome(r: &SweepRow, shaken: bool) -> Outcome {
    let rested = [
        crate::Reason::Stopped.as_str(),
        crate::Reason::TimeLimit.as_str(),
    ];
    if r.travel_m.is_none() {
        Outcome::NoRoute
    } else if r.reason == DID_NOT_SLIDE {
        Outcome::DidNotSlide
    } else if r.t_end_s == Some(0.0) {
        Outcome::EndedAtOnce
    } else if shaken && !rested.contains(&r.reason.as_str()) {
        Outcome::Cut
    } else {
        Outcome::Slid
    }
}

/// The combinations grouped by the values of every key but the first, groups in numeric
/// order of those values (−1, −0.5, 0; 6×10⁶ before 10⁷), each group's rows by the first key.
/// One sort, then runs of equal keys: linear but for the sort, whatever the number of groups.
fn groups(rows: &[SweepRow]) -> Vec<(Vec<f64>, Vec<&SweepRow>)> {
    fn others(r: &SweepRow) -> &[f64] {
        r.values.get(1..).unwrap_or(&[])
    }
    let order = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or_else(|| a.len().cmp(&b.len()))
    };
    let mut sorted: Vec<&SweepRow> = rows.iter().collect();
    sorted.sort_by(|a, b| order(others(a), others(b)).then(first_of(a).total_cmp(&first_of(b))));
    sorted
        .chunk_by(|a, b| order(others(a), others(b)).is_eq())
        .map(|g| (others(g[0]).to_vec(), g.to_vec()))
        .collect()
}

/// The first varied key's value of row `r` (0 where it has none, which no sweep row lacks).
fn first_of(r: &SweepRow) -> f64 {
    r.values.first().copied().unwrap_or(0.0)
}

/// Whether two combinations ended alike: the same reason and the same outcome (a line joins
/// only neighbours that did).
fn ended_alike(a: &SweepRow, b: &SweepRow, shaken: bool) -> bool {
    a.reason == b.reason && outcome(a, shaken) == outcome(b, shaken)
}

/// What the picture takes of a sweep, known from its varied keys before any route runs: the
/// lines it draws (the groups of the other keys' values that [`groups`] would make of every
/// combination, evenly spaced past [`MAX_LINES`]), and the counts of every combination, summed as
/// they come ([`Drawn::add`]). Of each combination on a line drawn it keeps what the picture
/// shows, in a store that spills past a few MB to an unnamed temporary file, and how it ended,
/// four bytes a combination: the values drawn along each line are chosen from those once every
/// combination has come ([`Drawn::choose`]), so that a sweep of any size keeps only a few MB.
pub struct Drawn {
    /// How many lines the whole sweep has.
    lines: usize,
    /// The other keys' values of each line drawn, in the order [`groups`] gives them.
    chosen: Vec<Vec<f64>>,
    combinations: usize,
    permanent: bool,
    /// How many combinations came out each way, as [`outcome`] says unshaken and shaken.
    counts: [[usize; 5]; 2],
    /// The first key's values in their order (`total_cmp`): a combination's place along its
    /// line is its value's, equal values in the order they came.
    sorted_first: Vec<f64>,
    /// For each line drawn, how the combination at each place along it ended (0: none came),
    /// [`Drawn::mark`].
    marks: Vec<Vec<u32>>,
    /// How many times each line drawn repeats (its key's values repeated among those varied).
    repeats: Vec<usize>,
    /// The reasons seen, a mark's number for each.
    reasons: Vec<String>,
    /// What the picture shows of each combination on a line drawn, [`STORED`] numbers a row.
    store: crate::probabilistic::Columns,
}

/// What the picture draws of the lines, chosen once every combination has come
/// ([`Drawn::choose`]): the rows drawn (in the order they came), the most values a line marks,
/// whether every line kept both sides of each change of how the route ended, and the first
/// key's values on the lines drawn (the lowest and highest, and how many distinct).
struct Chosen {
    rows: Vec<SweepRow>,
    along: usize,
    changes_kept: bool,
    first_span: Option<(f64, f64)>,
    first_distinct: usize,
}

/// The numbers [`Drawn`] keeps of a combination on a line drawn: the line, the place along it,
/// the first key's value, the reason's number, which of the next five are there (a bit each;
/// the factor of safety's kind in bits 4 and 5), the end time, the travel, the permanent
/// displacement along X and Z, and a finite factor of safety.
const STORED: usize = 10;
/// The rows of the store held in memory (80 bytes each): 2.6 MB.
const STORED_IN_MEMORY: usize = 1 << 15;

impl Drawn {
    /// The lines of `varies`: the groups of every key but the first are the combinations of
    /// their distinct values, in the order of each key's values (the second key's first), so
    /// the `j`-th group is `j` written in their mixed radix. A temporary file, if the sweep
    /// needs one, is made in `spill_in`.
    pub fn new(varies: &[Vary], spill_in: Option<std::path::PathBuf>) -> Drawn {
        let distinct: Vec<Vec<f64>> = varies
            .iter()
            .skip(1)
            .map(|v| {
                let mut d = v.values.clone();
                d.sort_by(f64::total_cmp);
                d.dedup_by(|a, b| a.total_cmp(b).is_eq());
                d
            })
            .collect();
        let lines = distinct
            .iter()
            .fold(1usize, |n, d| n.saturating_mul(d.len()));
        let chosen: Vec<Vec<f64>> = spread(lines, MAX_LINES)
            .into_iter()
            .map(|j| {
                let mut rest = j;
                let mut key = vec![0.0; distinct.len()];
                for (k, d) in distinct.iter().enumerate().rev() {
                    key[k] = d[rest % d.len().max(1)];
                    rest /= d.len().max(1);
                }
                key
            })
            .collect();
        let mut sorted_first = varies.first().map_or_else(Vec::new, |v| v.values.clone());
        sorted_first.sort_by(f64::total_cmp);
        // A line whose key repeats among the values varied has each value of the first key as
        // many times over.
        let repeats: Vec<usize> = chosen
            .iter()
            .map(|key| {
                key.iter()
                    .zip(varies.iter().skip(1))
                    .map(|(x, v)| v.values.iter().filter(|y| y.total_cmp(x).is_eq()).count())
                    .product()
            })
            .collect();
        Drawn {
            lines,
            marks: repeats
                .iter()
                .map(|&m| vec![0; sorted_first.len() * m])
                .collect(),
            repeats,
            chosen,
            combinations: 0,
            permanent: false,
            counts: [[0; 5]; 2],
            sorted_first,
            reasons: Vec::new(),
            store: crate::probabilistic::Columns::new(STORED, spill_in)
                .with_in_memory_rows(STORED_IN_MEMORY),
        }
    }

    /// Counts the combination `r` and, if it lies on a line drawn, keeps what the picture shows
    /// of it (an error only from the temporary file).
    pub fn add(&mut self, r: &SweepRow) -> std::io::Result<()> {
        self.combinations += 1;
        self.permanent |= r.permanent_x_m.is_some();
        for (shaken, counts) in self.counts.iter_mut().enumerate() {
            counts[outcome(r, shaken == 1) as usize] += 1;
        }
        let others = r.values.get(1..).unwrap_or(&[]);
        let Some(line) = self.chosen.iter().position(|key| {
            key.len() <= others.len() && key.iter().zip(others).all(|(a, b)| a.total_cmp(b).is_eq())
        }) else {
            return Ok(());
        };
        // Its place: the first among the places of its value that no combination took yet
        // (each value of the first key `repeats` places along the line). They are taken in
        // order, so those taken are the first ones: found by halving, however many repeat.
        let first = first_of(r);
        let m = self.repeats[line];
        let from = self
            .sorted_first
            .partition_point(|x| x.total_cmp(&first).is_lt());
        let to = self
            .sorted_first
            .partition_point(|x| x.total_cmp(&first).is_le());
        let places = &self.marks[line][from * m..to * m];
        let taken = places.partition_point(|&x| x != 0);
        let Some(place) = (taken < places.len()).then_some(from * m + taken) else {
            // A value the first key does not have, or more of it than it has: not drawn.
            return Ok(());
        };
        let reason = match self.reasons.iter().position(|x| *x == r.reason) {
            Some(k) => k,
            None => {
                self.reasons.push(r.reason.clone());
                self.reasons.len() - 1
            }
        };
        self.marks[line][place] = Drawn::mark(reason, r);
        let (fos_kind, fos) = match r.factor_of_safety {
            None => (0, 0.0),
            Some(FactorOfSafety::Finite { value }) => (1, value),
            Some(FactorOfSafety::Unbounded) => (2, 0.0),
            Some(FactorOfSafety::NotHoldable) => (3, 0.0),
        };
        let optional = [r.t_end_s, r.travel_m, r.permanent_x_m, r.permanent_z_m];
        let present = optional
            .iter()
            .enumerate()
            .fold(fos_kind << 4, |bits, (k, v)| {
                bits | (u32::from(v.is_some()) << k)
            });
        let [t, travel, px, pz] = optional.map(|v| v.unwrap_or(0.0));
        self.store.push(&[
            line as f64,
            place as f64,
            first,
            reason as f64,
            f64::from(present),
            t,
            travel,
            px,
            pz,
            fos,
        ])
    }

    /// How a combination that ended for the reason numbered `reason` came out: the reason and
    /// its [`outcome`], as one number above 0. Two combinations ended alike ([`ended_alike`])
    /// when their marks are equal, under a record or not: of two with the same reason, a record
    /// only turns both slid into both cut.
    fn mark(reason: usize, r: &SweepRow) -> u32 {
        let reason = u32::try_from(reason).unwrap_or(u32::MAX / 8 - 1);
        1 + reason * 5 + outcome(r, false) as u32
    }

    /// The combinations the picture draws, once every one has come, in the order they came: on
    /// each line drawn at most `along` of them ([`thin`]: evenly spaced, the ends and both sides
    /// of each change of how the route ended kept); `along` shared out among the lines that have
    /// any. Their details are not kept (sweep.csv has them).
    fn choose(&self) -> std::io::Result<Chosen> {
        let lines_with_rows = self
            .marks
            .iter()
            .filter(|m| m.iter().any(|&x| x != 0))
            .count();
        let along = (MAX_MARKED / lines_with_rows.max(1)).clamp(2, MAX_ALONG);
        let mut changes_kept = true;
        let mut keep: Vec<Vec<bool>> = Vec::with_capacity(self.marks.len());
        for marks in &self.marks {
            // The places a combination came to, one line at a time (4 bytes each).
            let places: Vec<u32> = (0..marks.len() as u32)
                .filter(|&p| marks[p as usize] != 0)
                .collect();
            let at = |i: usize| marks[places[i] as usize];
            let (kept, all_changes) = thin(places.len(), along, |i| at(i - 1) != at(i));
            changes_kept &= all_changes;
            let mut k = vec![false; marks.len()];
            for i in kept {
                k[places[i] as usize] = true;
            }
            keep.push(k);
        }
        let on_any: Vec<f64> = (0..self.sorted_first.len())
            .filter(|&p| {
                let on =
                    |(m, r): (&Vec<u32>, &usize)| m[p * r..(p + 1) * r].iter().any(|&x| x != 0);
                self.marks.iter().zip(&self.repeats).any(on)
            })
            .map(|p| self.sorted_first[p])
            .collect();
        let first_span = on_any.first().zip(on_any.last()).map(|(a, b)| (*a, *b));
        let first_distinct = on_any.chunk_by(|a, b| a.total_cmp(b).is_eq()).count();
        let mut rows = Vec::new();
        let (chosen, reasons) = (&self.chosen, &self.reasons);
        self.store.scan(|s| {
            let (line, place) = (s[0] as usize, s[1] as usize);
            if !keep[line][place] {
                return;
            }
            let present = s[4] as u32;
            let has = |k: usize| (present >> k) & 1 == 1;
            let at = |k: usize| has(k).then_some(s[5 + k]);
            let mut values = vec![s[2]];
            values.extend_from_slice(&chosen[line]);
            rows.push(SweepRow {
                values,
                reason: reasons[s[3] as usize].clone(),
                t_end_s: at(0),
                travel_m: at(1),
                final_theta_deg: None,
                max_alpha_deg: None,
                max_beta_deg: None,
                permanent_x_m: at(2),
                permanent_z_m: at(3),
                factor_of_safety: match present >> 4 {
                    1 => Some(FactorOfSafety::Finite { value: s[9] }),
                    2 => Some(FactorOfSafety::Unbounded),
                    3 => Some(FactorOfSafety::NotHoldable),
                    _ => None,
                },
                detail: String::new(),
            });
        })?;
        Ok(Chosen {
            rows,
            along,
            changes_kept,
            first_span,
            first_distinct,
        })
    }

    /// How many combinations came out as `o`.
    fn count(&self, o: Outcome) -> usize {
        self.counts[usize::from(self.permanent)][o as usize]
    }
}

/// `m` of the indices `0..n`, evenly spaced, the first and the last among them (every index
/// when `n <= m`).
fn spread(n: usize, m: usize) -> Vec<usize> {
    if n <= m {
        return (0..n).collect();
    }
    if m <= 1 {
        return vec![0];
    }
    (0..m)
        .map(|k| (k * (n - 1) + (m - 1) / 2) / (m - 1))
        .collect()
}

/// Which of a line's `n` combinations (in the first key's order) to draw, at most `along`:
/// every one when they are few; else evenly spaced, the first and last kept and, where there is
/// room for them (half of `along`), both neighbours at every change of how the route ended
/// (`differs(i)`: the `i`-th ended otherwise than the one before), so that the line breaks where
/// the full sweep's does. The places in order, with whether every such change was kept.
fn thin(n: usize, along: usize, differs: impl Fn(usize) -> bool) -> (Vec<usize>, bool) {
    if n <= along {
        return ((0..n).collect(), true);
    }
    let changes: Vec<usize> = (1..n)
        .filter(|&i| differs(i))
        .flat_map(|i| [i - 1, i])
        .collect();
    let room = changes.len() <= along / 2;
    let mut keep = if room {
        let mut keep = spread(n, along - changes.len());
        keep.extend(changes);
        keep
    } else {
        spread(n, along)
    };
    keep.sort_unstable();
    keep.dedup();
    (keep, room)
}

/// [`thin`] of a line's rows.
#[cfg(test)]
fn thin_line<'r>(
    members: &[&'r SweepRow],
    along: usize,
    shaken: bool,
) -> (Vec<&'r SweepRow>, bool) {
    let differs = |i: usize| !ended_alike(members[i - 1], members[i], shaken);
    let (keep, room) = thin(members.len(), along, differs);
    (keep.into_iter().map(|i| members[i]).collect(), room)
}

/// A varied value for people: the word, or the number short with the key's unit.
fn value_text(v: &Vary, x: f64) -> String {
    match &v.words {
        Some(_) => format!("{} = {}", v.key, word_label(&v.cell(x))),
        None => sheet::key_value(&v.key, &sheet::short(x)),
    }
}

/// The x-axis description: the key and its unit.
fn axis_name(v: &Vary) -> String {
    match sheet::unit_of(&v.key) {
        "" => v.key.clone(),
        u => format!("{} ({u})", v.key),
    }
}

/// The colour of value `x` of a key spanning `lo..=hi` on the scale.
fn scale_color(x: f64, lo: f64, hi: f64) -> RGBColor {
    let h = if hi > lo { (x - lo) / (hi - lo) } else { 0.5 };
    // Viridis, stopped short of its palest yellow, which is hard to see on white.
    ViridisRGB.get_color((0.9 * h.clamp(0.0, 1.0)) as f32)
}

/// Travel and factor of safety against the first varied key, of every row of the sweep held.
#[cfg(test)]
pub(super) fn sweep(path: &Path, varies: &[Vary], rows: &[SweepRow]) -> Res<()> {
    let mut drawn = Drawn::new(varies, None);
    for r in rows {
        drawn.add(r).map_err(err(path))?;
    }
    sweep_drawn(path, varies, &drawn)
}

/// Travel and factor of safety against the first varied key, of the combinations `drawn` kept
/// ([`Drawn::add`], every one counted), those drawn chosen now ([`Drawn::choose`]).
pub fn sweep_drawn(path: &Path, varies: &[Vary], drawn: &Drawn) -> Res<()> {
    let Some(first) = varies.first() else {
        return sheet::message(
            path,
            (900, 300),
            "sweep",
            &["No key was varied, so there is nothing to plot.".into()],
        );
    };
    let chosen = drawn.choose().map_err(err(path))?;
    let plot = SweepPlot::new(path, varies, &chosen, drawn);
    let title = format!(
        "sweep: {} and factor of safety against {}",
        if plot.shaken {
            "permanent displacement"
        } else {
            "travel of the centre of mass"
        },
        first.key
    );
    // A sweep too large to draw whole says across the picture's foot what it drew of it.
    let sheet = Sheet::captioned(path, SIZE, &title, plot.drawn_words().as_deref())?;
    let (_, ch) = sheet.chart.dim_in_pixel();
    let (top, bottom) = sheet.chart.split_vertically((f64::from(ch) * 0.6) as u32);
    plot.draw_travel(&top)?;
    plot.draw_factors_of_safety(&bottom)?;
    let mut y = plot.draw_group_key(&sheet.panel)?;
    y = plot.draw_markers(&sheet.panel, y)?;
    y = plot.draw_counts(&sheet.panel, y)?;
    plot.draw_numbered(&sheet.panel, y)?;
    sheet.root.present().map_err(err(path))
}

/// The tick labels of the x axis over `(x0, x1)`: numbers, or the words of a word key at 0,
/// 1, … (none between; `numbered`, their numbers from 1, which the panel lists).
fn x_labels(first: &Vary, (x0, x1): (f64, f64), numbered: bool) -> impl Fn(&f64) -> String {
    let words = first.words.clone();
    let numbers = sheet::ticks(x0, x1);
    move |v: &f64| match &words {
        Some(w) => {
            let k = v.round();
            if (v - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < w.len() {
                if numbered {
                    format!("{}", k as usize + 1)
                } else {
                    word_label(&w[k as usize])
                }
            } else {
                String::new()
            }
        }
        None => numbers(v),
    }
}

/// A word as an axis shows it: a file's name without its folder (a sweep over a folder of
/// records names each by its path).
fn word_label(word: &str) -> String {
    Path::new(word)
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or(word)
        .to_string()
}

/// Whether the words of a word key, side by side under an axis `width` pixels wide, would run
/// into each other (at about 7 pixels a character): then the axis numbers them and the panel
/// lists them.
fn words_crowd(words: &[String], width: u32) -> bool {
    let room = f64::from(width) / words.len().max(1) as f64;
    words
        .iter()
        .any(|w| 7.0 * word_label(w).chars().count() as f64 + 10.0 > room)
}

/// A chart of the sweep: the first varied key across, travel or factor of safety up.
type SweepChart<'a, 'p> =
    ChartContext<'a, SVGBackend<'p>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// What the drawing steps of a sweep picture share: the file (for its errors), the varied keys
/// (at least one), the rows, the groups drawn (one line each, thinned past [`MAX_LINES`] and
/// [`MAX_ALONG`]), the range of the second key's values (for a colour scale) and the range of
/// the x axis.
struct SweepPlot<'a> {
    path: &'a Path,
    varies: &'a [Vary],
    /// The lines and counts of the whole sweep.
    totals: &'a Drawn,
    /// The groups drawn, each with the rows drawn of it.
    groups: Vec<(Vec<f64>, Vec<&'a SweepRow>)>,
    /// The rows drawn: those of `groups`.
    drawn: Vec<&'a SweepRow>,
    /// How many groups (lines) the sweep has, drawn or not.
    lines: usize,
    /// The most rows a line marks (every one, when its rows are fewer).
    along: usize,
    /// Whether each line drawn keeps both neighbours at every change of how the route ended
    /// (a line with too many changes keeps only its evenly spaced rows).
    changes_kept: bool,
    /// How many distinct values of the first key the lines drawn have.
    first_values: usize,
    /// The second key's lowest and highest values (0, 0 without one).
    second_range: (f64, f64),
    /// The x axis's range: the first key's values, or its words at 0, 1, ….
    x_range: (f64, f64),
    /// Under a ground-motion record (some row has a permanent displacement): the upper chart
    /// is the permanent displacement, not the travel.
    shaken: bool,
    /// The first key's words are too long to stand side by side under the axis: it numbers
    /// them from 1, and the panel lists them.
    numbered: bool,
}

impl<'a> SweepPlot<'a> {
    /// The picture of the rows `chosen`, `varies` not empty.
    fn new(path: &'a Path, varies: &'a [Vary], chosen: &'a Chosen, totals: &'a Drawn) -> Self {
        let second_range = varies.get(1).map_or((0.0, 0.0), |v| {
            v.values
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |a, &x| {
                    (a.0.min(x), a.1.max(x))
                })
        });
        // The x axis spans the first key's values on every line drawn, not only those marked.
        let x_range = match &varies[0].words {
            Some(w) => (-0.5, w.len() as f64 - 0.5),
            None => sheet::ranges(chosen.first_span.into_iter().flat_map(|(a, b)| [a, b])),
        };
        let shaken = totals.permanent;
        // The rows are those drawn: their groups are the lines.
        let groups = groups(&chosen.rows);
        let drawn = groups.iter().flat_map(|g| g.1.iter().copied()).collect();
        SweepPlot {
            path,
            varies,
            totals,
            groups,
            drawn,
            lines: totals.lines,
            along: chosen.along,
            changes_kept: chosen.changes_kept,
            first_values: chosen.first_distinct,
            second_range,
            x_range,
            shaken,
            numbered: varies[0]
                .words
                .as_ref()
                .is_some_and(|w| words_crowd(w, AXIS_WIDTH)),
        }
    }

    /// Whether the first key is a word key (records, files): its values are categories, so
    /// the markers stand alone, no line joining one to the next.
    fn categorical(&self) -> bool {
        self.first().words.is_some()
    }

    /// What the upper chart shows of row `r`: its permanent displacement's length under a
    /// record, else its travel (m).
    fn upper_value(&self, r: &SweepRow) -> Option<f64> {
        if self.shaken {
            r.permanent_x_m
                .zip(r.permanent_z_m)
                .map(|(x, z)| x.hypot(z))
        } else {
            r.travel_m
        }
    }

    /// A group's rows (in the first key's order) cut where the route's end changes between
    /// neighbours: its outcome (slid, did not slide, ended at once, …) or its reason.
    fn regimes<'r>(&self, members: &[&'r SweepRow]) -> Vec<Vec<&'r SweepRow>> {
        let mut runs: Vec<Vec<&SweepRow>> = Vec::new();
        for &r in members {
            let same = runs
                .last()
                .and_then(|run| run.last())
                .is_some_and(|q| ended_alike(q, r, self.shaken));
            match runs.last_mut() {
                Some(run) if same => run.push(r),
                _ => runs.push(vec![r]),
            }
        }
        runs
    }

    /// The first varied key, across both charts.
    fn first(&self) -> &Vary {
        &self.varies[0]
    }

    /// Whether the groups are few enough for a colour each, named in a legend (else the
    /// colour follows the second key on a scale).
    fn few(&self) -> bool {
        self.lines <= COLORS.len()
    }

    /// Whether some combinations are not drawn (the sweep is larger than a picture holds).
    fn thinned(&self) -> bool {
        self.drawn.len() < self.totals.combinations
    }

    /// The colour of the `k`-th group, whose other keys' values are `key`.
    fn color_of(&self, k: usize, key: &[f64]) -> RGBColor {
        if self.groups.len() == 1 {
            COLORS[1]
        } else if self.few() {
            COLORS[k % COLORS.len()]
        } else {
            let (lo, hi) = self.second_range;
            scale_color(key.first().copied().unwrap_or(0.0), lo, hi)
        }
    }

    /// The finite factors of safety of the rows drawn.
    fn finite_factors(&self) -> Vec<f64> {
        self.drawn
            .iter()
            .filter_map(|r| r.factor_of_safety.and_then(|f| f.value()))
            .collect()
    }

    /// A chart on `area` over `y_range`, its axes drawn: the first key across (numbers, or
    /// the words of a word key at 0, 1, …), `y_desc` up.
    fn axes<'c, 'p>(
        &self,
        area: &'c Area<'p>,
        y_range: (f64, f64),
        y_desc: &str,
    ) -> Res<SweepChart<'c, 'p>> {
        let first = self.first();
        let (x0, x1) = self.x_range;
        let (y0, y1) = y_range;
        let x_label = x_labels(first, self.x_range, self.numbered);
        let x_count = first
            .words
            .as_ref()
            .map_or(10, |w| w.len().min(MAX_WORD_TICKS));
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(50)
            .y_label_area_size(85)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err(self.path))?;
        let fy = sheet::ticks(y0, y1);
        chart
            .configure_mesh()
            .label_style(sheet::label_font())
            .axis_desc_style(sheet::label_font())
            .max_light_lines(1)
            .x_desc(axis_name(first))
            .y_desc(y_desc)
            .x_labels(x_count)
            .x_label_formatter(&x_label)
            .y_label_formatter(&fy)
            .draw()
            .map_err(err(self.path))?;
        Ok(chart)
    }

    /// The upper chart: the CM's travel (under a record, the permanent displacement) against
    /// the first key, a line for each group (none across words, broken where the route's end
    /// changes) and each combination's outcome marked (slid, did not slide, ended at once).
    /// Where nothing moved the axis runs from 0 to 1 m and says so.
    fn draw_travel(&self, area: &Area) -> Res<()> {
        let values: Vec<f64> = self
            .drawn
            .iter()
            .filter_map(|r| self.upper_value(r))
            .collect();
        // Nothing moved: the axis from 0 (a travel is never negative) to 1 m, said in words.
        let still = values.iter().all(|&v| v == 0.0);
        let y_range = if still {
            (0.0, 1.0)
        } else {
            sheet::ranges(values.iter().copied().chain([0.0]))
        };
        let y_desc = if self.shaken {
            "permanent displacement (m)"
        } else {
            "travel of the CM (m)"
        };
        let mut chart = self.axes(area, y_range, y_desc)?;
        if still && !values.is_empty() {
            let words = if self.shaken {
                "no permanent displacement: the record moved no combination's block"
            } else {
                "nothing slid: every combination's travel is 0"
            };
            let (x0, x1) = self.x_range;
            chart
                .draw_series(std::iter::once(Text::new(
                    words,
                    (0.5 * (x0 + x1), 0.55),
                    ("sans-serif", sheet::FONT)
                        .into_font()
                        .color(&BLACK)
                        .pos(Pos::new(HPos::Center, VPos::Center)),
                )))
                .map_err(err(self.path))?;
        }
        for (k, (key, members)) in self.groups.iter().enumerate() {
            let color = self.color_of(k, key);
            if !self.categorical() {
                // A line only between neighbours that ended alike: across a change of regime
                // (slid at one μ, held at the next) a line would suggest travels between.
                for run in self.regimes(members) {
                    let pts: Vec<(f64, f64)> = run
                        .iter()
                        .filter_map(|r| self.upper_value(r).map(|t| (first_of(r), t)))
                        .collect();
                    if pts.len() > 1 {
                        chart
                            .draw_series(LineSeries::new(pts, color.mix(0.8).stroke_width(2)))
                            .map_err(err(self.path))?;
                    }
                }
            }
            for r in members {
                let Some(t) = self.upper_value(r) else {
                    continue;
                };
                let at = (first_of(r), t);
                let mark = match outcome(r, self.shaken) {
                    Outcome::Slid => Mark::Dot(color),
                    Outcome::Cut => Mark::Ring(color),
                    Outcome::DidNotSlide => Mark::Square(color),
                    Outcome::EndedAtOnce => Mark::Cross(color),
                    Outcome::NoRoute => continue,
                };
                draw_at(self.path, &chart, at, mark)?;
            }
        }
        Ok(())
    }

    /// The lower chart: the factor of safety against the first key, dashed at 1, a line for
    /// each group through its finite values, and an unbounded one or one the weight alone
    /// overcomes marked at the top or the bottom.
    fn draw_factors_of_safety(&self, area: &Area) -> Res<()> {
        let (f0, f1) = sheet::ranges(self.finite_factors().into_iter().chain([1.0]));
        let mut chart = self.axes(area, (f0, f1), "factor of safety")?;
        let (x0, x1) = self.x_range;
        chart
            .draw_series(DashedLineSeries::new(
                [(x0, 1.0), (x1, 1.0)],
                8,
                5,
                BLACK.mix(0.7).stroke_width(1),
            ))
            .map_err(err(self.path))?;
        for (k, (key, members)) in self.groups.iter().enumerate() {
            let color = self.color_of(k, key);
            let pts: Vec<(f64, f64)> = members
                .iter()
                .filter_map(|r| {
                    r.factor_of_safety
                        .and_then(|f| f.value())
                        .map(|f| (first_of(r), f))
                })
                .collect();
            if !self.categorical() {
                chart
                    .draw_series(LineSeries::new(pts, color.mix(0.8).stroke_width(2)))
                    .map_err(err(self.path))?;
            }
            for r in members {
                let (at, mark) = match r.factor_of_safety {
                    Some(FactorOfSafety::Finite { value }) => {
                        ((first_of(r), value), Mark::Dot(color))
                    }
                    Some(FactorOfSafety::Unbounded) => {
                        ((first_of(r), f1), Mark::Triangle(color, true))
                    }
                    Some(FactorOfSafety::NotHoldable) => {
                        ((first_of(r), f0), Mark::Triangle(color, false))
                    }
                    None => continue,
                };
                draw_at(self.path, &chart, at, mark)?;
            }
        }
        Ok(())
    }

    /// At the top of the panel, what tells the groups apart: a legend line for each of a few
    /// groups, or the colour bar of the second key (and which other keys share its colours);
    /// nothing for a single group. Returns the y below it.
    fn draw_group_key(&self, panel: &Area) -> Res<i32> {
        let (path, varies) = (self.path, self.varies);
        let mut y = 0;
        if self.groups.len() > 1 && self.few() {
            let heading = if self.categorical() {
                "Colours"
            } else {
                "Lines"
            };
            y = sheet::heading(path, panel, heading, y)?;
            let entries: Vec<Entry> = self
                .groups
                .iter()
                .enumerate()
                .map(|(k, (key, _))| {
                    let text = varies[1..]
                        .iter()
                        .zip(key)
                        .map(|(v, &x)| value_text(v, x))
                        .collect::<Vec<_>>()
                        .join(", ");
                    Entry::new(Mark::Line(self.color_of(k, key)), text)
                })
                .collect();
            y = sheet::legend(path, panel, &entries, y)?;
        } else if let Some(v) = varies.get(1).filter(|_| !self.few()) {
            y = sheet::heading(path, panel, "Colour", y)?;
            y = colour_bar(path, panel, v, self.second_range, y)?;
            if varies.len() > 2 {
                let others: Vec<&str> = varies[2..].iter().map(|v| v.key.as_str()).collect();
                y = sheet::legend(
                    path,
                    panel,
                    &[Entry::new(
                        Mark::None,
                        format!(
                            "one line for each value of {} and of {}{}",
                            v.key,
                            others.join(", "),
                            if self.lines > self.groups.len() {
                                " (some left out: see the foot)"
                            } else {
                                ""
                            }
                        ),
                    )],
                    y,
                )?;
            }
        }
        Ok(y)
    }

    /// The markers this sweep uses, explained from `y` in the panel (in the group's colour
    /// for a single group, else in black); returns the y below them.
    fn draw_markers(&self, panel: &Area, y: i32) -> Res<i32> {
        let rows = &self.drawn;
        let marker = if self.groups.len() == 1 {
            COLORS[1]
        } else {
            BLACK
        };
        let y = sheet::heading(self.path, panel, "Markers", y + 6)?;
        let has = |o: Outcome| rows.iter().any(|r| outcome(r, self.shaken) == o);
        let has_fs = |f: FactorOfSafety| rows.iter().any(|r| r.factor_of_safety == Some(f));
        let marks = [
            (
                has(Outcome::Slid) || !self.finite_factors().is_empty(),
                Entry::new(
                    Mark::Dot(marker),
                    if self.shaken {
                        "the block slid (its permanent displacement), or a factor of safety"
                    } else {
                        "the block slid (its travel), or a factor of safety"
                    },
                ),
            ),
            (
                has(Outcome::DidNotSlide),
                Entry::new(
                    Mark::Square(marker),
                    "did not slide: travel 0, friction holds it",
                ),
            ),
            (
                has(Outcome::EndedAtOnce),
                Entry::new(
                    Mark::Cross(marker),
                    "ended at once (t = 0) for another reason: see sweep.csv",
                ),
            ),
            (
                has(Outcome::Cut),
                Entry::new(
                    Mark::Ring(marker),
                    "the route ended before the record did (a contact left its plane, …): \
                     its displacement so far, see sweep.csv",
                ),
            ),
            (
                has_fs(FactorOfSafety::Unbounded),
                Entry::new(
                    Mark::Triangle(marker, true),
                    "factor of safety unbounded (no multiple of the water load starts it)",
                ),
            ),
            (
                has_fs(FactorOfSafety::NotHoldable),
                Entry::new(
                    Mark::Triangle(marker, false),
                    "no factor of safety: the weight alone slides it",
                ),
            ),
            (
                true,
                Entry::new(
                    Mark::Dashed(BLACK),
                    "factor of safety 1: the loads just start the block",
                ),
            ),
        ];
        let marks: Vec<Entry> = marks.into_iter().filter(|m| m.0).map(|m| m.1).collect();
        sheet::legend(self.path, panel, &marks, y)
    }

    /// The first key's words as the axis numbers them, under its name from `y` in the panel
    /// (nothing where the axis shows the words themselves); returns the y below. Past
    /// `LISTED` words, the rest are counted.
    fn draw_numbered(&self, panel: &Area, y: i32) -> Res<i32> {
        let Some(words) = self.first().words.as_ref().filter(|_| self.numbered) else {
            return Ok(y);
        };
        let y = sheet::heading(self.path, panel, &self.first().key, y + 6)?;
        let mut lines: Vec<Entry> = words
            .iter()
            .take(LISTED)
            .enumerate()
            .map(|(k, w)| Entry::new(Mark::None, format!("{}: {}", k + 1, word_label(w))))
            .collect();
        if words.len() > LISTED {
            lines.push(Entry::new(
                Mark::None,
                format!("… and {} more (see sweep.csv)", words.len() - LISTED),
            ));
        }
        sheet::legend(self.path, panel, &lines, y)
    }

    /// How many combinations slid, did not slide, ended at once or had no route, under the
    /// heading "Sweep" from `y` in the panel; returns the y below.
    fn draw_counts(&self, panel: &Area, y: i32) -> Res<i32> {
        let all = self.totals.combinations;
        let count = |o: Outcome| self.totals.count(o);
        let plural = if all == 1 { "" } else { "s" };
        let mut counts = format!(
            "{} combination{plural}: {} slid, {} did not slide, {} ended at once",
            all,
            count(Outcome::Slid),
            count(Outcome::DidNotSlide),
            count(Outcome::EndedAtOnce)
        );
        if count(Outcome::Cut) > 0 {
            counts.push_str(&format!(
                ", {} ended before the record did",
                count(Outcome::Cut)
            ));
        }
        if count(Outcome::NoRoute) > 0 {
            counts.push_str(&format!(
                ", {} had no route (not drawn; see sweep.csv)",
                count(Outcome::NoRoute)
            ));
        }
        let y = sheet::heading(self.path, panel, "Sweep", y + 6)?;
        sheet::legend(self.path, panel, &[Entry::new(Mark::None, counts)], y)
    }

    /// What was drawn of a sweep larger than a picture holds, in words (none when every
    /// combination is): how many combinations of how many, how many lines, how many values of
    /// the first key along each, how they were chosen, and that `sweep.csv` has them all.
    fn drawn_words(&self) -> Option<String> {
        if !self.thinned() {
            return None;
        }
        let first = &self.first().key;
        let values = self.first_values;
        let mut words = format!(
            "Drawn: {} of the {} combinations, to keep the picture small",
            self.drawn.len(),
            self.totals.combinations
        );
        if self.lines > self.groups.len() {
            let keys: Vec<&str> = self.varies[1..].iter().map(|v| v.key.as_str()).collect();
            let what = match keys.as_slice() {
                [one] => format!("values of {one}"),
                [rest @ .., last] => format!("combinations of {} and {last}", rest.join(", ")),
                [] => String::new(),
            };
            words.push_str(&format!(
                "; {} of the {} lines ({what}), evenly spaced, the first and last kept",
                self.groups.len(),
                self.lines,
            ));
        }
        if values > self.along {
            words.push_str(&format!(
                "; along each line at most {} of the {values} values of {first}, evenly \
                 spaced, the ends kept{}",
                self.along,
                if self.changes_kept {
                    " and both sides of each change of how the route ended"
                } else {
                    " (the route's end changes too often along a line to keep both sides of \
                     each change)"
                }
            ));
        }
        words.push_str(". sweep.csv has every combination.");
        Some(words)
    }
}

/// Draws `mark` at data point `at` of `chart`.
fn draw_at(path: &Path, chart: &SweepChart<'_, '_>, at: (f64, f64), mark: Mark) -> Res<()> {
    let (x, y) = chart.backend_coord(&at);
    let area = chart.plotting_area().strip_coord_spec();
    let (ox, oy) = area.get_base_pixel();
    sheet::draw_mark(&area, mark, (x - ox, y - oy)).map_err(err(path))
}

/// A vertical colour bar of the second key's values from `y` in the panel, its values marked
/// (the words, for a word key); returns the y below it.
fn colour_bar(path: &Path, panel: &Area, v: &Vary, (lo, hi): (f64, f64), y: i32) -> Res<i32> {
    let (bar_h, bar_w, x) = (200, 22, 4);
    let steps = 100;
    for k in 0..steps {
        let h = f64::from(k) / f64::from(steps);
        let color = scale_color(lo + h * (hi - lo), lo, hi);
        let y1 = y + bar_h - (bar_h * k) / steps;
        let y0 = y + bar_h - (bar_h * (k + 1)) / steps;
        panel
            .draw(&Rectangle::new([(x, y0), (x + bar_w, y1)], color.filled()))
            .map_err(err(path))?;
    }
    panel
        .draw(&Rectangle::new([(x, y), (x + bar_w, y + bar_h)], BLACK))
        .map_err(err(path))?;
    // Ticks: every value when they are few, else the ends and three between.
    let mut values = v.values.clone();
    values.sort_by(f64::total_cmp);
    values.dedup();
    let shown: Vec<f64> = if values.len() <= 9 {
        values
    } else {
        (0..5)
            .map(|k| lo + (hi - lo) * f64::from(k) / 4.0)
            .collect()
    };
    let label = |x: f64| match &v.words {
        Some(_) => v.cell(x),
        None => sheet::short(x),
    };
    for value in shown {
        let h = if hi > lo {
            (value - lo) / (hi - lo)
        } else {
            0.5
        };
        let yy = y + bar_h - (f64::from(bar_h) * h).round() as i32;
        panel
            .draw(&PathElement::new(
                vec![(x + bar_w, yy), (x + bar_w + 5, yy)],
                BLACK,
            ))
            .map_err(err(path))?;
        panel
            .draw(&Text::new(
                label(value),
                (x + bar_w + 9, yy),
                ("sans-serif", sheet::FONT)
                    .into_font()
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center)),
            ))
            .map_err(err(path))?;
    }
    let name = axis_name(v);
    sheet::legend(
        path,
        panel,
        &[Entry::new(Mark::None, format!("colour: {name}"))],
        y + bar_h + 8,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(values: Vec<f64>) -> SweepRow {
        SweepRow {
            values,
            reason: "stopped".into(),
            t_end_s: Some(1.0),
            travel_m: Some(1.0),
            final_theta_deg: Some(0.0),
            max_alpha_deg: Some(0.0),
            max_beta_deg: Some(0.0),
            permanent_x_m: None,
            permanent_z_m: None,
            factor_of_safety: None,
            detail: String::new(),
        }
    }

    #[test]
    fn groups_sort_numerically_not_as_text() {
        let rows: Vec<SweepRow> = [0.0, -0.5, -1.0, 1e7, 6e6]
            .iter()
            .map(|&e| row(vec![0.1, e]))
            .collect();
        let keys: Vec<f64> = groups(&rows).iter().map(|g| g.0[0]).collect();
        assert_eq!(keys, vec![-1.0, -0.5, 0.0, 6e6, 1e7]);
    }

    #[test]
    fn outcomes_tell_did_not_slide_from_ended_at_once() {
        let mut held = row(vec![0.1]);
        held.reason = DID_NOT_SLIDE.into();
        held.t_end_s = Some(0.0);
        held.travel_m = Some(0.0);
        let mut at_once = row(vec![0.1]);
        at_once.reason = "the contact forces are not determined".into();
        at_once.t_end_s = Some(0.0);
        at_once.travel_m = Some(0.0);
        let mut invalid = row(vec![0.1]);
        invalid.travel_m = None;
        assert_eq!(outcome(&held, false), Outcome::DidNotSlide);
        assert_eq!(outcome(&at_once, false), Outcome::EndedAtOnce);
        assert_eq!(outcome(&invalid, false), Outcome::NoRoute);
        assert_eq!(outcome(&row(vec![0.1]), false), Outcome::Slid);
    }

    fn vary(key: &str, values: &[f64]) -> Vary {
        Vary {
            key: key.into(),
            values: values.to_vec(),
            words: None,
        }
    }

    /// The texts of an SVG, in order, with their y.
    fn texts(svg: &str) -> Vec<(f64, String)> {
        svg.split("<text")
            .skip(1)
            .filter_map(|s| {
                let (tag, rest) = s.split_once('>')?;
                let y = tag.split(" y=\"").nth(1)?.split('"').next()?.parse().ok()?;
                Some((y, rest.split("</text>").next()?.trim().to_string()))
            })
            .collect()
    }

    fn draw(name: &str, varies: &[Vary], rows: &[SweepRow]) -> String {
        let path = std::env::temp_dir().join(format!(
            "slideroute-sweep-{name}-{}.svg",
            std::process::id()
        ));
        sweep(&path, varies, rows).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        svg
    }

    fn grid(first: &[f64], second: &[f64]) -> Vec<SweepRow> {
        second
            .iter()
            .flat_map(|&e| first.iter().map(move |&m| row(vec![m, e])))
            .collect()
    }

    #[test]
    fn sweep_legend_is_in_numeric_order_with_units() {
        let varies = [
            vary("friction.mu_k", &[0.2, 0.4]),
            vary("loads.eccentricity_m", &[0.0, -0.5, -1.0]),
        ];
        let svg = draw("order", &varies, &grid(&[0.2, 0.4], &[0.0, -0.5, -1.0]));
        let mut legend: Vec<(f64, String)> = texts(&svg)
            .into_iter()
            .filter(|t| t.1.starts_with("loads.eccentricity_m = "))
            .collect();
        legend.sort_by(|a, b| a.0.total_cmp(&b.0));
        let order: Vec<&str> = legend.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(
            order,
            [
                "loads.eccentricity_m = -1 m",
                "loads.eccentricity_m = -0.5 m",
                "loads.eccentricity_m = 0 m"
            ]
        );
    }

    #[test]
    fn sweep_past_six_groups_colours_by_a_scale_with_a_colour_bar() {
        let second: Vec<f64> = (0..8).map(f64::from).collect();
        let varies = [
            vary("friction.mu_k", &[0.2, 0.4]),
            vary("loads.eccentricity_m", &second),
        ];
        let svg = draw("bar", &varies, &grid(&[0.2, 0.4], &second));
        let t = texts(&svg);
        assert!(t.iter().any(|t| t.1 == "Colour"));
        assert!(t.iter().any(|t| t.1 == "colour: loads.eccentricity_m (m)"));
        // Every value of the key marked on the bar; no legend line per group.
        for v in ["0", "3", "7"] {
            assert!(t.iter().any(|t| t.1 == v), "{v} not on the bar");
        }
        assert!(!t.iter().any(|t| t.1 == "Lines"));
        // Eight groups, eight colours of the scale on their lines.
        let lines: std::collections::BTreeSet<&str> = svg
            .split("<polyline")
            .skip(1)
            .filter_map(|p| p.split("stroke=\"").nth(1)?.split('"').next())
            .collect();
        assert!(lines.len() >= 8, "{lines:?}");
    }

    #[test]
    fn under_a_record_a_route_that_ended_before_the_record_is_marked_apart() {
        // "a contact left its plane" at 2.15 s under a 40 s record: its displacement is only
        // what it had moved, not a permanent one; without a record the same end is a route's.
        let mut cut = row(vec![0.1]);
        cut.reason = crate::Reason::ContactLeftPlane.as_str().into();
        cut.permanent_x_m = Some(4e-4);
        cut.permanent_z_m = Some(5e-4);
        let mut stopped = row(vec![0.2]);
        stopped.permanent_x_m = Some(0.1);
        stopped.permanent_z_m = Some(0.0);
        assert_eq!(outcome(&cut, true), Outcome::Cut);
        assert_eq!(outcome(&cut, false), Outcome::Slid);
        assert_eq!(outcome(&stopped, true), Outcome::Slid);
        let mut limit = stopped.clone();
        limit.reason = crate::Reason::TimeLimit.as_str().into();
        assert_eq!(outcome(&limit, true), Outcome::Slid);
        let svg = draw(
            "cut",
            &[vary("friction.mu_k", &[0.1, 0.2])],
            &[cut, stopped],
        );
        let t: Vec<String> = texts(&svg).into_iter().map(|t| t.1).collect();
        let words = t.join(" ");
        assert!(words.contains("ended before the record did"), "{words}");
        assert!(words.contains("1 slid"), "{words}");
        // The cut route's marker is a ring (an unfilled circle), the stopped one's a dot.
        let rings = svg
            .split("<circle")
            .skip(1)
            .filter(|c| {
                c.split("/>")
                    .next()
                    .is_some_and(|c| c.contains("fill=\"none\""))
            })
            .count();
        assert_eq!(rings, 2, "one on the chart, one in the legend");
    }

    #[test]
    fn a_sweep_over_records_marks_each_records_permanent_displacement_unjoined_and_numbers_long_names()
     {
        let names = [
            "Coalinga_1983_PVB-045.csv",
            "Kobe_1995_TAK-090.csv",
            "Loma_Prieta_1989_HSP-000.csv",
            "Nisqually_2001_UNR-058.csv",
            "Northridge_1994_PAC-175.csv",
        ];
        let first = Vary {
            key: "seismic.record_x".into(),
            values: (0..5).map(f64::from).collect(),
            words: Some(names.iter().map(|n| format!("records/{n}")).collect()),
        };
        // Travel 9 m each; permanent displacement (0.3 k, 0.4 k) m, k = 0…4: 0.5 k m long.
        let rows: Vec<SweepRow> = (0..5)
            .map(|k| SweepRow {
                travel_m: Some(9.0),
                permanent_x_m: Some(0.3 * f64::from(k)),
                permanent_z_m: Some(0.4 * f64::from(k)),
                ..row(vec![f64::from(k)])
            })
            .collect();
        let svg = draw("records", &[first], &rows);
        let t: Vec<String> = texts(&svg).into_iter().map(|t| t.1).collect();
        assert!(t.iter().any(|t| t == "permanent displacement (m)"), "{t:?}");
        assert!(!t.iter().any(|t| t.contains("travel of the CM")));
        // The upper axis reaches 2 m (the longest, 0.5 × 4), not the travel's 9 m.
        let ticks: Vec<f64> = t.iter().filter_map(|t| t.parse().ok()).collect();
        assert!(
            ticks.contains(&2.0) && !ticks.iter().any(|&v| v >= 9.0),
            "{ticks:?}"
        );
        // The names do not fit side by side: the axis numbers them, the panel lists them by
        // file name.
        for k in 1..=5 {
            assert!(t.iter().any(|t| *t == k.to_string()), "tick {k}: {t:?}");
        }
        assert!(t.iter().any(|t| t == "2: Kobe_1995_TAK-090.csv"), "{t:?}");
        assert!(!t.iter().any(|t| t.contains("records/")), "{t:?}");
        // Records are categories: no line joins one record's marker to the next.
        let coloured = svg
            .split("<polyline")
            .skip(1)
            .filter(|p| !p.contains("stroke=\"#000000\""))
            .count();
        assert_eq!(coloured, 0);
    }

    #[test]
    fn sweep_marks_did_not_slide_and_ended_at_once_apart_and_shows_the_factor_of_safety() {
        let mut rows = grid(&[0.2, 0.4, 0.6], &[0.0]);
        rows[0].factor_of_safety = Some(FactorOfSafety::Finite { value: 0.7 });
        rows[1].reason = DID_NOT_SLIDE.into();
        rows[1].t_end_s = Some(0.0);
        rows[1].travel_m = Some(0.0);
        rows[1].factor_of_safety = Some(FactorOfSafety::Finite { value: 1.2 });
        rows[2].reason = "the contact forces are not determined".into();
        rows[2].t_end_s = Some(0.0);
        rows[2].travel_m = Some(0.0);
        rows[2].factor_of_safety = Some(FactorOfSafety::Unbounded);
        let varies = [vary("friction.mu_k", &[0.2, 0.4, 0.6])];
        let svg = draw("marks", &varies, &rows);
        let t: Vec<String> = texts(&svg).into_iter().map(|t| t.1).collect();
        let words = t.join(" ");
        for want in [
            "did not slide: travel 0, friction holds it",
            "ended at once (t = 0) for another reason: see sweep.csv",
            "3 combinations: 1 slid, 1 did not slide, 1 ended at once",
        ] {
            assert!(words.contains(want), "{want:?} in {words}");
        }
        assert!(
            t.iter().any(|s| s == "factor of safety"),
            "no axis of the factor of safety"
        );
        // The square of "did not slide" and the cross of "ended at once" are drawn on the
        // chart, not only in the legend (one each there, one each on the chart).
        let squares = svg.matches("<rect").count();
        assert!(squares >= 2, "{squares} rects");
        // The unbounded factor of safety: a triangle, on the chart and in the legend.
        assert!(svg.matches("<polygon").count() >= 2);
        assert!(words.contains("factor of safety unbounded"));
    }

    #[test]
    fn a_sweep_where_no_combination_ran_still_draws_and_says_so() {
        let mut rows = grid(&[0.2, 0.4], &[0.0, 1.0]);
        for r in &mut rows {
            r.reason = "invalid scene".into();
            r.travel_m = None;
            r.t_end_s = None;
        }
        let varies = [
            vary("friction.mu_k", &[0.2, 0.4]),
            vary("loads.eccentricity_m", &[0.0, 1.0]),
        ];
        let svg = draw("none", &varies, &rows);
        assert!(svg.trim_end().ends_with("</svg>") && !svg.contains("NaN"));
        let words: String = texts(&svg).into_iter().map(|t| t.1 + " ").collect();
        assert!(words.contains("4 had no route"), "{words}");
    }

    /// The coloured polylines of an SVG with two points or more, as lists of points.
    fn coloured_lines(svg: &str) -> Vec<Vec<(f64, f64)>> {
        svg.split("<polyline")
            .skip(1)
            .filter_map(|p| p.split("/>").next())
            .filter(|p| !p.contains("stroke=\"#000000\""))
            .filter_map(|p| {
                let pts = p.split("points=\"").nth(1)?.split('"').next()?;
                let pts: Vec<(f64, f64)> = pts
                    .split_whitespace()
                    .filter_map(|q| {
                        let (x, y) = q.split_once(',')?;
                        Some((x.parse().ok()?, y.parse().ok()?))
                    })
                    .collect();
                (pts.len() > 1).then_some(pts)
            })
            .collect()
    }

    #[test]
    fn sweep_lines_do_not_join_across_a_change_of_how_the_route_ended() {
        // 12.9 m of travel up to μ = 0.45, where contact 0 reaches an inclined plane; from 0.50
        // the block does not slide. No line may join 12.9 m to 0 as if travels lay between.
        let mu = [0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6];
        let rows: Vec<SweepRow> = mu
            .iter()
            .map(|&m| {
                let mut r = row(vec![m]);
                if m < 0.47 {
                    r.reason = "contact 0 reached an inclined plane".into();
                    r.travel_m = Some(12.9);
                } else {
                    r.reason = DID_NOT_SLIDE.into();
                    r.t_end_s = Some(0.0);
                    r.travel_m = Some(0.0);
                }
                r
            })
            .collect();
        let svg = draw("regimes", &[vary("friction.mu_k", &mu)], &rows);
        // No factor of safety: every coloured line is the travel's, and each joins only
        // neighbours that ended alike, so each is level.
        let lines = coloured_lines(&svg);
        assert_eq!(lines.len(), 2, "{lines:?}");
        for line in &lines {
            assert!(
                line.iter().all(|p| (p.1 - line[0].1).abs() < 0.5),
                "a line across a change of end: {line:?}"
            );
        }
        // The end's reason alone also breaks the line, between two routes that both slid.
        let mut two = rows.clone();
        for r in &mut two[4..] {
            r.reason = "stopped".into();
            r.t_end_s = Some(3.0);
            r.travel_m = Some(4.0);
        }
        let svg = draw("reasons", &[vary("friction.mu_k", &mu)], &two);
        assert_eq!(coloured_lines(&svg).len(), 2);
    }

    /// Row `k` of a large synthetic sweep over `values`: the travel falls with the first
    /// value to none (did not slide) past 0.48 + 0.01 × the second; every 97th ended at once
    /// with an unbounded factor of safety, every 89th cannot be held (markers of every kind,
    /// and changes of how the route ended all along the lines).
    fn synthetic(k: usize, values: Vec<f64>) -> SweepRow {
        let (mu, e) = (values[0], values.get(1).copied().unwrap_or(1.0));
        let travel = (10.0 * (0.48 + 0.01 * e - mu)).max(0.0);
        let mut r = SweepRow {
            travel_m: Some(travel),
            factor_of_safety: Some(FactorOfSafety::Finite {
                value: mu / 0.45 - 0.01 * e,
            }),
            ..row(values)
        };
        if travel == 0.0 {
            r.reason = DID_NOT_SLIDE.into();
            r.t_end_s = Some(0.0);
        }
        if k.is_multiple_of(97) {
            r.reason = "the contact forces are not determined".into();
            r.t_end_s = Some(0.0);
            r.travel_m = Some(0.0);
            r.factor_of_safety = Some(FactorOfSafety::Unbounded);
        } else if k.is_multiple_of(89) {
            r.factor_of_safety = Some(FactorOfSafety::NotHoldable);
        }
        r
    }

    /// `n` values evenly spaced from `a` to `b`.
    fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
        (0..n)
            .map(|k| a + (b - a) * k as f64 / (n - 1).max(1) as f64)
            .collect()
    }

    #[test]
    fn a_sweep_of_any_size_draws_a_picture_under_2_mb_that_says_what_it_left_out() {
        // 300 × 300 combinations drew an 18 MB sweep.svg; one key of 90 000 values and three
        // keys of 100 × 30 × 30 grow alike. Every picture under 2 MB, whole, and saying in its
        // panel how many of the 90 000 it drew.
        let mu = linspace(0.3, 0.6, 300);
        let e = linspace(0.5, 1.5, 300);
        let two: Vec<SweepRow> = grid(&mu, &e)
            .into_iter()
            .enumerate()
            .map(|(k, r)| synthetic(k, r.values))
            .collect();
        let long = linspace(0.3, 0.6, 90_000);
        let one: Vec<SweepRow> = long
            .iter()
            .enumerate()
            .map(|(k, &m)| synthetic(k, vec![m]))
            .collect();
        let (mu3, e3, f3) = (
            linspace(0.3, 0.6, 100),
            linspace(0.5, 1.5, 30),
            linspace(6e6, 1e7, 30),
        );
        let three: Vec<SweepRow> = f3
            .iter()
            .flat_map(|&f| e3.iter().map(move |&e| (e, f)))
            .flat_map(|(e, f)| mu3.iter().map(move |&m| vec![m, e, f]))
            .enumerate()
            .map(|(k, v)| synthetic(k, v))
            .collect();
        // The largest markers everywhere: every combination a cross (ended at once) over a
        // triangle (unbounded) or a dot (finite), every other one a change of reason.
        let crosses: Vec<SweepRow> = grid(&mu, &e)
            .into_iter()
            .enumerate()
            .map(|(k, r)| SweepRow {
                reason: format!("reason {}", k % 2),
                t_end_s: Some(0.0),
                travel_m: Some(0.0),
                factor_of_safety: Some(if k.is_multiple_of(2) {
                    FactorOfSafety::Unbounded
                } else {
                    FactorOfSafety::Finite {
                        value: 0.1 + k as f64 * 1e-5,
                    }
                }),
                ..r
            })
            .collect();
        let cases = [
            (
                "crosses",
                vec![vary("friction.mu_k", &mu), vary("loads.eccentricity_m", &e)],
                crosses,
            ),
            (
                "two",
                vec![vary("friction.mu_k", &mu), vary("loads.eccentricity_m", &e)],
                two,
            ),
            ("one", vec![vary("friction.mu_k", &long)], one),
            (
                "three",
                vec![
                    vary("friction.mu_k", &mu3),
                    vary("loads.eccentricity_m", &e3),
                    vary("loads.hydraulic_force_n", &f3),
                ],
                three,
            ),
        ];
        for (name, varies, rows) in cases {
            assert_eq!(rows.len(), 90_000);
            let svg = draw(&format!("large-{name}"), &varies, &rows);
            assert!(svg.len() < 2_000_000, "{name}: {} bytes", svg.len());
            assert!(svg.trim_end().ends_with("</svg>"), "{name}: cut");
            assert!(!svg.contains("NaN") && !svg.contains("inf"), "{name}");
            let words: String = texts(&svg).into_iter().map(|t| t.1 + " ").collect();
            assert!(words.contains("90000 combinations:"), "{name}: {words}");
            assert!(
                words.contains(" of the 90000 combinations"),
                "{name}: {words}"
            );
            assert!(
                words.contains("sweep.csv has every combination"),
                "{name}: {words}"
            );
        }
    }

    #[test]
    fn a_thinned_line_keeps_its_ends_and_where_the_route_ended_otherwise() {
        assert_eq!(spread(5, 10), vec![0, 1, 2, 3, 4]);
        assert_eq!(spread(10, 4), vec![0, 3, 6, 9]);
        assert_eq!(spread(1000, 1), vec![0]);
        let s = spread(90_000, 400);
        assert_eq!((s.len(), s[0], s[399]), (400, 0, 89_999));
        assert!(s.windows(2).all(|w| w[0] < w[1]));
        // Slid up to 0.4870, did not slide from 0.4871: both kept, and the line breaks there.
        let mu = linspace(0.3, 0.6, 3001);
        let rows: Vec<SweepRow> = mu
            .iter()
            .map(|&m| {
                let mut r = row(vec![m]);
                if m > 0.48705 {
                    r.reason = DID_NOT_SLIDE.into();
                    r.t_end_s = Some(0.0);
                    r.travel_m = Some(0.0);
                }
                r
            })
            .collect();
        let members: Vec<&SweepRow> = rows.iter().collect();
        let (kept, all_changes) = thin_line(&members, 120, false);
        assert!(all_changes);
        assert!(kept.len() <= 120 && kept.len() > 100, "{}", kept.len());
        let at = |r: &SweepRow| (first_of(r) * 1e4).round() / 1e4;
        let xs: Vec<f64> = kept.iter().map(|r| at(r)).collect();
        for want in [0.3, 0.487, 0.4871, 0.6] {
            assert!(xs.contains(&want), "{want} not kept");
        }
        // A change at every value: too many to keep both sides of each, still at most 120.
        let mut alternating = rows.clone();
        for (k, r) in alternating.iter_mut().enumerate() {
            r.reason = format!("reason {}", k % 2);
        }
        let members: Vec<&SweepRow> = alternating.iter().collect();
        let (kept, all_changes) = thin_line(&members, 120, false);
        assert!(!all_changes);
        assert_eq!(kept.len(), 120);
    }

    #[test]
    fn a_sweep_where_nothing_slid_has_a_travel_axis_from_zero_and_says_so() {
        let mu = [0.5, 0.55, 0.6];
        let rows: Vec<SweepRow> = mu
            .iter()
            .map(|&m| SweepRow {
                reason: DID_NOT_SLIDE.into(),
                t_end_s: Some(0.0),
                travel_m: Some(0.0),
                factor_of_safety: Some(FactorOfSafety::Finite { value: 2.0 * m }),
                ..row(vec![m])
            })
            .collect();
        let svg = draw("still", &[vary("friction.mu_k", &mu)], &rows);
        let t = texts(&svg);
        let words: Vec<&str> = t.iter().map(|t| t.1.as_str()).collect();
        assert!(
            words.iter().any(|w| w.contains("nothing slid")),
            "{words:?}"
        );
        // The travel axis's ticks: from 0 up, none below.
        let ticks: Vec<f64> = words.iter().filter_map(|w| w.parse().ok()).collect();
        assert!(ticks.iter().all(|&v| v >= 0.0), "{ticks:?}");
        assert!(ticks.contains(&0.0) && ticks.contains(&1.0), "{ticks:?}");
    }

    #[test]
    fn the_lines_drawn_known_from_the_keys_are_those_every_row_held_would_give() {
        // The picture keeps only the rows of the lines it draws, chosen before any route runs:
        // they must be the groups that grouping every combination and spreading would choose.
        let grid = |values: &[Vec<f64>]| -> Vec<SweepRow> {
            let n: usize = values.iter().map(Vec::len).product();
            (0..n)
                .map(|mut k| {
                    let mut v = vec![0.0; values.len()];
                    for (i, vals) in values.iter().enumerate().rev() {
                        v[i] = vals[k % vals.len()];
                        k /= vals.len();
                    }
                    row(v)
                })
                .collect()
        };
        let lin = |n: usize, lo: f64| (0..n).map(|i| lo + i as f64 * 0.5).collect::<Vec<f64>>();
        for values in [
            vec![lin(3, 0.0)],
            vec![lin(3, 0.0), lin(4, -1.0)],
            vec![lin(2, 0.0), vec![1.0, 0.0, 1.0, -0.0, 0.0, -2.0]],
            vec![lin(5, 0.0), lin(41, 3.0)],
            vec![lin(2, 0.0), lin(7, 1.0), vec![3.0, -3.0, 1e7, 6e6, 2.0]],
            vec![lin(1, 0.0), lin(31, 0.0), lin(30, 9.0)],
        ] {
            let varies: Vec<Vary> = values
                .iter()
                .enumerate()
                .map(|(k, v)| Vary::numbers(&format!("k.{k}"), v.clone()))
                .collect();
            let rows = grid(&values);
            let all = groups(&rows);
            let want: Vec<Vec<f64>> = spread(all.len(), MAX_LINES)
                .into_iter()
                .map(|k| all[k].0.clone())
                .collect();
            let mut drawn = Drawn::new(&varies, None);
            for r in &rows {
                drawn.add(r).unwrap();
            }
            let kept = drawn.marks.iter().flatten().filter(|&&m| m != 0).count();
            let bits = |v: &[Vec<f64>]| -> Vec<Vec<u64>> {
                v.iter()
                    .map(|k| k.iter().map(|x| x.to_bits()).collect())
                    .collect()
            };
            assert_eq!(drawn.lines, all.len(), "{values:?}");
            assert_eq!(bits(&drawn.chosen), bits(&want), "{values:?}");
            let in_chosen: usize = all
                .iter()
                .filter(|g| {
                    want.iter()
                        .any(|w| bits(std::slice::from_ref(w)) == bits(std::slice::from_ref(&g.0)))
                })
                .map(|g| g.1.len())
                .sum();
            assert_eq!(kept, in_chosen, "{values:?}");
            assert_eq!(drawn.combinations, rows.len());
        }
    }

    /// The rows drawn when every combination is held: the lines [`Drawn`] chose, each grouped
    /// from every row and thinned along itself ([`thin_line`]), in the sweep's order; with
    /// whether every change was kept, the first key's lowest and highest values on the lines
    /// and how many distinct.
    fn drawn_when_held(
        rows: &[SweepRow],
        chosen: &[Vec<f64>],
        shaken: bool,
    ) -> (Vec<SweepRow>, bool, Option<(f64, f64)>, usize) {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
        let on_lines: Vec<SweepRow> = rows
            .iter()
            .filter(|r| chosen.iter().any(|k| bits(k) == bits(&r.values[1..])))
            .cloned()
            .collect();
        let all = groups(&on_lines);
        let along = (MAX_MARKED / all.len().max(1)).clamp(2, MAX_ALONG);
        let mut kept: Vec<*const SweepRow> = Vec::new();
        let mut every_change = true;
        for (_, members) in &all {
            let (line, changes) = thin_line(members, along, shaken);
            every_change &= changes;
            kept.extend(line.into_iter().map(|r| r as *const SweepRow));
        }
        let mut firsts: Vec<f64> = on_lines.iter().map(first_of).collect();
        firsts.sort_by(f64::total_cmp);
        let span = firsts.first().zip(firsts.last()).map(|(a, b)| (*a, *b));
        firsts.dedup_by(|a, b| a.total_cmp(b).is_eq());
        let drawn = on_lines
            .iter()
            .filter(|r| kept.contains(&(*r as *const SweepRow)))
            .cloned()
            .collect();
        (drawn, every_change, span, firsts.len())
    }

    #[test]
    fn the_rows_drawn_chosen_as_they_come_are_those_every_row_held_would_give() {
        // Long lines (more values of the first key than a line marks) whose routes end in
        // runs and at scattered values, the first key's values out of order and repeated (−0
        // beside 0), under a record and not, a sweep cut short, and the store spilled to its
        // file after a few rows: the rows drawn, their order and what the caption says are
        // those of holding every combination and thinning each line whole.
        let mut firsts: Vec<f64> = (0..900).map(|i| (i as f64 * 0.37).sin() * 3.0).collect();
        firsts.extend([0.0, -0.0, 0.0, 1.5, 1.5]);
        let seconds = [2.0, -1.0, 0.5, -1.0];
        let ended = |k: usize, x: f64| -> (String, Option<f64>) {
            if x > 2.2 {
                (DID_NOT_SLIDE.into(), Some(0.0))
            } else if k % 97 == 13 {
                ("a contact lifted off".into(), Some(0.0))
            } else if (k / 7).is_multiple_of(5) && x < -2.5 {
                ("stopped".into(), Some(1.0))
            } else {
                ("time limit".into(), Some(2.0))
            }
        };
        for (shaken, cut, spill) in [(false, 0, 1), (true, 0, 1 << 15), (false, 1000, 7)] {
            let mut rows = Vec::new();
            for (i, &x) in firsts.iter().enumerate() {
                for (j, &y) in seconds.iter().enumerate() {
                    let k = i * seconds.len() + j;
                    let mut r = row(vec![x, y]);
                    (r.reason, r.t_end_s) = ended(k, x);
                    r.travel_m = Some(x.abs() + y);
                    if shaken {
                        r.permanent_x_m = Some(0.1 * x);
                        r.permanent_z_m = Some(-0.2 * y);
                    }
                    r.factor_of_safety = match k % 4 {
                        0 => Some(FactorOfSafety::Finite { value: 1.0 + x }),
                        1 => Some(FactorOfSafety::Unbounded),
                        2 => Some(FactorOfSafety::NotHoldable),
                        _ => None,
                    };
                    rows.push(r);
                }
            }
            rows.truncate(rows.len() - cut);
            let varies = vec![Vary::numbers("k.0", firsts.clone()), vary("k.1", &seconds)];
            let mut drawn = Drawn::new(&varies, None);
            drawn.store =
                crate::probabilistic::Columns::new(STORED, None).with_in_memory_rows(spill);
            for r in &rows {
                drawn.add(r).unwrap();
            }
            let got = drawn.choose().unwrap();
            let (want, every_change, span, distinct) =
                drawn_when_held(&rows, &drawn.chosen, shaken);
            let shown = |r: &SweepRow| {
                let v = |x: Option<f64>| x.map(f64::to_bits);
                (
                    r.values.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    r.reason.clone(),
                    [
                        v(r.t_end_s),
                        v(r.travel_m),
                        v(r.permanent_x_m),
                        v(r.permanent_z_m),
                    ],
                    format!("{:?}", r.factor_of_safety),
                )
            };
            let (got_shown, want_shown): (Vec<_>, Vec<_>) = (
                got.rows.iter().map(shown).collect(),
                want.iter().map(shown).collect(),
            );
            assert!(
                want.len() < rows.len() && want.len() > 100,
                "{}",
                want.len()
            );
            assert_eq!(got_shown, want_shown, "shaken {shaken}, cut {cut}");
            assert_eq!(got.changes_kept, every_change);
            assert_eq!(got.first_span, span);
            assert_eq!(got.first_distinct, distinct);
        }
    }
}
