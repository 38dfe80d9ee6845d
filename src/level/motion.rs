//! A kinematic body's prescribed motion as functions of time: the level's own definition
//! (`Motion` in `format.rs`), read by the simulation (which moves the body there) and by the
//! analyses (which need the support's acceleration). Pure kinematics, no engine.

use super::format::{BodyDef, Motion, V2};

/// A body-frame pose or rate: (origin, angle) or (velocity of the origin, omega), or their
/// derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Planar {
    pub linear: V2,
    pub angular: f64,
}

impl Planar {
    const ZERO: Planar = Planar {
        linear: (0.0, 0.0),
        angular: 0.0,
    };
}

impl Motion {
    /// The motion's vector and angle, (a, alpha) or (A, Theta), times the factor its kind
    /// takes: `accelerate` for `Accelerate`, `oscillate(w, phi)` for `Oscillate`.
    fn scaled(&self, accelerate: f64, oscillate: impl Fn(f64, f64) -> f64) -> Planar {
        let (v, a, f) = match *self {
            Motion::Accelerate {
                acceleration,
                angular,
            } => (acceleration, angular, accelerate),
            Motion::Oscillate {
                amplitude,
                angular_amplitude,
                omega,
                phase,
            } => (amplitude, angular_amplitude, oscillate(omega, phase)),
        };
        Planar {
            linear: (v.0 * f, v.1 * f),
            angular: a * f,
        }
    }

    /// The displacement from the start pose at time t beyond the constant velocity's:
    /// a t^2 / 2, or A (sin(w t + phi) - sin(phi)).
    fn offset(&self, t: f64) -> Planar {
        self.scaled(0.5 * t * t, |w, phi| (w * t + phi).sin() - phi.sin())
    }

    /// The offset's rate at t: a t, or A w cos(w t + phi).
    fn offset_rate(&self, t: f64) -> Planar {
        self.scaled(t, |w, phi| w * (w * t + phi).cos())
    }

    /// The acceleration of the origin and the angular acceleration at t: a, or
    /// -A w^2 sin(w t + phi).
    pub fn acceleration_at(&self, t: f64) -> Planar {
        self.scaled(1.0, |w, phi| -w * w * (w * t + phi).sin())
    }

    /// Whether the acceleration is the same at every time and the body does not turn: its
    /// frame is then a uniformly accelerated one, where gravity reads g - a.
    pub fn uniform_translation(&self) -> Option<V2> {
        match *self {
            Motion::Accelerate {
                acceleration,
                angular,
            } => (angular == 0.0).then_some(acceleration),
            Motion::Oscillate { .. } => None,
        }
    }
}

/// rapier's speed cap, m/s: `normalized_max_linear_velocity` (400) times `length_unit` (1, which
/// rigidlab keeps), applied to every body after each substep, kinematic ones included, in f32 and
/// f64 alike. A prescribed motion must stay within it (validation).
pub const SPEED_CAP: f64 = 400.0;

/// The range of cos over [a, b] (b >= a), as (least, largest); the whole [-1, 1] when the
/// interval spans a turn or its ends are too large to place between multiples of pi.
fn cos_range(a: f64, b: f64) -> (f64, f64) {
    use std::f64::consts::{PI, TAU};
    if !(b - a < TAU && a.abs() < 1e12 && b.abs() < 1e12) {
        return (-1.0, 1.0);
    }
    let (mut lo, mut hi) = (a.cos().min(b.cos()), a.cos().max(b.cos()));
    let mut k = (a / PI).ceil();
    while k * PI <= b {
        if k.rem_euclid(2.0) == 0.0 {
            hi = 1.0;
        } else {
            lo = -1.0;
        }
        k += 1.0;
    }
    (lo, hi)
}

/// The ends of the factor a motion's rate grows with over [0, duration]: a t for `Accelerate`
/// (t from 0 to the duration), w cos(w t + phi) for `Oscillate` (cos over the phases the run
/// covers). A rate r0 + s f has a convex size in f, so its largest is at one of these.
fn factor_ends(m: &Motion, duration: f64) -> [f64; 2] {
    match *m {
        Motion::Accelerate { .. } => [0.0, duration],
        Motion::Oscillate { omega, phase, .. } => {
            let (lo, hi) = cos_range(phase, phase + omega * duration);
            [omega * lo, omega * hi]
        }
    }
}

/// The largest speed of the body frame's origin over [0, duration], m/s: its `velocity` plus
/// the motion's rate, |v0 + a t| or |v0 + A w cos(w t + phi)|.
pub fn largest_speed(b: &BodyDef, m: &Motion, duration: f64) -> f64 {
    let unit = m.scaled(1.0, |_, _| 1.0).linear;
    factor_ends(m, duration)
        .iter()
        .map(|f| (b.velocity.0 + unit.0 * f).hypot(b.velocity.1 + unit.1 * f))
        .fold(
            0.0,
            |a: f64, x| if x.is_nan() { f64::INFINITY } else { a.max(x) },
        )
}

/// The largest angular rate of the body over [0, duration], rad/s: |omega0 + alpha t| or
/// |omega0 + Theta w cos(w t + phi)|.
pub fn largest_rate(b: &BodyDef, m: &Motion, duration: f64) -> f64 {
    let unit = m.scaled(1.0, |_, _| 1.0).angular;
    factor_ends(m, duration)
        .iter()
        .map(|f| (b.omega + unit * f).abs())
        .fold(
            0.0,
            |a: f64, x| if x.is_nan() { f64::INFINITY } else { a.max(x) },
        )
}

/// The pose (origin, angle) at time t of a body that starts at its `position` and `angle` with
/// its `velocity` and `omega`, moved by its `motion` if it has one.
pub fn pose_at(b: &BodyDef, t: f64) -> Planar {
    let off = b.motion.map_or(Planar::ZERO, |m| m.offset(t));
    Planar {
        linear: (
            b.position.0 + b.velocity.0 * t + off.linear.0,
            b.position.1 + b.velocity.1 * t + off.linear.1,
        ),
        angular: b.angle + b.omega * t + off.angular,
    }
}

/// The velocity of the body frame's origin and omega at time t (see [`pose_at`]).
pub fn rate_at(b: &BodyDef, t: f64) -> Planar {
    let off = b.motion.map_or(Planar::ZERO, |m| m.offset_rate(t));
    Planar {
        linear: (b.velocity.0 + off.linear.0, b.velocity.1 + off.linear.1),
        angular: b.omega + off.angular,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rate is the pose's derivative and the acceleration the rate's (central differences,
    /// h = 1e-5 s: truncation ~ h^2 |x'''| ~ 1e-10 · 20^3 · 0.1 ~ 1e-7, so 1e-6 relative).
    #[test]
    fn rates_are_derivatives() {
        for motion in [
            Motion::Accelerate {
                acceleration: (2.0, -1.0),
                angular: 0.5,
            },
            Motion::Oscillate {
                amplitude: (0.1, 0.05),
                angular_amplitude: 0.2,
                omega: 20.0,
                phase: 0.3,
            },
        ] {
            let mut b: BodyDef = crate::level::ron_options()
                .from_str(
                    "(name: \"s\", kind: kinematic, position: (3, 4), angle: 0.1, \
                     velocity: (1, 0.5), omega: -0.25)",
                )
                .unwrap();
            b.motion = Some(motion);
            let h = 1e-5;
            for t in [0.0, 0.37, 1.2] {
                let (p0, p1) = (pose_at(&b, t - h), pose_at(&b, t + h));
                let r = rate_at(&b, t);
                assert!(((p1.linear.0 - p0.linear.0) / (2.0 * h) - r.linear.0).abs() < 1e-6);
                assert!(((p1.linear.1 - p0.linear.1) / (2.0 * h) - r.linear.1).abs() < 1e-6);
                assert!(((p1.angular - p0.angular) / (2.0 * h) - r.angular).abs() < 1e-6);
                let (r0, r1) = (rate_at(&b, t - h), rate_at(&b, t + h));
                let a = motion.acceleration_at(t);
                assert!(((r1.linear.0 - r0.linear.0) / (2.0 * h) - a.linear.0).abs() < 1e-5);
                assert!(((r1.angular - r0.angular) / (2.0 * h) - a.angular).abs() < 1e-5);
            }
            // The start pose is the level's.
            assert_eq!(pose_at(&b, 0.0).linear, (3.0, 4.0));
        }
    }
}
