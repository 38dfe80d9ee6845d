//! [`QuestionProbe`]: one question watching a run, deciding when its quantity is read (the
//! question's `at`: a time, the end, an extreme, a crossing, a contact event, a blow) and
//! turning the reading into a [`QuestionResult`].

use super::contact_events::{PairEvent, PairTracker};
use super::dispatch::FamilyMeter;
use super::impact_solution::{Blow, Impact, NO_IMPACT};
use super::instants::{Extreme, Slip};
use super::leaving::{self, Leaving};
use super::level_facts::LevelFacts;
use super::result::QuestionResult;
use super::sample::{Occasion, Reading, Sample};
use crate::level::{Level, Quantity, QuestionDef, When};
use crate::snapshot::Snapshot;
use std::collections::VecDeque;
use std::sync::Arc;

/// Reads one question's quantity from every snapshot.
#[derive(Clone)]
pub struct QuestionProbe {
    def: QuestionDef,
    facts: Arc<LevelFacts>,
    meter: FamilyMeter,
    /// The signal a crossing waits for.
    trigger: Option<FamilyMeter>,
    /// The pair whose contact the question waits for.
    pair: Option<PairTracker>,
    /// The extreme (`MaxOf`, `MinOf`) or the slip event (`SlipEnds`, `SlipStarts`) waited for.
    extreme: Option<Extreme>,
    slip: Option<Slip>,
    /// The pair `Leaves` waits for.
    leaving: Option<Leaving>,
    /// The snapshots the next samples still need (their averaging windows).
    hist: VecDeque<Arc<Snapshot>>,
    last: Option<Reading>,
    last_signal: Option<f64>,
    value: Option<Reading>,
    /// A contact-end reading waiting for the contact to stay quiet.
    pending: Option<Reading>,
    done: bool,
    note: String,
    /// Averaging window of the quantity, s, and its half-width in steps.
    window: f64,
    lag: usize,
    /// Step number of the next sample to process.
    next_step: u64,
}

impl QuestionProbe {
    /// A probe for one of the level's questions (it reads the level's declared restitution,
    /// friction and joints for its analyses).
    pub fn for_level(level: &Level, def: &QuestionDef) -> Self {
        Self::sharing(Arc::new(LevelFacts::of(level)), def)
    }

    /// A probe that shares the level's facts with the run's other questions (`runner::Observers`
    /// builds them once: a copy per question is a copy of every body per question).
    pub fn sharing(facts: Arc<LevelFacts>, def: &QuestionDef) -> Self {
        let trigger = match &def.at {
            When::Angle { body, .. } => Some(FamilyMeter::new(
                &Quantity::Angle(body.clone()),
                facts.clone(),
            )),
            When::Crossing { of, .. } | When::MaxOf { of, .. } | When::MinOf { of, .. } => {
                Some(FamilyMeter::new(of, facts.clone()))
            }
            _ => None,
        };
        let extreme = match &def.at {
            When::MaxOf { .. } => Some(Extreme::new(true)),
            When::MinOf { .. } => Some(Extreme::new(false)),
            _ => None,
        };
        let slip = match &def.at {
            When::SlipEnds { body, other, after } => Some(Slip::new(body, other, true, *after)),
            When::SlipStarts { body, other, after } => Some(Slip::new(body, other, false, *after)),
            _ => None,
        };
        let leaving = match &def.at {
            When::Leaves { body, other, after } => Some(Leaving::new(body, other, *after)),
            _ => None,
        };
        let pair = match &def.at {
            When::FirstContact { body, other } | When::ContactEnds { body, other } => {
                Some(PairTracker::new(body, other.as_deref()))
            }
            _ => None,
        };
        let mut meter = FamilyMeter::new(&def.quantity, facts.clone());
        meter.common.configuration_event = !matches!(def.at, When::Time(_) | When::End);
        meter.common.impact_instant = matches!(
            def.at,
            When::FirstContact { .. } | When::ContactEnds { .. } | When::AfterEvent(_)
        );
        QuestionProbe {
            def: def.clone(),
            meter,
            facts,
            trigger,
            pair,
            extreme,
            slip,
            leaving,
            hist: VecDeque::new(),
            last: None,
            last_signal: None,
            value: None,
            pending: None,
            done: false,
            note: String::new(),
            window: def.quantity.averaging_window(),
            lag: 1,
            next_step: 0,
        }
    }

    pub fn id(&self) -> &str {
        &self.def.id
    }

    /// For a period: the general method's value (the linearized equations of the whole scene,
    /// PL-14) and the one-body closed form's, when the closed form's assumptions hold; the
    /// closed form is a cross-check only (tests hold the two together). None otherwise.
    pub fn closed_form_cross_check(&self) -> Option<(f64, f64)> {
        self.meter.period_methods()
    }

    /// Whether the question has been read for good (later snapshots change nothing).
    pub fn is_done(&self) -> bool {
        self.done
    }

    /// Observes a snapshot of its own (the window's single-question use).
    pub fn observe(&mut self, s: &Snapshot) {
        let own = if s.is_initial() {
            initial_in_f64(s)
        } else {
            s.clone()
        };
        self.observe_shared(&Arc::new(own));
    }

    /// Observes a snapshot shared with the run's other questions; the initial one must have
    /// been passed through [`initial_in_f64`].
    pub fn observe_shared(&mut self, s: &Arc<Snapshot>) {
        if self.done {
            // Read once, the question is settled (nothing after its moment changes its result):
            // it keeps no history and does no work for the rest of the run.
            self.hist.clear();
            return;
        }
        if s.step == 1 {
            // The averaging window in steps, each side.
            self.lag = ((0.5 * self.window / s.dt).round() as usize).max(1);
        }
        self.hist.push_back(Arc::clone(s));
        while self.ready() {
            self.process_next();
        }
    }

    /// Whether the next sample has its window's snapshots.
    fn ready(&self) -> bool {
        self.hist
            .back()
            .is_some_and(|b| b.step >= self.next_step + self.lag as u64 && b.step > self.next_step)
    }

    /// Processes the next unprocessed sample and drops the history it no longer needs.
    fn process_next(&mut self) {
        let Some(k) = self.hist.iter().position(|h| h.step == self.next_step) else {
            return;
        };
        self.process(k);
        self.next_step += 1;
        let keep = self.lag.max(2);
        while self.hist.len() > keep + 1
            && self
                .hist
                .front()
                .is_some_and(|f| f.step + (keep as u64) < self.next_step)
        {
            self.hist.pop_front();
        }
    }

    /// Processes the sample at `hist[k]`.
    fn process(&mut self, k: usize) {
        let mut hist = std::mem::take(&mut self.hist);
        hist.make_contiguous();
        let all = hist.as_slices().0;
        let lo = k.saturating_sub(self.lag);
        let hi = (k + self.lag).min(all.len() - 1);
        let sample = Sample {
            prev: k.checked_sub(1).map(|p| &all[p]),
            cur: &all[k],
            next: all.get(k + 1),
            window: if self.lag > 1 {
                &all[lo..=hi]
            } else {
                &all[k..=k]
            },
        };
        self.meter.advance(&sample);
        if let Some(t) = &mut self.trigger {
            t.advance(&sample);
        }
        let event = match &mut self.pair {
            Some(p) => p.update(&sample, &self.facts),
            None => None,
        };
        if !self.done {
            self.read_if_due(&sample, event, all, k);
        }
        self.hist = hist;
    }

    /// Reads the quantity when the sample is the moment the question's `at` names (`all[k]` is
    /// the sample, `event` what the question's pair did at it).
    // A match over every instant a question can be read at (`When`), one arm per instant: each
    // arm is that instant's whole rule, read in one place beside the others. Not per family: the
    // dispatcher hands the reading to the family, the instant is the probe's alone.
    #[allow(clippy::too_many_lines)]
    fn read_if_due(
        &mut self,
        sample: &Sample,
        event: Option<PairEvent>,
        all: &[Arc<Snapshot>],
        k: usize,
    ) {
        let t = sample.cur.time;
        match self.def.at.clone() {
            When::End => self.value = Some(self.meter.read(sample, Occasion::Plain)),
            When::Time(at) => {
                let r = self.meter.read(sample, Occasion::Plain);
                if t >= at {
                    self.value = Some(match self.last {
                        Some(l) if l.t < at && t > l.t => {
                            self.between(sample, l, r, (at - l.t) / (t - l.t))
                        }
                        _ => r,
                    });
                    self.done = true;
                } else {
                    self.value = Some(r);
                }
                self.last = Some(r);
            }
            When::Max(from) | When::Min(from) => {
                let r = self.meter.read(sample, Occasion::Plain);
                let max = matches!(self.def.at, When::Max(_));
                let better = self.value.is_none_or(|v| {
                    if max {
                        r.engine > v.engine
                    } else {
                        r.engine < v.engine
                    }
                });
                if t >= from && better && r.engine.is_finite() {
                    self.value = Some(r);
                }
            }
            When::MaxOf { after, .. } | When::MinOf { after, .. } => {
                let r = self.meter.read(sample, Occasion::Plain);
                let sig = self
                    .trigger
                    .as_ref()
                    .map_or(f64::NAN, |m| m.read(sample, Occasion::Plain).engine);
                if t >= after {
                    if let Some(best) = self.extreme.as_mut().and_then(|e| e.feed(sig, r)) {
                        self.value = Some(best);
                    }
                }
            }
            When::SlipEnds { .. } | When::SlipStarts { .. } => {
                let r = self.meter.read(sample, Occasion::Plain);
                let found = match self.slip.as_mut() {
                    Some(slip) => slip.feed(&self.facts, sample.cur, r),
                    None => None,
                };
                if let Some(found) = found {
                    let mut at = Reading::lerp(found.from, r, found.fraction);
                    if matches!(self.def.at, When::SlipEnds { .. }) {
                        self.slide_to_roll(sample.cur, &mut at);
                    }
                    self.value = Some(at);
                    self.done = true;
                }
            }
            When::Angle { angle: value, .. } | When::Crossing { value, .. } => {
                let after = match &self.def.at {
                    When::Crossing { after, .. } => *after,
                    _ => 0.0,
                };
                let r = self.meter.read(sample, Occasion::Plain);
                let sig = self
                    .trigger
                    .as_ref()
                    .map_or(f64::NAN, |m| m.read(sample, Occasion::Plain).engine - value);
                if let (Some(l), Some(s0)) = (self.last, self.last_signal) {
                    let crossed = l.t >= after
                        && s0.is_finite()
                        && sig.is_finite()
                        && s0 != 0.0
                        && (sig == 0.0 || (s0 > 0.0) != (sig > 0.0));
                    if crossed {
                        // Where the step had an impact, the crossing is found on the path the
                        // step's start state takes without it (the end state is past it).
                        let f = self
                            .crossing_before_contact(sample, value, s0)
                            .unwrap_or(s0 / (s0 - sig));
                        self.value = Some(self.between(sample, l, r, f));
                        self.done = true;
                    } else if l.t >= after && s0.is_finite() && s0 != 0.0 {
                        // An impact met a hair before the value (rigidlab's impact cuts leave
                        // the bodies 2 um apart): the step's end stops short of it, and the
                        // approach reaches it at the touch.
                        if let Some(f) = self.crossing_by_touch(sample, value, s0) {
                            let prev = sample.prev.expect("a touch has a step before it");
                            let dt = sample.cur.time - prev.time;
                            self.value = Some(read_carried(&self.meter, prev, f * dt));
                            self.done = true;
                        }
                    }
                }
                self.last = Some(r);
                self.last_signal = Some(sig);
            }
            When::FirstContact { .. } => {
                let r = self.meter.read(sample, Occasion::Plain);
                if event == Some(PairEvent::Touch) {
                    if let Some(l) = self.last {
                        // The engine's value the step before the touch; the analysis is the
                        // impact solution's state at the touching instant.
                        let imp = self.pair.as_ref().and_then(|p| p.impact.clone());
                        let analysis = match (&imp, sample.prev) {
                            (Some(imp), Some(prev)) => {
                                let before = Sample {
                                    prev: k.checked_sub(2).map(|p| &all[p]),
                                    cur: prev,
                                    next: Some(sample.cur),
                                    window: &all[k - 1..k],
                                };
                                self.meter.read(&before, Occasion::PreImpact(imp)).analysis
                            }
                            _ => None,
                        };
                        self.value = Some(Reading { analysis, ..l });
                    } else {
                        self.note =
                            "the body touches at the start: there is no pre-contact state".into();
                    }
                    self.done = true;
                }
                self.last = Some(r);
            }
            When::ContactEnds { .. } => match event {
                Some(PairEvent::Quiet) => {
                    let pair = self.pair.as_ref();
                    let imp = pair.and_then(|p| p.impact.clone());
                    let lasting = pair.and_then(|p| p.not_impulsive());
                    let occ = match (&imp, lasting) {
                        (Some(i), None) => {
                            self.meter.common.inapplicable = self.solution_left_out(
                                sample,
                                Occasion::PostImpact(i),
                                &i.left_out,
                            );
                            Occasion::PostImpact(i)
                        }
                        (Some(_), Some(why)) => {
                            self.note = why;
                            Occasion::Plain
                        }
                        (None, _) => {
                            self.note = NO_IMPACT.into();
                            Occasion::Plain
                        }
                    };
                    self.pending = Some(self.meter.read(sample, occ));
                }
                Some(PairEvent::Resumed) => self.pending = None,
                Some(PairEvent::Released) => {
                    self.value = self.pending.take();
                    self.done = true;
                }
                _ => {}
            },
            When::Leaves { body, other, .. } => {
                let r = self.meter.read(sample, Occasion::Plain);
                let found = match self.leaving.as_mut() {
                    Some(l) => l.feed(&self.facts, &all[k], r),
                    None => None,
                };
                if let Some(left) = found {
                    let mut at = Reading::lerp(left.from, left.to, left.fraction);
                    self.leaving_analysis((&body, &other), &mut at);
                    self.value = Some(at);
                    self.done = true;
                }
            }
            When::FirstStep => {
                if sample.cur.step == 1 {
                    self.read_after_blow(sample);
                }
            }
            When::AfterEvent(name) => {
                if sample.cur.impulses.iter().any(|e| e.name == name) {
                    self.read_after_blow(sample);
                }
            }
        }
    }

    /// At `SlipEnds`, the time and the speed of the slide-to-roll closed form as the analysis of
    /// `Time` and `Speed`, or why it does not apply.
    fn slide_to_roll(&mut self, s: &Snapshot, at: &mut Reading) {
        let Some(slip) = &self.slip else { return };
        let body_speed = |b: &str| matches!(&self.def.quantity, Quantity::Speed(x) if x == b);
        let wanted = match (&self.def.quantity, &self.def.at) {
            (Quantity::Time, _) => Some(0),
            (_, When::SlipEnds { body, .. }) if body_speed(body) => Some(1),
            _ => None,
        };
        let Some(which) = wanted else { return };
        match slip.closed_form(&self.facts, s) {
            Ok((t, v)) => at.analysis = Some(if which == 0 { t } else { v }),
            Err(why) => self.meter.common.inapplicable = Some(why),
        }
    }

    /// At `Leaves`, the textbook's leaving point as the analysis of `PolarAngle` about the arc's
    /// centre and of `Speed` (sim-free: from the state the body touched in), or why it does not
    /// apply; other quantities keep their own.
    fn leaving_analysis(&mut self, pair: (&str, &str), at: &mut Reading) {
        let Some(want) = leaving::wanted(&self.facts, &self.def.quantity, pair) else {
            return;
        };
        let start = self.leaving.as_ref().and_then(|l| l.start.clone());
        let found = want.and_then(|w| {
            let s = start.ok_or("no leaving analysis: the body never touched the other")?;
            let b = self.facts.body_index(&s, pair.0).ok_or("no body")?;
            let o = self.facts.body_index(&s, pair.1).ok_or("no body")?;
            leaving::leaving_analysis(&self.facts, &s, (b, o), w)
        });
        match found {
            Ok(v) => at.analysis = Some(v),
            Err(why) => {
                at.analysis = None;
                self.meter.common.inapplicable = Some(why);
            }
        }
    }

    /// The reading a fraction `f` into the step from the last reading `l` to this sample's `r`:
    /// interpolated, unless a contact began pushing in the step (an impact), whose end state
    /// must not leak into an instant before it. Then the state at the start of the step is
    /// carried to the instant (`carried_to`) and read there.
    fn between(&self, sample: &Sample, l: Reading, r: Reading, f: f64) -> Reading {
        let Some(prev) = sample.prev else {
            return Reading::lerp(l, r, f);
        };
        let Some(t_c) = contact_began(&self.facts, prev, sample.cur) else {
            return Reading::lerp(l, r, f);
        };
        let tau = f * (sample.cur.time - prev.time);
        // After the touch, the step's end state (the first after the impact); at the touch
        // (to round-off), the approach's.
        if prev.time + tau > t_c + TOUCH_ROUND_OFF * (sample.cur.time - prev.time) {
            return r;
        }
        read_carried(&self.meter, prev, tau)
    }

    /// In a step where a contact began, the fraction of the step at which the trigger quantity
    /// reaches `value` on the path carried from the step's start (`carried_to`), found by
    /// bisection; None when no contact began or that path does not reach it within the step.
    fn crossing_before_contact(&self, sample: &Sample, value: f64, s0: f64) -> Option<f64> {
        let prev = sample.prev?;
        let trigger = self.trigger.as_ref()?;
        let t_c = contact_began(&self.facts, prev, sample.cur)?;
        let dt = sample.cur.time - prev.time;
        let signal = |f: f64| read_carried(trigger, prev, f * dt).engine - value;
        let end = signal(1.0);
        if !end.is_finite() || (end > 0.0) == (s0 > 0.0) && end != 0.0 {
            return None;
        }
        let (mut a, mut b) = (0.0, 1.0);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if (signal(m) > 0.0) == (s0 > 0.0) {
                a = m;
            } else {
                b = m;
            }
        }
        // Only a crossing before the touch (or at it, to round-off) is one on this path. The
        // touch is found on the shapes as the engine holds them (f32: a 0.05 m radius is
        // 0.05 + 7e-10), the value is the level's: at the touching distance the path may reach
        // it a hair after the touch (a ball meeting a box at RelativeDistance r + h/2 never
        // did, n14_21); a path within length round-off of the value at the touch crosses there.
        let f = 0.5 * (a + b);
        if prev.time + f * dt <= t_c + TOUCH_ROUND_OFF * dt {
            return Some(f);
        }
        let f_c = (t_c - prev.time) / dt;
        let at_touch = signal(f_c);
        ((0.0..=1.0).contains(&f_c) && at_touch.abs() <= touch_length_round_off(value, s0))
            .then_some(f_c)
    }

    /// In a step where a contact began and the step's end has not reached `value` (the impact
    /// was met just before it), the fraction of the step at which the path carried from the
    /// step's start reaches `value` by the touching instant (at the touch itself within
    /// round-off: a crossing at the touching height), by bisection up to the touch; None
    /// otherwise. Measured on a disc dropped onto a floor (e = 0), asked its v_y at the crossing
    /// of its touching height: it read the landing's 0 at 2x, 4x substeps and dt/2 before.
    fn crossing_by_touch(&self, sample: &Sample, value: f64, s0: f64) -> Option<f64> {
        let prev = sample.prev?;
        let trigger = self.trigger.as_ref()?;
        let t_c = contact_began(&self.facts, prev, sample.cur)?;
        let dt = sample.cur.time - prev.time;
        let f_c = (t_c - prev.time) / dt;
        if !(0.0..=2.0).contains(&f_c) {
            return None;
        }
        let signal = |f: f64| read_carried(trigger, prev, f * dt).engine - value;
        let at_touch = signal(f_c);
        let near = touch_length_round_off(value, s0);
        let reached =
            at_touch.is_finite() && ((at_touch > 0.0) != (s0 > 0.0) || at_touch.abs() <= near);
        if !reached {
            return None;
        }
        let (mut a, mut b) = (0.0, f_c);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            let x = signal(m);
            if (x > 0.0) == (s0 > 0.0) && x.abs() > near {
                a = m;
            } else {
                b = m;
            }
        }
        Some(b)
    }

    /// Reads the quantity right after the impulse events of the sample's step, with the blow's
    /// impulse-momentum solution as the analysis.
    fn read_after_blow(&mut self, sample: &Sample) {
        let blow = sample.prev.map(|p| Blow::solve(&self.facts, p, sample.cur));
        let occ = match &blow {
            Some(b) => {
                let occ = Occasion::AfterBlow(b);
                self.meter.common.inapplicable = self.solution_left_out(sample, occ, &b.left_out);
                occ
            }
            None => Occasion::Plain,
        };
        self.value = Some(self.meter.read(sample, occ));
        self.done = true;
    }

    /// The meter's reason for no analysis after an impact or blow whose solution left a contact
    /// out (`left_out`): the reason, when the quantity's analysis is the solution's (it differs
    /// from the analysis without the solution: a velocity, a kinetic energy, a pin impulse);
    /// else the meter's own reason, unchanged (a quantity whose analysis does not read the
    /// solution keeps it).
    fn solution_left_out(
        &self,
        sample: &Sample,
        occ: Occasion,
        left_out: &Option<String>,
    ) -> Option<String> {
        let own = self.meter.common.inapplicable.clone();
        let Some(why) = left_out else { return own };
        if own.is_some() {
            return own;
        }
        let solved = self.meter.read(sample, occ).analysis;
        let plain = self.meter.read(sample, Occasion::Plain).analysis;
        (solved.is_some() && solved != plain).then(|| why.clone())
    }

    /// The question's result, with the grade of the student's answer when there is one.
    pub fn finish(mut self, student: Option<f64>) -> QuestionResult {
        while self.hist.iter().any(|h| h.step >= self.next_step) {
            self.process_next();
        }
        // A contact that went quiet before the run ended counts as ended.
        if !self.done {
            if let Some(p) = self.pending.take() {
                self.value = Some(p);
            }
        }
        // A body parting from the other as the run ends counts as leaving it.
        if let (When::Leaves { body, other, .. }, false) = (self.def.at.clone(), self.done) {
            if let Some(left) = self.leaving.as_mut().and_then(Leaving::at_run_end) {
                let mut at = Reading::lerp(left.from, left.to, left.fraction);
                self.leaving_analysis((&body, &other), &mut at);
                self.value = Some(at);
            }
        }
        if self.value.is_none() && self.note.is_empty() {
            self.note = match &self.def.at {
                When::End | When::Time(_) | When::Max(_) | When::Min(_) => "no sample".into(),
                w => format!("the event {w:?} did not happen in the run"),
            };
        }
        let mut r = self.value.unwrap_or(Reading::MISSING);
        if r.engine.is_nan() && self.note.is_empty() {
            self.note = match (self.meter.why_missing(), &self.def.at) {
                (Some(why), _) => why,
                (None, When::Time(t)) if *t <= 0.0 => "the quantity could not be read at t = 0: the engine reports joint reactions and contact forces from its first step on (ask at a later time, or at an event)".into(),
                _ => "the quantity could not be read (too few oscillations, no contact, or a missing item)".into(),
            };
        }
        // Where the textbook formula's assumptions fail, the general method: the reference
        // trajectory, when the scene fits it.
        let source = self.reference_analysis(&mut r);
        // A reading taken before the analysis stopped applying (a contact that stuck after the
        // sample) keeps its analysis.
        if let Some(why) = &self.meter.common.inapplicable {
            let said = if source.is_empty() {
                r.analysis
                    .is_none()
                    .then(|| format!("analysis not applicable: {why}; graded on the engine alone"))
            } else {
                Some(format!(
                    "the closed form does not apply ({why}): the analysis is the reference trajectory's"
                ))
            };
            if let Some(said) = said {
                self.note = if self.note.is_empty() {
                    said
                } else {
                    format!("{}; {said}", self.note)
                };
            }
        }
        let mut result = QuestionResult::new(&self.def, r, self.note, student);
        result.analysis_source = source;
        result
    }

    /// A motion or force quantity read at a time that has no textbook formula, or whose
    /// formula's assumptions fail, gets the reference trajectory's value as its analysis
    /// (`analysis::reference`); where the scene is outside the reference, the note says why.
    /// Returns the analysis's source label ("" when not used).
    fn reference_analysis(&mut self, r: &mut Reading) -> String {
        let m = &self.meter.common;
        if r.analysis.is_some()
            || m.configuration_event
            || !super::level_facts::served_by_reference(&m.q)
            || !r.engine.is_finite()
        {
            return String::new();
        }
        match self.meter.reference_value(r.t) {
            Ok(v) => {
                r.analysis = Some(v);
                crate::analysis::reference::LABEL.to_string()
            }
            Err(why) => {
                let said = format!("reference trajectory not applicable: {why}");
                self.note = if self.note.is_empty() {
                    said
                } else {
                    format!("{}; {said}", self.note)
                };
                String::new()
            }
        }
    }
}

/// When a contact that did not push in the step before `cur` first touched in the step that
/// led to it (an impact inside the step): the earliest such touch, as the impact solution finds
/// it from the step's start state (`Impact::find`). None when no contact began, or none of those
/// that began was an approach.
fn contact_began(facts: &LevelFacts, prev: &Snapshot, cur: &Snapshot) -> Option<f64> {
    let pushed_before = |a: usize, b: usize| {
        prev.contacts
            .iter()
            .any(|c| c.pushes() && ((c.body1, c.body2) == (a, b) || (c.body1, c.body2) == (b, a)))
    };
    cur.contacts
        .iter()
        .filter(|c| c.pushes() && !pushed_before(c.body1, c.body2))
        .filter_map(|c| Impact::find(facts, prev, cur, c.body1, Some(c.body2)))
        .map(|imp| imp.t_c)
        .min_by(f64::total_cmp)
}

/// A crossing this fraction of a step after the touching instant (or less) is at the touch:
/// the touch and the crossing of a touching height are found by different roots and agree to
/// round-off only.
const TOUCH_ROUND_OFF: f64 = 1e-9;

/// How near a crossing's value the path carried to a touch must come for the crossing to be
/// at the touch: the engine's shapes in f32 round lengths at 6e-8 relative (a box's half height
/// plus a ball's radius), so 1e-6 of the value and of the step's start distance from it
/// (1e-7 m at a 0.1 m touching distance, 3e-8 s at 3 m/s).
fn touch_length_round_off(value: f64, s0: f64) -> f64 {
    1e-6 * (value.abs() + s0.abs())
}

/// `meter`'s reading of the snapshot `prev` carried `tau` seconds on ([`carried_to`]).
fn read_carried(meter: &FamilyMeter, prev: &Arc<Snapshot>, tau: f64) -> Reading {
    let at = Arc::new(carried_to(prev, tau));
    let window = [Arc::clone(prev), Arc::clone(&at)];
    let carried = Sample {
        prev: Some(prev),
        cur: &at,
        next: None,
        window: &window,
    };
    meter.read(&carried, Occasion::Plain)
}

/// `s` carried `tau` seconds on, as its state says the bodies move before any new contact:
/// bodies flying free (no joint, coupling, or contact that pushed in the step before) under
/// gravity, other moving bodies at their velocity.
fn carried_to(s: &Snapshot, tau: f64) -> Snapshot {
    use crate::analysis::touching::{flies_free, free_acceleration};
    use crate::snapshot::BodyKind;
    let mut out = s.clone();
    for (i, b) in out.bodies.iter_mut().enumerate() {
        if b.kind == BodyKind::Fixed {
            continue;
        }
        let held = s
            .contacts
            .iter()
            .any(|c| (c.body1 == i || c.body2 == i) && c.pushes());
        let a = if flies_free(s, i) && !held {
            free_acceleration(s, i)
        } else {
            glam::DVec2::ZERO
        };
        *b = super::snapshot_reading::carried_forward(b, tau, a);
    }
    out.time = s.time + tau;
    out
}

/// The initial snapshot as the questions read it. Its mass centers are rapier's pose times
/// local_com in f32, where every later snapshot's are computed in f64: recomputed in f64, so
/// that the changes since the start (gravity's work, the pendulum's amplitude) carry no f32
/// round-off.
pub fn initial_in_f64(s: &Snapshot) -> Snapshot {
    let mut first = s.clone();
    for b0 in first.bodies.iter_mut() {
        b0.com = b0.world_point(b0.local_com);
    }
    first
}
