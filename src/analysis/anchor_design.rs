//! `check --design-anchors`: the prestress a monolith's anchors need for each load case to
//! meet its guideline by the gravity method (`derivations/11-dam-loads.md` §10). The anchors
//! are those of `[[anchor]]`, where each is and which way it runs; the total prestress is
//! shared among them as their given prestresses are (equally where none is given), and the
//! least total that meets the requirement is found by a scan and bisection.

use super::check::{gravity_case, verdict};
use super::gravity_method::gravity_method;
use crate::model::LoadCase;
use crate::scene::{Scene, SceneError};

/// Steps of the scan over the total prestress, from 0 to [`REACH`] times the weight.
const SCAN: usize = 400;

/// The largest total prestress sought, as a multiple of the monolith's weight.
const REACH: f64 = 4.0;

/// What one load case needs of the anchors.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AnchorDesign {
    /// The case's name.
    pub case: String,
    /// Its required sliding factor of safety.
    pub required_fs: f64,
    /// The least total prestress (N) for the sliding factor to meet the requirement; `None`
    /// where no prestress up to four times the weight does (anchors that pull downstream).
    pub for_sliding_n: Option<f64>,
    /// The least total prestress (N) for every verdict — sliding, the resultant's limit, the
    /// allowable bearing stress; `None` where none up to four times the weight does.
    pub for_every_verdict_n: Option<f64>,
    /// Each anchor's share of `for_every_verdict_n` (N), in `[[anchor]]`'s order.
    pub per_anchor_n: Vec<f64>,
    /// Whether every share is within its anchor's capacity.
    pub within_capacity: bool,
}

/// The anchors' prestress each load case of `scene` needs (`[[case]]`, or the scene as written).
/// A scene without a monolith and its water, or without an anchor, is an error naming what it
/// lacks.
pub fn design_anchors(scene: &Scene) -> Result<Vec<AnchorDesign>, SceneError> {
    let anchors = scene.anchors();
    if anchors.is_empty() {
        return Err(SceneError::new(
            scene.origin(),
            "anchor",
            "designing anchors needs at least one [[anchor]]: where it is and which way it runs \
             (its prestress sets its share, or all share equally)",
        ));
    }
    let mut out = Vec::new();
    for case in super::check::cases_of(scene).iter() {
        out.push(design_case(scene, case)?);
    }
    Ok(out)
}

/// One case's design, each of its anchors taking the share of the total its prestress has
/// (equal shares where none has any).
fn design_case(scene: &Scene, case: &LoadCase) -> Result<AnchorDesign, SceneError> {
    let s = scene.for_case(case)?;
    let anchors = s.anchors();
    let given: f64 = anchors.iter().map(|a| a.prestress).sum();
    let shares: Vec<f64> = anchors
        .iter()
        .map(|a| {
            if given > 0.0 {
                a.prestress / given
            } else {
                1.0 / anchors.len() as f64
            }
        })
        .collect();
    // Where it starts is all the gravity method takes of a route: one increment of it.
    let dt = s.settings().map_or(1e-3, |r| r.dt);
    let start = s.with("solver.t_end_s", dt)?;
    let route = crate::route::Runner::new(&start.simulation()?).run().route;
    let Some(base) = gravity_case(&s, case.category, &route) else {
        return Err(SceneError::new(
            scene.origin(),
            "water",
            "designing anchors needs the gravity method: a [monolith] with its [water]",
        ));
    };
    let weight = base.section.mass_properties().mass * base.gravity;
    let with_total = |total: f64| {
        let mut c = base.clone();
        for (a, share) in c.anchors.iter_mut().zip(&shares) {
            a.prestress = total * share;
        }
        gravity_method(&c)
    };
    let required = case.required_fs;
    let sliding = |p: f64| with_total(p).sliding_fs.is_none_or(|fs| fs >= required);
    let every = |p: f64| verdict(&with_total(p), required, scene.guideline());
    let least = |meets: &dyn Fn(f64) -> bool| -> Option<f64> {
        let top = REACH * weight;
        if meets(0.0) {
            return Some(0.0);
        }
        let hi = (1..=SCAN)
            .map(|k| top * k as f64 / SCAN as f64)
            .find(|&p| meets(p))?;
        let (mut lo, mut hi) = (hi - top / SCAN as f64, hi);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if meets(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(hi)
    };
    let for_every = least(&every);
    let per_anchor: Vec<f64> = shares
        .iter()
        .map(|share| for_every.unwrap_or(0.0) * share)
        .collect();
    let within_capacity = for_every.is_some()
        && per_anchor
            .iter()
            .zip(&base.anchors)
            .all(|(p, a)| *p < a.capacity);
    Ok(AnchorDesign {
        case: case.name.clone(),
        required_fs: required,
        for_sliding_n: least(&sliding),
        for_every_verdict_n: for_every,
        per_anchor_n: per_anchor,
        within_capacity,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dam template with one anchor from its crest, plunging `plunge` degrees towards
    /// `trend`, of prestress `p`.
    fn anchored(plunge: f64, trend: f64, p: f64) -> Scene {
        let text = format!(
            "{}\n[[anchor]]\nx_m = 2.0\ny_m = 15.0\nplunge_deg = {plunge}\ntrend_deg = {trend}\n\
             prestress_n = {p}\ncapacity_n = 1.0e8\nfree_length_m = 200.0\nsteel_area_m2 = 4.0e-3\n",
            Scene::DAM_TOML
        );
        Scene::from_toml(&text, "dam").unwrap()
    }

    #[test]
    fn the_prestress_for_sliding_is_the_closed_form_on_an_uncracked_base() {
        // FS (N0 + P sin p) tan φ / (T0 + P cos p cos t) = required, uncracked, N0 and T0 with
        // no prestress: P = (F T0 − N0 tan φ) / (sin p tan φ − F cos p cos t).
        for (plunge, trend) in [(90.0, 0.0), (60.0, 180.0)] {
            let scene = anchored(plunge, trend, 0.0);
            let design = design_anchors(&scene).unwrap();
            let results = super::super::check::check_cases(&scene, |_| ()).unwrap();
            let quake = 3;
            let g = results[quake].gravity.unwrap();
            assert_eq!(g.crack_length_m, 0.0);
            let (p, t): (f64, f64) = (plunge.to_radians(), trend.to_radians());
            let f = design[quake].required_fs;
            let want = (f * g.shear_n - g.normal_n * g.tan_phi)
                / (p.sin() * g.tan_phi - f * p.cos() * t.cos());
            let got = design[quake].for_sliding_n.unwrap();
            assert!((got - want).abs() < 1e-9 * want, "{got} against {want}");
            // The cases that already pass need none.
            assert_eq!(design[0].for_sliding_n, Some(0.0));
            // At that prestress the case passes, a little under it not.
            let at = |total: f64| {
                let s = anchored(plunge, trend, total);
                super::super::check::check_cases(&s, |_| ()).unwrap()[quake]
                    .gravity
                    .unwrap()
                    .sliding_fs
                    .unwrap()
            };
            assert!(at(got * (1.0 + 1e-9)) >= f && at(got * 0.999) < f);
            // Every verdict asks at least what sliding does; the one anchor takes all of it,
            // within its capacity.
            let every = design[quake].for_every_verdict_n.unwrap();
            assert!(every >= got * (1.0 - 1e-12), "{every} under {got}");
            assert_eq!(design[quake].per_anchor_n, vec![every]);
            assert_eq!(design[quake].within_capacity, every < 1.0e8);
        }
    }

    #[test]
    fn anchors_that_pull_downstream_and_barely_down_cannot_bring_a_case_to_its_requirement() {
        // Plunging 5° downstream: each newton adds more to T than tan φ takes from it.
        let design = design_anchors(&anchored(5.0, 0.0, 1.0e6)).unwrap();
        assert_eq!(design[3].for_sliding_n, None);
        assert_eq!(design[3].for_every_verdict_n, None);
    }

    #[test]
    fn designing_anchors_without_any_is_an_error_naming_the_anchor() {
        let e = design_anchors(&Scene::from_toml(Scene::DAM_TOML, "dam").unwrap()).unwrap_err();
        assert_eq!(e.key, "anchor");
    }
}
