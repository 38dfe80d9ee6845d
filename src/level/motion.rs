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
