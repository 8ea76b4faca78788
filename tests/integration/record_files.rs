//! Records as strong-motion files come (`seismic.record_x`, `record_y`, `record_z`: PEER
//! `.AT2`, two columns, one column at `seismic.dt_s`; `units`, `scale`, `target_pga_g`,
//! `polarity`): each routes exactly as the same accelerations in fractions of g in one
//! three-component file (`seismic.record`), which the closed forms of `ground_motion.rs` check.

use slideroute::Scene;
use slideroute::sweep::{Sweep, Vary};
use slideroute::{Outcome, Route};
use std::path::{Path, PathBuf};

/// A record along X and Z: 300 samples 0.01 s apart, in thousandths of g (exact in decimal),
/// that slides the block forward (+X) only.
fn motion() -> Vec<(f64, f64, f64)> {
    (0..300)
        .map(|k| {
            let t = k as f64 * 0.01;
            let x = -(150.0 * (7.0 * t).sin() * (-0.3 * t).exp() + 100.0).round() / 1000.0;
            let z = (50.0 * (11.0 * t + 1.0).sin()).round() / 1000.0;
            (t, x, z)
        })
        .collect()
}

/// A fresh folder for one test's files.
fn folder(tag: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("slideroute-recfiles-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The level paper-like block with no water, its `[seismic]` table `seismic`, in `dir`.
fn scene(dir: &Path, seismic: &str) -> Result<Scene, String> {
    let text = crate::common::paper_like_on_level_planes()
        .replace("hydraulic_force_n = 8.0e6", "hydraulic_force_n = 0.0")
        .replace("mu_k = 0.40", "mu_k = 0.15")
        .replace("t_end_s = 20.0", "t_end_s = 4.0")
        + "\n[seismic]\n"
        + seismic;
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    Scene::from_file(&path).map_err(|e| e.to_string())
}

/// The same motion as one three-component file, each acceleration times `k`.
fn as_one_file(dir: &Path, k: f64) -> Route {
    let mut csv = String::from("t_s,ax_g,ay_g,az_g\n");
    for (t, x, z) in motion() {
        csv += &format!("{t},{},0,{}\n", k * x, k * z);
    }
    std::fs::write(dir.join("three.csv"), csv).unwrap();
    slideroute::run(&scene(dir, "record = \"three.csv\"\n").unwrap()).unwrap()
}

fn at2(values: &[f64]) -> String {
    let mut s = String::from(
        "PEER NGA STRONG MOTION DATABASE RECORD\nA test, 11/27/2026, here, 000\n\
         ACCELERATION TIME SERIES IN UNITS OF G\n",
    );
    s += &format!("NPTS= {:5}, DT=   .0100 SEC\n", values.len());
    for row in values.chunks(5) {
        for v in row {
            s += &format!("{v:15.7E}");
        }
        s.push('\n');
    }
    s
}

fn same_route(a: &Route, b: &Route, tol: f64) {
    assert_eq!(a.rows.len(), b.rows.len());
    assert_eq!(a.termination.reason, b.termination.reason);
    for (p, q) in a.rows.iter().zip(&b.rows) {
        for (u, v) in [(p.x_m, q.x_m), (p.z_m, q.z_m), (p.theta_deg, q.theta_deg)] {
            assert!((u - v).abs() <= tol * (1.0 + v.abs()), "{p:?}\n{q:?}");
        }
    }
}

#[test]
fn an_at2_component_and_a_two_column_one_route_as_the_same_record_in_one_file() {
    let dir = folder("at2");
    let m = motion();
    let x: Vec<f64> = m.iter().map(|p| p.1).collect();
    std::fs::write(dir.join("RSN1_X.AT2"), at2(&x)).unwrap();
    let mut two = String::from("time (s)  acceleration (g)\n");
    for (t, _, z) in &m {
        two += &format!("{t} {z}\n");
    }
    std::fs::write(dir.join("z.txt"), two).unwrap();
    let parts = scene(&dir, "record_x = \"RSN1_X.AT2\"\nrecord_z = \"z.txt\"\n").unwrap();
    let route = slideroute::run(&parts).unwrap();
    let whole = as_one_file(&dir, 1.0);
    assert!(
        whole.rows.last().unwrap().x_m.abs() > 1e-3,
        "the record slides the block"
    );
    same_route(&route, &whole, 0.0);
    // The permanent displacement as a signed vector: forward along X, as the record pushes it;
    // its length the displacement.
    let (first, last) = (route.rows[0], *route.rows.last().unwrap());
    let [dx, dz] = route.permanent_displacement_xz_m.unwrap();
    assert_eq!([dx, dz], [last.x_m - first.x_m, last.z_m - first.z_m]);
    assert!(dx > 1e-2, "{dx}");
    assert_eq!(route.permanent_displacement_m, Some(dx.hypot(dz)));
    // And what the record measures: its PGA along X is the largest sample.
    let pga = motion().iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    assert_eq!(route.record_intensity.unwrap().pga_g[0], pga);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_column_in_cm_s2_scaled_to_a_target_pga_routes_as_the_record_in_g_at_that_pga() {
    let dir = folder("pga");
    let m = motion();
    // One column along X in cm/s² at the scene's g (9.81 m/s²), its step in the scene.
    let mut one = String::new();
    for (_, x, _) in &m {
        one += &format!("{}\n", x * 981.0);
    }
    std::fs::write(dir.join("x.txt"), one).unwrap();
    let target = 0.45;
    let given = scene(
        &dir,
        &format!("record_x = \"x.txt\"\ndt_s = 0.01\nunits = \"cm/s2\"\ntarget_pga_g = {target}\n"),
    )
    .unwrap();
    let pga = m.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let route = slideroute::run(&given).unwrap();
    // The scene as used names the file and the keys that made the record of it.
    let echo = toml::to_string(&given.as_used()).unwrap();
    for key in [
        "record_x = \"x.txt\"",
        "dt_s = 0.01",
        "units = \"cm/s2\"",
        "target_pga_g = 0.45",
    ] {
        assert!(echo.contains(key), "{key} in {echo}");
    }
    // The same along X only, in g, scaled by hand.
    let mut csv = String::from("t_s,ax_g,ay_g,az_g\n");
    for (t, x, _) in &m {
        csv += &format!("{t},{},0,0\n", x * target / pga);
    }
    std::fs::write(dir.join("three.csv"), csv).unwrap();
    let whole = slideroute::run(&scene(&dir, "record = \"three.csv\"\n").unwrap()).unwrap();
    let last = whole.rows.last().unwrap();
    assert!(
        last.x_m.abs() > 1e-2,
        "the record slides the block: {last:?} {:?}",
        whole.termination
    );
    same_route(&route, &whole, 1e-9);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_reversed_or_scaled_record_routes_as_its_accelerations_negated_or_scaled() {
    let dir = folder("polarity");
    let reversed = as_one_file(&dir, -1.0);
    let given = scene(&dir, "record = \"three.csv\"\npolarity = \"reversed\"\n").unwrap();
    // three.csv now holds the negated motion: reversed again, it is the motion itself.
    let twice = slideroute::run(&given).unwrap();
    let plain = as_one_file(&dir, 1.0);
    same_route(&twice, &plain, 0.0);
    assert!((reversed.rows.last().unwrap().x_m - plain.rows.last().unwrap().x_m).abs() > 1e-3);
    let doubled = as_one_file(&dir, 2.0);
    as_one_file(&dir, 1.0);
    let scaled = scene(&dir, "record = \"three.csv\"\nscale = 2.0\n").unwrap();
    same_route(&slideroute::run(&scaled).unwrap(), &doubled, 0.0);
    // Edited by a key, the scene reads its record again and scales it once, not twice.
    let edited = scaled.with("solver.t_end_s", 4.0).unwrap();
    same_route(&slideroute::run(&edited).unwrap(), &doubled, 0.0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn both_polarities_report_the_longer_route_and_each_ones_displacement() {
    // The motion slides the block forward (+X); reversed, back (−X) and, its weights differing
    // with the turn of a_z, by another length. "both" runs each: the route is the longer's,
    // row for row, and each displacement is as its own run gives it.
    let dir = folder("both");
    let reversed = as_one_file(&dir, -1.0);
    let plain = as_one_file(&dir, 1.0);
    let both = scene(&dir, "record = \"three.csv\"\npolarity = \"both\"\n").unwrap();
    let route = slideroute::run(&both).unwrap();
    let p = route.polarities.expect("both polarities");
    let xz = |r: &Route| r.permanent_displacement_xz_m.unwrap();
    assert_eq!(p.normal_xz_m, xz(&plain));
    assert_eq!(p.reversed_xz_m, xz(&reversed));
    let length = |d: [f64; 2]| d[0].hypot(d[1]);
    let (longer, name) = if length(xz(&reversed)) > length(xz(&plain)) {
        (&reversed, "reversed")
    } else {
        (&plain, "normal")
    };
    assert_eq!(p.reported, name);
    same_route(&route, longer, 0.0);
    assert!((length(xz(&reversed)) - length(xz(&plain))).abs() > 1e-6);
    // One polarity as given reports none.
    assert!(plain.polarities.is_none());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_record_given_two_ways_or_with_keys_it_cannot_use_is_refused_naming_the_key() {
    let dir = folder("refused");
    let m = motion();
    let x: Vec<f64> = m.iter().map(|p| p.1).collect();
    std::fs::write(dir.join("x.AT2"), at2(&x)).unwrap();
    std::fs::write(
        dir.join("three.csv"),
        "t_s,ax_g,ay_g,az_g\n0,0,0,0\n1,0.1,0,0\n",
    )
    .unwrap();
    let cm: String = x.iter().map(|v| format!("{}\n", v * 981.0)).collect();
    std::fs::write(dir.join("cm.txt"), cm).unwrap();
    for (seismic, key, words) in [
        (
            "record = \"three.csv\"\nrecord_x = \"x.AT2\"\n",
            "seismic.record",
            "not both",
        ),
        (
            "record_x = \"x.AT2\"\nunits = \"cm/s2\"\n",
            "seismic.record_x",
            "the file is in g",
        ),
        (
            "record_x = \"x.AT2\"\nunits = \"ft/s2\"\n",
            "seismic.units",
            "`ft/s2`",
        ),
        (
            "record_x = \"cm.txt\"\n",
            "seismic.record_x",
            "seismic.dt_s",
        ),
        (
            "record_x = \"cm.txt\"\ndt_s = 0.01\n",
            "seismic.record_x",
            "seismic.units",
        ),
        (
            "record_z = \"cm.txt\"\ndt_s = 0.01\n",
            "seismic.record_z",
            "over 10 g",
        ),
        (
            "record_x = \"x.AT2\"\npolarity = \"up\"\n",
            "seismic.polarity",
            "`up`",
        ),
        (
            "record_x = \"x.AT2\"\nscale = 2.0\ntarget_pga_g = 0.3\n",
            "seismic.scale",
            "not both",
        ),
        (
            "record = \"three.csv\"\ndt_s = 0.01\n",
            "seismic.dt_s",
            "one file a component",
        ),
        ("kh = 0.1\nscale = 2.0\n", "seismic.scale", "has none"),
        (
            "record_x = \"missing.AT2\"\n",
            "seismic.record_x",
            "missing.AT2",
        ),
    ] {
        let e = scene(&dir, seismic).unwrap_err();
        assert!(e.contains(key) && e.contains(words), "{seismic}: {e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_sweep_over_record_files_runs_each_record_as_a_scene_naming_it_would() {
    let dir = folder("sweep");
    let m = motion();
    for (name, k) in [("a.AT2", 1.0), ("b.AT2", 1.5)] {
        let x: Vec<f64> = m.iter().map(|p| k * p.1).collect();
        std::fs::write(dir.join(name), at2(&x)).unwrap();
    }
    let base = scene(&dir, "record_x = \"a.AT2\"\n").unwrap();
    let vary: Vary = "seismic.record_x=a.AT2,b.AT2".parse().unwrap();
    let sweep = Sweep::new(&base, vec![vary]).unwrap();
    let rows = sweep.run(|| {}, || false);
    assert_eq!(rows.len(), 2);
    for (row, name) in rows.iter().zip(["a.AT2", "b.AT2"]) {
        let alone =
            slideroute::run(&scene(&dir, &format!("record_x = \"{name}\"\n")).unwrap()).unwrap();
        let r = row.outcome.route().unwrap();
        assert_eq!(r.x_m, alone.rows.last().unwrap().x_m, "{name}");
    }
    let (a, b) = (
        rows[0].outcome.route().unwrap(),
        rows[1].outcome.route().unwrap(),
    );
    assert!(b.x_m > a.x_m + 1e-3, "{} {}", a.x_m, b.x_m);
    // A word that names no file is that combination's reason, naming the key.
    let vary: Vary = "seismic.record_x=a.AT2,none.AT2".parse().unwrap();
    let rows = Sweep::new(&base, vec![vary]).unwrap().run(|| {}, || false);
    match &rows[1].outcome {
        Outcome::Invalid { reason } => assert!(reason.contains("seismic.record_x"), "{reason}"),
        other => panic!("{other:?}"),
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_yield_acceleration_of_a_block_on_level_planes_is_mu_less_its_push_along_the_push() {
    // Level planes (0.01° dips), μ = 0.5, pushed along X by 0.3 W at its base: the ground must
    // accelerate it by (μ − 0.3) g more along X, the least of any direction (its push and the
    // inertial force add as vectors within the cone μ W).
    let dir = folder("ky");
    std::fs::write(
        dir.join("quiet.csv"),
        "t_s,ax_g,ay_g,az_g\n0,0,0,0\n0.01,0,0,0\n",
    )
    .unwrap();
    let text = crate::common::paper_like_on_level_planes()
        .replace("hydraulic_force_n = 8.0e6", "hydraulic_force_n = 2.943e6")
        .replace("mu_k = 0.40", "mu_k = 0.5")
        .replace("t_end_s = 20.0", "t_end_s = 0.1")
        + "\n[seismic]\nrecord = \"quiet.csv\"\n";
    let path = dir.join("scene.toml");
    std::fs::write(&path, &text).unwrap();
    let scene = Scene::from_file(&path).unwrap();
    let route = slideroute::run(&scene).unwrap();
    let y = route.yield_acceleration.unwrap();
    // The planes' 0.01° dips move it by about 2e-4.
    assert!((y.ky_g - 0.2).abs() < 1e-3, "{y:?}");
    assert!(y.push_deg.min(360.0 - y.push_deg) < 1.0, "{y:?}");
    // No push: μ in any direction.
    let still = scene.with("loads.hydraulic_force_n", 0.0).unwrap();
    let y = slideroute::run(&still).unwrap().yield_acceleration.unwrap();
    assert!((y.ky_g - 0.5).abs() < 1e-3, "{y:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_ground_acceleration_just_under_the_yield_acceleration_holds_the_block_and_just_over_slides_it()
{
    // scenes/shaken.toml (the paper's planes, a water push 2 m off the centre of mass): its
    // yield acceleration and direction, then a steady ground acceleration of 0.99 and 1.01
    // k_y the other way for 0.5 s.
    let dir = folder("ky-route");
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/shaken.toml"))
            .unwrap()
            .replace("shaken-motion.csv", "steady.csv");
    let write = |k: f64, push_deg: f64| {
        let (c, s) = (push_deg.to_radians().cos(), push_deg.to_radians().sin());
        let (ax, az) = (-k * c, -k * s);
        std::fs::write(
            dir.join("steady.csv"),
            format!("t_s,ax_g,ay_g,az_g\n0,{ax},0,{az}\n0.5,{ax},0,{az}\n"),
        )
        .unwrap();
        let path = dir.join("scene.toml");
        std::fs::write(&path, &text).unwrap();
        slideroute::run(&Scene::from_file(&path).unwrap()).unwrap()
    };
    let y = write(0.0, 0.0).yield_acceleration.unwrap();
    assert!(y.ky_g > 0.05 && y.ky_g < 0.5, "{y:?}");
    let held = write(0.99 * y.ky_g, y.push_deg);
    assert!(
        held.travel_m < 1e-9,
        "{} {:?}",
        held.travel_m,
        held.termination
    );
    let slid = write(1.01 * y.ky_g, y.push_deg);
    assert!(
        slid.travel_m > 1e-5,
        "{} {:?}",
        slid.travel_m,
        slid.termination
    );
    // Along another direction 1.01 k_y is held: k_y is the least.
    let aside = write(1.01 * y.ky_g, y.push_deg + 30.0);
    assert!(aside.travel_m < 1e-9, "{}", aside.travel_m);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_yield_acceleration_of_a_monolith_on_its_base_is_mu_or_its_base_over_its_height() {
    // A rectangular monolith (B × 10 m × H, CM at H/2) on level rock, no water, on its base: the
    // ground slides it at μ g, or tips it about an edge at (B/2)/(H/2) g, whichever is less.
    let dir = folder("ky-base");
    std::fs::write(
        dir.join("quiet.csv"),
        "t_s,ax_g,ay_g,az_g\n0,0,0,0\n0.01,0,0,0\n",
    )
    .unwrap();
    let monolith = |b: f64, h: f64, mu: f64| {
        let text = format!(
            "name = \"ky-base\"\n[frame]\nl1x = 1.0\nl2x = 1.0\nl1z = 1.0\nl2z = 1.0\n\
             [foundation]\n[[foundation.plane]]\ndip_deg = 0.0\ndip_direction_deg = 0.0\n\
             point_m = [0.0, 0.0, 0.0]\n[monolith]\nbase_length_m = {b}\nwidth_m = 10.0\n\
             height_m = {h}\ncrest_length_m = {b}\ndensity_kg_m3 = 2400.0\n[loads]\n\
             hydraulic_force_n = 0.0\neccentricity_m = 0.0\ngravity_m_s2 = 9.81\n[friction]\n\
             model = \"coulomb\"\nmu_k = {mu}\n[solver]\nmode = \"exact\"\ndt_s = 1.0e-3\n\
             t_end_s = 0.1\n[seismic]\nrecord = \"quiet.csv\"\n"
        );
        let path = dir.join("scene.toml");
        std::fs::write(&path, text).unwrap();
        let route = slideroute::run(&Scene::from_file(&path).unwrap()).unwrap();
        route.yield_acceleration.expect("a yield acceleration")
    };
    // Stocky: friction first, in any direction.
    let y = monolith(20.0, 15.0, 0.45);
    assert!((y.ky_g - 0.45).abs() < 1e-6, "{y:?}");
    // Slender on rough rock: it tips about its heel or toe, B/H = 5/20, before about its sides
    // (10/20).
    let y = monolith(5.0, 20.0, 2.0);
    assert!((y.ky_g - 0.25).abs() < 1e-6, "{y:?}");
    let along_x = y
        .push_deg
        .min((y.push_deg - 180.0).abs())
        .min(360.0 - y.push_deg);
    assert!(along_x < 0.5, "{y:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_sweep_over_a_folder_of_records_runs_every_file_in_it_as_the_list_of_them_would() {
    let dir = folder("sweep-folder");
    std::fs::create_dir_all(dir.join("records")).unwrap();
    let m = motion();
    for (name, k) in [("b.AT2", 1.5), ("a.AT2", 1.0)] {
        let x: Vec<f64> = m.iter().map(|p| k * p.1).collect();
        std::fs::write(dir.join("records").join(name), at2(&x)).unwrap();
    }
    // Hidden files and sub-folders are not records.
    std::fs::write(dir.join("records/.notes"), "not a record").unwrap();
    std::fs::create_dir_all(dir.join("records/old")).unwrap();
    let base = scene(&dir, "record_x = \"records/a.AT2\"\n").unwrap();
    let run = |vary: &str| {
        let vary: Vary = vary.parse().unwrap();
        let sweep = Sweep::new(&base, vec![vary]).unwrap();
        let names: Vec<String> = (0..sweep.varies()[0].values.len())
            .map(|k| sweep.varies()[0].cell(k as f64))
            .collect();
        let rows = sweep.run(|| {}, || false);
        let x: Vec<f64> = rows
            .iter()
            .map(|r| r.outcome.route().unwrap().x_m)
            .collect();
        (names, x)
    };
    let (names, x) = run("seismic.record_x=records/");
    assert_eq!(names, ["records/a.AT2", "records/b.AT2"]);
    let (_, listed) = run("seismic.record_x=records/a.AT2,records/b.AT2");
    assert_eq!(x, listed);
    assert!(x[1] > x[0] + 1e-3, "{x:?}");
    // An empty folder is refused, naming the key.
    std::fs::create_dir_all(dir.join("none")).unwrap();
    let vary: Vary = "seismic.record_x=none".parse().unwrap();
    let e = Sweep::new(&base, vec![vary]).unwrap_err().to_string();
    assert!(
        e.contains("seismic.record_x") && e.contains("no files"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
