//! The pose system for any contact triangle and any three planes
//! (`derivations/09-general-pose.md`): on the paper's site it has the paper's roots; on any site
//! its selected root is the direct pose solver's pose.

use crate::common::{sample, scene};
use proptest::prelude::*;
use slideroute::Mode;
use slideroute::internals::geometry::{Displacement, Plane, Pose, Site, direct};
use slideroute::internals::roots::{self, Tracker};

/// The paper's site as a general one: the same contacts on the same planes.
fn twin(site: &Site) -> Site {
    Site::general(*site.contacts(), *site.planes())
}

/// A scalene triangle under three planes of any dip and dip direction, each through its
/// contact's start.
fn scalene(dips_deg: [f64; 3], directions_deg: [f64; 3]) -> Site {
    let contacts = [[-4.0, 3.0], [5.5, 1.5], [0.5, -4.5]];
    let planes = std::array::from_fn(|k| {
        let start = nalgebra::Vector3::new(contacts[k][0], 0.0, contacts[k][1]);
        Plane::from_dip(
            dips_deg[k].to_radians(),
            directions_deg[k].to_radians(),
            start,
        )
    });
    Site::general(contacts, planes)
}

#[test]
fn on_the_papers_site_the_general_system_has_the_papers_roots_to_1e_12() {
    // Every root of the exact systems, paper's and general, at displacements from tiny to where
    // a contact leaves its plane; matched one to one.
    let cases = [
        (10.0, 0.4, 0.5, 20.0, 25.0, 30.0),
        (7.0, 0.3, 0.8, 5.0, 40.0, 70.0),
        (25.0, 0.6, 0.2, 55.0, 12.0, 5.0),
    ];
    let mut compared = 0;
    for (l, l2x, l1z, xi, zeta, kappa) in cases {
        let s = scene(l, l2x, l1z, xi, zeta, kappa);
        let general = twin(s.site());
        for d in [
            Displacement::new(1e-6 * l, 0.0, 0.0),
            Displacement::new(0.05 * l, -0.01 * l, 0.03),
            Displacement::new(0.2 * l, 0.04 * l, -0.2),
        ] {
            let p = roots::solve_all(s.site(), d, Mode::Exact).unwrap();
            let g = roots::solve_all(&general, d, Mode::Exact).unwrap();
            assert_eq!(p.finite_roots, g.finite_roots, "{d:?}");
            for r in &p.roots {
                let psi = r.psi.unwrap();
                let nearest = g
                    .roots
                    .iter()
                    .map(|q| {
                        (q.alpha - r.alpha)
                            .norm()
                            .max((q.psi.unwrap() - psi).norm())
                    })
                    .fold(f64::INFINITY, f64::min);
                assert!(nearest < 1e-12, "{nearest:e} at {d:?}, L = {l}");
                compared += 1;
            }
            // The same root is selected.
            let (ps, gs) = (p.selected.unwrap(), g.selected.unwrap());
            assert!((p.roots[ps].alpha - g.roots[gs].alpha).norm() < 1e-12);
            assert_eq!(p.roots[ps].admissible, g.roots[gs].admissible);
        }
    }
    assert!(compared >= 30, "{compared}");
}

#[test]
fn on_the_papers_site_the_general_tracker_follows_the_papers_branch() {
    let s = scene(10.0, 0.4, 0.5, 20.0, 25.0, 30.0);
    let general = twin(s.site());
    let (mut a, mut b) = (
        Tracker::new(s.site(), Mode::Exact),
        Tracker::new(&general, Mode::Exact),
    );
    let end = Displacement::new(2.5, 0.6, 0.3);
    for k in 1..=50 {
        let d = end.scaled(k as f64 / 50.0);
        let (p, q) = (a.advance(d).unwrap(), b.advance(d).unwrap());
        assert!((p.u[0] - q.u[0]).abs() < 1e-12 && (p.u[1] - q.u[1]).abs() < 1e-12);
    }
}

fn any_site() -> impl Strategy<Value = (Site, Displacement)> {
    (
        prop::array::uniform3(0.0..50.0f64),
        prop::array::uniform3(-180.0..180.0f64),
        -1.5..1.5f64,
        -1.5..1.5f64,
        -0.4..0.4f64,
        -4.0..0.0f64,
    )
        .prop_map(|(dips, dirs, x, z, theta, size)| {
            let k = 10f64.powf(size);
            (
                scalene(dips, dirs),
                Displacement::new(x * k, z * k, theta * k),
            )
        })
}

#[test]
fn on_any_site_the_followed_root_is_the_direct_solvers_pose() {
    // Scalene triangles on planes of any dip (0–50°) and dip direction, displacements from
    // 1e-4 to 1.5 m, each contact held on its own plane extended without limit (no regions):
    // the branch followed from the flat start places every contact where the oracle, continued
    // along the same segment, does.
    let (mut compared, mut refused) = (0, 0);
    for (site, d) in sample(any_site(), 400) {
        let Ok(oracle) = direct::solve(&site, d) else {
            continue;
        };
        let mut tracker = Tracker::new(&site, Mode::Exact).without_regions();
        match tracker.advance(d) {
            Ok(p) => {
                let pose = Pose::from_tilt_roll(&site, d, p.u[0], p.u[1]).unwrap();
                for (v, w) in pose.vertices.iter().zip(&oracle.vertices) {
                    assert!((v - w).norm() < 1e-9, "{v} vs {w} at {d:?}");
                }
                // And each contact is on its plane.
                for (k, v) in pose.vertices.iter().enumerate() {
                    assert!(site.planes()[k].signed_distance(v).abs() < 1e-11);
                }
                compared += 1;
            }
            Err(_) => refused += 1,
        }
    }
    println!("compared {compared}, refused {refused}");
    assert!(compared >= 200, "compared {compared}, refused {refused}");
}

#[test]
fn the_general_small_angle_pose_is_the_exact_one_to_second_order() {
    let site = scalene([8.0, 12.0, 10.0], [170.0, -160.0, 100.0]);
    let err = |s: f64| {
        let d = Displacement::new(0.4 * s, -0.1 * s, 0.05 * s);
        let follow = |mode| {
            let mut t = Tracker::new(&site, mode).without_regions();
            t.advance(d).unwrap()
        };
        let (e, a) = (follow(Mode::Exact), follow(Mode::SmallAngle));
        (e.u[0] - a.u[0]).abs().max((e.u[1] - a.u[1]).abs())
    };
    let (e1, e2) = (err(0.2), err(0.1));
    let order = (e1 / e2).log2();
    assert!((1.6..3.4).contains(&order), "{e1:e} {e2:e}: order {order}");
    // Bilinear in (α, ψ): at most two roots, found by the same eigenvalue solver, one of them
    // the followed one.
    let d = Displacement::new(0.04, -0.01, 0.005);
    let all = roots::solve_all(&site, d, Mode::SmallAngle).unwrap();
    assert!(all.finite_roots <= 2, "{}", all.finite_roots);
    let mut t = Tracker::new(&site, Mode::SmallAngle).without_regions();
    let u = t.advance(d).unwrap().u;
    assert!(all.roots.iter().any(|r| {
        (r.alpha.re - u[0]).abs() < 1e-10 && (r.psi.unwrap().re - u[1]).abs() < 1e-10
    }));
}
