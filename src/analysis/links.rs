//! Which contacts and joints touch each body in a snapshot, so that a reading about one body
//! (or a pair) visits only its own: a check on every body of a scene would otherwise scan every
//! contact and joint once per body, O(bodies x contacts) a step (benches/analysis.rs, C).
//! Also `joined_bodies`: the set of bodies joined to some through pairs that act on each other.

use crate::snapshot::Snapshot;

/// Per body, the indices of the contacts and of the joints that touch it, ascending (the
/// snapshot's order, so sums over them add in the same order as a scan of the whole list).
#[derive(Debug, Clone, Default)]
pub struct BodyLinks {
    contacts: Adjacency,
    joints: Adjacency,
    /// Per body: whether a contact pushed it over the step (a positive normal impulse).
    pushed: Vec<bool>,
}

impl BodyLinks {
    /// The links of `snap` (reusing the buffers: no allocation once sized).
    pub fn rebuild(&mut self, snap: &Snapshot) {
        let n = snap.bodies.len();
        self.contacts
            .rebuild(n, snap.contacts.iter().map(|c| (c.body1, c.body2)));
        self.joints
            .rebuild(n, snap.joints.iter().map(|j| (j.body1, j.body2)));
        self.pushed.clear();
        self.pushed.resize(n, false);
        for c in snap.contacts.iter().filter(|c| c.pushes()) {
            for i in [c.body1, c.body2] {
                if let Some(x) = self.pushed.get_mut(i) {
                    *x = true;
                }
            }
        }
    }

    /// Whether a contact pushed body i over the step (a body held up by its floor, not flying
    /// free: `analysis::touching`).
    pub fn pushed(&self, i: usize) -> bool {
        self.pushed.get(i).copied().unwrap_or(false)
    }

    /// The contacts touching body i, ascending.
    pub fn contacts_of(&self, i: usize) -> &[u32] {
        self.contacts.of(i)
    }

    /// The joints touching body i, ascending.
    pub fn joints_of(&self, i: usize) -> &[u32] {
        self.joints.of(i)
    }
}

/// Items touching each body, in compressed rows: body i's are `items[start[i]..start[i + 1]]`.
#[derive(Debug, Clone, Default)]
struct Adjacency {
    start: Vec<u32>,
    items: Vec<u32>,
    /// Scratch while filling: where each body's next item goes.
    next: Vec<u32>,
}

impl Adjacency {
    fn rebuild(&mut self, bodies: usize, pairs: impl Iterator<Item = (usize, usize)> + Clone) {
        self.start.clear();
        self.start.resize(bodies + 1, 0);
        // Each item once per body it touches (twice only for two different bodies).
        for (a, b) in pairs.clone() {
            if a < bodies {
                self.start[a + 1] += 1;
            }
            if b != a && b < bodies {
                self.start[b + 1] += 1;
            }
        }
        // Counts to row starts (start[0] = 0): a running sum.
        let mut sum = 0;
        for x in self.start.iter_mut() {
            sum += *x;
            *x = sum;
        }
        self.items.clear();
        self.items.resize(self.start[bodies] as usize, 0);
        // Fill each body's row in item order.
        self.next.clear();
        self.next.extend_from_slice(&self.start[..bodies]);
        for (k, (a, b)) in pairs.enumerate() {
            if a < bodies {
                self.items[self.next[a] as usize] = k as u32;
                self.next[a] += 1;
            }
            if b != a && b < bodies {
                self.items[self.next[b] as usize] = k as u32;
                self.next[b] += 1;
            }
        }
    }

    fn of(&self, i: usize) -> &[u32] {
        match (self.start.get(i), self.start.get(i + 1)) {
            (Some(&a), Some(&b)) => &self.items[a as usize..b as usize],
            _ => &[],
        }
    }
}

/// The bodies joined to `seeds` through `pairs` (two bodies that act on each other: a joint, a
/// coupling, a spring), as a flag per body of `bodies`: the set grows until nothing changes, a
/// pair (x, y), taken either way round, adding y when x is in the set, `passes_on(x)` (x hands
/// the set on) and `admits(y)` (y may join it). The seeds are in the set as given: filter them
/// first where they must be admitted. A pair naming a body past `bodies` joins nothing.
///
/// What a mechanism is depends on the reader: the bodies on one side of a joint (the joint left
/// out of `pairs`, bodies with mass admitted), a mechanism and the supports it hangs on
/// (dynamic bodies pass it on, fixed and kinematic ones do not), the bodies a motor drives.
pub fn joined_bodies(
    bodies: usize,
    seeds: impl IntoIterator<Item = usize>,
    pairs: impl IntoIterator<Item = (usize, usize)>,
    passes_on: impl Fn(usize) -> bool,
    admits: impl Fn(usize) -> bool,
) -> Vec<bool> {
    let mut inside = vec![false; bodies];
    for i in seeds {
        if let Some(x) = inside.get_mut(i) {
            *x = true;
        }
    }
    let pairs: Vec<(usize, usize)> = pairs
        .into_iter()
        .filter(|&(a, b)| a < bodies && b < bodies)
        .collect();
    let mut grew = true;
    while grew {
        grew = false;
        for &(a, b) in &pairs {
            for (x, y) in [(a, b), (b, a)] {
                if inside[x] && !inside[y] && passes_on(x) && admits(y) {
                    inside[y] = true;
                    grew = true;
                }
            }
        }
    }
    inside
}

/// The indices in two ascending lists, merged ascending, each once.
pub(crate) fn merged<'a>(a: &'a [u32], b: &'a [u32]) -> impl Iterator<Item = usize> + 'a {
    let (mut i, mut j) = (0, 0);
    std::iter::from_fn(move || {
        let next = match (a.get(i), b.get(j)) {
            (Some(&x), Some(&y)) if x == y => {
                i += 1;
                j += 1;
                x
            }
            (Some(&x), Some(&y)) if x < y => {
                i += 1;
                x
            }
            (_, Some(&y)) => {
                j += 1;
                y
            }
            (Some(&x), None) => {
                i += 1;
                x
            }
            (None, None) => return None,
        };
        Some(next as usize)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_hold_each_body_items_in_order() {
        let mut a = Adjacency::default();
        a.rebuild(4, [(0, 1), (1, 2), (0, 2), (3, 3)].into_iter());
        assert_eq!(a.of(0), &[0, 2]);
        assert_eq!(a.of(1), &[0, 1]);
        assert_eq!(a.of(2), &[1, 2]);
        assert_eq!(a.of(3), &[3]);
        assert_eq!(a.of(9), &[] as &[u32]);
    }

    #[test]
    fn joined_bodies_follow_the_predicates() {
        // A chain 0 - 1 - 2 - 3, body 4 apart, a pair naming body 9 (outside): ignored.
        let pairs = [(0, 1), (2, 1), (2, 3), (4, 9)];
        let all = |_: usize| true;
        assert_eq!(
            joined_bodies(5, [1], pairs, all, all),
            vec![true, true, true, true, false]
        );
        // Body 2 does not pass the set on: 3 is reached only through it.
        assert_eq!(
            joined_bodies(5, [0], pairs, |i| i != 2, all),
            vec![true, true, true, false, false]
        );
        // Body 2 may not join: neither may 3 behind it.
        assert_eq!(
            joined_bodies(5, [0], pairs, all, |i| i != 2),
            vec![true, true, false, false, false]
        );
        // A seed joins as given, even one `admits` refuses; no seed, no set.
        assert_eq!(
            joined_bodies(5, [4], pairs, all, |i| i != 4),
            vec![false, false, false, false, true]
        );
        assert_eq!(joined_bodies(5, [], pairs, all, all), vec![false; 5]);
    }

    #[test]
    fn merging_keeps_order_and_drops_repeats() {
        let m: Vec<usize> = merged(&[0, 2, 5], &[1, 2, 7]).collect();
        assert_eq!(m, vec![0, 1, 2, 5, 7]);
        assert_eq!(merged(&[], &[3]).collect::<Vec<_>>(), vec![3]);
    }
}
