//! Impact (concepts.md IM-9 to IM-15, RM-10): detecting impacts from contact impulses and
//! measuring restitution, tangential velocity change, energy lost and angular momentum about
//! the contact point.
//!
//! The engine resolves an impact inside one step (or a few): the impact is bracketed by the
//! steps whose contact impulse between the pair is impulsive, and "just before" and "just after"
//! are the states at the ends of the bracket (general caveat 5 of concepts.md).

use super::{cross, Motion};
use crate::snapshot::{ContactState, Snapshot};
use glam::DVec2;

/// Coefficient of restitution from the normal components of the relative velocity of the
/// contact points (B over A, n from A to B): e = -(v_B2 - v_A2).n / (v_B1 - v_A1).n (IM-9, IM-12).
///
/// # Examples
///
/// A ball meeting a floor at 4 m/s (B over A along n: -4) and leaving at 2 m/s (+2): e = 0.5.
/// ```
/// use rigidlab::analysis::impact::coefficient_of_restitution;
/// assert_eq!(coefficient_of_restitution(-4.0, 2.0), 0.5);
/// ```
pub fn coefficient_of_restitution(v_rel_before_n: f64, v_rel_after_n: f64) -> f64 {
    -v_rel_after_n / v_rel_before_n
}

/// Velocities after a direct central impact (IM-9):
/// v_A2 = [m_A v_A1 + m_B v_B1 - m_B e (v_A1 - v_B1)]/(m_A + m_B),
/// v_B2 = [m_A v_A1 + m_B v_B1 + m_A e (v_A1 - v_B1)]/(m_A + m_B).
///
/// # Examples
///
/// JH P9.10.1: car A (3220 lb) at 20 mph strikes car B (2800 lb) at rest. Weights stand in
/// for masses (g cancels): e = 0.5 gives v_A' = 6.047 mph and v_B' = 16.047 mph, e = 0 both 10.698.
/// ```
/// use rigidlab::analysis::impact::central_impact_velocities;
/// let (a, b) = central_impact_velocities(3220.0, 2800.0, 20.0, 0.0, 0.5);
/// assert!((a - 6.047).abs() < 5e-4 && (b - 16.047).abs() < 5e-4);
/// let (a, b) = central_impact_velocities(3220.0, 2800.0, 20.0, 0.0, 0.0);
/// assert!((a - 10.698).abs() < 5e-4 && (a - b).abs() < 1e-12);
/// ```
pub fn central_impact_velocities(m_a: f64, m_b: f64, v_a1: f64, v_b1: f64, e: f64) -> (f64, f64) {
    let p = m_a * v_a1 + m_b * v_b1;
    let m = m_a + m_b;
    (
        (p - m_b * e * (v_a1 - v_b1)) / m,
        (p + m_a * e * (v_a1 - v_b1)) / m,
    )
}

/// Kinetic energy lost in a direct central impact (IM-14):
/// dT = 1/2 m_A m_B/(m_A + m_B) (1 - e^2)(v_A1 - v_B1)^2. `m_b = inf` is a fixed barrier.
///
/// # Examples
///
/// JH P9.10.1 in SI-free units: m_A = 100 slug, m_B = 86.96 slug (W/32.2), 20 mph = 29.333 ft/s;
/// the plastic impact loses 20,010 ft lb, e = 0.5 loses three quarters of that, 15,008 ft lb.
/// ```
/// use rigidlab::analysis::impact::central_impact_energy_loss;
/// let (m_a, m_b, v) = (3220.0 / 32.2, 2800.0 / 32.2, 20.0 * 5280.0 / 3600.0);
/// assert!((central_impact_energy_loss(m_a, m_b, v, 0.0, 0.0) - 20_010.0).abs() < 1.0);
/// assert!((central_impact_energy_loss(m_a, m_b, v, 0.0, 0.5) - 15_008.0).abs() < 1.0);
/// ```
pub fn central_impact_energy_loss(m_a: f64, m_b: f64, v_a1: f64, v_b1: f64, e: f64) -> f64 {
    let mu = if m_b.is_infinite() {
        m_a
    } else {
        m_a * m_b / (m_a + m_b)
    };
    0.5 * mu * (1.0 - e * e) * (v_a1 - v_b1).powi(2)
}

/// The contact between bodies a and b in one snapshot, summed over manifolds and points, with
/// the normal oriented from a to b.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairContact {
    /// Unit normal from a to b (impulse-weighted over manifolds).
    pub normal: DVec2,
    /// Impulse-weighted mean contact point (first point if no impulse), world.
    pub point: DVec2,
    /// The same mean of the points on a's surface and on b's (they differ by the points'
    /// separation along the normal): the material points that touch.
    pub surfaces: (DVec2, DVec2),
    /// Total impulse on b over the step, N s (a gets the opposite).
    pub impulse_on_b: DVec2,
    /// Sum of the normal impulses, N s.
    pub normal_impulse: f64,
    /// Number of contact points.
    pub points: usize,
    /// Where the solver applied the pair's impulses (impulse-weighted mean, or the first point
    /// when none pushed): the points' lever arms (`ContactPoint::arms`) from a side with mass,
    /// carried with its mass center to the snapshot. While the bodies overlap by a soft
    /// contact's settled depth, the surface points are that depth apart and the friction row
    /// holds this point still (a ball's rim under rigidlab's contact hook, else rapier's
    /// midpoint). None when no point has arms or neither side has mass.
    pub solver_point: Option<DVec2>,
}

/// The contact between a and b in `snap`, if their colliders touch (or are within prediction distance).
pub fn pair_contact(snap: &Snapshot, a: usize, b: usize) -> Option<PairContact> {
    pair_contact_among(snap, a, b, 0..snap.contacts.len())
}

/// [`pair_contact`] reading only the contacts `links` (built from `snap`) lists for a: the same
/// result without scanning the scene's contacts.
pub fn pair_contact_linked(
    snap: &Snapshot,
    a: usize,
    b: usize,
    links: &super::links::BodyLinks,
) -> Option<PairContact> {
    pair_contact_among(snap, a, b, links.contacts_of(a).iter().map(|&k| k as usize))
}

/// Whether a contact pushes impulsively this step: over twice the normal impulse it gave the
/// step before (a floor under a block struck down into it, a support under a body struck from
/// above), where a resting contact pushes about the same every step. Its impulse then changes
/// the velocities within the step, and the bodies' motion over the step is taken from the
/// velocities before it (analysis/frame.rs books it at the mean velocity; FrictionLoss and
/// FrictionWork slip from the velocities before the step's blow, not after).
pub fn pushes_impulsively(now: f64, before: f64) -> bool {
    now > 2.0 * before
}

/// The total normal impulse over the step between bodies a and b (`b` None: between a and any
/// body), N s: the normal impulses of the contacts' points summed in the snapshot's order, a
/// negative one counted as zero (a contact only pushes; rapier's impulses are never negative, so
/// for the engine's contacts this is their plain sum, the pair's
/// [`PairContact::normal_impulse`]). With `links` (built from `snap`) only a's own contacts are
/// visited, in the same order (the same sum to the last bit) without scanning the scene's: for
/// a reading on every step of every body; without, every contact is scanned.
pub fn pair_normal_impulse(
    snap: &Snapshot,
    a: usize,
    b: Option<usize>,
    links: Option<&super::links::BodyLinks>,
) -> f64 {
    let mut sum = 0.0;
    let mut add = |c: &ContactState| {
        let between = match b {
            Some(b) => pair_sign(c, a, b).is_some(),
            None => c.body1 == a || c.body2 == a,
        };
        if between {
            for p in &c.points {
                sum += p.normal_impulse.max(0.0);
            }
        }
    };
    match links {
        Some(links) => {
            for &k in links.contacts_of(a) {
                add(&snap.contacts[k as usize]);
            }
        }
        None => snap.contacts.iter().for_each(add),
    }
    sum
}

/// Whether contact `c` is between a and b: +1 with a as its body1, -1 with b, else None.
fn pair_sign(c: &ContactState, a: usize, b: usize) -> Option<f64> {
    if c.body1 == a && c.body2 == b {
        Some(1.0)
    } else if c.body1 == b && c.body2 == a {
        Some(-1.0)
    } else {
        None
    }
}

/// [`pair_contact`] over the contacts `ids` (ascending: the sums add in the snapshot's order).
fn pair_contact_among(
    snap: &Snapshot,
    a: usize,
    b: usize,
    ids: impl Iterator<Item = usize>,
) -> Option<PairContact> {
    let mut out = PairContact::default();
    let (mut wsum, mut psum, mut nsum) = (0.0, DVec2::ZERO, DVec2::ZERO);
    // The points on a's surface and on b's: a point is on body1's, body2's is `normal * distance`
    // from it.
    let (mut sa, mut sb) = (DVec2::ZERO, DVec2::ZERO);
    let mut first: Option<(DVec2, DVec2, (DVec2, DVec2))> = None;
    let (mut solver_sum, mut solver_first, mut solver_all) = (DVec2::ZERO, None, true);
    for c in ids.map(|k| &snap.contacts[k]) {
        let Some(sign) = pair_sign(c, a, b) else {
            continue;
        };
        let n = c.normal * sign;
        out.impulse_on_b += c.impulse_on_body2() * sign;
        for p in &c.points {
            let other = p.point + c.normal * p.distance;
            let on = if sign > 0.0 {
                (p.point, other)
            } else {
                (other, p.point)
            };
            first.get_or_insert((p.point, n, on));
            match solver_point(snap, c, p) {
                Some(q) => {
                    solver_first.get_or_insert(q);
                    solver_sum += q * p.normal_impulse;
                }
                None => solver_all = false,
            }
            wsum += p.normal_impulse;
            psum += p.point * p.normal_impulse;
            nsum += n * p.normal_impulse;
            sa += on.0 * p.normal_impulse;
            sb += on.1 * p.normal_impulse;
            out.normal_impulse += p.normal_impulse;
            out.points += 1;
        }
    }
    let (p0, n0, on0) = first?;
    if wsum > 0.0 {
        out.normal = nsum.normalize_or(n0);
        out.point = psum / wsum;
        out.surfaces = (sa / wsum, sb / wsum);
        out.solver_point = solver_all.then(|| solver_sum / wsum);
    } else {
        out.normal = n0;
        out.point = p0;
        out.surfaces = on0;
        out.solver_point = solver_first.filter(|_| solver_all);
    }
    Some(out)
}

/// The world point at which the solver applied a contact point's impulses: its lever arm from
/// the mass center of body2 (or body1) when that body has mass, added to that mass center now
/// (rapier freezes a recycled contact's arms and carries them with the mass center). None
/// without arms or when neither body has mass.
fn solver_point(
    snap: &Snapshot,
    c: &ContactState,
    p: &crate::snapshot::ContactPoint,
) -> Option<DVec2> {
    let (arm1, arm2) = p.arms?;
    let has_mass = |k: usize| snap.bodies.get(k).filter(|x| x.mass > 0.0);
    has_mass(c.body2)
        .map(|x| x.com + arm2)
        .or_else(|| has_mass(c.body1).map(|x| x.com + arm1))
}

/// What one impact did, from the states at the two ends of its bracket.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImpactMeasure {
    /// Normal from a to b at the first impulsive step.
    pub normal: DVec2,
    /// Contact point C (fixed in space for the angular-momentum balance).
    pub point: DVec2,
    /// Relative normal velocity (B over A, along n) before and after, m/s: negative when approaching.
    pub v_n_before: f64,
    pub v_n_after: f64,
    /// Relative tangential velocity before and after, m/s.
    pub v_t_before: f64,
    pub v_t_after: f64,
    /// Measured e = -v_n_after / v_n_before (IM-9).
    pub e: f64,
    /// Total contact impulse on b over the bracket, N s.
    pub impulse_on_b: DVec2,
}

/// Measures an impact between a and b at contact point `p` with normal `n` (a to b).
pub fn measure_impact(
    a: (&Motion, &Motion),
    b: (&Motion, &Motion),
    p: DVec2,
    n: DVec2,
    impulse_on_b: DVec2,
) -> ImpactMeasure {
    let t = n.perp();
    let before = b.0.velocity_at(p) - a.0.velocity_at(p);
    let after = b.1.velocity_at(p) - a.1.velocity_at(p);
    let (v_n_before, v_n_after) = (before.dot(n), after.dot(n));
    ImpactMeasure {
        normal: n,
        point: p,
        v_n_before,
        v_n_after,
        v_t_before: before.dot(t),
        v_t_after: after.dot(t),
        e: coefficient_of_restitution(v_n_before, v_n_after),
        impulse_on_b,
    }
}

/// Is the impact eccentric for a body? The line of the normal impulse through the contact point
/// misses G by more than `tol` (IM-15: then the textbook uses momentum and angular momentum, not e).
pub fn is_eccentric(r_g: DVec2, p: DVec2, n: DVec2, tol: f64) -> bool {
    cross(p - r_g, n).abs() > tol
}

/// Follows one pair's contact impulses step by step and brackets impacts: an impact starts at a
/// step whose normal impulse is impulsive (more than `threshold` N s, after a step below it) and
/// lasts while the following steps carry more than `fraction` of the first step's impulse and
/// still change the pair's motion. A contact that only carries a load (a ball at the bottom of a
/// pile holds up the balls above it with several times its own weight) is not an impact: the
/// step that changes the pair's relative normal velocity by no more than gravity does in a step
/// ends it (IM-9: an impact is over when compression and restitution are).
#[derive(Debug, Clone, Default)]
pub struct ImpactDetector {
    pub threshold: f64,
    pub fraction: f64,
    active: Option<f64>,
    previous: f64,
}

/// What the detector says about a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bracket {
    /// No impact in progress.
    Quiet,
    /// This step starts an impact.
    Start,
    /// This step continues the impact.
    Continue,
    /// The previous step was the impact's last; this step is not part of it.
    End,
}

impl ImpactDetector {
    pub fn new(threshold: f64, fraction: f64) -> Self {
        ImpactDetector {
            threshold,
            fraction,
            active: None,
            previous: 0.0,
        }
    }

    /// Feeds the normal impulse of the pair in a step, and whether the step changed the pair's
    /// relative normal velocity by more than gravity does in a step (`changes_motion`; always
    /// true without gravity).
    pub fn step(&mut self, normal_impulse: f64, changes_motion: bool) -> Bracket {
        let prev = std::mem::replace(&mut self.previous, normal_impulse);
        match self.active {
            Some(first) if normal_impulse > self.fraction * first && changes_motion => {
                Bracket::Continue
            }
            Some(_) => {
                self.active = None;
                Bracket::End
            }
            None if normal_impulse > self.threshold && prev <= self.threshold => {
                self.active = Some(normal_impulse);
                Bracket::Start
            }
            None => Bracket::Quiet,
        }
    }

    pub fn in_impact(&self) -> bool {
        self.active.is_some()
    }
}
