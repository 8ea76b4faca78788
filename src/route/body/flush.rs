//! The base lying flush on one plane face of the rock, sliding on it
//! (`derivations/13-base-contact.md` §13): the motion of three degrees of freedom — the CM
//! along the plane, the turn about its normal — with the pressure of §9 (a rigid base on a
//! uniform bed, cracked where the resultant leaves the kern) and Coulomb friction −μ p û at
//! every point of the base's quadrature, û the direction of that point's slip. The normal
//! force balances the loads across the plane, the pressure's centre the moments about the
//! plane's axes (the friction's own, acting at the base, and the turn's gyroscopic couple
//! with them), so that the accelerations are a smooth function of the state wherever the
//! block slides: an ordinary differential equation, integrated to the tolerance and its stops
//! located (`sliding.rs`).
//!
//! At rest the question is whether friction holds the block, and if not in which mode it
//! starts: [`Flush::onset`].

use super::step::Ctx;
use crate::geometry::BodyPose;
use crate::mechanics::pressure::Bed;
use nalgebra::{Matrix2, Rotation3, Unit, Vector2, Vector3};

/// The state of the slide: the CM's displacement along the plane's two axes from where the
/// phase began (m), the turn about the normal (rad), their rates (m/s, rad/s), the path of
/// the point under the CM (m), the works of the loads other than gravity and of friction (J),
/// and the time (s).
pub(super) type Slide = [f64; 10];

/// Why the base leaves the flush slide: the loads lift it off the plane, its resultant leaves
/// the base (it tips), the pressure's centre does not settle, or the base meets another face
/// or the face's edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Leaves {
    Lifts,
    Tips,
    Unsettled,
    Meets,
}

/// Newton's iterations that settle the pressure's centre with the friction it causes.
const CENTRE_ITERATIONS: usize = 30;

/// Newton's iterations for the direction a slip settles to.
const SETTLE_ITERATIONS: usize = 40;

/// Friction's stiffness times the step above which a slow block's slip direction is settled
/// ([`Flush::rates`]): RK4 is unstable past about 2.8 on the real axis, as for the frame
/// (`src/mechanics/rigid_body/accelerations.rs`).
const TURNING: f64 = 2.5;

/// How far (on the unit sphere of the metric) a settled direction may lie from the slip's
/// own: farther, the block is turning, not settling.
const NEARBY: f64 = 1e-2;

/// The base flush on one face: the plane, the base's points, the friction coefficient, where
/// the phase began.
#[derive(Debug, Clone)]
pub(super) struct Flush {
    /// The face of the rock it lies on.
    pub face: usize,
    /// The face's unit normal, into the block.
    n: Vector3<f64>,
    /// Two unit axes in the plane (n, e1, e2 right-handed in that order's sense: e1 × e2 = n).
    axes: (Vector3<f64>, Vector3<f64>),
    mu: f64,
    /// The base's area quadrature: the points in body axes about the CM and their weights.
    arms: Vec<Vector3<f64>>,
    bed: Bed,
    /// The pose where the phase began, flush on the plane: the origin of [`Slide`].
    origin: BodyPose,
    /// The CM's height above the base (m).
    depth: f64,
    /// Each point's share of the normal force (N), the last found.
    shares: Vec<f64>,
    /// The pressure's centre last found (from the CM's foot along e1, e2): the next search's
    /// start.
    last_centre: Vector2<f64>,
    /// The length of the step the rates are for (s): it sets the band where a slow slip's
    /// direction is settled ([`Flush::rates`]).
    pub step: f64,
    /// The slip mode the block starts in from rest (accelerations along e1, e2 and about n,
    /// unit in the mass metric): the slip's direction while its speed is zero.
    pub mode: Option<[f64; 3]>,
    /// The velocities at the start of a step that ends where the block stops (world): a
    /// stage of the step beyond the stop (its velocities against these) slides on in their
    /// sense, so that the step's stages stay on one smooth motion.
    pub sense: Option<(Vector3<f64>, Vector3<f64>)>,
    /// The mode the last rate's slip was held to (unit in the mass metric), where it was:
    /// from rest, the mode it starts in; slow and stiff, the direction it settles to
    /// ([`Flush::rates`]). A step from a state so held starts with its velocities along it.
    pub along: Option<[f64; 3]>,
    /// The slide's steps in a row under a hundredth of the reference step (`sliding.rs`).
    pub tiny: usize,
}

/// The forces of the slide at one instant: the CM's acceleration (world, in the plane), the
/// angular acceleration about the normal, and friction's power (W, ≤ 0).
#[derive(Debug, Clone, Copy)]
pub(super) struct Rates {
    pub a: Vector3<f64>,
    pub alpha: f64,
    pub friction_power: f64,
}

/// The friction of one slip field over the base: its force (world), its moment about the
/// normal through the CM, and Σ μ p / |u| and Σ μ p r² / |u| over its points (the parts of
/// its stiffness, [`Metric::stiffness`]).
struct Rubbing {
    force: Vector3<f64>,
    torque: f64,
    stiff: (f64, f64),
}

impl Flush {
    /// The slide on face `face` whose unit normal (into the block) is `n`, friction `mu`,
    /// from `pose`, the base's area quadrature `area` (body axes about the CM, weights m²) at
    /// `depth` below the CM. None where the quadrature has no area.
    pub fn new(
        face: usize,
        n: Vector3<f64>,
        mu: f64,
        pose: BodyPose,
        (area, depth): (&[(Vector3<f64>, f64)], f64),
    ) -> Option<Flush> {
        let plan: Vec<[f64; 2]> = area.iter().map(|(p, _)| [p.x, p.z]).collect();
        let weights: Vec<f64> = area.iter().map(|(_, w)| *w).collect();
        let bed = Bed::new(&plan, &weights)?;
        let e1 = pose.rotation.column(0).into_owned();
        let e1 = (e1 - n * n.dot(&e1)).try_normalize(1e-12)?;
        let e2 = n.cross(&e1);
        Some(Flush {
            face,
            n,
            axes: (e1, e2),
            mu,
            arms: area.iter().map(|(p, _)| *p).collect(),
            bed,
            origin: pose,
            depth,
            shares: Vec::new(),
            last_centre: Vector2::zeros(),
            step: 0.0,
            mode: None,
            sense: None,
            along: None,
            tiny: 0,
        })
    }

    /// The slide's state at time `t` from `pose`, now its origin, with the body's velocities
    /// `v` and `w` (their parts along the plane and about its normal), the path and the works
    /// as given.
    pub fn start(
        &mut self,
        (t, pose): (f64, BodyPose),
        (v, w): (Vector3<f64>, Vector3<f64>),
        (path, wa, wc): (f64, f64, f64),
    ) -> Slide {
        self.origin = pose;
        let (e1, e2) = self.axes;
        [
            0.0,
            0.0,
            0.0,
            v.dot(&e1),
            v.dot(&e2),
            w.dot(&self.n),
            path,
            wa,
            wc,
            t,
        ]
    }

    /// The pose of state `y`.
    pub fn pose(&self, y: &Slide) -> BodyPose {
        let (e1, e2) = self.axes;
        let turn = Rotation3::from_axis_angle(&Unit::new_unchecked(self.n), y[2]);
        BodyPose {
            cm: self.origin.cm + e1 * y[0] + e2 * y[1],
            rotation: turn.matrix() * self.origin.rotation,
        }
    }

    /// The CM's velocity and the angular velocity (world) of state `y`.
    pub fn velocities(&self, y: &Slide) -> (Vector3<f64>, Vector3<f64>) {
        let (e1, e2) = self.axes;
        (e1 * y[3] + e2 * y[4], self.n * y[5])
    }

    /// The rate of state `y`.
    pub fn rate(&mut self, ctx: &Ctx<'_>, y: &Slide) -> Result<Slide, Leaves> {
        let pose = self.pose(y);
        let (v, w) = self.velocities(y);
        let (force, moment, driving) = ctx.loads(&pose, y[9]);
        let r = self.rates(ctx, &pose, (force, moment), (v, w))?;
        let (e1, e2) = self.axes;
        Ok([
            y[3],
            y[4],
            y[5],
            r.a.dot(&e1),
            r.a.dot(&e2),
            r.alpha,
            v.norm(),
            driving.dot(&v) + moment.dot(&w),
            r.friction_power,
            1.0,
        ])
    }

    /// The points of the base at `pose` from the CM's foot on the plane (world, in the plane).
    fn spots(&self, pose: &BodyPose) -> Vec<Vector3<f64>> {
        let lift = self.n * self.depth;
        let r = pose.rotation;
        self.arms.iter().map(|a| r * a + lift).collect()
    }

    /// The normal force's shares at the points for its centre `c` (world, from the CM's foot):
    /// none where no pressure without tension has it (the block tips).
    fn press(&mut self, pose: &BodyPose, normal: f64, c: &Vector3<f64>) -> Result<(), Leaves> {
        let local = pose.rotation.transpose() * c;
        if self
            .bed
            .spread(normal, [local.x, local.z], &mut self.shares)
        {
            Ok(())
        } else {
            Err(Leaves::Tips)
        }
    }

    /// Friction over the pressed points, each sliding along its field value `field(r)`
    /// (zero where that is zero).
    fn rub(
        &self,
        spots: &[Vector3<f64>],
        field: impl Fn(&Vector3<f64>) -> Vector3<f64>,
    ) -> Rubbing {
        let mut out = Rubbing {
            force: Vector3::zeros(),
            torque: 0.0,
            stiff: (0.0, 0.0),
        };
        for (r, p) in spots.iter().zip(&self.shares) {
            let u = field(r);
            let speed = u.norm();
            if speed > 0.0 {
                let f = u * (-self.mu * p / speed);
                out.force += f;
                out.torque += r.cross(&f).dot(&self.n);
                let k = self.mu * p / speed;
                out.stiff.0 += k;
                out.stiff.1 += k * r.norm_squared();
            }
        }
        out
    }

    /// The pressure's centre (world, from the CM's foot) that balances the moments about the
    /// plane's axes: those of the loads `moment`, of the inertia `inertia_moment` (I α + ω × I ω),
    /// and of friction's force `rubbing` acting at the base, under the normal force `normal`.
    fn centre(
        &self,
        normal: f64,
        moment: &Vector3<f64>,
        inertia_moment: &Vector3<f64>,
        rubbing: &Vector3<f64>,
    ) -> Vector3<f64> {
        let n = self.n;
        let t = inertia_moment - moment + n.cross(rubbing) * self.depth;
        let across = t - n * n.dot(&t);
        n.cross(&across) / normal
    }

    /// The accelerations of the block at `pose` under `loads` (the force and the moment about
    /// the CM), moving at `(v, w)`: friction opposing each point's slip — or, at rest, the
    /// mode it starts in ([`Flush::mode`]) — with the pressure whose centre it moves.
    ///
    /// A block so slow that friction would turn its slip's direction faster than the step
    /// [`Flush::step`] can follow (the stiffness times the step above [`TURNING`]), and barely
    /// speeding up or slowing down, has its friction along the direction its slip settles to
    /// within that time ([`Flush::settled`]), as the three-point frame's is
    /// (`src/mechanics/rigid_body/accelerations.rs`): where the slip already has that
    /// direction (a block shaken along one line) nothing changes; elsewhere an explicit step
    /// would make the direction swing about. Its accelerations are then those along that
    /// direction alone (as from rest along the mode it starts in), the slip across it being
    /// one friction takes off within a fraction of the step ([`Flush::along`]): where the
    /// net accelerations are round-off of the loads' and friction's, as at an onset or a stop,
    /// their parts across would otherwise seed a swing the step amplifies.
    pub fn rates(
        &mut self,
        ctx: &Ctx<'_>,
        pose: &BodyPose,
        (force, moment): (Vector3<f64>, Vector3<f64>),
        (v, w): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Rates, Leaves> {
        let n = self.n;
        let normal = -force.dot(&n);
        if normal.is_nan() || normal <= 0.0 {
            return Err(Leaves::Lifts);
        }
        let m = Metric::of(ctx, pose, n);
        let inertia = pose.rotation * ctx.inertia * pose.rotation.transpose();
        let gyro = w.cross(&(inertia * w));
        let spots = self.spots(pose);
        let still = v.norm() + w.norm() * ctx.size == 0.0;
        let l2 = ctx.size * ctx.size;
        let own = match (still, self.mode, self.sense) {
            (true, Some(mode), _) => mode,
            (_, _, Some((v0, w0))) if v.dot(&v0) + l2 * w.dot(&w0) <= 0.0 => self.mode_of(v0, w0),
            _ => self.mode_of(v, w),
        };
        let (e1, e2) = self.axes;
        let demand = [force.dot(&e1), force.dot(&e2), (moment - gyro).dot(&n)];
        // The pressure's centre c (in the plane's axes) where the moments it balances, the
        // friction's among them, put it: G(c) = centre(c) − c = 0 by Newton's method (a
        // finite-difference Jacobian; G is affine where the bed is not cracked and the slips'
        // directions do not depend on c), from the last centre found.
        let eval = |flush: &mut Flush,
                    c: Vector2<f64>|
         -> Result<(Vector2<f64>, Rubbing, [f64; 3]), Leaves> {
            let world = e1 * c[0] + e2 * c[1];
            flush.press(pose, normal, &world)?;
            let mut rub = flush.rub_mode(&spots, own);
            flush.along = still.then_some(own).filter(|d| d.iter().any(|x| *x != 0.0));
            if !still && flush.band(&rub, &m, demand, own) {
                let found = flush.settled(&spots, &m, demand, (own, NEARBY));
                if let Some(settled) = found.filter(|s| s.exact) {
                    rub = flush.rub_mode(&spots, settled.mode);
                    flush.along = Some(settled.mode);
                }
            }
            let mut acc = m.accelerate(flush.net(demand, &rub));
            if let Some(d) = flush.along {
                acc = m.along(acc, d);
            }
            let inertia_moment = inertia * n * acc[2] + gyro;
            let next = flush.centre(normal, &moment, &inertia_moment, &rub.force);
            Ok((Vector2::new(next.dot(&e1), next.dot(&e2)) - c, rub, acc))
        };
        let close = 1e-14 * ctx.size;
        let mut c = self.last_centre;
        for _ in 0..CENTRE_ITERATIONS {
            let (g, rub, acc) = eval(self, c)?;
            if g.norm() <= close {
                self.last_centre = c;
                return Ok(Rates {
                    a: e1 * acc[0] + e2 * acc[1],
                    alpha: acc[2],
                    friction_power: rub.force.dot(&v) + rub.torque * w.dot(&n),
                });
            }
            let d = 1e-7 * ctx.size;
            let g1 = eval(self, c + Vector2::new(d, 0.0)).map(|x| (x.0 - g) / d);
            let g2 = eval(self, c + Vector2::new(0.0, d)).map(|x| (x.0 - g) / d);
            let newton = match (g1, g2) {
                (Ok(g1), Ok(g2)) => Matrix2::from_columns(&[g1, g2]).lu().solve(&-g),
                _ => None,
            };
            // Where Newton's step cannot be had, the plain step c + G(c).
            c += newton.unwrap_or(g);
        }
        Err(Leaves::Unsettled)
    }

    /// The velocities of `y` held to the mode the last rate's slip was ([`Flush::along`]),
    /// where they were not along it already (none left where they were against it): the
    /// kinetic energy taken off, friction's, booked with the contacts' work. Whether they
    /// moved.
    pub fn hold_along(&self, ctx: &Ctx<'_>, y: &mut Slide) -> bool {
        let Some(d) = self.along else {
            return false;
        };
        let m = Metric::of(ctx, &self.pose(y), self.n);
        let u = [y[3], y[4], y[5]];
        let mut kept = m.along(u, d);
        if kept.iter().zip(&d).any(|(k, d)| k * d < 0.0) {
            kept = [0.0; 3];
        }
        if kept == u {
            return false;
        }
        let kinetic = |u: [f64; 3]| 0.5 * m.norm(u).powi(2);
        y[8] += kinetic(kept) - kinetic(u);
        [y[3], y[4], y[5]] = kept;
        true
    }

    /// The mode of the velocities `v` and `w` (along e1, e2, about n).
    fn mode_of(&self, v: Vector3<f64>, w: Vector3<f64>) -> [f64; 3] {
        [v.dot(&self.axes.0), v.dot(&self.axes.1), w.dot(&self.n)]
    }

    /// Friction over the pressed points, the base sliding in `mode`.
    fn rub_mode(&self, spots: &[Vector3<f64>], mode: [f64; 3]) -> Rubbing {
        let dv = self.axes.0 * mode[0] + self.axes.1 * mode[1];
        let dw = self.n * mode[2];
        self.rub(spots, |r| dv + dw.cross(r))
    }

    /// The net force along e1, e2 and moment about n of `demand` (the loads') and friction
    /// `rub`.
    fn net(&self, demand: [f64; 3], rub: &Rubbing) -> [f64; 3] {
        let (e1, e2) = self.axes;
        [
            demand[0] + rub.force.dot(&e1),
            demand[1] + rub.force.dot(&e2),
            demand[2] + rub.torque,
        ]
    }

    /// Whether the slip `own`, rubbing as `rub` under `demand` (the force along e1, e2 and
    /// the moment about n), is in the band where its direction is settled: friction's
    /// stiffness times the step over [`TURNING`] (or the block slowing to a stop within the
    /// step), and the block speeding up at under a tenth of its friction's acceleration, or
    /// slowing down.
    fn band(&self, rub: &Rubbing, m: &Metric, demand: [f64; 3], own: [f64; 3]) -> bool {
        let a = m.accelerate(self.net(demand, rub));
        let slowing = a[0] * own[0] + a[1] * own[1] + a[2] * own[2] < 0.0;
        // Slowing to a stop within the step: its last part is as slow as any.
        let stops = slowing && m.norm(own) <= self.step * m.norm(a);
        let turning = self.step * m.stiffness(rub);
        if !stops && (turning.is_nan() || turning <= TURNING) {
            return false;
        }
        let friction = self.shares.iter().sum::<f64>() * self.mu / m.mass.sqrt();
        slowing || m.norm(a) < 0.1 * friction
    }

    /// The slip direction within `within` of `near` (on the unit sphere of the mass metric)
    /// that the block's slip settles to under `demand` (the force along e1, e2 and the moment
    /// about n) at the present pressure: the mode whose friction leaves the accelerations
    /// along itself — where the loads' power in it over friction's is greatest, for friction's
    /// is convex in the mode — found by Newton's method on that sphere (a finite-difference
    /// Jacobian), each step kept only where it raises that power (else the gradient's, halved
    /// until it does). The mode and the power (positive where the block speeds up in it), and
    /// whether it settled to round-off (else the best found).
    fn settled(
        &self,
        spots: &[Vector3<f64>],
        m: &Metric,
        demand: [f64; 3],
        (near, within): ([f64; 3], f64),
    ) -> Option<Settled> {
        let root = Vector3::new(m.mass.sqrt(), m.mass.sqrt(), m.about_n.sqrt());
        let to_mode = |z: &Vector3<f64>| [z[0] / root[0], z[1] / root[1], z[2] / root[2]];
        // The accelerations in the metric's own coordinates (M^-1/2 of the net force), and
        // the power over friction's: (w + g(z))·z on the unit sphere.
        let net = |z: &Vector3<f64>| {
            let rub = self.rub_mode(spots, to_mode(z));
            Vector3::from(self.net(demand, &rub)).component_div(&root)
        };
        let start = Vector3::from(near)
            .component_mul(&root)
            .try_normalize(0.0)?;
        let scale = self.shares.iter().sum::<f64>() * self.mu / root[0]
            + Vector3::from(demand).component_div(&root).norm();
        let (mut z, mut f) = (start, net(&start));
        for _ in 0..SETTLE_ITERATIONS {
            let (b1, b2) = tangent_basis(&z);
            let r = Vector2::new(b1.dot(&f), b2.dot(&f));
            if r.norm() <= 1e-13 * scale {
                let found = Settled {
                    mode: to_mode(&z),
                    power: f.dot(&z),
                    exact: true,
                };
                return ((z - start).norm() <= within).then_some(found);
            }
            let across = |z: &Vector3<f64>| {
                let f = net(z);
                Vector2::new(b1.dot(&f), b2.dot(&f))
            };
            let eps = 1e-7;
            let d1 = (across(&(z + b1 * eps).normalize()) - r) / eps;
            let d2 = (across(&(z + b2 * eps).normalize()) - r) / eps;
            let newton = Matrix2::from_columns(&[d1, d2]).lu().solve(&-r);
            let power = f.dot(&z);
            let mut t = newton.filter(|t| t.dot(&r) > 0.0).unwrap_or(r / scale);
            if t.norm() > 0.5 {
                t *= 0.5 / t.norm();
            }
            let mut next = None;
            for _ in 0..40 {
                let y = (z + b1 * t[0] + b2 * t[1]).normalize();
                let g = net(&y);
                if g.dot(&y) >= power {
                    next = Some((y, g));
                    break;
                }
                t *= 0.5;
            }
            let Some((y, g)) = next else {
                break;
            };
            (z, f) = (y, g);
        }
        let found = Settled {
            mode: to_mode(&z),
            power: f.dot(&z),
            exact: false,
        };
        ((z - start).norm() <= within).then_some(found)
    }

    /// At rest at `pose` under `loads` (the force and the moment about the CM): None where
    /// friction holds the block, else the slip mode the loads start (accelerations along the
    /// plane's axes and about its normal, unit in the mass metric) and by how much the loads'
    /// power in it exceeds friction's (W per unit mode).
    ///
    /// At rest friction's force balances the loads' along the plane, which fixes the
    /// pressure; the block is held where no slip mode m has the loads' power W·m above the
    /// most friction can take, Σ μ p |u_m|. The mode sought is the one the block would take:
    /// the direction whose friction leaves the accelerations along itself
    /// ([`Flush::settled`]), from each direction of positive power among the loads' own and
    /// a fixed set; a mode of positive power found proves that the block slips.
    pub fn onset(
        &mut self,
        ctx: &Ctx<'_>,
        pose: &BodyPose,
        (force, moment): (Vector3<f64>, Vector3<f64>),
    ) -> Result<Option<([f64; 3], f64)>, Leaves> {
        let n = self.n;
        let normal = -force.dot(&n);
        if normal.is_nan() || normal <= 0.0 {
            return Err(Leaves::Lifts);
        }
        let along = force - n * n.dot(&force);
        let c = self.centre(normal, &moment, &Vector3::zeros(), &-along);
        self.press(pose, normal, &c)?;
        let spots = self.spots(pose);
        let m = Metric::of(ctx, pose, n);
        let demand = [
            along.dot(&self.axes.0),
            along.dot(&self.axes.1),
            moment.dot(&n),
        ];
        if self.surely_held(&spots, along, demand[2]) {
            return Ok(None);
        }
        Ok(self.search(&spots, &m, demand, ctx.size))
    }

    /// The slip mode the loads' `demand` (the force along e1, e2 and the moment about n)
    /// starts at the present pressure, sought from their own direction and each of
    /// [`DIRECTIONS`] (turns at the base's size `l`) of positive power: the mode (unit in the
    /// metric `m`) and its power, or None where none has any.
    fn search(
        &self,
        spots: &[Vector3<f64>],
        m: &Metric,
        demand: [f64; 3],
        l: f64,
    ) -> Option<([f64; 3], f64)> {
        let mut starts = vec![m.unit(m.accelerate(demand))];
        starts.extend(DIRECTIONS.iter().map(|d| m.unit([d[0], d[1], d[2] / l])));
        for start in starts {
            let net = self.net(demand, &self.rub_mode(spots, start));
            if net[0] * start[0] + net[1] * start[1] + net[2] * start[2] <= 0.0 {
                continue;
            }
            let found = self.settled(spots, m, demand, (start, f64::INFINITY));
            if let Some(s) = found.filter(|s| s.power > 0.0) {
                return Some((m.unit(s.mode), s.power));
            }
        }
        None
    }
}

impl Flush {
    /// Whether friction at the present pressure surely holds the block against the force
    /// `along` the plane and the moment `twist` about its normal through the CM: a sufficient
    /// test, cheaper than [`Flush::onset`]'s search, that holds the block at rest under most
    /// of a record's samples.
    ///
    /// Friction's power in a slip mode (v, ω) is D = Σ μ pᵢ |v + ω n × rᵢ|. Its points'
    /// slips sum to N w, w = v + ω n × c at the pressure's centre c, so D ≥ μ N |w|; and
    /// |rᵢ − q| ≥ |(rᵢ − q)·e| for any unit e, so D ≥ μ |ω| J, J the least over s of
    /// Σ pᵢ |rᵢ·e − s| (the weighted median's deviation along e; the greatest of four e).
    /// The loads' power is F·w + M_c ω, M_c their moment about c. So D ≥ F·w + M_c ω in every
    /// mode where |F| / μN + |M_c| / μJ ≤ 1.
    fn surely_held(&self, spots: &[Vector3<f64>], along: Vector3<f64>, twist: f64) -> bool {
        let normal: f64 = self.shares.iter().sum();
        if !(normal > 0.0 && self.mu > 0.0) {
            return false;
        }
        let centre = spots
            .iter()
            .zip(&self.shares)
            .fold(Vector3::zeros(), |c, (r, p)| c + r * *p)
            / normal;
        let about_centre = twist - centre.cross(&along).dot(&self.n);
        let free = 1.0 - 1e-12 - along.norm() / (self.mu * normal);
        if free.is_nan() || free <= 0.0 {
            return false;
        }
        if about_centre == 0.0 {
            return true;
        }
        let (e1, e2) = self.axes;
        let root = std::f64::consts::FRAC_1_SQRT_2;
        let arm = [e1, e2, (e1 + e2) * root, (e1 - e2) * root]
            .iter()
            .map(|e| median_deviation(spots.iter().map(|r| r.dot(e)).zip(&self.shares)))
            .fold(0.0, f64::max);
        about_centre.abs() / (self.mu * arm) <= free
    }
}

/// Σ wᵢ |xᵢ − m| about the weighted median m of the pairs (xᵢ, wᵢ): the least of
/// Σ wᵢ |xᵢ − s| over s.
fn median_deviation<'a>(pairs: impl Iterator<Item = (f64, &'a f64)>) -> f64 {
    let mut pairs: Vec<(f64, f64)> = pairs.map(|(x, w)| (x, *w)).collect();
    pairs.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let half = 0.5 * pairs.iter().map(|p| p.1).sum::<f64>();
    let mut below = 0.0;
    let median = pairs
        .iter()
        .find(|p| {
            below += p.1;
            below >= half
        })
        .map_or(0.0, |p| p.0);
    pairs.iter().map(|(x, w)| w * (x - median).abs()).sum()
}

/// A slip direction settled ([`Flush::settled`]): the mode, the loads' power in it over
/// friction's, and whether it settled to round-off.
#[derive(Debug, Clone, Copy)]
struct Settled {
    mode: [f64; 3],
    power: f64,
    exact: bool,
}

/// A unit basis of the plane tangent to the unit sphere at `z`.
fn tangent_basis(z: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let other = if z.x.abs() < 0.6 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let b1 = z.cross(&other).normalize();
    (b1, z.cross(&b1))
}

/// Directions of slip tried from where the block's own direction does not settle: the
/// translations along the axes and their diagonals, the turn each way, and their mixtures
/// (rates along e1, e2 and the turn at the base's size).
const DIRECTIONS: [[f64; 3]; 14] = [
    [1.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, -1.0],
    [1.0, 1.0, 1.0],
    [1.0, 1.0, -1.0],
    [1.0, -1.0, 1.0],
    [1.0, -1.0, -1.0],
    [-1.0, 1.0, 1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [-1.0, -1.0, -1.0],
];

/// The mass metric of the slide's modes: the mass along the plane, the moment of inertia
/// about its normal.
struct Metric {
    mass: f64,
    about_n: f64,
}

impl Metric {
    fn of(ctx: &Ctx<'_>, pose: &BodyPose, n: Vector3<f64>) -> Metric {
        let inertia = pose.rotation * ctx.inertia * pose.rotation.transpose();
        Metric {
            mass: ctx.body.block().mass,
            about_n: n.dot(&(inertia * n)),
        }
    }

    /// The accelerations a force and a moment give.
    fn accelerate(&self, f: [f64; 3]) -> [f64; 3] {
        [f[0] / self.mass, f[1] / self.mass, f[2] / self.about_n]
    }

    /// Friction's stiffness of `rub` in this metric (1/s): how fast a slip across the motion
    /// dies away, Σ μ p (1/m + r²/I) / |u| over the points sliding at u. An explicit step
    /// longer than a few times its inverse amplifies round-off across the motion instead.
    fn stiffness(&self, rub: &Rubbing) -> f64 {
        rub.stiff.0 / self.mass + rub.stiff.1 / self.about_n
    }

    fn norm(&self, a: [f64; 3]) -> f64 {
        (self.mass * (a[0] * a[0] + a[1] * a[1]) + self.about_n * a[2] * a[2]).sqrt()
    }

    /// The part of `a` along the unit mode `d` (both in this metric's terms: accelerations
    /// or velocities along e1, e2 and about n).
    fn along(&self, a: [f64; 3], d: [f64; 3]) -> [f64; 3] {
        let k = self.mass * (a[0] * d[0] + a[1] * d[1]) + self.about_n * a[2] * d[2];
        d.map(|x| x * k)
    }

    /// `a` scaled to one in this metric (zero stays zero).
    fn unit(&self, a: [f64; 3]) -> [f64; 3] {
        let k = self.norm(a);
        if k > 0.0 { a.map(|x| x / k) } else { a }
    }
}

#[cfg(test)]
mod tests {
    use super::super::OnBase;
    use super::super::tests::set_down;
    use super::*;
    use crate::scene::Scene;

    /// A 4 m square block of 1000 t, its CM 1 m over its base, on rock dipping `dip` (degrees)
    /// along +X with μ = 0.4, pushed along X by `push` of its weight through a line `e` (m)
    /// off its CM.
    fn scene(dip: f64, push: f64, e: f64) -> String {
        format!(
            "name = \"flush\"\n[frame]\ncontacts_m = [[-2.0, 2.0], [2.0, 2.0], [2.0, -2.0]]\n\
             [foundation]\n[[foundation.plane]]\ndip_deg = {dip}\ndip_direction_deg = 0.0\n\
             point_m = [0.0, 0.0, 0.0]\n[block]\nmass_kg = 1.0e6\ninertia_kg_m2 = 2.6667e6\n\
             [loads]\nhydraulic_force_n = {}\neccentricity_m = {e}\ngravity_m_s2 = 9.81\n\
             [friction]\nmodel = \"coulomb\"\nmu_k = 0.4\n[solver]\nmode = \"exact\"\n\
             dt_s = 1.0e-3\nt_end_s = 1.0\ncontacts = \"base\"\n",
            push * 1e6 * 9.81
        )
    }

    /// What `check` says of the block of `text` set down on its rock, its slide there.
    fn on_its_rock<T>(text: &str, check: impl Fn(&mut OnBase<'_>, &mut Flush) -> T) -> T {
        let sim = Scene::from_toml(text, "flush")
            .unwrap()
            .simulation()
            .unwrap();
        let mut on = set_down(&sim, 1e-3);
        assert!(on.flush_phase(), "the base lies flush on its plane");
        let mut flush = on.flush.take().unwrap();
        check(&mut on, &mut flush)
    }

    /// Whether the block of `text` at rest on its rock starts: the mode, if so.
    fn starts(text: &str) -> Option<[f64; 3]> {
        on_its_rock(text, |on, flush| {
            let ctx = on.ctx();
            let (force, moment, _) = ctx.loads(&on.s.pose, 0.0);
            flush
                .onset(&ctx, &on.s.pose, (force, moment))
                .unwrap()
                .map(|(m, _)| m)
        })
    }

    #[test]
    fn pushed_through_its_cm_a_block_starts_just_past_mu_times_its_weight_along_the_push() {
        for push in [0.3, 0.399_999, 0.4 - 1e-9] {
            assert_eq!(starts(&scene(0.0, push, 0.0)), None, "push {push} W");
        }
        for push in [0.4 + 1e-9, 0.400_001, 0.5] {
            let [a1, a2, alpha] = starts(&scene(0.0, push, 0.0)).expect("it starts");
            // Along the push (e1 is the block's x′ on level rock), not turning.
            assert!(a1 > 0.0 && a2.abs() < 1e-12 * a1, "{a1} {a2}");
            assert!(alpha.abs() < 1e-12 * a1, "{alpha}");
        }
    }

    #[test]
    fn on_an_incline_a_block_holds_below_its_friction_angle_and_slides_at_g_sin_less_mu_g_cos() {
        // tan 21.8° = 0.39997: held; tan 21.81° = 0.40004: it starts.
        assert_eq!(starts(&scene(21.8, 0.0, 0.0)), None);
        assert!(starts(&scene(21.81, 0.0, 0.0)).is_some());
        let dip = 30f64.to_radians();
        let a = on_its_rock(&scene(30.0, 0.0, 0.0), |on, flush| {
            let ctx = on.ctx();
            let loads = ctx.loads(&on.s.pose, 0.0);
            let (e1, _) = flush.axes;
            // Sliding down the dip at 1 m/s.
            let down = e1 * e1.dot(&Vector3::new(1.0, -dip.tan(), 0.0)).signum();
            let r = flush.rates(
                &ctx,
                &on.s.pose.clone(),
                (loads.0, loads.1),
                (down, Vector3::zeros()),
            );
            r.unwrap().a.dot(&down)
        });
        let want = 9.81 * (dip.sin() - 0.4 * dip.cos());
        assert!((a - want).abs() < 1e-12 * want, "{a} against {want}");
    }

    #[test]
    fn a_twisting_push_starts_the_block_where_the_static_check_of_the_steps_law_says() {
        // A push of 0.05 W along a line e off the CM: the bed's friction holds a couple of
        // about μ W a (√2 + ln(1 + √2))/3 = 0.612 W·m; the onset here and the static check of
        // the time-stepping scheme's law (the same bed, `mechanics::held::held_pressing`)
        // part at the same e.
        for e in [4.0, 8.0, 10.0, 11.0, 11.5, 12.5, 13.0, 14.0, 17.0, 22.0] {
            let text = scene(0.0, 0.05, e);
            let law = on_its_rock(&text, |on, _| {
                on.ctx().held_by_its_law(&on.s.pose, 0.0, 1e-3, &on.last)
            });
            assert_eq!(
                starts(&text).is_none(),
                law,
                "a push of 0.05 W {e} m off its CM"
            );
        }
    }

    #[test]
    fn the_quick_hold_never_holds_a_block_the_search_starts() {
        // Pushes of 0.02–0.44 W through lines 0–24 m off the CM, on level rock and dipping
        // 10°: wherever the sufficient test holds the block, the search finds no mode that
        // starts it; and it holds most that the search holds, twisted ones among them.
        let (mut quick, mut held, mut twisted) = (0, 0, 0);
        for dip in [0.0, 10.0] {
            for push in [0.02, 0.1, 0.2, 0.3, 0.35, 0.39, 0.41, 0.44] {
                for e in [0.0, 0.5, 2.0, 6.0, 12.0, 24.0] {
                    let (sure, found) = on_its_rock(&scene(dip, push, e), |on, flush| {
                        let ctx = on.ctx();
                        let (force, moment, _) = ctx.loads(&on.s.pose, 0.0);
                        let sure = flush.onset(&ctx, &on.s.pose, (force, moment)).unwrap();
                        let n = flush.n;
                        let along = force - n * n.dot(&force);
                        let demand = [along.dot(&flush.axes.0), along.dot(&flush.axes.1)];
                        let spots = flush.spots(&on.s.pose);
                        let m = Metric::of(&ctx, &on.s.pose, n);
                        let twist = moment.dot(&n);
                        let found =
                            flush.search(&spots, &m, [demand[0], demand[1], twist], ctx.size);
                        (
                            flush.surely_held(&spots, along, twist) && sure.is_none(),
                            found,
                        )
                    });
                    assert!(!(sure && found.is_some()), "{push} W {e} m off, {dip}°");
                    quick += usize::from(sure);
                    held += usize::from(found.is_none());
                    twisted += usize::from(sure && e > 0.0);
                }
            }
        }
        assert!(
            quick * 2 > held && twisted > 0,
            "{quick} of {held}, {twisted}"
        );
    }

    #[test]
    fn the_median_deviation_is_the_least_sum_of_distances() {
        // 0, 1, 2, 3 evenly: any s in [1, 2] gives 4. Weighted 1, 1, 1, 5: s = 3 gives 6.
        let even = [1.0; 4];
        let xs = [3.0, 0.0, 2.0, 1.0];
        assert_eq!(median_deviation(xs.iter().copied().zip(&even)), 4.0);
        let heavy = [1.0, 1.0, 1.0, 5.0];
        let xs = [0.0, 1.0, 2.0, 3.0];
        assert_eq!(median_deviation(xs.iter().copied().zip(&heavy)), 6.0);
    }

    #[test]
    fn a_spinning_base_slows_at_its_pressures_friction_couple() {
        // Spinning at 1 rad/s about its CM on level rock, pressed evenly: the couple is
        // μ W a (√2 + ln(1 + √2))/3 for the 4 m square (a = 2 m), to the quadrature's error.
        let (alpha, spin) = on_its_rock(&scene(0.0, 0.0, 0.0), |on, flush| {
            let ctx = on.ctx();
            let loads = ctx.loads(&on.s.pose, 0.0);
            let w = flush.n;
            let r = flush.rates(
                &ctx,
                &on.s.pose.clone(),
                (loads.0, loads.1),
                (Vector3::zeros(), w),
            );
            (r.unwrap().alpha, 2.6667e6)
        });
        let couple = 0.4 * 9.81e6 * 2.0 * (2f64.sqrt() + (1.0 + 2f64.sqrt()).ln()) / 3.0;
        assert!(alpha < 0.0, "friction slows the spin: {alpha}");
        assert!(
            ((-alpha * spin) / couple - 1.0).abs() < 0.02,
            "{} against {couple}",
            -alpha * spin
        );
    }
}
