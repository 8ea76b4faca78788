//! The rock every body stands on, and its shaking: the ground (its faces or surface, or the
//! three planes of a three-plane site) and a ground-motion record, run as it is or under both
//! polarities. The foundation's acceleration at a time is the record's
//! ([`Foundation::acceleration`]).

use super::error::ModelError;
use super::record::Record;
use crate::geometry::{Ground, Site};
use std::sync::Arc;

/// The rock and its shaking. Unshaken unless given a record ([`Foundation::shaken`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Foundation {
    ground: Arc<Ground>,
    record: Option<Arc<Record>>,
    /// The record run as it is and reversed (`seismic.polarity = "both"`).
    both_polarities: bool,
}

impl Foundation {
    /// The rock `ground`, unshaken.
    pub fn new(ground: Arc<Ground>) -> Foundation {
        Foundation {
            ground,
            record: None,
            both_polarities: false,
        }
    }

    /// The rock under `site`: its ground of faces or surface, or, for the paper's site and any
    /// three planes, the ground of those planes (the highest of them: the paper's valley).
    pub fn under(site: &Site) -> Foundation {
        Foundation::new(match site.shared_ground() {
            Some(g) => Arc::clone(g),
            None => Arc::new(Ground::planes(site.planes().to_vec())),
        })
    }

    /// The same rock shaken by `record` (`seismic.record`).
    pub fn shaken(self, record: impl Into<Arc<Record>>) -> Foundation {
        Foundation {
            record: Some(record.into()),
            ..self
        }
    }

    /// The same rock with its record to be run as it is and reversed, the larger permanent
    /// displacement reported (`seismic.polarity = "both"`; `route::Runner::run`). Nothing for
    /// an unshaken rock.
    pub fn reversed_too(self) -> Foundation {
        Foundation {
            both_polarities: true,
            ..self
        }
    }

    /// The rock's ground.
    pub fn ground(&self) -> &Arc<Ground> {
        &self.ground
    }

    /// The number of the rock's faces (numbered from 0, as route.csv's `face` columns).
    pub fn face_count(&self) -> usize {
        self.ground.faces().len()
    }

    /// The ground-motion record, when the rock is shaken.
    pub fn record(&self) -> Option<&Record> {
        self.record.as_deref()
    }

    /// Whether the record is to be run as it is and reversed, the larger permanent
    /// displacement reported (`seismic.polarity = "both"`).
    pub fn both_polarities(&self) -> bool {
        self.both_polarities && self.record.is_some()
    }

    /// The foundation's acceleration (g, along X, Y, Z) at time t: the record's, or none.
    pub fn acceleration(&self, t: f64) -> [f64; 3] {
        self.record.as_ref().map_or([0.0; 3], |r| r.at(t))
    }

    /// The same rock under one polarity of its record: reversed (every acceleration negated) or
    /// as it is, run once.
    pub fn one_polarity(&self, reversed: bool) -> Result<Foundation, ModelError> {
        let record = match (&self.record, reversed) {
            (Some(r), true) => Some(Arc::new(r.scaled(-1.0)?)),
            (r, _) => r.clone(),
        };
        Ok(Foundation {
            ground: Arc::clone(&self.ground),
            record,
            both_polarities: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_sites_rock_is_its_three_planes_and_shaking_is_the_records() {
        let site = crate::scene::Scene::default_scene().site().clone();
        let rock = Foundation::under(&site);
        assert_eq!(rock.face_count(), 3);
        assert_eq!(rock.ground().faces(), site.planes());
        assert_eq!(rock.acceleration(0.5), [0.0; 3]);
        // Both polarities asked of an unshaken rock: nothing to run twice.
        assert!(!rock.clone().reversed_too().both_polarities());
        let record = Record::new(vec![(0.0, [0.0; 3]), (1.0, [0.2, 0.0, 0.0])]).unwrap();
        let shaken = rock.shaken(record).reversed_too();
        assert!(shaken.both_polarities());
        assert!((shaken.acceleration(0.5)[0] - 0.1).abs() < 1e-15);
        let back = shaken.one_polarity(true).unwrap();
        assert!(!back.both_polarities());
        assert!((back.acceleration(0.5)[0] + 0.1).abs() < 1e-15);
    }
}
