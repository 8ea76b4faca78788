//! One recorded row of a route, in the units of `route.csv`.

use serde::Serialize;

/// One recorded increment, in the units of `route.csv` (degrees, m, s, N). The default is the
/// start at rest, without reactions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct Row {
    /// The body the row is of: its number in the simulation's bodies, from 0 (a scene of one
    /// block: 0).
    pub body: u32,
    /// Time (s).
    pub t_s: f64,
    /// The CM's X (m).
    pub x_m: f64,
    /// The CM's height Y (m).
    pub y_m: f64,
    /// The CM's Z (m).
    pub z_m: f64,
    /// The yaw θ (degrees).
    pub theta_deg: f64,
    /// The tilt α: the elevation of side 01 (degrees).
    pub alpha_deg: f64,
    /// The tilt β: the elevation of side 02 (degrees).
    pub beta_deg: f64,
    /// The tilt γ: the elevation of side 1→2 (degrees).
    pub gamma_deg: f64,
    /// Ẋ (m/s).
    pub vx_m_s: f64,
    /// Ż (m/s).
    pub vz_m_s: f64,
    /// θ̇ (degrees a second).
    pub omega_deg_s: f64,
    /// Normal reaction magnitudes at contacts 0, 1, 2 (N); `None` where the reactions could not
    /// be had (the last row of a route that ended for that reason, a block at rest).
    pub n_n: Option<[f64; 3]>,
    /// Shear reaction magnitudes at contacts 0, 1, 2 (N), likewise.
    pub s_n: Option<[f64; 3]>,
    /// The face each contact rests on: its plane's number (the paper's planes and any three
    /// planes: 0, 1, 2 for contacts 0, 1, 2; a ground of faces: the face's number).
    pub faces: [u32; 3],
    /// The second face of each contact riding a crease (`None` for a contact on its face alone).
    pub crease: [Option<u32>; 3],
    /// A base touching the ground (`contacts = "base"`): the corners of the base that carry the
    /// block, as the sum of 2^k over corner numbers k (the outline's order, from 0); `None` for
    /// the three-point frame.
    pub corners_carrying: Option<u32>,
    /// A base touching the ground: how many points carry the block (its corners, the ground's
    /// vertices under it, ground edges across its edges); `None` for the three-point frame.
    pub points_carrying: Option<u32>,
}

impl Row {
    /// The names of a row's values, with their units, in the order of [`Row::values`]: the
    /// header of `route.csv`.
    pub const COLUMNS: [&'static str; 26] = [
        "body",
        "t_s",
        "x_m",
        "y_m",
        "z_m",
        "theta_deg",
        "alpha_deg",
        "beta_deg",
        "gamma_deg",
        "vx_m_s",
        "vz_m_s",
        "omega_deg_s",
        "n0_n",
        "n1_n",
        "n2_n",
        "s0_n",
        "s1_n",
        "s2_n",
        "face0",
        "face1",
        "face2",
        "crease_face0",
        "crease_face1",
        "crease_face2",
        "corners_carrying",
        "points_carrying",
    ];

    /// The row's values in the order of [`Row::COLUMNS`]; `None` for reactions that could not
    /// be had and for a contact on no crease.
    pub fn values(&self) -> [Option<f64>; 26] {
        let mut v = [None; 26];
        let scalars = [
            f64::from(self.body),
            self.t_s,
            self.x_m,
            self.y_m,
            self.z_m,
            self.theta_deg,
            self.alpha_deg,
            self.beta_deg,
            self.gamma_deg,
            self.vx_m_s,
            self.vz_m_s,
            self.omega_deg_s,
        ];
        for (k, x) in scalars.into_iter().enumerate() {
            v[k] = Some(x);
        }
        for k in 0..3 {
            v[12 + k] = self.n_n.map(|n| n[k]);
            v[15 + k] = self.s_n.map(|s| s[k]);
            v[18 + k] = Some(f64::from(self.faces[k]));
            v[21 + k] = self.crease[k].map(f64::from);
        }
        v[24] = self.corners_carrying.map(f64::from);
        v[25] = self.points_carrying.map(f64::from);
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_value_of_a_row_stands_under_its_own_column_name() {
        let r = Row {
            body: 2,
            t_s: 1.0,
            x_m: 2.0,
            y_m: 3.0,
            z_m: 4.0,
            theta_deg: 5.0,
            alpha_deg: 6.0,
            beta_deg: 7.0,
            gamma_deg: 8.0,
            vx_m_s: 9.0,
            vz_m_s: 10.0,
            omega_deg_s: 11.0,
            n_n: Some([12.0, 13.0, 14.0]),
            s_n: Some([15.0, 16.0, 17.0]),
            faces: [18, 19, 20],
            crease: [None, Some(21), None],
            corners_carrying: Some(0b101),
            points_carrying: Some(3),
        };
        let at = |name: &str| r.values()[Row::COLUMNS.iter().position(|c| *c == name).unwrap()];
        assert_eq!(Row::COLUMNS[0], "body");
        assert_eq!(at("body"), Some(2.0));
        assert_eq!(at("t_s"), Some(r.t_s));
        assert_eq!(at("theta_deg"), Some(r.theta_deg));
        assert_eq!(at("omega_deg_s"), Some(r.omega_deg_s));
        assert_eq!(at("n1_n"), Some(13.0));
        assert_eq!(at("s2_n"), Some(17.0));
        assert_eq!(at("face0"), Some(18.0));
        assert_eq!(at("crease_face1"), Some(21.0));
        assert_eq!(at("crease_face0"), None);
        assert_eq!(at("corners_carrying"), Some(5.0));
        assert_eq!(at("points_carrying"), Some(3.0));
        let lost = Row {
            n_n: None,
            s_n: None,
            ..r
        };
        let v = lost.values();
        assert!(v[12..18].iter().all(Option::is_none));
        assert_eq!(v.iter().filter(|x| x.is_some()).count(), 12 + 3 + 1 + 2);
    }
}
