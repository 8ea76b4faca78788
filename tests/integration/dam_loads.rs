//! Dam loads in the engineer's terms: the monolith from its section, the water from
//! its levels, pseudo-static coefficients, and the guideline factor of safety, each against its
//! closed form on a level base (`derivations/11-dam-loads.md`).

use slideroute::internals::route;
use slideroute::internals::{model::DynamicsModel, scene::Scene};

fn monolith() -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/monolith.toml");
    std::fs::read_to_string(path).unwrap()
}

/// `text` with each (old, new) replaced, exactly once each.
fn edit(text: &str, edits: &[(&str, &str)]) -> String {
    edits.iter().fold(text.to_string(), |t, (a, b)| {
        assert_eq!(t.matches(a).count(), 1, "{a}");
        t.replace(a, b)
    })
}

/// The factor of safety at the start, as a number.
fn fs(text: &str) -> f64 {
    let s = Scene::from_toml(text, "dam")
        .unwrap()
        .with("solver.t_end_s", 0.01)
        .unwrap();
    let r = slideroute::run(&s).unwrap();
    r.factor_of_safety.and_then(|f| f.value()).unwrap()
}

const LEVEL: &str = "[[foundation.plane]]
dip_deg = 0.0
dip_direction_deg = 0.0
point_m = [0.0, 0.0, 0.0]";

const PAPERS_FLAT: &str = "xi_deg = 0.01
zeta_deg = 0.01
kappa_deg = 0.0";

/// The monolith of `scenes/monolith.toml` by hand: a 5 × 15 m rectangle and a 15 × 15 m right
/// triangle, 10 m wide, of concrete at 2400 kg/m³.
const W: f64 = 2400.0 * 9.81 * 10.0 * (75.0 + 112.5);

#[test]
fn on_a_level_base_the_factor_of_safety_is_mu_w_minus_u_over_h_with_and_without_drains() {
    // EM 1110-2-2100's sliding factor (N tan φ)/T with N = W − U: the reservoir of H1 m
    // pushes ½ γ H1² w; the uplift falls from γ H1 at the heel to 0 at the toe, or with drains
    // of efficiency E at X to H3 = (1 − E) H1 (b − X)/b there. No tailwater, no couple.
    let gamma = 1000.0 * 9.81;
    let (b, w, mu) = (20.0, 10.0, 0.45);
    for base in [LEVEL, PAPERS_FLAT] {
        for (h1, e) in [(14.0, 0.0), (14.0, 0.5), (10.0, 0.25)] {
            let text = edit(
                &monolith(),
                &[
                    ("eccentricity_m = 1.0 ", "eccentricity_m = 0.0 "),
                    ("tailwater_m = 2.0 ", "tailwater_m = 0.0 "),
                    ("headwater_m = 14.0 ", &format!("headwater_m = {h1} ")),
                    (
                        "drain_efficiency = 0.5 ",
                        &format!("drain_efficiency = {e} "),
                    ),
                    (
                        "[[foundation.plane]]\ndip_deg = 0.0\ndip_direction_deg = 0.0\npoint_m = [0.0, 0.0, 0.0]",
                        base,
                    ),
                ],
            );
            let h = 0.5 * gamma * h1 * h1 * w;
            let x = 2.0;
            let h3 = (1.0 - e) * h1 * (b - x) / b;
            let u = if e == 0.0 {
                0.5 * gamma * h1 * b * w
            } else {
                gamma * w * (x * (h1 + h3) / 2.0 + (b - x) * h3 / 2.0)
            };
            let want = mu * (W - u) / h;
            let got = fs(&text);
            assert!(
                (got - want).abs() < 5e-3 * want,
                "H1 {h1} m, E {e}: {got} against {want}"
            );
        }
    }
}

#[test]
fn pseudo_static_factor_of_safety_is_mu_one_minus_kv_over_kh() {
    // No water: the horizontal inertial force k_h W drives, the vertical k_v W lightens the
    // block; μ (1 − k_v) W / (k_h W) on 0.01° dips, with the block given by mass.
    let paper = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like.toml"),
    )
    .unwrap();
    for (kh, kv) in [(0.1, 0.0), (0.1, 0.05), (0.2, -0.1)] {
        let text = edit(
            &paper,
            &[
                ("xi_deg = 20.0", "xi_deg = 0.01"),
                ("zeta_deg = 25.0", "zeta_deg = 0.01"),
                ("kappa_deg = 30.0", "kappa_deg = 0.0"),
                ("hydraulic_force_n = 8.0e6", "hydraulic_force_n = 0.0"),
                ("eccentricity_m = 1.0", "eccentricity_m = 0.0"),
            ],
        ) + &format!("\n[seismic]\nkh = {kh}\nkv = {kv}\n");
        let want = 0.4 * (1.0 - kv) / kh;
        let got = fs(&text);
        assert!(
            (got - want).abs() < 5e-3 * want,
            "kh {kh}, kv {kv}: {got} against {want}"
        );
    }
}

#[test]
fn the_summary_echoes_the_loads_and_the_scene_as_used_reads_back() {
    let s = Scene::from_toml(&monolith(), "monolith").unwrap();
    let l = s.loads_used().unwrap();
    assert!((l.weight_n - W).abs() < 1e-9 * W);
    let water = l.water.unwrap();
    // Reservoir 14 m: ½ γ 14² w at 14/3 m; tailwater 2 m: ½ γ 2² w at 2/3 m.
    let gamma_w = 1000.0 * 9.81 * 10.0;
    assert!((water.headwater.force_n - 0.5 * gamma_w * 196.0).abs() < 1e-6);
    assert!((water.headwater.at_m - 14.0 / 3.0).abs() < 1e-12);
    assert!((l.hydraulic_force_n - 0.5 * gamma_w * (196.0 - 4.0)).abs() < 1e-6);
    // Drains: H3 = 2 + 0.5 · 12 · 18/20 = 7.4 m.
    assert!((water.drain_head_m - 7.4).abs() < 1e-12);
    let u = gamma_w * (2.0 * (14.0 + 7.4) / 2.0 + 18.0 * (7.4 + 2.0) / 2.0);
    assert!((l.uplift_n - u).abs() < 1e-6 * u);
    // The centre of mass: (75 · 7.5 + 112.5 · 5) / 187.5 = 6 m above the base.
    assert!((l.cm_height_m - 6.0).abs() < 1e-12);
    let text = toml::to_string(&s.as_used()).unwrap();
    let back = Scene::from_toml(&text, "echo").unwrap();
    assert_eq!(back.loads(), s.loads());
    assert_eq!(back.block(), s.block());
}

#[test]
fn dam_sections_that_do_not_fit_together_are_refused_naming_the_key() {
    let m = monolith();
    let cases: Vec<(String, &str, &str)> = vec![
        (
            m.replace(
                "[monolith]",
                "[block]\nmass_kg = 1e6\ninertia_kg_m2 = 1e7\n\n[monolith]",
            ),
            "monolith",
            "not both",
        ),
        (
            m.replace(
                "eccentricity_m = 1.0",
                "hydraulic_force_n = 8e6\neccentricity_m = 1.0",
            ),
            "loads.hydraulic_force_n",
            "remove",
        ),
        (
            m.replace("tailwater_m = 2.0", "tailwater_m = 15.0"),
            "water.tailwater_m",
            "at most the headwater",
        ),
        (
            m.replace("l1x = 6.0", "l1x = 8.0")
                .replace("l2x = 4.0", "l2x = 2.0"),
            "frame",
            "off the monolith's base",
        ),
        (
            m.replace("crest_length_m = 5.0", "crest_length_m = 25.0"),
            "monolith.crest_length_m",
            "at most the base length",
        ),
        (
            m.replace("drain_position_m = 2.0", "drain_position_m = 30.0"),
            "water.drain_position_m",
            "within the base",
        ),
        (
            m + "\n[seismic]\nrecord = \"motion.csv\"\n",
            "seismic.record",
            "motion.csv",
        ),
    ];
    for (text, key, why) in cases {
        let e = Scene::from_toml(&text, "dam").unwrap_err();
        assert_eq!(e.key, key, "{e}");
        assert!(e.to_string().contains(why), "{e}");
    }
    // Water needs the monolith.
    let paper = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like.toml"),
    )
    .unwrap()
    .replace("hydraulic_force_n = 8.0e6", "")
        + "\n[water]\nheadwater_m = 10.0\n";
    let e = Scene::from_toml(&paper, "dam").unwrap_err();
    assert_eq!(e.key, "water");
}

#[test]
fn check_gives_each_case_its_guideline_requirement_and_routes_it() {
    // scenes/monolith.toml's three cases: usual, unusual, extreme under a normal structure and
    // ordinary site information (1.5, 1.3, 1.1). The flood raises the uplift more than the
    // push and lowers the factor; the earthquake's kh W drives it under 1 and the block slides.
    let s = Scene::from_toml(&monolith(), "monolith").unwrap();
    let r = slideroute::check::check_cases(&s, |_| ()).unwrap();
    assert_eq!(r.len(), 3);
    let required: Vec<f64> = r.iter().map(|c| c.case.required_fs).collect();
    assert_eq!(required, [1.5, 1.3, 1.1]);
    let fs: Vec<f64> = r
        .iter()
        .map(|c| c.factor_of_safety.unwrap().value().unwrap())
        .collect();
    assert!(fs[0] > fs[1] && fs[1] > 1.0 && fs[2] < 1.0, "{fs:?}");
    assert_eq!(
        r.iter().map(|c| c.passes).collect::<Vec<_>>(),
        [true, true, false]
    );
    assert!(r[2].run.route.increments > 0 && r[2].run.route.travel_m > 1.0);
    assert_eq!(r[0].run.route.increments, 0);
    // The case's own levels reach its loads.
    let w = r[1].loads.unwrap().water.unwrap();
    assert_eq!((w.levels.headwater, w.levels.tailwater), (15.0, 5.0));
    assert_eq!(r[2].loads.unwrap().kh, 0.2);
}

#[test]
fn with_cohesion_the_factor_of_safety_is_mu_n_plus_c_a_over_t() {
    // EM 1110-2-2100's sliding factor with cohesion, (N tan φ + c A)/T: the base's 200 m² of
    // bonded joint share their cohesion among the contacts so that its resultant acts at the
    // base's centre, on the water's line (no eccentricity): no twist to hold.
    let gamma = 1000.0 * 9.81;
    let (b, w, mu, h1, h2) = (20.0, 10.0, 0.45, 14.0, 2.0);
    let with = |c: f64| {
        edit(
            &monolith(),
            &[
                ("eccentricity_m = 1.0 ", "eccentricity_m = 0.0 "),
                ("mu_k = 0.45", &format!("mu_k = 0.45\ncohesion_pa = {c}")),
            ],
        )
    };
    for c in [0.0, 25e3, 50e3] {
        let text = with(c);
        let h = 0.5 * gamma * (h1 * h1 - h2 * h2) * w;
        let v = 0.5 * gamma * h2 * h2 * w;
        let h3 = h2 + 0.5 * (h1 - h2) * (b - 2.0) / b;
        let u = gamma * w * (2.0 * (h1 + h3) / 2.0 + (b - 2.0) * (h3 + h2) / 2.0);
        let want = (mu * (W - u + v) + c * b * w) / h;
        let got = fs(&text);
        assert!(
            (got - want).abs() < 5e-3 * want,
            "c {c} Pa: {got} against {want}"
        );
    }
    // Stronger still, the driving loads scaled up tip the block over its downstream contacts
    // (the heel's normal force falls to zero) before they slide it: more cohesion adds nothing.
    let (strong, stronger) = (fs(&with(200e3)), fs(&with(1e6)));
    let sliding = (mu * 33.942e6 + 200e3 * b * w) / 9.418e6;
    assert!(strong < 0.6 * sliding, "{strong} against {sliding}");
    assert!(
        (strong - stronger).abs() < 1e-3 * strong,
        "{strong}, {stronger}"
    );
}

#[test]
fn each_face_carries_its_own_friction() {
    // The paper's planes at 0.01°, the push through the centre of mass: the normals are
    // (0.4, 0.1, 0.5) W (statics of the frame about its centre of mass). With μ = 0.3, 0.8,
    // 0.4 on planes 0, 1, 2 the three friction forces along −X have no moment about the centre
    // of mass (0.3·0.4·5 + 0.8·0.1·5 − 0.4·0.5·5 = 0), so every cone is used to its edge:
    // FS = Σ μ_i N_i / H = 0.4 W / H.
    let paper = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like.toml"),
    )
    .unwrap();
    let flat = edit(
        &paper,
        &[
            ("xi_deg = 20.0", "xi_deg = 0.01"),
            ("zeta_deg = 25.0", "zeta_deg = 0.01"),
            ("kappa_deg = 30.0", "kappa_deg = 0.0"),
            ("eccentricity_m = 1.0", "eccentricity_m = 0.0"),
            ("mu_k = 0.40", "mu_k = 0.3"),
        ],
    );
    let faces = "\n[[friction.face]]\nfaces = [1]\nmu_k = 0.8\n\
                 \n[[friction.face]]\nfaces = [2]\nmodel = \"coulomb\"\nmu_k = 0.4\n";
    let got = fs(&(flat.clone() + faces));
    let want = 0.4 * 9.81e6 / 8e6;
    assert!((got - want).abs() < 5e-3 * want, "{got} against {want}");
    // One entry for all three planes is [friction] itself.
    let all = fs(&(flat.clone() + "\n[[friction.face]]\nfaces = [0, 1, 2]\nmu_k = 0.4\n"));
    let plain = fs(&flat.replace("mu_k = 0.3", "mu_k = 0.4"));
    assert!((all - plain).abs() < 1e-9 * plain, "{all} against {plain}");
    // The route uses them too: on the paper's planes as given, a rougher plane 2 holds the
    // block longer.
    let run = |text: &str| {
        let s = Scene::from_toml(text, "faces")
            .unwrap()
            .with("solver.t_end_s", 2.0)
            .unwrap();
        slideroute::run(&s).unwrap().travel_m
    };
    let rough = run(&(paper.clone() + "\n[[friction.face]]\nfaces = [2]\nmu_k = 0.5\n"));
    let smooth = run(&paper);
    assert!(rough < smooth, "{rough} m against {smooth} m");
}

#[test]
fn strengths_the_scene_cannot_use_are_refused_naming_the_key() {
    let m = monolith();
    let paper = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like.toml"),
    )
    .unwrap();
    let cases: Vec<(String, &str, &str)> = vec![
        (
            m.clone() + "\n[[friction.face]]\nfaces = [1]\nmu_k = 0.5\n",
            "friction.face[0].faces",
            "face 1 does not exist",
        ),
        (
            m.clone() + "\n[[friction.face]]\nfaces = []\nmu_k = 0.5\n",
            "friction.face[0].faces",
            "empty",
        ),
        (
            m.clone() + "\n[[friction.face]]\nfaces = [0]\nmu_k = -0.5\n",
            "friction.face[0].mu_k",
            "zero or positive",
        ),
        (
            m.clone() + "\n[[friction.face]]\nfaces = [0]\njrc = 5.0\n",
            "friction.face[0].jrc",
            "unknown key",
        ),
        (
            m.replace("mu_k = 0.45", "mu_k = 0.45\ncohesion_pa = -1.0"),
            "friction.cohesion_pa",
            "zero or positive",
        ),
        (
            m.replace("mu_k = 0.45", "mu_k = 0.45\ncohesion_area_m2 = 5.0"),
            "friction.cohesion_area_m2",
            "without cohesion",
        ),
        (
            paper.replace("mu_k = 0.40", "mu_k = 0.40\ncohesion_pa = 1e5"),
            "friction.cohesion_area_m2",
            "bonded area",
        ),
        (
            paper.replace(
                "mu_k = 0.40",
                "mu_k = 0.40\ncohesion_pa = 1e5\ncohesion_area_m2 = 50.0",
            ) + "",
            "",
            "",
        ),
        (
            m.replace("l1x = 6.0", "l1x = 3.0")
                .replace("l2x = 4.0", "l2x = 7.0")
                .replace("l1z = 5.0 ", "l1z = 9.0 ")
                .replace("l2z = 5.0 ", "l2z = 1.0 ")
                .replace("width_m = 10.0", "width_m = 20.0")
                .replace("mu_k = 0.45", "mu_k = 0.45\ncohesion_pa = 1e5"),
            "friction.cohesion_pa",
            "outside the contact triangle",
        ),
    ];
    for (text, key, why) in cases {
        match Scene::from_toml(&text, "dam") {
            Err(e) => {
                assert_eq!(e.key, key, "{e}");
                assert!(e.to_string().contains(why), "{e}");
            }
            Ok(s) => {
                // Cohesion with an area reads; the paper's dynamics cannot use it.
                assert!(key.is_empty(), "{key}: read");
                let e = s.with_dynamics(DynamicsModel::Paper).unwrap_err();
                assert_eq!(e.key, "friction.cohesion_pa", "{e}");
            }
        }
    }
}

#[test]
fn cohesion_holds_a_block_until_it_first_slides() {
    // The monolith without water's uplift drains, cohesion enough to hold it: held at rest;
    // the same block set sliding (an initial velocity) has broken its bond and slides as
    // without cohesion.
    let held = edit(
        &monolith(),
        &[("mu_k = 0.45", "mu_k = 0.2\ncohesion_pa = 100e3")],
    );
    let s = Scene::from_toml(&held, "c").unwrap();
    let r = slideroute::run(&s).unwrap();
    assert_eq!(
        r.termination.reason,
        route::Reason::DoesNotSlide,
        "{:?}",
        r.termination
    );
    assert!(r.factor_of_safety.and_then(|f| f.value()).unwrap() > 1.0);
    // On its base too, when asked (a scene with cohesion keeps its frame unless told).
    let on_base = Scene::from_toml(&held, "c")
        .unwrap()
        .with("solver.contacts", "base")
        .unwrap();
    let r = slideroute::run(&on_base).unwrap();
    assert_eq!(r.termination.reason, route::Reason::DoesNotSlide);
    let kicked = |text: &str, contacts: &str| {
        let s = Scene::from_toml(&(text.to_string() + "\n[initial]\nvx_m_s = 1.0\n"), "k")
            .unwrap()
            .with("solver.t_end_s", 1.0)
            .and_then(|s| s.with("solver.contacts", contacts))
            .unwrap();
        slideroute::run(&s).unwrap()
    };
    for contacts in ["frame", "base"] {
        let with = kicked(&held, contacts);
        let without = kicked(&held.replace("cohesion_pa = 100e3", ""), contacts);
        assert_eq!(with.rows.last(), without.rows.last(), "{contacts}");
    }
    // The scene as used reads back as the same scene, cohesion and faces' own entries too.
    let faced = held.clone() + "\n[[friction.face]]\nfaces = [0]\ncohesion_pa = 5e4\n";
    let s = Scene::from_toml(&faced, "faced").unwrap();
    let echo = toml::to_string(&s.as_used()).unwrap();
    assert!(
        echo.contains("cohesion_area_m2") && echo.contains("[[friction.face]]"),
        "{echo}"
    );
    assert_eq!(Scene::from_toml(&echo, "faced").unwrap(), s);
}

#[test]
fn a_monolith_turning_about_its_raised_centre_of_mass_keeps_its_energy_balance() {
    // Newton–Euler about the centre of mass 6 m above the base, the loads' moments moved to it
    // and gravity's work taken at its height: the works, the kinetic energy and the potential
    // change close to round-off (a moment booked at the wrong point would not).
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/monolith-earthquake.toml");
    let s = Scene::from_file(&path)
        .unwrap()
        .with("solver.t_end_s", 3.0)
        .unwrap()
        .with("solver.contacts", "frame")
        .unwrap();
    let r = slideroute::run(&s).unwrap();
    let e = r.energy().unwrap();
    assert!(r.travel_m > 3.0, "{}", r.travel_m);
    assert!(
        e.residual_j.abs() < 1e-9 * e.work_hydraulic_j.abs(),
        "{e:?}"
    );
}

#[test]
fn check_gives_the_gravity_method_s_verdicts_of_a_hand_calculation_with_tailwater_drains_and_kh() {
    // scenes/monolith.toml by hand: a 5 m × 15 m rectangle (A 75 m², centroid 2.5, 7.5) and a
    // 15 m × 15 m triangle (A 112.5 m², centroid 10, 5): x̄ = 7 m, ȳ = 6 m, W = ρ g A w. Its
    // earthquake case: H1 = 14, H2 = 2, drains at 2 m 50 % efficient, kh 0.2, kv 0.05, μ 0.45.
    let s = Scene::from_toml(&monolith(), "monolith").unwrap();
    let r = slideroute::check::check_cases(&s, |_| ()).unwrap();
    let gamma = 1000.0 * 9.81 * 10.0;
    let (b, kh, kv) = (20.0, 0.2, 0.05);
    let p1 = 0.5 * gamma * 196.0;
    let p2 = 0.5 * gamma * 4.0;
    // The tailwater over the 1:1 downstream face: a triangle of legs 2 and 2, 2/3 m from the toe.
    let wt = 0.5 * gamma * 4.0;
    let h3 = 2.0 + 0.5 * 12.0 * 18.0 / 20.0;
    let (u1, u2) = (
        gamma * 2.0 * (14.0 + h3) / 2.0,
        gamma * 18.0 * (h3 + 2.0) / 2.0,
    );
    // Each trapezoid's centroid from the toe.
    let c1 = 20.0 - 2.0 * (14.0 + 2.0 * h3) / (3.0 * (14.0 + h3));
    let c2 = 18.0 - 18.0 * (h3 + 2.0 * 2.0) / (3.0 * (h3 + 2.0));
    let u = u1 + u2;
    let n = W * (1.0 - kv) + wt - u;
    let t = p1 - p2 + kh * W;
    let m = W * (1.0 - kv) * 13.0 - kh * W * 6.0 + wt * 2.0 / 3.0 + p2 * 2.0 / 3.0
        - p1 * 14.0 / 3.0
        - u1 * c1
        - u2 * c2;
    let a = m / n;
    let g = r[2]
        .gravity
        .expect("the gravity method on a monolith with its water");
    let close = |got: f64, want: f64, what: &str| {
        assert!(
            (got - want).abs() <= 1e-9 * want.abs(),
            "{what}: {got} against {want}"
        )
    };
    close(g.uplift_n, u, "U");
    close(g.normal_n, n, "N");
    close(g.shear_n, t, "T");
    close(g.sliding_fs.unwrap(), 0.45 * n / t, "sliding FS");
    close(g.resultant_from_heel_m.unwrap(), b - a, "resultant");
    assert!(a > b / 3.0, "uncracked: {a}");
    let e = b / 2.0 - a;
    close(
        g.heel_pressure_pa,
        n / (b * 10.0) * (1.0 - 6.0 * e / b),
        "heel",
    );
    close(
        g.toe_pressure_pa,
        n / (b * 10.0) * (1.0 + 6.0 * e / b),
        "toe",
    );
    assert_eq!((g.crack_length_m, g.base_in_compression_pct), (0.0, 100.0));
    assert!(!r[2].passes && r[0].passes);
    // An allowable bearing stress under the usual case's heel pressure fails it.
    let heel = r[0].gravity.unwrap().heel_pressure_pa;
    let strict = edit(
        &monolith(),
        &[(
            "site_information = \"ordinary\" #",
            &format!(
                "allowable_bearing_pa = {}\nsite_information = \"ordinary\" #",
                0.9 * heel
            ),
        )],
    );
    let r = slideroute::check::check_cases(&Scene::from_toml(&strict, "strict").unwrap(), |_| ())
        .unwrap();
    assert!(!r[0].passes);
    // The sliding factor is linear in tan φ at any φ, never capped by tipping.
    let at = |mu: f64| {
        let text = edit(&monolith(), &[("mu_k = 0.45", &format!("mu_k = {mu}"))]);
        let r = slideroute::check::check_cases(&Scene::from_toml(&text, "mu").unwrap(), |_| ())
            .unwrap();
        r[0].gravity.unwrap().sliding_fs.unwrap()
    };
    let base = at(0.4);
    for mu in [0.8, 1.2, 2.0] {
        close(at(mu), base * mu / 0.4, "linear in tan φ");
    }
}

#[test]
fn the_base_may_crack_unless_water_crack_is_false() {
    // `[water] crack`: true unless the scene says otherwise; false keeps the uncracked base.
    let levels = |text: &str| {
        Scene::from_toml(text, "dam")
            .unwrap()
            .loads()
            .unwrap()
            .water
            .unwrap()
            .levels
    };
    assert!(levels(&monolith()).crack);
    let off = edit(
        &monolith(),
        &[(
            "drain_position_m = 2.0 ",
            "drain_position_m = 2.0\ncrack = false ",
        )],
    );
    assert!(!levels(&off).crack);
    // The earthquake case at kh 0.7 puts the heel in tension: it cracks with the key, not
    // without it.
    let shaken = |crack: &str| {
        edit(
            &off,
            &[("crack = false", crack), ("kh = 0.2 ", "kh = 0.7 ")],
        )
    };
    let verdict = |text: &str| {
        let s = Scene::from_toml(text, "shaken").unwrap();
        slideroute::check::check_cases(&s, |_| ()).unwrap()[2]
            .gravity
            .unwrap()
    };
    let (open, shut) = (
        verdict(&shaken("crack = true")),
        verdict(&shaken("crack = false")),
    );
    assert!(open.crack_length_m > 0.0, "{open:?}");
    assert_eq!(shut.crack_length_m, 0.0);
    assert!(open.uplift_n > shut.uplift_n);
}

#[test]
fn silt_and_ice_push_on_the_upstream_face_as_computed_by_hand() {
    // Silt 5 m deep, γ′ 8000 N/m³, φ 30°: at rest K0 = 1 − sin 30° = ½, ½ K0 γ′ d² w =
    // 500 kN at 5/3 m. Ice 150 kN/m at 13.5 m over the 10 m width: 1.5 MN.
    let text = monolith()
        + "\n[silt]\ndepth_m = 5.0\nunit_weight_n_m3 = 8000.0\nfriction_angle_deg = 30.0\n\
           [ice]\nforce_n_m = 150.0e3\nelevation_m = 13.5\n";
    let s = Scene::from_toml(&text, "silted").unwrap();
    let w = s.loads().unwrap().water.unwrap();
    let close = |got: f64, want: f64, what: &str| {
        assert!(
            (got - want).abs() <= 1e-9 * want.abs(),
            "{what}: {got} against {want}"
        )
    };
    close(w.silt.force_n, 500e3, "silt");
    close(w.silt.at_m, 5.0 / 3.0, "silt's height");
    close(w.ice.force_n, 1.5e6, "ice");
    let gamma = 1000.0 * 9.81 * 10.0;
    let water = 0.5 * gamma * (196.0 - 4.0);
    // The route's push is the water's, the silt's and the ice's.
    close(
        s.loads().unwrap().hydraulic_force,
        water + 2.0e6,
        "the route's push",
    );
    let r = slideroute::check::check_cases(&s, |_| ()).unwrap();
    let plain =
        slideroute::check::check_cases(&Scene::from_toml(&monolith(), "m").unwrap(), |_| ())
            .unwrap();
    let (g, g0) = (r[0].gravity.unwrap(), plain[0].gravity.unwrap());
    close(g.shear_n, g0.shear_n + 2.0e6, "T");
    close(g.normal_n, g0.normal_n, "N");
    close(
        g.sliding_fs.unwrap(),
        0.45 * g.normal_n / g.shear_n,
        "sliding FS",
    );
    // Their moments about the toe move the resultant downstream by (S d/3 + I y)/N.
    let shift = (500e3 * 5.0 / 3.0 + 1.5e6 * 13.5) / g.normal_n;
    close(
        g.resultant_from_heel_m.unwrap() - g0.resultant_from_heel_m.unwrap(),
        shift,
        "the resultant's shift",
    );
    // A case may set them: no ice in the first.
    let cased = text.replace(
        "name = \"normal pool\"",
        "name = \"normal pool\"\nice_force_n_m = 0.0\nsilt_depth_m = 0.0",
    );
    let r =
        slideroute::check::check_cases(&Scene::from_toml(&cased, "c").unwrap(), |_| ()).unwrap();
    close(r[0].gravity.unwrap().shear_n, g0.shear_n, "no ice, no silt");
    // Refused: silt without water, silt over the reservoir.
    let dry = "[silt]\ndepth_m = 1.0\nunit_weight_n_m3 = 8000.0\nfriction_angle_deg = 30.0\n";
    let paper = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like.toml"),
    )
    .unwrap();
    assert_eq!(
        Scene::from_toml(&(paper + dry), "d").unwrap_err().key,
        "silt"
    );
    let deep = text.replace("depth_m = 5.0", "depth_m = 20.0");
    assert_eq!(
        Scene::from_toml(&deep, "d").unwrap_err().key,
        "silt.depth_m"
    );
}

#[test]
fn the_load_multiple_says_the_block_slides_under_low_friction_and_tips_under_high_with_its_closed_forms()
 {
    // On a level base, no tailwater, drains or couple: sliding gives μ (W − U)/H; tipping about
    // the line of contacts 1 and 2 (x' = +4 m, 11 m from the heel) gives
    // t = (W·4 − U (11 − b/3)) / (H·H1/3), U triangular from the heel.
    let gamma = 1000.0 * 9.81;
    let (b, w, h1) = (20.0, 10.0, 14.0);
    let h = 0.5 * gamma * h1 * h1 * w;
    let u = 0.5 * gamma * h1 * b * w;
    let tips = (W * 4.0 - u * (11.0 - b / 3.0)) / (h * h1 / 3.0);
    for (mu, want, limit) in [
        (0.45, 0.45 * (W - u) / h, slideroute::Limit::Slides),
        (1.2, tips, slideroute::Limit::Tips),
    ] {
        let text = edit(
            &monolith(),
            &[
                ("eccentricity_m = 1.0 ", "eccentricity_m = 0.0 "),
                ("tailwater_m = 2.0 ", "tailwater_m = 0.0 "),
                ("drain_efficiency = 0.5 ", "drain_efficiency = 0.0 "),
                ("mu_k = 0.45", &format!("mu_k = {mu}")),
            ],
        );
        let s = Scene::from_toml(&text, "dam")
            .unwrap()
            .with("solver.t_end_s", 0.01)
            .unwrap();
        let r = slideroute::run(&s).unwrap();
        let got = r.factor_of_safety.and_then(|f| f.value()).unwrap();
        assert!(
            (got - want).abs() < 1e-6 * want,
            "μ {mu}: {got} against {want}"
        );
        assert_eq!(r.factor_of_safety_limit, Some(limit), "μ {mu}");
    }
}

#[test]
fn on_a_base_sloping_up_downstream_the_sliding_factor_is_mu_w_cos_minus_u_over_h_minus_w_sin() {
    // One joint dipping α upstream: the monolith's base rises downstream by α. The water pushes
    // along the base (the section stands on it); the weight presses W cos α and resists
    // W sin α: FS = μ (W cos α − U)/(H − W sin α), uncracked, no tailwater or drains.
    let gamma = 1000.0 * 9.81;
    let (b, w, mu, h1) = (20.0, 10.0, 0.45, 14.0);
    for alpha_deg in [0.0f64, 5.0, 8.0] {
        let text = edit(
            &monolith(),
            &[
                ("tailwater_m = 2.0 ", "tailwater_m = 0.0 "),
                ("drain_efficiency = 0.5 ", "drain_efficiency = 0.0 "),
                (
                    "dip_deg = 0.0\ndip_direction_deg = 0.0",
                    &format!("dip_deg = {alpha_deg}\ndip_direction_deg = 180.0"),
                ),
            ],
        ) + "\n";
        let text = text.replace("[water]\n", "[water]\ncrack = false\n");
        // The scene as written, without its load cases.
        let text = &text[..text.find("[[case]]").unwrap()];
        let s = Scene::from_toml(text, "sloping").unwrap();
        let results = slideroute::check::check_cases(&s, |_| ()).unwrap();
        let g = results[0].gravity.unwrap();
        let a = alpha_deg.to_radians();
        let h = 0.5 * gamma * h1 * h1 * w;
        let u = 0.5 * gamma * h1 * b * w;
        let want = mu * (W * a.cos() - u) / (h - W * a.sin());
        let got = g.sliding_fs.unwrap();
        assert!(
            (got - want).abs() < 1e-9 * want,
            "α {alpha_deg}°: {got} against {want}"
        );
        // One face, its plane the base's.
        let f = g.faces[0].unwrap();
        assert!(g.faces[1].is_none() && f.dip_deg.abs() < 1e-9, "{f:?}");
    }
}

/// The uplift's force (N) and its moment about the toe (N·m) of a head profile linear between
/// `points` (x from the heel, head in m), over a base `b` long and `w` wide: trapezoid by
/// trapezoid.
fn uplift_by_hand(points: &[(f64, f64)], b: f64, w: f64) -> (f64, f64) {
    let gamma = 1000.0 * 9.81;
    points.windows(2).fold((0.0, 0.0), |(f, m), p| {
        let ((x0, h0), (x1, h1)) = (p[0], p[1]);
        let len = x1 - x0;
        if len <= 0.0 || h0 + h1 <= 0.0 {
            return (f, m);
        }
        let force = gamma * w * (h0 + h1) / 2.0 * len;
        let centroid = x0 + len * (h0 + 2.0 * h1) / (3.0 * (h0 + h1));
        (f + force, m + force * (b - centroid))
    })
}

#[test]
fn a_cracked_anchored_section_with_drains_tailwater_silt_ice_and_kh_meets_its_hand_calculation() {
    // A slender section nobody here had run: b = 16, h = 30, crest 4, 10 m wide; H1 26 m, H2 3 m,
    // drains of 50 % at 4 m, 5 m of silt (γ' 9 kN/m³, φ 30°), 100 kN/m of ice at 25.5 m,
    // k_h 0.1, k_v 0.05, one vertical anchor of 12 MN from the crest 1.5 m from the heel.
    // Its base cracks; everything below is the guideline's arithmetic, written out again.
    let (b, h, c, w) = (16.0, 30.0, 4.0, 10.0);
    let (h1, h2, e, xd) = (26.0, 3.0, 0.5, 4.0);
    let (kh, kv, mu) = (0.1, 0.05, 0.65);
    let (p_anchor, x_anchor) = (12.0e6, 1.5);
    let g = 9.81;
    let gamma = 1000.0 * g;
    let text = format!(
        r#"name = "slender"
[frame]
contacts_m = [[-5.0, 4.0], [9.0, 4.0], [9.0, -4.0]]
[foundation]
[[foundation.plane]]
dip_deg = 0.0
dip_direction_deg = 0.0
point_m = [0.0, 0.0, 0.0]
[monolith]
base_length_m = {b}
width_m = {w}
height_m = {h}
crest_length_m = {c}
density_kg_m3 = 2400.0
[water]
headwater_m = {h1}
tailwater_m = {h2}
density_kg_m3 = 1000.0
drain_efficiency = {e}
drain_position_m = {xd}
[silt]
depth_m = 5.0
unit_weight_n_m3 = 9000.0
friction_angle_deg = 30.0
[ice]
force_n_m = 100.0e3
elevation_m = 25.5
[seismic]
kh = {kh}
kv = {kv}
[loads]
eccentricity_m = 0.0
gravity_m_s2 = {g}
[friction]
model = "coulomb"
mu_k = {mu}
[solver]
mode = "exact"
dt_s = 1.0e-3
t_end_s = 0.01
[[anchor]]
x_m = {x_anchor}
y_m = {h}
prestress_n = {p_anchor}
capacity_n = 2.0e7
free_length_m = 40.0
steel_area_m2 = 8.0e-3
"#
    );
    let s = Scene::from_toml(&text, "slender").unwrap();
    let v = slideroute::check::check_cases(&s, |_| ()).unwrap()[0]
        .gravity
        .unwrap();

    // The section: a 4 × 30 rectangle and a 12 × 30 triangle.
    let (a1, a2) = (c * h, 0.5 * (b - c) * h);
    let weight = 2400.0 * g * w * (a1 + a2);
    let x_cm = (a1 * c / 2.0 + a2 * (c + (b - c) / 3.0)) / (a1 + a2);
    let y_cm = (a1 * h / 2.0 + a2 * h / 3.0) / (a1 + a2);
    // The pushes, the tailwater's wedge on the 12:30 face, silt at rest, ice.
    let p1 = 0.5 * gamma * h1 * h1 * w;
    let p2 = 0.5 * gamma * h2 * h2 * w;
    let slope = (b - c) / h;
    let v_tw = gamma * w * 0.5 * slope * h2 * h2;
    let x_tw = b - slope * h2 / 3.0;
    let k0 = 1.0 - 30f64.to_radians().sin();
    let silt = 0.5 * k0 * 9000.0 * 25.0 * w;
    let ice = 100.0e3 * w;
    let t_drive = p1 - p2 + silt + ice + kh * weight;
    // The loads but the uplift, about the toe (resisting positive), and their N.
    let n_rest = weight * (1.0 - kv) + v_tw + p_anchor;
    let m_rest =
        weight * (1.0 - kv) * (b - x_cm) - kh * weight * y_cm + v_tw * (b - x_tw) + p2 * h2 / 3.0
            - p1 * h1 / 3.0
            - silt * 5.0 / 3.0
            - ice * 25.5
            + p_anchor * (b - x_anchor);
    // The uplift with a crack `t` long from the heel: the reservoir's head in it, then the
    // drains' rule short of them (H3 over the uncracked b − t), linear to the toe past them.
    let uplift = |t: f64| {
        let points = if t < xd {
            let h3 = h2 + (1.0 - e) * (h1 - h2) * (b - xd) / (b - t);
            vec![(0.0, h1), (t, h1), (xd, h3), (b, h2)]
        } else {
            vec![(0.0, h1), (t, h1), (b, h2)]
        };
        uplift_by_hand(&points, b, w)
    };
    let at = |t: f64| {
        let (u, mu_toe) = uplift(t);
        let n = n_rest - u;
        (n, (m_rest - mu_toe) / n, u)
    };
    // Uncracked the resultant falls short of the middle third: the base cracks.
    assert!(at(0.0).1 < b / 3.0, "{:?}", at(0.0));
    // The crack's tip where 3 a = b − T: the first sign change on a fine scan, then bisection.
    let gap = |t: f64| 3.0 * at(t).1 - (b - t);
    let mut hi = (1..100_000)
        .map(|k| b * k as f64 / 100_000.0)
        .find(|&t| gap(t) >= 0.0)
        .expect("the crack stops short of the toe");
    let mut lo = hi - b / 100_000.0;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) >= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let t = hi;
    let (n, a, u) = at(t);
    let close = |got: f64, want: f64, what: &str| {
        assert!(
            (got - want).abs() <= 1e-6 * want.abs().max(1.0),
            "{what}: {got} against {want} by hand"
        );
    };
    close(v.crack_length_m, t, "crack length");
    close(v.uplift_n, u, "uplift");
    close(v.normal_n, n, "N");
    close(v.shear_n, t_drive, "T");
    close(v.sliding_fs.unwrap(), mu * n / t_drive, "sliding FS");
    close(
        v.resultant_from_heel_m.unwrap(),
        b - a,
        "resultant from the heel",
    );
    close(
        v.base_in_compression_pct,
        100.0 * (b - t) / b,
        "base in compression",
    );
    close(v.toe_pressure_pa, 2.0 * n / (3.0 * a * w), "toe pressure");
    assert_eq!(v.heel_pressure_pa, 0.0);
    assert!(
        t > 0.5 && t < xd,
        "the crack {t} m stops short of the drains"
    );
}

#[test]
fn an_inclined_anchor_above_the_base_adds_its_moment_about_the_tipping_line_to_the_load_multiple() {
    // The tipping multiple of the previous test with an anchor of 5 MN from the crest, 2 m from
    // the heel, plunging 60° upstream: its pull P (−cos 60°, −sin 60°) at (2, 15) m resists
    // about the line x = 11 m by (2 − 11)(−P sin 60°) − 15 (−P cos 60°). (Off the middle, at
    // z = 2 m, the contacts' friction gives first, a little earlier, sliding and turning.)
    let gamma = 1000.0 * 9.81;
    let (b, w, h1, p) = (20.0, 10.0, 14.0, 5.0e6);
    let h = 0.5 * gamma * h1 * h1 * w;
    let u = 0.5 * gamma * h1 * b * w;
    let (sin, cos) = 60f64.to_radians().sin_cos();
    let m_anchor = (2.0 - 11.0) * (-p * sin) - 15.0 * (-p * cos);
    let want = (W * 4.0 - u * (11.0 - b / 3.0) + m_anchor) / (h * h1 / 3.0);
    let text = edit(
        &monolith(),
        &[
            ("eccentricity_m = 1.0 ", "eccentricity_m = 0.0 "),
            ("tailwater_m = 2.0 ", "tailwater_m = 0.0 "),
            ("drain_efficiency = 0.5 ", "drain_efficiency = 0.0 "),
            ("mu_k = 0.45", "mu_k = 1.2"),
        ],
    ) + &format!(
        "\n[[anchor]]\nx_m = 2.0\ny_m = 15.0\nz_m = 0.0\nplunge_deg = 60.0\ntrend_deg = 180.0\n\
         prestress_n = {p}\ncapacity_n = 2.0e7\nfree_length_m = 40.0\nsteel_area_m2 = 4.0e-3\n"
    );
    let s = Scene::from_toml(&text, "dam")
        .unwrap()
        .with("solver.t_end_s", 0.01)
        .unwrap();
    for contacts in ["base", "frame"] {
        let s = s.with("solver.contacts", contacts).unwrap();
        let r = slideroute::run(&s).unwrap();
        let got = r.factor_of_safety.and_then(|f| f.value()).unwrap();
        assert!(
            (got - want).abs() < 1e-6 * want,
            "{contacts}: {got} against {want}"
        );
        assert_eq!(r.factor_of_safety_limit, Some(slideroute::Limit::Tips));
    }
}
