//! What a route on a base reports beyond its rows: where the block rested before any load, what
//! carried it there, and how deep its base ever went into the ground by an independent check.

use crate::geometry::{Feature, Rest, Touch};
use serde::Serialize;

/// A point that carries the block.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Carrying {
    /// Which features touch: "corner 2", "ground vertex", "ground edge across base edge 1".
    pub feature: String,
    /// The face of the ground it is on (one of those that meet there, at an edge or a vertex).
    pub face: u32,
    /// Where (m).
    pub x_m: f64,
    /// Where (m).
    pub y_m: f64,
    /// Where (m).
    pub z_m: f64,
    /// Its share of the weight (a fraction; the shares sum to one along Y).
    pub share: f64,
}

impl Carrying {
    fn of(t: &Touch, share: f64) -> Carrying {
        let feature = match t.feature {
            Feature::Corner(k) => format!("corner {k}"),
            Feature::GroundVertex => "ground vertex".to_string(),
            Feature::Crossing(k) => format!("ground edge across base edge {k}"),
            Feature::ReliefVertex(k) => format!("cast base vertex {k}"),
            Feature::ReliefCrossing(k) => format!("ground edge across cast base edge {k}"),
        };
        Carrying {
            feature,
            face: t.face as u32,
            x_m: t.on_base.x,
            y_m: t.on_base.y,
            z_m: t.on_base.z,
            share,
        }
    }
}

/// The pose the block rests in on the ground under its own weight, before any load.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Resting {
    /// The centre of mass (m).
    pub x_m: f64,
    /// The centre of mass (m).
    pub y_m: f64,
    /// The centre of mass (m).
    pub z_m: f64,
    /// The yaw of x′ (degrees).
    pub theta_deg: f64,
    /// The base's tilt from level (degrees).
    pub tilt_deg: f64,
    /// Body to world, row by row: its columns are the block's x′, y′, z′ in world axes.
    pub rotation: [[f64; 3]; 3],
    /// What carries it.
    pub carrying: Vec<Carrying>,
}

impl Resting {
    pub(super) fn of(rest: &Rest) -> Resting {
        let r = rest.pose.rotation;
        let i = r.column(0);
        Resting {
            x_m: rest.pose.cm.x,
            y_m: rest.pose.cm.y,
            z_m: rest.pose.cm.z,
            theta_deg: i.z.atan2(i.x).to_degrees(),
            tilt_deg: r[(1, 1)].clamp(-1.0, 1.0).acos().to_degrees(),
            rotation: [0, 1, 2].map(|row| [0, 1, 2].map(|col| r[(row, col)])),
            carrying: rest
                .carrying
                .iter()
                .map(|(t, s)| Carrying::of(t, *s))
                .collect(),
        }
    }
}

/// What a route on its base adds to its summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BaseReport {
    /// Where it rested before any load.
    pub resting: Resting,
    /// The deepest any recorded row's base went into the ground (m; zero or less when it never
    /// did), by sampling the base against the ground's height (not the contact model's gaps).
    pub max_penetration_m: f64,
    /// The corners of the base (x′, z′ about the CM, m), in the order `route.csv`'s
    /// `corners_carrying` numbers them.
    pub outline_m: Vec<[f64; 2]>,
    /// When the joint's bond broke (s): the block had cohesion with its rock and first slid
    /// then, at 0 where it was set going or its bond could not hold it
    /// (`derivations/13-base-contact.md` §11). None without cohesion, or where it never slid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bond_broken_s: Option<f64>,
}

/// The pose of a block on its base at a recorded `row`, rebuilt from the row alone: the point
/// under the centre of mass, the yaw θ and the elevations α, β of the frame's sides 0→1 and 0→2
/// (`contacts`, x′ z′ about the centre of mass), with the centre of mass `depth` above its base.
/// The rotation is the yaw, then a pitch about z′ and a roll about x′, found by Newton on the two
/// elevations. `None` where Newton does not converge (the sides' elevations do not fit a
/// rotation of that yaw).
pub fn pose_of_row(
    row: &crate::route::Row,
    contacts: &[[f64; 2]; 3],
    depth: f64,
) -> Option<crate::geometry::BodyPose> {
    use nalgebra::{Matrix2, Rotation3, Vector2, Vector3};
    let c = contacts.map(|[x, z]| Vector3::new(x, 0.0, z));
    let yaw = Rotation3::from_axis_angle(&Vector3::y_axis(), -row.theta_deg.to_radians());
    let at = |p: f64, r: f64| {
        yaw * Rotation3::from_axis_angle(&Vector3::z_axis(), p)
            * Rotation3::from_axis_angle(&Vector3::x_axis(), r)
    };
    let elevation = |m: &Rotation3<f64>, a: usize, b: usize| {
        let d = m * (c[b] - c[a]);
        (d.y / d.norm()).clamp(-1.0, 1.0).asin()
    };
    let want = Vector2::new(row.alpha_deg.to_radians(), row.beta_deg.to_radians());
    let f = |p: f64, r: f64| {
        let m = at(p, r);
        Vector2::new(elevation(&m, 0, 1), elevation(&m, 0, 2)) - want
    };
    let (mut p, mut r) = (want[0], 0.0);
    for _ in 0..60 {
        let f0 = f(p, r);
        if f0.norm() < 1e-13 {
            let rotation = at(p, r).into_inner();
            let under = Vector3::new(row.x_m, row.y_m, row.z_m);
            return Some(crate::geometry::BodyPose {
                cm: under + rotation.column(1) * depth,
                rotation,
            });
        }
        let eps = 1e-7;
        let (fp, fr) = (f(p + eps, r), f(p, r + eps));
        let j = Matrix2::from_columns(&[(fp - f0) / eps, (fr - f0) / eps]);
        let step = j.try_inverse()? * f0;
        p -= step[0];
        r -= step[1];
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::BodyPose;
    use nalgebra::{Rotation3, Vector3};

    #[test]
    fn a_pose_is_rebuilt_from_its_row_alone() {
        let contacts = [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]];
        let r = Rotation3::from_euler_angles(0.1, -0.7, 0.2).into_inner();
        let pose = BodyPose {
            cm: Vector3::new(1.0, 2.0, 3.0),
            rotation: r,
        };
        let depth = 1.5;
        let p = contacts.map(|[x, z]| pose.point(&Vector3::new(x, -depth, z)));
        let under = pose.point(&Vector3::new(0.0, -depth, 0.0));
        let elevation = |a: usize, b: usize| {
            let d = p[b] - p[a];
            (d.y / d.norm()).asin().to_degrees()
        };
        let i = r.column(0);
        let row = crate::route::Row {
            x_m: under.x,
            y_m: under.y,
            z_m: under.z,
            theta_deg: i.z.atan2(i.x).to_degrees(),
            alpha_deg: elevation(0, 1),
            beta_deg: elevation(0, 2),
            ..Default::default()
        };
        let back = pose_of_row(&row, &contacts, depth).unwrap();
        assert!((back.rotation - r).norm() < 1e-9, "{}", back.rotation - r);
        assert!((back.cm - pose.cm).norm() < 1e-9);
    }
}
