//! The touches the solver finds with its own exact geometry against a collision library's view
//! of the same rock (`parry3d-f64`, through `Rock`): a base in any pose, lowered onto rough rock
//! until parry first sees it meet the rock and then raised 10 µm, is as far from the rock by
//! the touches' least gap as by parry's distance. A place where base and rock first meet that
//! the touches miss (a vertex, an edge across an edge) shows as a least gap larger than parry's
//! distance; a touch that is not there, as a smaller one.

use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use slideroute::internals::geometry::{
    BodyPose, Footprint, Ground, Relief, Touches, cast, relief_touches, touches,
};
use slideroute::internals::scene::Scene;
use std::path::Path;

/// The ground of a scene of `scenes/body/`.
fn ground_of(scene: &str) -> Ground {
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/body")
        .join(scene);
    let scene = Scene::from_file(&file).unwrap();
    (**scene.site().shared_ground().unwrap()).clone()
}

/// A rotation with yaw `yaw` and a tilt `tilt` (rad) about a horizontal axis at `axis` (rad
/// from +X).
fn turned(yaw: f64, tilt: f64, axis: f64) -> Matrix3<f64> {
    let h = Unit::new_normalize(Vector3::new(axis.cos(), 0.0, axis.sin()));
    (Rotation3::from_axis_angle(&h, tilt) * Rotation3::from_axis_angle(&Vector3::y_axis(), yaw))
        .into_inner()
}

/// Lowers the base (its triangles in body axes, `tris`) at `pose` until parry first sees it
/// meet `ground`'s rock (a triangle wholly under a surface meets none of its faces: a corner
/// below the rock counts too), to 1e-12 m. Returns the pose there.
fn first_contact(ground: &Ground, tris: &[[Vector3<f64>; 3]], pose: &BodyPose) -> BodyPose {
    let rock = ground.rock();
    let inside = |dy: f64| {
        let p = raised(pose, dy);
        tris.iter().any(|t| {
            let w = t.map(|c| p.point(&c));
            rock.distance(w) == 0.0 || rock.deepest(w) > 0.0
        })
    };
    let (mut hi, mut lo) = (0.0, -1.0);
    while inside(hi) {
        hi += 1.0;
    }
    while !inside(lo) {
        lo -= 1.0;
    }
    while hi - lo > 1e-12 {
        let mid = 0.5 * (hi + lo);
        if inside(mid) { lo = mid } else { hi = mid }
    }
    raised(pose, hi)
}

/// `pose` moved up by `dy` (m).
fn raised(pose: &BodyPose, dy: f64) -> BodyPose {
    BodyPose {
        cm: pose.cm + Vector3::new(0.0, dy, 0.0),
        rotation: pose.rotation,
    }
}

/// How far above parry's first contact the two are compared (m): clear of parry's own
/// tolerance on meeting (seen up to 1.5e-7 m).
const CLEAR: f64 = 1e-5;

/// Checks that at `pose` raised by [`CLEAR`] the touches' least gap is parry's distance from
/// the base's triangles `tris` (body axes) to the rock, to 1e-10 m.
fn assert_touches_agree(
    what: &str,
    ground: &Ground,
    tris: &[[Vector3<f64>; 3]],
    pose: &BodyPose,
    find: impl Fn(&BodyPose) -> Touches,
) {
    let up = raised(pose, CLEAR);
    let found = find(&up);
    assert!(found.off_ground.is_empty(), "{what}: off ground");
    let ours = found
        .touches
        .iter()
        .map(|t| t.gap)
        .fold(f64::INFINITY, f64::min);
    let parry = tris
        .iter()
        .map(|t| ground.rock().distance(t.map(|c| up.point(&c))))
        .fold(f64::INFINITY, f64::min);
    assert!(
        parry > 0.5 * CLEAR && (ours - parry).abs() <= 1e-10,
        "{what}: the touches' least gap {ours:e} m, parry's distance {parry:e} m"
    );
}

#[test]
fn a_flat_base_lowered_onto_rough_rock_first_meets_it_where_a_touch_says() {
    // A 10 m × 8 m rectangle and an L of the same size (a re-entrant corner), 2 m under the CM,
    // yawed anyhow and tilted up to 8° over the steep rough terrain (cells 2 m, slopes to 6°).
    let ground = ground_of("cast-monolith.toml");
    let rectangle = vec![[-5.0, -4.0], [5.0, -4.0], [5.0, 4.0], [-5.0, 4.0]];
    let ell = vec![
        [-5.0, -4.0],
        [5.0, -4.0],
        [5.0, 0.0],
        [0.0, 0.0],
        [0.0, 4.0],
        [-5.0, 4.0],
    ];
    let ell_tris = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
    let depth = 2.0;
    let mut rng = ChaCha8Rng::seed_from_u64(26);
    for case in 0..200 {
        let (outline, tris): (&[[f64; 2]], Vec<[usize; 3]>) = if case % 2 == 0 {
            (&rectangle, vec![[0, 1, 2], [0, 2, 3]])
        } else {
            (&ell, ell_tris.to_vec())
        };
        let body = |k: usize| Vector3::new(outline[k][0], -depth, outline[k][1]);
        let tris: Vec<[Vector3<f64>; 3]> = tris.iter().map(|t| t.map(body)).collect();
        let pose = BodyPose {
            cm: Vector3::new(
                rng.random_range(-12.0..28.0),
                10.0,
                rng.random_range(-9.0..9.0),
            ),
            rotation: turned(
                rng.random_range(0.0..std::f64::consts::TAU),
                rng.random_range(0.0..8f64.to_radians()),
                rng.random_range(0.0..std::f64::consts::TAU),
            ),
        };
        let contact = first_contact(&ground, &tris, &pose);
        let base = Footprint { outline, depth };
        assert_touches_agree(&format!("case {case}"), &ground, &tris, &contact, |p| {
            touches(&ground, base, p, 1.0, 0.0)
        });
    }
}

/// The relief's faces as triangles, in body axes.
fn relief_triangles(relief: &Relief) -> Vec<[Vector3<f64>; 3]> {
    let v = relief.vertices();
    relief
        .faces()
        .iter()
        .flat_map(|f| {
            (1..f.corners.len() - 1)
                .map(|k| [v[f.corners[0]], v[f.corners[k]], v[f.corners[k + 1]]])
        })
        .collect()
}

#[test]
fn a_cast_base_moved_off_its_bed_and_lowered_onto_it_first_meets_it_where_a_touch_says() {
    // Cast where it rests on the steep rough terrain and on the 10° teeth, then moved up to
    // 0.6 m and turned up to 3° in any direction: its asperities meet the rock's wherever they
    // first do, vertex on face, face on vertex or edge across edge.
    let mut rng = ChaCha8Rng::seed_from_u64(27);
    for scene in ["cast-monolith.toml", "cast-teeth.toml"] {
        let ground = ground_of(scene);
        let outline = [[-4.0, -3.0], [4.0, -3.0], [4.0, 3.0], [-4.0, 3.0]];
        let footprint = [
            [outline[0], outline[1], outline[2]],
            [outline[0], outline[2], outline[3]],
        ];
        for case in 0..40 {
            let rest = BodyPose {
                cm: Vector3::new(
                    rng.random_range(-4.0..4.0),
                    5.0,
                    rng.random_range(-4.0..4.0),
                ),
                rotation: turned(rng.random_range(0.0..std::f64::consts::TAU), 0.0, 0.0),
            };
            let relief = cast(&ground, &footprint, &rest).unwrap();
            let tris = relief_triangles(&relief);
            let moved = BodyPose {
                cm: rest.cm
                    + Vector3::new(
                        rng.random_range(-0.6..0.6),
                        0.0,
                        rng.random_range(-0.6..0.6),
                    ),
                rotation: turned(
                    rng.random_range(-3f64..3.0).to_radians(),
                    rng.random_range(0.0..3f64.to_radians()),
                    rng.random_range(0.0..std::f64::consts::TAU),
                ) * rest.rotation,
            };
            let contact = first_contact(&ground, &tris, &moved);
            let what = format!("{scene} case {case}");
            assert_touches_agree(&what, &ground, &tris, &contact, |p| {
                relief_touches(&ground, &relief, p, 1.0, 0.0)
            });
        }
    }
}
