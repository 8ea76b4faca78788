//! `[frame]` and `[foundation]`: the contacts and the ground under them, as a [`Site`].

use super::Reader;
use crate::geometry::{Frame, Ground, PaperPlanes, Plane, Site};
use crate::scene::SceneError;
use crate::scene::error::SceneErrorKind;
use crate::scene::raw;
use std::sync::Arc;

/// Relative tolerance on L1X + L2X = L1Z + L2Z.
const FRAME_TOLERANCE: f64 = 1e-9;

/// How far (as a fraction of the frame's scale) a contact's start may lie off the ground.
pub const START_TOL: f64 = 1e-9;

/// The frame as given: the paper's lengths, or any triangle's contacts.
enum FrameIn {
    Paper(Frame),
    Contacts([[f64; 2]; 3]),
}

/// The foundation as given: the paper's three planes, a list of faces, or a surface.
enum FoundationIn {
    Paper(PaperPlanes),
    Faces(Vec<Plane>),
    Surface(Arc<Ground>),
}

impl Reader<'_> {
    /// `[frame]` on `[foundation]`: the site.
    pub(super) fn site(
        &self,
        frame: &raw::RawFrame,
        foundation: &raw::RawFoundation,
        set_down: bool,
    ) -> Result<Site, SceneError> {
        let frame = self.frame(frame)?;
        let foundation = self.foundation(foundation)?;
        self.site_of(frame, foundation, set_down)
    }

    /// `[frame]`: either the paper's four lengths or `contacts_m`, not both.
    fn frame(&self, f: &raw::RawFrame) -> Result<FrameIn, SceneError> {
        let paper_keys = [f.l1x, f.l2x, f.l1z, f.l2z];
        match &f.contacts_m {
            Some(_) if paper_keys.iter().any(Option::is_some) => Err(self.invalid(
                "frame.contacts_m",
                "give either l1x, l2x, l1z, l2z (the paper's right isosceles frame) or contacts_m \
                 (any triangle), not both",
            )),
            Some(c) => self.contacts(c).map(FrameIn::Contacts),
            None if paper_keys.iter().all(Option::is_none) => Err(self.fault(
                SceneErrorKind::MissingKey,
                "frame",
                "give l1x, l2x, l1z, l2z (the paper's right isosceles frame) or contacts_m (any \
                 triangle)",
            )),
            None => self.paper_frame(f).map(FrameIn::Paper),
        }
    }

    /// `contacts_m`: three points (x', z') in metres, finite, about the CM, spanning a triangle.
    fn contacts(&self, c: &[Vec<f64>]) -> Result<[[f64; 2]; 3], SceneError> {
        let key = "frame.contacts_m";
        if c.len() != 3 || c.iter().any(|p| p.len() != 2) {
            return Err(self.invalid(
                key,
                format!(
                    "must be three points [x, z] (m), e.g. [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]]; \
                     got {} item(s)",
                    c.len()
                ),
            ));
        }
        let pts: [[f64; 2]; 3] = std::array::from_fn(|k| [c[k][0], c[k][1]]);
        if let Some(v) = pts.iter().flatten().find(|v| !v.is_finite()) {
            return Err(self.invalid(
                key,
                format!("must be finite numbers, got {}", crate::numeric::given(*v)),
            ));
        }
        let side = |a: usize, b: usize| (pts[a][0] - pts[b][0]).hypot(pts[a][1] - pts[b][1]);
        let longest = side(0, 1).max(side(1, 2)).max(side(0, 2));
        let twice_area = (pts[1][0] - pts[0][0]) * (pts[2][1] - pts[0][1])
            - (pts[2][0] - pts[0][0]) * (pts[1][1] - pts[0][1]);
        let spans = twice_area.abs() > 1e-6 * longest * longest;
        if !(longest * longest).is_finite() || !spans {
            return Err(self.invalid(
                key,
                format!(
                    "the three contacts must span a triangle (finite sides, not on one line): \
                     longest side {longest:e} m, area {:e} m²",
                    0.5 * twice_area.abs()
                ),
            ));
        }
        Ok(pts)
    }

    /// The paper's frame: positive lengths, a finite side, and the two legs of the right isosceles
    /// triangle equal.
    fn paper_frame(&self, f: &raw::RawFrame) -> Result<Frame, SceneError> {
        let length = |key: &str, v: Option<f64>| self.positive(key, self.need(key, v)?);
        let frame = Frame {
            l1x: length("frame.l1x", f.l1x)?,
            l2x: length("frame.l2x", f.l2x)?,
            l1z: length("frame.l1z", f.l1z)?,
            l2z: length("frame.l2z", f.l2z)?,
        };
        let (lx, lz) = (frame.l1x + frame.l2x, frame.l1z + frame.l2z);
        // Each length is finite, but their sum (L, on which every derived length and the pose's
        // coordinates rest) may not be (1.5e308 m each gave NaN tilts); nor may L²,
        // which the pose and the inertia scales use.
        if !(lx * lx).is_finite() || !(lz * lz).is_finite() {
            return Err(self.invalid("frame",
                format!(
                    "l1x + l2x = {lx:e} m and l1z + l2z = {lz:e} m: the frame's side L (and L²) must \
                     be finite numbers"
                ),
            ));
        }
        if (lx - lz).abs() > FRAME_TOLERANCE * lx.max(lz) {
            return Err(self.invalid(
                "frame",
                format!(
                    "l1x + l2x = {lx} m but l1z + l2z = {lz} m; the frame is an isosceles right \
                     triangle, so the two sums must be equal"
                ),
            ));
        }
        Ok(frame)
    }

    /// `[foundation]`: exactly one of the paper's three angles, a list of faces, or a surface (not
    /// read again when the files read before hold it under its name).
    fn foundation(&self, d: &raw::RawFoundation) -> Result<FoundationIn, SceneError> {
        let paper = [d.xi_deg, d.zeta_deg, d.kappa_deg]
            .iter()
            .any(Option::is_some);
        let forms = [
            (paper, "foundation.xi_deg"),
            (d.plane.is_some(), "foundation.plane"),
            (d.surface.is_some(), "foundation.surface"),
        ];
        let given: Vec<&str> = forms.iter().filter(|f| f.0).map(|f| f.1).collect();
        const FORMS: &str = "xi_deg, zeta_deg, kappa_deg (the paper's three planes), \
                             [[foundation.plane]] faces, or surface = \"rock.obj\" (a triangulated \
                             surface)";
        match given.as_slice() {
            [] => Err(self.fault(
                SceneErrorKind::MissingKey,
                "foundation",
                format!("give one of {FORMS}"),
            )),
            [_, second, ..] => Err(self.invalid(*second, format!("give one of {FORMS}, not more"))),
            ["foundation.plane"] => match d.plane.as_deref().unwrap_or_default() {
                [] => Err(self.invalid(
                    "foundation.plane",
                    "a foundation of faces needs at least one [[foundation.plane]]",
                )),
                planes => planes
                    .iter()
                    .enumerate()
                    .map(|(k, p)| self.face(k, p))
                    .collect::<Result<Vec<_>, _>>()
                    .map(FoundationIn::Faces),
            },
            ["foundation.surface"] => {
                let name = d.surface.as_deref().unwrap_or_default();
                self.files
                    .surface(self.folder, name)
                    .map(FoundationIn::Surface)
                    .map_err(|why| self.invalid("foundation.surface", why))
            }
            _ => self.paper_foundation(d).map(FoundationIn::Paper),
        }
    }

    /// The paper's three planes: dips strictly between 0° and 90°, κ strictly between −90° and 90°.
    fn paper_foundation(&self, d: &raw::RawFoundation) -> Result<PaperPlanes, SceneError> {
        let dip = |key: &str, v: Option<f64>| {
            let v = self.need(key, v)?;
            self.check(
                key,
                v,
                v > 0.0 && v < 90.0,
                "a dip strictly between 0° and 90°",
            )
            .map(f64::to_radians)
        };
        let kappa = self.need("foundation.kappa_deg", d.kappa_deg)?;
        Ok(PaperPlanes {
            xi: dip("foundation.xi_deg", d.xi_deg)?,
            zeta: dip("foundation.zeta_deg", d.zeta_deg)?,
            kappa: self
                .check(
                    "foundation.kappa_deg",
                    kappa,
                    kappa > -90.0 && kappa < 90.0,
                    "an azimuth strictly between -90° and 90°",
                )?
                .to_radians(),
        })
    }

    /// One `[[foundation.plane]]`: dip in [0°, 90°), any dip direction, a point of three finite
    /// coordinates.
    fn face(&self, k: usize, p: &raw::RawPlane) -> Result<Plane, SceneError> {
        let key = |name: &str| format!("foundation.plane[{k}].{name}");
        let dip = self.need(&key("dip_deg"), p.dip_deg)?;
        let dip = self.check(
            &key("dip_deg"),
            dip,
            (0.0..90.0).contains(&dip),
            "a dip from 0° up to (not including) 90°",
        )?;
        let dir = self.need(&key("dip_direction_deg"), p.dip_direction_deg)?;
        let dir = self.check(&key("dip_direction_deg"), dir, true, "finite")?;
        let point = self.need(&key("point_m"), p.point_m.as_ref())?;
        if point.len() != 3 || point.iter().any(|v| !v.is_finite()) {
            return Err(self.invalid(
                key("point_m"),
                format!("must be a point [X, Y, Z] of three finite numbers (m), got {point:?}"),
            ));
        }
        Ok(Plane::from_dip(
            dip.to_radians(),
            dir.to_radians(),
            nalgebra::Vector3::new(point[0], point[1], point[2]),
        ))
    }

    /// The site: the paper's frame on the paper's planes keeps the paper's systems; any triangle on
    /// the paper's planes (each through its contact's start, as the paper's are) takes the general
    /// system; on a list of faces each contact starts on the face under it (the block starts flat at
    /// Y = 0, so each contact must be on the ground there, neither under it nor above it), unless
    /// the block is `set_down` on its base (`contacts = "base"`), when it starts where it rests.
    fn site_of(
        &self,
        frame: FrameIn,
        foundation: FoundationIn,
        set_down: bool,
    ) -> Result<Site, SceneError> {
        let contacts = match &frame {
            FrameIn::Paper(f) => f.vertices(),
            FrameIn::Contacts(c) => *c,
        };
        let start = |k: usize| nalgebra::Vector3::new(contacts[k][0], 0.0, contacts[k][1]);
        match (frame, foundation) {
            (FrameIn::Paper(f), FoundationIn::Paper(g)) => Ok(Site::paper(f, g)),
            (FrameIn::Contacts(c), FoundationIn::Paper(g)) => {
                let pi = std::f64::consts::PI;
                let planes = [
                    Plane::from_dip(0.0, 0.0, start(0)),
                    Plane::from_dip(g.xi, pi, start(1)),
                    Plane::from_dip(g.zeta, pi - g.kappa, start(2)),
                ];
                Ok(Site::general(c, planes))
            }
            (_, FoundationIn::Faces(faces)) => {
                self.on_ground(contacts, Arc::new(Ground::planes(faces)), set_down)
            }
            (_, FoundationIn::Surface(ground)) => self.on_ground(contacts, ground, set_down),
        }
    }

    /// Contacts starting flat at Y = 0 on a ground of faces: each must be on the ground there,
    /// neither under it nor above it, and takes the face under it. A block `set_down` on its base
    /// only needs ground under its contacts' plan positions.
    fn on_ground(
        &self,
        contacts: [[f64; 2]; 3],
        ground: Arc<Ground>,
        set_down: bool,
    ) -> Result<Site, SceneError> {
        let key = if ground.is_surface() {
            "foundation.surface"
        } else {
            "foundation.plane"
        };
        let scale = Site::general(contacts, [ground.faces()[0]; 3]).l();
        let tol = START_TOL * scale;
        let mut faces = [0; 3];
        for (k, &[x, z]) in contacts.iter().enumerate() {
            let at = format!("contact {k} starts at (X, Z) = ({x}, {z}) m");
            let Some((top, h)) = ground.top(x, z) else {
                return Err(self.invalid(key, format!("{at}, off the surveyed surface")));
            };
            if h > tol && !set_down {
                return Err(self.invalid(
                    key,
                    format!(
                        "{at}, under the ground: face {top} stands {h:.6} m above it (the block \
                         starts flat at Y = 0 with every contact on the ground)"
                    ),
                ));
            }
            if h < -tol && !set_down {
                return Err(self.invalid(key,
                    format!(
                        "{at}, above the ground: the highest face there, face {top}, is {:.6} m \
                         below it (the block starts flat at Y = 0 with every contact on the ground)",
                        -h
                    ),
                ));
            }
            // At a crease, the face that rises first along x' (the push of the water).
            faces[k] = ground
                .face_under(x, z, (1.0, 0.0), 1e-3 * scale, tol)
                .unwrap_or(top);
        }
        Ok(Site::on_ground(contacts, ground, faces))
    }
}
