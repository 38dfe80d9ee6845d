//! Which of a step's contacts rest (`Pass::contact`): a contact whose pair of bodies pushed the
//! step before, and not impulsively more now (`impact::pushes_impulsively`), is no impact, and its
//! normal impulse works through the bodies' displacement (`energy::work_of_contact_impulse`).
//!
//! Answered per contact once a step from two sorted lists of pairs: the pairs a contact pushed
//! in this step and in the step before, each with the pair's normal impulse (its manifolds'
//! summed in the snapshot's order). This step's pairs are matched to the step before's by one
//! merge of the two lists and to their contacts by position, instead of two binary searches per
//! contact: a tenth of the frame pass on the 100-body bench scene (benches/analysis.rs).

use super::super::impact::pushes_impulsively;
use crate::snapshot::ContactState;

/// No pair (a contact that did not push).
const NONE: u32 = u32::MAX;

/// The pushed pairs of the last two steps and, per contact of the last, whether it rests.
#[derive(Debug, Clone, Default)]
pub(super) struct Pushed {
    /// The pairs (lower body index in the high half, higher in the low) a contact pushed in the
    /// last step, ascending, with the pair's normal impulse, N s; and in the step before.
    now: Vec<(u64, f64)>,
    before: Vec<(u64, f64)>,
    /// Per pair of `now`, its impulse the step before, if it pushed then.
    now_before: Vec<Option<f64>>,
    /// Per contact of the last step: whether it rests.
    resting: Vec<bool>,
    /// Scratch: the pushing contacts' indices by pair (`order_pushing`), their sort keys, and
    /// per contact its pair's place in `now` (`NONE` if it did not push).
    order: Vec<u32>,
    keys: Vec<u64>,
    pair_of: Vec<u32>,
}

/// A pair of bodies as one key, lower index first (ascending keys: ascending (lower, higher)).
fn pair_key(a: usize, b: usize) -> u64 {
    ((a.min(b) as u64) << 32) | b.max(a) as u64
}

impl Pushed {
    /// Reads the step's contacts, between `bodies` bodies; `stepped` false (the initial
    /// state) forgets the step before.
    pub(super) fn observe(&mut self, contacts: &[ContactState], bodies: usize, stepped: bool) {
        std::mem::swap(&mut self.before, &mut self.now);
        if !stepped {
            self.before.clear();
        }
        self.order_pushing(contacts, bodies);
        // A pair's manifolds as one entry, their impulses summed in the snapshot's order.
        self.now.clear();
        self.pair_of.clear();
        self.pair_of.resize(contacts.len(), NONE);
        for &k in &self.order {
            let c = &contacts[k as usize];
            let pair = pair_key(c.body1, c.body2);
            let normal: f64 = c.points.iter().map(|p| p.normal_impulse).sum();
            match self.now.last_mut() {
                Some(last) if last.0 == pair => last.1 += normal,
                _ => self.now.push((pair, normal)),
            }
            self.pair_of[k as usize] = (self.now.len() - 1) as u32;
        }
        // Each pair's impulse the step before, by one merge of the two ascending lists.
        self.now_before.clear();
        let mut j = 0;
        for &(pair, _) in &self.now {
            while j < self.before.len() && self.before[j].0 < pair {
                j += 1;
            }
            let before = self.before.get(j).filter(|b| b.0 == pair).map(|b| b.1);
            self.now_before.push(before);
        }
        let impulse = |list: &[(u64, f64)], key| {
            let k = list.binary_search_by_key(&key, |&(p, _)| p);
            k.ok().map(|k| list[k].1)
        };
        self.resting.clear();
        self.resting
            .extend(contacts.iter().enumerate().map(|(k, c)| {
                let (now, before) = match self.pair_of[k] {
                    // A contact that did not push: its pair's other manifolds may have (rare).
                    NONE => {
                        let key = pair_key(c.body1, c.body2);
                        (impulse(&self.now, key), impulse(&self.before, key))
                    }
                    n => (Some(self.now[n as usize].1), self.now_before[n as usize]),
                };
                before.is_some_and(|before| !pushes_impulsively(now.unwrap_or(0.0), before))
            }));
    }

    /// The pushing contacts' indices into `order`, by pair and, within a pair, in the
    /// snapshot's order: sorted as one integer each, (lower body, higher body, contact) packed
    /// into 64 bits where they fit (every scene short of a million bodies), else 128.
    fn order_pushing(&mut self, contacts: &[ContactState], bodies: usize) {
        let bits = |n: usize| usize::BITS - n.leading_zeros();
        let (bb, kb) = (bits(bodies), bits(contacts.len()));
        let pushing = contacts.iter().enumerate().filter(|(_, c)| c.pushes());
        let parts = pushing.map(|(k, c)| (c.body1.min(c.body2), c.body1.max(c.body2), k));
        self.order.clear();
        if 2 * bb + kb <= 64 {
            let key = |(lo, hi, k): (usize, usize, usize)| {
                ((lo as u64) << (bb + kb)) | ((hi as u64) << kb) | k as u64
            };
            self.keys.clear();
            self.keys.extend(parts.map(key));
            self.keys.sort_unstable();
            let mask = (1u64 << kb) - 1;
            self.order
                .extend(self.keys.iter().map(|&key| (key & mask) as u32));
        } else {
            let key = |(lo, hi, k): (usize, usize, usize)| {
                ((lo as u128) << 96) | ((hi as u128) << 32) | k as u128
            };
            let mut wide: Vec<u128> = parts.map(key).collect();
            wide.sort_unstable();
            self.order.extend(wide.iter().map(|&key| key as u32));
        }
    }

    /// Whether contact k of the last step observed rests.
    pub(super) fn rests(&self, k: usize) -> bool {
        self.resting[k]
    }
}
