//! The state just before a pair's first impact, from the level's start in closed form where the
//! bodies have flown free under gravity alone since it.
//!
//! The impact solution (`impact_solution`, IM-9 to IM-14) carries the engine's state at the
//! start of the impact's step to the touching instant. Under constant gravity a body's velocity
//! after n symplectic-Euler steps is exact, but its position leads the parabola's by g h t / 2
//! (h the substep, t the time flown), so the engine meets the surface early and slow: a disc
//! dropped 5.8 mm onto an incline at 1/240 s and 4 substeps (tests/newuser, n3_11) lands at
//! 0.3316 for 0.33657 m/s, and an impact solution from that state took 2.95e-2 less energy than
//! the textbook's landing. From the start the flight is a parabola with a steady spin (PK-8),
//! so the pre-impact state is exact and the analysis answers the textbook's question; the
//! engine's value keeps its own landing (its touching instant, point and normal are the
//! engine's, `contact_events`).
//!
//! Only while each body of the pair that moves is dynamic, neither jointed, coupled, sprung,
//! loaded nor damped, touched by no contact that pushed, and its velocity and position are
//! those of its flight from the start to within what the steps explain (a blow or any force
//! rigidlab does not see ends the flight).

use super::level_facts::LevelFacts;
use super::snapshot_reading::carried_forward;
use crate::analysis::touching::flies_free;
use crate::level::BodyKind;
use crate::snapshot::Snapshot;
use std::sync::Arc;

/// The pair's flight from the level's start, while it lasts.
#[derive(Debug, Clone, Default)]
pub(super) struct FlightFromStart {
    /// The level's start, while every body of the pair has flown free since it.
    start: Option<Arc<Snapshot>>,
    /// The flight has ended (or never began at step 0): never taken up again.
    ended: bool,
}

impl FlightFromStart {
    /// Follows the flight to `s`: keeps the start while the pair (`body`, `other`) still flies
    /// free in it. An impact with anything unnamed (`other` None) is not followed.
    pub fn follow(&mut self, s: &Arc<Snapshot>, pair: (usize, Option<usize>), facts: &LevelFacts) {
        if self.ended {
            return;
        }
        let Some(other) = pair.1 else {
            self.end();
            return;
        };
        if self.start.is_none() {
            if s.step != 0 {
                self.end();
                return;
            }
            self.start = Some(Arc::clone(s));
        }
        let free = self
            .start
            .as_ref()
            .is_some_and(|start| [pair.0, other].iter().all(|&i| flown(start, s, i, facts)));
        if !free {
            self.end();
        }
    }

    fn end(&mut self) {
        self.start = None;
        self.ended = true;
    }

    /// `pre` with the pair's moving bodies where their flight from the start puts them at
    /// `pre`'s time; None once the flight has ended.
    pub fn exact(&self, pre: &Snapshot, pair: (usize, Option<usize>)) -> Option<Snapshot> {
        let start = self.start.as_ref()?;
        let other = pair.1?;
        let mut exact = pre.clone();
        for i in [pair.0, other] {
            if start.bodies[i].kind == BodyKind::Dynamic {
                exact.bodies[i] =
                    carried_forward(&start.bodies[i], pre.time - start.time, start.gravity);
            }
        }
        Some(exact)
    }
}

/// Whether body `i` has flown from `start` to `s` under gravity alone: fixed, or dynamic and
/// free of joints, couplings, springs, loads, damping and pushing contacts in `s`, with its
/// velocity and spin the flight's (to f32's rounding of the sum of the steps) and its mass
/// center within the steps' lead, g dt t, of the parabola's.
fn flown(start: &Snapshot, s: &Snapshot, i: usize, facts: &LevelFacts) -> bool {
    let b = &s.bodies[i];
    match b.kind {
        BodyKind::Fixed => return true,
        BodyKind::Kinematic => return false,
        BodyKind::Dynamic => {}
    }
    let held = !flies_free(s, i)
        || s.springs
            .iter()
            .any(|sp| sp.body1 == i || sp.body2 == Some(i))
        || s.loads.iter().any(|l| l.body == i)
        || facts.bodies.get(i).is_none_or(|x| x.damped)
        || s.contacts
            .iter()
            .any(|c| (c.body1 == i || c.body2 == i) && c.pushes());
    if held {
        return false;
    }
    let t = s.time - start.time;
    let flight = carried_forward(&start.bodies[i], t, start.gravity);
    let g = s.gravity.length();
    // f32 sums n steps' increments: relative rounding up to about 1e-6 a step; a blow or an
    // unseen force changes the velocity by far more.
    let speed_scale = flight.velocity.length() + g * t + 1e-3;
    let velocity_ok = (b.velocity - flight.velocity).length() <= 1e-4 * speed_scale;
    let spin_ok = (b.omega - flight.omega).abs() <= 1e-4 * (flight.omega.abs() + 1e-3);
    let lead_ok = (b.com - flight.com).length() <= g * s.dt.max(0.0) * t + 1e-5;
    velocity_ok && spin_ok && lead_ok
}
