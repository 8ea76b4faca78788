//! Routes do not move under refactoring: every scene of `scenes/` under both
//! dynamics against reference rows stored in `tests/reference/` (every 25th row and the last,
//! at full precision, with the reason and the number of increments), to 1e-12 of each
//! column's scale.
//!
//! The references are the routes as they were before the layer above the numerical core was
//! reshaped. To record them again, deliberately, after a change that is meant to move routes:
//! `SLIDEROUTE_BLESS=1 cargo test --test integration route_reference`.

use slideroute::internals::route::{self, Row};
use slideroute::internals::{
    model::{Contacts, DynamicsModel},
    scene::Scene,
};
use std::path::{Path, PathBuf};

const EVERY: usize = 25;
const RELATIVE: f64 = 1e-12;

fn fields(r: &Row) -> Vec<f64> {
    let [n0, n1, n2] = r.n_n.unwrap_or([f64::NAN; 3]);
    let [s0, s1, s2] = r.s_n.unwrap_or([f64::NAN; 3]);
    vec![
        r.t_s,
        r.x_m,
        r.y_m,
        r.z_m,
        r.theta_deg,
        r.alpha_deg,
        r.beta_deg,
        r.gamma_deg,
        r.vx_m_s,
        r.vz_m_s,
        r.omega_deg_s,
        n0,
        n1,
        n2,
        s0,
        s1,
        s2,
    ]
}

/// The reference text of a route: a line with the reason and the number of increments, then
/// every EVERY-th row and the last, each value as Rust writes it back exactly.
fn reference_text(route: &route::Route) -> String {
    let mut text = format!(
        "reason={:?} increments={}\n",
        route.termination.reason.as_str(),
        route.increments
    );
    let n = route.rows.len();
    for (k, r) in route.rows.iter().enumerate() {
        if k % EVERY == 0 || k + 1 == n {
            let cells: Vec<String> = fields(r).iter().map(|v| format!("{v:?}")).collect();
            text.push_str(&format!("{k},{}\n", cells.join(",")));
        }
    }
    text
}

fn scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_route_of_every_scene_matches_its_stored_reference() {
    let bless = std::env::var_os("SLIDEROUTE_BLESS").is_some();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference");
    let mut checked = 0;
    for file in scenes() {
        let base = Scene::from_file(&file).unwrap();
        for model in DynamicsModel::ALL {
            // A ground-motion record moves the foundation under a rigid body only.
            let Ok(scene) = base.with_dynamics(model) else {
                assert!(base.record().is_some() && model == DynamicsModel::Paper);
                continue;
            };
            // The three-point frame's routes, whatever a scene's default contacts.
            let scene = scene.with("solver.contacts", "frame").unwrap();
            let name = format!(
                "{}-{}.csv",
                file.file_stem().unwrap().to_string_lossy(),
                model.as_str()
            );
            checked += usize::from(matches_reference(&dir, &name, &scene, bless));
        }
        // A block on its base, where the scene's default is its base: the first 3 s.
        if base
            .settings()
            .is_some_and(|s| s.contacts == Contacts::Base)
        {
            let name = format!("{}-base.csv", file.file_stem().unwrap().to_string_lossy());
            let scene = base.with("solver.t_end_s", 3.0).unwrap();
            checked += usize::from(matches_reference(&dir, &name, &scene, bless));
        }
    }
    assert!(bless || checked >= 20, "{checked} routes checked");
}

/// Runs `scene` and checks its route against the reference `name` in `dir` (true), or, when
/// `bless`, records it there (false).
fn matches_reference(dir: &Path, name: &str, scene: &Scene, bless: bool) -> bool {
    let got = reference_text(&slideroute::run(scene).unwrap());
    let path = dir.join(name);
    if bless {
        std::fs::create_dir_all(dir).unwrap();
        std::fs::write(&path, &got).unwrap();
        return false;
    }
    let want = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{name}: {e} (record with SLIDEROUTE_BLESS=1)"));
    compare(name, &got, &want);
    true
}

fn compare(name: &str, got: &str, want: &str) {
    let (got_head, got_rows) = got.split_once('\n').unwrap();
    let (want_head, want_rows) = want.split_once('\n').unwrap();
    assert_eq!(got_head, want_head, "{name}: how the route ended");
    let parse = |text: &str| -> Vec<Vec<f64>> {
        text.lines()
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect()
    };
    let (got, want) = (parse(got_rows), parse(want_rows));
    assert_eq!(got.len(), want.len(), "{name}: rows");
    let columns = want.first().map_or(0, Vec::len);
    for c in 0..columns {
        let scale = want
            .iter()
            .map(|r| r[c].abs())
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        for (g, w) in got.iter().zip(&want) {
            let (a, b) = (g[c], w[c]);
            let same = (a.is_nan() && b.is_nan()) || (a - b).abs() <= RELATIVE * scale;
            assert!(same, "{name}: row {}, column {c}: {a} against {b}", w[0]);
        }
    }
}
