//! A base cast onto its rock (`[base] cast = true`) against closed forms: on a plane it is the
//! flat base; on regular asperities it holds until the push reaches W tan(φ + i) and then rides
//! up their flanks at the angle i (Patton's bilinear law), where a flat base resting on their
//! crests slides at W tan φ.

use super::base_contact::{assert_physical_and_out_of_rock, block_scene, plane, travel_along};
use slideroute::internals::route::{Reason, Route};
use slideroute::internals::scene::Scene;
use std::path::{Path, PathBuf};

/// A sawtooth along X: teeth 1 m long, flanks at `angle` degrees, level along Z, over
/// ±10 m (an OBJ in a fresh folder).
fn sawtooth(angle: f64, tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slideroute-cast-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let h = 0.5 * angle.to_radians().tan();
    let mut obj = String::new();
    for k in 0..=40 {
        let (x, y) = (-10.0 + 0.5 * k as f64, if k % 2 == 0 { 0.0 } else { h });
        obj.push_str(&format!("v {x} {y} -10\nv {x} {y} 10\n"));
    }
    for k in 0..40 {
        let (a, b, c, d) = (2 * k + 1, 2 * k + 2, 2 * k + 3, 2 * k + 4);
        obj.push_str(&format!("f {a} {b} {d}\nf {a} {d} {c}\n"));
    }
    std::fs::write(dir.join("teeth.obj"), obj).unwrap();
    dir
}

/// The block of `block_scene` on the sawtooth, pushed along +X by `push` times its weight, its
/// base cast or flat.
fn on_teeth(dir: &Path, push: f64, mu: f64, cast: bool, t_end: f64) -> Route {
    let text = block_scene(
        "[foundation]\nsurface = \"teeth.obj\"\n",
        mu,
        &format!("[base]\ncast = {cast}"),
        t_end,
        1e-3,
    )
    .replace(
        "hydraulic_force_n = 0.0",
        &format!("hydraulic_force_n = {}", push * 1e6 * 9.81),
    );
    let file = dir.join(format!("teeth-{push}-{cast}.toml"));
    std::fs::write(&file, text).unwrap();
    let scene = Scene::from_file(&file).unwrap();
    slideroute::run(&scene).unwrap()
}

#[test]
fn a_base_cast_on_asperities_holds_below_w_tan_phi_plus_i_where_a_flat_one_slides() {
    let dir = sawtooth(10.0, "hold");
    // μ = 0.5 (φ = 26.57°), i = 10°: the cast base holds up to tan 36.57° = 0.7415 W, to the
    // thousandth: whether it is held is a cone program over its touches, not a step's sweeps.
    let limit = (0.5f64.atan() + 10f64.to_radians()).tan();
    let held = on_teeth(&dir, 0.999 * limit, 0.5, true, 0.5);
    assert_eq!(
        held.termination.reason,
        Reason::DoesNotSlide,
        "{:?}",
        held.termination
    );
    let pushed = on_teeth(&dir, 1.001 * limit, 0.5, true, 1.0);
    assert_eq!(
        pushed.termination.reason,
        Reason::TimeLimit,
        "{:?}",
        pushed.termination
    );
    assert!(pushed.rows.last().unwrap().x_m > 1e-3);
    let flat = on_teeth(&dir, 0.73, 0.5, false, 0.5);
    assert_eq!(
        flat.termination.reason,
        Reason::TimeLimit,
        "{:?}",
        flat.termination
    );
    assert!(flat.rows.last().unwrap().x_m > 0.1);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_base_cast_on_asperities_rides_up_their_flanks_as_a_block_up_an_incline() {
    let dir = sawtooth(10.0, "ride");
    let (i, mu, push, t) = (10f64.to_radians(), 0.5, 0.8, 1.0);
    let route = on_teeth(&dir, push, mu, true, t);
    assert_eq!(
        route.termination.reason,
        Reason::TimeLimit,
        "{:?}",
        route.termination
    );
    // Up a flank of angle i pushed horizontally by P W: a = g (P (cos i − μ sin i) − sin i −
    // μ cos i) along it, so x = ½ a cos i t², y = x tan i (before it reaches a crest).
    let a = 9.81 * (push * (i.cos() - mu * i.sin()) - i.sin() - mu * i.cos());
    let along = 0.5 * a * t * t;
    let (first, last) = (route.rows[0], *route.rows.last().unwrap());
    let (dx, dy) = (last.x_m - first.x_m, last.y_m - first.y_m);
    assert!(dx < 0.5, "past a crest: {dx}");
    let travel = travel_along(&route);
    eprintln!("cast on teeth: travel {travel} m against {along} m, rise {dy} m over {dx} m");
    assert!((travel - along).abs() < 5e-3 * along, "{travel} {along}");
    assert!((dy - dx * i.tan()).abs() < 1e-6, "{dy} {dx}");
    assert!(
        last.theta_deg.abs() < 1e-6 && last.z_m.abs() < 1e-6,
        "{last:?}"
    );
    let summary = route.base().unwrap();
    assert!(
        summary.max_penetration_m < 1e-6 * 4.0,
        "{}",
        summary.max_penetration_m
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_base_cast_on_a_plane_dipping_downstream_slides_as_the_flat_base_does() {
    let (dip, mu, t) = (20f64.to_radians(), 0.2, 1.0);
    let text = block_scene(&plane(20.0, 0.0), mu, "[base]\ncast = true", t, 1e-3);
    let scene = Scene::from_toml(&text, "cast").unwrap();
    let route = slideroute::run(&scene).unwrap();
    let exact = 0.5 * 9.81 * (dip.sin() - mu * dip.cos()) * t * t;
    assert!((travel_along(&route) - exact).abs() < 2e-3 * exact);
    let flat = slideroute::run(
        &Scene::from_toml(&block_scene(&plane(20.0, 0.0), mu, "", t, 1e-3), "flat").unwrap(),
    )
    .unwrap();
    let (c, f) = (route.rows.last().unwrap(), flat.rows.last().unwrap());
    assert!(
        (c.x_m - f.x_m).abs() < 1e-9 && (c.y_m - f.y_m).abs() < 1e-9,
        "{c:?} {f:?}"
    );
}

#[test]
fn a_base_cast_on_a_plane_and_pushed_off_its_centre_slides_and_turns_as_the_flat_base_does() {
    // Up a plane rising 10° along +X, pushed by 0.85 W 0.5 m off its centre of mass (μ 0.5): a
    // relief that is one plane is the flat base, and where it lies flush it presses over its
    // area as the flat base does (its friction at its rim alone turned it 6.7° less by 1 s).
    let push = |text: String| {
        text.replace("hydraulic_force_n = 0.0", "hydraulic_force_n = 8.34e6")
            .replace("eccentricity_m = 0.0", "eccentricity_m = 0.5")
    };
    let run = |cast: &str| {
        let text = push(block_scene(&plane(10.0, 180.0), 0.5, cast, 1.0, 1e-3));
        slideroute::run(&Scene::from_toml(&text, "plane").unwrap()).unwrap()
    };
    let (cast, flat) = (run("[base]\ncast = true"), run(""));
    let (c, f) = (cast.rows.last().unwrap(), flat.rows.last().unwrap());
    assert!(f.theta_deg.abs() > 10.0, "{f:?}");
    let gap = (c.x_m - f.x_m).hypot(c.z_m - f.z_m);
    assert!(
        gap < 1e-3 && (c.theta_deg - f.theta_deg).abs() < 0.05,
        "cast {c:?}, flat {f:?}"
    );
}

#[test]
fn a_cast_base_on_the_three_point_frame_is_refused_naming_the_key() {
    let text = block_scene(&plane(0.0, 0.0), 0.2, "[base]\ncast = true", 1.0, 1e-3)
        .replace("mode = \"exact\"", "mode = \"exact\"\ncontacts = \"frame\"");
    let err = Scene::from_toml(&text, "cast").unwrap_err();
    assert!(err.to_string().contains("base.cast"), "{err}");
}

#[test]
fn a_block_cast_on_teeth_and_pushed_off_its_centre_turns_over_them_out_of_the_rock() {
    // scenes/body/cast-teeth.toml: 0.85 W, 0.5 m off the centre of mass, for 2 s.
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/body/cast-teeth.toml");
    let scene = Scene::from_file(&file)
        .unwrap()
        .with("solver.t_end_s", 2.0)
        .unwrap();
    let route = slideroute::run(&scene).unwrap();
    assert_physical_and_out_of_rock("cast-teeth", &scene, &route);
    // It turned, and rode over the teeth: to pass them its CM rose at least by their height,
    // 0.5 tan 10°, tip on tip (more where it leaves a crest in flight).
    let (first, last) = (route.rows[0], *route.rows.last().unwrap());
    assert!(last.theta_deg.abs() > 10.0, "{last:?}");
    let h = 0.5 * 10f64.to_radians().tan();
    let top = route
        .rows
        .iter()
        .map(|r| r.y_m - first.y_m)
        .fold(0.0, f64::max);
    assert!(top >= h - 1e-6, "{top} {h}");
    let e = route.energy().unwrap();
    assert!(e.residual_j.abs() < 1e-3 * e.work_hydraulic_j, "{e:?}");
}

/// The start of a block flush on the +10° flanks of `scenes/body/teeth.obj` (the four strips
/// x ∈ [n, n + ½], n = −2 … 1, under its 4 m square), found apart from the route: the
/// motion that starts from rest is self-similar (every velocity grows as t, so the slip's
/// direction at each point of the flanks is fixed), and the accelerations (a_s up the flanks,
/// a_z across them, α about their normal n) with the linear pressure p = p₀ + p₁ξ + p₂ζ of a
/// uniform bed (derivations/13-base-contact.md §9) are the root of Newton's and Euler's six
/// equations, the friction −μ p û integrated over the strips by the midpoint rule (`cells` a side
/// of each). Loads as the scene's: F along x at the centre of mass, the couple −e F about y,
/// the weight; I = diag(I_y/2, I_y, I_y/2). Returns (a_s, α).
fn flank_start(cells: usize) -> (f64, f64) {
    use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
    let i = 10f64.to_radians();
    let (m, g, f, e, mu, iy) = (1e6, 9.81, 8.34e6, 0.5, 0.5, 2.6667e6);
    let inertia = Matrix3::from_diagonal(&Vector3::new(iy / 2.0, iy, iy / 2.0));
    let n = Vector3::new(-i.sin(), i.cos(), 0.0);
    let (s, z) = (Vector3::new(i.cos(), i.sin(), 0.0), Vector3::z());
    let cm = Vector3::new(0.0, 0.5 * i.tan(), 0.0);
    let mut points = Vec::new(); // (r from the CM, area)
    for v in [-2.0, -1.0, 0.0, 1.0] {
        for a in 0..cells {
            for b in 0..cells {
                let x = v + 0.5 * (a as f64 + 0.5) / cells as f64;
                let zz = -2.0 + 4.0 * (b as f64 + 0.5) / cells as f64;
                let area = 0.5 * 4.0 / (cells * cells) as f64 / i.cos();
                points.push((Vector3::new(x, (x - v) * i.tan(), zz) - cm, area));
            }
        }
    }
    let residual = |q: &Vector6<f64>| {
        let (mut force, mut moment) =
            (Vector3::new(f, -m * g, 0.0), Vector3::new(0.0, -e * f, 0.0));
        for (r, area) in &points {
            let p = q[3] + q[4] * r.dot(&s) + q[5] * r.dot(&z);
            let slip = s * q[0] + z * q[1] + n.cross(r) * q[2];
            let df = (n - slip.normalize() * mu) * (p * area);
            force += df;
            moment += r.cross(&df);
        }
        let lin = (s * q[0] + z * q[1]) * m - force;
        let ang = inertia * n * q[2] - moment;
        Vector6::new(lin.x, lin.y, lin.z, ang.x, ang.y, ang.z)
    };
    let scale = Vector6::new(1.0, 1.0, 1.0, 1e6, 1e6, 1e6);
    let mut q = Vector6::new(1.0, 0.0, -0.3, 5e6, 0.0, 0.0);
    for _ in 0..50 {
        let r0 = residual(&q);
        let mut jac = Matrix6::zeros();
        for k in 0..6 {
            let mut d = q;
            d[k] += 1e-7 * scale[k];
            jac.set_column(k, &((residual(&d) - r0) / (1e-7 * scale[k])));
        }
        let step = jac.lu().solve(&-r0).unwrap();
        q += step;
        if step.component_div(&scale).amax() < 1e-12 {
            break;
        }
    }
    (q[0], q[2])
}

#[test]
fn a_block_cast_on_teeth_and_pushed_off_its_centre_starts_to_turn_as_friction_over_its_flanks_says()
{
    // scenes/body/cast-teeth.toml's first 0.05 s at dt 0.1 ms (its strips narrow by 0.4 %
    // meanwhile): the travel ½ a_s cos i t² and the yaw ½ α cos i t² of the self-similar start.
    // Drake's bed with each grid point weighing its whole cell (a flank's bed one spacing too
    // long) started 5.3 %, 3.6 % and 2.1 % slower at 20, 40 and 80 points a side.
    let (a_s, alpha) = flank_start(40);
    let (fine, _) = flank_start(80);
    assert!((a_s - fine).abs() < 1e-4 * a_s, "{a_s} {fine}");
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/body/cast-teeth.toml");
    let scene = Scene::from_file(&file)
        .unwrap()
        .with_keys([("solver.t_end_s", 0.05), ("solver.dt_s", 1e-4)])
        .unwrap();
    let route = slideroute::run(&scene).unwrap();
    let last = route.rows.last().unwrap();
    let (t, c) = (last.t_s, 10f64.to_radians().cos());
    assert!((t - 0.05).abs() < 1e-9, "{last:?}");
    let x = 0.5 * a_s * c * t * t;
    let yaw = (-0.5 * alpha * c * t * t).to_degrees();
    assert!(
        (last.x_m / x - 1.0).abs() < 5e-3,
        "x {} against {x}",
        last.x_m
    );
    assert!(
        (last.theta_deg / yaw - 1.0).abs() < 5e-3,
        "yaw {}° against {yaw}°",
        last.theta_deg
    );
}

#[test]
fn the_energy_balance_of_a_block_riding_over_teeth_closes_at_the_first_order_of_the_step() {
    // Up a flank, over a crest and down into the next valley, where the block lands on the
    // rising flank beyond: the impact that turns its slip is booked as friction's
    // ½ P_t (u + u⁺) and the normal's ½ P_n (u_n + u_n⁺), so what is left halves with the step.
    let dir = sawtooth(10.0, "energy");
    let residual = |dt: f64| {
        let text = block_scene(
            "[foundation]\nsurface = \"teeth.obj\"\n",
            0.5,
            "[base]\ncast = true",
            1.4,
            dt,
        )
        .replace("hydraulic_force_n = 0.0", "hydraulic_force_n = 8.3385e6");
        let file = dir.join(format!("energy-{dt}.toml"));
        std::fs::write(&file, text).unwrap();
        let route = slideroute::run(&Scene::from_file(&file).unwrap()).unwrap();
        assert!(route.rows.last().unwrap().x_m > 1.0, "not past the crest");
        let e = route.energy().unwrap();
        e.residual_j / e.work_hydraulic_j
    };
    let (coarse, fine) = (residual(1e-3), residual(5e-4));
    assert!(coarse.abs() < 1e-3, "{coarse}");
    // At least first order: the phases on one flank are extrapolated, held to the tolerance,
    // and leave less than half.
    let ratio = coarse / fine;
    assert!((1.6..4.0).contains(&ratio), "{coarse} {fine}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_monolith_cast_onto_rough_rock_is_held_where_its_flat_base_slides() {
    // scenes/body/cast-monolith.toml: 15.5 m of headwater, μ = 0.48, cells within 6.2° of level.
    // Cast, it rests on hundreds of touches at once, and whether it is held is asked of a cone
    // program over them (a step's sweeps left a micrometre's creep that then stopped).
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/body/cast-monolith.toml");
    let scene = Scene::from_file(&file).unwrap();
    let cast = slideroute::run(&scene).unwrap();
    assert_eq!(
        cast.termination.reason,
        Reason::DoesNotSlide,
        "{:?}",
        cast.termination
    );
    let flat = slideroute::run(
        &scene
            .with("base.cast", false)
            .unwrap()
            .with("solver.t_end_s", 1.0)
            .unwrap(),
    )
    .unwrap();
    assert_eq!(
        flat.termination.reason,
        Reason::TimeLimit,
        "{:?}",
        flat.termination
    );
    assert!(travel_along(&flat) > 0.05, "{}", travel_along(&flat));
}

/// crosscheck/make_terrain.py's bump: level ground on a 2 m grid (X −24 to 40 m, Z ±20 m) with
/// a ridge of two faces rising at `deg` degrees to a crest along Z at X = `at`, 2 m wide (an
/// OBJ in a fresh folder).
fn ridge(deg: f64, at: f64, tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slideroute-ridge-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut xs: Vec<f64> = (0..=32).map(|k| -24.0 + 2.0 * k as f64).collect();
    xs.extend([at - 1.0, at, at + 1.0]);
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let zs: Vec<f64> = (0..=20).map(|k| -20.0 + 2.0 * k as f64).collect();
    let t = deg.to_radians().tan();
    let mut obj = String::new();
    for x in &xs {
        for z in &zs {
            let y = t * (1.0 - (x - at).abs()).max(0.0);
            obj.push_str(&format!("v {x} {y} {z}\n"));
        }
    }
    let id = |i: usize, j: usize| i * zs.len() + j + 1;
    for i in 0..xs.len() - 1 {
        for j in 0..zs.len() - 1 {
            let (p, q, r, s) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            obj.push_str(&format!("f {p} {s} {r}\nf {p} {r} {q}\n"));
        }
    }
    std::fs::write(dir.join("ridge.obj"), obj).unwrap();
    dir
}

#[test]
fn a_block_cast_over_a_ridge_and_held_by_its_flank_stays_where_it_was_cast() {
    // Fuzz seed 14, case 26: a 7.6 m square block cast over a 12.5° ridge 1.8 m behind its
    // centre, pushed by 0.66 W off its centre, μ = 0.449 (φ = 24.2°). It rests on 370 touches;
    // a step's sweeps, and 40 000 of them in a trial step, left it moving at 7e-7 m/s, and it
    // crept 2 µm to the time limit. The cone program over the touches holds it (a bed of springs
    // on the triangles creeps 2.4 mm in 0.3 s at a sink of 0.1 mm, 1.0 mm and slowing at
    // 25 µm: its creep is its compliance).
    let dir = ridge(12.5, -1.8, "held");
    let a = 3.797329255668137;
    let text = format!(
        r#"
name = "cast over a ridge"
[frame]
contacts_m = [[{m}, {a}], [{a}, {a}], [{a}, {m}]]
[block]
mass_kg = 1.0e6
inertia_kg_m2 = 9.6131e6
[loads]
hydraulic_force_n = 6.484e6
eccentricity_m = -0.66
gravity_m_s2 = 9.81
[foundation]
surface = "ridge.obj"
[friction]
model = "coulomb"
mu_k = 0.449
[solver]
mode = "exact"
dt_s = 1.0e-3
t_end_s = 1.5
contacts = "base"
[base]
cast = true
"#,
        m = -a
    );
    let file = dir.join("ridge.toml");
    std::fs::write(&file, text).unwrap();
    let scene = Scene::from_file(&file).unwrap();
    let route = slideroute::run(&scene).unwrap();
    assert_eq!(
        route.termination.reason,
        Reason::DoesNotSlide,
        "{:?}",
        route.termination
    );
    // Pushed a fifth harder it slides, and climbs the flank.
    let pushed = slideroute::run(&scene.with("loads.hydraulic_force_n", 7.8e6).unwrap()).unwrap();
    assert_eq!(pushed.termination.reason, Reason::TimeLimit);
    let (first, last) = (pushed.rows[0], *pushed.rows.last().unwrap());
    assert!(
        last.x_m - first.x_m > 0.01 && last.y_m > first.y_m,
        "{last:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
