//! The rigid-body dynamics mode (issue #7): energy, the direct pose solver, the scenes where
//! the paper's dynamics has no solution, the flat limit with friction, and the start.

mod common;

use slideroute::route::{self, Reason, Route};
use slideroute::scene::{DynamicsModel, Friction, Scene};

fn rigid(f: impl FnOnce(&mut Scene)) -> Scene {
    let mut s = Scene::default_scene().with_dynamics(DynamicsModel::RigidBody);
    f(&mut s);
    s
}

fn run(s: &Scene) -> Route {
    route::run(s).expect("scene has the dynamics sections")
}

fn set_time(s: &mut Scene, dt: f64, t_end: f64) {
    let solver = s.solver.as_mut().unwrap();
    solver.dt = dt;
    solver.t_end = t_end;
}

#[test]
fn frictionless_rigid_body_conserves_energy_at_fourth_order() {
    // Work of F and its couple = kinetic + potential energy, to RK4's error: the residual
    // falls about 16× per halving of dt.
    let residual = |dt: f64| {
        let s = rigid(|s| {
            s.friction = Some(Friction::Coulomb { mu_k: 0.0 });
            set_time(s, dt, 1.0);
        });
        let r = run(&s);
        assert_eq!(
            r.termination.reason,
            Reason::TimeLimit,
            "{:?}",
            r.termination
        );
        let e = r.energy.unwrap();
        assert_eq!(e.work_friction_j, 0.0);
        (e.residual_j.abs(), e.work_hydraulic_j)
    };
    let (r1, w) = residual(0.02);
    let (r2, _) = residual(0.01);
    let (r3, _) = residual(0.005);
    println!("residuals {r1:.3e} {r2:.3e} {r3:.3e} J of {w:.3e} J");
    assert!(r3 < 1e-7 * w, "{r3} J");
    assert!(r1 / r2 > 10.0 && r2 / r3 > 10.0, "{r1} {r2} {r3}");
}

#[test]
fn with_friction_the_energy_lost_equals_the_friction_work() {
    let s = rigid(|s| set_time(s, 1e-3, 3.0));
    let r = run(&s);
    let e = r.energy.unwrap();
    println!("{e:?}");
    assert!(e.work_friction_j < -1e7, "friction did work: {e:?}");
    // W_h + W_f − ΔT − ΔV = 0 to the integrator's error.
    assert!(e.residual_j.abs() < 1e-9 * e.work_hydraulic_j, "{e:?}");
}

#[test]
fn every_rigid_body_row_agrees_with_the_direct_pose_solver() {
    let s = rigid(|s| set_time(s, 1e-3, 4.0));
    let r = run(&s);
    assert!(r.rows.len() > 3000);
    common::assert_rows_match_direct(&s, &r.rows);
}

#[test]
fn rigid_body_moves_where_the_papers_frictional_system_has_no_solution() {
    // κ = 0 (a common foundation), and μ = 0.05 on the paper-like geometry: the paper's
    // dynamics ends with "no solution"; the rigid body gives a route to a stated physical end.
    let kappa0 = |s: &mut Scene| s.foundation.kappa = 0.0;
    let mu005 = |s: &mut Scene| s.friction = Some(Friction::Coulomb { mu_k: 0.05 });
    for (name, edit) in [
        ("κ = 0", &kappa0 as &dyn Fn(&mut Scene)),
        ("μ = 0.05", &mu005),
    ] {
        let mut paper = Scene::default_scene();
        edit(&mut paper);
        let p = run(&paper);
        assert_eq!(
            p.termination.reason,
            Reason::NoFrictionSolution,
            "{name}: paper {:?}",
            p.termination
        );
        let r = run(&paper.with_dynamics(DynamicsModel::RigidBody));
        println!(
            "{name}: paper ends at {} s ({}); rigid body {} at {} s after {:.3} m",
            p.termination.t_s,
            p.termination.reason,
            r.termination.reason,
            r.termination.t_s,
            r.travel_m
        );
        assert!(r.travel_m > 1.0, "{name}: {:?}", r.termination);
        assert!(
            matches!(
                r.termination.reason,
                Reason::TimeLimit
                    | Reason::Contact0ReachedInclinedPlane
                    | Reason::ContactLeftPlane
                    | Reason::TiltReachedDip
                    | Reason::ContactLiftedOff
                    | Reason::Stopped
            ),
            "{name}: {:?}",
            r.termination
        );
    }
}

#[test]
fn flat_limit_with_friction_converges_to_the_sliding_block_closed_form() {
    // With c = 0 on planes of vanishing dip, the normals carry the weight at the CM's
    // centroid of contact loads, so friction against pure translation has no moment:
    // X(t) = ½ (F/m − μ g) t², Z = θ = 0. The planes' dips change it at first order.
    let err = |dip_deg: f64| {
        let s = rigid(|s| {
            s.foundation.xi = dip_deg.to_radians();
            s.foundation.zeta = dip_deg.to_radians();
            s.loads.as_mut().unwrap().eccentricity = 0.0;
            set_time(s, 1e-3, 1.0);
        });
        let r = run(&s);
        assert_eq!(r.termination.reason, Reason::TimeLimit);
        let last = r.rows.last().unwrap();
        let want = 0.5 * (8.0 - 0.4 * 9.81) * last.t_s * last.t_s;
        ((last.x_m - want).abs() / want, last.theta_deg.abs())
    };
    let (e1, th1) = err(0.04);
    let (e2, _) = err(0.02);
    let (e3, th3) = err(0.01);
    println!("relative errors {e1:.3e} {e2:.3e} {e3:.3e}; |θ| {th1:.2e}° {th3:.2e}°");
    assert!(e3 < 1e-3, "{e3}");
    let order = (e1 / e3).log2() / 2.0;
    assert!((0.8..1.2).contains(&order), "order {order}");
}

#[test]
fn held_blocks_do_not_slide() {
    let no_force = rigid(|s| s.loads.as_mut().unwrap().hydraulic_force = 0.0);
    let high_friction = rigid(|s| s.friction = Some(Friction::Coulomb { mu_k: 1.0 }));
    for s in [no_force, high_friction] {
        let r = run(&s);
        assert_eq!(
            r.termination.reason,
            Reason::DoesNotSlide,
            "{:?}",
            r.termination
        );
        assert!(r.factor_of_safety.unwrap().at_least_one());
        assert_eq!(r.rows.len(), 1);
    }
}

#[test]
fn factor_of_safety_onset_separates_sliding_from_holding() {
    // Just below and just above the load that static friction can hold.
    let base = run(&rigid(|s| set_time(s, 1e-3, 0.05)));
    let fs = base.factor_of_safety.unwrap().value().unwrap();
    assert!((0.8..0.95).contains(&fs), "{fs}");
    let scaled = |k: f64| {
        run(&rigid(|s| {
            s.loads.as_mut().unwrap().hydraulic_force *= k;
            set_time(s, 1e-3, 0.05);
        }))
    };
    // Dividing F by FS puts the block at the limit: 1% less is held.
    assert_eq!(scaled(fs * 0.99).termination.reason, Reason::DoesNotSlide);
    assert_ne!(scaled(fs * 1.05).termination.reason, Reason::DoesNotSlide);
}

/// The speeds of a route's last row are exactly zero.
fn ends_at_rest(r: &Route) -> bool {
    let last = r.rows.last().unwrap();
    last.vx_m_s == 0.0 && last.vz_m_s == 0.0 && last.omega_deg_s == 0.0
}

#[test]
fn a_kicked_block_stops_where_the_sliding_block_closed_form_says() {
    // Flat limit (c = 0, dips → 0), μ g > F/m: a block set moving at v0 along X decelerates at
    // d = μ g − F/m and stops at t* = v0/d after x* = v0²/(2d); static friction then holds it.
    let (v0, mu) = (2.0, 1.0);
    let d = mu * 9.81 - 8.0;
    let err = |dip_deg: f64| {
        let s = rigid(|s| {
            s.foundation.xi = dip_deg.to_radians();
            s.foundation.zeta = dip_deg.to_radians();
            s.loads.as_mut().unwrap().eccentricity = 0.0;
            s.friction = Some(Friction::Coulomb { mu_k: mu });
            s.initial.vx = v0;
            set_time(s, 1e-3, 3.0);
        });
        let r = run(&s);
        assert_eq!(r.termination.reason, Reason::Stopped, "{:?}", r.termination);
        assert!(ends_at_rest(&r));
        let e = r.energy.unwrap();
        assert_eq!(e.kinetic_j, 0.0);
        // ½ m v0², plus the small tilting the planes' dips bring into the twist.
        let k0 = 0.5 * 1e6 * v0 * v0;
        assert!((e.kinetic_initial_j - k0).abs() < 1e-3 * k0, "{e:?}");
        assert!(e.residual_j.abs() < 1e-8 * e.work_friction_j.abs(), "{e:?}");
        let last = r.rows.last().unwrap();
        (
            (r.termination.t_s - v0 / d).abs() / (v0 / d),
            (last.x_m - v0 * v0 / (2.0 * d)).abs() / (v0 * v0 / (2.0 * d)),
        )
    };
    let (t1, x1) = err(0.04);
    let (t3, x3) = err(0.01);
    println!("stop time errors {t1:.3e} {t3:.3e}; distance errors {x1:.3e} {x3:.3e}");
    assert!(t3 < 1e-3 && x3 < 1e-3, "{t3} {x3}");
    for (a, b) in [(t1, t3), (x1, x3)] {
        let order = (a / b).log2() / 2.0;
        assert!((0.8..1.2).contains(&order), "order {order}");
    }
}

#[test]
fn a_kicked_block_on_the_paper_like_foundation_stops_and_is_held() {
    // μ = 0.6 (FS 1.23 at onset) and 1 m/s along X: the block turns, its contacts' slips pass
    // through zero one after another, and it comes to rest where static friction holds it.
    let s = Scene::from_file(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/kicked.toml"),
    )
    .unwrap();
    let r = run(&s);
    assert_eq!(r.termination.reason, Reason::Stopped, "{:?}", r.termination);
    assert!(ends_at_rest(&r));
    assert!(r.termination.detail.contains("static friction holds"));
    assert!(
        (0.5..1.0).contains(&r.termination.t_s),
        "{}",
        r.termination.t_s
    );
    let e = r.energy.unwrap();
    assert!(e.residual_j.abs() < 1e-6 * e.work_friction_j.abs(), "{e:?}");
    common::assert_rows_match_direct(&s, &r.rows);
}
