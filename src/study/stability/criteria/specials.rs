//! The case-specific criteria (`Special`): a spinning disc's rate, a bouncing ball's apex, the
//! friction ramp, a bullet that must not tunnel, springs at the stability limit, a body's height,
//! a scene that comes to rest, a row of dominoes that falls to its end.

use super::*;

/// Torque-free spin: omega must hold, and the body turns by the linearized angle.
///
/// rapier integrates rotation per substep h = dt / substeps as q' = normalize(q + omega h q_perp),
/// a turn of exactly atan(omega h) instead of omega h. So the mean angle rate is
/// omega atan(omega h) / (omega h): the theory this criterion compares with.
pub struct Spin {
    pub body: String,
    pub omega0: f64,
    /// Substep h, s.
    pub h: f64,
    /// Largest allowed |omega / omega0 - 1|.
    pub omega_tol: f64,
    /// Largest allowed |rate ratio - linearized theory|.
    pub rate_tol: f64,
    index: Option<usize>,
    max_dev: f64,
    turned: f64,
    last_angle: Option<f64>,
    omega_end: f64,
    t_end: f64,
}

impl Spin {
    pub fn new(body: &str, omega0: f64, h: f64, omega_tol: f64, rate_tol: f64) -> Self {
        Spin {
            body: body.to_string(),
            omega0,
            h,
            omega_tol,
            rate_tol,
            index: None,
            max_dev: 0.0,
            turned: 0.0,
            last_angle: None,
            omega_end: omega0,
            t_end: 0.0,
        }
    }
}

/// The angle rate of rapier's linearized rotation relative to omega: atan(omega h) / (omega h).
pub fn linearized_rate_ratio(omega: f64, h: f64) -> f64 {
    let x = omega * h;
    if x.abs() < 1e-12 {
        1.0
    } else {
        x.atan() / x
    }
}

/// Wraps an angle difference to (-pi, pi].
pub fn wrap(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let r = (a + PI).rem_euclid(TAU) - PI;
    if r <= -PI {
        r + TAU
    } else {
        r
    }
}

impl Special for Spin {
    fn observe(&mut self, s: &Snapshot, _: &[(f64, f64)]) {
        let i = *self
            .index
            .get_or_insert_with(|| s.body_index(&self.body).unwrap_or(usize::MAX));
        let Some(b) = s.bodies.get(i) else { return };
        self.max_dev = self.max_dev.max((b.omega / self.omega0 - 1.0).abs());
        if let Some(a0) = self.last_angle {
            self.turned += wrap(b.angle - a0);
        }
        self.last_angle = Some(b.angle);
        self.omega_end = b.omega;
        self.t_end = s.time;
    }
    fn finish(&self, out: &mut Outcome) {
        out.criteria.push(Criterion::at_most(
            "omega_deviation",
            self.max_dev,
            self.omega_tol,
        ));
        // Measured mean angle rate over the mean omega (omega is constant when the first criterion holds).
        let ratio = if self.t_end > 0.0 {
            self.turned / self.t_end / self.omega_end
        } else {
            0.0
        };
        let theory = linearized_rate_ratio(self.omega_end, self.h);
        out.criteria.push(Criterion::at_most(
            "angle_rate_vs_theory",
            (ratio - theory).abs(),
            self.rate_tol,
        ));
        out.figures.insert("omega_end".into(), self.omega_end);
        out.figures.insert("angle_rate_ratio".into(), ratio);
        out.figures.insert("angle_rate_theory".into(), theory);
    }
}

/// Bounce apex: after the first impact, the mass center never climbs above `max_y`.
pub struct Apex {
    pub body: String,
    pub max_y: f64,
    index: Option<usize>,
    falling: bool,
    bounced: bool,
    last_vy: f64,
    apexes: Vec<f64>,
}

impl Apex {
    pub fn new(body: &str, max_y: f64) -> Self {
        Apex {
            body: body.to_string(),
            max_y,
            index: None,
            falling: true,
            bounced: false,
            last_vy: 0.0,
            apexes: Vec::new(),
        }
    }
}

impl Special for Apex {
    fn observe(&mut self, s: &Snapshot, _: &[(f64, f64)]) {
        let i = *self
            .index
            .get_or_insert_with(|| s.body_index(&self.body).unwrap_or(usize::MAX));
        let Some(b) = s.bodies.get(i) else { return };
        let vy = b.velocity.y;
        if self.falling && vy > 0.0 && self.last_vy <= 0.0 && s.step > 0 {
            // Turned from falling to rising: a bounce.
            self.bounced = true;
            self.falling = false;
        } else if !self.falling && vy <= 0.0 && self.last_vy > 0.0 {
            // Turned from rising to falling: an apex (the step's end position is within |v| dt of it).
            self.apexes.push(b.com.y);
            self.falling = true;
        }
        self.last_vy = vy;
    }
    fn finish(&self, out: &mut Outcome) {
        let max = self
            .apexes
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let min = self.apexes.iter().copied().fold(f64::INFINITY, f64::min);
        // A ball that never bounced has no apex to judge (it read 0, a pass): NaN, which fails.
        let none = self.apexes.is_empty();
        let max = if none { f64::NAN } else { max };
        out.criteria
            .push(Criterion::at_most("apex_max", max, self.max_y));
        out.figures
            .insert("bounces".into(), self.apexes.len() as f64);
        out.figures
            .insert("apex_min".into(), if none { f64::NAN } else { min });
        out.figures.insert(
            "apex_last".into(),
            self.apexes.last().copied().unwrap_or(f64::NAN),
        );
    }
}

/// Friction ramp: boxes with mu > tan(theta) stay (creep below a limit over the whole run);
/// boxes with mu < tan(theta) slide d = 1/2 g (sin(theta) - mu cos(theta)) t^2 by time `at`
/// (a block on an incline, Newton's second law along the slope).
pub struct Ramp {
    /// Slope angle, rad (positive: the magnitude of the tilt).
    pub theta: f64,
    pub g: f64,
    /// When the slid distances are read, s (before the sliders reach the foot of the ramp).
    pub at: f64,
    /// (body, largest creep, m).
    pub stick: Vec<(String, f64)>,
    /// (body, mu, relative tolerance on the slid distance).
    pub slide: Vec<(String, f64, f64)>,
    start: Vec<Option<DVec2>>,
    /// Positions at the last snapshot at or before `at`.
    at_pos: Vec<DVec2>,
    /// Positions at the end of the run.
    end: Vec<DVec2>,
    names: Vec<String>,
    t_at: f64,
}

impl Ramp {
    pub fn new(
        theta: f64,
        g: f64,
        at: f64,
        stick: Vec<(String, f64)>,
        slide: Vec<(String, f64, f64)>,
    ) -> Self {
        let names: Vec<String> = stick
            .iter()
            .map(|s| s.0.clone())
            .chain(slide.iter().map(|s| s.0.clone()))
            .collect();
        let n = names.len();
        Ramp {
            theta,
            g,
            at,
            stick,
            slide,
            start: vec![None; n],
            at_pos: vec![DVec2::ZERO; n],
            end: vec![DVec2::ZERO; n],
            names,
            t_at: 0.0,
        }
    }

    /// Slid distance by time t from rest: 1/2 g (sin(theta) - mu cos(theta)) t^2, m.
    pub fn theory(theta: f64, g: f64, mu: f64, t: f64) -> f64 {
        0.5 * g * (theta.sin() - mu * theta.cos()).max(0.0) * t * t
    }
}

impl Special for Ramp {
    fn observe(&mut self, s: &Snapshot, _: &[(f64, f64)]) {
        let before = s.time <= self.at + 1e-9;
        for (k, name) in self.names.iter().enumerate() {
            if let Some(i) = s.body_index(name) {
                let p = s.bodies[i].com;
                self.start[k].get_or_insert(p);
                self.end[k] = p;
                if before {
                    self.at_pos[k] = p;
                }
            }
        }
        if before {
            self.t_at = s.time;
        }
    }
    fn finish(&self, out: &mut Outcome) {
        let disp =
            |k: usize, p: &[DVec2]| self.start[k].map_or(f64::INFINITY, |p0| (p[k] - p0).length());
        for (k, (name, limit)) in self.stick.iter().enumerate() {
            out.criteria.push(Criterion::at_most(
                &format!("creep:{name}"),
                disp(k, &self.end),
                *limit,
            ));
        }
        let n = self.stick.len();
        for (k, (name, mu, tol)) in self.slide.iter().enumerate() {
            let d = disp(n + k, &self.at_pos);
            let theory = Ramp::theory(self.theta, self.g, *mu, self.t_at);
            out.criteria.push(Criterion::at_most(
                &format!("slide_error:{name}"),
                (d / theory - 1.0).abs(),
                *tol,
            ));
            out.figures.insert(format!("slide:{name}"), d);
            out.figures.insert(format!("slide_theory:{name}"), theory);
        }
    }
}

/// No tunnelling: the body's mass center never gets past `x_max` (the near face of a wall minus
/// the body's radius, plus the allowed penetration).
pub struct NoTunnel {
    pub body: String,
    pub x_max: f64,
    index: Option<usize>,
    x: f64,
}

impl NoTunnel {
    pub fn new(body: &str, x_max: f64) -> Self {
        NoTunnel {
            body: body.to_string(),
            x_max,
            index: None,
            x: f64::NEG_INFINITY,
        }
    }
}

impl Special for NoTunnel {
    fn observe(&mut self, s: &Snapshot, _: &[(f64, f64)]) {
        let i = *self
            .index
            .get_or_insert_with(|| s.body_index(&self.body).unwrap_or(usize::MAX));
        if let Some(b) = s.bodies.get(i) {
            self.x = self.x.max(b.com.x);
        }
    }
    fn finish(&self, out: &mut Outcome) {
        out.criteria
            .push(Criterion::at_most("bullet_x_max", self.x, self.x_max));
    }
}

/// Springs at the step's stability limit. Each spring holds one body to the ground; with the
/// force evaluated once per step and one substep, rigidlab + rapier integrate it by symplectic
/// Euler (v' = v - h w^2 x, x' = x + h v'), which conserves the modified energy
/// H = 1/2 v^2 + 1/2 w^2 x^2 - 1/2 h w^2 x v exactly. On H = const the true energy E stays within
/// H / (1 +- w h / 2); released from rest (H = E0) it never exceeds E0 / (1 - w h / 2).
pub struct SpringBound {
    /// (spring index, body index, w = sqrt(k/m) rad/s).
    pub springs: Vec<(usize, usize, f64)>,
    pub dt: f64,
    /// Relative allowance for f32 round-off on top of the bound, over the first
    /// [`SpringBound::TOL_STEPS`] steps.
    pub tol: f64,
    e0: Vec<Option<f64>>,
    ratio: Vec<f64>,
    steps: u64,
}

impl SpringBound {
    pub fn new(springs: Vec<(usize, usize, f64)>, dt: f64, tol: f64) -> Self {
        let n = springs.len();
        SpringBound {
            springs,
            dt,
            tol,
            e0: vec![None; n],
            ratio: vec![0.0; n],
            steps: 0,
        }
    }

    /// The steps over which `tol` was set: the recorded 10 s at dt 1/60.
    pub const TOL_STEPS: f64 = 600.0;

    /// The round-off allowance after `steps` steps. Symplectic Euler keeps the modified energy
    /// exactly in exact arithmetic; f32 rounding kicks it by an uncorrelated ~1e-7 relative each
    /// step, a random walk that grows as sqrt(steps), not as steps (a drift would reach 1.7e-2 in
    /// 1e5 steps; `study stability --long` measures at most 1.3e-4).
    pub fn tol_after(tol: f64, steps: u64) -> f64 {
        tol * (steps as f64 / Self::TOL_STEPS).max(1.0).sqrt()
    }

    /// The symplectic-Euler bound on E / E0 for a release from rest: 1 / (1 - w h / 2)
    /// (infinite at and beyond the stability limit w h = 2).
    pub fn bound(omega: f64, h: f64) -> f64 {
        let x = 0.5 * omega * h;
        if x < 1.0 {
            1.0 / (1.0 - x)
        } else {
            f64::INFINITY
        }
    }
}

impl Special for SpringBound {
    fn observe(&mut self, s: &Snapshot, masses: &[(f64, f64)]) {
        for (k, &(si, bi, _)) in self.springs.iter().enumerate() {
            let (Some(sp), Some(b)) = (s.springs.get(si), s.bodies.get(bi)) else {
                continue;
            };
            let m = masses.get(bi).map_or(0.0, |m| m.0);
            self.steps = self.steps.max(s.step);
            let e = energy::kinetic_energy_translation(m, b.velocity) + sp.energy;
            let e0 = *self.e0[k].get_or_insert(e);
            if e0 > 0.0 {
                self.ratio[k] = self.ratio[k].max(e / e0);
            }
        }
    }
    fn finish(&self, out: &mut Outcome) {
        for (k, &(_, _, w)) in self.springs.iter().enumerate() {
            let bound = SpringBound::bound(w, self.dt);
            out.criteria.push(Criterion::at_most(
                &format!("spring{k}_energy_ratio"),
                self.ratio[k],
                bound * (1.0 + SpringBound::tol_after(self.tol, self.steps)),
            ));
            out.figures
                .insert(format!("spring{k}_omega_dt"), w * self.dt);
        }
    }
}

/// A body's mass center stays above (`Sense::Min`) or below (`Sense::Max`) a height from a
/// time on: no sinking through its support, no popping up.
pub struct Height {
    pub body: String,
    pub sense: Sense,
    pub y: f64,
    pub after: f64,
    index: Option<usize>,
    extreme: Option<f64>,
}

impl Height {
    pub fn at_least(body: &str, y: f64, after: f64) -> Self {
        Height {
            body: body.to_string(),
            sense: Sense::Min,
            y,
            after,
            index: None,
            extreme: None,
        }
    }
    pub fn at_most(body: &str, y: f64, after: f64) -> Self {
        Height {
            sense: Sense::Max,
            ..Height::at_least(body, y, after)
        }
    }
}

impl Special for Height {
    fn observe(&mut self, s: &Snapshot, _: &[(f64, f64)]) {
        let i = *self
            .index
            .get_or_insert_with(|| s.body_index(&self.body).unwrap_or(usize::MAX));
        if s.time < self.after - 1e-9 {
            return;
        }
        if let Some(b) = s.bodies.get(i) {
            let y = b.com.y;
            self.extreme = Some(match (self.extreme, self.sense) {
                (None, _) => y,
                (Some(e), Sense::Min) => e.min(y),
                (Some(e), Sense::Max) => e.max(y),
            });
        }
    }
    fn finish(&self, out: &mut Outcome) {
        match self.sense {
            Sense::Min => out.criteria.push(Criterion::at_least(
                &format!("lowest:{}", self.body),
                self.extreme.unwrap_or(f64::NEG_INFINITY),
                self.y,
            )),
            Sense::Max => out.criteria.push(Criterion::at_most(
                &format!("highest:{}", self.body),
                self.extreme.unwrap_or(f64::INFINITY),
                self.y,
            )),
        }
    }
}

/// A scene that comes to rest: from a time on, no body's mass center moves faster than a limit
/// (a settling pile, not one that keeps flowing or jittering). The mean height of the moving
/// bodies at the end is reported as a figure.
pub struct Rest {
    pub after: f64,
    pub limit: f64,
    /// The fastest mass center seen from `after` on (None: no snapshot there, which fails).
    fastest: Option<f64>,
    mean_height: f64,
}

impl Rest {
    pub fn new(after: f64, limit: f64) -> Self {
        Rest {
            after,
            limit,
            fastest: None,
            mean_height: f64::NAN,
        }
    }
}

impl Special for Rest {
    fn observe(&mut self, s: &Snapshot, masses: &[(f64, f64)]) {
        if s.time < self.after - 1e-9 {
            return;
        }
        // Moving bodies only: the fixed ones have zero mass here (`body_masses`).
        let moving = || {
            s.bodies
                .iter()
                .zip(masses)
                .filter(|(_, m)| m.0 > 0.0)
                .map(|(b, _)| b)
        };
        let fastest = moving().map(|b| b.velocity.length()).fold(0.0, f64::max);
        self.fastest = Some(self.fastest.map_or(fastest, |f| f.max(fastest)));
        let (sum, n) = moving().fold((0.0, 0usize), |(y, n), b| (y + b.com.y, n + 1));
        self.mean_height = sum / n as f64;
    }
    fn finish(&self, out: &mut Outcome) {
        out.criteria.push(Criterion::at_most(
            "rest",
            self.fastest.unwrap_or(f64::INFINITY),
            self.limit,
        ));
        out.figures.insert("mean_height".into(), self.mean_height);
    }
}

/// Every moving body ends tilted at least `limit` from the vertical (a domino wave that ran to
/// the end of every row: one standing domino anywhere is a wave that stopped). Figures: how many
/// ended toppled, their least and median tilt at the end, and the time the last one first passed
/// the limit (the wave's end).
pub struct Toppled {
    pub limit: f64,
    /// The last snapshot's tilts |wrap(angle)| of the moving bodies.
    tilts: Vec<f64>,
    /// When every moving body was first past the limit.
    all_down_at: Option<f64>,
}

impl Toppled {
    pub fn new(limit: f64) -> Self {
        Toppled {
            limit,
            tilts: Vec::new(),
            all_down_at: None,
        }
    }
}

impl Special for Toppled {
    fn observe(&mut self, s: &Snapshot, masses: &[(f64, f64)]) {
        self.tilts.clear();
        self.tilts.extend(
            s.bodies
                .iter()
                .zip(masses)
                .filter(|(_, m)| m.0 > 0.0)
                .map(|(b, _)| wrap(b.angle).abs()),
        );
        // `all` of no tilts is true: a run that has no dominoes moving has not toppled them.
        if self.all_down_at.is_none()
            && !self.tilts.is_empty()
            && self.tilts.iter().all(|a| *a >= self.limit)
        {
            self.all_down_at = Some(s.time);
        }
    }
    fn finish(&self, out: &mut Outcome) {
        // Never a pass on a value not measured: no tilt read, or one that is NaN (`f64::min`
        // would skip it), makes the least tilt NaN, which no limit passes.
        let least = if self.tilts.is_empty() || self.tilts.iter().any(|a| a.is_nan()) {
            f64::NAN
        } else {
            self.tilts.iter().copied().fold(f64::INFINITY, f64::min)
        };
        out.criteria
            .push(Criterion::at_least("toppled", least, self.limit));
        let mut sorted = self.tilts.clone();
        sorted.sort_by(f64::total_cmp);
        let down = sorted.iter().filter(|a| **a >= self.limit).count();
        out.figures.insert("toppled_count".into(), down as f64);
        out.figures
            .insert("standing_count".into(), (sorted.len() - down) as f64);
        out.figures.insert(
            "median_tilt_deg".into(),
            sorted
                .get(sorted.len() / 2)
                .map_or(f64::NAN, |a| a.to_degrees()),
        );
        out.figures
            .insert("least_tilt_deg".into(), least.to_degrees());
        out.figures
            .insert("wave_end_s".into(), self.all_down_at.unwrap_or(f64::NAN));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `toppled` judges tilts it read: a run that read none fails it (the least of no tilts is
    /// not +inf), and no wave end is reported.
    #[test]
    fn toppled_fails_when_no_tilt_was_read() {
        let mut out = Outcome::default();
        Toppled::new(0.2).finish(&mut out);
        assert!(!out.criteria[0].passed);
        assert!(out.criteria[0].value.is_nan());
        assert!(out.figures["wave_end_s"].is_nan());
    }

    /// `apex_max` judges apexes it saw: a ball that never bounced fails it.
    #[test]
    fn apex_fails_when_the_ball_never_bounced() {
        let mut out = Outcome::default();
        Apex::new("ball", 1.11).finish(&mut out);
        assert!(!out.criteria[0].passed);
        assert_eq!(out.figures["bounces"], 0.0);
    }
}
