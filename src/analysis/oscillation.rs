//! Oscillations observed in a sampled signal: the period as the mean time between successive
//! zero crossings of the same direction of a velocity (between its extremes, where the velocity
//! changes sign), each crossing time interpolated linearly within its sample interval. The
//! questions' periods (questions/periods.rs) and the window's period timer both read it.

/// Crossings of a signal through zero, by direction, at interpolated times.
///
/// The signal is a rate (a velocity, an omega): its integral between two crossings is a half
/// swing. Once a half swing falls under 1 % of the largest seen, the motion has died into
/// rounding noise (a damped pair after 3 s read its period 1.8e-2 off, counting the noise's
/// random crossings) or a crossing is jitter at an extreme: the crossings stop there, and the
/// period is the whole swings' before. A crossing whose coordinate (the rate's integral) is
/// within 1 % of the coordinate's range over the run from the last one counted is rounding
/// jitter too, wherever it comes: a body at rest before an impact sets it swinging (a platform
/// on a spring, in f64, jitters by 8e-17 m: two "extremes" at t = 0 and 0.18 s shortened its
/// period 2.9%, n14_20), or the start itself.
#[derive(Debug, Clone, Default)]
pub struct Crossings {
    last: Option<(f64, f64)>,
    /// Every crossing counted: (time, the rate's integral there, down).
    list: Vec<(f64, f64, bool)>,
    /// The signal's integral since the first sample, and at the last crossing kept.
    swept: f64,
    at_crossing: Option<f64>,
    largest_half_swing: f64,
    stopped: bool,
}

/// The share of the largest half swing under which crossings stop being counted.
const NOISE_FLOOR: f64 = 0.01;

impl Crossings {
    pub fn add(&mut self, t: f64, x: f64) {
        if let Some((t0, x0)) = self.last {
            let down = x0 > 0.0 && x <= 0.0 && x0 != x;
            let up = x0 < 0.0 && x >= 0.0 && x0 != x;
            if (down || up) && !self.stopped {
                // The crossing, and the integral up to it (x linear over the interval).
                let tc = t0 + (t - t0) * x0 / (x0 - x);
                let swept = self.swept + 0.5 * x0 * (tc - t0);
                let half = self.at_crossing.map(|a| (swept - a).abs());
                if half.is_some_and(|h| h < NOISE_FLOOR * self.largest_half_swing) {
                    self.stopped = true;
                } else {
                    self.largest_half_swing = self.largest_half_swing.max(half.unwrap_or(0.0));
                    self.at_crossing = Some(swept);
                    self.list.push((tc, swept, down));
                }
            }
            self.swept += 0.5 * (x0 + x) * (t - t0);
        }
        self.last = Some((t, x));
    }

    /// True before the first sample.
    pub fn is_empty(&self) -> bool {
        self.last.is_none()
    }

    /// The crossings' times by direction (down, up), less the jitter: a crossing within
    /// [`NOISE_FLOOR`] of the coordinate's range from the last one kept (the start, for the
    /// first) is left out; two of one direction in a row keep the farther.
    fn kept(&self) -> (Vec<f64>, Vec<f64>) {
        let (lo, hi) = self
            .list
            .iter()
            .fold((0.0f64, 0.0f64), |(lo, hi), c| (lo.min(c.1), hi.max(c.1)));
        let floor = NOISE_FLOOR * (hi - lo);
        let mut kept: Vec<(f64, f64, bool)> = Vec::new();
        let mut from = 0.0;
        for &c in &self.list {
            if (c.1 - from).abs() < floor {
                continue;
            }
            match kept.last_mut() {
                Some(k) if k.2 == c.2 => {
                    if (c.2 && c.1 > k.1) || (!c.2 && c.1 < k.1) {
                        *k = c;
                    }
                }
                _ => kept.push(c),
            }
            from = kept.last().map_or(0.0, |k| k.1);
        }
        let times = |down: bool| kept.iter().filter(|c| c.2 == down).map(|c| c.0).collect();
        (times(true), times(false))
    }

    /// How many full periods the crossings span (one direction's crossings less one).
    pub fn periods(&self) -> usize {
        let (down, up) = self.kept();
        down.len().max(up.len()).saturating_sub(1)
    }

    /// Mean interval between successive crossings of the same direction: the period.
    pub fn period(&self) -> f64 {
        let (down, up) = self.kept();
        let diffs: Vec<f64> = [&down, &up]
            .iter()
            .flat_map(|v| v.windows(2).map(|w| w[1] - w[0]))
            .collect();
        if diffs.is_empty() {
            f64::NAN
        } else {
            diffs.iter().sum::<f64>() / diffs.len() as f64
        }
    }
}

/// A swinging coordinate's extremes, alternating largest and smallest. A turn back within 1 %
/// of the largest swing seen is jitter at an extreme (f32 rounding can flip a rate's sign two
/// or three times there) and cancels with the extreme it followed; two extremes of one kind in
/// a row keep the farther.
#[derive(Debug, Clone, Default)]
pub struct Extremes {
    /// (is a largest, value), the last three.
    list: Vec<(bool, f64)>,
    largest_swing: f64,
}

impl Extremes {
    /// An extreme of the coordinate: `largest` when its rate turned from positive to negative.
    pub fn add(&mut self, largest: bool, x: f64) {
        match self.list.last().copied() {
            Some((k, y)) if k == largest => {
                if (largest && x > y) || (!largest && x < y) {
                    *self.list.last_mut().expect("not empty") = (k, x);
                }
            }
            Some((_, y)) if (x - y).abs() < 0.01 * self.largest_swing => {
                self.list.pop();
            }
            last => {
                if let Some((_, y)) = last {
                    self.largest_swing = self.largest_swing.max((x - y).abs());
                }
                self.list.push((largest, x));
                if self.list.len() > 3 {
                    self.list.remove(0);
                }
            }
        }
    }

    /// The middle of the last whole swing: the mean of the last largest and smallest.
    pub fn middle(&self) -> Option<f64> {
        match self.list.as_slice() {
            [.., (_, a), (_, b)] => Some(0.5 * (a + b)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A damped oscillation x = e^(-t/2) sin(2 pi t) (period 1 s, decaying to 1 % by 9.2 s)
    /// followed by rounding noise that flips sign every few samples: the period is 1 s from
    /// the swings before the noise (to the crossings' interpolation error, (dt f)^2 ~ 1e-6),
    /// where counting the noise's crossings would shorten it.
    #[test]
    fn crossings_stop_at_the_noise_floor() {
        let mut c = Crossings::default();
        let dt = 1e-3;
        let w = 2.0 * std::f64::consts::PI;
        for k in 0..20_000 {
            let t = k as f64 * dt;
            // The rate of e^(-t/2) sin(w t), then noise of 1e-6 from t = 12 s.
            let x = if t < 12.0 {
                (-t / 2.0).exp() * (w * (w * t).cos() - 0.5 * (w * t).sin())
            } else {
                1e-6 * if (k / 3) % 2 == 0 { 1.0 } else { -1.0 }
            };
            c.add(t, x);
        }
        assert!((c.period() - 1.0).abs() < 1e-4, "{}", c.period());
        assert!(c.periods() >= 8, "{}", c.periods());
    }

    /// A body at rest (its coordinate jittering by 1e-17, the rate's sign flipping twice) and
    /// then set swinging with period 0.5441 s (n14_20's platform in f64): the period is the
    /// swing's, to the crossings' interpolation error ((dt / T)^2 ~ 3e-6 at 1 ms). Before, the
    /// two jitter crossings entered the mean: 2.9% short on the level.
    #[test]
    fn jitter_at_rest_before_the_swing_is_not_an_extreme() {
        let mut c = Crossings::default();
        let dt = 1e-3;
        let period = 0.5441;
        let w = 2.0 * std::f64::consts::PI / period;
        for k in 0..2000 {
            let t = k as f64 * dt;
            let v = if t < 0.2 {
                // Jitter: a rate of +-1e-14 m/s flipping at t = 0.0005 and 0.18 s.
                if (0.0005..0.18).contains(&t) {
                    -1e-14
                } else {
                    1e-14
                }
            } else {
                -0.6 * (w * (t - 0.2)).cos()
            };
            c.add(t, v);
        }
        assert!((c.period() / period - 1.0).abs() < 1e-4, "{}", c.period());
        assert!(c.periods() >= 2, "{}", c.periods());
    }

    /// A swing between -0.4 and -0.2 with jitter at one extreme: the middle stays -0.3.
    #[test]
    fn extremes_ignore_jitter() {
        let mut e = Extremes::default();
        e.add(true, -0.2);
        e.add(false, -0.4);
        e.add(true, -0.2001);
        e.add(false, -0.20009); // jitter: a turn back of 1e-5 against a 0.2 swing
        e.add(true, -0.2002);
        assert_eq!(e.middle(), Some(0.5 * (-0.4 + -0.2002)));
        e.add(false, -0.39);
        assert_eq!(e.middle(), Some(0.5 * (-0.2002 + -0.39)));
    }
}
