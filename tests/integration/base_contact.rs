//! A block on its whole base (`contacts = "base"`) against closed forms: sliding down a plane
//! dipping downstream, held on one, a kicked block's stopping distance, a drop off a step and
//! the landing after it; every recorded row out of the ground by an independent check that
//! rebuilds the base from the row alone; no route ending at a three-point limit.

use nalgebra::{Matrix3, Rotation3, Vector3};
use slideroute::internals::geometry::penetration::{deepest, deepest_of};
use slideroute::internals::geometry::{BodyPose, Ground, cast};
use slideroute::internals::model::Contacts;
use slideroute::internals::route::{Reason, Route, Row};
use slideroute::internals::scene::Scene;
use std::path::{Path, PathBuf};

/// A 4 m × 4 m block of 1000 t (its frame's contacts at ±2 m), CM in its base, on `foundation`
/// (TOML), pushed by nothing, with μ and `[initial]` as given.
pub(crate) fn block_scene(foundation: &str, mu: f64, initial: &str, t_end: f64, dt: f64) -> String {
    format!(
        r#"
name = "base test"
[frame]
contacts_m = [[-2.0, 2.0], [2.0, 2.0], [2.0, -2.0]]
{foundation}
[block]
mass_kg = 1.0e6
inertia_kg_m2 = 2.6667e6
[loads]
hydraulic_force_n = 0.0
eccentricity_m = 0.0
gravity_m_s2 = 9.81
[friction]
model = "coulomb"
mu_k = {mu}
[solver]
mode = "exact"
dt_s = {dt}
t_end_s = {t_end}
{initial}
"#
    )
}

/// One plane through the origin, dipping `dip` degrees towards `direction` degrees.
pub(crate) fn plane(dip: f64, direction: f64) -> String {
    format!(
        "[foundation]\n[[foundation.plane]]\ndip_deg = {dip}\ndip_direction_deg = \
         {direction}\npoint_m = [0.0, 0.0, 0.0]\n"
    )
}

fn run(text: &str) -> Route {
    let scene = Scene::from_toml(text, "base test").unwrap();
    assert_eq!(scene.settings().unwrap().contacts, Contacts::Base);
    slideroute::run(&scene).unwrap()
}

pub(crate) fn travel_along(route: &Route) -> f64 {
    let (a, b) = (route.rows[0], *route.rows.last().unwrap());
    (b.x_m - a.x_m).hypot(b.y_m - a.y_m).hypot(b.z_m - a.z_m)
}

#[test]
fn a_block_on_a_plane_dipping_downstream_starts_on_it_and_slides_at_g_sin_less_mu_g_cos() {
    let (dip, mu, t) = (20f64.to_radians(), 0.2, 2.0);
    let a = 9.81 * (dip.sin() - mu * dip.cos());
    let exact = 0.5 * a * t * t;
    for dt in [2e-3, 1e-3, 5e-4] {
        let route = run(&block_scene(&plane(20.0, 0.0), mu, "", t, dt));
        assert_eq!(route.termination.reason, Reason::TimeLimit);
        // It rests on the plane before it moves: its base tilted by the dip, down along +X.
        let rest = &route.base().unwrap().resting;
        assert!((rest.tilt_deg - 20.0).abs() < 1e-9, "{}", rest.tilt_deg);
        let last = route.rows.last().unwrap();
        // Straight down the dip: no yaw, no sideways drift.
        assert!(
            last.theta_deg.abs() < 1e-9 && last.z_m.abs() < 1e-9,
            "{last:?}"
        );
        assert!((last.alpha_deg + 20.0).abs() < 1e-9, "{}", last.alpha_deg);
        // Flush on one plane the steps are extrapolated and held to the tolerance (1e-9 of
        // the base's size a step): the closed form to 1e-9 of the travel, whatever dt, the
        // interval of the rows only.
        let error = travel_along(&route) - exact;
        assert!(error.abs() < 1e-9 * exact, "dt {dt}: {error} of {exact}");
        let e = route.energy().unwrap();
        assert!(e.residual_j.abs() < 1e-8 * e.work_friction_j.abs(), "{e:?}");
    }
    // At τ = 1e-12 to 1e-12 of the travel.
    let tight = block_scene(&plane(20.0, 0.0), mu, "", t, 1e-3)
        .replace("[solver]", "[solver]\ntolerance = 1e-12");
    let error = travel_along(&run(&tight)) - exact;
    assert!(error.abs() < 1e-12 * exact, "{error} of {exact}");
}

#[test]
fn a_block_on_a_plane_dipping_less_than_its_friction_angle_rests_there() {
    let route = run(&block_scene(&plane(20.0, 0.0), 0.5, "", 1.0, 1e-3));
    assert_eq!(route.termination.reason, Reason::DoesNotSlide);
    let rest = &route.base().unwrap().resting;
    assert_eq!(rest.carrying.len(), 4, "{:?}", rest.carrying);
    let shares: f64 = rest.carrying.iter().map(|c| c.share).sum();
    // The shares carry the weight along Y: each normal is cos 20° up.
    assert!(
        (shares * 20f64.to_radians().cos() - 1.0).abs() < 1e-6,
        "{shares}"
    );
}

#[test]
fn a_kicked_block_on_level_ground_stops_where_friction_says() {
    let (v, mu, g) = (2.0, 0.4, 9.81);
    let route = run(&block_scene(
        &plane(0.0, 0.0),
        mu,
        &format!("[initial]\nvx_m_s = {v}"),
        3.0,
        1e-3,
    ));
    assert_eq!(route.termination.reason, Reason::Stopped);
    let (distance, time) = (v * v / (2.0 * mu * g), v / (mu * g));
    let last = route.rows.last().unwrap();
    // Flush on its plane it slides as the equation of the slide says, its stop located by
    // Newton's method: the closed form to round-off (`derivations/13-base-contact.md` §13).
    assert!(
        (last.x_m - distance).abs() < 1e-12,
        "{} against {distance}",
        last.x_m
    );
    assert!((route.termination.t_s - time).abs() <= 1e-12);
    // The friction work is the kinetic energy it took: booked at the mean of each step's slip
    // before and after, ½ P_t (u + u⁺), it is exact step by step (at the slip after alone it
    // was ½ (μ g h)² m a step off, 0.2 % here).
    let e = route.energy().unwrap();
    let kinetic = 0.5 * 1e6 * v * v;
    assert!(
        (e.work_friction_j + kinetic).abs() < 1e-7 * kinetic,
        "{e:?}"
    );
    assert!(e.residual_j.abs() < 1e-7 * kinetic, "{e:?}");
}

#[test]
fn a_block_kicked_against_a_push_it_cannot_hold_turns_back_where_it_comes_to_rest() {
    // Pushed along +X by 0.3 W with μ = 0.2 and kicked along −X: it slows at 0.5 g, comes to
    // rest exactly at the end of step 300, and, the push beyond what friction holds, slides
    // back at 0.1 g. At rest for an instant it is slow, but not held: it must not stop there.
    let (mu, g, h) = (0.2, 9.81, 1e-3);
    let v0 = 0.5 * g * 300.0 * h;
    let text = block_scene(
        &plane(0.0, 0.0),
        mu,
        &format!("[initial]\nvx_m_s = {}", -v0),
        1.0,
        h,
    )
    .replace(
        "hydraulic_force_n = 0.0",
        &format!("hydraulic_force_n = {}", 0.3 * 1e6 * g),
    );
    let route = run(&text);
    assert_eq!(route.termination.reason, Reason::TimeLimit);
    let back = 0.5 * 0.1 * g * 0.7 * 0.7;
    let want = -v0 * v0 / (2.0 * 0.5 * g) + back;
    let last = route.rows.last().unwrap();
    assert!(
        (last.x_m - want).abs() < 1e-12,
        "{} against {want}",
        last.x_m
    );
}

#[test]
fn a_block_pushed_along_level_rock_under_barton_choubey_slides_as_its_coefficient_at_its_stress_says()
 {
    // The 4 m square block, its CM in its base, on level rock under Barton–Choubey (JRC 10,
    // JCS 50 MPa, φr 30°), each contact standing for 2/3 m²: the area of each of the base's 24
    // quadrature points, over which the flush base presses evenly (nothing turns it: the push
    // and the friction both act in the plane of its CM), each at the base's mean stress
    // σ = W / A. Pushed through its CM by 1.5 times what friction at that stress holds, it
    // slides at a = 0.5 g μ(σ), μ(σ) = tan(JRC log10(JCS / σ) + φr) the criterion's own
    // coefficient there; and as a block under Coulomb's μ(σ) does, to the impulse solve's
    // tolerance. (Before, a base took Coulomb friction only.)
    let (g, t, h) = (9.81f64, 1.0, 1e-3);
    let w = 1e6 * g;
    let sigma = w / 16.0;
    let mu = (10.0 * (5.0e7 / sigma).log10() + 30.0).to_radians().tan();
    let pushed = |text: String, by: f64| {
        text.replace(
            "hydraulic_force_n = 0.0",
            &format!("hydraulic_force_n = {}", by * mu * w),
        )
    };
    let barton = |by: f64| {
        let text = pushed(block_scene(&plane(0.0, 0.0), mu, "", t, h), by)
            .replace(
                &format!("model = \"coulomb\"\nmu_k = {mu}"),
                "model = \"barton-choubey\"\njrc = 10.0\njcs_pa = 5.0e7\nphi_r_deg = 30.0\n\
                 contact_area_m2 = 0.6666666666666666",
            )
            .replace("[solver]", "[solver]\ncontacts = \"base\"");
        assert!(text.contains("barton-choubey"), "{text}");
        run(&text)
    };
    // Pushed by half of it, it is held.
    assert_eq!(barton(0.5).termination.reason, Reason::DoesNotSlide);
    let route = barton(1.5);
    assert_eq!(route.termination.reason, Reason::TimeLimit);
    // Flush on one plane, the steps extrapolated: ½ a t² to the tolerance.
    let exact = 0.5 * 0.5 * g * mu * t * t;
    let last = route.rows.last().unwrap();
    assert!(
        (last.x_m - exact).abs() < 1e-6 * exact,
        "{} against {exact}",
        last.x_m
    );
    assert!(
        last.z_m.abs() < 1e-9 && last.theta_deg.abs() < 1e-6,
        "{last:?}"
    );
    let coulomb = run(&pushed(block_scene(&plane(0.0, 0.0), mu, "", t, h), 1.5));
    let same = coulomb.rows.last().unwrap();
    assert!(
        (last.x_m - same.x_m).abs() < 1e-9 * exact,
        "{} against {} under Coulomb",
        last.x_m,
        same.x_m
    );
}

#[test]
fn a_block_twisted_beyond_its_beds_friction_turns_though_forces_at_its_corners_could_hold_it() {
    // A 4 m square base on level rock, μ = 0.4, pushed by 0.05 W with a couple of 8.3 MN·m
    // (17 m off its centre). Forces at its corners could hold a couple of μ W √2 a = 11.1 MN·m,
    // so a rigid equilibrium exists; but it presses evenly over its area, whose friction holds
    // μ W a (√2 + ln(1 + √2)) / 3 = 6.0 MN·m (derivations/13-base-contact.md §6, §9): it turns.
    let g = 9.81;
    let text = block_scene(&plane(0.0, 0.0), 0.4, "", 0.5, 1e-3)
        .replace(
            "hydraulic_force_n = 0.0",
            &format!("hydraulic_force_n = {}", 0.05 * 1e6 * g),
        )
        .replace("eccentricity_m = 0.0", "eccentricity_m = 17.0");
    let route = run(&text);
    assert_eq!(route.termination.reason, Reason::TimeLimit);
    let last = route.rows.last().unwrap();
    assert!(last.theta_deg.abs() > 1.0, "{last:?}");
}

#[test]
fn a_block_spun_on_level_rock_stops_as_friction_over_its_whole_base_says() {
    // A 4 m square base pressing evenly: the friction's moment about its centre is
    // μ m g ∫|r| dA / A = μ m g a (√2 + ln(1 + √2)) / 6, and the spin stops after turning
    // ω0² I / (2 T). The corners alone would give μ m g a / √2, turning it 46 % less.
    let (w0, mu, g, a, m, inertia) = (30f64.to_radians(), 0.4, 9.81, 4.0, 1e6, 2.6667e6);
    let torque = mu * m * g * a * (2f64.sqrt() + (1.0 + 2f64.sqrt()).ln()) / 6.0;
    let (turn, time) = (w0 * w0 * inertia / (2.0 * torque), w0 * inertia / torque);
    let route = run(&block_scene(
        &plane(0.0, 0.0),
        mu,
        &format!("[initial]\nomega_deg_s = {}", w0.to_degrees()),
        3.0,
        1e-3,
    ));
    // The quadrature's own error for |r| over the square is 0.2 %.
    assert_spun_in_place_and_stopped(&route, turn, time);
}

/// A block spun in place stopped after turning `turn` (rad, to 0.5 %) at `time` (s, to 2 ms),
/// its centre where it was.
fn assert_spun_in_place_and_stopped(route: &Route, turn: f64, time: f64) {
    assert_eq!(route.termination.reason, Reason::Stopped);
    let last = route.rows.last().unwrap();
    assert!(
        (last.theta_deg.abs() - turn.to_degrees()).abs() < 5e-3 * turn.to_degrees(),
        "turned {}° against {}°",
        last.theta_deg,
        turn.to_degrees()
    );
    assert!(
        (route.termination.t_s - time).abs() <= 2e-3,
        "{} against {time}",
        route.termination.t_s
    );
    assert!(last.x_m.hypot(last.z_m) < 1e-6, "{last:?}");
}

/// A surface level at Y = 0 over ±10 m (0.5 m cells, each two triangles) but for eight tips
/// 0.1 m high: four 0.5 m from the origin on the axes, four at (±1.5, ±1.5) m.
fn eight_tips(dir: &Path) -> PathBuf {
    let n = 41;
    let mut obj = String::new();
    for i in 0..n {
        for j in 0..n {
            let (x, z) = (-10.0 + 0.5 * i as f64, -10.0 + 0.5 * j as f64);
            let tip =
                (x.abs() + z.abs() == 0.5 && x * z == 0.0) || (x.abs() == 1.5 && z.abs() == 1.5);
            obj.push_str(&format!("v {x} {} {z}\n", if tip { 0.1 } else { 0.0 }));
        }
    }
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let v = |a: usize, b: usize| a * n + b + 1;
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            obj.push_str(&format!("f {a} {d} {c}\nf {a} {c} {b}\n"));
        }
    }
    let path = dir.join("tips.obj");
    std::fs::write(&path, obj).unwrap();
    path
}

#[test]
fn a_block_spun_on_eight_tips_of_rock_stops_as_equal_springs_at_them_say() {
    // A flat base on eight equal tips, four 0.5 m from its centre and four 1.5 √2 m: the rigid
    // body leaves their shares open (any that put the resultant at the centre); a uniform bed of
    // points, equal springs at the tips, shares the weight equally, W/8 each, and friction's
    // moment about the centre is μ m g (0.5 + 1.5 √2)/2; the spin stops after turning
    // ω0² I / (2 T). Springs in proportion to the tips' distance from the centre turn it 2.93°
    // where this says 4.07°.
    let dir = std::env::temp_dir().join(format!("slideroute-tips-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    eight_tips(&dir);
    let (w0, mu, g, m, inertia) = (30f64.to_radians(), 0.4, 9.81, 1e6, 2.6667e6);
    let torque = mu * m * g * (0.5 + 1.5 * 2f64.sqrt()) / 2.0;
    let (turn, time) = (w0 * w0 * inertia / (2.0 * torque), w0 * inertia / torque);
    let text = block_scene(
        "[foundation]\nsurface = \"tips.obj\"\n",
        mu,
        &format!("[initial]\nomega_deg_s = {}", w0.to_degrees()),
        3.0,
        1e-3,
    );
    let file = dir.join("tips.toml");
    std::fs::write(&file, text).unwrap();
    let scene = Scene::from_file(&file).unwrap();
    assert_eq!(scene.settings().unwrap().contacts, Contacts::Base);
    let route = slideroute::run(&scene).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_spun_in_place_and_stopped(&route, turn, time);
}

/// A surface: level at Y = 0 for X < 3, a face falling 0.3 m over 0.05 m, level at −0.3 beyond;
/// 40 m wide.
fn step_surface(dir: &Path) -> PathBuf {
    let xs = [(-10.0, 0.0), (3.0, 0.0), (3.05, -0.3), (40.0, -0.3)];
    let mut obj = String::new();
    for (x, y) in xs {
        for z in [-20.0, 20.0] {
            obj.push_str(&format!("v {x} {y} {z}\n"));
        }
    }
    for k in 0..3 {
        let (a, b, c, d) = (2 * k + 1, 2 * k + 2, 2 * k + 3, 2 * k + 4);
        obj.push_str(&format!("f {a} {b} {d}\nf {a} {d} {c}\n"));
    }
    let path = dir.join("step.obj");
    std::fs::write(&path, obj).unwrap();
    path
}

#[test]
fn a_block_sliding_off_a_step_drops_lands_and_slides_on_to_a_stop_out_of_the_rock() {
    let dir = std::env::temp_dir().join(format!("slideroute-step-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    step_surface(&dir);
    let text = block_scene(
        "[foundation]\nsurface = \"step.obj\"\n",
        0.2,
        "[initial]\nvx_m_s = 12.0",
        8.0,
        1e-3,
    );
    let file = dir.join("step.toml");
    std::fs::write(&file, text).unwrap();
    let scene = Scene::from_file(&file).unwrap();
    let route = slideroute::run(&scene).unwrap();
    assert_eq!(
        route.termination.reason,
        Reason::Stopped,
        "{:?}",
        route.termination
    );
    let last = route.rows.last().unwrap();
    // On the lower level, flat, past the step.
    assert!((last.y_m + 0.3).abs() < 1e-6, "{}", last.y_m);
    assert!(last.x_m > 3.05 + 2.0 && last.alpha_deg.abs() < 1e-6);
    // In the air for a while (rows with nothing carrying it), nose down, landing on its front
    // corners (1 and 2) alone before it comes down flat.
    assert!(route.rows.iter().any(|r| r.points_carrying == Some(0)));
    assert!(route.rows.iter().any(|r| r.alpha_deg < -1.0));
    assert!(route.rows.iter().any(|r| r.corners_carrying == Some(0b110)));
    // The energy: what it had and the drop, taken by friction and the landing's impacts, to
    // the step's first order.
    let e = route.energy().unwrap();
    let given = 0.5 * 1e6 * 144.0 + 1e6 * 9.81 * 0.3;
    assert!((e.potential_change_j + 1e6 * 9.81 * 0.3).abs() < 1e-3);
    assert!(e.residual_j.abs() < 0.01 * given, "{e:?}");
    assert_rows_out_of_ground(&scene, &route, 2e-6 * 4.0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_monolith_pushed_over_a_steps_edge_tips_once_its_centre_of_mass_is_past_it_by_its_height_times_a_over_g()
 {
    // The monolith of scenes/monolith.toml (20 m base, 15 m high, 5 m crest and 10 m wide:
    // ȳ = 6 m, 4.5e6 kg) pushed in its base plane by F = 1.3e7 N (μ 0.2) towards the
    // step at X = 3 m, its toe already over the lower level. Flush, it slides at
    // a = F/m − μg; about its centre of mass the push and the friction, both ȳ below it, turn
    // it by ȳ m a heel down, so the ground's resultant is ȳ a/g behind the centre of mass: the
    // heel lifts, the block turning about the edge, when the centre of mass is that far past
    // the edge.
    let dir = std::env::temp_dir().join(format!("slideroute-tip-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    step_surface(&dir);
    let text = r#"
name = "tip"
[frame]
l1x = 6.0
l2x = 4.0
l1z = 5.0
l2z = 5.0
[foundation]
surface = "step.obj"
[monolith]
base_length_m = 20.0
width_m = 10.0
height_m = 15.0
crest_length_m = 5.0
density_kg_m3 = 2400.0
[loads]
hydraulic_force_n = 1.3e7
eccentricity_m = 0.0
gravity_m_s2 = 9.81
[friction]
model = "coulomb"
mu_k = 0.20
[solver]
mode = "exact"
dt_s = 1.0e-3
t_end_s = 3.1
contacts = "base"
"#;
    let file = dir.join("tip.toml");
    std::fs::write(&file, text).unwrap();
    let route = slideroute::run(&Scene::from_file(&file).unwrap()).unwrap();
    let (g, mass, height): (f64, f64, f64) = (9.81, 187.5 * 10.0 * 2400.0, 6.0);
    let a = 1.3e7 / mass - 0.2 * g;
    let tips_at = 3.0 + height * a / g;
    // The tilt grows as the cube of the distance past that point (the edge's moment grows
    // with it): 1e-7°, ten times the flush block's, is reached within
    // 1.5 cm.
    let tilted = route
        .rows
        .iter()
        .position(|r| r.alpha_deg.abs() > 1e-7)
        .expect("it tips");
    let x = route.rows[tilted].x_m;
    assert!(
        x >= tips_at && x <= tips_at + 0.015,
        "it tips at X = {x} m, the closed form says {tips_at} m"
    );
    // Turning about the edge, nose down: a tenth of a degree by 0.3 s later.
    assert!(route.rows.last().unwrap().alpha_deg < -0.1);
    std::fs::remove_dir_all(&dir).ok();
}

/// Rebuilds the base at each row from the row alone — the point under the CM, the yaw and the
/// tilts of the frame's sides — and samples it densely against the ground.
fn assert_rows_out_of_ground(scene: &Scene, route: &Route, limit: f64) {
    let sim = scene.simulation().unwrap();
    let base = sim.first_body().base().unwrap();
    let ground: Ground = match scene.site().shared_ground() {
        Some(g) => (**g).clone(),
        None => Ground::planes(scene.site().planes().to_vec()),
    };
    let contacts = scene
        .site()
        .contacts()
        .map(|[x, z]| Vector3::new(x, 0.0, z));
    let mut relief: Option<Option<Vec<Vector3<f64>>>> = None;
    for row in &route.rows {
        let rotation = rebuild(row, &contacts);
        let under = Vector3::new(row.x_m, row.y_m, row.z_m);
        let pose = BodyPose {
            cm: under + rotation.column(1) * base.depth(),
            rotation,
        };
        // A cast base's underside is the ground under it where it rested (the first row).
        let relief = relief.get_or_insert_with(|| {
            base.is_cast()
                .then(|| cast(&ground, &base.triangles(), &pose).unwrap().samples(6))
        });
        let inside = match relief {
            Some(samples) => deepest_of(&ground, samples, &pose),
            None => deepest(&ground, base.outline(), base.depth(), &pose, 40),
        };
        assert!(inside <= limit, "t = {} s: {inside} m inside", row.t_s);
    }
}

/// The rotation with the row's yaw whose frame sides 0→1 and 0→2 rise at the row's α and β:
/// yaw θ, then a pitch and a roll found by Newton on the two elevations.
fn rebuild(row: &Row, c: &[Vector3<f64>; 3]) -> Matrix3<f64> {
    let yaw = Rotation3::from_axis_angle(&Vector3::y_axis(), -row.theta_deg.to_radians());
    let at = |p: f64, r: f64| {
        yaw * Rotation3::from_axis_angle(&Vector3::z_axis(), p)
            * Rotation3::from_axis_angle(&Vector3::x_axis(), r)
    };
    let elevation = |m: &Rotation3<f64>, a: usize, b: usize| {
        let d = m * (c[b] - c[a]);
        (d.y / d.norm()).asin()
    };
    let want = [row.alpha_deg.to_radians(), row.beta_deg.to_radians()];
    let (mut p, mut r) = (0.0, 0.0);
    for _ in 0..50 {
        let f = |p: f64, r: f64| {
            let m = at(p, r);
            [elevation(&m, 0, 1) - want[0], elevation(&m, 0, 2) - want[1]]
        };
        let f0 = f(p, r);
        let eps = 1e-7;
        let (fp, fr) = (f(p + eps, r), f(p, r + eps));
        let j = nalgebra::Matrix2::new(
            (fp[0] - f0[0]) / eps,
            (fr[0] - f0[0]) / eps,
            (fp[1] - f0[1]) / eps,
            (fr[1] - f0[1]) / eps,
        );
        let step = j.try_inverse().unwrap() * nalgebra::Vector2::new(f0[0], f0[1]);
        p -= step[0];
        r -= step[1];
        if step.norm() < 1e-14 {
            break;
        }
    }
    at(p, r).into_inner()
}

/// scenes/valley.toml on its surface with each triangle split in four at its sides' midpoints:
/// the same rock, in four times the triangles (1 m apart instead of 2 m); the scene in `dir`.
fn valley_split_in_four(dir: &Path) -> Scene {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let obj = std::fs::read_to_string(root.join("valley.obj")).unwrap();
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<[usize; 3]> = Vec::new();
    for line in obj.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first() {
            Some(&"v") => vertices.push([1, 2, 3].map(|k| w[k].parse().unwrap())),
            Some(&"f") => faces.push([1, 2, 3].map(|k| w[k].parse::<usize>().unwrap() - 1)),
            _ => {}
        }
    }
    let mut middles = std::collections::HashMap::new();
    let mut middle = |a: usize, b: usize, v: &mut Vec<[f64; 3]>| {
        *middles.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let (p, q) = (v[a], v[b]);
            v.push([0, 1, 2].map(|k| 0.5 * (p[k] + q[k])));
            v.len() - 1
        })
    };
    let mut split = Vec::new();
    for [a, b, c] in faces {
        let (ab, bc, ca) = (
            middle(a, b, &mut vertices),
            middle(b, c, &mut vertices),
            middle(c, a, &mut vertices),
        );
        split.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    let mut text = String::new();
    for [x, y, z] in &vertices {
        text.push_str(&format!("v {x:?} {y:?} {z:?}\n"));
    }
    for t in &split {
        text.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    std::fs::write(dir.join("valley-1m.obj"), text).unwrap();
    let scene = std::fs::read_to_string(root.join("valley.toml"))
        .unwrap()
        .replace("surface = \"valley.obj\"", "surface = \"valley-1m.obj\"");
    std::fs::write(dir.join("valley-1m.toml"), scene).unwrap();
    Scene::from_file(&dir.join("valley-1m.toml")).unwrap()
}

#[test]
fn a_base_on_the_same_rock_meshed_twice_as_finely_takes_the_same_route() {
    // The vertices inside a plane of the rock were touches of their own, each a point of a
    // flush patch or of a patch of points on a plane: a finer mesh of the same rock spread
    // friction and the support over more points and moved the route (at 3 s, 5.7 mm along X
    // and 0.086° of yaw between 2 m and 1 m triangles; 0.7 % of the whole route's travel).
    // A flat vertex is no touch now, and a flush patch keeps its hull's corners.
    let dir = std::env::temp_dir().join(format!("slideroute-valley-1m-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let coarse = Scene::from_file(&root.join("valley.toml")).unwrap();
    let fine = valley_split_in_four(&dir);
    let [coarse, fine] = [coarse, fine].map(|s| {
        let route = slideroute::run(&s.with("solver.t_end_s", 3.0).unwrap()).unwrap();
        *route.rows.last().unwrap()
    });
    assert_eq!((coarse.t_s, fine.t_s), (3.0, 3.0));
    let (dx, dz) = (fine.x_m - coarse.x_m, fine.z_m - coarse.z_m);
    assert!(dx.hypot(dz) < 1e-4, "{dx} {dz}");
    assert!(
        (fine.theta_deg - coarse.theta_deg).abs() < 1e-3,
        "{coarse:?} {fine:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_row_of_every_base_route_in_scenes_is_out_of_the_rock_and_ends_for_a_physical_reason() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut checked = 0;
    for name in ["four-faces", "ramp-faces", "paper-like-faces", "valley"] {
        let scene = Scene::from_file(&dir.join(format!("{name}.toml")))
            .unwrap()
            .with("solver.t_end_s", 3.0)
            .unwrap();
        assert_eq!(scene.settings().unwrap().contacts, Contacts::Base);
        let route = slideroute::run(&scene).unwrap();
        let three_point = [
            Reason::ContactLiftedOff,
            Reason::ContactOverRidge,
            Reason::Contact0ReachedInclinedPlane,
            Reason::ContactReachedAnotherFace,
            Reason::CreaseLetsGo,
            Reason::CreaseTakesOver,
        ];
        assert!(
            !three_point.contains(&route.termination.reason),
            "{name}: {:?}",
            route.termination
        );
        assert_physical_and_out_of_rock(name, &scene, &route);
        checked += 1;
    }
    assert_eq!(checked, 4);
}

#[test]
fn every_row_of_the_whole_body_scenes_is_out_of_the_rock_and_ends_for_a_physical_reason() {
    // A plane dipping downstream, a bump, a monolith over a step, a rough surveyed-style surface
    // and a block cast onto it, and a block cast onto rock rising downstream whose flat base is
    // first set down with its weight's line through two supports, and a slender monolith whose
    // set-down went back and forth between two poses 3 nm apart (scenes/body/,
    // crosscheck/make_terrain.py), 2 s each.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/body");
    for name in [
        "dip-faces",
        "bump",
        "monolith-step",
        "rough",
        "cast-rough",
        "cast-adverse",
        "slender",
    ] {
        let scene = Scene::from_file(&dir.join(format!("{name}.toml")))
            .unwrap()
            .with("solver.t_end_s", 2.0)
            .unwrap();
        let route = slideroute::run(&scene).unwrap();
        assert_physical_and_out_of_rock(name, &scene, &route);
        // The energy balance closes to the first-order step's error.
        let e = route.energy().unwrap();
        let work = e.work_hydraulic_j.abs().max(e.work_friction_j.abs());
        assert!(e.residual_j.abs() < 1e-3 * work, "{name}: {e:?}");
    }
}

/// A base route ends for a physical reason (no three-point limit), and no row's base is more
/// than 1e-6·L in the rock, by the solver's own report and by the base rebuilt from each row.
pub(crate) fn assert_physical_and_out_of_rock(name: &str, scene: &Scene, route: &Route) {
    assert!(
        matches!(
            route.termination.reason,
            Reason::TimeLimit | Reason::Stopped | Reason::Overturned | Reason::BaseOffGround
        ),
        "{name}: {:?}",
        route.termination
    );
    let l = scene.l();
    let report = route.base().unwrap();
    assert!(report.max_penetration_m <= 1e-6 * l, "{name}: {report:?}");
    assert_rows_out_of_ground(scene, route, 1e-6 * l);
}

#[test]
fn a_monolith_outline_is_read_from_the_heel_and_stands_its_centre_of_mass_high() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let text = std::fs::read_to_string(dir.join("monolith.toml")).unwrap();
    let text = text.replacen(
        "[solver]",
        "[base]\noutline_m = [[0.0, -5.0], [12.0, -5.0], [12.0, 5.0], [0.0, 5.0]]\n\n[solver]",
        1,
    );
    let scene = Scene::from_toml(&text, "monolith with an outline").unwrap();
    let sim = scene.simulation().unwrap();
    let base = sim.first_body().base().unwrap();
    // The section's centre of mass by hand, from the file's own dimensions.
    let monolith = scene.document()["monolith"].as_table().unwrap();
    let (b, h, c) = (
        monolith["base_length_m"].as_float().unwrap(),
        monolith["height_m"].as_float().unwrap(),
        monolith["crest_length_m"].as_float().unwrap(),
    );
    // A trapezoid heel (0, 0), toe (b, 0), crest (c, h), (0, h): x̄ = (b² + b c + c²) / (3 (b + c)),
    // ȳ = h (b + 2 c) / (3 (b + c)).
    let x_bar = (b * b + b * c + c * c) / (3.0 * (b + c));
    let y_bar = h * (b + 2.0 * c) / (3.0 * (b + c));
    assert!(
        (base.outline()[0][0] + x_bar).abs() < 1e-9,
        "{:?}",
        base.outline()
    );
    assert!((base.outline()[1][0] - (12.0 - x_bar)).abs() < 1e-9);
    assert!((base.depth() - y_bar).abs() < 1e-9, "{}", base.depth());
    assert!((base.area() - 120.0).abs() < 1e-9);
}

#[test]
fn a_monolith_climbing_a_six_degree_face_on_its_base_needs_no_tracker_and_keeps_its_balance() {
    // `scenes/monolith-earthquake.toml` with one more face rising at 6° along +X from
    // X = 4.5 m: on its three-point frame the tracker took about 850 steps an increment there
    // (a hop the model does not follow, an energy residual of 2.4e4 J over 3 s).
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let text = std::fs::read_to_string(dir.join("monolith-earthquake.toml")).unwrap();
    let face = "[[foundation.plane]]\ndip_deg = 6.0\ndip_direction_deg = 180.0\n\
                point_m = [4.5, 0.0, 0.0]\n\n[monolith]";
    let text = text.replacen("[monolith]", face, 1);
    let scene = Scene::from_toml(&text, "monolith onto a 6° face")
        .unwrap()
        .with("solver.t_end_s", 3.0)
        .unwrap();
    let sim = scene.simulation().unwrap();
    let computed = slideroute::Runner::new(&sim).run();
    let route = &computed.route;
    assert_eq!(route.termination.reason, Reason::TimeLimit);
    assert!(
        route.increments == 3000 && route.travel_m > 1.0,
        "{}",
        route.travel_m
    );
    // No pose system is tracked on a base: no tracker steps an increment, against 5 allowed.
    let tracked = computed.diagnostics.tracker.map_or(0, |t| t.steps);
    let steps = tracked as f64 / route.increments as f64;
    assert!(steps < 5.0, "{steps} tracker steps an increment");
    // Its base rests on the 6° face as well as the level one, and stays out of the rock.
    let report = route.base().unwrap();
    assert!(report.resting.tilt_deg > 1.0, "{}", report.resting.tilt_deg);
    assert!(report.max_penetration_m <= 1e-6 * scene.l());
    let e = route.energy().unwrap();
    assert!(
        e.residual_j.abs() < 1e-3 * e.work_hydraulic_j.abs(),
        "{e:?}"
    );
}

/// [`block_scene`] on level rock, pushed along X through its CM by `push` (N), with cohesion
/// `c` (Pa) over the base's 16 m² (zero: none), on `contacts`, for `t` s at 1 ms.
fn bonded_block(mu: f64, c: f64, push: f64, contacts: &str, t: f64) -> String {
    let cohesion = if c > 0.0 {
        format!("\ncohesion_pa = {c}\ncohesion_area_m2 = 16.0")
    } else {
        String::new()
    };
    block_scene(&plane(0.0, 0.0), mu, "", t, 1e-3)
        .replace(
            "hydraulic_force_n = 0.0",
            &format!("hydraulic_force_n = {push}"),
        )
        .replace(&format!("mu_k = {mu}"), &format!("mu_k = {mu}{cohesion}"))
        .replace("[solver]", &format!("[solver]\ncontacts = \"{contacts}\""))
}

fn run_on(text: &str) -> Route {
    let scene = Scene::from_toml(text, "bonded").unwrap();
    slideroute::run(&scene).unwrap()
}

#[test]
fn a_bonded_base_holds_a_push_up_to_friction_and_cohesion_over_its_area_and_then_slides_by_friction_alone()
 {
    // The 4 m square block (W = 9.81 MN, its CM in its base, A = 16 m²) on level rock of μ 0.4
    // and cohesion c = 0.2 W / A: Mohr–Coulomb over the base holds a push through the CM up to
    // μ W + c A = 0.6 W. At 0.99 of it the base is held; at 1.01 the bond breaks at once and
    // the block slides at (0.606 − 0.4) g, as the same block without cohesion does, step for
    // step. The frame (three points sharing the same area, `derivations/11-dam-loads.md` §8)
    // holds and lets go at the same push.
    let (mu, g, t) = (0.4, 9.81, 1.0);
    let w = 1e6 * g;
    let c = 0.2 * w / 16.0;
    let limit = mu * w + c * 16.0;
    for contacts in ["base", "frame"] {
        let held = run_on(&bonded_block(mu, c, 0.99 * limit, contacts, t));
        assert_eq!(
            held.termination.reason,
            Reason::DoesNotSlide,
            "{contacts}: {}",
            held.termination.detail
        );
        let slid = run_on(&bonded_block(mu, c, 1.01 * limit, contacts, t));
        assert_ne!(slid.termination.reason, Reason::DoesNotSlide, "{contacts}");
        if contacts == "frame" {
            // The frame's three points (one corner of the square left out) then tip: what it
            // says is only that the bond does not hold.
            continue;
        }
        assert_eq!(slid.termination.reason, Reason::TimeLimit, "{contacts}");
        let plain = run_on(&bonded_block(mu, 0.0, 1.01 * limit, contacts, t));
        let (x, x0) = (
            slid.rows.last().unwrap().x_m - slid.rows[0].x_m,
            plain.rows.last().unwrap().x_m - plain.rows[0].x_m,
        );
        let a = (1.01 * limit / w - mu) * g;
        // Flush on one plane, the steps extrapolated: ½ a t² to the tolerance.
        let exact = 0.5 * a * t * t;
        assert!(
            (x - exact).abs() < 1e-6 * exact,
            "{contacts}: {x} m against {exact} m"
        );
        assert!(
            (x - x0).abs() <= 1e-12 * exact,
            "{contacts}: {x} m with cohesion, {x0} m without"
        );
        assert_eq!(held.base().unwrap().bond_broken_s, None);
        assert_eq!(slid.base().unwrap().bond_broken_s, Some(0.0));
        assert_eq!(plain.base().unwrap().bond_broken_s, None);
    }
    // Each touch takes the cohesion of its face: face 0, under the whole base, with its own
    // entry holds with it where the default has none, and without it where the default has it.
    let bonded = bonded_block(mu, c, 0.99 * limit, "base", t);
    let face = |default: f64, own: f64| {
        let text = bonded.replace(
            &format!("cohesion_pa = {c}\n"),
            &format!("cohesion_pa = {default}\n"),
        );
        assert!(
            text.contains(&format!("cohesion_pa = {default}\n")),
            "{text}"
        );
        run_on(&(text + &format!("\n[[friction.face]]\nfaces = [0]\ncohesion_pa = {own}\n")))
    };
    assert_eq!(face(0.0, c).termination.reason, Reason::DoesNotSlide);
    assert_eq!(face(c, 0.0).termination.reason, Reason::TimeLimit);
}

#[test]
fn a_kicked_bonded_base_has_broken_its_bond_and_slides_as_without_cohesion() {
    // Cohesion twice the weight's friction, and a kick of 2 m/s: it stops where friction alone
    // stops it, row for row the route without cohesion.
    let (mu, g) = (0.4, 9.81);
    let c = 2.0 * mu * 1e6 * g / 16.0;
    let kicked = |c: f64| {
        run_on(
            &bonded_block(mu, c, 0.0, "base", 2.0)
                .replace("[solver]", "[initial]\nvx_m_s = 2.0\n[solver]"),
        )
    };
    let (with, without) = (kicked(c), kicked(0.0));
    assert_eq!(with.termination.reason, Reason::Stopped);
    assert_eq!(with.rows, without.rows);
    assert_eq!(with.base().unwrap().bond_broken_s, Some(0.0));
}

#[test]
fn a_base_under_barton_choubey_takes_each_touchs_stress_over_its_own_share_of_the_base() {
    // The 4 m square block on level rock under Barton–Choubey (JRC 10, JCS 50 MPa, φr 30°),
    // the criterion's contact_area_m2 = 1 m² (meant for the frame's three points). On its base
    // each touch and each point takes its stress over its own share of the base's 16 m²: the
    // flush base presses evenly at σ = W/A, and holds a push through its CM up to
    // P = A τ(σ) = W tan(JRC log10(JCS/σ) + φr); pushed by 1.5 P it slides at 0.5 P/m.
    // Taken over 1 m² instead (σ = W/1), the coefficient would be 0.40 smaller.
    let (g, t, h) = (9.81f64, 1.0, 1e-3);
    let w = 1e6 * g;
    let coefficient = |sigma: f64| (10.0 * (5.0e7 / sigma).log10() + 30.0).to_radians().tan();
    let mu = coefficient(w / 16.0);
    assert!(mu - coefficient(w) > 0.39);
    let barton = |by: f64| {
        let text = block_scene(&plane(0.0, 0.0), 0.5, "", t, h)
            .replace(
                "hydraulic_force_n = 0.0",
                &format!("hydraulic_force_n = {}", by * mu * w),
            )
            .replace(
                "model = \"coulomb\"\nmu_k = 0.5",
                "model = \"barton-choubey\"\njrc = 10.0\njcs_pa = 5.0e7\nphi_r_deg = 30.0\n\
                 contact_area_m2 = 1.0",
            )
            .replace("[solver]", "[solver]\ncontacts = \"base\"");
        assert!(text.contains("barton-choubey"), "{text}");
        run(&text)
    };
    assert_eq!(barton(0.99).termination.reason, Reason::DoesNotSlide);
    let route = barton(1.01);
    assert_eq!(route.termination.reason, Reason::TimeLimit);
    // A net acceleration a fiftieth of the push's: the solve's tolerance weighs fifty times.
    let exact = 0.5 * 0.01 * g * mu * t * t;
    let x = route.rows.last().unwrap().x_m - route.rows[0].x_m;
    assert!((x - exact).abs() < 1e-4 * exact, "{x} m against {exact} m");
    let route = barton(1.5);
    let exact = 0.5 * 0.5 * g * mu * t * t;
    let x = route.rows.last().unwrap().x_m - route.rows[0].x_m;
    assert!((x - exact).abs() < 1e-6 * exact, "{x} m against {exact} m");
}

#[test]
fn a_bonded_block_on_a_frame_around_its_centre_lets_go_at_the_same_push_and_slides_as_its_base() {
    // The same bonded block on three points around its CM (the frame's triangle holding it
    // upright, its base the same 4 m square): the frame holds at 0.99 (μ W + c A) and slides at
    // 1.01 of it at the same acceleration, exactly (½ a t², the frame's rigid body to its
    // tolerance, and the base's steps, extrapolated flush on one plane, to theirs).
    let (mu, g, t) = (0.4, 9.81, 1.0);
    let w = 1e6 * g;
    let c = 0.2 * w / 16.0;
    let limit = mu * w + c * 16.0;
    let around = |push: f64, contacts: &str| {
        let text = bonded_block(mu, c, push, contacts, t).replace(
            "contacts_m = [[-2.0, 2.0], [2.0, 2.0], [2.0, -2.0]]",
            "contacts_m = [[-2.0, -2.0], [2.0, -2.0], [0.0, 2.0]]",
        );
        assert!(text.contains("[0.0, 2.0]"), "{text}");
        run_on(&text)
    };
    let a = (0.01 * limit / w + limit / w - mu) * g;
    for (contacts, exact) in [("frame", 0.5 * a * t * t), ("base", 0.5 * a * t * t)] {
        let held = around(0.99 * limit, contacts);
        assert_eq!(held.termination.reason, Reason::DoesNotSlide, "{contacts}");
        let slid = around(1.01 * limit, contacts);
        assert_eq!(slid.termination.reason, Reason::TimeLimit, "{contacts}");
        let x = slid.rows.last().unwrap().x_m - slid.rows[0].x_m;
        assert!(
            (x - exact).abs() < 1e-6 * exact,
            "{contacts}: {x} m against {exact} m"
        );
    }
}
