//! What every quantity's meter holds over a run, whatever its family: the quantity, the level's
//! facts, the first snapshot, when it is read, and why its analysis does not apply. A family keeps
//! what it accumulates in a state of its own, in its own file; `dispatch` routes a quantity to
//! its family with both.

use super::level_facts::LevelFacts;
use crate::level::Quantity;
use crate::snapshot::{BodyState, Snapshot};
use std::sync::Arc;

/// A quantity's value at a sample: the engine's, and the textbook analysis when one applies.
pub(super) type EngineAndAnalysis = (f64, Option<f64>);

/// One quantity followed over a run: the part of its state every family reads.
#[derive(Clone)]
pub(super) struct Meter {
    pub q: Quantity,
    pub facts: Arc<LevelFacts>,
    /// The first snapshot the meter saw (the initial state).
    pub init: Option<Arc<Snapshot>>,
    /// Read at a configuration event (not a fixed time): see `Quantity::KineticEnergy`.
    pub configuration_event: bool,
    /// Read at an impact or a blow (`FirstContact`, `ContactEnds`, `AfterEvent`), whose
    /// analyses are the impulse-momentum solution's.
    pub impact_instant: bool,
    /// Why the quantity's analysis does not apply to this scene (a precondition of its formula
    /// that the scene breaks), set by the family: then the analysis is None and the question is
    /// graded on the engine alone, saying so.
    pub inapplicable: Option<String>,
}

impl Meter {
    pub fn new(q: &Quantity, facts: Arc<LevelFacts>) -> Self {
        Meter {
            q: q.clone(),
            facts,
            init: None,
            configuration_event: true,
            impact_instant: false,
            inapplicable: None,
        }
    }

    /// Body `name`'s index in `s` (`LevelFacts::body_index`: no scan of every name).
    pub fn body_index(&self, s: &Snapshot, name: &str) -> Option<usize> {
        self.facts.body_index(s, name)
    }

    /// Body `name` of `s` with its index.
    pub fn named_body<'a>(&self, s: &'a Snapshot, name: &str) -> Option<(usize, &'a BodyState)> {
        self.facts.named_body(s, name)
    }
}
