//! Contact: what the bodies touch, as pairs with frames and strengths, and the rows and
//! patches the impulse solve sees.
//!
//! The middle of the contact pipeline (ARCHITECTURE.md, "The contact pipeline"), between the
//! geometry of contact (`src/geometry/contact/`: the narrow phase and the patches) and the
//! solve (`src/mechanics/impulses/`):
//!
//! * [`bodies`]: the bodies of a simulation as the narrow phase sees them.
//! * [`pair`]: a [`ContactPair`] — which body, against a face of the rock or another body, the
//!   point, the unit normal, the gap, the features and the pair's friction criterion.
//! * [`row`]: a [`ContactRow`] — body `a`, body `b` or the rock, each body's arm, the normal,
//!   the friction over the step ([`Shear`]), the speed the gap may close at, and the warm start
//!   matched from the last step. Body–rock and body–body rows are one type.
//! * [`patch`]: the solve's [`Patch`] of a body lying flush, each point with its friction and
//!   warm start.
//! * [`quadrature`]: a body's quadrature points, from its base or its cast relief.

pub mod bodies;
pub mod pair;
pub mod patch;
pub mod quadrature;
pub mod row;

pub use pair::{ContactPair, on_rock, rock_criterion, rock_strength};
pub use patch::{Patch, patches};
pub use row::{ContactRow, Share, Side, Warm, closing_rows, rows};
// The rest, for the tests and `internals`: the route builds these types through the functions
// above, and follows one body (`placed` gives every body of a simulation).
#[cfg_attr(not(feature = "internals"), allow(unused_imports))]
pub use {bodies::placed, pair::Against, patch::PatchPoint, row::Shear};
