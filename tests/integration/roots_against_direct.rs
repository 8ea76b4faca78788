//! The selected root (exact mode) agrees with the independent direct pose solver, on random
//! scenes and poses that include the awkward ones: θ = 0, θ + κ = 0, dips of 1–3° and 55–70°,
//! κ from 0 to 80°, lopsided frames, and displacements from 1e-6·L to where a contact leaves
//! its plane.

use crate::common::{sample, scene};
use proptest::prelude::*;
use slideroute::internals::geometry::{Displacement, Pose, direct};
use slideroute::internals::roots::{self, classify};
use slideroute::internals::{model::Mode, scene::Scene};

fn dip() -> impl Strategy<Value = f64> {
    prop_oneof![1.0..3.0f64, 3.0..55.0f64, 55.0..70.0f64]
}

fn frame_fraction() -> impl Strategy<Value = f64> {
    // l1z / L from lopsided (l1z/l2z = 0.1 and 10) to even.
    prop_oneof![Just(1.0 / 11.0), Just(10.0 / 11.0), 0.1..0.9f64]
}

prop_compose! {
    fn hard_cases()(
        l in 1.0..50.0f64,
        l2x in 0.15..0.85f64,
        l1z in frame_fraction(),
        xi in dip(),
        zeta in dip(),
        kappa in 0.0..80.0f64,
        x_exp in -6.0..0.2f64,
        z in -0.1..0.1f64,
        theta in prop_oneof![Just(0.0), Just(f64::NAN), -25.0..25.0f64],
    ) -> (Scene, Displacement) {
        let s = scene(l, l2x, l1z, xi, zeta, kappa);
        let x = 10f64.powf(x_exp) * l;
        // NAN marks "θ + κ = 0" (the other perfect-square case of (15)).
        let th = if theta.is_nan() { -kappa } else { theta };
        (s, Displacement::new(x, z * x, th.to_radians() * (x / l).min(1.0)))
    }
}

/// The oracle's pose, if it is an admissible one.
fn oracle(s: &Scene, d: Displacement) -> Option<(f64, f64)> {
    let p = direct::solve(s.site(), d).ok()?;
    let l = s.l();
    let (a, b) = (p.alpha(l), p.beta(l));
    let pose = Pose::from_tilts(s.site().as_paper().unwrap(), d, a, b).ok()?;
    classify::check_pose(s.site(), &pose).ok()?;
    Some((a, b))
}

#[test]
fn selected_exact_root_matches_the_direct_solver() {
    let (mut compared, mut both_refused) = (0, 0);
    for (s, d) in sample(hard_cases(), 1500) {
        let want = oracle(&s, d);
        let got = roots::select(s.site(), d, Mode::Exact);
        match (want, got) {
            (Some((a, b)), Ok(p)) => {
                let pose = Pose::from_tilt_roll(s.site(), d, p.u[0], p.u[1]).unwrap();
                assert!(
                    (pose.alpha - a).abs() <= 1e-10,
                    "α {} vs {} at {d:?} in {s:?}",
                    pose.alpha,
                    a
                );
                assert!(
                    (pose.beta - b).abs() <= 1e-10,
                    "β {} vs {} at {d:?} in {s:?}",
                    pose.beta,
                    b
                );
                compared += 1;
            }
            (Some(_), Err(e)) => panic!("oracle admissible but tracker: {e} at {d:?} in {s:?}"),
            (None, Ok(p)) => {
                panic!("tracker admissible ({p:?}) where the oracle is not, {d:?} in {s:?}")
            }
            (None, Err(_)) => both_refused += 1,
        }
    }
    eprintln!("compared {compared}, refused by both {both_refused}");
    assert!(compared >= 500, "only {compared} admissible cases compared");
}

#[test]
fn all_roots_select_the_same_pose_as_the_tracker_and_the_oracle() {
    let s = Scene::default_scene();
    for (x, z, th) in [
        (1e-5, 0.0, 0.0),
        (0.3, 0.05, 1.0),
        (1.5, -0.2, -2.0),
        (2.5, 0.4, 3.0),
    ] {
        let d = Displacement::new(x, z, f64::to_radians(th));
        let (a, b) = oracle(&s, d).expect("admissible");
        let all = roots::solve_all(s.site(), d, Mode::Exact).unwrap();
        let k = all.selected.expect("selected");
        let r = &all.roots[k];
        assert!(r.admissible);
        assert!((r.alpha.re - a).abs() < 1e-10 && (r.beta.re - b).abs() < 1e-10);
        assert_eq!(all.finite_roots + all.roots_at_infinity, 8);
    }
}

#[test]
fn poses_beyond_a_contact_leaving_its_plane_are_refused_with_the_reason() {
    // Yawed far negative, vertex 2 climbs down off plane 2 (β < 0): the region test, which
    // names the contact, decides (the tilt's lower bound is the same test in another form).
    let s = Scene::default_scene();
    let d = Displacement::new(1.0, 0.0, (-30f64).to_radians());
    let e = roots::select(s.site(), d, Mode::Exact).unwrap_err();
    assert!(e.to_string().contains("contact 2 left plane 2"), "{e}");
}

#[test]
fn the_rest_pose_is_a_selected_root() {
    // X = Z = θ = 0, both inclined contacts on their strikes: the eigenvalue solve of the
    // resultant misses this root (the system degenerates there), and `roots` answered "no pose
    // selected". The tracked pose, which satisfies the equations, is the root.
    let s = Scene::default_scene();
    for mode in [Mode::Exact, Mode::SmallAngle] {
        let all = roots::solve_all(s.site(), Displacement::new(0.0, 0.0, 0.0), mode).unwrap();
        let k = all
            .selected
            .unwrap_or_else(|| panic!("{mode:?}: {:?}", all.selection_error));
        let r = &all.roots[k];
        assert!(r.admissible && r.real);
        assert!(r.alpha.re.abs() < 1e-12 && r.beta.re.abs() < 1e-12, "{r:?}");
    }
}
