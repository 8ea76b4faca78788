//! The sheet every picture is drawn on: the chart on the left and a side
//! panel on the right for the legend, notes, an inset or a colour bar. Nothing in the panel is
//! drawn over the chart, so a legend can never cover data.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

pub(super) type Res<T> = Result<T, String>;
pub(super) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// The error of drawing `path`, as one line.
pub(super) fn err<E: std::fmt::Display>(path: &Path) -> impl Fn(E) -> String + '_ {
    move |e| format!("{}: cannot draw: {e}", path.display())
}

/// Width of the side panel (pixels).
pub(super) const PANEL_W: u32 = 320;
/// Font size of legends, notes, tick labels and axis names, the smallest text of any picture:
/// plotters' SVG backend writes a font's size divided by 1.24, so this is 14.5 px in the
/// picture (every text at least 14 px at the default size).
pub(super) const FONT: f64 = 18.0;
/// Font size of a picture's title: 17.7 px.
const TITLE: f64 = 22.0;
/// The width a character of [`FONT`] takes, about (pixels).
const CHAR_W: f64 = 0.56 * FONT / 1.24;
/// Height of one line of legend or notes.
const LINE_H: i32 = 20;
/// The width of a thick line (px): the plan's frame at the start.
pub(super) const THICK: u32 = 3;
/// Room left of a legend's text for its mark.
const MARK_W: i32 = 34;

/// A picture: the whole sheet, the chart's part of it and the side panel.
pub(super) struct Sheet<'a> {
    pub root: Area<'a>,
    pub chart: Area<'a>,
    pub panel: Area<'a>,
}

impl<'a> Sheet<'a> {
    /// A white sheet of `w` × `h` pixels: `title` across the top, the chart below it on the left,
    /// the panel of [`PANEL_W`] on the right.
    pub fn new(path: &'a Path, size: (u32, u32), title: &str) -> Res<Sheet<'a>> {
        Sheet::captioned(path, size, title, None)
    }

    /// A sheet as [`Sheet::new`] makes it, with a `caption` across its foot, under both the
    /// chart and the panel, on a pale band, wrapped to the sheet's width: what a picture says
    /// of all of it (what it left out of a sweep too large to draw whole). The sheet grows by
    /// the caption's lines, so that the chart and the panel keep their size.
    pub fn captioned(
        path: &'a Path,
        (w, h): (u32, u32),
        title: &str,
        caption: Option<&str>,
    ) -> Res<Sheet<'a>> {
        let lines = caption.map_or(Vec::new(), |c| wrap(c, w as i32 - 2 * CAPTION_X));
        let foot = if lines.is_empty() {
            0
        } else {
            LINE_H * lines.len() as i32 + 2 * CAPTION_PAD
        };
        let root = SVGBackend::new(path, (w, h + foot as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(err(path))?;
        let body = root
            .titled(title, ("sans-serif", TITLE))
            .map_err(err(path))?;
        let (_, body_h) = body.dim_in_pixel();
        let (body, foot_area) = body.split_vertically(body_h as i32 - foot);
        if foot > 0 {
            foot_area
                .draw(&Rectangle::new(
                    [(CAPTION_X / 2, 2), (w as i32 - CAPTION_X / 2, foot - 2)],
                    RGBColor(240, 240, 235).filled(),
                ))
                .map_err(err(path))?;
            for (k, line) in lines.into_iter().enumerate() {
                foot_area
                    .draw(&Text::new(
                        line,
                        (CAPTION_X, CAPTION_PAD + LINE_H * k as i32 + LINE_H / 2),
                        font(FONT),
                    ))
                    .map_err(err(path))?;
            }
        }
        let (chart, panel) = body.split_horizontally(w - PANEL_W);
        let panel = panel.margin(8, 8, 6, 6);
        Ok(Sheet { root, chart, panel })
    }
}

/// The left margin of a caption's text (pixels).
const CAPTION_X: i32 = 16;
/// The room above and below a caption's lines (pixels).
const CAPTION_PAD: i32 = 6;

/// How an entry of a legend is marked.
#[derive(Debug, Clone, Copy)]
pub(super) enum Mark {
    Line(RGBColor),
    /// A line [`THICK`] px wide.
    Thick(RGBColor),
    Dashed(RGBColor),
    Dot(RGBColor),
    Ring(RGBColor),
    Square(RGBColor),
    Cross(RGBColor),
    Triangle(RGBColor, bool),
    Swatch(RGBColor),
    /// A line through a filled marker, dashed or not: one series of a chart.
    Series(RGBColor, Shape, bool),
    /// No mark: a heading or a note.
    None,
}

/// The shape of a filled marker of a series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Shape {
    Dot,
    Square,
    Triangle,
    Diamond,
}

impl Shape {
    /// Every shape, in the order series take them.
    pub const ALL: [Shape; 4] = [Shape::Dot, Shape::Square, Shape::Triangle, Shape::Diamond];
}

/// Draws a filled `shape` of `color` centred at (x, y) of `area` (pixels).
pub(super) fn draw_shape<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    shape: Shape,
    color: RGBColor,
    (x, y): (i32, i32),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let fill = color.filled();
    match shape {
        Shape::Dot => area.draw(&Circle::new((x, y), 4, fill)),
        Shape::Square => area.draw(&Rectangle::new([(x - 4, y - 4), (x + 4, y + 4)], fill)),
        Shape::Triangle => area.draw(&Polygon::new(
            vec![(x, y - 6), (x + 5, y + 4), (x - 5, y + 4)],
            fill,
        )),
        Shape::Diamond => area.draw(&Polygon::new(
            vec![(x, y - 6), (x + 5, y), (x, y + 6), (x - 5, y)],
            fill,
        )),
    }
}

/// One line of a legend.
#[derive(Debug, Clone)]
pub(super) struct Entry {
    pub mark: Mark,
    pub text: String,
}

impl Entry {
    pub fn new(mark: Mark, text: impl Into<String>) -> Entry {
        Entry {
            mark,
            text: text.into(),
        }
    }
}

/// `text` broken at spaces into lines of at most `width` pixels (about).
fn wrap(text: &str, width: i32) -> Vec<String> {
    let max = ((f64::from(width) / CHAR_W) as usize).max(8);
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > max {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// The font of tick labels and axis names: [`FONT`], in black.
pub(super) fn label_font<'b>() -> TextStyle<'b> {
    ("sans-serif", FONT).into_font().color(&BLACK)
}

fn font<'b>(size: f64) -> TextStyle<'b> {
    ("sans-serif", size)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center))
}

/// Draws `mark` centred at (x, y) of `area` (pixels).
pub(super) fn draw_mark<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    mark: Mark,
    (x, y): (i32, i32),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    match mark {
        Mark::Line(c) => area.draw(&PathElement::new(
            vec![(x - 12, y), (x + 12, y)],
            c.stroke_width(2),
        )),
        Mark::Thick(c) => area.draw(&PathElement::new(
            vec![(x - 12, y), (x + 12, y)],
            c.stroke_width(THICK),
        )),
        Mark::Dashed(c) => {
            for k in 0..3 {
                let x0 = x - 12 + 9 * k;
                area.draw(&PathElement::new(
                    vec![(x0, y), (x0 + 5, y)],
                    c.stroke_width(2),
                ))?;
            }
            Ok(())
        }
        Mark::Dot(c) => area.draw(&Circle::new((x, y), 4, c.filled())),
        Mark::Ring(c) => area.draw(&Circle::new((x, y), 5, c.stroke_width(2))),
        Mark::Square(c) => area.draw(&Rectangle::new(
            [(x - 5, y - 5), (x + 5, y + 5)],
            c.stroke_width(2),
        )),
        Mark::Cross(c) => area.draw(&Cross::new((x, y), 5, c.stroke_width(2))),
        Mark::Triangle(c, up) => {
            let s = if up { -1 } else { 1 };
            area.draw(&Polygon::new(
                vec![(x - 6, y - 4 * s), (x + 6, y - 4 * s), (x, y + 6 * s)],
                c.filled(),
            ))
        }
        Mark::Swatch(c) => {
            area.draw(&Rectangle::new(
                [(x - 12, y - 6), (x + 12, y + 6)],
                c.mix(0.25).filled(),
            ))?;
            area.draw(&Rectangle::new(
                [(x - 12, y - 6), (x + 12, y + 6)],
                c.mix(0.6),
            ))
        }
        Mark::Series(c, shape, dashed) => {
            if dashed {
                draw_mark(area, Mark::Dashed(c), (x, y))?;
            } else {
                draw_mark(area, Mark::Line(c), (x, y))?;
            }
            draw_shape(area, shape, c, (x, y))
        }
        Mark::None => Ok(()),
    }
}

/// Draws `entries` down the panel from `y` (pixels from its top), long texts wrapped to the
/// panel's width; returns the y below the last line.
pub(super) fn legend(path: &Path, panel: &Area, entries: &[Entry], mut y: i32) -> Res<i32> {
    let width = panel.dim_in_pixel().0 as i32;
    for e in entries {
        let (indent, size) = match e.mark {
            Mark::None => (0, FONT),
            _ => (MARK_W, FONT),
        };
        let lines = wrap(&e.text, width - indent);
        draw_mark(panel, e.mark, (MARK_W / 2 - 2, y + LINE_H / 2)).map_err(err(path))?;
        for line in lines {
            panel
                .draw(&Text::new(line, (indent, y + LINE_H / 2), font(size)))
                .map_err(err(path))?;
            y += LINE_H;
        }
        y += 3;
    }
    Ok(y)
}

/// A heading in the panel at `y`; returns the y below it.
pub(super) fn heading(path: &Path, panel: &Area, text: &str, y: i32) -> Res<i32> {
    let style = ("sans-serif", FONT + 1.0)
        .into_font()
        .style(FontStyle::Bold)
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    panel
        .draw(&Text::new(text.to_string(), (0, y + LINE_H / 2), style))
        .map_err(err(path))?;
    Ok(y + LINE_H + 4)
}

/// A picture that says in words why there is nothing to plot (a scene that does not slide, a
/// route that ended at once), instead of empty axes.
pub(super) fn message(path: &Path, size: (u32, u32), title: &str, lines: &[String]) -> Res<()> {
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(err(path))?;
    let body = root
        .titled(title, ("sans-serif", TITLE))
        .map_err(err(path))?;
    let (w, h) = body.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    let width = (w - 160).max(200);
    // Paragraphs apart by a blank line.
    let wrapped: Vec<String> = lines
        .iter()
        .enumerate()
        .flat_map(|(k, l)| {
            let gap = (k > 0).then(String::new);
            gap.into_iter().chain(wrap(l, width))
        })
        .collect();
    let top = (h - LINE_H * wrapped.len() as i32) / 2 - 20;
    body.draw(&Rectangle::new(
        [
            (60, top - 20),
            (w - 60, top + LINE_H * wrapped.len() as i32 + 20),
        ],
        RGBColor(240, 240, 235).filled(),
    ))
    .map_err(err(path))?;
    for (k, line) in wrapped.into_iter().enumerate() {
        body.draw(&Text::new(
            line,
            (80, top + LINE_H * k as i32 + LINE_H / 2),
            font(FONT + 1.0),
        ))
        .map_err(err(path))?;
    }
    root.present().map_err(err(path))
}

/// The range of the finite `values`, padded by 5 %; a constant (or no) value gets a range
/// about it wide enough for readable ticks, not `-0.0 … 0.0`. The range is always finite and
/// within ±[`AXIS_LIMIT`], however large the values (a span near ±`f64::MAX` would overflow to
/// an infinite one and leave the axis without ticks); values beyond it fall off the chart.
pub(super) fn ranges(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v.clamp(-AXIS_LIMIT, AXIS_LIMIT));
        hi = hi.max(v.clamp(-AXIS_LIMIT, AXIS_LIMIT));
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let size = hi.abs().max(lo.abs());
    let (lo, hi) = if hi - lo <= 1e-9 * size.max(1e-300) {
        let pad = if size > 0.0 { 0.1 * size } else { 1.0 };
        (lo - pad, hi + pad)
    } else {
        let pad = ((hi - lo) * 0.05).max(1e-3 * size);
        (lo - pad, hi + pad)
    };
    (lo.max(-AXIS_LIMIT), hi.min(AXIS_LIMIT))
}

/// The largest size an axis reaches: a quarter of `f64::MAX`, so that the span of an axis from
/// −`AXIS_LIMIT` to `AXIS_LIMIT` is still finite.
pub(super) const AXIS_LIMIT: f64 = f64::MAX / 4.0;

/// Tick labels for an axis over `lo..hi`: as many decimals as about ten ticks need, no `-0`,
/// never `inf` or `NaN`.
pub(super) fn ticks(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    let decimals = (-(span / 10.0).log10().floor()).clamp(0.0, 9.0) as usize;
    move |v: &f64| {
        // No label rather than `inf` or `NaN` (no tick of a finite axis is either).
        if !v.is_finite() {
            return String::new();
        }
        // A tick at zero computed as lo + k·step carries round-off (−3.3e-24): it is zero.
        let v = &(if v.abs() < 1e-9 * span { 0.0 } else { *v });
        if *v == 0.0 && decimals > 4 {
            return "0".into();
        }
        if v.abs() >= 1e6 || (v.abs() < 1e-4 && decimals > 4) {
            return format!("{v:.1e}");
        }
        let s = format!("{v:.decimals$}");
        if s.trim_start_matches('-')
            .chars()
            .all(|c| c == '0' || c == '.')
        {
            s.trim_start_matches('-').to_string()
        } else {
            s
        }
    }
}

/// A value for a legend or note, short: four significant digits, trailing zeros dropped, in
/// powers of ten (`6×10⁶`) past a million or under a thousandth. Finite for every finite value,
/// the subnormal (`10⁻³¹⁰`, `4.941×10⁻³²⁴`), the largest (`1.798×10³⁰⁸`) and zero of either sign
/// (`0`): the power of ten is read off Rust's own exponent notation, never divided out (10⁻³¹⁰
/// underflows to 0, and dividing by it gave `inf×10⁻³¹⁰`). An infinite value is `∞` or `−∞`,
/// and one that is not a number, which no caller means to pass, a dash `—`: never `inf` or
/// `NaN`.
pub(super) fn short(v: f64) -> String {
    if v.is_nan() {
        return "—".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "∞" } else { "−∞" }.into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-3..1e6).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        return if s == "-0" { "0".into() } else { s };
    }
    // `-1.235e-310`: four significant digits, rounded once, whatever the size.
    let sci = format!("{v:.3e}");
    let Some((m, e)) = sci.split_once('e') else {
        return sci;
    };
    let m = m.trim_end_matches('0').trim_end_matches('.');
    let sup: String = e
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d => d.to_digit(10).map_or(d, |d| {
                ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d as usize]
            }),
        })
        .collect();
    if m == "1" {
        format!("10{sup}")
    } else {
        format!("{m}×10{sup}")
    }
}

/// A force in N as a person writes it: `8 MN`, `650 kN`, `12 N`.
pub(super) fn force(f: f64) -> String {
    let a = f.abs();
    if a >= 1e6 {
        format!("{} MN", short(f / 1e6))
    } else if a >= 1e3 {
        format!("{} kN", short(f / 1e3))
    } else {
        format!("{} N", short(f))
    }
}

/// The unit of a scene key, from its suffix (`_deg` °, `_m` m, …); empty when it has none.
pub(super) fn unit_of(key: &str) -> &'static str {
    const UNITS: [(&str, &str); 10] = [
        ("_deg_s", "°/s"),
        ("_m_s2", "m/s²"),
        ("_m_s", "m/s"),
        ("_kg_m2", "kg·m²"),
        ("_kg", "kg"),
        ("_deg", "°"),
        ("_n_m", "N·m"),
        ("_n", "N"),
        ("_m", "m"),
        ("_s", "s"),
    ];
    UNITS
        .iter()
        .find(|(s, _)| key.ends_with(s))
        .map_or("", |(_, u)| u)
}

/// `key = value unit`, the value short.
pub(super) fn key_value(key: &str, value: &str) -> String {
    match unit_of(key) {
        "" => format!("{key} = {value}"),
        "°" => format!("{key} = {value}°"),
        u => format!("{key} = {value} {u}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_values_get_a_readable_range_and_no_negative_zero_ticks() {
        let (lo, hi) = ranges([0.0, 0.0].into_iter());
        assert!(lo <= -0.5 && hi >= 0.5, "{lo} {hi}");
        let t = ticks(lo, hi);
        assert_eq!(t(&-0.0), "0.0");
        assert_eq!(t(&-1e-17), "0.0");
        assert_eq!(t(&-0.5), "-0.5");
        let t = ticks(-2e-8, 1e-9);
        assert_eq!(t(&-3.3e-24), "0");
        let (lo, hi) = ranges([5e6].into_iter());
        assert!(lo < 5e6 && hi > 5e6 && (hi - lo) > 1e5);
    }

    #[test]
    fn short_numbers_are_finite_and_sensible_at_the_extremes_of_f64() {
        for (v, text) in [
            (0.0, "0"),
            (-0.0, "0"),
            (1e-310, "10⁻³¹⁰"),
            (-1e-310, "-1×10⁻³¹⁰"),
            (2.5e-310, "2.5×10⁻³¹⁰"),
            (5e-324, "4.941×10⁻³²⁴"),
            (f64::MIN_POSITIVE, "2.225×10⁻³⁰⁸"),
            (f64::MAX, "1.798×10³⁰⁸"),
            (-f64::MAX, "-1.798×10³⁰⁸"),
            (1e300, "10³⁰⁰"),
            (9.99996e6, "10⁷"),
            (f64::INFINITY, "∞"),
            (f64::NEG_INFINITY, "−∞"),
            (f64::NAN, "—"),
        ] {
            let s = short(v);
            assert_eq!(s, text, "{v:e}");
            let lower = s.to_lowercase();
            assert!(
                !lower.contains("inf") && !lower.contains("nan"),
                "{v:e}: {s}"
            );
        }
        // A force, or a legend's key and value, of the same extremes.
        assert_eq!(force(1e-310), "10⁻³¹⁰ N");
        assert_eq!(force(f64::MAX), "1.798×10³⁰² MN");
        assert_eq!(
            key_value("loads.eccentricity_m", &short(1e-310)),
            "loads.eccentricity_m = 10⁻³¹⁰ m"
        );
    }

    #[test]
    fn axes_of_extreme_values_are_finite_and_label_no_infinity() {
        for values in [
            vec![-f64::MAX, f64::MAX],
            vec![f64::MAX],
            vec![5e-324, 1e-310],
            vec![0.0, f64::INFINITY, f64::NAN],
            vec![1e300, -1e300],
        ] {
            let (lo, hi) = ranges(values.iter().copied());
            assert!(
                lo.is_finite() && hi.is_finite() && lo < hi,
                "{values:?}: {lo} {hi}"
            );
            assert!((hi - lo).is_finite(), "{values:?}: {lo} {hi}");
            let t = ticks(lo, hi);
            for k in 0..=10 {
                let label = t(&(lo + (hi - lo) * f64::from(k) / 10.0));
                assert!(!label.contains("inf") && !label.contains("NaN"), "{label}");
            }
        }
        let t = ticks(0.0, 1.0);
        assert_eq!(t(&f64::INFINITY), "");
        assert_eq!(t(&f64::NAN), "");
    }

    #[test]
    fn short_numbers_for_legends() {
        assert_eq!(short(0.30000000000000004), "0.3");
        assert_eq!(short(-0.5), "-0.5");
        assert_eq!(short(6e6), "6×10⁶");
        assert_eq!(short(1e7), "10⁷");
        assert_eq!(short(2.5e-5), "2.5×10⁻⁵");
        assert_eq!(short(123.456), "123.5");
        assert_eq!(force(8e6), "8 MN");
        assert_eq!(force(6.5e5), "650 kN");
    }

    #[test]
    fn units_come_from_the_key_suffix() {
        assert_eq!(unit_of("friction.mu_k"), "");
        assert_eq!(unit_of("foundation.xi_deg"), "°");
        assert_eq!(unit_of("loads.eccentricity_m"), "m");
        assert_eq!(unit_of("loads.hydraulic_force_n"), "N");
        assert_eq!(unit_of("block.inertia_kg_m2"), "kg·m²");
        assert_eq!(unit_of("initial.omega_deg_s"), "°/s");
        assert_eq!(
            key_value("foundation.xi_deg", "20"),
            "foundation.xi_deg = 20°"
        );
    }

    #[test]
    fn long_legend_texts_wrap_at_spaces() {
        let lines = wrap(
            "contacts 0, 1, 2 at the start and their frame every eighth",
            140,
        );
        assert!(lines.len() > 1);
        assert!(lines.iter().all(|l| l.chars().count() <= 20), "{lines:?}");
    }
}
