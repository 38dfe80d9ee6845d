//! The dispatcher: routes a quantity to its family. It holds the meter every family reads
//! ([`Meter`]) beside the state the quantity's family keeps (each family's `State`, in its own
//! file), and hands both to the family to advance and read. Imports run one way: this file ->
//! the families -> the plain types they share (`meter`, `sample`, `level_facts`, ...).

use super::level_facts::LevelFacts;
use super::meter::Meter;
use super::sample::{Occasion, Reading, Sample};
use super::{
    forces, impacts, linkages, motion, periods, reference_forces, rolling, work_and_power,
};
use crate::level::{Quantity, QuantityFamily};
use std::sync::Arc;

/// What the quantity's family accumulates over the run, one variant a family
/// ([`QuantityFamily`]); rolling and linkage quantities accumulate nothing.
#[derive(Clone)]
enum FamilyState {
    Motion(motion::State),
    Forces(forces::State),
    WorkAndPower(work_and_power::State),
    Periods(periods::State),
    Impacts(impacts::State),
    Rolling,
    Linkages,
}

/// Evaluates one quantity at every sample: its meter and its family's state.
#[derive(Clone)]
pub(super) struct FamilyMeter {
    pub common: Meter,
    state: FamilyState,
}

impl FamilyMeter {
    pub fn new(q: &Quantity, facts: Arc<LevelFacts>) -> Self {
        let state = match q.family() {
            QuantityFamily::Motion => FamilyState::Motion(motion::State::default()),
            QuantityFamily::Forces => FamilyState::Forces(forces::State::default()),
            QuantityFamily::WorkAndPower => {
                FamilyState::WorkAndPower(work_and_power::State::default())
            }
            QuantityFamily::Periods => FamilyState::Periods(periods::State::default()),
            QuantityFamily::Impacts => FamilyState::Impacts(impacts::State::new(q)),
            QuantityFamily::Rolling => FamilyState::Rolling,
            QuantityFamily::Linkages => FamilyState::Linkages,
        };
        FamilyMeter {
            common: Meter::new(q, facts),
            state,
        }
    }

    /// Accumulates what the quantity needs from the step that led to the sample.
    pub fn advance(&mut self, f: &Sample) {
        let s = f.cur;
        let m = &mut self.common;
        if m.init.is_none() {
            m.init = Some(Arc::clone(s));
        }
        let pair_event = match &mut self.state {
            FamilyState::Impacts(st) => st.follow_pair(f, &m.facts),
            _ => None,
        };
        if let FamilyState::Linkages = self.state {
            // From the first sample on: a percussion distance may be read at t = 0.
            linkages::advance(m);
        }
        let Some(prev) = f.prev else {
            return;
        };
        match &mut self.state {
            FamilyState::Motion(st) => motion::advance(m, st, prev, s),
            FamilyState::Forces(st) => forces::advance(m, st, prev, s),
            FamilyState::WorkAndPower(st) => work_and_power::advance(m, st, prev, s),
            FamilyState::Periods(st) => periods::advance(m, st, prev, s),
            FamilyState::Impacts(st) => impacts::advance(m, st, s, pair_event),
            FamilyState::Rolling => rolling::advance(m, prev, s),
            FamilyState::Linkages => {}
        }
    }

    /// Why the quantity has no engine value, where its family can tell (an impact that never
    /// happened or never ended; a mode whose shape the linearization could not give).
    pub fn why_missing(&self) -> Option<String> {
        match &self.state {
            FamilyState::Impacts(st) => impacts::why_missing(&self.common, st),
            FamilyState::Periods(st) => periods::why_missing(&self.common, st),
            _ => None,
        }
    }

    /// The quantity at the sample (NaN when it cannot be read there).
    pub fn read(&self, f: &Sample, occ: Occasion) -> Reading {
        let m = &self.common;
        let value = match &self.state {
            FamilyState::Motion(st) => motion::read(m, st, f, occ),
            FamilyState::Forces(st) => forces::read(m, st, f, occ),
            FamilyState::WorkAndPower(st) => work_and_power::read(m, st, f, occ),
            FamilyState::Periods(st) => periods::read(m, st, f),
            FamilyState::Rolling => rolling::read(m, f),
            FamilyState::Impacts(st) => impacts::read(m, st, f),
            FamilyState::Linkages => linkages::read(m, f),
        };
        let (engine, analysis) = value.unwrap_or((f64::NAN, None));
        Reading {
            t: f.cur.time,
            engine,
            analysis: analysis.filter(|a| a.is_finite() && m.inapplicable.is_none()),
        }
    }

    /// For a period: the general method's period and the one-body closed form's
    /// (`periods::State`), when both were found.
    pub fn period_methods(&self) -> Option<(f64, f64)> {
        match &self.state {
            FamilyState::Periods(st) => Some((st.linearized?, st.closed_form?)),
            _ => None,
        }
    }

    /// A motion or force quantity's value at time t on the reference trajectory, or why there
    /// is none.
    pub fn reference_value(&self, t: f64) -> Result<f64, String> {
        match &self.state {
            FamilyState::Motion(st) => motion::reference_value(&self.common, st, t),
            FamilyState::Forces(st) => {
                reference_forces::reference_value(&self.common, st.contact_seen.as_ref(), t)
            }
            _ => Err(format!(
                "{:?} is not read on the reference trajectory",
                self.common.q
            )),
        }
    }
}
