//! Shared test helpers: scenes built from numbers, the hand-derived formulas typed from
//! `derivations/03-small-angle.md` and `derivations/04-exact.md`, and the paper's relations as
//! printed (`relations.rs`).

pub mod browser;
pub mod newmark;
pub mod relations;

use slideroute::Displacement;
use slideroute::Scene;
use std::f64::consts::SQRT_2;

/// A geometry-only scene. `l2x_frac`, `l1z_frac` are fractions of L.
pub fn scene(
    l: f64,
    l2x_frac: f64,
    l1z_frac: f64,
    xi_deg: f64,
    zeta_deg: f64,
    kappa_deg: f64,
) -> Scene {
    let l2x = l * l2x_frac;
    let l1z = l * l1z_frac;
    let text = format!(
        "name = \"test\"\n\
         [frame]\nl1x = {:e}\nl2x = {l2x:e}\nl1z = {l1z:e}\nl2z = {:e}\n\
         [foundation]\nxi_deg = {xi_deg:e}\nzeta_deg = {zeta_deg:e}\nkappa_deg = {kappa_deg:e}\n",
        l - l2x,
        l - l1z,
    );
    Scene::from_toml(&text, "<test>").unwrap_or_else(|e| panic!("test scene: {e}"))
}

/// The trigonometric quantities every hand formula uses.
pub struct Trig {
    pub l: f64,
    pub st: f64,
    pub ct: f64,
    /// sin, cos of φ = θ + κ.
    pub sp: f64,
    pub cp: f64,
    /// cot ξ, cot ζ.
    pub cx: f64,
    pub cz: f64,
    /// D = R − S = cos κ (L2X − X) + sin κ (L2Z + Z).
    pub dd: f64,
}

impl Trig {
    pub fn new(s: &Scene, d: Displacement) -> Self {
        let f = s.site().as_paper().unwrap().frame;
        let g = s.site().as_paper().unwrap().foundation;
        let (st, ct) = d.theta.sin_cos();
        let (sp, cp) = (d.theta + g.kappa).sin_cos();
        Trig {
            l: f.l1z + f.l2z,
            st,
            ct,
            sp,
            cp,
            cx: 1.0 / g.xi.tan(),
            cz: 1.0 / g.zeta.tan(),
            dd: g.kappa.cos() * (f.l2x - d.x) + g.kappa.sin() * (f.l2z + d.z),
        }
    }
}

/// A hand formula's value and its natural magnitude (the size of its largest terms), so that
/// comparisons of coefficients that pass through zero are judged against that magnitude.
pub struct Hand {
    pub value: f64,
    pub scale: f64,
}

/// f1–f12 by hand (re-derived; `derivations/03-small-angle.md`, "Result").
pub fn hand_small_angle(s: &Scene, d: Displacement) -> [Hand; 12] {
    let f = s.site().as_paper().unwrap().frame;
    let Trig {
        l,
        st,
        ct,
        sp,
        cp,
        cx,
        cz,
        dd,
    } = Trig::new(s, d);
    let b = d.x - f.l2x * (1.0 - ct);
    let e = dd - f.l2x * cp;
    let m = l + d.x.abs() + d.z.abs();
    let h = |value: f64, scale: f64| Hand { value, scale };
    [
        h(b * b - f.l1z.powi(2) * st * st, m * m),
        h(-2.0 * l * cx * b, l * cx * m),
        h(2.0 * SQRT_2 * f.l1z * (b * ct - f.l1z * st * st), f.l1z * m),
        h(l * l * cx * cx, l * l * cx * cx),
        h(-2.0 * SQRT_2 * l * f.l1z * ct * cx, l * f.l1z * cx),
        h(2.0 * f.l1z.powi(2), f.l1z.powi(2)),
        h(e * e - f.l2z.powi(2) * sp * sp, m * m),
        h(2.0 * SQRT_2 * l * cz * e, l * cz * m),
        h(2.0 * SQRT_2 * f.l2z * (e * cp - f.l2z * sp * sp), f.l2z * m),
        h(2.0 * l * l * cz * cz, l * l * cz * cz),
        h(4.0 * l * f.l2z * cp * cz, l * f.l2z * cz),
        h(2.0 * f.l2z.powi(2), f.l2z.powi(2)),
    ]
}

/// The printed (misprinted) f1, f2, f7, f11 of the paper, as printed but with 1.41 → √2.
pub fn printed_f1_f2_f7_f11(s: &Scene, d: Displacement) -> [f64; 4] {
    let f = s.site().as_paper().unwrap().frame;
    let Trig {
        l,
        st,
        ct,
        sp,
        cp,
        cx,
        cz,
        dd,
    } = Trig::new(s, d);
    [
        d.x * d.x + 2.0 * f.l2x * (ct - 1.0) * d.x + (f.l2x.powi(2) - f.l1z.powi(2)) * st * st,
        2.0 * l * cx * (f.l2x - d.x - ct * (f.l2x + f.l1z)),
        dd * dd - 2.0 * f.l2x * cp * dd + cp * cp * (-f.l2x + 2.0 * f.l2z).powi(2)
            - f.l2z.powi(2) * sp * sp,
        4.0 * l * f.l1z * cp * cz,
    ]
}

/// Exact (13), (14) coefficients by hand (`derivations/04-exact.md`, "Result"), by basis name.
pub fn hand_exact(s: &Scene, d: Displacement) -> [Vec<(&'static str, f64)>; 2] {
    let f = s.site().as_paper().unwrap().frame;
    let Trig {
        l,
        st,
        ct,
        sp,
        cp,
        cx,
        cz,
        dd,
    } = Trig::new(s, d);
    [
        vec![
            ("one", f.l2x - d.x),
            ("ca", -f.l2x * ct),
            ("cp", f.l1z * st),
            ("sa", l * cx),
            ("sa_sp", f.l1z * ct),
        ],
        vec![
            ("one", -dd),
            ("ca", f.l2x * cp),
            ("ca_sp", l * cz),
            ("cp", f.l2z * sp),
            ("sa", -l * cz),
            ("sa_sp", f.l2z * cp),
        ],
    ]
}

/// Every route row agrees with the direct pose solver at its (X, Z, θ): α, β to 1e-10 rad and
/// the CM height to 1e-9·L (each solve starts from the previous row's pose).
pub fn assert_rows_match_direct(s: &Scene, rows: &[slideroute::Row]) {
    use slideroute::internals::geometry::direct;
    let l = s.l();
    let mut near = None;
    for row in rows {
        let d = Displacement::new(row.x_m, row.z_m, row.theta_deg.to_radians());
        let p = match near {
            Some(ref q) => direct::solve_from(s.site(), d, q).unwrap(),
            None => direct::solve(s.site(), d).unwrap(),
        };
        // α: the tilt of x' (side 01 of the paper's frame); β: the elevation of side 02.
        let (alpha, beta) = match s.site().as_paper() {
            Some(_) => (p.alpha(l), p.beta(l)),
            None => {
                let c = s.site().contacts();
                let side02 = (c[2][0] - c[0][0]).hypot(c[2][1] - c[0][1]);
                (
                    p.tilt,
                    ((p.vertices[2].y - p.vertices[0].y) / side02).asin(),
                )
            }
        };
        assert!(
            (alpha.to_degrees() - row.alpha_deg).abs() < 1e-10f64.to_degrees(),
            "α at t = {}",
            row.t_s
        );
        assert!(
            (beta.to_degrees() - row.beta_deg).abs() < 1e-10f64.to_degrees(),
            "β at t = {}",
            row.t_s
        );
        assert!(
            (p.cm_y - row.y_m).abs() < 1e-9 * l,
            "CM height at t = {}",
            row.t_s
        );
        near = Some(p);
    }
}

/// `s` with each key set to its number, in the scene file's keys and units (validated as a file
/// is: a scene changes in no other way).
pub fn with(s: &Scene, keys: &[(&str, f64)]) -> Scene {
    s.with_keys(keys.iter().copied())
        .unwrap_or_else(|e| panic!("test scene: {e}"))
}

/// Draws `n` cases from `strategy` with a fixed seed.
pub fn sample<S: proptest::strategy::Strategy>(strategy: S, n: usize) -> Vec<S::Value> {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    (0..n)
        .map(|_| strategy.new_tree(&mut runner).expect("sample").current())
        .collect()
}

/// `scenes/paper-like.toml` on its planes tilted to 0.01° (κ = 0) with the push through the
/// centre of mass (no eccentricity): a level base in all but name, where closed forms hold.
pub fn paper_like_on_level_planes() -> String {
    std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like.toml"),
    )
    .unwrap()
    .replace("xi_deg = 20.0", "xi_deg = 0.01")
    .replace("zeta_deg = 25.0", "zeta_deg = 0.01")
    .replace("kappa_deg = 30.0", "kappa_deg = 0.0")
    .replace("eccentricity_m = 1.0", "eccentricity_m = 0.0")
}

/// `scenes/paper-like-faces.toml` held by friction (water 6 MN), its three points (the frame's
/// contacts), shaken by 1.9 s of filtered noise (`tests/reference/records/crease-chatter.csv`,
/// 0.6 g; the record's path absolute), at `dt_s` until `t_end_s`: contact 2 crosses between
/// the paper's planes 1 and 2 (12° between their normals), meets each again and again, and
/// rides their crease, while the record starts and stops the block.
pub fn crease_chatter_text(dt_s: &str, t_end_s: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(dir.join("scenes/paper-like-faces.toml"))
        .unwrap()
        .replace("hydraulic_force_n = 8.0e6", "hydraulic_force_n = 6.0e6")
        .replace(
            "dt_s = 1.0e-3",
            &format!("dt_s = {dt_s}\ncontacts = \"frame\""),
        )
        .replace("t_end_s = 20.0", &format!("t_end_s = {t_end_s}"))
        + &format!(
            "\n[seismic]\nrecord = \"{}\"\n",
            dir.join("tests/reference/records/crease-chatter.csv")
                .display()
        )
}
