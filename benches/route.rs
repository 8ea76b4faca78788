//! Whole routes and single increments: `cargo bench --bench route`.
//!
//! * the paper-like route (20 s at dt = 1 ms; it ends at 2.024 s), exact and small-angle,
//!   frictional and frictionless (what a scene pays for); the rigid-body route over 3 s;
//! * one increment: pose by continuation, frictionless statics, the followed frictional
//!   reactions, accelerations — and the same with the pose by all roots.

use criterion::{Criterion, criterion_group, criterion_main};
use slideroute::stages::geometry::Displacement;
use slideroute::stages::route::pose_finder::PoseFinder;
use slideroute::stages::route::{self, PoseMethod, rhs};
use slideroute::stages::scene::{DynamicsModel, Friction, Mode, Scene};
use std::hint::black_box;

fn whole_routes(c: &mut Criterion) {
    // The paper's dynamics (the default is the rigid body's).
    let base = Scene::default_scene().with_dynamics(DynamicsModel::Paper);
    let mut small = base.clone();
    small.solver.as_mut().unwrap().mode = Mode::SmallAngle;
    let mut frictionless = base.clone();
    frictionless.friction = Some(Friction::Coulomb { mu_k: 0.0 });
    frictionless.loads.as_mut().unwrap().hydraulic_force = 4.0e6;
    // Rigid-body dynamics, 3 s at 1 ms (RK4: four evaluations per increment).
    let mut rigid = base.with_dynamics(DynamicsModel::RigidBody);
    rigid.solver.as_mut().unwrap().t_end = 3.0;
    let mut rigid_frictionless = frictionless.with_dynamics(DynamicsModel::RigidBody);
    rigid_frictionless.solver.as_mut().unwrap().t_end = 3.0;
    for (name, s) in [
        ("paper-like route, exact, friction", &base),
        ("paper-like route, small-angle, friction", &small),
        ("paper-like route, exact, frictionless", &frictionless),
        ("rigid-body route 3 s, exact, friction", &rigid),
        (
            "rigid-body route 3 s, exact, frictionless",
            &rigid_frictionless,
        ),
    ] {
        c.bench_function(name, |b| b.iter(|| route::run(black_box(s)).unwrap()));
    }
}

fn one_increment(c: &mut Criterion) {
    let scene = Scene::default_scene().with_dynamics(DynamicsModel::Paper);
    let dynamics = slideroute::stages::scene::Simulation::new(&scene).unwrap();
    for method in [PoseMethod::Continuation, PoseMethod::AllRoots] {
        // Position the finder and the chosen reaction at X = 0.5 m, then time the next 1 mm.
        let mut finder = PoseFinder::new(&scene, Mode::Exact, method);
        let mut prev = None;
        for k in 1..=500 {
            let d = Displacement::new(1e-3 * k as f64, 0.0, -1e-4 * k as f64);
            let ev = rhs::evaluate(&scene, &dynamics, &mut finder, d, prev.as_ref(), None).unwrap();
            prev = Some(ev.reaction);
        }
        let next = Displacement::new(0.501, 0.0, -0.0501);
        c.bench_function(&format!("one increment ({})", method.as_str()), |b| {
            b.iter(|| {
                let mut f = finder.clone();
                rhs::evaluate(
                    &scene,
                    &dynamics,
                    &mut f,
                    black_box(next),
                    prev.as_ref(),
                    None,
                )
                .unwrap()
            })
        });
    }
}

criterion_group!(benches, whole_routes, one_increment);
criterion_main!(benches);
