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
