//! `check`'s `report.html`: one self-contained page a reviewer reads or prints — per load case
//! the monolith's section drawn to scale with its water, its loads on their lines of action, the
//! uplift under the base, the crack and the resultant; the loads and the verdicts with the
//! guideline each comes from; then the scene as used and the manifest.

mod drawing;

use crate::RockAnchor;
use crate::Section;
use crate::check::{CaseResult, GravityVerdict, Guideline};
use drawing::drawing;
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
pub(crate) fn report(
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
