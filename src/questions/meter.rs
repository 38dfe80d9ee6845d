//! One quantity followed over a run: what it accumulates from step to step, and its reading at
//! a sample. The meter holds the state; the quantity's family (see
//! [`QuantityFamily`]) owns how that state is advanced and how the quantity is read.

use super::contact_events::PairTracker;
use super::level_facts::LevelFacts;
use super::periods::{Crossings, Extremes};
use super::sample::{Occasion, Reading, Sample};
use super::{forces, impacts, linkages, motion, periods, rolling, work_and_power};
use crate::level::{Quantity, QuantityFamily};
use crate::snapshot::{BodyState, Snapshot};
use glam::DVec2;
use std::sync::Arc;

/// A quantity's value at a sample: the engine's, and the textbook analysis when one applies.
pub(super) type EngineAndAnalysis = (f64, Option<f64>);

/// Evaluates one quantity at every sample, keeping whatever it accumulates over the run.
#[derive(Clone)]
pub(super) struct Meter {
    pub q: Quantity,
    pub facts: Arc<LevelFacts>,
    /// The first snapshot the meter saw (the initial state).
    pub init: Option<Arc<Snapshot>>,
    /// Running sum of the engine's value (works, distance).
    pub engine_sum: f64,
    /// Running sum for the analysis: path work of springs, loads and events on the body
    /// (work-energy analyses), or friction's Coulomb work.
    pub analysis_sum: f64,
    /// Zero crossings of an oscillating velocity (periods).
    pub crossings: Crossings,
    /// Direction of the spring a `SpringPeriod` body oscillates along.
    pub spring_axis: Option<DVec2>,
    /// Periods: the general method's period, from the linearized equations of the whole scene
    /// (PL-14), which is the analysis.
    pub linearized: Option<f64>,
    /// Periods: the one-body closed form's period, where its assumptions hold (a cross-check
    /// of `linearized`, never the analysis).
    pub closed_form: Option<f64>,
    /// `ModePeriod`: per snapshot body, the weights (m dx_G, I_G dtheta) of the mode's
    /// modal rate eta' = phi^T M v, and the support's velocity at t = 0 and acceleration.
    pub modal_weights: Option<Vec<(DVec2, f64)>>,
    pub support_motion: (DVec2, DVec2),
    /// `EquilibriumAngle`: the body's angle at its last two extremes (interpolated), and the
    /// equilibrium angle of its mechanism (PL-14), found once.
    pub swing: Extremes,
    pub equilibrium: Option<f64>,
    /// For `SpringPeriod`: the free body at the spring's other end, when the body's springs all
    /// join it to that one (their relative motion is what vibrates).
    pub spring_partner: Option<usize>,
    /// The pair an impact quantity is about.
    pub pair: Option<PairTracker>,
    /// Highest mass center since the contact went quiet (rebound height), m.
    pub rebound_apex: f64,
    /// `LoadWork`: the first load seen (force, couple, point, body angle) and whether it stayed equal.
    pub first_load: Option<(DVec2, f64, DVec2, f64)>,
    pub load_constant: bool,
    /// `Efficiency`: the input's work since the start (engine), J, and, when the input is a
    /// load, its first (force, couple, point, body angle) and whether it stayed equal.
    pub input_work: f64,
    pub input_load: Option<(DVec2, f64, DVec2, f64)>,
    pub input_constant: bool,
    /// Read at a configuration event (not a fixed time): see `Quantity::KineticEnergy`.
    pub configuration_event: bool,
    /// Read at an impact or a blow (`FirstContact`, `ContactEnds`, `AfterEvent`), whose
    /// analyses are the impulse-momentum solution's.
    pub impact_instant: bool,
    /// Why the quantity's analysis does not apply to this scene (a precondition of its formula
    /// that the scene breaks), set by the family: then the analysis is None and the question is
    /// graded on the engine alone, saying so.
    pub inapplicable: Option<String>,
    /// The first contact that pushed in the run: the start of the step it pushed in, and which
    /// bodies, said for a note. The reference trajectory (`analysis::reference`) models no
    /// contact, so it does not apply to a reading after that.
    pub contact_seen: Option<(f64, String)>,
}

impl Meter {
    /// Body `name`'s index in `s` (`LevelFacts::body_index`: no scan of every name).
    pub fn body_index(&self, s: &Snapshot, name: &str) -> Option<usize> {
        self.facts.body_index(s, name)
    }

    /// Body `name` of `s` with its index.
    pub fn named_body<'a>(&self, s: &'a Snapshot, name: &str) -> Option<(usize, &'a BodyState)> {
        self.facts.named_body(s, name)
    }

    pub fn new(q: &Quantity, facts: Arc<LevelFacts>) -> Self {
        Meter {
            q: q.clone(),
            facts,
            init: None,
            engine_sum: 0.0,
            analysis_sum: 0.0,
            crossings: Crossings::default(),
            spring_axis: None,
            linearized: None,
            closed_form: None,
            modal_weights: None,
            support_motion: (DVec2::ZERO, DVec2::ZERO),
            swing: Extremes::default(),
            equilibrium: None,
            spring_partner: None,
            pair: impacts::pair_tracker(q),
            rebound_apex: f64::NEG_INFINITY,
            first_load: None,
            load_constant: true,
            input_work: 0.0,
            input_load: None,
            input_constant: true,
            configuration_event: true,
            impact_instant: false,
            inapplicable: None,
            contact_seen: None,
        }
    }

    /// Accumulates what the quantity needs from the step that led to the sample.
    pub fn advance(&mut self, f: &Sample) {
        let s = f.cur;
        if self.init.is_none() {
            self.init = Some(Arc::clone(s));
        }
        let pair_event = match &mut self.pair {
            Some(p) => p.update(f, &self.facts),
            None => None,
        };
        if self.q.family() == QuantityFamily::Linkages {
            // From the first sample on: a percussion distance may be read at t = 0.
            linkages::advance(self);
        }
        let Some(prev) = f.prev else {
            return;
        };
        match self.q.family() {
            QuantityFamily::Motion => motion::advance(self, prev, s),
            QuantityFamily::Forces => forces::advance(self, prev, s),
            QuantityFamily::WorkAndPower => work_and_power::advance(self, prev, s),
            QuantityFamily::Periods => periods::advance(self, prev, s),
            QuantityFamily::Impacts => impacts::advance(self, s, pair_event),
            QuantityFamily::Rolling => rolling::advance(self, prev, s),
            QuantityFamily::Linkages => {}
        }
    }

    /// Why the quantity has no engine value, where its family can tell (an impact that never
    /// happened or never ended).
    pub fn why_missing(&self) -> Option<String> {
        match self.q.family() {
            QuantityFamily::Impacts => impacts::why_missing(self),
            QuantityFamily::Periods => periods::why_missing(self),
            _ => None,
        }
    }

    /// The quantity at the sample (NaN when it cannot be read there).
    pub fn read(&self, f: &Sample, occ: Occasion) -> Reading {
        let value = match self.q.family() {
            QuantityFamily::Motion => motion::read(self, f, occ),
            QuantityFamily::Forces => forces::read(self, f, occ),
            QuantityFamily::WorkAndPower => work_and_power::read(self, f, occ),
            QuantityFamily::Periods => periods::read(self, f),
            QuantityFamily::Rolling => rolling::read(self, f),
            QuantityFamily::Impacts => impacts::read(self, f),
            QuantityFamily::Linkages => linkages::read(self, f),
        };
        let (engine, analysis) = value.unwrap_or((f64::NAN, None));
        Reading {
            t: f.cur.time,
            engine,
            analysis: analysis.filter(|a| a.is_finite() && self.inapplicable.is_none()),
        }
    }
}
