//! Records against the exact solution of the same continuous problem: a
//! block on a level face pushed along X by a constant force through its centre of mass, shaken
//! along X by a record whose acceleration is linear between samples. Its relative motion is
//! Newmark's one-dimensional sliding block with a push, solved here in closed form interval by
//! interval: the onset where the linear acceleration leaves the band the friction holds, the
//! velocity a quadratic in time while it slides, the stop where that quadratic reaches zero. The
//! route (three points of the paper's frame, Newton–Euler in three dimensions) must give the
//! same permanent displacement, stop there, and keep its energy balance.

use crate::common::newmark::{G, Run, exact, record, two_way, write_along, write_shaken};
use slideroute::{Reason, Route, Scene};

/// The closed forms' own check, by hand: a pulse of −A g for T then a ramp to zero over r
/// (a trapezoid, as samples linear between them give it) and nothing after. Sliding from the
/// start at g (A − N) (N = μ − push), it reaches v₁ = g (A − N) T, then over the ramp
/// v₂ = v₁ + g r (A/2 − N) and travels v₁ r + g r² ((A − N)/2 − A/6), and stops after
/// v₂²/(2 g N) more; with r → 0, Newmark's V²/(2 g N)(1 − N/A), V = A g T.
#[test]
fn the_exact_solution_gives_a_trapezoidal_pulse_by_hand() {
    let (dt, amp, mu, push) = (0.01, 0.5, 0.6, 0.5);
    let mut a = vec![-amp; 21];
    a.extend(std::iter::repeat_n(0.0, 400));
    let (n, t, r) = (mu - push, 0.2, dt);
    let v1 = G * (amp - n) * t;
    let v2 = v1 + G * r * (amp / 2.0 - n);
    let want = 0.5 * G * (amp - n) * t * t
        + v1 * r
        + G * r * r * ((amp - n) / 2.0 - amp / 6.0)
        + v2 * v2 / (2.0 * G * n);
    let got = exact(&a, dt, mu, push);
    assert!(
        (got - want).abs() < 1e-12 * want,
        "{got} m against {want} m"
    );
    // Reversed, against a push the other way: the same distance back.
    let back: Vec<f64> = a.iter().map(|v| -v).collect();
    let got = exact(&back, dt, mu, -push);
    assert!(
        (got + want).abs() < 1e-12 * want,
        "{got} m against −{want} m"
    );
}

/// The block on one level face, three points of the frame, pushed by `push` of its weight along
/// X through its centre of mass, friction `mu`, the record `a` along X at `dt`.
fn pushed(name: &str, a: &[f64], dt: f64, mu: f64, push: f64) -> Scene {
    let (s, dir) = pushed_in(name, a, dt, mu, push, "frame");
    std::fs::remove_dir_all(&dir).ok();
    s
}

/// [`pushed`] on `contacts` (`frame` or `base`), its folder (with the record's file) kept for
/// the caller to remove: a scene edited by key reads a component file again.
fn pushed_in(
    name: &str,
    a: &[f64],
    dt: f64,
    mu: f64,
    push: f64,
    contacts: &str,
) -> (Scene, std::path::PathBuf) {
    let dir = std::env::temp_dir().join(format!("slideroute-exact-{name}-{}", std::process::id()));
    let run = Run {
        contacts,
        dt_s: 1e-3,
        stride: 1,
    };
    let path = write_along(&dir, name, (a, dt, "x"), (mu, push), run);
    let s = Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    (s, dir)
}

/// How closely the energy balance closes, as a fraction of the work: under a push at μ = 1 to
/// 1e-15, without one to 1e-10 (a slow block's directions settled together,
/// `src/mechanics/rigid_body/accelerations.rs`; before that, a slip just started from rest
/// turned the block by 1e-5° and left up to 6.3e-5 of the work).
const BALANCE: f64 = 1e-8;

/// One case: the route's permanent displacement against the exact one (to 0.1 % or 1e-6 m, the
/// issue's figure), no creep (it ends stopped, before the time limit, at rest), and the energy
/// balance closed to [`BALANCE`] of the work.
fn agrees(name: &str, seed: u64, pga: f64, mu: f64, push: f64) {
    let dt = 0.005;
    let a = record(seed, 12.0, dt, pga);
    let want = exact(&a, dt, mu, push);
    let route: Route = slideroute::run(&pushed(name, &a, dt, mu, push)).unwrap();
    let [x, z] = route
        .permanent_displacement_xz_m
        .expect("a permanent displacement");
    let err = (x - want).abs();
    assert!(
        err <= 1e-3 * want.abs() + 1e-6,
        "{name}: {x} m against the exact {want} m ({:.2e} of it)",
        err / want.abs()
    );
    assert!(z.abs() < 1e-3 * want.abs() + 1e-6, "{name}: {z} m across");
    let end = &route.termination;
    assert_eq!(end.reason, Reason::Stopped, "{name}: {}", end.detail);
    balanced(name, &route);
}

/// The route's energy balance closed to [`BALANCE`] of the larger work.
fn balanced(name: &str, route: &Route) {
    balanced_to(name, route, BALANCE);
}

/// The route's energy balance closed to `bound` of the larger work.
fn balanced_to(name: &str, route: &Route, bound: f64) {
    let e = route.energy().expect("an energy balance");
    let scale = e.work_hydraulic_j.abs().max(e.work_friction_j.abs());
    assert!(
        e.residual_j.abs() <= bound * scale,
        "{name}: energy residual {} J of {scale} J of work",
        e.residual_j
    );
}

#[test]
fn a_block_pushed_to_within_a_tenth_of_its_friction_slides_the_exact_distance_and_stops() {
    // μ = 1 and the push 0.9 W: k_y = 0.1 g, the dam at a factor of safety of 1.11.
    for seed in [1, 2, 3] {
        agrees(&format!("p90-{seed}"), seed, 0.4, 1.0, 0.9);
    }
}

#[test]
fn a_push_of_ninety_five_hundredths_of_friction_slides_the_exact_distance() {
    for seed in [4, 5] {
        agrees(&format!("p95-{seed}"), seed, 0.5, 1.0, 0.95);
    }
}

#[test]
fn other_frictions_and_yield_accelerations_slide_the_exact_distance() {
    // k_y = 0.2 g at μ = 1; 0.1 g at μ = 0.6 (where contacts came to rest one by one, the block
    // turned and went on: a residual of 6.6e-5 of the work); 0.05 g at μ = 0.5 and μ = 0.3.
    agrees("mu100-p80", 6, 0.5, 1.0, 0.8);
    agrees("mu60-p50", 1, 0.4, 0.6, 0.5);
    agrees("mu50-p45", 7, 0.3, 0.5, 0.45);
    agrees("mu30-p25", 5, 0.5, 0.3, 0.25);
}

/// Without a push the block slides both ways: it stops and starts from rest again wherever the
/// record's acceleration crosses ±μ g, each time with an acceleration that grows from nothing.
/// Along X and along Z it must slide the exact distance to 1e-7 of it, turn by nothing (the
/// load passes through the centre of mass: under 1e-7°) and keep its balance to [`BALANCE`]
/// (before the slow block's directions were settled together these six were 4e-6 to 1.1e-3
/// off and turned by up to 2e-6°).
#[test]
fn a_block_shaken_both_ways_slides_the_exact_distance_without_turning() {
    for (seed, mu, axis) in [
        (2, 0.1, "x"),
        (3, 0.1, "z"),
        (8, 0.1, "z"),
        (3, 0.2, "x"),
        (4, 0.2, "z"),
        (5, 0.2, "z"),
    ] {
        let (name, off, route) = both_ways(seed, mu, axis);
        off.within(&name, &route, (1e-7, 1e-7, BALANCE));
    }
}

/// Record 35 at μ = 0.1 along X: the exact block's slip comes near zero at 2.2226 s without
/// reaching it, and a middle RK4 stage of a step across that moment passes zero. Where that
/// stage's stop was located and taken, the block stopped with 4.7e-6 m/s left and ended 2.4e-5
/// of the distance short; the step is now taken again shorter (`derivations/08-rigid-body.md`
/// §4a). Measured: 1e-15.
#[test]
fn a_slip_that_only_comes_near_zero_does_not_stop_the_block() {
    let (name, off, route) = both_ways(35, 0.1, "x");
    off.within(&name, &route, (1e-12, 1e-12, BALANCE));
}

/// Record 35 at μ = 0.1 along Z: at a stop and reversal (4.55 s) the shortest step reaching the
/// event showed a switch of friction's regime at its end and the stop at a stage; the switch,
/// taken from that step's end (friction turned round in its later stages), left the block
/// 1.6e-5 m/s off and the distance 1.6e-5 of itself off (2.5e-5 before the stop above was
/// mended too). The stage's stop now comes first. Measured: 1.8e-11.
#[test]
fn a_switch_is_not_taken_from_a_step_that_passed_through_a_stop() {
    let (name, off, route) = both_ways(35, 0.1, "z");
    off.within(&name, &route, (1e-9, 1e-7, BALANCE));
}

/// The six cases above over forty records each (seeds 1–40; μ = 0.1 and 0.2 along Z, μ = 0.1
/// along X): every one within 1e-6 of the exact distance, nothing across beyond 1e-9 m, no
/// turning beyond 1e-6°, stopped, its balance within [`BALANCE`] of the work; and half of them
/// within 1e-12. Measured: median 6e-14, nine in ten within 2.6e-9, the worst 4.0e-7 and
/// 2.8e-7 (seeds 30 and 31, μ = 0.1, along Z only, the same records along X exact to 1e-14;
/// seed 30 turned by 2.9e-8°: a rotation of round-off's size grown at slip onsets,
/// `derivations/08-rigid-body.md` §4a; seed 31 a stop met 0.18 µs late, its slip across not
/// yet zero), 9.8e-8° of turning, balances within 1.7e-9 of the work. Before a stop met only
/// at a middle RK4 stage was taken again shorter, and a stage's stop put before a switch at
/// the step's end, three were 2.4–2.5e-5 off (a stop where the exact block's slip only comes
/// near zero; a switch taken from a step through a stop) and two balances 2.1e-8 of the work.
/// The bound is 1e-3.
#[test]
#[ignore = "120 routes: run by .ci/run (many_records)"]
fn many_records_both_ways_slide_within_a_millionth_of_the_exact_distance() {
    let mut offs = Vec::new();
    for seed in 1..=40 {
        for (mu, axis) in [(0.1, "z"), (0.2, "z"), (0.1, "x")] {
            let (name, off, route) = both_ways(seed, mu, axis);
            off.within(&name, &route, (1e-6, 1e-6, BALANCE));
            offs.push(off.along.abs());
        }
    }
    offs.sort_by(f64::total_cmp);
    let median = offs[offs.len() / 2];
    assert!(
        median <= 1e-12,
        "median {median:.2e} of the exact distance off"
    );
}

/// How far a route is from the exact block: along (a fraction of the exact distance), across
/// (m), turned (°).
struct Off {
    along: f64,
    across: f64,
    turned_deg: f64,
}

impl Off {
    /// Route `name` within `along` of the exact distance and `turned` degrees of turning,
    /// nothing across beyond 1e-9 m, stopped, its energy balance within `balance` of the work.
    fn within(&self, name: &str, route: &Route, (along, turned, balance): (f64, f64, f64)) {
        assert!(
            self.along.abs() <= along,
            "{name}: {:.2e} of the exact distance off",
            self.along
        );
        assert!(self.across.abs() < 1e-9, "{name}: {} m across", self.across);
        assert!(
            self.turned_deg.abs() < turned,
            "{name}: turned {}°",
            self.turned_deg
        );
        assert_eq!(route.termination.reason, Reason::Stopped, "{name}");
        balanced_to(name, route, balance);
    }
}

/// The block without a push shaken along `axis` by record `seed` (pga 0.4 g, 12 s at 5 ms),
/// friction `mu`, three points of the frame, rows every second: its name, how far it is from
/// Newmark's exact block, and the route.
fn both_ways(seed: u64, mu: f64, axis: &str) -> (String, Off, Route) {
    let dt = 0.005;
    let name = format!("both-{seed}-{mu}-{axis}");
    let a = record(seed, 12.0, dt, 0.4);
    let want = exact(&a, dt, mu, 0.0);
    let dir = std::env::temp_dir().join(format!("slideroute-{name}-{}", std::process::id()));
    let run = Run {
        contacts: "frame",
        dt_s: 1e-3,
        stride: 1000,
    };
    let path = write_along(&dir, &name, (&a, dt, axis), (mu, 0.0), run);
    let route: Route = slideroute::run(&Scene::from_file(&path).unwrap()).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let [x, z] = route.permanent_displacement_xz_m.expect("a displacement");
    let (along, across) = if axis == "x" { (x, z) } else { (z, x) };
    assert!(want != 0.0, "{name}: the exact block does not slide");
    let off = Off {
        along: (along - want) / want,
        across,
        turned_deg: route.permanent_rotation_deg.expect("a rotation"),
    };
    (name, off, route)
}

/// The two-directional reference ([`two_way`]) shaken along one axis is Newmark's block in closed
/// form ([`exact`]) to 1e-5 of it, along X and along Z, nothing across.
#[test]
fn the_two_directional_reference_shaken_along_one_axis_is_the_closed_form_block() {
    let dt = 0.005;
    let a = record(3, 12.0, dt, 0.4);
    let none = vec![0.0; a.len()];
    let want = exact(&a, dt, 0.15, 0.0);
    for (x, z, along, across) in [(&a, &none, 0, 1), (&none, &a, 1, 0)] {
        let got = two_way(x, z, dt, 0.15, 1000);
        assert!(
            (got[along] - want).abs() < 1e-5 * want.abs(),
            "{got:?} against {want}"
        );
        assert_eq!(got[across], 0.0);
    }
}

/// Shaken along X and Z at once, the block slides in the plane: its slip turns with the ground's
/// acceleration, stops wherever it comes to rest within the cone and starts again from rest
/// against the record; with a constant push along X of up to 0.95 of its friction too (the
/// push, m g p, is the reference's ground acceleration less p g along X, its record padded with
/// rest until the block stops). Its permanent displacement must be the two-directional Newmark
/// block's ([`two_way`]; converged: halving its step moves it by under 1e-4 of itself) to 0.1 %
/// of its length in each component (the bound), with no turning beyond 1e-4° (its load
/// passes through the centre of mass in the base plane, so friction has no moment) and its
/// balance within 1e-6 of the work.
///
/// Measured at dt 1 ms: 2.9e-6, 3.0e-5 and 9.3e-5 of the length off without a push, 7.9e-6
/// and 2.1e-5 with 0.95 and 0.8 of friction; balance under 1e-7 of the work
/// (`derivations/11-dam-loads.md` §7). Before a young slip's direction was slaved only where
/// it is slow beside the block's own speed (`derivations/08-rigid-body.md` §3), 5.3e-3.
#[test]
fn a_block_shaken_along_x_and_z_at_once_slides_to_the_two_directional_newmark_distance() {
    let dt = 0.005;
    let cases = [
        (1, 0.1, 0.0),
        (2, 0.15, 0.0),
        (6, 0.2, 0.0),
        (3, 0.2, 0.19),
        (4, 0.3, 0.24),
    ];
    for (seed, mu, push) in cases {
        let (ax, az) = (
            record(seed, 12.0, dt, 0.4),
            record(seed + 100, 12.0, dt, 0.3),
        );
        let name = format!("two-way-{seed}-{mu}-{push}");
        if let Err(e) = two_way_case(&name, (&ax, &az, dt), (mu, push, "frame"), 1000) {
            panic!("{e}");
        }
    }
}

/// One block shaken along X by `ax` and along Z by `az` (g, `dt` apart), pushed along X by
/// `push` of its weight, against [`two_way`] in `per_sample` steps a sample (and half that
/// step, which must agree to 1e-4): the permanent displacement to 0.1 % of its length in each
/// component (or 1e-6 m), turned by under 1e-4°, at rest, the balance within 1e-6 of the work.
fn two_way_case(
    name: &str,
    (ax, az, dt): (&[f64], &[f64], f64),
    (mu, push, contacts): (f64, f64, &'static str),
    per_sample: usize,
) -> Result<(), String> {
    let n = ax.len().min(az.len());
    let (ax, az) = (&ax[..n], &az[..n]);
    // The reference: the push as the ground accelerating the other way, to the block's rest.
    let rest = (40.0 / dt) as usize;
    let padded = |a: &[f64], by: f64| -> Vec<f64> {
        a.iter()
            .chain(std::iter::repeat_n(&0.0, rest))
            .map(|v| v - by)
            .collect()
    };
    let (px, pz) = (padded(ax, push), padded(az, 0.0));
    let want = two_way(&px, &pz, dt, mu, per_sample);
    let finer = two_way(&px, &pz, dt, mu, 2 * per_sample);
    let size = want[0].hypot(want[1]);
    if (want[0] - finer[0]).hypot(want[1] - finer[1]) > 1e-4 * size {
        return Err(format!(
            "{name}: the reference {want:?} against {finer:?} at half its step"
        ));
    }
    let dir = std::env::temp_dir().join(format!("slideroute-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (file, a) in [("x.txt", ax), ("z.txt", az)] {
        let column: String = a.iter().map(|v| format!("{v:?}\n")).collect();
        std::fs::write(dir.join(file), column).unwrap();
    }
    let seismic = format!("record_x = \"x.txt\"\nrecord_z = \"z.txt\"\ndt_s = {dt}\n");
    let run = Run {
        contacts,
        dt_s: 1e-3,
        stride: 1000,
    };
    let t_end = n as f64 * dt + 40.0;
    let path = write_shaken(&dir, name, &seismic, t_end, (mu, push), run);
    let route = Scene::from_file(&path).map(|s| slideroute::run(&s));
    std::fs::remove_dir_all(&dir).ok();
    let route: Route = route
        .map_err(|e| format!("{name}: {e}"))?
        .map_err(|e| format!("{name}: {e}"))?;
    let got = route
        .permanent_displacement_xz_m
        .ok_or(format!("{name}: no displacement"))?;
    let turned = route.permanent_rotation_deg.unwrap_or(f64::NAN);
    let e = route.energy().ok_or(format!("{name}: no energy balance"))?;
    let end = &route.termination;
    if (0..2).any(|k| (got[k] - want[k]).abs() > 1e-3 * size + 1e-6) {
        Err(format!(
            "{name}: {got:?} m against the two-directional block's {want:?} m"
        ))
    } else if turned.abs() >= 1e-4 {
        Err(format!("{name}: turned {turned}°"))
    } else if end.reason != Reason::Stopped && !(size == 0.0 && end.reason == Reason::DoesNotSlide)
    {
        Err(format!("{name}: {}", end.detail))
    } else if e.residual_j.abs() > 1e-5 * e.work_friction_j.abs() {
        // Steps chosen against the default tolerance (10⁻⁹ a step) and ending at every sample:
        // up to 1.2e-6 of the friction work over a record of a minute.
        Err(format!(
            "{name}: energy residual {} J of {} J",
            e.residual_j, e.work_friction_j
        ))
    } else {
        Ok(())
    }
}

#[test]
fn under_a_record_the_probabilistic_analysis_gives_the_chance_of_a_displacement_over_a_limit() {
    use slideroute::internals::analysis::probabilistic::{Design, Limits, summarise};
    use slideroute::probabilistic::{Sampling, Uncertain};
    // No push, −0.5 g for 0.2 s (a trapezoid, by hand as above) and μ uniform on (0.1, 0.5):
    // every block slides, though no static load pushes it (its factor of safety is unbounded,
    // which called none of them sliding), and the displacement falls with μ, so it exceeds the
    // displacement at μ = 0.3 exactly when μ < 0.3: half the Latin hypercube's strata.
    let dt = 0.01;
    let mut a = vec![-0.5; 21];
    a.extend(std::iter::repeat_n(0.0, 200));
    let limit = exact(&a, dt, 0.3, 0.0);
    let (scene, dir) = pushed_in("probabilistic", &a, dt, 0.3, 0.0, "frame");
    let uncertain: Vec<Uncertain> = vec!["friction.mu_k=uniform:0.1:0.5".parse().unwrap()];
    let design = Design {
        scene: &scene,
        uncertain: &uncertain,
        samples: 40,
        seed: 5,
        sampling: Sampling::LatinHypercube,
    };
    let rows = design.run(|| {}, || false);
    std::fs::remove_dir_all(&dir).ok();
    let limits = Limits::default().with_displacement(Some(limit)).unwrap();
    let s = summarise(&design, limits, &rows);
    assert!(s.shaken);
    assert_eq!(s.routes, 40);
    assert_eq!(s.probability_of_sliding.value, 1.0);
    let over = s.probability_displacement_exceeds_limit.unwrap().value;
    assert_eq!(over, 0.5, "limit {limit} m");
    // Each sample's displacement is the exact one for its μ, so its count is the closed form's.
    for r in &rows {
        let mu = r.values[0];
        let d = r.outcome.route().unwrap().permanent_m().unwrap();
        let want = exact(&a, dt, mu, 0.0);
        assert!(
            (d - want).abs() <= 1e-6 * want + 1e-9,
            "μ = {mu}: {d} m against {want} m"
        );
    }
}

#[test]
fn a_block_on_its_base_rests_while_the_record_holds_it_and_stops_where_the_exact_block_does() {
    // The same block on its whole base (contacts = "base"): flush on the level plane, it
    // rests while friction holds it, each onset and stop located, and its displacement is
    // the exact one to 1e-9.
    let dt = 0.005;
    let a = record(1, 12.0, dt, 0.4);
    let want = exact(&a, dt, 1.0, 0.9);
    let (scene, dir) = pushed_in("base", &a, dt, 1.0, 0.9, "base");
    let route = slideroute::run(&scene).unwrap();
    let x = route.permanent_displacement_xz_m.unwrap()[0];
    assert_eq!(
        route.termination.reason,
        Reason::Stopped,
        "{}",
        route.termination.detail
    );
    assert!(
        (x - want).abs() <= 1e-9 * want,
        "{x} m against the exact {want} m"
    );
    // A record under the yield acceleration (0.05 g against 0.1 g): it never moves.
    let weak = record(2, 6.0, dt, 0.05);
    let (scene, dir2) = pushed_in("base-weak", &weak, dt, 1.0, 0.9, "base");
    let route = slideroute::run(&scene).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    std::fs::remove_dir_all(&dir2).ok();
    assert_eq!(
        route.termination.reason,
        Reason::DoesNotSlide,
        "{}",
        route.termination.detail
    );
    assert_eq!(route.permanent_displacement_xz_m, Some([0.0, 0.0]));
    assert!(
        (route.termination.t_s - 6.0).abs() < 1e-9,
        "{:?}",
        route.termination
    );
}

/// The real records `crosscheck/setup.sh` fetches into `crosscheck/.records`: the eighteen
/// strong-motion records SLAMMER's Python port ships (pyslammer 0.2.2 from PyPI, its
/// `sample_ground_motions`: Cape Mendocino, Chi-Chi, Kobe, Loma Prieta, Northridge and others,
/// 0.005–0.02 s apart, PGA 0.1–1.3 g), as they come: a `#` comment, a header line, then time (s)
/// and acceleration (g).
fn real_records() -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crosscheck/.records");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e} (run crosscheck/setup.sh)", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "csv"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 18, "{}: the eighteen records", dir.display());
    files
}

/// A record file read here, apart from the library's reader: the lines that are two numbers,
/// their accelerations (g) and their common step (s).
fn two_columns(path: &std::path::Path) -> (Vec<f64>, f64) {
    let text = std::fs::read_to_string(path).unwrap();
    let rows: Vec<(f64, f64)> = text
        .lines()
        .filter_map(|l| {
            let (t, a) = l.split_once(',')?;
            Some((t.trim().parse().ok()?, a.trim().parse().ok()?))
        })
        .collect();
    let dt = rows[1].0 - rows[0].0;
    for w in rows.windows(2) {
        assert!(
            (w[1].0 - w[0].0 - dt).abs() < 1e-9,
            "{}: uneven",
            path.display()
        );
    }
    (rows.iter().map(|r| r.1).collect(), dt)
}

/// Real records, as they come, at ky = 0.2 g along X and along Z, at 0.1 g along X, and at
/// 0.1 and 0.05 g under a push of 0.9 and 0.95 of friction (μ = 1): every permanent displacement is the exact one to 0.1 %
/// (or 1e-6 m), the block ends at rest (or never slid, where the exact block does not), nothing
/// moves across, and the energy balance closes to
/// [`BALANCE`] of the work (90 routes, two at a time).
#[test]
#[ignore = "needs the real records (crosscheck/setup.sh); run by .ci/run"]
fn real_records_as_they_come_slide_the_block_the_exact_distance() {
    real_records_on("frame", 1e-3, 1e-3);
}

/// The same ninety on the block's whole base, rows 7 ms apart (no sample's step): each the
/// exact displacement to 1e-6 (the base lies flush on the level plane, so its slide is the
/// equation of `src/route/body/flush.rs`, its onsets and stops located).
#[test]
#[ignore = "needs the real records (crosscheck/setup.sh); run by .ci/run"]
fn real_records_as_they_come_slide_the_block_on_its_base_the_exact_distance() {
    real_records_on("base", 1e-6, 7e-3);
}

/// Every real record as it comes, along X and Z, free and pushed, on `contacts` with rows `dt`
/// (s) apart: the permanent displacement the exact one's to `relative` (and 1e-6 m), two
/// routes at a time.
fn real_records_on(contacts: &'static str, relative: f64, dt: f64) {
    let cases: Vec<_> = real_records()
        .into_iter()
        .flat_map(|f| {
            [
                (f.clone(), "x", 0.2, 0.0),
                (f.clone(), "z", 0.2, 0.0),
                (f.clone(), "x", 0.1, 0.0),
                (f.clone(), "x", 1.0, 0.9),
                (f, "x", 1.0, 0.95),
            ]
        })
        .collect();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let failures = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                while let Some((file, axis, mu, push)) =
                    cases.get(next.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
                {
                    let on = (contacts, relative, dt);
                    if let Err(e) = real_case(file, axis, (*mu, *push), on) {
                        failures.lock().unwrap().push(e);
                    }
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Real records two at a time, each along X with the next of the same sample step along Z
/// (cut to the shorter), at μ = 0.15 without a push and μ = 0.2 pushed along X by 0.9 of it:
/// every permanent displacement is the two-directional Newmark block's ([`two_way_case`]) to
/// 0.1 % (36 routes, two at a time).
#[test]
#[ignore = "needs the real records (crosscheck/setup.sh); run by .ci/run"]
fn real_records_two_at_a_time_slide_the_block_the_two_directional_distance() {
    real_records_two_at_a_time_on("frame");
}

/// Each real record along X with the next of its sample step along Z, on `contacts`, against
/// the two-directional Newmark block ([`two_way_case`]), two routes at a time.
fn real_records_two_at_a_time_on(contacts: &'static str) {
    let records: Vec<_> = real_records()
        .into_iter()
        .map(|f| {
            let (a, dt) = two_columns(&f);
            (f.file_stem().unwrap().to_string_lossy().into_owned(), a, dt)
        })
        .collect();
    let mut cases = Vec::new();
    for (i, (x, ax, dt)) in records.iter().enumerate() {
        let same: Vec<_> = records.iter().filter(|r| (r.2 - dt).abs() < 1e-9).collect();
        let at = same.iter().position(|r| r.0 == *x).unwrap();
        let (z, az, _) = same[(at + 1) % same.len()];
        for (mu, push) in [(0.15, 0.0), (0.2, 0.18)] {
            cases.push((i, format!("{x}+{z}-{mu}-{push}"), ax, az, *dt, mu, push));
        }
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let failures = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                while let Some((_, name, ax, az, dt, mu, push)) =
                    cases.get(next.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
                {
                    // The reference's step 25 µs.
                    let per_sample = (dt / 2.5e-5).round() as usize;
                    let case = (ax.as_slice(), az.as_slice(), *dt);
                    if let Err(e) = two_way_case(name, case, (*mu, *push, contacts), per_sample) {
                        failures.lock().unwrap().push(e);
                    }
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// One real record along `axis`: the route against the exact solution, or what is wrong.
fn real_case(
    file: &std::path::Path,
    axis: &str,
    (mu, push): (f64, f64),
    (contacts, relative, dt_s): (&'static str, f64, f64),
) -> Result<(), String> {
    let stem = file.file_stem().unwrap().to_string_lossy();
    let name = format!("{stem}-{axis}-{mu}-{push}-{contacts}");
    let dir = std::env::temp_dir().join(format!("slideroute-real-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(file, dir.join(file.file_name().unwrap())).unwrap();
    let (a, dt) = two_columns(file);
    let seismic = format!(
        "record_{axis} = \"{}\"\n",
        file.file_name().unwrap().to_string_lossy()
    );
    let run = Run {
        contacts,
        dt_s,
        stride: 1000,
    };
    let t_end = (a.len() - 1) as f64 * dt + 10.0;
    let path = write_shaken(&dir, &name, &seismic, t_end, (mu, push), run);
    let route = Scene::from_file(&path).map(|s| slideroute::run(&s));
    std::fs::remove_dir_all(&dir).ok();
    let route: Route = route
        .map_err(|e| format!("{name}: {e}"))?
        .map_err(|e| format!("{name}: {e}"))?;
    let want = exact(&a, dt, mu, push);
    let [x, z] = route
        .permanent_displacement_xz_m
        .ok_or(format!("{name}: none"))?;
    let (along, across) = if axis == "x" { (x, z) } else { (z, x) };
    let tolerance = relative * want.abs() + relative.min(1e-6);
    let e = route.energy().ok_or(format!("{name}: no energy balance"))?;
    let scale = e.work_hydraulic_j.abs().max(e.work_friction_j.abs());
    let end = &route.termination;
    if (along - want).abs() > tolerance || across.abs() > tolerance {
        Err(format!(
            "{name}: ({along}, {across}) m against the exact {want} m"
        ))
    } else if end.reason != Reason::Stopped && !(want == 0.0 && end.reason == Reason::DoesNotSlide)
    {
        Err(format!("{name}: {}", end.detail))
    } else if e.residual_j.abs() > BALANCE * scale {
        Err(format!(
            "{name}: energy residual {} J of {scale} J",
            e.residual_j
        ))
    } else {
        Ok(())
    }
}

/// The block of [`pushed_in`] on its base, μ 1 and pushed by 0.9 W (k_y 0.1 g without cohesion),
/// shaken along X by `a` at 5 ms, with cohesion c over 20 m² such that c A = `bond` W (zero:
/// none): its route.
fn bonded_on_base(name: &str, a: &[f64], bond: f64) -> Route {
    let dir = std::env::temp_dir().join(format!("slideroute-bond-{name}-{}", std::process::id()));
    let run = Run {
        contacts: "base",
        dt_s: 1e-3,
        stride: 1,
    };
    let path = write_along(&dir, name, (a, 0.005, "x"), (1.0, 0.9), run);
    if bond > 0.0 {
        let text = std::fs::read_to_string(&path).unwrap().replace(
            "[friction]\n",
            &format!(
                "[friction]\ncohesion_pa = {}\ncohesion_area_m2 = 20.0\n",
                bond * 1.0e6 * G / 20.0
            ),
        );
        std::fs::write(&path, text).unwrap();
    }
    let scene = Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let route = slideroute::run(&scene).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    route
}

/// `lead` samples of nothing, then `pulse` g towards −X (the block pushed along +X) for 0.2 s,
/// then 0.5 s of nothing, at 5 ms.
fn pulse(lead: usize, pulse: f64) -> Vec<f64> {
    let mut a = vec![0.0; lead];
    a.extend(std::iter::repeat_n(-pulse, 41));
    a.extend(std::iter::repeat_n(0.0, 100));
    a
}

#[test]
fn a_bonded_base_under_a_record_holds_until_a_pulse_passes_its_cohesion_and_then_slides_by_friction_alone()
 {
    // Cohesion adds 0.1 g to the yield acceleration (0.1 g of friction against the push): the
    // base's is 0.2 g where it rests.
    let weak = pulse(0, 0.15);
    let bonded = bonded_on_base("weak", &weak, 0.1);
    assert!(
        (bonded.yield_acceleration.unwrap().ky_g - 0.2).abs() < 1e-6,
        "{:?}",
        bonded.yield_acceleration
    );
    // A pulse of 0.15 g: over friction's 0.1 g, under the bond's 0.2 g. Without cohesion it
    // slides the exact distance; with it, not at all.
    assert_eq!(
        bonded.termination.reason,
        Reason::DoesNotSlide,
        "{}",
        bonded.termination.detail
    );
    assert_eq!(bonded.permanent_displacement_xz_m, Some([0.0, 0.0]));
    assert_eq!(bonded.base().unwrap().bond_broken_s, None);
    let free = bonded_on_base("weak-free", &weak, 0.0);
    let want = exact(&weak, 0.005, 1.0, 0.9);
    let x = free.permanent_displacement_xz_m.unwrap()[0];
    assert!(
        want > 0.01 && (x - want).abs() < 1e-9 * want,
        "{x} m against {want} m"
    );
    // A pulse of 0.3 g from the start breaks the bond at once: it slides as without cohesion,
    // row for row, Newmark's exact distance for μ alone.
    let strong = pulse(0, 0.3);
    let (with, without) = (
        bonded_on_base("strong", &strong, 0.1),
        bonded_on_base("strong-free", &strong, 0.0),
    );
    assert_eq!(with.rows, without.rows);
    assert_eq!(with.base().unwrap().bond_broken_s, Some(0.0));
    let want = exact(&strong, 0.005, 1.0, 0.9);
    let x = with.permanent_displacement_xz_m.unwrap()[0];
    assert!((x - want).abs() < 1e-9 * want, "{x} m against {want} m");
    // Rising from nothing at 0.095 s to 0.3 g at 0.1 s, it passes 0.2 g at 0.09833 s: the bond
    // holds the step from rest at 0.098 s (0.18 g) and breaks at the one from 0.099 s (0.24 g).
    let late = bonded_on_base("late", &pulse(20, 0.3), 0.1);
    let broke = late.base().unwrap().bond_broken_s.unwrap();
    assert!((broke - 0.099).abs() < 1e-9, "{broke}");
    assert!(late.permanent_displacement_xz_m.unwrap()[0] > 0.0);
}
