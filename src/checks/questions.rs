//! Questions: an exercise's asked quantity, read from the run and compared with the expected answer.

use crate::level::{Quantity, QuestionDef, When};
use crate::snapshot::Snapshot;
use serde::{Deserialize, Serialize};

/// One question's result (the JSON report's `questions[]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuestionResult {
    pub id: String,
    pub ask: String,
    pub unit: String,
    pub expected: f64,
    /// The answer computed by the analysis layer from the engine's state (textbook formula), if one applies.
    pub analysis: Option<f64>,
    /// The engine's own value.
    pub engine: f64,
    /// |engine - expected| / |expected| (absolute when expected is 0).
    pub rel_error: f64,
    pub tolerance: f64,
    pub passed: bool,
    /// Time at which the value was read, s.
    pub time: f64,
    pub why: String,
    /// A student's answer and its grade, when given with `--answer ID=VALUE`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub student: Option<StudentGrade>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudentGrade {
    pub answer: f64,
    pub rel_error: f64,
    pub passed: bool,
}

/// Reads one question's quantity from every snapshot.
pub struct QuestionProbe {
    def: QuestionDef,
    value: Option<(f64, f64)>,
    distance: f64,
    last_com: Option<glam::DVec2>,
}

impl QuestionProbe {
    pub fn new(def: &QuestionDef) -> Self {
        QuestionProbe {
            def: def.clone(),
            value: None,
            distance: 0.0,
            last_com: None,
        }
    }

    fn read(&mut self, s: &Snapshot) -> Option<f64> {
        let body = |name: &str| s.body_index(name).map(|i| &s.bodies[i]);
        Some(match &self.def.quantity {
            Quantity::X(b) => body(b)?.com.x,
            Quantity::Y(b) => body(b)?.com.y,
            Quantity::Angle(b) => body(b)?.angle,
            Quantity::Vx(b) => body(b)?.velocity.x,
            Quantity::Vy(b) => body(b)?.velocity.y,
            Quantity::Speed(b) => body(b)?.velocity.length(),
            Quantity::Omega(b) => body(b)?.omega,
            Quantity::KineticEnergy(b) => {
                let b = body(b)?;
                0.5 * b.mass * b.velocity.length_squared() + 0.5 * b.inertia * b.omega * b.omega
            }
            Quantity::JointForce(j) => {
                let j = s.joints.iter().find(|x| &x.name == j)?;
                if s.dt > 0.0 {
                    j.impulse_on_body2.length() / s.dt
                } else {
                    return None;
                }
            }
            Quantity::ContactForce(b) => {
                let i = s.body_index(b)?;
                if s.dt <= 0.0 {
                    return None;
                }
                let total: glam::DVec2 = s
                    .contacts
                    .iter()
                    .map(|c| {
                        if c.body2 == i {
                            c.impulse_on_body2()
                        } else if c.body1 == i {
                            -c.impulse_on_body2()
                        } else {
                            glam::DVec2::ZERO
                        }
                    })
                    .sum();
                total.length() / s.dt
            }
            Quantity::Distance(b) => {
                let com = body(b)?.com;
                if let Some(last) = self.last_com {
                    self.distance += (com - last).length();
                }
                self.last_com = Some(com);
                self.distance
            }
        })
    }

    pub fn id(&self) -> &str {
        &self.def.id
    }

    pub fn observe(&mut self, s: &Snapshot) {
        let Some(x) = self.read(s) else { return };
        let t = s.time;
        match self.def.at {
            When::End => self.value = Some((x, t)),
            When::Time(at) => {
                // Keep the sample nearest to `at`.
                let better = self
                    .value
                    .is_none_or(|(_, tv)| (t - at).abs() < (tv - at).abs());
                if better {
                    self.value = Some((x, t));
                }
            }
            When::Max(from) => {
                if t >= from && self.value.is_none_or(|(v, _)| x > v) {
                    self.value = Some((x, t));
                }
            }
            When::Min(from) => {
                if t >= from && self.value.is_none_or(|(v, _)| x < v) {
                    self.value = Some((x, t));
                }
            }
        }
    }

    pub fn finish(self, student: Option<f64>) -> QuestionResult {
        let (engine, time) = self.value.unwrap_or((f64::NAN, f64::NAN));
        let rel = |x: f64| {
            let e = (x - self.def.expected).abs() / self.def.expected.abs().max(f64::MIN_POSITIVE);
            if e.is_nan() {
                f64::INFINITY
            } else {
                e
            }
        };
        let rel_error = if self.def.expected == 0.0 {
            (engine - 0.0).abs()
        } else {
            rel(engine)
        };
        let rel_error = if rel_error.is_nan() {
            f64::INFINITY
        } else {
            rel_error
        };
        QuestionResult {
            id: self.def.id.clone(),
            ask: self.def.ask.clone(),
            unit: self.def.unit.clone(),
            expected: self.def.expected,
            analysis: None,
            engine,
            rel_error,
            tolerance: self.def.tolerance,
            passed: rel_error <= self.def.tolerance,
            time,
            why: self.def.why.clone(),
            student: student.map(|a| {
                let e = if self.def.expected == 0.0 {
                    a.abs()
                } else {
                    rel(a)
                };
                StudentGrade {
                    answer: a,
                    rel_error: e,
                    passed: e <= self.def.student_tolerance,
                }
            }),
        }
    }
}
