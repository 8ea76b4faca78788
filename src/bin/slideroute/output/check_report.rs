//! `check`'s `report.html`: one self-contained page a reviewer reads or prints — per load case
//! the monolith's section drawn to scale with its water, its loads on their lines of action, the
//! uplift under the base, the crack and the resultant; the loads and the verdicts with the
//! guideline each comes from; then the scene as used and the manifest.

use slideroute::RockAnchor;
use slideroute::Section;
use slideroute::check::{CaseResult, GravityVerdict, Guideline, uplift_heads};
use std::fmt::Write;

/// Text for HTML: `&`, `<`, `>` and `"` escaped.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A number to `d` decimals.
fn n(v: f64, d: usize) -> String {
    format!("{v:.d$}")
}

/// The page: every case of `results` on `section` (where the scene has one), under
/// `guideline`, then `scene_toml` and `manifest_json`.
pub fn report(
    scene: &str,
    guideline: &Guideline,
    section: Option<&Section>,
    results: &[CaseResult],
    scene_toml: &str,
    manifest_json: &str,
) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>Stability check: {s}</title>\n<style>{CSS}</style></head><body>\n\
         <h1>Stability check: {s}</h1>\n<p class=\"sub\">{g}. Sliding by the gravity method, \
         (N tan φ + c L w)/T on the base; resultant location and base pressures with the base \
         cracked where it would be in tension; the load multiple the three contacts' friction \
         cones hold, for comparison. Forces in MN, pressures in kPa, lengths in m.</p>\n",
        s = esc(scene),
        g = esc(&guideline.describe()),
    );
    h.push_str(&summary_table(results));
    for (k, r) in results.iter().enumerate() {
        let _ = writeln!(
            h,
            "<section class=\"case\"><h2>Case {k}: {name} <span class=\"cat\">{cat}</span> \
             <span class=\"{cls}\">{verdict}</span></h2>",
            name = esc(&r.case.name),
            cat = r.case.category.as_str(),
            cls = if r.passes { "pass" } else { "fail" },
            verdict = if r.passes { "passes" } else { "FAILS" },
        );
        if let (Some(s), Some(g)) = (section, r.gravity.as_ref()) {
            h.push_str(&drawing(s, &r.anchors, r, g));
            h.push_str(&loads_table(r, g, &r.anchors));
            h.push_str(&verdict_table(r, g, guideline));
        } else {
            let _ = write!(
                h,
                "<p>No monolith with its water: the load multiple alone, {}.</p>",
                r.factor_of_safety.map_or("none".into(), |f| f.cell())
            );
        }
        h.push_str("</section>\n");
    }
    let _ = write!(
        h,
        "<section class=\"case\"><h2>The scene as used</h2><pre>{}</pre>\
         <h2>Manifest</h2><pre>{}</pre></section>\n</body></html>\n",
        esc(scene_toml),
        esc(manifest_json)
    );
    h
}

/// The arrows' colours: water, weight, pseudo-static, resultant, anchors.
const COLOURS: [&str; 5] = ["#1f5f99", "#333333", "#8e44ad", "#c62828", "#2e7d32"];

const CSS: &str = "body{font-family:system-ui,sans-serif;margin:2em;color:#222;max-width:60em}\
h1{font-size:1.5em}h2{font-size:1.15em;margin-top:1.5em}.sub{color:#555}\
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #bbb;padding:.2em .5em;\
text-align:right}th{background:#eee}td:first-child,th:first-child{text-align:left}\
.pass{color:#1a7f37;font-weight:600}.fail{color:#c62828;font-weight:600}.cat{color:#666;\
font-weight:400}pre{background:#f6f6f6;padding:.8em;font-size:.8em;overflow-x:auto}\
svg{border:1px solid #ddd;background:#fff}\
@media print{.case{page-break-before:always}body{margin:0}}";

/// Every case in one table: the verdicts at a glance.
fn summary_table(results: &[CaseResult]) -> String {
    let mut t = String::from(
        "<table><tr><th>case</th><th>category</th><th>sliding FS</th><th>required</th>\
         <th>in compression %</th><th>required %</th><th>load multiple</th><th>result</th></tr>\n",
    );
    for r in results {
        let g = r.gravity.as_ref();
        let _ = writeln!(
            t,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td class=\"{}\">{}</td></tr>",
            esc(&r.case.name),
            r.case.category.as_str(),
            g.map_or("—".into(), |g| g
                .sliding_fs
                .map_or("unbounded".into(), |v| n(v, 3))),
            n(r.case.required_fs, 2),
            g.map_or("—".into(), |g| n(g.base_in_compression_pct, 1)),
            g.map_or("—".into(), required_pct),
            r.factor_of_safety.map_or("—".into(), |f| match f.value() {
                Some(v) => match r.run.route.factor_of_safety_limit {
                    Some(limit) => format!("{} {}", n(v, 3), limit.as_str()),
                    None => n(v, 3),
                },
                None => f.cell(),
            }),
            if r.passes { "pass" } else { "fail" },
            if r.passes { "pass" } else { "FAIL" },
        );
    }
    t.push_str("</table>\n");
    t
}

/// What the category asks of the base in compression, in words for the extreme case.
fn required_pct(g: &GravityVerdict) -> String {
    if g.required_compression_pct > 0.0 {
        n(g.required_compression_pct, 0)
    } else {
        "within base".into()
    }
}

/// The case's loads: size, and where each acts.
fn loads_table(r: &CaseResult, g: &GravityVerdict, anchors: &[RockAnchor]) -> String {
    let mut t = String::from("<table><tr><th>load</th><th>MN</th><th>acts</th></tr>\n");
    let mut row = |name: &str, f: f64, at: String| {
        let _ = writeln!(
            t,
            "<tr><td>{name}</td><td>{}</td><td>{at}</td></tr>",
            n(f / 1e6, 3)
        );
    };
    if let Some(l) = &r.loads {
        row(
            "weight W",
            l.weight_n,
            format!("at the centre of mass, {} m up", n(l.cm_height_m, 2)),
        );
        if l.kh != 0.0 {
            row(
                "kh W (downstream)",
                l.kh * l.weight_n,
                format!("at {} m up", n(l.cm_height_m, 2)),
            );
        }
        if l.kv != 0.0 {
            row(
                "kv W (up)",
                l.kv * l.weight_n,
                "at the centre of mass".into(),
            );
        }
        if let Some(w) = &l.water {
            row(
                "reservoir P1",
                w.headwater.force_n,
                format!("{} m up", n(w.headwater.at_m, 3)),
            );
            row(
                "tailwater P2",
                w.tailwater.force_n,
                format!("{} m up", n(w.tailwater.at_m, 3)),
            );
            row(
                "tailwater's weight",
                w.tailwater_weight.force_n,
                format!("{} m from the heel", n(w.tailwater_weight.at_m, 3)),
            );
            if w.silt.force_n > 0.0 {
                row(
                    "silt",
                    w.silt.force_n,
                    format!("{} m up", n(w.silt.at_m, 3)),
                );
            }
            if w.ice.force_n > 0.0 {
                row("ice", w.ice.force_n, format!("{} m up", n(w.ice.at_m, 3)));
            }
        }
    }
    for (k, a) in anchors.iter().enumerate() {
        let [x, y, z] = a.head;
        row(
            &format!("anchor {k} (prestress)"),
            a.prestress,
            format!(
                "from ({}, {}) m, {} m across, plunging {}° towards {}°",
                n(x, 2),
                n(y, 2),
                n(z, 2),
                n(a.plunge.to_degrees(), 1),
                n(a.trend.to_degrees(), 1)
            ),
        );
    }
    row(
        "uplift U",
        g.uplift_n,
        if g.crack_length_m > 0.0 {
            format!("with the crack of {} m", n(g.crack_length_m, 3))
        } else {
            "uncracked base".into()
        },
    );
    row("N (normal to the base)", g.normal_n, String::new());
    row("T (along the base)", g.shear_n, String::new());
    t.push_str("</table>\n");
    t
}

/// The verdicts with the guideline each comes from.
fn verdict_table(r: &CaseResult, g: &GravityVerdict, guideline: &Guideline) -> String {
    let ok = |b: bool| {
        if b {
            "<td class=\"pass\">pass</td>"
        } else {
            "<td class=\"fail\">FAIL</td>"
        }
    };
    let mut t = String::from(
        "<table><tr><th>verdict</th><th>value</th><th>limit</th><th></th><th>from</th></tr>\n",
    );
    let sliding_ok = g.sliding_fs.is_none_or(|v| v >= r.case.required_fs);
    let _ = writeln!(
        t,
        "<tr><td>sliding FS (N tan φ + c L w)/T, tan φ {}</td><td>{}</td><td>≥ {}</td>{}\
         <td>EM 1110-2-2100, {} category (Tables 3-2, 3-3)</td></tr>",
        n(g.tan_phi, 3),
        g.sliding_fs.map_or("unbounded".into(), |v| n(v, 3)),
        n(r.case.required_fs, 2),
        ok(sliding_ok),
        r.case.category.as_str()
    );
    // A faceted or sloping base: each face it could slide on, the least governing.
    let faces: Vec<_> = g.faces.iter().flatten().collect();
    if faces.len() > 1 || faces.iter().any(|f| f.dip_deg.abs() > 1e-9) {
        for f in faces {
            let _ = writeln!(
                t,
                "<tr><td>… on face {} (dip {}° towards {}°), pushed towards {}°</td><td>{}</td>\
                 <td></td><td></td><td>the whole base on the face's plane</td></tr>",
                f.face,
                n(f.dip_deg, 1),
                n(f.dip_direction_deg, 1),
                n(f.slide_trend_deg, 1),
                f.sliding_fs.map_or("unbounded".into(), |v| n(v, 3)),
            );
        }
    }
    let _ = writeln!(
        t,
        "<tr><td>base in compression (resultant {} m from the heel)</td><td>{} %</td>\
         <td>{}</td>{}<td>EM 1110-2-2100, resultant location</td></tr>",
        g.resultant_from_heel_m.map_or("—".into(), |v| n(v, 3)),
        n(g.base_in_compression_pct, 1),
        if g.required_compression_pct > 0.0 {
            format!("≥ {} %", n(g.required_compression_pct, 0))
        } else {
            "within the base".into()
        },
        ok(g.resultant_passes)
    );
    let max = g.heel_pressure_pa.max(g.toe_pressure_pa);
    let _ = writeln!(
        t,
        "<tr><td>base pressure, heel / toe</td><td>{} / {} kPa</td><td>{}</td>{}\
         <td>[check] allowable_bearing_pa</td></tr>",
        n(g.heel_pressure_pa / 1e3, 1),
        n(g.toe_pressure_pa / 1e3, 1),
        guideline
            .allowable_bearing_pa
            .map_or("none given".into(), |q| format!("≤ {} kPa", n(q / 1e3, 1))),
        match guideline.allowable_bearing_pa {
            Some(q) => ok(max <= q),
            None => "<td></td>",
        }
    );
    if g.overturns {
        t.push_str(
            "<tr><td colspan=\"5\" class=\"fail\">The resultant leaves the base: the monolith \
             tips.</td></tr>\n",
        );
    }
    t.push_str("</table>\n");
    t
}

/// The section to scale with its water, loads, uplift, crack and resultant (SVG, metres to
/// pixels at one scale for the whole drawing).
fn drawing(s: &Section, anchors: &[RockAnchor], r: &CaseResult, g: &GravityVerdict) -> String {
    let (b, h, c) = (s.base_length, s.height, s.crest_length);
    let water = r.loads.as_ref().and_then(|l| l.water.as_ref());
    let (h1, h2) = water.map_or((0.0, 0.0), |w| (w.levels.headwater, w.levels.tailwater));
    // The drawing spans from a reservoir strip upstream to past the toe, and from the uplift
    // diagram under the base to the top of the water or the crest.
    let reach = 0.35 * b.max(h);
    let top = h.max(h1) + 0.05 * h;
    let uplift_depth = 0.25 * h;
    let (x0, x1) = (-reach, b + reach);
    let (y0, y1) = (-uplift_depth - 0.05 * h, top);
    let width = 720.0;
    let k = width / (x1 - x0);
    let height = (y1 - y0) * k;
    let px = |x: f64| (x - x0) * k;
    let py = |y: f64| (y1 - y) * k;
    let mut d = String::new();
    let _ = write!(
        d,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{hh:.0}\" \
         viewBox=\"0 0 {w:.0} {hh:.0}\" role=\"img\" aria-label=\"the section with its loads\">\
         <defs>",
        w = width,
        hh = height
    );
    // One arrowhead a colour, 10 px whatever the line's width.
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
    // The rock, the water, the section.
    let _ = write!(
        d,
        "<rect x=\"0\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#e8e2d6\"/>",
        py(0.0),
        width,
        height - py(0.0)
    );
    if h1 > 0.0 {
        let _ = write!(
            d,
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#bcdcf2\"/>",
            px(x0),
            py(h1),
            px(0.0) - px(x0),
            py(0.0) - py(h1)
        );
    }
    if h2 > 0.0 {
        // Over the downstream face from the toe up to H2, then level downstream.
        let slope = (b - c) / h;
        let _ = write!(
            d,
            "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"#bcdcf2\"/>",
            px(b - slope * h2.min(h)),
            py(h2),
            px(x1),
            py(h2),
            px(x1),
            py(0.0),
            px(b),
            py(0.0)
        );
    }
    if let Some(silt) = water.filter(|w| w.silt.force_n > 0.0) {
        let depth = 3.0 * silt.silt.at_m;
        let _ = write!(
            d,
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"#a98f62\" \
             opacity=\"0.7\"/>",
            px(x0),
            py(depth),
            px(0.0) - px(x0),
            py(0.0) - py(depth)
        );
    }
    let _ = write!(
        d,
        "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"#c9c9c9\" \
         stroke=\"#555\" stroke-width=\"1.5\"/>",
        px(0.0),
        py(0.0),
        px(b),
        py(0.0),
        px(c),
        py(h),
        px(0.0),
        py(h)
    );
    // The uplift's head under the base, scaled so that the heel's head fills the band.
    let crack = g.crack_length_m;
    if let Some(w) = water {
        let (heads, _) = uplift_heads(s, &w.levels, crack);
        let scale = uplift_depth / h1.max(h2).max(f64::MIN_POSITIVE);
        let mut pts = format!("{:.1},{:.1}", px(0.0), py(0.0));
        for [x, head] in &heads {
            let _ = write!(pts, " {:.1},{:.1}", px(*x), py(-head * scale));
        }
        let _ = write!(pts, " {:.1},{:.1}", px(b), py(0.0));
        let _ = write!(
            d,
            "<polygon points=\"{pts}\" fill=\"#7fb3d5\" opacity=\"0.8\" stroke=\"#2b6a99\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\">uplift U = {} MN</text>",
            px(0.02 * b),
            py(-uplift_depth) + 14.0,
            n(g.uplift_n / 1e6, 2)
        );
    }
    if crack > 0.0 {
        let _ = write!(
            d,
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#c62828\" \
             stroke-width=\"4\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\" \
             fill=\"#c62828\">crack {} m</text>",
            px(0.0),
            py(0.0),
            px(crack.min(b)),
            py(0.0),
            px(0.0),
            py(0.0) - 6.0,
            n(crack, 2)
        );
    }
    // Forces as arrows: length in proportion to size, the largest a third of the drawing's
    // height.
    let loads = r.loads.as_ref();
    let biggest = [
        loads.map_or(0.0, |l| l.weight_n),
        g.normal_n.abs(),
        g.shear_n.abs(),
    ]
    .into_iter()
    .fold(f64::MIN_POSITIVE, f64::max);
    let len = |f: f64| (height / 3.0) * f / biggest;
    // An arrow from its tail (xa, ya) to its head, labelled at its tail: above a horizontal
    // one, beside a vertical one.
    let arrow = |xa: f64, ya: f64, xb: f64, yb: f64, label: String, colour: &str| {
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
    };
    if let (Some(l), Some(w)) = (loads, water) {
        // The reservoir's push on its line, ending at the face.
        let y = py(w.headwater.at_m);
        d.push_str(&arrow(
            px(0.0) - len(w.headwater.force_n),
            y,
            px(0.0),
            y,
            format!("P1 {} MN", n(w.headwater.force_n / 1e6, 2)),
            "#1f5f99",
        ));
        if w.tailwater.force_n > 0.0 {
            let y = py(w.tailwater.at_m);
            let xf = px(b - (b - c) / h * w.tailwater.at_m);
            d.push_str(&arrow(
                xf + len(w.tailwater.force_n).max(12.0),
                y,
                xf,
                y,
                format!("P2 {}", n(w.tailwater.force_n / 1e6, 2)),
                "#1f5f99",
            ));
        }
        // The weight from the centre of mass down.
        let yc = py(l.cm_height_m);
        let x_cm = s.mass_properties().cm_from_heel;
        d.push_str(&arrow(
            px(x_cm),
            yc,
            px(x_cm),
            yc + len(l.weight_n),
            format!("W {} MN", n(l.weight_n / 1e6, 2)),
            "#333333",
        ));
        if l.kh != 0.0 {
            d.push_str(&arrow(
                px(x_cm),
                yc,
                px(x_cm) + len(l.kh * l.weight_n),
                yc,
                format!("kh W {}", n(l.kh * l.weight_n / 1e6, 2)),
                "#8e44ad",
            ));
        }
    }
    // Each anchor: its tendon from the head down into the rock (dashed past the base), its pull
    // an arrow at the head along the tendon.
    for (k, a) in anchors.iter().enumerate() {
        let [x, y, _] = a.head;
        let dir = a.direction();
        let (dx, dy) = (dir.x, dir.y);
        let across = dy.abs().max(1e-9);
        let to_base = y / across;
        let into_rock = (uplift_depth / across)
            .min(a.free_length - to_base)
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
        let l = len(a.prestress).max(30.0);
        let norm = dx.hypot(dy).max(1e-12);
        d.push_str(&arrow(
            px(x),
            py(y),
            px(x) + l * dx / norm,
            py(y) - l * dy / norm,
            format!("A{k} {} MN", n(a.prestress / 1e6, 2)),
            "#2e7d32",
        ));
    }
    // The resultant where it meets the base.
    if let Some(at) = g.resultant_from_heel_m.filter(|a| a.is_finite()) {
        let x = px(at);
        let _ = write!(
            d,
            "<circle cx=\"{x:.1}\" cy=\"{:.1}\" r=\"4\" fill=\"#c62828\"/>",
            py(0.0)
        );
        d.push_str(&arrow(
            x,
            py(0.0) + len(g.normal_n.max(0.0)).min(py(y0) - py(0.0)),
            x,
            py(0.0),
            format!(
                "N {} MN, {} m from the heel",
                n(g.normal_n / 1e6, 2),
                n(at, 2)
            ),
            "#c62828",
        ));
    }
    // The middle third.
    let _ = writeln!(
        d,
        "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#555\" \
         stroke-dasharray=\"4 3\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"11\" fill=\"#555\">\
         middle third</text></svg>",
        px(b / 3.0),
        py(0.0) + 3.0,
        px(2.0 * b / 3.0),
        py(0.0) + 3.0,
        px(2.0 * b / 3.0) + 4.0,
        py(0.0) + 7.0
    );
    d
}
