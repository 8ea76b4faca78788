//! The guideline's gravity method on a monolith's section (`derivations/11-dam-loads.md` §9):
//! the loads of a load case resolved on the base plane, the sliding factor of safety
//! (N tan φ + c L w)/T, the resultant's place on the base with the part of the base in
//! compression, the heel and toe pressures, and a base that cracks where it would be in
//! tension, its uplift raised in the crack, found by iteration — what EM 1110-2-2100 asks of a
//! gravity dam and CADAM computes. Two-dimensional by design: the section's plane, the base
//! level, the loads through the section (the route is the three-dimensional answer).

use nalgebra::Vector3;
use std::cmp::Ordering;

use crate::model::{
    Category, Friction, Levels, MassProperties, RockAnchor, Section, WaterLoads,
    water_loads_cracked,
};

/// What the gravity method needs of a case: the monolith, its water and coefficients, the
/// base's strength, its anchors.
#[derive(Debug, Clone)]
pub struct GravityCase {
    /// The monolith's section (its weight and centre of mass follow from it).
    pub section: Section,
    /// The case's water levels, drains, silt and ice, and whether the base may crack.
    pub levels: Levels,
    /// g (m/s²).
    pub gravity: f64,
    /// Pseudo-static coefficients (fractions of g): kh downstream, kv up.
    pub kh: f64,
    /// kv, up.
    pub kv: f64,
    /// The base's friction criterion (tan φ, at the mean stress on the part in compression for a
    /// stress-dependent one).
    pub friction: Friction,
    /// The base's cohesion c (Pa), on the part in compression.
    pub cohesion_pa: f64,
    /// The case's category (the resultant's limit).
    pub category: Category,
    /// Post-tensioned anchors, each at its prestress (`derivations/11-dam-loads.md` §10).
    pub anchors: Vec<RockAnchor>,
    /// The faces of the foundation under the monolith's contacts (at most three), each a plane
    /// it could slide on; none is the level base alone, with `friction`.
    pub faces: Vec<BaseFace>,
    /// The scene's axes in the base's at the start: the upward vertical Y and the downstream
    /// horizontal X, each as (x′, y′, z′). (0, 1, 0) and (1, 0, 0) for a level base; on a base
    /// that slopes the weight and k_h W have parts along and across it.
    pub up: [f64; 3],
    /// X in the base's axes.
    pub downstream: [f64; 3],
}

/// A face of the foundation under the monolith's contacts: its number, its upward unit normal
/// in the axes of the monolith's base at the start (x′ downstream, y′ up, z′ across) and its
/// friction criterion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaseFace {
    /// The face's number (`Row::faces`).
    pub face: u32,
    /// Its upward unit normal.
    pub normal: [f64; 3],
    /// Its friction criterion.
    pub friction: Friction,
    /// Its cohesion (Pa).
    pub cohesion_pa: f64,
}

/// Sliding on one face of a faceted base: the case's loads resolved on the face's plane, the
/// whole base on it (`derivations/11-dam-loads.md` §9).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FaceSliding {
    /// The face's number.
    pub face: u32,
    /// Its dip (degrees) and dip direction (degrees, from x′ towards z′).
    pub dip_deg: f64,
    /// Its dip direction.
    pub dip_direction_deg: f64,
    /// The loads' part pressing on the face (N).
    pub normal_n: f64,
    /// Their part along it (N).
    pub shear_n: f64,
    /// tan φ of the face's criterion.
    pub tan_phi: f64,
    /// (N tan φ + c A)/T on the face, A the base's part in compression over the face; `None`
    /// where nothing drives the block along it.
    pub sliding_fs: Option<f64>,
    /// Which way the loads push the block along the face: the trend of their part along it
    /// (degrees, from x′ towards z′) and its plunge (degrees below the horizontal).
    pub slide_trend_deg: f64,
    /// The plunge.
    pub slide_plunge_deg: f64,
}

/// The gravity method's verdicts on one case.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GravityVerdict {
    /// N: the resultant normal to the base, W (1 − kv) + the tailwater's weight − U (N).
    pub normal_n: f64,
    /// T: the resultant along the base, downstream: the pushes and kh W (N).
    pub shear_n: f64,
    /// U: the uplift (N), with the crack's.
    pub uplift_n: f64,
    /// The anchors' prestress, all of them (N; their parts along and across the base are in N
    /// and T).
    pub anchor_force_n: f64,
    /// (N tan φ + c L w)/T, L the base in compression: the least of the faces' (`faces`) where
    /// the case has them (T then the loads' part along each face, whichever way it points: an
    /// anchor pulling upstream hard enough drives the block upstream); else on the level base,
    /// `None` where T ≤ 0 (nothing drives the block downstream). 0 where N ≤ 0 (it floats).
    pub sliding_fs: Option<f64>,
    /// tan φ used.
    pub tan_phi: f64,
    /// Where the resultant meets the base, from the heel (m); `None` where N ≤ 0.
    pub resultant_from_heel_m: Option<f64>,
    /// The part of the base in compression (%): 100 with the resultant in the middle third,
    /// 3 a / b below it (a its distance from the toe), 0 outside the base.
    pub base_in_compression_pct: f64,
    /// Sliding on each face under the contacts (a faceted base), where the scene has them; the
    /// least of theirs is `sliding_fs`.
    pub faces: [Option<FaceSliding>; 3],
    /// What the case's category asks (%): usual 100, unusual 75, extreme a resultant within the
    /// base (any part in compression).
    pub required_compression_pct: f64,
    /// Whether the resultant meets its limit.
    pub resultant_passes: bool,
    /// The effective normal pressure at the heel and at the toe (Pa, compression positive).
    pub heel_pressure_pa: f64,
    /// At the toe.
    pub toe_pressure_pa: f64,
    /// The crack's length from the heel (m); 0 uncracked. The base's whole length where the
    /// resultant leaves the base (it would tip).
    pub crack_length_m: f64,
    /// True where the resultant leaves the base (or N ≤ 0): the monolith tips (or floats).
    pub overturns: bool,
}

/// The part of the base in compression a category asks for (%, EM 1110-2-2100's resultant
/// location: usual the whole base, unusual 75 %, extreme the resultant within the base).
pub fn required_compression(category: Category) -> f64 {
    match category {
        Category::Usual => 100.0,
        Category::Unusual => 75.0,
        Category::Extreme => 0.0,
    }
}

/// tan φ of `friction` at the mean normal stress `sigma` (Pa): μ for Coulomb; Barton–Choubey's
/// JRC log10(JCS/σ) + φ_r (capped as in the route).
fn tan_phi(friction: &Friction, sigma: f64) -> f64 {
    match *friction {
        Friction::BartonChoubey {
            contact_area_m2, ..
        } => friction.coefficient(sigma.max(f64::MIN_POSITIVE) * contact_area_m2),
        _ => friction.coefficient(1.0),
    }
}

/// The loads resolved at a crack of length `t`: (N, T, U, the moment about the toe of every
/// load, resisting positive, N·m).
fn resolve(c: &GravityCase, props: &MassProperties, t: f64) -> (f64, f64, f64, f64) {
    let s = &c.section;
    let b = s.base_length;
    let wl: WaterLoads = water_loads_cracked(s, &c.levels, c.gravity, t);
    let w = props.mass * c.gravity;
    let (xw, yw) = (props.cm_from_heel, props.cm_height);
    // The weight less k_v W, down, and k_h W, downstream, at the centre of mass, in the base's
    // axes: (F_x, F_y) in the section's plane.
    let body = |k: usize| -w * (1.0 - c.kv) * c.up[k] + c.kh * w * c.downstream[k];
    let (fx, fy) = (body(0), body(1));
    let normal = -fy + wl.tailwater_weight.force_n - wl.uplift.force_n;
    let shear = wl.headwater.force_n - wl.tailwater.force_n + wl.silt.force_n + wl.ice.force_n + fx;
    let moment = (xw - b) * fy - yw * fx
        + wl.tailwater_weight.force_n * (b - wl.tailwater_weight.at_m)
        + wl.tailwater.force_n * wl.tailwater.at_m
        - wl.headwater.force_n * wl.headwater.at_m
        - wl.silt.force_n * wl.silt.at_m
        - wl.ice.force_n * wl.ice.at_m
        - wl.uplift.force_n * (b - wl.uplift.at_m);
    // Each anchor pulls its prestress P along its tendon d from the head (x, y): P (−d_y) on
    // N, P d_x on T, and (x − b) P d_y − y P d_x about the toe. Its part across the section
    // (trend off the section's plane) enters only the faces' resultant (`on_face`).
    let (mut normal, mut shear, mut moment) = (normal, shear, moment);
    for a in &c.anchors {
        let d = a.direction() * a.prestress;
        let [x, y, _] = a.head;
        normal -= d.y;
        shear += d.x;
        moment += (x - b) * d.y - y * d.x;
    }
    (normal, shear, wl.uplift.force_n, moment)
}

/// The gravity method on case `c` (`derivations/11-dam-loads.md` §9).
///
/// Uncracked, the resultant N meets the base a = M_toe / N from the toe; the pressures are
/// N/(b w) (1 ± 6 e/b), e = b/2 − a, where a ≥ b/3, and 2 N/(3 a w) at the toe over 3 a where
/// not. Cracking, where a < b/3 the base opens from the heel to T with 3 a(T) = b − T (the
/// pressure at the crack's tip zero), the reservoir's full head in the crack: the smallest such
/// T, found by a scan and bisection; none below b (the resultant leaves the base) is a monolith
/// that tips.
pub fn gravity_method(c: &GravityCase) -> GravityVerdict {
    let (b, width) = (c.section.base_length, c.section.width);
    let props = c.section.mass_properties();
    let at = |t: f64| {
        let (n, shear, u, m) = resolve(c, &props, t);
        (n, shear, u, if n > 0.0 { m / n } else { f64::NEG_INFINITY })
    };
    let (n0, _, _, a0) = at(0.0);
    let (t, through) = if c.levels.crack && n0 > 0.0 && a0 < b / 3.0 {
        crack(b, |t| 3.0 * at(t).3 - (b - t))
    } else {
        (0.0, false)
    };
    let (n, shear, uplift, a) = at(t);
    let floats = n <= 0.0;
    let overturns = floats || through || a <= 0.0 || a >= b;
    // The base in compression: L from the toe.
    let compressed = if overturns {
        0.0
    } else if t > 0.0 {
        b - t
    } else {
        (3.0 * a).min(b).min(3.0 * (b - a))
    };
    let (heel, toe) = if overturns {
        (0.0, 0.0)
    } else {
        base_pressures(n, a, b, width, compressed)
    };
    let sigma = if compressed > 0.0 {
        n / (compressed * width)
    } else {
        0.0
    };
    let mut tan_phi = tan_phi(&c.friction, sigma);
    let mut sliding_fs = if shear <= 0.0 {
        None
    } else if floats {
        Some(0.0)
    } else {
        Some((n * tan_phi + c.cohesion_pa * compressed * width) / shear)
    };
    let faces = on_faces(c, &props, [shear, -n], compressed * width);
    if !c.faces.is_empty() {
        // A faceted base: the least factor of its faces governs.
        let least = faces
            .iter()
            .flatten()
            .filter(|f| f.sliding_fs.is_some())
            .min_by(|a, b| {
                a.sliding_fs
                    .partial_cmp(&b.sliding_fs)
                    .unwrap_or(Ordering::Equal)
            });
        sliding_fs = least.and_then(|f| f.sliding_fs);
        if let Some(f) = least {
            tan_phi = f.tan_phi;
        }
    }
    let pct = 100.0 * compressed / b;
    let required = required_compression(c.category);
    GravityVerdict {
        normal_n: n,
        shear_n: shear,
        uplift_n: uplift,
        anchor_force_n: c.anchors.iter().map(|a| a.prestress).sum(),
        sliding_fs,
        tan_phi,
        resultant_from_heel_m: (!floats).then_some(b - a),
        base_in_compression_pct: pct,
        required_compression_pct: required,
        resultant_passes: !overturns && pct >= required - 1e-9,
        heel_pressure_pa: heel,
        toe_pressure_pa: toe,
        crack_length_m: t,
        overturns,
        faces,
    }
}

/// The crack's length T on a base of length `b` where `gap(T)` = 3 a(T) − (b − T) changes sign
/// from negative at T = 0: the smallest such T, by a scan and bisection; `(b, true)` where no
/// crack short of the toe holds the resultant (cracked through, the reservoir's head under the
/// whole base).
fn crack(b: f64, gap: impl Fn(f64) -> f64) -> (f64, bool) {
    const SCAN: usize = 1000;
    let mut lo = 0.0;
    let hi = (1..SCAN).map(|k| b * k as f64 / SCAN as f64).find(|&x| {
        let found = gap(x) >= 0.0;
        if !found {
            lo = x;
        }
        found
    });
    let Some(mut hi) = hi else {
        return (b, true);
    };
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) >= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    (hi, false)
}

/// The pressures (Pa) at the heel and the toe of a base of length `b` and width `width` under
/// the normal force `n` meeting it `a` from the toe, `compressed` of it in compression: the
/// trapezoid N/(b w) (1 ± 6 e/b) where the whole base is, the triangle 2 N/(3 a w) at the end
/// nearer the resultant where not.
fn base_pressures(n: f64, a: f64, b: f64, width: f64, compressed: f64) -> (f64, f64) {
    if compressed >= b {
        let e = b / 2.0 - a;
        let mean = n / (b * width);
        (mean * (1.0 - 6.0 * e / b), mean * (1.0 + 6.0 * e / b))
    } else if a <= b / 2.0 {
        (0.0, 2.0 * n / (3.0 * a * width))
    } else {
        (2.0 * n / (3.0 * (b - a) * width), 0.0)
    }
}

/// Each upward face's sliding under the loads `[shear, −N]` in the section's plane and the
/// lateral force the anchors and the inclined weight give, the base's area in compression
/// `area` (m²) on it. A face that does not face up (a wall, an overhang) carries no base.
fn on_faces(
    c: &GravityCase,
    props: &MassProperties,
    [shear, down]: [f64; 2],
    area: f64,
) -> [Option<FaceSliding>; 3] {
    let lateral: f64 = c
        .anchors
        .iter()
        .map(|a| a.prestress * a.direction().z)
        .sum::<f64>()
        + props.mass * c.gravity * (-(1.0 - c.kv) * c.up[2] + c.kh * c.downstream[2]);
    let mut faces = [None; 3];
    let upward = c.faces.iter().filter(|f| f.normal[1] > 1e-6);
    for (slot, f) in faces.iter_mut().zip(upward) {
        *slot = Some(on_face(f, [shear, down, lateral], area));
    }
    faces
}

/// The loads `r` (N: the resultant on the monolith other than its supports', in the base's
/// axes) on face `f`'s plane, the whole base on it: N_f = −r·n, T_f = |r − (r·n) n|, the
/// base's area in compression `area` (m²) over the face A = area / n_y, and
/// FS = (N_f tan φ + c A)/T_f with the face's c (`derivations/11-dam-loads.md` §9).
fn on_face(f: &BaseFace, r: [f64; 3], area: f64) -> FaceSliding {
    let n = Vector3::from(f.normal);
    let r = Vector3::from(r);
    let normal = -r.dot(&n);
    let along = r + n * normal;
    let shear = along.norm();
    let face_area = area / n.y;
    let tan_phi = tan_phi(
        &f.friction,
        if face_area > 0.0 {
            normal / face_area
        } else {
            0.0
        },
    );
    let sliding_fs = if shear <= 1e-12 * r.norm() {
        None
    } else if normal <= 0.0 {
        Some(0.0)
    } else {
        let cohesion = if f.cohesion_pa > 0.0 {
            f.cohesion_pa * face_area
        } else {
            0.0
        };
        Some((normal * tan_phi + cohesion) / shear)
    };
    FaceSliding {
        face: f.face,
        dip_deg: n.y.clamp(-1.0, 1.0).acos().to_degrees(),
        dip_direction_deg: if n.x.hypot(n.z) > 1e-12 {
            n.z.atan2(n.x).to_degrees()
        } else {
            0.0
        },
        normal_n: normal,
        shear_n: shear,
        tan_phi,
        sliding_fs,
        slide_trend_deg: along.z.atan2(along.x).to_degrees(),
        slide_plunge_deg: if shear > 0.0 {
            (-along.y / shear).clamp(-1.0, 1.0).asin().to_degrees()
        } else {
            0.0
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = 9.81;
    const GAMMA: f64 = 1000.0 * G;

    /// A rectangle b × h of width w (crest = base), of density 2400, under `head` and no tailwater.
    fn rect(b: f64, h: f64, head: f64, crack: bool, category: Category) -> GravityCase {
        let section = Section {
            base_length: b,
            width: 1.0,
            height: h,
            crest_length: b,
            density: 2400.0,
        };
        GravityCase {
            section,
            levels: Levels {
                headwater: head,
                tailwater: 0.0,
                density: 1000.0,
                drain_efficiency: 0.0,
                drain_position: 0.0,
                crack,
                silt: None,
                ice: None,
            },
            gravity: G,
            kh: 0.0,
            kv: 0.0,
            friction: Friction::coulomb(0.7),
            cohesion_pa: 0.0,
            category,
            anchors: Vec::new(),
            faces: Vec::new(),
            up: [0.0, 1.0, 0.0],
            downstream: [1.0, 0.0, 0.0],
        }
    }

    #[test]
    fn on_a_face_dipping_downstream_the_loads_resolve_as_on_an_inclined_plane_by_hand() {
        // The level base's N and T on a face dipping δ towards +x′ (upward normal
        // (sin δ, cos δ, 0)): N_f = N cos δ − T sin δ, T_f = T cos δ + N sin δ, and the least
        // factor governs.
        let level = gravity_method(&rect(15.0, 20.0, 18.0, false, Category::Usual));
        let delta = 10f64.to_radians();
        let mut c = rect(15.0, 20.0, 18.0, false, Category::Usual);
        let flat = BaseFace {
            face: 0,
            normal: [0.0, 1.0, 0.0],
            friction: Friction::coulomb(0.7),
            cohesion_pa: 0.0,
        };
        let dipping = BaseFace {
            face: 3,
            normal: [delta.sin(), delta.cos(), 0.0],
            friction: Friction::coulomb(0.8),
            cohesion_pa: 0.0,
        };
        c.faces = vec![flat, dipping];
        let v = gravity_method(&c);
        let (n, t) = (level.normal_n, level.shear_n);
        let f0 = v.faces[0].unwrap();
        assert!((f0.sliding_fs.unwrap() - level.sliding_fs.unwrap()).abs() < 1e-12);
        let f1 = v.faces[1].unwrap();
        let nf = n * delta.cos() - t * delta.sin();
        let tf = t * delta.cos() + n * delta.sin();
        assert!((f1.normal_n - nf).abs() < 1e-9 * n && (f1.shear_n - tf).abs() < 1e-9 * n);
        let want = 0.8 * nf / tf;
        assert!((f1.sliding_fs.unwrap() - want).abs() < 1e-12, "{f1:?}");
        assert!((f1.dip_deg - 10.0).abs() < 1e-12 && f1.dip_direction_deg.abs() < 1e-12);
        // The block would slide down the dip: trend 0°, plunging below δ.
        assert!(f1.slide_trend_deg.abs() < 1e-9 && f1.slide_plunge_deg > 0.0);
        let least = want.min(level.sliding_fs.unwrap());
        assert!((v.sliding_fs.unwrap() - least).abs() < 1e-12);
        assert!(v.faces[2].is_none());
    }

    #[test]
    fn on_a_base_that_slopes_the_weight_has_parts_along_and_across_it_by_hand() {
        // A base rising downstream by α (i′ = (cos α, sin α, 0), j′ = (−sin α, cos α, 0)): Y in
        // its axes (sin α, cos α, 0), X (cos α, −sin α, 0). N = W cos α − U, T = P − W sin α,
        // M_toe with the weight's parts at the CM.
        let alpha = 8f64.to_radians();
        let mut c = rect(15.0, 20.0, 18.0, false, Category::Usual);
        c.up = [alpha.sin(), alpha.cos(), 0.0];
        c.downstream = [alpha.cos(), -alpha.sin(), 0.0];
        let v = gravity_method(&c);
        let w = 2400.0 * 300.0 * G;
        let p = 0.5 * GAMMA * 324.0;
        let u = 0.5 * GAMMA * 18.0 * 15.0;
        let (n, t) = (w * alpha.cos() - u, p - w * alpha.sin());
        assert!((v.normal_n - n).abs() < 1e-9 * n && (v.shear_n - t).abs() < 1e-9 * n);
        assert!((v.sliding_fs.unwrap() - 0.7 * n / t).abs() < 1e-12);
        // About the toe: W cos α at 7.5 m, W sin α (upstream) at 10 m up resists.
        let m = w * alpha.cos() * 7.5 + w * alpha.sin() * 10.0 - p * 6.0 - u * 10.0;
        assert!((v.resultant_from_heel_m.unwrap() - (15.0 - m / n)).abs() < 1e-9);
    }

    #[test]
    fn anchors_add_their_prestress_to_n_t_and_the_moment_about_the_toe_by_hand() {
        // The rectangle b = 15, h = 20 under 18 m, with a vertical anchor of 2 MN at the heel's
        // crest (x 1 m, y 20 m) and one of 1 MN from the base 2 m from the heel, plunging 60°
        // upstream: P (cos 60°·(−1), −sin 60°).
        let mut c = rect(15.0, 20.0, 18.0, false, Category::Usual);
        let vertical = RockAnchor {
            head: [1.0, 20.0, 0.0],
            plunge: std::f64::consts::FRAC_PI_2,
            trend: 0.0,
            prestress: 2.0e6,
            capacity: 3.0e6,
            free_length: 30.0,
            steel_area: 2.0e-3,
            modulus: 1.95e11,
        };
        let inclined = RockAnchor {
            head: [2.0, 0.0, 0.0],
            plunge: 60f64.to_radians(),
            trend: std::f64::consts::PI,
            prestress: 1.0e6,
            ..vertical
        };
        c.anchors = vec![vertical, inclined];
        let v = gravity_method(&c);
        let w = 2400.0 * 300.0 * G;
        let p = 0.5 * GAMMA * 324.0;
        let u = 0.5 * GAMMA * 18.0 * 15.0;
        let s3 = 3f64.sqrt();
        let n = w - u + 2.0e6 + 1.0e6 * s3 / 2.0;
        let t = p - 1.0e6 * 0.5;
        // About the toe: the vertical one's arm 14 m, the inclined one's line through (2, 0):
        // (x − b) F_y − y F_x = (−13)(−√3/2 MN).
        let m_toe = w * 7.5 - p * 6.0 - u * 10.0 + 2.0e6 * 14.0 + 13.0 * 1.0e6 * s3 / 2.0;
        assert!(
            (v.normal_n - n).abs() < 1e-9 * n,
            "{} against {n}",
            v.normal_n
        );
        assert!((v.shear_n - t).abs() < 1e-9 * t);
        assert!((v.sliding_fs.unwrap() - 0.7 * n / t).abs() < 1e-12);
        assert!((v.resultant_from_heel_m.unwrap() - (15.0 - m_toe / n)).abs() < 1e-9);
        assert_eq!(v.anchor_force_n, 3.0e6);
    }

    #[test]
    fn an_uncracked_rectangle_has_the_hand_calculated_resultant_pressures_and_sliding_factor() {
        // b = 15, h = 20, H1 = 18, no tailwater, no drains, 1 m wide: W = 2400·300·g at 7.5 m,
        // P = ½γ·18² at 6 m up, U = ½γ·18·15 at 5 m from the heel (10 m from the toe).
        let c = rect(15.0, 20.0, 18.0, false, Category::Usual);
        let v = gravity_method(&c);
        let w = 2400.0 * 300.0 * G;
        let p = 0.5 * GAMMA * 324.0;
        let u = 0.5 * GAMMA * 18.0 * 15.0;
        let n = w - u;
        let m_toe = w * 7.5 - p * 6.0 - u * 10.0;
        let a = m_toe / n;
        assert!((v.normal_n - n).abs() < 1e-9 * n);
        assert!((v.shear_n - p).abs() < 1e-9 * p);
        assert!((v.sliding_fs.unwrap() - 0.7 * n / p).abs() < 1e-12);
        assert!((v.resultant_from_heel_m.unwrap() - (15.0 - a)).abs() < 1e-9);
        // a = 5.26 m ≥ b/3: all in compression, e = b/2 − a.
        assert!(a > 5.0 && a < 7.5, "{a}");
        let e = 7.5 - a;
        let mean = n / 15.0;
        let (heel, toe) = (mean * (1.0 - 6.0 * e / 15.0), mean * (1.0 + 6.0 * e / 15.0));
        assert!((v.heel_pressure_pa - heel).abs() < 1e-9 * mean);
        assert!((v.toe_pressure_pa - toe).abs() < 1e-9 * mean);
        assert_eq!(v.base_in_compression_pct, 100.0);
        assert!(v.resultant_passes && !v.overturns);
        assert_eq!(v.crack_length_m, 0.0);
        // The same with the crack allowed: nothing cracks.
        assert_eq!(
            gravity_method(&rect(15.0, 20.0, 18.0, true, Category::Usual)),
            v
        );
    }

    #[test]
    fn the_sliding_factor_is_linear_in_tan_phi_and_in_cohesion() {
        let v = |mu: f64, c: f64| {
            let mut case = rect(15.0, 20.0, 18.0, false, Category::Usual);
            case.friction = Friction::coulomb(mu);
            case.cohesion_pa = c;
            gravity_method(&case).sliding_fs.unwrap()
        };
        let (f1, f2, f4) = (v(0.4, 0.0), v(0.8, 0.0), v(1.6, 0.0));
        assert!((f2 - 2.0 * f1).abs() < 1e-12 && (f4 - 4.0 * f1).abs() < 1e-12);
        let p = 0.5 * GAMMA * 324.0;
        assert!((v(0.4, 1e5) - f1 - 1e5 * 15.0 / p).abs() < 1e-12);
    }

    #[test]
    fn a_stress_dependent_criterion_takes_its_tan_phi_at_the_mean_stress_on_the_base() {
        // Barton–Choubey: tan(JRC log10(JCS/σ) + φ_r) at σ = N/(L w), by hand.
        let mut c = rect(15.0, 20.0, 18.0, false, Category::Usual);
        c.friction = Friction::barton_choubey(10.0, 50e6, 30f64.to_radians(), 2.0);
        let v = gravity_method(&c);
        let sigma = v.normal_n / 15.0;
        let want = (10.0 * (50e6 / sigma).log10() + 30.0).to_radians().tan();
        assert!(
            (v.tan_phi - want).abs() < 1e-12,
            "{} against {want}",
            v.tan_phi
        );
        assert!((v.sliding_fs.unwrap() - want * v.normal_n / v.shear_n).abs() < 1e-12);
    }

    #[test]
    fn a_cracked_base_opens_until_the_pressure_at_its_tip_is_zero_under_full_uplift_in_it() {
        // b = 10, h = 20, H1 = 18: uncracked the resultant is 2.12 m from the toe, under b/3.
        let plain = gravity_method(&rect(10.0, 20.0, 18.0, false, Category::Usual));
        assert!(
            plain.base_in_compression_pct < 100.0 && !plain.overturns,
            "{plain:?}"
        );
        assert_eq!(plain.heel_pressure_pa, 0.0);
        let v = gravity_method(&rect(10.0, 20.0, 18.0, true, Category::Usual));
        let t = v.crack_length_m;
        assert!(t > 4.0 && t < 5.0, "{v:?}");
        // By hand at that T: uplift 18 m over the crack, then linear to 0 at the toe.
        let w = 2400.0 * 200.0 * G;
        let p = 0.5 * GAMMA * 324.0;
        let u_crack = GAMMA * 18.0 * t;
        let u_rest = 0.5 * GAMMA * 18.0 * (10.0 - t);
        let u = u_crack + u_rest;
        let m_toe =
            w * 5.0 - p * 6.0 - u_crack * (10.0 - t / 2.0) - u_rest * (2.0 * (10.0 - t) / 3.0);
        let n = w - u;
        assert!((v.uplift_n - u).abs() < 1e-9 * u);
        let a = m_toe / n;
        // The crack's tip at the compressed part's end: 3 a = b − T.
        assert!((3.0 * a - (10.0 - t)).abs() < 1e-9, "a {a}, T {t}");
        assert!((v.toe_pressure_pa - 2.0 * n / (3.0 * a)).abs() < 1e-9 * v.toe_pressure_pa);
        assert_eq!(v.heel_pressure_pa, 0.0);
        assert!((v.base_in_compression_pct - 100.0 * (10.0 - t) / 10.0).abs() < 1e-9);
        // The crack's uplift lowers the sliding factor below the uncracked one.
        assert!(v.sliding_fs.unwrap() < plain.sliding_fs.unwrap());
        assert!(!v.resultant_passes);
    }

    #[test]
    fn a_monolith_whose_resultant_leaves_the_base_tips_and_says_so() {
        // b = 4 under 20 m of water on a 20 m block: the crack runs through.
        let v = gravity_method(&rect(4.0, 20.0, 20.0, true, Category::Extreme));
        assert!(v.overturns && !v.resultant_passes, "{v:?}");
        assert_eq!(v.crack_length_m, 4.0);
        assert_eq!(v.base_in_compression_pct, 0.0);
    }

    #[test]
    fn the_category_sets_the_part_of_the_base_in_compression_it_asks() {
        assert_eq!(required_compression(Category::Usual), 100.0);
        assert_eq!(required_compression(Category::Unusual), 75.0);
        assert_eq!(required_compression(Category::Extreme), 0.0);
        // 80 % in compression passes unusual, not usual.
        let mut c = rect(10.0, 20.0, 18.0, false, Category::Unusual);
        let pct = |c: &GravityCase| gravity_method(c).base_in_compression_pct;
        // Lower the water until the uncracked base is 75–100 % in compression.
        let head = (100..190)
            .map(|k| k as f64 / 10.0)
            .find(|&h| {
                c.levels.headwater = h;
                let p = pct(&c);
                (80.0..100.0).contains(&p)
            })
            .unwrap();
        c.levels.headwater = head;
        assert!(gravity_method(&c).resultant_passes);
        c.category = Category::Usual;
        assert!(!gravity_method(&c).resultant_passes);
    }
}
