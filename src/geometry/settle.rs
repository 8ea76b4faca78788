//! The block set down on the ground under its own weight (`derivations/13-base-contact.md`
//! §3): the lowest pose of the base with nothing below the ground, its centre of mass kept over
//! the same plan point and its yaw kept, as a crane would lower it.
//!
//! Exact search by sequential linear programs: at a pose, each touch's gap moves to first
//! order by n·(Δc + δ × r) for a drop Δc = (0, d, 0) of the centre of mass and a small tilt δ
//! about the horizontal axes. The lowest d with every gap ≥ 0, δ within a trust region, is a
//! linear program (Clarabel; with a small cost on the tilt, so that where tilting lowers nothing
//! it asks for none); the pose is moved by it, the touches found again exactly, and the program
//! solved again until the tilt it asks for is at round-off or lowers nothing. The program's dual values
//! are the contact forces that carry the weight at the pose: the contacts that carry it are
//! those whose force is not zero. A flat base over a convex ground touches at the supporting
//! plane of the ground's upper hull under the footprint; this finds that plane by the physics.

use super::ground::Ground;
use super::touch::{BodyPose, Footprint, Touch, plan_box, touches};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, SolverStatus, SupportedConeT::NonnegativeConeT,
};
use nalgebra::{Rotation3, Vector3};

/// The pose the block rests in, and what carries it.
#[derive(Debug, Clone, PartialEq)]
pub struct Rest {
    /// The resting pose.
    pub pose: BodyPose,
    /// The touches that carry the weight, each with its share of it (a fraction; they sum
    /// to 1 along Y).
    pub carrying: Vec<(Touch, f64)>,
    /// The linear programs solved.
    pub iterations: usize,
}

/// Why the block cannot be set down.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SettleError {
    /// Part of the footprint over no ground.
    #[error("corner {0} of the base is over no ground (off the surveyed surface)")]
    OffGround(usize),
    /// Nothing under the footprint holds it without tipping (its weight's line leaves every
    /// support the ground gives it within a tilt of 60°).
    #[error("the ground under the base does not hold it: it tips over ({0})")]
    Tips(String),
    /// The linear program failed.
    #[error("the linear program of the resting pose failed: {0}")]
    Solver(String),
    /// The search did not settle.
    #[error("the search for the resting pose did not settle in {0} programs")]
    NotSettled(usize),
}

/// The largest tilt (rad) one program may ask for (about each horizontal axis).
const TRUST: f64 = 0.05;

/// The lowest pose of `base` on `ground` with the centre of mass over the plan point and the
/// yaw of `start` (whose height does not matter), to `tol` (m) in every gap.
pub fn set_down(
    ground: &Ground,
    base: Footprint<'_>,
    start: BodyPose,
    tol: f64,
) -> Result<Rest, SettleError> {
    let size = (0..base.outline.len())
        .map(|k| base.corner(k).norm())
        .fold(0.0, f64::max)
        .max(base.depth);
    let mut pose = start;
    // Flat at its yaw, its base at the highest ground under the footprint's box (whatever the
    // survey's elevation), then lowered until its lowest touch meets the ground.
    above_ground(ground, base, &mut pose)?;
    lift_to_ground(ground, base, &mut pose, size)?;
    // The tilt one program may ask for: cut where the pose it gives, on the ground found
    // again exactly, is not lower by a quarter of what the program foresaw (the linear model
    // missed a touch that the tilt brings on), grown back where the model holds.
    let mut trust = TRUST;
    // The lowest pose found, and the programs since it was lowered by more than `tol`: where
    // the programs foresee no more than round-off and go back and forth between poses within
    // `tol` of each other, the block has settled there.
    let (mut best, mut stalled) = (pose, 0);
    for iteration in 1..=200 {
        let found = touches(ground, base, &pose, 0.2 * size, 0.0);
        if let Some(&k) = found.off_ground.first() {
            return Err(SettleError::OffGround(k));
        }
        let (d, tilt, forces) = lowest_step(&pose, &found.touches, trust)?;
        let before = pose;
        let step = Rotation3::from_scaled_axis(tilt);
        pose.rotation = step.matrix() * pose.rotation;
        pose.cm.y += d;
        lift_to_ground(ground, base, &mut pose, size)?;
        let lowered = before.cm.y - pose.cm.y;
        let asked = tilt.x.abs().max(tilt.z.abs());
        let at_trust = asked >= 0.5 * trust;
        if d < -tol && lowered < 0.25 * -d && asked > 0.0 {
            pose = before;
            trust = 0.25 * asked;
            if trust < 1e-12 {
                return Err(SettleError::NotSettled(iteration));
            }
            continue;
        }
        if lowered > 0.75 * -d && at_trust {
            trust = (2.0 * trust).min(TRUST);
        }
        let up = pose.up();
        if up.y < 0.5 {
            return Err(SettleError::Tips(format!(
                "its base tilted {:.1}° without finding a support",
                up.y.acos().to_degrees()
            )));
        }
        if pose.cm.y < best.cm.y - tol {
            stalled = 0;
        } else {
            stalled += 1;
        }
        if pose.cm.y < best.cm.y {
            best = pose;
        }
        // Settled: the tilt asked for is at round-off; or it lowers nothing (a tilt about a
        // line of supports, left by the solver's tolerance, below a millionth of the size);
        // or four programs have found nothing lower by `tol` while foreseeing a lowering of
        // at most a thousand times it.
        let level = d.abs() <= 1e-3 * tol && tilt.norm() <= 1e-6;
        let stuck = stalled >= 4 && d >= -1e3 * tol;
        if (tilt.norm() * size <= tol && !at_trust) || level || stuck {
            let pose = if stuck { best } else { pose };
            let found = touches(ground, base, &pose, 0.2 * size, 0.0);
            let (_, _, forces) =
                lowest_step(&pose, &found.touches, TRUST).unwrap_or((0.0, tilt, forces));
            let carrying = forces
                .into_iter()
                .filter(|(t, f)| *f > 1e-6 && t.gap <= tol.max(1e-9 * size))
                .collect();
            return Ok(Rest {
                pose,
                carrying,
                iterations: iteration,
            });
        }
    }
    Err(SettleError::NotSettled(200))
}

/// Levels the block at its yaw with its base at the highest ground over the footprint's plan
/// box: every ground point under the base is then at or below it.
fn above_ground(
    ground: &Ground,
    base: Footprint<'_>,
    pose: &mut BodyPose,
) -> Result<(), SettleError> {
    let yaw = pose.rotation.column(0).into_owned();
    let flat = Vector3::new(yaw.x, 0.0, yaw.z);
    let flat = if flat.norm() > 1e-12 {
        flat.normalize()
    } else {
        Vector3::x()
    };
    pose.rotation =
        nalgebra::Matrix3::from_columns(&[flat, Vector3::y(), flat.cross(&Vector3::y())]);
    let corners: Vec<Vector3<f64>> = (0..base.outline.len())
        .map(|k| pose.point(&base.corner(k)))
        .collect();
    let [x0, x1, z0, z1] = plan_box(corners.iter().map(|c| [c.x, c.z]));
    let mut top = f64::NEG_INFINITY;
    for (k, c) in corners.iter().enumerate() {
        match ground.top(c.x, c.z) {
            Some((_, h)) => top = top.max(h),
            None => return Err(SettleError::OffGround(k)),
        }
    }
    for f in ground.faces_in((x0, x1, z0, z1)) {
        if let Some(tri) = ground.triangle(f) {
            let plane = &ground.faces()[f];
            for [x, z] in tri {
                if (x0..=x1).contains(&x) && (z0..=z1).contains(&z) {
                    top = top.max(plane.height(x, z));
                }
            }
        }
    }
    pose.cm.y = top + base.depth;
    Ok(())
}

/// Moves the block along Y so that its smallest gap is zero.
fn lift_to_ground(
    ground: &Ground,
    base: Footprint<'_>,
    pose: &mut BodyPose,
    size: f64,
) -> Result<(), SettleError> {
    for _ in 0..4 {
        let found = touches(ground, base, pose, 2.0 * size, 0.0);
        if let Some(&k) = found.off_ground.first() {
            return Err(SettleError::OffGround(k));
        }
        // Along Y a gap g along normal n closes at the rate n_y.
        let dy = found
            .touches
            .iter()
            .filter(|t| t.normal.y > 1e-6)
            .map(|t| t.gap / t.normal.y)
            .fold(f64::INFINITY, f64::min);
        if !dy.is_finite() {
            return Err(SettleError::Tips("no touch faces up".into()));
        }
        pose.cm.y -= dy;
        if dy.abs() <= 1e-15 * size {
            break;
        }
    }
    Ok(())
}

/// What one linear program gives: the drop d (m), the tilt δ (rad, about X and Z), and each
/// touch with its share of the weight.
type Lowest = (f64, Vector3<f64>, Vec<(Touch, f64)>);

/// One linear program at `pose`: the drop d (negative: down), the tilt δ (about X and Z), and
/// each touch's share of the weight (the program's dual values).
fn lowest_step(pose: &BodyPose, found: &[Touch], trust: f64) -> Result<Lowest, SettleError> {
    // Lowering and tilting move a touch along the vertical: a touch whose normal is nearly
    // level (a steep face beside the base) cannot be closed by them and is left to the
    // dynamics.
    let found: Vec<Touch> = found.iter().filter(|t| t.normal.y > 0.2).copied().collect();
    let found = &found[..];
    let n_touch = found.len();
    if n_touch == 0 {
        return Err(SettleError::Tips("nothing under the base".into()));
    }
    // Variables (d, s_x, s_z), the tilt δ = s / size in metres at the base's size so that the
    // columns are alike; rows: each touch, then the trust region.
    let arms: Vec<Vector3<f64>> = found.iter().map(|t| pose.rotation * t.body).collect();
    let size = arms.iter().map(|r| r.norm()).fold(1e-12, f64::max);
    let rows = n_touch + 4;
    let mut a = vec![vec![0.0; 3]; rows];
    let mut b = vec![0.0; rows];
    for (k, (t, r)) in found.iter().zip(&arms).enumerate() {
        // gap + n_y d + δ·(r × n) ≥ 0, r from the CM (the tilt is about it).
        let m = r.cross(&t.normal);
        a[k] = vec![-t.normal.y, -m.x / size, -m.z / size];
        b[k] = t.gap;
    }
    for (j, (col, sign)) in [(1, 1.0), (1, -1.0), (2, 1.0), (2, -1.0)]
        .into_iter()
        .enumerate()
    {
        a[n_touch + j][col] = sign;
        b[n_touch + j] = trust * size;
    }
    // Where tilting lowers nothing to first order (the weight's line through two supports, or a
    // support's edge), every tilt of that kind is as low, and an interior-point solution picks
    // one in the middle: the search then tilts back and forth without end. A small cost on the
    // tilt, ½ κ |s|² with κ = 10⁻²/size, picks the least: it moves no program whose lowest
    // pose is one vertex of its feasible set, and none at all once the tilt is nothing.
    let kappa = 1e-2 / size;
    let p = CscMatrix::<f64>::from(&[[0.0, 0.0, 0.0], [0.0, kappa, 0.0], [0.0, 0.0, kappa]]);
    let q = [1.0, 0.0, 0.0];
    let a = CscMatrix::from(&a);
    let cones = [NonnegativeConeT(rows)];
    let settings = DefaultSettings {
        verbose: false,
        tol_gap_abs: 1e-12,
        tol_gap_rel: 1e-12,
        tol_feas: 1e-12,
        ..DefaultSettings::default()
    };
    let mut solver = DefaultSolver::new(&p, &q, &a, &b, &cones, settings)
        .map_err(|e| SettleError::Solver(e.to_string()))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            let x = &solver.solution.x;
            let tilt = Vector3::new(x[1], 0.0, x[2]) / size;
            let forces = found
                .iter()
                .copied()
                .zip(solver.solution.z[..n_touch].to_vec())
                .collect();
            Ok((x[0], tilt, forces))
        }
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => Err(
            SettleError::Tips("nothing under the base stops it going down".into()),
        ),
        other => Err(SettleError::Solver(format!("{other:?}"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Plane;
    use crate::geometry::penetration::deepest;
    use nalgebra::Matrix3;

    fn square(half: f64) -> Vec<[f64; 2]> {
        vec![[-half, -half], [half, -half], [half, half], [-half, half]]
    }

    fn at(x: f64, z: f64) -> BodyPose {
        BodyPose {
            cm: Vector3::new(x, 5.0, z),
            rotation: Matrix3::identity(),
        }
    }

    #[test]
    fn a_base_on_a_plane_dipping_downstream_rests_on_it_at_its_depth() {
        // Falling 10° along +X: its normal leans downstream.
        let dip = 10f64.to_radians();
        let plane = Plane::through(
            Vector3::new(dip.sin(), dip.cos(), 0.0),
            Vector3::new(0.0, -1.0, 0.0),
        );
        let ground = Ground::planes(vec![plane]);
        let outline = square(2.0);
        let base = Footprint {
            outline: &outline,
            depth: 0.7,
        };
        let rest = set_down(&ground, base, at(0.0, 0.0), 1e-12).unwrap();
        let up = rest.pose.up();
        assert!((up - plane.normal()).norm() < 1e-9, "{up}");
        // The CM stands its depth above the plane along the normal, over the same plan point.
        assert!((plane.signed_distance(&rest.pose.cm) - 0.7).abs() < 1e-9);
        assert!(rest.pose.cm.x.abs() < 1e-15 && rest.pose.cm.z.abs() < 1e-15);
        // All four corners carry it, their shares of the weight summing to one along Y.
        assert_eq!(rest.carrying.len(), 4);
        let total: f64 = rest.carrying.iter().map(|(t, f)| f * t.normal.y).sum();
        assert!((total - 1.0).abs() < 1e-6, "{total}");
        let inside = deepest(&ground, &outline, 0.7, &rest.pose, 40);
        assert!(inside <= 1e-9, "{inside}");
    }

    #[test]
    fn a_base_over_a_bump_tips_off_it_onto_a_corner_and_stays_out_of_the_rock() {
        let ground = crate::geometry::fixtures::pyramid_over(3.0, 0.1);
        let outline = square(1.0);
        let base = Footprint {
            outline: &outline,
            depth: 0.5,
        };
        // The CM a little off the peak towards +X: the block rocks down towards +X.
        let rest = set_down(&ground, base, at(0.2, 0.0), 1e-12).unwrap();
        let flat_on_peak = 0.1 + 0.5;
        assert!(rest.pose.cm.y < flat_on_peak - 1e-3, "{}", rest.pose.cm.y);
        let inside = deepest(&ground, &outline, 0.5, &rest.pose, 60);
        assert!(inside <= 1e-9, "{inside}");
        let kinds: Vec<_> = rest.carrying.iter().map(|(t, _)| t.feature).collect();
        assert!(
            kinds.contains(&crate::geometry::Feature::GroundVertex),
            "{kinds:?}"
        );
        assert!(
            kinds
                .iter()
                .any(|k| matches!(k, crate::geometry::Feature::Corner(_)))
        );
        // It leans towards +X: its up turned towards +X.
        assert!(rest.pose.up().x > 0.0);
    }

    #[test]
    fn a_base_hanging_over_the_end_of_a_surface_is_refused() {
        let tri = [[[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 0.0, 10.0]]];
        let ground = Ground::surface(&tri).unwrap();
        let outline = square(1.0);
        let base = Footprint {
            outline: &outline,
            depth: 0.0,
        };
        let e = set_down(&ground, base, at(0.5, 0.5), 1e-12).unwrap_err();
        assert_eq!(e, SettleError::OffGround(0));
    }

    #[test]
    fn a_tall_block_on_a_plane_dipping_downstream_rests_flush_on_it() {
        // A monolith's base 20 m × 10 m, its centre of mass 8 m up, on a 6° plane: the lowest
        // pose with the centre of mass over its plan point is the base along the plane.
        let dip = 6f64.to_radians();
        let plane = Plane::through(Vector3::new(dip.sin(), dip.cos(), 0.0), Vector3::zeros());
        let ground = Ground::planes(vec![plane]);
        let outline = vec![[-7.0, -5.0], [13.0, -5.0], [13.0, 5.0], [-7.0, 5.0]];
        let base = Footprint {
            outline: &outline,
            depth: 8.0,
        };
        let start = BodyPose {
            cm: Vector3::new(0.0, 8.0, 0.0),
            rotation: Matrix3::identity(),
        };
        let rest = set_down(&ground, base, start, 1e-12).unwrap();
        assert!(
            (rest.pose.up() - plane.normal()).norm() < 1e-9,
            "{}",
            rest.pose.up()
        );
    }
}
