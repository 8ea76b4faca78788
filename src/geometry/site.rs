//! What geometry needs of a scene: the contact frame and the foundation's planes
//! (`docs/conventions.md`, "The frame" and "The foundation"). The scene builds them from its
//! file and validates them; geometry takes nothing else.

use super::ground::Ground;
use super::plane::Plane;
use nalgebra::Vector3;
use std::sync::Arc;

/// The contact triangle in the monolith base, in its own plane (x', z'), CM at the origin:
/// r0 = (−L1X, L1Z), r1 = (L2X, L1Z), r2 = (L2X, −L2Z) (paper eq. (20)); all lengths in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// From the CM to vertex 0 along −x′.
    pub l1x: f64,
    /// From the CM to side 12 along x′.
    pub l2x: f64,
    /// From the CM to side 01 along z′.
    pub l1z: f64,
    /// From the CM to vertex 2 along −z′.
    pub l2z: f64,
}

impl Frame {
    /// Side length L = L1X + L2X = L1Z + L2Z (sides 01 and 12; side 02 is √2·L).
    pub fn l(&self) -> f64 {
        self.l1x + self.l2x
    }

    /// In-plane coordinates (x', z') of vertices 0, 1, 2 relative to the CM (eq. (20)).
    pub fn vertices(&self) -> [[f64; 2]; 3] {
        [
            [-self.l1x, self.l1z],
            [self.l2x, self.l1z],
            [self.l2x, -self.l2z],
        ]
    }
}

/// The paper's three foundation planes ξ, ζ, κ: horizontal (vertex 0), plane 1 (vertex 1),
/// plane 2 (vertex 2). Angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperPlanes {
    /// ξ: true dip of plane 1, in (0, π/2).
    pub xi: f64,
    /// ζ: true dip of plane 2, in (0, π/2).
    pub zeta: f64,
    /// κ: azimuth of int. line 2/horiz, in (−π/2, π/2).
    pub kappa: f64,
}

impl PaperPlanes {
    /// The upward unit normals of the horizontal plane, plane 1 and plane 2 (the planes under
    /// vertices 0, 1 and 2; `docs/conventions.md`, "The foundation").
    pub fn normals(&self) -> [Vector3<f64>; 3] {
        let (s1, c1) = self.xi.sin_cos();
        let (s2, c2) = self.zeta.sin_cos();
        [
            Vector3::y(),
            Vector3::new(-s1, c1, 0.0),
            Vector3::new(-s2 * self.kappa.cos(), c2, s2 * self.kappa.sin()),
        ]
    }
}

/// The paper's site: its right isosceles frame and its three planes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperSite {
    /// The paper's frame.
    pub frame: Frame,
    /// The paper's three planes.
    pub foundation: PaperPlanes,
}

/// What geometry takes of a scene: the contact triangle and the plane under each contact. A
/// site made from the paper's frame and planes ([`Site::paper`]) keeps them
/// ([`Site::as_paper`]), and the pose then comes from the paper's own systems (13)–(15); any
/// other site ([`Site::general`], [`Site::on_ground`]) from the general system
/// (`derivations/09-general-pose.md`). A site on a ground of faces knows the ground, so that a
/// pose with a contact under another face is not admissible.
#[derive(Debug, Clone, PartialEq)]
pub struct Site {
    contacts: [[f64; 2]; 3],
    planes: [Plane; 3],
    paper: Option<PaperSite>,
    l: f64,
    ground: Option<(Arc<Ground>, [usize; 3])>,
}

impl Site {
    /// The paper's site: the contacts of its frame, the horizontal plane, plane 1 and plane 2.
    pub fn paper(frame: Frame, planes: PaperPlanes) -> Site {
        let contacts = frame.vertices();
        let normals = planes.normals();
        let start = |k: usize| Vector3::new(contacts[k][0], 0.0, contacts[k][1]);
        Site {
            contacts,
            planes: std::array::from_fn(|k| Plane::through(normals[k], start(k))),
            paper: Some(PaperSite {
                frame,
                foundation: planes,
            }),
            l: frame.l(),
            ground: None,
        }
    }

    /// Any contact triangle (x', z' of each contact, CM at the origin, m) with any plane under
    /// each contact.
    pub fn general(contacts: [[f64; 2]; 3], planes: [Plane; 3]) -> Site {
        Site {
            contacts,
            planes,
            paper: None,
            l: scale(&contacts),
            ground: None,
        }
    }

    /// Contacts on a ground of faces, contact k on face `faces[k]`.
    pub fn on_ground(contacts: [[f64; 2]; 3], ground: Arc<Ground>, faces: [usize; 3]) -> Site {
        let planes = faces.map(|k| ground.faces()[k]);
        Site {
            ground: Some((ground, faces)),
            ..Site::general(contacts, planes)
        }
    }

    /// The same site with contact `contact` on face `face` of its ground (`None` off a ground
    /// or for a face it does not have).
    pub fn with_face(&self, contact: usize, face: usize) -> Option<Site> {
        let (ground, faces) = self.ground.as_ref()?;
        ground.faces().get(face)?;
        let mut faces = *faces;
        *faces.get_mut(contact)? = face;
        Some(Site::on_ground(self.contacts, ground.clone(), faces))
    }

    /// The shared ground itself (a scene edited by key keeps it rather than reading its
    /// surface again).
    pub fn shared_ground(&self) -> Option<&Arc<Ground>> {
        self.ground.as_ref().map(|(g, _)| g)
    }

    /// The ground and the face each contact is on, for a site on a ground of faces.
    pub fn ground(&self) -> Option<(&Ground, [usize; 3])> {
        self.ground.as_ref().map(|(g, f)| (g.as_ref(), *f))
    }

    /// The paper's frame and planes, when this is the paper's site.
    pub fn as_paper(&self) -> Option<&PaperSite> {
        self.paper.as_ref()
    }

    /// The contacts' (x', z') about the CM (m).
    pub fn contacts(&self) -> &[[f64; 2]; 3] {
        &self.contacts
    }

    /// The plane under each contact.
    pub fn planes(&self) -> &[Plane; 3] {
        &self.planes
    }

    /// The upward unit normals of the planes under contacts 0, 1, 2.
    pub fn normals(&self) -> [Vector3<f64>; 3] {
        self.planes.map(|p| p.normal())
    }

    /// The frame's length scale (m): the paper's L, and for any triangle the longest side over
    /// √2 (which is L for the paper's).
    pub fn l(&self) -> f64 {
        self.l
    }
}

/// The longest side of a triangle over √2.
fn scale(c: &[[f64; 2]; 3]) -> f64 {
    let side = |a: usize, b: usize| (c[a][0] - c[b][0]).hypot(c[a][1] - c[b][1]);
    side(0, 1).max(side(1, 2)).max(side(0, 2)) / std::f64::consts::SQRT_2
}
