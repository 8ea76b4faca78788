//! A load case's section drawn to scale for `report.html`: the rock, the water, the section,
//! the uplift under the base, the crack, the loads as arrows on their lines of action, the
//! anchors and the resultant where it meets the base (SVG, metres to pixels at one scale for the
//! whole drawing).

use super::{COLOURS, n};
use crate::check::{CaseResult, GravityVerdict, uplift_heads};
use crate::{LoadsUsed, RockAnchor, Section, WaterLoads};
use std::fmt::Write;

/// The drawing's frame: where the section and its water stand in metres, and the one scale
/// from metres to pixels.
struct Canvas {
    /// The section's base length, height and crest length (m).
    base: f64,
    height: f64,
    crest: f64,
    /// The reservoir's and the tailwater's levels (m).
    h1: f64,
    h2: f64,
    /// The depth of the band under the base that the uplift diagram fills (m).
    uplift_depth: f64,
    /// The drawing's left and right (m along the base), and its bottom and top (m up).
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    /// Pixels a metre, and the drawing's size (px).
    k: f64,
    width_px: f64,
    height_px: f64,
}

impl Canvas {
    /// The frame of section `s` under water levels `h1`, `h2`: from a reservoir strip upstream
    /// to past the toe, and from the uplift diagram under the base to the top of the water or
    /// the crest.
    fn new(s: &Section, (h1, h2): (f64, f64)) -> Canvas {
        let (b, h, c) = (s.base_length, s.height, s.crest_length);
        let reach = 0.35 * b.max(h);
        let top = h.max(h1) + 0.05 * h;
        let uplift_depth = 0.25 * h;
        let (x0, x1) = (-reach, b + reach);
        let (y0, y1) = (-uplift_depth - 0.05 * h, top);
        let width = 720.0;
        let k = width / (x1 - x0);
        let height = (y1 - y0) * k;
        Canvas {
            base: b,
            height: h,
            crest: c,
            h1,
            h2,
            uplift_depth,
            x0,
            x1,
            y0,
            y1,
            k,
            width_px: width,
            height_px: height,
        }
    }

    /// A distance along the base (m) in pixels from the left.
    fn px(&self, x: f64) -> f64 {
        (x - self.x0) * self.k
    }

    /// A height (m) in pixels from the top.
    fn py(&self, y: f64) -> f64 {
        (self.y1 - y) * self.k
    }
}

/// The arrows: length in proportion to size, the largest a third of the drawing's height.
struct Arrows {
    height: f64,
    biggest: f64,
}

impl Arrows {
    /// An arrow's length (px) for a force `f` (N).
    fn len(&self, f: f64) -> f64 {
        (self.height / 3.0) * f / self.biggest
    }

    /// An arrow from its tail (xa, ya) to its head, labelled at its tail: above a horizontal
    /// one, beside a vertical one.
    fn arrow(
        &self,
        (xa, ya): (f64, f64),
        (xb, yb): (f64, f64),
        label: String,
        colour: &str,
    ) -> String {
        let (lx, ly) = if (yb - ya).abs() < 1.0 {
            (xa.min(xb), ya - 7.0)
        } else {
            (xa + 6.0, ya + 14.0 * (yb - ya).signum())
        };
        format!(
            "<line x1=\"{xa:.1}\" y1=\"{ya:.1}\" x2=\"{xb:.1}\" y2=\"{yb:.1}\" stroke=\"{colour}\" \
             stroke-width=\"2.5\" marker-end=\"url(#a{})\"/><text x=\"{lx:.1}\" y=\"{ly:.1}\" \
             font-size=\"12\" fill=\"{colour}\">{label}</text>",
            &colour[1..]
        )
    }
}

/// The section to scale with its water, loads, uplift, crack and resultant.
pub(super) fn drawing(
    s: &Section,
    anchors: &[RockAnchor],
    r: &CaseResult,
    g: &GravityVerdict,
) -> String {
    let water = r.loads.as_ref().and_then(|l| l.water.as_ref());
    let canvas = Canvas::new(
        s,
        water.map_or((0.0, 0.0), |w| (w.levels.headwater, w.levels.tailwater)),
    );
    let mut d = String::new();
    head(&mut d, &canvas);
    ground_and_water(&mut d, &canvas, water);
    section(&mut d, &canvas);
    if let Some(w) = water {
        uplift(&mut d, &canvas, s, w, g);
    }
    crack(&mut d, &canvas, g.crack_length_m);
    let loads = r.loads.as_ref();
    let arrows = Arrows {
        height: canvas.height_px,
        biggest: [
            loads.map_or(0.0, |l| l.weight_n),
            g.normal_n.abs(),
            g.shear_n.abs(),
        ]
        .into_iter()
        .fold(f64::MIN_POSITIVE, f64::max),
    };
    if let (Some(l), Some(w)) = (loads, water) {
        forces(&mut d, &canvas, &arrows, s, l, w);
    }
    for (k, a) in anchors.iter().enumerate() {
        anchor(&mut d, &canvas, &arrows, k, a);
    }
    resultant(&mut d, &canvas, &arrows, g);
    middle_third(&mut d, &canvas);
    d
}

/// The `<svg>` element and one arrowhead a colour, 10 px whatever the line's width.
fn head(d: &mut String, c: &Canvas) {
    let _ = write!(
        d,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{hh:.0}\" \
         viewBox=\"0 0 {w:.0} {hh:.0}\" role=\"img\" aria-label=\"the section with its loads\">\
         <defs>",
        w = c.width_px,
        hh = c.height_px
    );
    for colour in COLOURS {
        let _ = write!(
            d,
            "<marker id=\"a{}\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" \
             markerUnits=\"userSpaceOnUse\" markerWidth=\"10\" markerHeight=\"10\" \
             orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\" fill=\"{colour}\"/></marker>",
            &colour[1..]
        );
    }
    d.push_str("</defs>");
}

/// The rock, the reservoir, the tailwater over the downstream face and the silt.
fn ground_and_water(d: &mut String, c: &Canvas, water: Option<&WaterLoads>) {
    let (px, py) = (|x| c.px(x), |y| c.py(y));
    let _ = write!(
        d,
        "<rect x=\"0\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#e8e2d6\"/>",
        py(0.0),
        c.width_px,
        c.height_px - py(0.0)
    );
    if c.h1 > 0.0 {
        let _ = write!(
            d,
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#bcdcf2\"/>",
            px(c.x0),
            py(c.h1),
            px(0.0) - px(c.x0),
            py(0.0) - py(c.h1)
        );
    }
    if c.h2 > 0.0 {
        // Over the downstream face from the toe up to H2, then level downstream.
        let slope = (c.base - c.crest) / c.height;
        let _ = write!(
            d,
            "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"#bcdcf2\"/>",
            px(c.base - slope * c.h2.min(c.height)),
            py(c.h2),
            px(c.x1),
            py(c.h2),
            px(c.x1),
            py(0.0),
            px(c.base),
            py(0.0)
        );
    }
    if let Some(silt) = water.filter(|w| w.silt.force_n > 0.0) {
        let depth = 3.0 * silt.silt.at_m;
        let _ = write!(
            d,
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#a98f62\" \
             opacity=\"0.7\"/>",
            px(c.x0),
            py(depth),
            px(0.0) - px(c.x0),
            py(0.0) - py(depth)
        );
    }
}

/// The section: heel, toe, crest's downstream and upstream edges.
fn section(d: &mut String, c: &Canvas) {
    let (px, py) = (|x| c.px(x), |y| c.py(y));
    let _ = write!(
        d,
        "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"#c9c9c9\" \
         stroke=\"#555\" stroke-width=\"1.5\"/>",
        px(0.0),
        py(0.0),
        px(c.base),
        py(0.0),
        px(c.crest),
        py(c.height),
        px(0.0),
        py(c.height)
    );
}

/// The uplift's head under the base, scaled so that the heel's head fills the band.
fn uplift(d: &mut String, c: &Canvas, s: &Section, w: &WaterLoads, g: &GravityVerdict) {
    let (px, py) = (|x| c.px(x), |y| c.py(y));
    let (heads, _) = uplift_heads(s, &w.levels, g.crack_length_m);
    let scale = c.uplift_depth / c.h1.max(c.h2).max(f64::MIN_POSITIVE);
    let mut pts = format!("{:.1},{:.1}", px(0.0), py(0.0));
    for [x, head] in &heads {
        let _ = write!(pts, " {:.1},{:.1}", px(*x), py(-head * scale));
    }
    let _ = write!(pts, " {:.1},{:.1}", px(c.base), py(0.0));
    let _ = write!(
        d,
        "<polygon points=\"{pts}\" fill=\"#7fb3d5\" opacity=\"0.8\" stroke=\"#2b6a99\"/>\
         <text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\">uplift U = {} MN</text>",
        px(0.02 * c.base),
        py(-c.uplift_depth) + 14.0,
        n(g.uplift_n / 1e6, 2)
    );
}

/// The crack from the heel, where there is one.
fn crack(d: &mut String, c: &Canvas, crack: f64) {
    let (px, py) = (|x| c.px(x), |y| c.py(y));
    if crack > 0.0 {
        let _ = write!(
            d,
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#c62828\" \
         stroke-width=\"4\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\" \
         fill=\"#c62828\">crack {} m</text>",
            px(0.0),
            py(0.0),
            px(crack.min(c.base)),
            py(0.0),
            px(0.0),
            py(0.0) - 6.0,
            n(crack, 2)
        );
    }
}

/// The reservoir's push on its line ending at the face, the tailwater's, the weight from the
/// centre of mass down, and kh W.
fn forces(d: &mut String, c: &Canvas, a: &Arrows, s: &Section, l: &LoadsUsed, w: &WaterLoads) {
    let (px, py) = (|x| c.px(x), |y| c.py(y));
    let y = py(w.headwater.at_m);
    d.push_str(&a.arrow(
        (px(0.0) - a.len(w.headwater.force_n), y),
        (px(0.0), y),
        format!("P1 {} MN", n(w.headwater.force_n / 1e6, 2)),
        "#1f5f99",
    ));
    if w.tailwater.force_n > 0.0 {
        let y = py(w.tailwater.at_m);
        let xf = px(c.base - (c.base - c.crest) / c.height * w.tailwater.at_m);
        d.push_str(&a.arrow(
            (xf + a.len(w.tailwater.force_n).max(12.0), y),
            (xf, y),
            format!("P2 {}", n(w.tailwater.force_n / 1e6, 2)),
            "#1f5f99",
        ));
    }
    let yc = py(l.cm_height_m);
    let x_cm = s.mass_properties().cm_from_heel;
    d.push_str(&a.arrow(
        (px(x_cm), yc),
        (px(x_cm), yc + a.len(l.weight_n)),
        format!("W {} MN", n(l.weight_n / 1e6, 2)),
        "#333333",
    ));
    if l.kh != 0.0 {
        d.push_str(&a.arrow(
            (px(x_cm), yc),
            (px(x_cm) + a.len(l.kh * l.weight_n), yc),
            format!("kh W {}", n(l.kh * l.weight_n / 1e6, 2)),
            "#8e44ad",
        ));
    }
}

/// Anchor `k`: its tendon from the head down into the rock (dashed past the base), its pull an
/// arrow at the head along the tendon.
fn anchor(d: &mut String, c: &Canvas, a: &Arrows, k: usize, anchor: &RockAnchor) {
    let (px, py) = (|x| c.px(x), |y| c.py(y));
    let [x, y, _] = anchor.head;
    let dir = anchor.direction();
    let (dx, dy) = (dir.x, dir.y);
    let across = dy.abs().max(1e-9);
    let to_base = y / across;
    let into_rock = (c.uplift_depth / across)
        .min(anchor.free_length - to_base)
        .max(0.0);
    let (xb, yb) = (x + dx * to_base, 0.0);
    let (xr, yr) = (xb + dx * into_rock, -dy.abs() * into_rock);
    let _ = write!(
        d,
        "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#2e7d32\" \
         stroke-width=\"1.5\"/><line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" \
         stroke=\"#2e7d32\" stroke-width=\"1.5\" stroke-dasharray=\"5 3\"/>",
        px(x),
        py(y),
        px(xb),
        py(yb),
        px(xb),
        py(yb),
        px(xr),
        py(yr)
    );
    let l = a.len(anchor.prestress).max(30.0);
    let norm = dx.hypot(dy).max(1e-12);
    d.push_str(&a.arrow(
        (px(x), py(y)),
        (px(x) + l * dx / norm, py(y) - l * dy / norm),
        format!("A{k} {} MN", n(anchor.prestress / 1e6, 2)),
        "#2e7d32",
    ));
}

/// The resultant where it meets the base.
fn resultant(d: &mut String, c: &Canvas, a: &Arrows, g: &GravityVerdict) {
    let Some(at) = g.resultant_from_heel_m.filter(|a| a.is_finite()) else {
        return;
    };
    let x = c.px(at);
    let _ = write!(
        d,
        "<circle cx=\"{x:.1}\" cy=\"{:.1}\" r=\"4\" fill=\"#c62828\"/>",
        c.py(0.0)
    );
    d.push_str(&a.arrow(
        (
            x,
            c.py(0.0) + a.len(g.normal_n.max(0.0)).min(c.py(c.y0) - c.py(0.0)),
        ),
        (x, c.py(0.0)),
        format!(
            "N {} MN, {} m from the heel",
            n(g.normal_n / 1e6, 2),
            n(at, 2)
        ),
        "#c62828",
    ));
}

/// The middle third of the base, dashed; the drawing closed.
fn middle_third(d: &mut String, c: &Canvas) {
    let (px, py) = (|x| c.px(x), |y| c.py(y));
    let _ = writeln!(
        d,
        "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#555\" \
         stroke-dasharray=\"4 3\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\" fill=\"#555\">\
         middle third</text></svg>",
        px(c.base / 3.0),
        py(0.0) + 3.0,
        px(2.0 * c.base / 3.0),
        py(0.0) + 3.0,
        px(2.0 * c.base / 3.0) + 4.0,
        py(0.0) + 7.0
    );
}
