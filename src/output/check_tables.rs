//! `slideroute check`'s tables of load cases as it prints them: each case's levels, seismic
//! coefficients, water loads, factor of safety, requirement and verdict, as an engineer would
//! file it; and with `--design-anchors`, each case's prestress.

use crate::check::{CaseResult, GravityVerdict};
use crate::numeric::{fixed, seconds};
use std::fmt;

/// A case's value of a scene key it or the scene sets (the levels, the coefficients).
fn level(r: &CaseResult, f: impl Fn(&crate::LoadsUsed) -> f64) -> String {
    r.loads
        .as_ref()
        .map_or("—".into(), |l| fixed(f(l), 2).to_string())
}

/// The load multiple as a cell: three decimals, or the word.
fn fs_cell(r: &CaseResult) -> String {
    match r.factor_of_safety {
        Some(crate::FactorOfSafety::Finite { value }) => match r.run.route.factor_of_safety_limit {
            Some(limit) => format!("{} {}", fixed(value, 3), limit.as_str()),
            None => fixed(value, 3).to_string(),
        },
        Some(other) => other.cell(),
        None => "—".into(),
    }
}

/// A number of the gravity method's verdict, scaled and to `digits` decimals, or a dash.
fn gravity_cell(
    r: &CaseResult,
    f: impl Fn(&GravityVerdict) -> Option<f64>,
    digits: usize,
) -> String {
    r.gravity
        .as_ref()
        .and_then(f)
        .map_or("—".into(), |v| fixed(v, digits).to_string())
}

/// The horizontal load along the base (N): the gravity method's T, or the water's push and
/// kh W.
pub(crate) fn horizontal(r: &CaseResult) -> Option<f64> {
    match (&r.gravity, &r.loads) {
        (Some(g), _) => Some(g.shear_n),
        (None, Some(l)) => Some(l.hydraulic_force_n + l.kh * l.weight_n),
        _ => None,
    }
}

/// The tables, headed by the scene and the guideline.
pub(crate) struct CheckTable<'a> {
    pub scene: &'a str,
    pub guideline: String,
    pub results: &'a [CaseResult],
}

const LOADS: [&str; 13] = [
    "case",
    "category",
    "headwater m",
    "tailwater m",
    "kh",
    "kv",
    "W MN",
    "H MN",
    "U MN",
    "sliding FS",
    "required",
    "load multiple",
    "result",
];

const BASE: [&str; 8] = [
    "case",
    "resultant from heel m",
    "in compression %",
    "required %",
    "heel kPa",
    "toe kPa",
    "crack m",
    "tips",
];

impl CheckTable<'_> {
    fn loads(r: &CaseResult) -> Vec<String> {
        let water = |f: fn(&crate::WaterLoads) -> f64| {
            r.loads
                .as_ref()
                .and_then(|l| l.water.as_ref())
                .map_or("—".into(), |w| fixed(f(w), 2).to_string())
        };
        let uplift = r
            .gravity
            .map(|g| g.uplift_n)
            .or(r.loads.map(|l| l.uplift_n));
        let mn = |v: Option<f64>| v.map_or("—".into(), |v| fixed(v / 1e6, 2).to_string());
        let sliding = match r.gravity {
            Some(g) => g
                .sliding_fs
                .map_or("unbounded".into(), |v| fixed(v, 3).to_string()),
            None => "—".into(),
        };
        vec![
            r.case.name.clone(),
            r.case.category.as_str().to_string(),
            water(|w| w.levels.headwater),
            water(|w| w.levels.tailwater),
            level(r, |l| l.kh),
            level(r, |l| l.kv),
            mn(r.loads.map(|l| l.weight_n)),
            mn(horizontal(r)),
            mn(uplift),
            sliding,
            fixed(r.case.required_fs, 2).to_string(),
            fs_cell(r),
            if r.passes { "pass" } else { "FAIL" }.to_string(),
        ]
    }

    fn base(r: &CaseResult) -> Vec<String> {
        let kpa = |f: fn(&GravityVerdict) -> f64| gravity_cell(r, |g| Some(f(g) / 1e3), 1);
        vec![
            r.case.name.clone(),
            gravity_cell(r, |g| g.resultant_from_heel_m, 3),
            gravity_cell(r, |g| Some(g.base_in_compression_pct), 1),
            gravity_cell(r, |g| Some(g.required_compression_pct), 0),
            kpa(|g| g.heel_pressure_pa),
            kpa(|g| g.toe_pressure_pa),
            gravity_cell(r, |g| Some(g.crack_length_m), 3),
            r.gravity
                .map_or("—", |g| if g.overturns { "yes" } else { "no" })
                .to_string(),
        ]
    }
}

/// A table of `rows` under `head`, the first `left` columns aligned left.
fn table(
    f: &mut fmt::Formatter<'_>,
    head: &[&str],
    rows: &[Vec<String>],
    left: usize,
) -> fmt::Result {
    let width = |k: usize| {
        rows.iter()
            .map(|r| r[k].chars().count())
            .chain([head[k].chars().count()])
            .max()
            .unwrap_or(0)
    };
    let widths: Vec<usize> = (0..head.len()).map(width).collect();
    let line = |cells: &[String]| {
        let parts: Vec<String> = cells
            .iter()
            .zip(&widths)
            .enumerate()
            .map(|(k, (c, w))| {
                if k < left {
                    format!("{c:<w$}")
                } else {
                    format!("{c:>w$}")
                }
            })
            .collect();
        format!("  {}", parts.join("  "))
    };
    let head: Vec<String> = head.iter().map(|c| c.to_string()).collect();
    writeln!(f, "{}", line(&head))?;
    for r in rows {
        writeln!(f, "{}", line(r))?;
    }
    Ok(())
}

/// `check --design-anchors`: each case's least total prestress, for sliding and for every
/// verdict, and each anchor's share.
pub(crate) struct AnchorTable<'a>(pub &'a [crate::check::AnchorDesign]);

impl fmt::Display for AnchorTable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "  anchors: the least total prestress for each case to meet its guideline (shared \
             among the [[anchor]]s as their prestresses are)"
        )?;
        let mn = |v: Option<f64>| v.map_or("none".to_string(), |v| fixed(v / 1e6, 3).to_string());
        let rows: Vec<Vec<String>> = self
            .0
            .iter()
            .map(|d| {
                vec![
                    d.case.clone(),
                    fixed(d.required_fs, 2).to_string(),
                    mn(d.for_sliding_n),
                    mn(d.for_every_verdict_n),
                    d.per_anchor_n
                        .iter()
                        .map(|p| fixed(p / 1e6, 3).to_string())
                        .collect::<Vec<_>>()
                        .join(" "),
                    if d.for_every_verdict_n.is_none() {
                        "—"
                    } else if d.within_capacity {
                        "yes"
                    } else {
                        "NO"
                    }
                    .to_string(),
                ]
            })
            .collect();
        table(
            f,
            &[
                "case",
                "required",
                "for sliding MN",
                "for every verdict MN",
                "per anchor MN",
                "within capacity",
            ],
            &rows,
            1,
        )
    }
}

impl fmt::Display for CheckTable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "check {}: {}", self.scene, self.guideline)?;
        let rows: Vec<Vec<String>> = self.results.iter().map(Self::loads).collect();
        table(f, &LOADS, &rows, 2)?;
        let gravity: Vec<&CaseResult> = self
            .results
            .iter()
            .filter(|r| r.gravity.is_some())
            .collect();
        if !gravity.is_empty() {
            gravity_method(f, &gravity)?;
        }
        writeln!(
            f,
            "  load multiple: the driving loads' multiple the three contacts' friction cones hold \
             (H and its couples, kh W), with W, U and kv W as they are, and what gives there: \
             the block slides, or tips onto two contacts"
        )?;
        for r in self.results.iter().filter(|r| !r.passes) {
            failing(f, r)?;
        }
        Ok(())
    }
}

/// The gravity method's lines of the cases that have it: what the sliding factor is, each face
/// of a faceted or sloping base, and the resultant and base pressures.
fn gravity_method(f: &mut fmt::Formatter<'_>, gravity: &[&CaseResult]) -> fmt::Result {
    writeln!(
        f,
        "  sliding FS: (N tan φ + c L w)/T on the base, L its part in compression (the \
         guideline's gravity method{})",
        if gravity.iter().any(|r| r
            .loads
            .and_then(|l| l.water)
            .is_some_and(|w| w.levels.crack))
        {
            ", a crack let open where the base would be in tension"
        } else {
            ""
        }
    )?;
    for r in gravity {
        faces(f, r)?;
    }
    writeln!(
        f,
        "  resultant and base pressures (effective, compression positive):"
    )?;
    let rows: Vec<Vec<String>> = gravity.iter().map(|r| CheckTable::base(r)).collect();
    table(f, &BASE, &rows, 1)
}

/// A faceted or sloping base: the factor on each face under the monolith (nothing for one
/// level face).
fn faces(f: &mut fmt::Formatter<'_>, r: &CaseResult) -> fmt::Result {
    let Some(g) = r.gravity else { return Ok(()) };
    let faces: Vec<_> = g.faces.iter().flatten().collect();
    if faces.len() < 2 && faces.iter().all(|f| f.dip_deg.abs() < 1e-9) {
        return Ok(());
    }
    let each: Vec<String> = faces
        .iter()
        .map(|f| {
            format!(
                "face {} (dip {}° towards {}°) {}{}",
                f.face,
                fixed(f.dip_deg, 1),
                fixed(f.dip_direction_deg, 1),
                f.sliding_fs
                    .map_or("unbounded".to_string(), |v| fixed(v, 3).to_string()),
                if f.sliding_fs.is_some() {
                    format!(
                        ", pushed towards {}° plunging {}°",
                        fixed(f.slide_trend_deg, 1),
                        fixed(f.slide_plunge_deg, 1)
                    )
                } else {
                    String::new()
                }
            )
        })
        .collect();
    writeln!(
        f,
        "  {} slides on each face (the least governs): {}",
        r.case.name,
        each.join("; ")
    )
}

/// Why a failing case fails by the gravity method, and where its route went.
fn failing(f: &mut fmt::Formatter<'_>, r: &CaseResult) -> fmt::Result {
    if let Some(g) = &r.gravity {
        let mut why = Vec::new();
        if g.sliding_fs.is_some_and(|v| v < r.case.required_fs) {
            why.push("sliding".to_string());
        }
        if g.overturns {
            why.push("its resultant leaves the base: it tips".to_string());
        } else if !g.resultant_passes {
            why.push(format!(
                "{:.1} % of its base in compression, {} % asked",
                g.base_in_compression_pct, g.required_compression_pct
            ));
        }
        if why.is_empty() {
            why.push("its base pressure exceeds the allowable bearing stress".to_string());
        }
        writeln!(f, "  {} fails: {}", r.case.name, why.join("; "))?;
    }
    let t = &r.run.route.termination;
    let last = r.run.route.rows.last();
    if r.run.route.increments == 0 {
        if t.reason == crate::Reason::DoesNotSlide {
            return writeln!(
                f,
                "  {}: static friction holds the block at the start",
                r.case.name
            );
        }
        return writeln!(
            f,
            "  {}: the route ends at the start: {}: {}",
            r.case.name, t.reason, t.detail
        );
    }
    writeln!(
        f,
        "  {} slides: {} at t = {} s, travel {} m, yaw θ = {}°",
        r.case.name,
        t.reason,
        seconds(t.t_s),
        fixed(r.run.route.travel_m, 3),
        fixed(last.map_or(0.0, |l| l.theta_deg), 3)
    )?;
    for b in &r.run.route.anchors_broken {
        writeln!(
            f,
            "    anchor {} broke at its capacity at t = {} s",
            b.anchor,
            seconds(b.t_s)
        )?;
    }
    Ok(())
}
