//! Whole routes and single increments: `cargo bench --bench route`.
//!
//! * the paper-like route (20 s at dt = 1 ms; it ends at 2.024 s), exact and small-angle,
//!   frictional and frictionless (what a scene pays for); the rigid-body route over 3 s;
//! * one increment: pose by continuation, frictionless statics, the followed frictional
//!   reactions, accelerations — and the same with the pose by all roots.

use criterion::{Criterion, criterion_group, criterion_main};
use slideroute::Displacement;
use slideroute::internals::route::PoseMethod;
use slideroute::internals::route::paper::evaluate;
use slideroute::internals::route::pose_finder::PoseFinder;
use slideroute::internals::{
    model::{DynamicsModel, Mode},
    scene::Scene,
};
use std::hint::black_box;

/// `s` with its frame written as `contacts_m` (the same contacts, the general pose system).
fn as_contacts(s: &Scene) -> Scene {
    let c = s.site().contacts();
    let mut doc = s.document().clone();
    let frame = toml::Value::Array(
        c.iter()
            .map(|p| toml::Value::Array(vec![p[0].into(), p[1].into()]))
            .collect(),
    );
    let mut table = toml::Table::new();
    table.insert("contacts_m".into(), frame);
    doc.insert("frame".into(), toml::Value::Table(table));
    Scene::from_toml(&toml::to_string(&doc).unwrap(), "contacts").unwrap()
}

fn whole_routes(c: &mut Criterion) {
    // The paper's dynamics (the default is the rigid body's).
    let base = Scene::default_scene()
        .with_dynamics(DynamicsModel::Paper)
        .unwrap();
    let small = base.with("solver.mode", "small-angle").unwrap();
    let frictionless = base
        .with("friction.mu_k", 0.0)
        .and_then(|s| s.with("loads.hydraulic_force_n", 4.0e6))
        .unwrap();
    // Rigid-body dynamics, 3 s at 1 ms (RK4: four evaluations per increment).
    let rigid_3s = |s: &Scene| {
        s.with_dynamics(DynamicsModel::RigidBody)
            .and_then(|s| s.with("solver.t_end_s", 3.0))
            .unwrap()
    };
    let rigid = rigid_3s(&base);
    let rigid_frictionless = rigid_3s(&frictionless);
    // The same scene as any triangle (`contacts_m`): the general pose system.
    let general = rigid_3s(&as_contacts(&base));
    for (name, s) in [
        ("paper-like route, exact, friction", &base),
        ("paper-like route, small-angle, friction", &small),
        ("paper-like route, exact, frictionless", &frictionless),
        ("rigid-body route 3 s, exact, friction", &rigid),
        (
            "rigid-body route 3 s, exact, frictionless",
            &rigid_frictionless,
        ),
        (
            "rigid-body route 3 s, exact, friction, general system",
            &general,
        ),
    ] {
        c.bench_function(name, |b| b.iter(|| slideroute::run(black_box(s)).unwrap()));
    }
}

fn one_increment(c: &mut Criterion) {
    let scene = Scene::default_scene()
        .with_dynamics(DynamicsModel::Paper)
        .unwrap();
    let sim = scene.simulation().unwrap();
    for method in [PoseMethod::Continuation, PoseMethod::AllRoots] {
        // Position the finder and the chosen reaction at X = 0.5 m, then time the next 1 mm.
        let mut finder = PoseFinder::new(sim.first_body().site(), Mode::Exact, method);
        let mut prev = None;
        for k in 1..=500 {
            let d = Displacement::new(1e-3 * k as f64, 0.0, -1e-4 * k as f64);
            let ev = evaluate(
                (&sim, sim.first_body()),
                &mut finder,
                d,
                prev.as_ref(),
                None,
            )
            .unwrap();
            prev = Some(ev.reaction);
        }
        let next = Displacement::new(0.501, 0.0, -0.0501);
        c.bench_function(&format!("one increment ({})", method.as_str()), |b| {
            b.iter(|| {
                let mut f = finder.clone();
                evaluate(
                    (&sim, sim.first_body()),
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
