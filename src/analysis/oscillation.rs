//! Oscillations observed in a sampled signal: the period as the mean time between successive
//! zero crossings of the same direction of a velocity (between its extremes, where the velocity
//! changes sign), each crossing time interpolated linearly within its sample interval. The
//! questions' periods (questions/periods.rs) and the window's period timer both read it.

/// Crossings of a signal through zero, by direction, at interpolated times.
#[derive(Debug, Clone, Default)]
pub struct Crossings {
    last: Option<(f64, f64)>,
    down: Vec<f64>,
    up: Vec<f64>,
}

impl Crossings {
    pub fn add(&mut self, t: f64, x: f64) {
        if let Some((t0, x0)) = self.last {
            if x0 > 0.0 && x <= 0.0 && x0 != x {
                self.down.push(t0 + (t - t0) * x0 / (x0 - x));
            } else if x0 < 0.0 && x >= 0.0 && x0 != x {
                self.up.push(t0 + (t - t0) * x0 / (x0 - x));
            }
        }
        self.last = Some((t, x));
    }

    /// True before the first sample.
    pub fn is_empty(&self) -> bool {
        self.last.is_none()
    }

    /// How many full periods the crossings span (one direction's crossings less one).
    pub fn periods(&self) -> usize {
        self.down.len().max(self.up.len()).saturating_sub(1)
    }

    /// Mean interval between successive crossings of the same direction: the period.
    pub fn period(&self) -> f64 {
        let diffs: Vec<f64> = [&self.down, &self.up]
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
